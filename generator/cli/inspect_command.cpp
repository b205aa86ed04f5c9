// SPDX-License-Identifier: Apache-2.0
// railtab inspect TABLE.h5 [--scene] [--json]: axes, outputs, status counts and provenance of a table.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "core/check.hpp"
#include "railtab/lookup.hpp"
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
    // The lookup's own checks first (docs/table-format.md, "What readers check"): inspect shows
    // only a table a simulation could load, and a corrupt or crafted file is refused before the
    // summary reader touches it (docs/reliability.md).
    bool verified = false;
    try {
      verified = lookup::Table::load(*path).checksums_verified();
    } catch (const lookup::LoadError& e) {
      throw Error(e.what());
    }
    Table table = read_table(*path);
    if (*json) {
      std::cout << table_summary_json(table, *path, std::filesystem::file_size(*path), verified) << "\n";
      return;
    }
    print_table_summary(table, *path, std::filesystem::file_size(*path), *scene, std::cout);
    std::cout << (verified ? "integrity: checksums verified (every dataset and the metadata)\n"
                           : "integrity: NO checksums (a table written before format 1.1): a damaged "
                             "byte could change numbers unnoticed; regenerate it to get checksums\n");
  });
}

}  // namespace railtab
