// railtab generate as a library call: scene -> sweep -> table file, with checkpoint/resume,
// shards, progress and clean interruption. The subcommand (generate_command.cpp) and the tests
// drive this.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <ostream>

#include "scene/scene.hpp"
#include "sweep/sweep.hpp"

namespace railtab {

struct GenerateOptions {
  std::filesystem::path scene;               // scene file (TOML)
  std::filesystem::path output;              // table file to write (HDF5)
  int threads = 0;                           // worker threads, 0 = all cores
  bool resume = false;                       // keep/use the checkpoint OUTPUT.partial
  int shard_index = 1;                       // compute shard I of N (1-based, split along y)
  int shard_count = 1;
  const std::atomic<bool>* interrupt = nullptr;  // set = stop; throws Interrupted
  std::ostream* log = nullptr;               // progress and summary; nullptr = silent
  bool terminal = false;                     // log is a terminal: draw a progress bar
  std::function<SweepKernel(const Scene&)> make_kernel;  // default: make_contact_kernel
  std::uint64_t max_points = kDefaultMaxPoints;  // refuse a larger table (--max-points) [-]
  std::uint64_t max_bytes = kDefaultMaxBytes;    // refuse a table needing more memory (--max-bytes) [B]
};

// The checkpoint file of a table: OUTPUT.partial.
std::filesystem::path checkpoint_path(const std::filesystem::path& output);

// Parse "I/N" (1 <= I <= N) of --shard; throws railtab::Error naming the text.
std::pair<int, int> parse_shard(const std::string& text);

// Run the whole generation. On interruption throws Interrupted after removing every temporary
// file: no target is left (an existing target is not touched); with resume the checkpoint stays.
SweepSummary generate_table(const GenerateOptions& options);

}  // namespace railtab
