// SPDX-License-Identifier: Apache-2.0
// railtab: wheel-rail contact tables. Each subcommand registers itself (commands.hpp).
// Every command: results on stdout, diagnostics (progress, "wrote ...", errors) on stderr, -q/--quiet
// silences the diagnostics but not the errors; the exit codes are those of kExitCodes.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "cli/commands.hpp"
#include "core/input_files.hpp"
#include "table/version.hpp"

namespace {

constexpr const char* kExitCodes =
    "Results go to stdout, progress and diagnostics to stderr (-q/--quiet silences them).\n"
    "Exit codes: 0 success; 1 error (bad input, unreadable or unwritable file, failed computation;\n"
    "the message on stderr names the input and the problem); 2 usage error (unknown command or\n"
    "option, missing or malformed argument); 130 interrupted (Ctrl-C; a table being written is\n"
    "not left behind).";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"railtab: wheel-rail contact geometry, contact models and contact tables"};
  app.footer(kExitCodes);
  app.set_version_flag("--version", std::string(railtab::version_string()) + " (" +
                                        railtab::git_commit() + ")");
  app.require_subcommand(1);
  // One command is one run: no output of it may replace a file it read (core/input_files.hpp).
  railtab::track_input_files(true);
  railtab::add_eval_command(app);
  railtab::add_generate_command(app);
  railtab::add_inspect_command(app);
  railtab::add_query_command(app);
  railtab::add_merge_command(app);
  railtab::add_chart_commands(app);
  railtab::add_conicity_command(app);
  railtab::add_simulate_command(app);
  railtab::add_export_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // thrown by a command with its code (130: interrupted), message printed
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help/version (code 0) or the usage error
    return code == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    std::cerr << "railtab: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
