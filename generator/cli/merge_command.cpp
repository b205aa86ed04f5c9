// railtab merge OUT.h5 SHARD.h5...: join the shards of `railtab generate --shard I/N` into one
// table equal to a single run.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "table/merge.hpp"
#include "table/table_io.hpp"

namespace railtab {

void add_merge_command(CLI::App& app) {
  auto output = std::make_shared<std::string>();
  auto inputs = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("merge", "Join the shards of generate --shard I/N into one table");
  cmd->add_option("output", *output, "Table file to write (HDF5)")->required();
  cmd->add_option("shards", *inputs, "All N shard files, in any order")->required()->check(CLI::ExistingFile);
  cmd->callback([output, inputs] {
    std::vector<Table> shards;
    for (const std::string& path : *inputs) shards.push_back(read_table(path));
    Table merged = merge_shards(shards, *inputs);
    shards.clear();
    write_table(merged, *output);
    std::cerr << fmt::format("merged {} shards into {} ({} y values)\n", inputs->size(), *output,
                             merged.axis("y") ? merged.axis("y")->values.size() : 1);
  });
}

}  // namespace railtab
