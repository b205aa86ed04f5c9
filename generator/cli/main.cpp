// railtab: wheel-rail contact tables. Each subcommand registers itself (commands.hpp).
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "cli/commands.hpp"
#include "table/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"railtab: wheel-rail contact geometry, contact models and contact tables"};
  app.set_version_flag("--version", std::string(railtab::version_string()) + " (" +
                                        railtab::git_commit() + ")");
  app.require_subcommand(1);
  railtab::add_eval_command(app);
  railtab::add_generate_command(app);
  railtab::add_inspect_command(app);
  railtab::add_query_command(app);
  railtab::add_merge_command(app);
  railtab::add_chart_commands(app);
  railtab::add_simulate_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "railtab: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
