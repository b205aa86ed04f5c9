// SPDX-License-Identifier: Apache-2.0
// Safe output files (generator/table/output_file.hpp): non-regular targets and inputs refused by
// device and inode, stale temporaries of dead runs removed, live ones kept, SIGTERM sets the
// interrupt flag (docs/reliability.md, "Files railtab writes").
#include "table/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>

#include "core/check.hpp"
#include "core/input_files.hpp"
#include "error_message.hpp"
#include "generator/test_tables.hpp"
#include "table/interrupt.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;

std::string read_all(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The pid of a process that has exited (and been reaped): nobody holds its temporaries.
pid_t dead_pid() {
  pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

TEST(OutputFile, RefusesDeviceFifoAndDirectory) {
  testing::TempDir dir("out_nonregular");
  EXPECT_THROW(check_output_path("/dev/null"), Error);
  EXPECT_THROW(write_text_file("/dev/null", "x"), Error);
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));  // still the device (as root, it used to become a regular file)
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
  EXPECT_THROW(write_text_file(dir / "fifo", "x"), Error);
  ASSERT_EQ(::stat((dir / "fifo").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  fs::create_directory(dir / "sub");
  EXPECT_THROW(write_text_file(dir / "sub", "x"), Error);
  EXPECT_THROW(write_text_file(dir / "missing_dir" / "f", "x"), Error);
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"fifo", "sub"}));  // no temporary left behind
}

TEST(OutputFile, RefusesAnInputWhateverItsSpelling) {
  testing::TempDir dir("out_input");
  std::ofstream(dir / "scene.toml") << "original";
  fs::create_hard_link(dir / "scene.toml", dir / "hard.toml");
  fs::create_symlink("scene.toml", dir / "soft.toml");
  for (const char* name : {"scene.toml", "hard.toml", "soft.toml"}) {
    try {
      check_output_path(dir / name, {dir / "scene.toml"});
      ADD_FAILURE() << name << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("is the input"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(OutputFile(dir.path() / "." / "scene.toml", {dir / "hard.toml"}), Error);
  EXPECT_EQ(read_all(dir / "scene.toml"), "original");
  EXPECT_NO_THROW(check_output_path(dir / "other.toml", {dir / "scene.toml"}));
}

TEST(OutputFile, CommitReplacesTargetAndLeavesNoTemporary) {
  testing::TempDir dir("out_commit");
  std::ofstream(dir / "t.csv") << "old";
  {
    OutputFile f(dir / "t.csv");
    std::ofstream(f.temporary()) << "new";
    EXPECT_EQ(read_all(dir / "t.csv"), "old");  // not replaced before commit
    f.commit();
  }
  EXPECT_EQ(read_all(dir / "t.csv"), "new");
  {
    OutputFile f(dir / "t.csv");  // abandoned: an exception or an interruption
    std::ofstream(f.temporary()) << "half";
  }
  EXPECT_EQ(read_all(dir / "t.csv"), "new");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"t.csv"});
}

TEST(OutputFile, StaleTemporariesOfDeadRunsAreRemovedLiveOnesKept) {
  testing::TempDir dir("out_stale");
  const std::string dead = "t.h5.tmp." + std::to_string(dead_pid());
  const std::string live = "t.h5.tmp." + std::to_string(::getppid());  // a live process (ours' parent)
  std::ofstream(dir / dead) << "left by a killed run";
  std::ofstream(dir / live) << "someone else's";
  std::ofstream(dir / "t.h5.tmp.notapid") << "not ours";
  write_text_file(dir / "t.h5", "x");
  std::vector<std::string> kept{"t.h5", "t.h5.tmp.notapid", live};
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(dir.files(), kept);
}

TEST(OutputFile, TemporaryOfThisProcessIsLockedWhileAlive) {
  testing::TempDir dir("out_locked");
  OutputFile first(dir / "t.h5");
  // A second writer of the same target in this process cannot take the same temporary.
  EXPECT_THROW(OutputFile(dir / "t.h5"), Error);
  EXPECT_EQ(remove_stale_temporaries(dir / "t.h5"), 0u);  // held: not stale
  EXPECT_TRUE(fs::exists(first.temporary()));
}

// Where it writes, the output path follows no symbolic link and replaces no file with a second
// name: the file the link or the other name leads to keeps its content.
TEST(OutputFile, RefusesSymbolicAndHardLinks) {
  testing::TempDir dir("out_links");
  std::ofstream(dir / "victim.txt") << "precious";
  fs::create_symlink("victim.txt", dir / "soft.csv");
  fs::create_symlink("missing.txt", dir / "dangling.csv");
  fs::create_hard_link(dir / "victim.txt", dir / "hard.csv");
  for (const char* name : {"soft.csv", "dangling.csv"}) {
    const std::string error = test::error_message([&] { write_text_file(dir / name, "x"); });
    EXPECT_NE(error.find("symbolic link"), std::string::npos) << name << ": " << error;
  }
  const std::string error = test::error_message([&] { write_text_file(dir / "hard.csv", "x"); });
  EXPECT_NE(error.find("2 names (hard links)"), std::string::npos) << error;
  EXPECT_EQ(read_all(dir / "victim.txt"), "precious");
  EXPECT_FALSE(fs::exists(dir / "missing.txt"));
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"dangling.csv", "hard.csv", "soft.csv", "victim.txt"}));
}

// A temporary replaced while it is written (a link planted in its place) is not renamed.
TEST(OutputFile, CommitRefusesAReplacedTemporary) {
  testing::TempDir dir("out_swap");
  std::ofstream(dir / "victim.txt") << "precious";
  OutputFile f(dir / "t.csv");
  fs::remove(f.temporary());
  fs::create_symlink("victim.txt", f.temporary());
  EXPECT_NE(test::error_message([&] { f.commit(); }).find("was replaced"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "t.csv"));
  EXPECT_EQ(read_all(dir / "victim.txt"), "precious");
}

// A file the run read (core/input_files.hpp, on in the railtab command) is never an output,
// whatever path or link names it; with recording off only the inputs given count.
TEST(OutputFile, RefusesAFileTheRunRead) {
  testing::TempDir dir("out_read");
  std::ofstream(dir / "profile.txt") << "read";
  fs::create_hard_link(dir / "profile.txt", dir / "other_name.txt");
  track_input_files(true);
  ::close(open_input_file((dir / "profile.txt").string(), "profile"));
  const std::string error = test::error_message([&] { write_text_file(dir.path() / "." / "profile.txt", "x"); });
  track_input_files(false);
  EXPECT_NE(error.find("is the input"), std::string::npos) << error;
  EXPECT_NE(error.find("of this run"), std::string::npos) << error;
  EXPECT_EQ(read_all(dir / "profile.txt"), "read");
}

// --resume: an existing output is continued only when it is a regular file of one name, not an
// input and not held by another run; a FIFO is refused without waiting for a writer.
TEST(OutputFile, ContinuesOnlyARegularFileOfOneName) {
  testing::TempDir dir("out_continue");
  EXPECT_EQ(open_output_to_continue(dir / "none.partial"), -1);
  std::ofstream(dir / "victim.txt") << "precious";
  std::ofstream(dir / "scene.toml") << "scene";
  fs::create_symlink("victim.txt", dir / "soft.partial");
  fs::create_hard_link(dir / "victim.txt", dir / "hard.partial");
  ASSERT_EQ(::mkfifo((dir / "fifo.partial").c_str(), 0600), 0);
  EXPECT_NE(test::error_message([&] { open_output_to_continue(dir / "soft.partial"); }).find("symbolic link"),
            std::string::npos);
  EXPECT_NE(test::error_message([&] { open_output_to_continue(dir / "hard.partial"); }).find("hard links"),
            std::string::npos);
  EXPECT_NE(test::error_message([&] { open_output_to_continue(dir / "fifo.partial"); }).find("FIFO"),
            std::string::npos);
  EXPECT_NE(test::error_message([&] { open_output_to_continue(dir / "scene.toml", {dir / "scene.toml"}); })
                .find("is the input"),
            std::string::npos);
  EXPECT_EQ(read_all(dir / "victim.txt"), "precious");
  std::ofstream(dir / "ok.partial") << "records";
  const int fd = open_output_to_continue(dir / "ok.partial");
  ASSERT_GE(fd, 0);
  EXPECT_NE(test::error_message([&] { open_output_to_continue(dir / "ok.partial"); }).find("another railtab run"),
            std::string::npos);  // held while the first run has it open
  ::close(fd);
  const int again = open_output_to_continue(dir / "ok.partial");
  EXPECT_GE(again, 0);
  ::close(again);
}

TEST(OutputFile, DirectoryProbeLeavesNothing) {
  testing::TempDir dir("out_probe");
  EXPECT_NO_THROW(check_output_directory(dir.path()));
  EXPECT_TRUE(dir.files().empty());
  EXPECT_THROW(check_output_directory(dir / "missing"), Error);
}

TEST(Interrupt, SigtermSetsTheFlagLikeSigint) {
  interrupt_flag().store(false);
  {
    SigintGuard guard;
    std::raise(SIGTERM);
    EXPECT_TRUE(interrupt_flag().load());
    EXPECT_EQ(interrupt_signal(), SIGTERM);
  }
  interrupt_flag().store(false);
}

TEST(TableDataset, SizeOverflowThrows) {
  TableDataset d;
  d.name = "huge";
  d.shape = {std::size_t{1} << 32, std::size_t{1} << 32, 2};
  EXPECT_THROW(d.size(), Error);
  d.shape = {524288, 524288, 524288, 32, 2, 2};  // 2^64: wraps to 0 unchecked (hostile scene)
  EXPECT_THROW(d.size(), Error);
}

}  // namespace
}  // namespace railtab
