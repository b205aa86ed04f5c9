// SPDX-License-Identifier: Apache-2.0
// railtab conicity (--scene S | --table T) [--amplitudes a,b,...] [--compare S2|T2] [--json] [--out DIR]:
// equivalent conicity against amplitude (EN 15302 reference principle and regression), roll angle
// and contact angle parameters (charts/conicity.hpp); files and chart through charts/conicity_chart.hpp.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "charts/conicity.hpp"
#include "charts/conicity_chart.hpp"
#include "charts/gnuplot.hpp"
#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "cli/number_options.hpp"
#include "core/check.hpp"
#include "railtab/lookup.hpp"
#include "scene/state_rules.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

struct ConicityOptions {
  std::string scene_path;            // --scene: scene file
  std::string table_path;            // --table: generated table
  std::string compare_path;          // --compare: a second pair (scene or table), drawn beside
  std::vector<double> amplitudes;    // [m]; empty = 1 to 10 mm
  double y_max = 0.0;                // sweep range of a scene [m]; 0 = largest amplitude + 1 mm
  double y_step = 0.05e-3;           // sweep step of a scene [m]
  bool zero_roll = false;            // --zero-roll: the unrolled wheelset (Klingel) instead of equilibrium
  std::string out_dir;               // --out: where the files go (none without it)
  bool json = false;                 // JSON on stdout instead of text
  bool quiet = false;
};

// True when `path` starts with the HDF5 signature (a table), false for anything else (a scene).
bool is_hdf5(const std::string& path) {
  static constexpr std::array<char, 8> kSignature = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> head{};
  return in.read(head.data(), head.size()) && head == kSignature;
}

// One pair as given: a scene or a table, loaded (and a table checked by the lookup) before any
// output is created or any geometry solved.
struct PairInput {
  std::string path;
  std::optional<Scene> scene;
  std::optional<Table> table;
};

PairInput load_pair(const std::string& path, bool table) {
  PairInput in{path, std::nullopt, std::nullopt};
  if (!table) {
    in.scene = load_scene(path);
    return in;
  }
  try {
    lookup::Table::load(path);  // a corrupt or crafted file is refused before the reader sees it
  } catch (const lookup::LoadError& e) {
    throw Error(e.what());
  }
  in.table = read_table(path);
  return in;
}

LateralFunctions lateral_functions(const PairInput& in, const ConicityOptions& opt, const std::vector<double>& amplitudes) {
  if (in.table) return lateral_functions_from_table(*in.table, in.path);
  ConicitySweep sweep;
  sweep.y_step = opt.y_step;
  sweep.equilibrium_roll = !opt.zero_roll;
  sweep.y_max = opt.y_max > 0.0 ? opt.y_max : *std::max_element(amplitudes.begin(), amplitudes.end()) + 1e-3;
  return lateral_functions_from_scene(*in.scene, sweep);
}

void print_text(const ConicityCurve& c) {
  const LateralFunctions& f = c.functions;
  std::cout << fmt::format("conicity: {} [{}, roll {}]\n", f.title, f.source, f.roll_mode);
  std::cout << fmt::format("centre y = {:.4f} mm (Delta r = 0), e0 = {:.4f} m, r0 = {:.4f} m\n", c.centre * 1e3, f.e0, f.r0);
  std::cout << fmt::format("{:>9} {:>11} {:>11} {:>10} {:>9} {:>9} {:>9} {:>9}\n", "A [mm]", "tan_ge", "tan_ge_reg",
                           "lambda [m]", "ymin [mm]", "ymax [mm]", "sigma", "epsilon");
  for (const ConicityPoint& p : c.points) {
    std::cout << fmt::format("{:>9.3f} {:>11.5f} {:>11.5f} {:>10.2f} {:>9.3f} {:>9.3f} {:>9.5f} {:>9.4f}\n",
                             p.amplitude * 1e3, p.conicity, p.conicity_regression, p.wavelength, p.y_min * 1e3,
                             p.y_max * 1e3, p.roll_parameter, p.contact_angle_parameter);
  }
}

void run_conicity(const ConicityOptions& opt) {
  RAILTAB_CHECK(opt.scene_path.empty() != opt.table_path.empty(), "conicity: give exactly one of --scene and --table");
  const std::vector<double> amplitudes = opt.amplitudes.empty() ? default_conicity_amplitudes() : opt.amplitudes;
  check_conicity_amplitudes(amplitudes);
  const bool from_table = !opt.table_path.empty();
  const PairInput first = load_pair(from_table ? opt.table_path : opt.scene_path, from_table);
  std::optional<PairInput> second;
  if (!opt.compare_path.empty()) second = load_pair(opt.compare_path, is_hdf5(opt.compare_path));
  if (!opt.out_dir.empty()) require_writable_directory(opt.out_dir);
  const ConicityCurve curve = compute_conicity(lateral_functions(first, opt, amplitudes), amplitudes);
  std::optional<ConicityCurve> compare;
  if (second) compare = compute_conicity(lateral_functions(*second, opt, amplitudes), amplitudes);
  if (opt.json) {
    nlohmann::json j = conicity_json(curve);
    if (compare) j["compare"] = conicity_json(*compare);
    std::cout << j.dump() << "\n";
  } else {
    print_text(curve);
    if (compare) print_text(*compare);
  }
  if (!opt.out_dir.empty()) {
    const ConicityFiles files = write_conicity_outputs(opt.out_dir, curve, compare);
    for (const auto& f : files.written) diagnostics(opt.quiet) << fmt::format("conicity: wrote {}\n", f.string());
  }
}

}  // namespace

void add_conicity_command(CLI::App& app) {
  auto opt = std::make_shared<ConicityOptions>();
  CLI::App* cmd = app.add_subcommand(
      "conicity", "Equivalent conicity against amplitude (EN 15302), roll angle and contact angle parameters");
  auto* scene = cmd->add_option("--scene", opt->scene_path, "Scene file (TOML): rigid geometry solved along y");
  auto* table = cmd->add_option("--table", opt->table_path, "Generated table (HDF5): its geometry part");
  scene->excludes(table);
  // Amplitudes and the sweep: numbers by the one reader (number_options.hpp), exit 2 when refused.
  add_number_list_option(cmd, "--amplitudes", opt->amplitudes, NumberRule{1e-6, kMaxLateralShift, false, "m"},
                         "Amplitudes of the lateral motion [m] (default 0.001,...,0.010)");
  cmd->add_option("--compare", opt->compare_path, "A second pair (scene or table) to report and chart beside");
  add_number_option(cmd, "--y-max", opt->y_max, NumberRule{1e-6, kMaxLateralShift, false, "m"},
                    "Scene sweep from -y-max to +y-max [m] (default: largest amplitude + 0.001)")
      ->default_str("");
  add_number_option(cmd, "--y-step", opt->y_step, NumberRule{1e-6, kMaxLateralShift, false, "m"},
                    "Scene sweep step [m]");
  cmd->add_flag("--zero-roll", opt->zero_roll,
                "Scene: keep the wheelset unrolled (default: its kinematic equilibrium roll, both wheels touching)");
  cmd->add_flag("--json", opt->json, "Print JSON (amplitude_m, equivalent_conicity, ...) instead of text");
  cmd->add_option("--out", opt->out_dir, "Write conicity.csv, conicity_functions.csv, conicity.json and conicity.png here");
  cmd->add_flag("-q,--quiet", opt->quiet, "No diagnostics on stderr (results and errors are still printed)");
  cmd->callback([opt] {
    set_gnuplot_messages(diagnostics(opt->quiet));  // gnuplot's warnings: silenced by -q
    run_conicity(*opt);
  });
}

}  // namespace railtab
