// SPDX-License-Identifier: Apache-2.0
// What every railtab command shares: -q/--quiet, a stream for diagnostics (stderr, or nothing when
// quiet), and refusing an output that cannot be written before any long work starts.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>

namespace CLI {
class App;
class Validator;
}

namespace railtab {

// Numeric options: number_options.hpp (one reader for every number a user types).

// A validator from a core check that throws railtab::Error on a bad value (e.g. a model name): the
// value is refused while parsing, a usage error (exit 2) with the check's own message.
CLI::Validator error_check_validator(std::function<void(const std::string&)> check);

// Runs `work` with Ctrl-C and SIGTERM turned into the flag it is given to poll; a run that stops
// with Interrupted ends with its message and the shell's exit code (130 SIGINT, 143 SIGTERM).
void run_interruptible(const std::function<void(const std::atomic<bool>* interrupt)>& work);

// Adds -q/--quiet ("no progress or diagnostics on stderr; results and errors still printed").
std::shared_ptr<bool> add_quiet_flag(CLI::App* cmd);

// Where diagnostics go: std::cerr, or a stream that drops everything when `quiet`.
std::ostream& diagnostics(bool quiet);

// An output FILE is checked by check_output_path (table/output_file.hpp), called by the command
// before any work.

// Creates `dir` (with parents) and throws railtab::Error naming it unless a file can be created in it.
void require_writable_directory(const std::filesystem::path& dir);

}  // namespace railtab
