// SPDX-License-Identifier: Apache-2.0
// Radial wear depth across the wheel profile per step: CSV, then the gnuplot chart.
#include "charts/wear_chart.hpp"

#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "charts/gnuplot.hpp"
#include "core/check.hpp"
#include "table/output_file.hpp"

namespace railtab {

void draw_wear_chart(const std::vector<WearSeries>& series, const std::filesystem::path& png,
                     const std::string& title) {
  RAILTAB_CHECK(!series.empty(), "wear chart {}: no series to draw", png.string());
  for (const WearSeries& s : series) {
    RAILTAB_CHECK(s.u.size() == s.depth.size() && !s.u.empty(),
                  "wear chart {}: series '{}' has {} positions and {} depths", png.string(), s.name, s.u.size(),
                  s.depth.size());
    // The name is a CSV field (and a gnuplot string, which takes any text).
    RAILTAB_CHECK(s.name.find_first_of("\",\n") == std::string::npos,
                  "wear chart {}: series name '{}' must not contain double quotes, commas or newlines", png.string(),
                  s.name);
  }
  if (png.has_parent_path()) std::filesystem::create_directories(png.parent_path());
  std::filesystem::path csv = png;
  csv.replace_extension(".csv");
  std::filesystem::path gp = png;
  gp.replace_extension(".gp");

  std::ostringstream out;
  out << "series,name,u_mm,depth_mm\n";
  std::string plots;
  for (std::size_t k = 0; k < series.size(); ++k) {
    const WearSeries& s = series[k];
    for (std::size_t i = 0; i < s.u.size(); ++i) {
      RAILTAB_CHECK(std::isfinite(s.u[i]) && std::isfinite(s.depth[i]),
                    "wear chart {}: series '{}' has a non-finite value at bin {}", png.string(), s.name, i);
      out << fmt::format("{},{},{:.4f},{:.6g}\n", k, s.name, s.u[i] * 1e3, s.depth[i] * 1e3);
    }
    plots += fmt::format("{}{} every ::1 using ($1=={} ? $3 : NaN):4 with lines lw {} title {}",
                         k ? ", \\\n     " : "", gnuplot_quote(csv), k, s.bold ? 3.0 : 1.2, gnuplot_string(s.name));
  }
  write_text_file(csv, out.str());

  const std::string script = fmt::format(R"gp(set terminal pngcairo noenhanced size 1100,650 font ",11"
set datafile separator ','
set title {title}
set xlabel 'wheel profile lateral coordinate u [mm] (+ field side, 0 = running circle)'
set ylabel 'radial wear depth [mm]'
set grid
set key top left
plot {plots}
)gp",
                                         fmt::arg("title", gnuplot_string(title)),
                                         fmt::arg("plots", plots));
  run_gnuplot(gp, script, png);
}

}  // namespace railtab
