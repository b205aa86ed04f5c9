// SPDX-License-Identifier: Apache-2.0
// railtab generate as a library call (generator/generate/generate.hpp): target file, interrupt,
// resume, shards.
#include "generate/generate.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <streambuf>
#include <string>

#include "generator/synthetic_kernel.hpp"
#include "generator/test_tables.hpp"
#include "engine/checkpoint.hpp"
#include "table/interrupt.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

struct Fixture {
  testing::TempDir dir;
  testing::SyntheticControl control;
  std::atomic<bool> stop{false};
  GenerateOptions options;

  explicit Fixture(const std::string& name) : dir(name) {
    std::ofstream(dir / "scene.toml") << testing::kSyntheticScene;
    options.scene = dir / "scene.toml";
    options.output = dir / "t.h5";
    options.threads = 1;
    options.interrupt = &stop;
    control.flag = &stop;
    options.make_kernel = [this](const Scene& s) { return testing::synthetic_kernel(s, &control); };
  }
};

Table fresh_table(const std::string& name) {
  Fixture f(name);
  generate_table(f.options);
  return read_table(f.options.output);
}

TEST(Generate, WritesTargetOnlyAndReportsPoints) {
  Fixture f("gen_plain");
  SweepSummary s = generate_table(f.options);
  EXPECT_EQ(f.dir.files(), (std::vector<std::string>{"scene.toml", "t.h5"}));
  EXPECT_EQ(s.points_computed, s.points_total);
  EXPECT_EQ(read_table(f.options.output).attribute("scene_name") ? 1 : 0, 1);
}

TEST(Generate, InterruptedRunLeavesNoTarget) {
  Fixture f("gen_interrupt");
  f.control.interrupt_after = 3;
  EXPECT_THROW(generate_table(f.options), Interrupted);
  EXPECT_EQ(f.dir.files(), std::vector<std::string>{"scene.toml"});  // no target, temp or checkpoint
  // An interrupt during writing removes the temporary file too.
  f.stop = false;
  f.control.interrupt_after = 1000;  // the last column sets the flag: the sweep completes, writing stops
  f.control.columns = 1000 - 14;
  EXPECT_THROW(generate_table(f.options), Interrupted);
  EXPECT_EQ(f.dir.files(), std::vector<std::string>{"scene.toml"});
}

// A log that sets a flag once a given text has been written to it (unbuffered: every character).
class FlagOnText : public std::streambuf {
 public:
  FlagOnText(std::string text, std::atomic<bool>& flag) : text_(std::move(text)), flag_(flag) {}

 protected:
  int overflow(int c) override {
    if (c != EOF) seen_ += static_cast<char>(c);
    if (seen_.find(text_) != std::string::npos) flag_ = true;
    return c;
  }

 private:
  std::string text_, seen_;
  std::atomic<bool>& flag_;
};

// The interrupt reaches the contact-jump stages after the sweep: the flag, set when the jump
// locator reports its end (its 100 % line: an earlier line, printed when the locator outlasts one
// report interval on a slow or loaded machine, would stop the locator instead), stops the
// one-sided values (minutes of columns with the exact model) at their first report instead of
// after them, and nothing is written.
TEST(Generate, InterruptDuringTheContactJumpsStopsThem) {
  testing::TempDir dir{"gen_interrupt_jumps"};
  std::ofstream(dir / "scene.toml") << testing::kJumpScene;
  std::atomic<bool> stop{false};
  FlagOnText buffer("locating contact jumps: 100.0%", stop);
  std::ostream log(&buffer);
  GenerateOptions o;
  o.scene = dir / "scene.toml";
  o.output = dir / "t.h5";
  o.threads = 2;
  o.interrupt = &stop;
  o.log = &log;
  try {
    generate_table(o);
    FAIL() << "the run went through";
  } catch (const Interrupted& e) {
    EXPECT_NE(std::string(e.what()).find("one-sided jump values"), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.toml"});
}

TEST(Generate, ResumeAfterInterruptEqualsFreshRun) {
  Table fresh = fresh_table("gen_fresh");
  for (int threads : {1, 2}) {
    Fixture f("gen_resume");
    f.options.resume = true;
    f.options.threads = threads;
    f.control.interrupt_after = 5;  // 14 columns: 7 y blocks x 2 rolls
    EXPECT_THROW(generate_table(f.options), Interrupted);
    EXPECT_FALSE(std::filesystem::exists(f.options.output));
    ASSERT_TRUE(std::filesystem::exists(checkpoint_path(f.options.output)));

    f.stop = false;
    f.control.interrupt_after = -1;
    f.control.columns = 0;
    SweepSummary s = generate_table(f.options);
    EXPECT_GT(s.points_resumed, 0u);
    EXPECT_LT(f.control.columns.load(), 14);  // finished blocks were not recomputed
    EXPECT_EQ(s.points_resumed + s.points_computed, s.points_total);
    EXPECT_FALSE(std::filesystem::exists(checkpoint_path(f.options.output)));  // removed when done
    testing::expect_same_datasets(fresh, read_table(f.options.output));
  }
}

TEST(Generate, CheckpointOfAnotherSceneIsDiscarded) {
  Fixture f("gen_stale");
  f.options.resume = true;
  f.control.interrupt_after = 6;
  EXPECT_THROW(generate_table(f.options), Interrupted);
  std::ofstream(f.dir / "scene.toml", std::ios::app) << "# edited\n";  // other scene text
  f.stop = false;
  f.control.interrupt_after = -1;
  SweepSummary s = generate_table(f.options);
  EXPECT_EQ(s.points_resumed, 0u);
  EXPECT_EQ(s.points_computed, s.points_total);
}

// A checkpoint record altered with its checksum recomputed (every byte of its payload 0xff: NaN
// in every float64 output) is refused on resume, naming the checkpoint; no table is written.
TEST(Generate, AlteredCheckpointRecordIsRefused) {
  Fixture f("gen_ckpt_nan");
  f.options.resume = true;
  f.control.interrupt_after = 5;
  EXPECT_THROW(generate_table(f.options), Interrupted);
  const std::filesystem::path partial = checkpoint_path(f.options.output);
  std::string bytes;
  {
    std::ifstream in(partial, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  // Layout (sweep/checkpoint.cpp): 32-byte header (magic, key, record bytes), then records of
  // block index, payload and FNV-1a checksum over both.
  std::uint64_t record_bytes = 0;
  std::memcpy(&record_bytes, bytes.data() + 24, sizeof record_bytes);
  ASSERT_GE(bytes.size(), 32 + 16 + record_bytes);
  std::fill_n(bytes.begin() + 40, record_bytes, '\xff');
  const std::uint64_t sum = fnv1a(std::string_view(bytes.data() + 40, record_bytes), fnv1a(std::string_view(bytes.data() + 32, 8)));
  std::memcpy(bytes.data() + 40 + record_bytes, &sum, sizeof sum);
  std::ofstream(partial, std::ios::binary | std::ios::trunc) << bytes;

  f.stop = false;
  f.control.interrupt_after = -1;
  try {
    generate_table(f.options);
    ADD_FAILURE() << "an altered checkpoint was resumed";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(partial.string() + ": the record of y block"), std::string::npos) << m;
    EXPECT_NE(m.find("non-finite"), std::string::npos) << m;
  }
  EXPECT_FALSE(std::filesystem::exists(f.options.output));
}

TEST(Checkpoint, TornLastRecordIsDropped) {
  testing::TempDir dir("ckpt_torn");
  auto path = dir / "c.partial";
  {
    Checkpoint c(path, 42, 8);
    c.append(0, std::vector<char>(8, 'a'));
    c.append(3, std::vector<char>(8, 'b'));
  }
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 3);  // crash mid-record
  {
    Checkpoint c(path, 42, 8);
    auto records = c.take_records();
    ASSERT_EQ(records.size(), 1u);
    EXPECT_EQ(records[0].block, 0u);
    c.append(5, std::vector<char>(8, 'c'));
  }
  {
    Checkpoint c(path, 42, 8);
    auto records = c.take_records();
    ASSERT_EQ(records.size(), 2u);
    EXPECT_EQ(records[1].block, 5u);
    EXPECT_FALSE(c.discarded());
    // Held while open: a second writer of the same checkpoint is refused.
    EXPECT_THROW(Checkpoint(path, 42, 8), Error);
  }
  Checkpoint other(path, 43, 8);
  EXPECT_TRUE(other.discarded());
  EXPECT_TRUE(other.take_records().empty());
}

TEST(Generate, ShardArgument) {
  EXPECT_EQ(parse_shard("2/8"), (std::pair<int, int>{2, 8}));
  EXPECT_THROW(parse_shard("0/8"), Error);
  EXPECT_THROW(parse_shard("9/8"), Error);
  EXPECT_THROW(parse_shard("2-8"), Error);
  EXPECT_THROW(parse_shard("2/8x"), Error);
}

}  // namespace
}  // namespace railtab
