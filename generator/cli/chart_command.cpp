// SPDX-License-Identifier: Apache-2.0
// railtab chart-*: option parsing for the charts of generator/charts/, each drawn from a CSV it writes.
//   chart-geometry: rolling radius difference and contact angles against y (geometry_chart.hpp).
//   chart-pressure: pressure along the strip centre lines of every normal model (pressure_chart.hpp).
//   chart-stability: which status flags each normal model raises across y (stability_chart.hpp).
//   chart: speed against accuracy of every contact model setting and of table lookup
//          (speed_accuracy_chart.hpp; docs/speed-vs-accuracy.md).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "charts/geometry_chart.hpp"
#include "charts/gnuplot.hpp"
#include "charts/pressure_chart.hpp"
#include "speed_accuracy/speed_accuracy_chart.hpp"
#include "charts/stability_chart.hpp"
#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "cli/number_options.hpp"
#include "scene/scene.hpp"
#include "scene/state_rules.hpp"

namespace railtab {
namespace {

struct GeometryCommandOptions {
  std::string scene_path = "tables/default.toml";  // scene file
  std::string out_dir = "out";                     // output directory
  bool quiet = false;                              // -q: no "wrote" lines
  GeometryChartOptions chart;                      // y range and step [m]
};

void run_geometry_chart(const GeometryCommandOptions& opt) {
  const Scene scene = load_scene(opt.scene_path);  // a bad scene leaves no output directory behind
  require_writable_directory(opt.out_dir);
  const auto [csv, png] = draw_geometry_chart(scene, opt.out_dir, opt.chart);
  diagnostics(opt.quiet) << fmt::format("chart-geometry: wrote {} and {}\n", csv.string(), png.string());
}

struct SpeedChartOptions {
  std::string scene_path = "tables/default.toml";  // scene file
  std::string out_dir = "out";                     // output directory
  std::string reference;                           // block C CSV; default <source>/../shared/...
  int repeats = 11;                                // timed runs per state and model
  bool quick = false;                              // fewer settings (smoke runs)
  bool keep_tables = false;                        // keep the generated .h5 tables
  bool quiet = false;                              // -q: no "wrote" line
};

void run_speed_chart(const SpeedChartOptions& opt) {
  const Scene scene = load_scene(opt.scene_path);
  require_writable_directory(opt.out_dir);
  SpeedAccuracyOptions so;
  so.reference_csv = opt.reference.empty()
                         ? std::filesystem::path(RAILTAB_SOURCE_DIR) / ".." / "shared" / "reference" /
                               "blockC_sweep_integer_dy.csv"
                         : std::filesystem::path(opt.reference);
  so.keep_tables = opt.keep_tables;
  so.repeats = opt.repeats;
  if (opt.quick) {
    so.models = quick_model_settings();
    so.tables = quick_table_settings();
  }
  SpeedAccuracyChartFiles files;
  const SpeedAccuracyResult r = draw_speed_accuracy_charts(scene, opt.out_dir, so, files);
  std::cout << fmt::format("chart: {} states, {}; {}\n", r.states.size(), r.reference, r.setup);
  std::cout << fmt::format("{:<32} {:>9} {:>9} {:>9} {:>8} {:>8} {:>8} {:>10}\n", "setting", "t_tread", "t_flange",
                           "t_all", "e_tread", "e_flange", "e_all", "mem [B]");
  for (const SaRow& row : r.rows) {
    std::cout << fmt::format("{:<32} {:>8.2f}u {:>8.2f}u {:>8.2f}u {:>7.1f}% {:>7.1f}% {:>7.1f}% {:>10}{}\n",
                             row.label, row.time_tread_us, row.time_flange_us, row.time_us, row.err_force_tread * 100,
                             row.err_force_flange * 100, row.err_force * 100,
                             row.kind == "lookup" ? std::to_string(row.memory_bytes) : std::string("-"),
                             row.pareto_tread || row.pareto_flange ? "  *Pareto" : "");
  }
  diagnostics(opt.quiet) << fmt::format("chart: wrote {}, {}, {}, {} in {:.1f} s\n", files.csv.string(), files.png.string(),
                           files.memory_csv.string(), files.memory_png.string(), r.seconds);
}

// The options every chart command shares: the scene, the output directory, -q/--quiet.
void add_scene_and_out(CLI::App* cmd, std::string& scene_path, std::string& out_dir, bool& quiet) {
  cmd->add_option("--scene", scene_path, "Scene file (TOML)")->capture_default_str();
  cmd->add_option("--out", out_dir, "Output directory")->capture_default_str();
  cmd->add_flag("-q,--quiet", quiet, "No progress or diagnostics on stderr (results and errors are still printed)");
  // gnuplot's warnings are diagnostics too: silenced by -q (its errors are in the error message).
  cmd->parse_complete_callback([&quiet] { set_gnuplot_messages(diagnostics(quiet)); });
}

// A y sweep: first, last and step [m]; the step from 1 um (at most 2e5 points over the widest
// sweep) to the whole width.
constexpr NumberRule kYStepRule{1e-6, 2 * kMaxLateralShift, false, "m"};
// chart --repeats: timed runs per state and model.
constexpr NumberRule kRepeatsRule{1, 1000, true, ""};
// chart-pressure --reference-pmax: a contact pressure (up to 100 GPa).
constexpr NumberRule kPressureRule{0.0, 1e11, false, "Pa"};

void add_y_range(CLI::App* cmd, double& y_min, double& y_max, double& y_step) {
  add_number_option(cmd, "--y-min", y_min, kLateralShiftRule, "First lateral displacement [m]");
  add_number_option(cmd, "--y-max", y_max, kLateralShiftRule, "Last lateral displacement [m]");
  add_number_option(cmd, "--y-step", y_step, kYStepRule, "Step [m]");
}

}  // namespace

void add_chart_commands(CLI::App& app) {
  auto geo = std::make_shared<GeometryCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "chart-geometry", "Chart rolling radius difference and contact angle against y (CSV + PNG)");
  add_scene_and_out(cmd, geo->scene_path, geo->out_dir, geo->quiet);
  add_y_range(cmd, geo->chart.y_min, geo->chart.y_max, geo->chart.y_step);
  cmd->callback([geo] { run_geometry_chart(*geo); });

  struct StabilityChartOptions {
    std::string scene_path = "tables/default.toml";  // scene file
    std::string out_dir = "out";                     // output directory
    bool quiet = false;                              // -q: no "wrote" line
    StabilityMapOptions map;                         // y range and step [m]
  };
  auto st = std::make_shared<StabilityChartOptions>();
  CLI::App* stab = app.add_subcommand(
      "chart-stability", "Chart the status flags of every normal model across y (CSV + PNG)");
  add_scene_and_out(stab, st->scene_path, st->out_dir, st->quiet);
  add_y_range(stab, st->map.y_min, st->map.y_max, st->map.y_step);
  stab->callback([st] {
    const Scene scene = load_scene(st->scene_path);
    require_writable_directory(st->out_dir);
    draw_stability_chart(scene, st->out_dir, st->map);
    diagnostics(st->quiet) << fmt::format("chart-stability: wrote {}/stability_map.csv and stability_map.png\n", st->out_dir);
  });

  struct PressureCommandOptions {
    std::string scene_path = "tables/default.toml";  // scene file
    std::string out_dir = "out";                     // output directory
    std::string side = "right";                      // wheel
    bool quiet = false;                              // -q: no "wrote" line
    PressureChartOptions chart;
  };
  auto pr = std::make_shared<PressureCommandOptions>();
  CLI::App* pres = app.add_subcommand(
      "chart-pressure", "Chart the pressure along the strip centre lines of every normal model (CSV + PNG)");
  add_scene_and_out(pres, pr->scene_path, pr->out_dir, pr->quiet);
  add_number_option(pres, "--y", pr->chart.y, kLateralShiftRule, "Wheelset lateral displacement [m]");
  add_number_option(pres, "--load", pr->chart.load, kWheelLoadRule, "Vertical wheel load [N]");
  pres->add_option("--wheel", pr->side, "left|right")->check(CLI::IsMember({"left", "right"}))->capture_default_str();
  add_number_option(pres, "--reference-pmax", pr->chart.reference_max_pressure, kPressureRule,
                    "Half-space maximum pressure to draw as a line [Pa] (e.g. CONTACT block A: 888e6)");
  pres->callback([pr] {
    pr->chart.side = pr->side == "left" ? Side::left : Side::right;
    const Scene scene = load_scene(pr->scene_path);
    require_writable_directory(pr->out_dir);
    draw_pressure_chart(scene, pr->out_dir, pr->chart);
    diagnostics(pr->quiet) << fmt::format("chart-pressure: wrote {}/pressure.csv and pressure.png\n", pr->out_dir);
  });

  auto sa = std::make_shared<SpeedChartOptions>();
  CLI::App* chart = app.add_subcommand(
      "chart", "Speed against accuracy of every contact model and of table lookup (CSV + PNG charts)");
  add_scene_and_out(chart, sa->scene_path, sa->out_dir, sa->quiet);
  chart->add_option("--reference", sa->reference,
                    "CONTACT block C CSV (default: <source>/../shared/reference/blockC_sweep_integer_dy.csv; "
                    "absent: the exact half-space model as reference)");
  add_count_option(chart, "--repeats", sa->repeats, kRepeatsRule, "Timed runs per state and model setting");
  chart->add_flag("--quick", sa->quick, "Few settings only (smoke run)");
  chart->add_flag("--keep-tables", sa->keep_tables, "Keep the generated tables in OUT/tables");
  chart->callback([sa] { run_speed_chart(*sa); });
}

}  // namespace railtab
