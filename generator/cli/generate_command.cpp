// railtab generate SCENE -o TABLE.h5 [--threads N] [--quiet] [--resume] [--shard I/N]
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "sweep/generate.hpp"
#include "table/interrupt.hpp"

namespace railtab {

void add_generate_command(CLI::App& app) {
  auto opt = std::make_shared<GenerateOptions>();
  auto shard = std::make_shared<std::string>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("generate", "Compute a contact table (HDF5, docs/table-format.md) from a scene");
  cmd->add_option("scene", opt->scene, "Scene file (TOML, docs/scenes.md)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", opt->output, "Table file to write (HDF5)")->required();
  cmd->add_option("--threads", opt->threads, "Worker threads (0 = all cores)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--quiet", *quiet, "No progress and no summary");
  cmd->add_flag("--resume", opt->resume,
                "Keep finished y blocks in OUTPUT.partial and skip those already there (result = fresh run)");
  cmd->add_option("--shard", *shard, "Compute only part I of N (1-based, split along y); join with railtab merge");
  cmd->add_option("--max-points", opt->max_points,
                  "Refuse a table with more grid points (docs/reliability.md); raise it for a bigger run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-bytes", opt->max_bytes, "Refuse a table needing more memory [B]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([opt, shard, quiet] {
    if (!shard->empty()) std::tie(opt->shard_index, opt->shard_count) = parse_shard(*shard);
    opt->log = *quiet ? nullptr : &std::cerr;
    opt->terminal = ::isatty(STDERR_FILENO) != 0;
    interrupt_flag().store(false);
    opt->interrupt = &interrupt_flag();
    SigintGuard guard;
    try {
      generate_table(*opt);
    } catch (const Interrupted& e) {
      std::cerr << "\nrailtab: " << e.what() << "\n";
      throw CLI::RuntimeError(128 + (interrupt_signal() ? interrupt_signal() : 2));  // the shell's code: 130, 143
    }
  });
}

}  // namespace railtab
