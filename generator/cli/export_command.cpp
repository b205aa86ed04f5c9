// SPDX-License-Identifier: Apache-2.0
// railtab export TABLE.h5 --csv [-o FILE]: the table's creep forces in newtons on its nodes, one
// CSV row per node and slot (export/table_csv.hpp); on stdout without -o.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <string>

#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "export/table_csv.hpp"

namespace railtab {

void add_export_command(CLI::App& app) {
  struct Options {
    std::string table;
    bool csv = false;
    std::string output;  // empty: stdout
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "export", "Write a table's creep forces [N] on its nodes (physical creepages), one row per node and slot");
  cmd->add_option("table", opt->table, "Table file (HDF5)")->required();
  cmd->add_flag("--csv", opt->csv, "CSV with a header naming each column and its unit (the one format)")->required();
  cmd->add_option("-o,--output", opt->output, "File to write (default: stdout)");
  auto quiet = add_quiet_flag(cmd);
  cmd->callback([opt, quiet] {
    if (opt->output.empty()) {
      std::size_t rows = 0;
      std::cout << table_csv(opt->table, rows);
      std::cout.flush();
      return;
    }
    const std::size_t rows = write_table_csv(opt->table, opt->output);
    diagnostics(*quiet) << fmt::format("export: wrote {} ({} rows)\n", opt->output, rows);
  });
}

}  // namespace railtab
