// railtab: wheel-rail contact tables. Subcommands are registered in commands.cpp.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"railtab: wheel-rail contact geometry, contact models and contact tables"};
  app.set_version_flag("--version", std::string(railtab::version_string()) + " (" +
                                        railtab::git_commit() + ")");
  app.require_subcommand(1);
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
