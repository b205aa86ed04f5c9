// SPDX-License-Identifier: Apache-2.0
// Pressure along the strip centre lines of every normal model: CSV, then the gnuplot chart.
#include "charts/pressure_chart.hpp"

#include <fmt/format.h>

#include <array>
#include <sstream>
#include <iostream>
#include <string>

#include "charts/gnuplot.hpp"
#include "core/check.hpp"
#include "table/output_file.hpp"

namespace railtab {
namespace {

struct Variant {
  const char* label;
  NormalModel model;
  NegativeCurvature negative_curvature;
};
// Seed 000's comparison first (A with the classic clip + smoothing, A&B with the shift), then the rest.
constexpr std::array<Variant, 7> kVariants{{
    {"stripes-a clip+smooth", NormalModel::stripes_a, NegativeCurvature::clip_and_smooth},
    {"stripes-ab shift", NormalModel::stripes_ab, NegativeCurvature::shift},
    {"stripes-a shift", NormalModel::stripes_a, NegativeCurvature::shift},
    {"stripes-ab clip+smooth", NormalModel::stripes_ab, NegativeCurvature::clip_and_smooth},
    {"kik-piotrowski", NormalModel::kik_piotrowski, NegativeCurvature::shift},
    {"linder", NormalModel::linder, NegativeCurvature::shift},
    {"hertz", NormalModel::hertz, NegativeCurvature::shift},
}};

}  // namespace

void draw_pressure_chart(const Scene& scene, const std::filesystem::path& out_dir,
                         const PressureChartOptions& options) {
  std::filesystem::create_directories(out_dir);
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const double roll = scene.equilibrium_roll ? solver.equilibrium_roll(options.y) : 0.0;
  const WheelContactGeometry geometry = solver.solve_wheel(options.side, {options.y, roll});

  const std::filesystem::path csv = out_dir / "pressure.csv";
  std::ostringstream out;
  out << "variant,s_mm,rail_y_mm,pressure_MPa\n";
  std::string plots;
  for (std::size_t v = 0; v < kVariants.size(); ++v) {
    NormalOptions normal = scene.normal;
    normal.model = kVariants[v].model;
    normal.negative_curvature = kVariants[v].negative_curvature;
    normal.hertz_strips = true;  // the Hertz ellipse as strips, to draw it like the others
    const WheelNormalResult result = solve_normal_for_load(geometry, options.load, scene.material, normal);
    double peak = 0.0;
    for (const ContactPatch& patch : result.patches) {
      for (const Strip& strip : patch.strips) {
        out << fmt::format("{},{:.5f},{:.5f},{:.3f}\n", v, strip.s * 1e3, strip.rail_u * 1e3,
                           strip.pressure_peak * 1e-6);
        peak = std::max(peak, strip.pressure_peak);
      }
    }
    std::cout << fmt::format("  {:<24} p_max {:7.1f} MPa, {} patch(es), status {}\n", kVariants[v].label,
                             peak * 1e-6, result.patches.size(), status::describe(result.status));
    plots += fmt::format("{}{} every ::1 using ($1=={} ? $3 : NaN):4 with linespoints pt 7 ps 0.4 lw {} title '{}'",
                         v ? ", \\\n     " : "", gnuplot_quote(csv), v, v < 2 ? 2.5 : 1.0, kVariants[v].label);
  }
  write_text_file(csv, out.str());
  if (options.reference_max_pressure > 0.0) {
    plots += fmt::format(", \\\n     {:.1f} with lines dt 2 lc rgb 'black' title 'half-space p_max (CONTACT)'",
                         options.reference_max_pressure * 1e-6);
  }
  const std::filesystem::path png = out_dir / "pressure.png";
  const std::string script = fmt::format(R"gp(set terminal pngcairo noenhanced size 1100,650 font ",11"
set datafile separator ','
set title {title} noenhanced
set xlabel 'lateral position on the rail profile [mm] (+ field side)'
set ylabel 'pressure [MPa]'
set grid
set key outside right top
plot {plots}
)gp",
      fmt::arg("title", gnuplot_string(fmt::format(
                            "{}\npeak pressure along the strip centre lines, {} wheel, y = {:.1f} mm, {:.1f} kN",
                            scene_title(scene.name, scene.description), to_string(options.side), options.y * 1e3,
                            options.load * 1e-3))),
      fmt::arg("plots", plots));
  run_gnuplot(out_dir / "pressure.gp", script, png);
}

}  // namespace railtab
