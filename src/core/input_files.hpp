// SPDX-License-Identifier: Apache-2.0
// The input files of a run. Every reader records the file it opened here (device and inode), so
// that no output of the same run can replace an input, whatever path or link names it
// (generator/table/output_file.hpp asks). Recording is off until a program turns it on: the
// railtab command does, for its one run; a library caller or the Python module (a session, not
// one run) gets only the inputs each writer is given explicitly.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace railtab {

struct FileIdentity {
  std::uint64_t device = 0;  // st_dev
  std::uint64_t inode = 0;   // st_ino
};

// Turns recording on or off for the whole process (thread-safe); off also forgets the files
// recorded.
void track_input_files(bool on);

// Records that this run read `path`, the file `id` (nothing while recording is off).
void note_input_file(const std::string& path, FileIdentity id);

// The path under which this run read the file `id`; empty when it read no such file.
std::string input_file_path(FileIdentity id);

// What a path that is not a regular file is ("a directory", "a FIFO", ...), from its stat
// st_mode, for the messages that refuse it. The lookup keeps its own copy: it may not depend on src/.
const char* file_kind(unsigned mode);

// Opens `path` for reading without waiting (a FIFO without a writer must not hang the run) and
// refuses anything but a regular file: throws railtab::Error naming `what` and the path. Records
// the file as an input and returns its descriptor, back in blocking mode; the caller closes it.
int open_input_file(const std::string& path, std::string_view what);

}  // namespace railtab
