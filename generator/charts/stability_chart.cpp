// SPDX-License-Identifier: Apache-2.0
// The stability chart: the stability map's status flags per model and y, CSV then gnuplot.
#include "charts/stability_chart.hpp"

#include <fmt/format.h>

#include <array>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "charts/gnuplot.hpp"
#include "core/check.hpp"
#include "table/output_file.hpp"
#include "core/status.hpp"

namespace railtab {
namespace {

// The flags worth seeing on a map, in legend order.
struct Flag {
  StatusBits bit;
  const char* name;
  const char* colour;  // distinct for every flag (gnuplot's default cycle repeats after 8)
};
constexpr std::array<Flag, 10> kFlags{{
    {status::kTwoPoint, "two_point", "#7b2cbf"},
    {status::kFlangeContact, "flange_contact", "#1b9e77"},
    {status::kCurvatureShifted, "curvature_shifted", "#56b4e9"},
    {status::kCurvatureClipped, "curvature_clipped", "#e69f00"},
    {status::kNonHertzian, "non_hertzian", "#f0e442"},
    {status::kFallbackModel, "fallback_model", "#0072b2"},
    {status::kLiftOff, "lift_off", "#999999"},
    {status::kProfileEdge, "profile_edge", "#000000"},
    {status::kNotConverged, "not_converged", "#d55e00"},
    {status::kFailed, "failed", "#ff0000"},
}};

// The first `count` comma-separated fields of a line (the map's leading columns hold no commas).
std::vector<std::string> leading_fields(const std::string& line, std::size_t count) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (fields.size() < count && std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

}  // namespace

void draw_stability_chart(const Scene& scene, const std::filesystem::path& out_dir,
                          const StabilityMapOptions& options) {
  std::filesystem::create_directories(out_dir);
  const std::filesystem::path map_csv = out_dir / "stability_map.csv";
  write_stability_map_csv(scene, map_csv, options);

  // Rows of the chart: one per (variant, wheel), in the order of the map.
  std::ifstream in(map_csv);
  RAILTAB_CHECK(in.good(), "cannot read {}", map_csv.string());
  std::string line;
  std::getline(in, line);  // header: variant,model,negative_curvature,wheel,y_m,roll_rad,load_N,status,...
  std::map<std::string, int> row_of;
  std::vector<std::string> row_labels;
  const std::filesystem::path flags_csv = out_dir / "stability_map_flags.csv";
  std::ostringstream out;
  out << "y_mm,row,flag\n";
  while (std::getline(in, line)) {
    const std::vector<std::string> f = leading_fields(line, 8);
    RAILTAB_CHECK(f.size() == 8, "{}: malformed row '{}'", map_csv.string(), line);
    const std::string label = f[0] + " " + f[3];
    auto [it, inserted] = row_of.try_emplace(label, static_cast<int>(row_labels.size()));
    if (inserted) row_labels.push_back(label);
    const double y_mm = std::stod(f[4]) * 1e3;
    const auto bits = static_cast<StatusBits>(std::stoul(f[7]));
    for (std::size_t k = 0; k < kFlags.size(); ++k) {
      if (bits & kFlags[k].bit) out << fmt::format("{:.4f},{},{}\n", y_mm, it->second, k);
    }
  }
  write_text_file(flags_csv, out.str());

  std::string ytics;
  for (std::size_t r = 0; r < row_labels.size(); ++r) {
    ytics += fmt::format("{}\"{}\" {}", r ? ", " : "", row_labels[r], r);
  }
  std::string plots;
  for (std::size_t k = 0; k < kFlags.size(); ++k) {
    // Each flag sits at its own vertical offset inside the row, so overlapping flags stay visible.
    const double offset = -0.4 + 0.8 * static_cast<double>(k) / (kFlags.size() - 1);
    plots += fmt::format(
        "{}{} every ::1 using 1:($3=={} ? $2+({:.3f}) : NaN) with points pt 5 ps 0.35 lc rgb '{}' notitle",
        k ? ", \\\n     " : "", gnuplot_quote(flags_csv), k, offset, kFlags[k].colour);
  }
  // The legend gets its own, larger squares (keyentry): the data's 0.35 squares were too small to
  // tell the colours apart in the key.
  for (const auto& flag : kFlags) {
    plots += fmt::format(", \\\n     keyentry with points pt 5 ps 1.5 lc rgb '{}' title '{}'", flag.colour, flag.name);
  }
  const std::filesystem::path png = out_dir / "stability_map.png";
  const std::string script = fmt::format(R"gp(set terminal pngcairo noenhanced size 1400,{height} font ",10"
set datafile separator ','
set title {title} noenhanced
set xlabel 'wheelset lateral displacement y [mm] (+ left)'
set ytics ({ytics})
set yrange [-0.7:{top}]
set xrange [{xmin}:{xmax}]
set grid xtics
set key outside right top
plot {plots}
)gp",
      fmt::arg("height", 300 + 40 * row_labels.size()),
      fmt::arg("title", gnuplot_string(fmt::format(
                            "{}\nstatus flags of each normal model across y (load {:.1f} kN, roll {})",
                            scene_title(scene.name, scene.description), scene.grids.load[scene.grids.load.size() / 2] * 1e-3,
                            scene.equilibrium_roll ? "kinematic equilibrium" : "0"))),
      fmt::arg("ytics", ytics),
      fmt::arg("top", row_labels.size() - 0.3), fmt::arg("xmin", options.y_min * 1e3),
      fmt::arg("xmax", options.y_max * 1e3), fmt::arg("plots", plots));
  run_gnuplot(out_dir / "stability_map.gp", script, png);
}

}  // namespace railtab
