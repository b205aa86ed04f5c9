// railtab inspect TABLE.h5 [--scene] [--json]: axes, outputs, status counts and provenance of a table.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "table/inspect.hpp"
#include "table/table_io.hpp"

namespace railtab {

void add_inspect_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto scene = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("inspect", "Summary of a table file: axes, outputs, status counts, provenance");
  cmd->add_option("table", *path, "Table file (HDF5)")->required();
  cmd->add_flag("--scene", *scene, "Also print the scene text stored in the table");
  cmd->add_flag("--json", *json, "Print JSON (stable keys, SI units; the scene text included) instead of text");
  add_quiet_flag(cmd);  // inspect prints results only; accepted for uniformity
  cmd->callback([path, scene, json] {
    Table table = read_table(*path);
    if (*json) {
      std::cout << table_summary_json(table, *path, std::filesystem::file_size(*path)) << "\n";
    } else {
      print_table_summary(table, *path, std::filesystem::file_size(*path), *scene, std::cout);
    }
  });
}

}  // namespace railtab
