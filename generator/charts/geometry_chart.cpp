// SPDX-License-Identifier: Apache-2.0
// Rolling radius difference and contact angles against y (flange jump visible): CSV, then gnuplot.
#include "charts/geometry_chart.hpp"

#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "charts/gnuplot.hpp"
#include "core/check.hpp"
#include "table/output_file.hpp"

namespace railtab {

std::pair<std::filesystem::path, std::filesystem::path> draw_geometry_chart(const Scene& scene,
                                                                            const std::filesystem::path& dir,
                                                                            const GeometryChartOptions& opt) {
  RAILTAB_CHECK(opt.y_step > 0.0 && opt.y_max > opt.y_min, "chart-geometry: need y-min < y-max and step > 0");
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  std::filesystem::create_directories(dir);
  const std::filesystem::path csv = dir / "geometry_sweep.csv";
  std::ostringstream out;
  out << "y_m,roll_rad,rolling_radius_difference_m,left_contact_angle_rad,right_contact_angle_rad,"
         "left_rolling_radius_m,right_rolling_radius_m,left_contacts,right_contacts\n";
  const int n = static_cast<int>(std::lround((opt.y_max - opt.y_min) / opt.y_step));
  for (int i = 0; i <= n; ++i) {
    const double y = opt.y_min + i * opt.y_step;
    const double roll = scene.equilibrium_roll ? solver.equilibrium_roll(y) : 0.0;
    const WheelsetContactGeometry g = solver.solve({y, roll});
    const ContactPoint& left = g.wheels[0].points.front();
    const ContactPoint& right = g.wheels[1].points.front();
    out << fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{}\n", y, roll,
                       g.rolling_radius_difference, left.contact_angle, right.contact_angle,
                       left.rolling_radius, right.rolling_radius, g.wheels[0].points.size(),
                       g.wheels[1].points.size());
  }
  write_text_file(csv, out.str());
  const std::filesystem::path png = dir / "geometry.png";
  const std::string script = fmt::format(R"(set terminal pngcairo noenhanced size 1000,800 font ",11"
set datafile separator ','
set multiplot layout 2,1 title {title} noenhanced
set grid
set key top left
set xlabel 'wheelset lateral displacement y [mm] (+ left)'
set ylabel 'r_left - r_right [mm]'
plot {csv} every ::1 using ($1*1e3):($3*1e3) with lines lw 2 title 'rolling radius difference'
set ylabel 'contact angle [deg]'
plot {csv} every ::1 using ($1*1e3):($4*180/pi) with lines lw 2 title 'left wheel', \
     {csv} every ::1 using ($1*1e3):($5*180/pi) with lines lw 2 title 'right wheel'
unset multiplot
)",
                                         fmt::arg("csv", gnuplot_quote(csv)),
                                         fmt::arg("title", gnuplot_string(fmt::format(
                                                               "{}: rigid contact geometry, roll {}",
                                                               scene_title(scene.name, scene.description),
                                                               scene.equilibrium_roll ? "at kinematic equilibrium" : "0"))));
  run_gnuplot(dir / "geometry.gp", script, png);
  return {csv, png};
}

}  // namespace railtab
