// SPDX-License-Identifier: Apache-2.0
// railtab generate as a library call: adaptive grids, sweep, checkpoint and table file.
#include "generate/generate.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "core/number_input.hpp"
#include "adaptive/adaptive_grid.hpp"
#include "kernel/contact_kernel.hpp"
#include "adaptive/jump_locator.hpp"
#include "engine/parallel_for.hpp"
#include "engine/progress.hpp"
#include "adaptive/column_costs.hpp"
#include "generate/error_map.hpp"
#include "engine/shard_split.hpp"
#include "engine/mirror.hpp"
#include "engine/table_size.hpp"
#include "table/interrupt.hpp"
#include "table/table_io.hpp"

namespace railtab {

std::filesystem::path checkpoint_path(const std::filesystem::path& output) { return output.string() + ".partial"; }

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "MPI_LOCALNRANKS"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

namespace {

// Contact jumps along y (format 2.1) into `table`: located, their one-sided values sampled, a
// shard's own cells only (into kShardJumpGroup).
void add_contact_jumps(const GenerateOptions& options, const Scene& scene, Table& table, bool sharded) {
  std::ostream* log = options.log;
  CellRange cells;
  if (sharded) {
    cells.first = std::stoull(*table.attribute("shard_y_begin"));
    cells.last = std::stoull(*table.attribute("shard_y_end"));
  }
  const std::string root = sharded ? kShardJumpGroup : kJumpGroup;
  // Its own progress lines (the one-sided values cost columns of the kernel: minutes for the
  // exact model); none with --quiet.
  ProgressPrinter locating(log ? *log : std::cerr, options.terminal, "locating contact jumps", "tasks");
  ProgressPrinter sampling(log ? *log : std::cerr, options.terminal, "one-sided jump values", "columns");
  StageProgress locate_progress, sample_progress;
  if (log) locate_progress = [&locating](const SweepProgress& p) { locating(p); };
  if (log) sample_progress = [&sampling](const SweepProgress& p) { sampling(p); };
  // Both stages poll the interrupt flag through their progress reports (after a task, at most
  // every 0.25 s, and at the end), so SIGINT / SIGTERM stops them within one column: an exact
  // model's one-sided values would otherwise run on for minutes. A kept checkpoint stays.
  const bool checkpoint_kept = options.resume || options.always_checkpoint;
  auto stop_on_interrupt = [&options, checkpoint_kept](StageProgress report, const char* stage) -> StageProgress {
    if (!options.interrupt) return report;
    return [report = std::move(report), interrupt = options.interrupt, stage, checkpoint_kept](const SweepProgress& p) {
      if (interrupt->load()) {
        throw Interrupted(fmt::format("interrupted while {}: no table written{}", stage,
                                      checkpoint_kept ? "; the sweep's checkpoint is kept: rerun with --resume" : ""));
      }
      if (report) report(p);
    };
  };
  locate_progress = stop_on_interrupt(std::move(locate_progress), "locating the contact jumps");
  sample_progress = stop_on_interrupt(std::move(sample_progress), "computing the one-sided jump values");
  const auto t0 = std::chrono::steady_clock::now();
  ContactJumps jumps;
  auto t1 = t0;
  try {
    JumpLocatorOptions locator;
    locator.mirror = options.mirror;
    jumps = locate_jumps(scene, locator, options.threads, locate_progress, cells);
    locating.finish();
    t1 = std::chrono::steady_clock::now();
    add_jumps(table, scene, jumps, locator, options.threads, sample_progress, root);
  } catch (const Interrupted&) {
    throw;
  } catch (const Error& e) {
    // The locator and the one-sided values solve states between the grid nodes and stop at the
    // first failure, where the sweep flags a failed point and goes on: say which stage and file.
    throw Error(fmt::format("{}: locating the contact jumps along y: {} (keep the grid's y where the "
                            "wheels stay on their rails)",
                            options.scene.string(), e.what()));
  }
  sampling.finish();
  const auto t2 = std::chrono::steady_clock::now();
  if (log) {
    std::size_t n = 0;
    for (const auto& wheel : jumps.wheel)
      for (const auto& list : wheel) n += list.size();
    *log << fmt::format("located {} contact jump(s) along y ({} evaluations) in {:.2f} s, one-sided values in {:.2f} s\n",
                        n, jumps.evaluations, std::chrono::duration<double>(t1 - t0).count(),
                        std::chrono::duration<double>(t2 - t1).count());
  }
}

// The closing lines of a run: speed, resumed and failed points, the file written.
void log_generated(std::ostream& log, const GenerateOptions& options, const SweepSummary& s) {
  double rate = s.seconds > 0 ? static_cast<double>(s.points_computed) / s.seconds : 0.0;
  double per_point = s.points_computed > 0 ? s.seconds * s.threads / static_cast<double>(s.points_computed) : 0.0;
  log << fmt::format("computed {} points (both wheels each) in {:.2f} s with {} thread{}: {:.0f} points/s, "
                     "{:.3g} ms per point per thread{}\n",
                     s.points_computed, s.seconds, s.threads, s.threads == 1 ? "" : "s", rate,
                     1e3 * per_point * s.ranks, s.ranks > 1 ? fmt::format(" (each of {} MPI ranks)", s.ranks) : "");
  // Which sweep ran: the mirror (engine/mirror.hpp) computes the columns y >= 0 only.
  if (s.mirrored) {
    log << "mirrored sweep: the columns y < 0 are the mirror images of those at -y (the scene is mirror-symmetric)\n";
  } else {
    log << fmt::format("full sweep: {}\n", s.full_sweep_reason);
  }
  if (s.points_resumed > 0) log << fmt::format("resumed {} points from the checkpoint\n", s.points_resumed);
  if (s.failures > 0) {
    log << fmt::format("{} point(s) failed and are flagged failed; first: {}\n", s.failures,
                       s.first_failure);
  }
  log << fmt::format("wrote {} ({:.1f} KiB){}\n", options.output.string(),
                     static_cast<double>(std::filesystem::file_size(options.output)) / 1024.0,
                     options.shard_count > 1 ? fmt::format(", shard {}/{}", options.shard_index, options.shard_count)
                                             : "");
}

}  // namespace

SweepSummary generate_table(const GenerateOptions& options) {
  // Refused before any work: the output must be a regular file (or new) and not the scene itself;
  // the checkpoint beside it likewise.
  check_output_path(options.output, {options.scene});
  if (options.resume || options.always_checkpoint) check_output_path(checkpoint_path(options.output), {options.scene});
  Scene scene = load_scene(options.scene);
  // The profile files the scene names are inputs too: the output may replace none of them.
  std::vector<std::filesystem::path> inputs{options.scene};
  for (const ProfileSource* profile : {&scene.wheel, &scene.rail}) {
    if (!profile->file.empty()) inputs.push_back(profile->file);
  }
  check_output_path(options.output, inputs);
  if (options.resume || options.always_checkpoint) check_output_path(checkpoint_path(options.output), inputs);
  // [accuracy] scenes: place the adaptive axes' nodes first (docs/adaptive-grids.md); deterministic,
  // so shards and resumed runs get the same grids.
  AdaptiveGridSummary adaptive = build_adaptive_grids(scene, options.threads);
  if (options.log && scene.accuracy.enabled) {
    for (const AxisRefinement& r : adaptive.axes) {
      *options.log << fmt::format("adaptive {}: {} nodes, worst midpoint error {:.2f} of target, {} jump(s), "
                                  "{} unmet, {} evaluations: target {}\n",
                                  r.axis, r.nodes.size(), r.worst_error, r.jumps, r.unmet, r.evaluations,
                                  r.met() ? "met" : "NOT met");
    }
    *options.log << fmt::format("adaptive grids placed in {:.2f} s\n", adaptive.seconds);
  }
  // The grid's size before the kernel (which may solve per y node) and before any allocation. A
  // shard's y range is taken as an even split here (the cost-weighted split needs contact solves);
  // SweepPlan checks the exact range again before it allocates.
  const auto [y_begin, y_end] = shard_range(scene.grids.y.size(), options.shard_index, options.shard_count);
  const std::uint64_t points = table_points(scene, y_end - y_begin);
  check_table_size(scene, points, 0, options.max_points, options.max_bytes, contact_point_cost(scene));
  const SweepKernel kernel = options.make_kernel ? options.make_kernel(scene) : make_contact_kernel(scene);
  std::ostream* log = options.log;
  const std::uint64_t bytes = table_bytes(scene, kernel, y_end - y_begin);
  check_table_size(scene, points, bytes, options.max_points, options.max_bytes, kernel.point_cost);
  if (log) {
    // The estimate counts what the sweep solves: a mirrored sweep about half the points.
    const bool mirrored = options.mirror && mirror_obstacle(scene, kernel).empty();
    *log << describe_table_size(points, computed_points(scene, y_begin, y_end, mirrored), bytes,
                                effective_threads(options.threads), kernel.point_cost);
  }

  ProgressPrinter printer(log ? *log : std::cerr, options.terminal);
  SweepOptions sweep;
  sweep.threads = options.threads;
  sweep.shard_index = options.shard_index;
  sweep.shard_count = options.shard_count;
  if (options.shard_count > 1) sweep.y_costs = column_costs(scene);  // flange columns count more
  sweep.interrupt = options.interrupt;
  sweep.max_points = options.max_points;
  sweep.max_bytes = options.max_bytes;
  sweep.mirror = options.mirror;
  const bool keep_checkpoint = options.resume || options.always_checkpoint;
  if (keep_checkpoint) sweep.checkpoint = checkpoint_path(options.output);
  if (options.always_checkpoint && !options.resume && options.writes_files) {
    std::error_code ignored;  // a fresh run: an old checkpoint is not resumed
    std::filesystem::remove(sweep.checkpoint, ignored);
  }
  if (log) sweep.progress = [&printer](const SweepProgress& p) { printer(p); };

  std::optional<SweepResult> computed =
      options.engine ? options.engine(scene, kernel, sweep) : std::optional<SweepResult>(run_sweep(scene, kernel, sweep));
  if (!computed) return {};  // an MPI rank other than 0: rank 0 writes the table
  SweepResult& result = *computed;
  printer.finish();
  SweepSummary& s = result.summary;
  if (log && s.checkpoint_discarded) {
    *log << fmt::format("note: {} belonged to another scene or build; started afresh\n", sweep.checkpoint.string());
  }
  bool stop = options.interrupt && options.interrupt->load();
  if (s.interrupted || stop) {
    throw Interrupted(keep_checkpoint
                          ? fmt::format("interrupted: {} of {} y blocks kept in {}; rerun with --resume to finish",
                                        s.blocks_done, s.blocks_total, sweep.checkpoint.string())
                          : fmt::format("interrupted: nothing written ({} of {} y blocks were done; use --resume "
                                        "to keep finished blocks)",
                                        s.blocks_done, s.blocks_total));
  }
  if (scene.accuracy.enabled) {
    result.table.set_attribute("accuracy_targets", adaptive.targets_json(scene).dump());
    result.table.set_attribute("accuracy_achieved", adaptive.achieved_json().dump());
  }
  // Contact jumps along y (format 2.1), only with the contact kernel (the probe runs the scene's
  // contact chain). Every y cell's jumps are located independently, so a shard locates those of
  // its own cells (from its first node to the next shard's first) into kShardJumpGroup, and
  // `railtab merge` joins them into the single run's kJumpGroup.
  const bool sharded = options.shard_count > 1;
  if (sharded) result.table.set_attribute("shard_jumps", options.make_kernel ? "not located" : "located");
  if (!options.make_kernel) add_contact_jumps(options, scene, result.table, sharded);
  // The error map reads the written table through the lookup: written once to a stage file beside
  // the output, measured, then written with the map. A shard has no full table: `railtab merge`
  // computes the map on the merged one (the same function, so the same bytes).
  if (!options.make_kernel && !sharded) {
    const std::filesystem::path stage = options.output.string() + ".errmap-stage";
    check_output_path(stage, inputs);
    write_table(result.table, stage, options.interrupt, inputs);
    try {
      ErrorMap map = compute_error_map(scene, stage, options.threads);
      if (log) {
        *log << fmt::format("error map: {} states against the model, {} against the exact model, in {:.2f} s "
                            "(exact model {:.2f} s)\n",
                            map.model_states, map.exact_states, map.seconds, map.exact_seconds);
      }
      add_error_map(result.table, std::move(map));
    } catch (...) {
      std::error_code ignored;
      std::filesystem::remove(stage, ignored);
      throw;
    }
    std::error_code ignored;
    std::filesystem::remove(stage, ignored);
  }
  write_table(result.table, options.output, options.interrupt, inputs);
  if (keep_checkpoint) {
    std::error_code ignored;
    std::filesystem::remove(sweep.checkpoint, ignored);
  }

  if (log) log_generated(*log, options, s);
  return s;
}

}  // namespace railtab
