// SPDX-License-Identifier: Apache-2.0
// Safe output files: every file railtab writes goes through here. A target must be absent or a
// regular file and must not be one of the command's inputs (same device and inode); the content
// is written to a temporary beside it (TARGET.tmp.<pid>, held under a lock while alive), synced,
// renamed over the target and the directory synced, so a reader or a crash sees the old file or
// the whole new one, never half of it. Temporaries of dead runs are removed (docs/reliability.md).
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

namespace railtab {

// Throws railtab::Error naming `target` when it exists and is not a regular file (a device, a
// FIFO, a directory, a symbolic link to one of those), when it is the same file as one of
// `inputs` (compared by device and inode, so any spelling or link is caught), or when its
// directory does not exist or is not writable. Commands call it before any work.
void check_output_path(const std::filesystem::path& target, const std::vector<std::filesystem::path>& inputs = {});

// Removes TARGET.tmp.<pid> files that no live writer holds (their lock is free and their process
// is gone). Returns how many were removed.
std::size_t remove_stale_temporaries(const std::filesystem::path& target);

// One output in progress. The constructor checks the target (check_output_path), removes stale
// temporaries and creates the temporary exclusively, locked; write to temporary(), then commit().
// Destroyed without commit (an exception, an interruption), it removes the temporary and leaves an
// existing target untouched.
class OutputFile {
 public:
  explicit OutputFile(std::filesystem::path target, const std::vector<std::filesystem::path>& inputs = {});
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& target() const { return target_; }

  // fsync the temporary, check the target again, rename the temporary over it, fsync the directory.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int lock_fd_ = -1;  // open on the temporary, holding its lock until commit or destruction
  bool committed_ = false;
};

// The temporary name OutputFile uses for `target` in this process: TARGET.tmp.<pid>.
std::filesystem::path temporary_path(const std::filesystem::path& target);

// `text` into `target` through an OutputFile (charts' CSV and scripts, simulation outputs).
void write_text_file(const std::filesystem::path& target, std::string_view text);

}  // namespace railtab
