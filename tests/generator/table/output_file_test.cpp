// SPDX-License-Identifier: Apache-2.0
// Safe output files (generator/table/output_file.hpp): non-regular targets and inputs refused by
// device and inode, stale temporaries of dead runs removed, live ones kept, SIGTERM sets the
// interrupt flag (issue 19, items 1 and 8).
#include "table/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>

#include "core/check.hpp"
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
