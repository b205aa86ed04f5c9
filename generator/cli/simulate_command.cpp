// SPDX-License-Identifier: Apache-2.0
// railtab simulate SCENE --out DIR [--threads N] [--direct] [--duration SECONDS] [--yaw-nodes LIST]
//                  [--post-processors P ...] [-q]
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "cli/cli_common.hpp"
#include "charts/gnuplot.hpp"
#include "cli/commands.hpp"
#include "cli/number_options.hpp"
#include "scene/simulation_scene.hpp"
#include "scene/state_rules.hpp"
#include "simulate/simulation_run.hpp"

namespace railtab {
namespace {

// --duration: from a microsecond (one RK4 step at the smallest time_step) to a day, in seconds;
// leave it out to run the whole route.
constexpr NumberRule kDurationRule{1e-6, 86400.0, false, "s"};

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto opt = std::make_shared<SimulationOptions>();
  auto scene_file = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Run a bogie over a route with a contact table in the dynamics and accumulate wheel wear with each wear post-processor (docs/simulation.md)");
  // A missing scene is an input error (exit 1, named by the scene reader), not a usage error.
  cmd->add_option("scene", *scene_file, "Simulation scene (TOML, docs/simulation.md)")->required();
  cmd->add_option("--out", opt->out, "Output directory (results in OUT/<scene name>/)")->required();
  add_count_option(cmd, "--threads", opt->threads, kThreadsRule, "Table generation threads (0 = all cores)");
  cmd->add_flag("--direct", opt->direct,
                "Evaluate geometry, normal model and FASTSIM at every call instead of the table (reference, slow)");
  add_number_option(cmd, "--duration", opt->duration, kDurationRule,
                    "Simulate at most this long per run [s] (speed measurements; default: the whole route)")
      ->default_str("");
  add_number_list_option(cmd, "--yaw-nodes", opt->yaw_nodes, kYawRule,
                         "Tabulate yaw at these nodes in every step's table ([grid] yaw of its scene, increasing; "
                         "e.g. -0.002,-0.001,0,0.001,0.002): the dynamics then reads each wheelset's yaw from the "
                         "tables [rad]");
  cmd->add_option("--post-processors", opt->post_processors,
                  "Wear post-processors instead of the scene's (e.g. hertz stripes-a)")
      ->check(error_check_validator(check_wear_post_processor));  // a misspelt name, at once
  auto quiet = add_quiet_flag(cmd);
  cmd->callback([opt, scene_file, quiet] {
    // The scene first (a bad one leaves no output directory behind), then the output directory:
    // now, not after the first table.
    const SimulationScene scene = load_simulation_scene(*scene_file);
    require_writable_directory(opt->out);
    opt->log = *quiet ? nullptr : &std::cerr;
    set_gnuplot_messages(diagnostics(*quiet));  // the wear charts' gnuplot warnings: silenced by -q
    // Ctrl-C / SIGTERM only set a flag that the table generation and the RK4 loop poll, so no
    // file is cut mid-write.
    SimulationSummary summary;
    run_interruptible([&](const std::atomic<bool>* interrupt) {
      opt->interrupt = interrupt;
      summary = run_simulation(scene, *opt);
    });
    std::cout << fmt::format("{}: {} ({} dynamics, {})\n", summary.name, (summary.directory / "summary.json").string(),
                             summary.dynamics_model, opt->direct ? "direct contact evaluation" : "table lookup");
    for (const ModelSummary& m : summary.models) {
      const double total = m.steps.empty() ? 0.0 : m.steps.back().cumulative_worn_area;
      std::cout << fmt::format(
          "  {:<14} worn area {:.4f} mm2 after {:.0f} km; wear centroid u = {:.2f} mm; at u < 0: {:.1f} %, at u < "
          "-25 mm: {:.1f} %; peak {:.2f} um at u = {:.2f} mm\n",
          m.model, total * 1e6, m.running_distance / 1e3, m.centroid_u * 1e3, 100 * m.flange_side_share,
          100 * m.flange_root_share, m.peak_depth * 1e6, m.peak_u * 1e3);
    }
    std::cout << fmt::format("  simulated seconds per wall-clock second: {:.2f}\n", simulation_speed(summary));
  });
}

}  // namespace railtab
