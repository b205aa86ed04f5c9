// railtab chart-*: charts made by the project's own commands, each from a CSV it writes first.
//   chart-geometry: rolling radius difference and contact angles against y (flange jump visible).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "core/check.hpp"
#include "gnuplot.hpp"
#include "scene.hpp"

namespace railtab {
namespace {

struct GeometryChartOptions {
  std::string scene_path = "tables/default.toml";  // scene file
  std::string out_dir = "out";                     // output directory
  double y_min = -0.010;                           // [m]
  double y_max = 0.010;                            // [m]
  double y_step = 0.05e-3;                         // [m]
};

void run_geometry_chart(const GeometryChartOptions& opt) {
  RAILTAB_CHECK(opt.y_step > 0.0 && opt.y_max > opt.y_min, "chart-geometry: need y-min < y-max and step > 0");
  const Scene scene = load_scene(opt.scene_path);
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const std::filesystem::path dir(opt.out_dir);
  std::filesystem::create_directories(dir);
  const std::filesystem::path csv = dir / "geometry_sweep.csv";
  std::ofstream out(csv);
  RAILTAB_CHECK(out.good(), "cannot write {}", csv.string());
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
  out.close();
  const std::filesystem::path png = dir / "geometry.png";
  const std::string script = fmt::format(R"(set terminal pngcairo size 1000,800 font ",11"
set output '{png}'
set datafile separator ','
set multiplot layout 2,1 title "{title}: rigid contact geometry, roll {roll}"
set grid
set xlabel 'wheelset lateral displacement y [mm] (+ left)'
set ylabel 'r_{{left}} - r_{{right}} [mm]'
plot '{csv}' every ::1 using ($1*1e3):($3*1e3) with lines lw 2 title 'rolling radius difference'
set ylabel 'contact angle [deg]'
plot '{csv}' every ::1 using ($1*1e3):($4*180/pi) with lines lw 2 title 'left wheel', \
     '{csv}' every ::1 using ($1*1e3):($5*180/pi) with lines lw 2 title 'right wheel'
unset multiplot
)",
                                         fmt::arg("png", png.string()), fmt::arg("csv", csv.string()),
                                         fmt::arg("title", scene.name),
                                         fmt::arg("roll", scene.equilibrium_roll ? "at kinematic equilibrium" : "0"));
  run_gnuplot(dir / "geometry.gp", script);
  std::cout << fmt::format("chart-geometry: wrote {} and {}\n", csv.string(), png.string());
}

}  // namespace

void add_chart_commands(CLI::App& app) {
  auto geo = std::make_shared<GeometryChartOptions>();
  CLI::App* cmd = app.add_subcommand(
      "chart-geometry", "Chart rolling radius difference and contact angle against y (CSV + PNG)");
  cmd->add_option("--scene", geo->scene_path, "Scene file (TOML)")->capture_default_str();
  cmd->add_option("--out", geo->out_dir, "Output directory")->capture_default_str();
  cmd->add_option("--y-min", geo->y_min, "First lateral displacement [m]")->capture_default_str();
  cmd->add_option("--y-max", geo->y_max, "Last lateral displacement [m]")->capture_default_str();
  cmd->add_option("--y-step", geo->y_step, "Step [m]")->capture_default_str();
  cmd->callback([geo] { run_geometry_chart(*geo); });
}

}  // namespace railtab
