// SPDX-License-Identifier: Apache-2.0
// railtab merge OUT.h5 SHARD.h5...: join the shards of `railtab generate --shard I/N` into one
// table equal to a single run.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "generate/error_map.hpp"
#include "table/merge.hpp"

namespace railtab {

void add_merge_command(CLI::App& app) {
  auto output = std::make_shared<std::string>();
  auto inputs = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("merge", "Join the shards of generate --shard I/N into one table");
  cmd->add_option("output", *output, "Table file to write (HDF5)")->required();
  // A missing shard is an input error (exit 1, named by the table reader), not a usage error.
  cmd->add_option("shards", *inputs, "All N shard files, in any order")->required();
  auto quiet = add_quiet_flag(cmd);
  cmd->callback([output, inputs, quiet] {
    // The output is checked (check_output_path) by merge_table_files before any shard is read.
    // Shards carry no error map (it needs the whole table): computed here on the merged one.
    const std::size_t y_values = merge_table_files(*inputs, *output, error_map_merge_finish());
    diagnostics(*quiet) << fmt::format("merged {} shards into {} ({} y values)\n", inputs->size(), *output, y_values);
  });
}

}  // namespace railtab
