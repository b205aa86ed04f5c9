// SPDX-License-Identifier: Apache-2.0
// Safe output files: the one path through which railtab writes every file (tables, checkpoints,
// merges, CSVs, chart scripts and PNGs, simulation outputs, worn profiles, the Python module's
// SIMPACK profiles; tests/output_paths_test.py fails on a writer that bypasses it). A target must
// be absent or a regular file with one link, not a symbolic link, and none of the run's inputs
// (compared by device and inode: the `inputs` given, and every file the run read while
// core/input_files.hpp records them). The content goes to a temporary beside it
// (TARGET.tmp.<pid>, created exclusively without following links, locked while alive), is synced,
// and the temporary, checked to be still the file created, is renamed over the target and the
// directory synced: a reader or a crash sees the old file or the whole new one, never half of it.
// Temporaries of dead runs are removed (docs/reliability.md).
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

namespace railtab {

// Throws railtab::Error naming `target` when it is the same file as one of `inputs` or as a file
// this run read (by device and inode, so any spelling or link is caught), when it is a symbolic
// link, a hard link (more than one name), not a regular file (a device, a FIFO, a directory), or
// when its directory does not exist or is not writable. Commands call it before any work.
void check_output_path(const std::filesystem::path& target, const std::vector<std::filesystem::path>& inputs = {});

// Throws railtab::Error unless a file can be created in `dir` (an existing directory): creates
// and removes a probe file there, exclusively and without following links. For commands whose
// outputs go into a directory, before any work.
void check_output_directory(const std::filesystem::path& dir);

// Removes TARGET.tmp.<pid> files that no live writer holds (their lock is free and their process
// is gone). Returns how many were removed.
std::size_t remove_stale_temporaries(const std::filesystem::path& target);

// One output in progress. The constructor checks the target (check_output_path), removes stale
// temporaries and creates the temporary exclusively, locked; write to temporary() (or through
// descriptor()), then commit(). Destroyed without commit (an exception, an interruption), it
// removes the temporary and leaves an existing target untouched.
class OutputFile {
 public:
  explicit OutputFile(std::filesystem::path target, const std::vector<std::filesystem::path>& inputs = {});
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& target() const { return target_; }
  int descriptor() const { return lock_fd_; }  // the temporary, open for writing

  // fsync the temporary, check that it is still the file created and the target again (with the
  // same inputs), rename the temporary over the target, fsync the directory.
  void commit();

  // commit(), then hands the open descriptor (and its lock) to the caller, who closes it: for a
  // file that grows after it is in place (a checkpoint).
  int commit_and_keep_open();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::vector<std::filesystem::path> inputs_;
  int lock_fd_ = -1;  // open on the temporary, holding its lock until commit or destruction
  bool committed_ = false;
};

// An existing output that a run continues (a checkpoint on --resume): opened for reading and
// writing without following a symbolic link or blocking on a FIFO, refused unless a regular file
// with one link that is not an input (as check_output_path), and locked (another live run holding
// it is refused). Returns the descriptor, which the caller closes, or -1 when `path` does not exist.
int open_output_to_continue(const std::filesystem::path& path, const std::vector<std::filesystem::path>& inputs = {});

// Writes all of `bytes` to the descriptor `fd`; throws railtab::Error naming `file` on failure.
void write_all(int fd, std::string_view bytes, const std::filesystem::path& file);

// The temporary name OutputFile uses for `target` in this process: TARGET.tmp.<pid>.
std::filesystem::path temporary_path(const std::filesystem::path& target);

// `text` into `target` through an OutputFile (charts' CSV and scripts, simulation outputs,
// SIMPACK profiles).
void write_text_file(const std::filesystem::path& target, std::string_view text,
                     const std::vector<std::filesystem::path>& inputs = {});

}  // namespace railtab
