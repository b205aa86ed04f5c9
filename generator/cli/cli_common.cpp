// SPDX-License-Identifier: Apache-2.0
// -q/--quiet, the diagnostics stream and the early output checks of every command (cli_common.hpp).
#include "cli/cli_common.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <string>
#include <system_error>

#include "core/check.hpp"
#include "table/interrupt.hpp"
#include "table/output_file.hpp"

namespace railtab {
namespace {

// A stream buffer that accepts and drops everything.
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return c; }
};

}  // namespace

std::shared_ptr<bool> add_quiet_flag(CLI::App* cmd) {
  auto quiet = std::make_shared<bool>(false);
  cmd->add_flag("-q,--quiet", *quiet, "No progress or diagnostics on stderr (results and errors are still printed)");
  return quiet;
}

std::ostream& diagnostics(bool quiet) {
  static NullBuffer null_buffer;
  static std::ostream null_stream(&null_buffer);
  return quiet ? null_stream : std::cerr;
}

void require_writable_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  RAILTAB_CHECK(!ec && std::filesystem::is_directory(dir), "{}: cannot create the output directory ({}); refused "
                "before starting", dir.string(), ec ? ec.message() : "not a directory");
  check_output_directory(dir);
}

CLI::Validator error_check_validator(std::function<void(const std::string&)> check) {
  return CLI::Validator(
      [check = std::move(check)](std::string& text) -> std::string {
        try {
          check(text);
        } catch (const Error& e) {
          return e.what();
        }
        return {};
      },
      "");
}

void run_interruptible(const std::function<void(const std::atomic<bool>* interrupt)>& work) {
  interrupt_flag().store(false);
  SigintGuard guard;
  try {
    work(&interrupt_flag());
  } catch (const Interrupted& e) {
    std::cerr << "\nrailtab: " << e.what() << "\n";
    throw CLI::RuntimeError(128 + (interrupt_signal() ? interrupt_signal() : 2));  // the shell's code: 130, 143
  }
}

}  // namespace railtab
