// SPDX-License-Identifier: Apache-2.0
// railtab conicity's files: JSON, CSVs and the gnuplot chart of conicity against amplitude, Delta r
// and the contact angle difference against y, for one pair and optionally a second one beside it.
#include "charts/conicity_chart.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "charts/gnuplot.hpp"
#include "table/output_file.hpp"

namespace railtab {
namespace {

std::string points_csv(const ConicityCurve& c) {
  std::ostringstream out;
  out << "amplitude_m,equivalent_conicity,equivalent_conicity_regression,wavelength_m,y_min_m,y_max_m,"
         "roll_angle_parameter,contact_angle_parameter\n";
  for (const ConicityPoint& p : c.points) {
    out << fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", p.amplitude, p.conicity,
                       p.conicity_regression, p.wavelength, p.y_min, p.y_max, p.roll_parameter,
                       p.contact_angle_parameter);
  }
  return out.str();
}

std::string functions_csv(const LateralFunctions& f) {
  std::ostringstream out;
  out << "y_m,roll_rad,rolling_radius_difference_m,contact_angle_difference,left_rolling_radius_m,"
         "right_rolling_radius_m,left_contact_angle_side_rad,right_contact_angle_side_rad\n";
  for (std::size_t i = 0; i < f.y.size(); ++i) {
    out << fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", f.y[i], f.roll[i], f.delta_r[i],
                       f.delta_tan_gamma[i], f.radius_left[i], f.radius_right[i], f.angle_left[i], f.angle_right[i]);
  }
  return out.str();
}

// Half height [mm] of the Delta r detail panel: 1.2 times the largest |Delta r| within 2 mm of the
// kinematic centre (the tread around the centred wheelset), at least 0.01 mm.
double detail_range(const ConicityCurve& c) {
  double largest = 0.0;
  for (std::size_t i = 0; i < c.functions.y.size(); ++i) {
    if (std::abs(c.functions.y[i] - c.centre) <= 2e-3) largest = std::max(largest, std::abs(c.functions.delta_r[i]));
  }
  return std::max(1.2e3 * largest, 0.01);
}

// The gnuplot script: conicity against amplitude; Delta r (whole and around the centre) and
// Delta tan gamma against y.
std::string chart_script(const ConicityCurve& c, const std::filesystem::path& points, const std::filesystem::path& functions,
                         const std::optional<ConicityCurve>& other, const std::filesystem::path& other_points,
                         const std::filesystem::path& other_functions) {
  // Names and titles come from the scene or table: gnuplot strings only (charts/gnuplot_string.hpp).
  const std::string& name = c.functions.name;
  const std::string title =
      gnuplot_string(fmt::format("{}: equivalent conicity, rigid wheelset, roll {}",
                                 other ? c.functions.name + " beside " + other->functions.name : c.functions.title,
                                 c.functions.roll_mode));
  const double detail = std::max(detail_range(c), other ? detail_range(*other) : 0.0);
  auto series = [](const std::filesystem::path& csv, const std::string& using_, const std::string& style,
                   const std::string& label) {
    return fmt::format("{} every ::1 using {} with {} title {}", gnuplot_quote(csv), using_, style, gnuplot_string(label));
  };
  std::string conicity = series(points, "($1*1e3):2", "linespoints lw 2 pt 7 lc 1", name + ": wavelength (EN 15302)") +
                         ", \\\n     " +
                         series(points, "($1*1e3):3", "linespoints lw 2 dt 2 pt 6 lc 1", name + ": regression");
  std::string delta_r = series(functions, "($1*1e3):($3*1e3)", "lines lw 2 lc 1", name);
  std::string delta_tan = series(functions, "($1*1e3):4", "lines lw 2 lc 1", name);
  if (other) {
    const std::string& other_name = other->functions.name;
    conicity += ", \\\n     " +
                series(other_points, "($1*1e3):2", "linespoints lw 2 pt 5 lc 2", other_name + ": wavelength (EN 15302)") +
                ", \\\n     " +
                series(other_points, "($1*1e3):3", "linespoints lw 2 dt 2 pt 4 lc 2", other_name + ": regression");
    delta_r += ", \\\n     " + series(other_functions, "($1*1e3):($3*1e3)", "lines lw 2 lc 2", other_name);
    delta_tan += ", \\\n     " + series(other_functions, "($1*1e3):4", "lines lw 2 lc 2", other_name);
  }
  return fmt::format(R"(set terminal pngcairo noenhanced size 1000,1400 font ",11"
set datafile separator ','
set datafile missing 'nan'
set multiplot layout 4,1 title {title} noenhanced
set grid
set key top left
set xlabel 'amplitude of the lateral motion [mm]'
set ylabel 'equivalent conicity tan(gamma_e) [-]'
plot {conicity}
set xlabel 'wheelset lateral displacement y [mm] (+ left)'
set ylabel 'r_left - r_right [mm]'
plot {delta_r}
set ylabel 'r_left - r_right [mm], detail'
set yrange [-{detail}:{detail}]
plot {delta_r}
set autoscale y
set ylabel 'tan(g_left) - tan(g_right) [-]'
plot {delta_tan}
unset multiplot
)",
                     fmt::arg("title", title),
                     fmt::arg("conicity", conicity), fmt::arg("delta_r", delta_r),
                     fmt::arg("detail", fmt::format("{:.6g}", detail)),
                     fmt::arg("delta_tan", delta_tan));
}

}  // namespace

nlohmann::json conicity_json(const ConicityCurve& c) {
  const LateralFunctions& f = c.functions;
  nlohmann::json j;
  j["pair"] = f.name;
  j["source"] = f.source;
  j["roll"] = f.roll_mode;
  j["e0_m"] = f.e0;
  j["r0_m"] = f.r0;
  j["centre_m"] = c.centre;
  auto column = [&](double ConicityPoint::*member) {
    nlohmann::json a = nlohmann::json::array();
    for (const ConicityPoint& p : c.points) a.push_back(std::isfinite(p.*member) ? nlohmann::json(p.*member) : nlohmann::json());
    return a;
  };
  j["amplitude_m"] = column(&ConicityPoint::amplitude);
  j["equivalent_conicity"] = column(&ConicityPoint::conicity);
  j["equivalent_conicity_regression"] = column(&ConicityPoint::conicity_regression);
  j["wavelength_m"] = column(&ConicityPoint::wavelength);
  j["y_min_m"] = column(&ConicityPoint::y_min);
  j["y_max_m"] = column(&ConicityPoint::y_max);
  j["roll_angle_parameter"] = column(&ConicityPoint::roll_parameter);
  j["contact_angle_parameter"] = column(&ConicityPoint::contact_angle_parameter);
  j["functions"] = {{"y_m", f.y},
                    {"roll_rad", f.roll},
                    {"rolling_radius_difference_m", f.delta_r},
                    {"contact_angle_difference", f.delta_tan_gamma}};
  return j;
}

ConicityFiles write_conicity_outputs(const std::filesystem::path& dir, const ConicityCurve& curve,
                                     const std::optional<ConicityCurve>& compare) {
  ConicityFiles files;
  auto text = [&](const std::string& file, const std::string& content) {
    write_text_file(dir / file, content);
    files.written.push_back(dir / file);
    return dir / file;
  };
  const auto points = text("conicity.csv", points_csv(curve));
  const auto functions = text("conicity_functions.csv", functions_csv(curve.functions));
  std::filesystem::path other_points, other_functions;
  nlohmann::json json = conicity_json(curve);
  if (compare) {
    other_points = text("conicity_compare.csv", points_csv(*compare));
    other_functions = text("conicity_compare_functions.csv", functions_csv(compare->functions));
    json["compare"] = conicity_json(*compare);
  }
  text("conicity.json", json.dump(1) + "\n");
  const std::filesystem::path png = dir / "conicity.png";
  run_gnuplot(dir / "conicity.gp", chart_script(curve, points, functions, compare, other_points, other_functions), png);
  files.written.push_back(dir / "conicity.gp");
  files.written.push_back(png);
  return files;
}

}  // namespace railtab
