// SPDX-License-Identifier: Apache-2.0
// railtab generate SCENE -o TABLE.h5 [--threads N] [-q] [--resume] [--shard I/N]; under mpirun/srun
// the MPI engine (generator/distributed/) when built with it
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "generate/generate.hpp"
#include "engine/shard_split.hpp"
#ifdef RAILTAB_HAVE_MPI
#include "distributed/mpi_sweep.hpp"
#endif

namespace railtab {

void add_generate_command(CLI::App& app) {
  auto opt = std::make_shared<GenerateOptions>();
  auto shard = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("generate", "Compute a contact table (HDF5, docs/table-format.md) from a scene");
  // No CLI::ExistingFile: a missing scene is an input error (exit 1, named by the scene reader), not
  // a usage error (exit 2), as in eval, inspect and query.
  cmd->add_option("scene", opt->scene, "Scene file (TOML, docs/scenes.md)")->required();
  cmd->add_option("-o,--output", opt->output, "Table file to write (HDF5)")->required();
  cmd->add_option("--threads", opt->threads, "Worker threads (0 = all cores)")
      ->check(thread_count_validator())
      ->capture_default_str();
  auto quiet = add_quiet_flag(cmd);
  cmd->add_flag("--resume", opt->resume,
                "Keep finished y blocks in OUTPUT.partial and skip those already there (result = fresh run)");
  cmd->add_option("--shard", *shard, "Compute only part I of N (1-based, contiguous y ranges of about equal estimated cost; "
                "\"auto\": from SLURM_ARRAY_TASK_ID/COUNT); join with railtab merge");
  cmd->add_option("--max-points", opt->max_points,
                  "Refuse a table with more grid points (docs/reliability.md); raise it for a bigger run")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-bytes", opt->max_bytes, "Refuse a table needing more memory [B]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([opt, shard, quiet] {
    if (!shard->empty()) std::tie(opt->shard_index, opt->shard_count) = parse_shard_spec(*shard);
    opt->log = *quiet ? nullptr : &std::cerr;
    opt->terminal = ::isatty(STDERR_FILENO) != 0;
    run_interruptible([&opt](const std::atomic<bool>* interrupt) {
      opt->interrupt = interrupt;
      if (launched_by_mpi()) {
#ifdef RAILTAB_HAVE_MPI
        generate_table_mpi(*opt);
#else
        throw Error("railtab generate was started by an MPI launcher, but this build has no MPI (RAILTAB_MPI=OFF): "
                    "every process would compute and write the whole table; rebuild with MPI or run it once");
#endif
      } else {
        generate_table(*opt);
      }
    });
  });
}

}  // namespace railtab
