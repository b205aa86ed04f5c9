// SPDX-License-Identifier: Apache-2.0
// The lateral functions of a wheelset (from a scene's rigid geometry or a table's geometry part) and
// the equivalent conicity, roll angle and contact angle parameters computed from them.
#include "charts/conicity.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "charts/gnuplot.hpp"
#include "core/check.hpp"
#include "geometry/equivalent_conicity.hpp"

namespace railtab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void add_sample(LateralFunctions& f, double y, double roll, double r_left, double r_right, double angle_left,
                double angle_right) {
  f.y.push_back(y);
  f.roll.push_back(roll);
  f.delta_r.push_back(r_left - r_right);
  f.delta_tan_gamma.push_back(std::tan(angle_left) - std::tan(angle_right));
  f.radius_left.push_back(r_left);
  f.radius_right.push_back(r_right);
  f.angle_left.push_back(angle_left);
  f.angle_right.push_back(angle_right);
}

// The index of `name` among a dataset's dimensions, -1 when absent.
int dimension(const TableDataset& d, const std::string& name) {
  for (std::size_t i = 0; i < d.axes.size(); ++i) {
    if (d.axes[i] == name) return static_cast<int>(i);
  }
  return -1;
}

// Q0 = back_to_back/2 - flange_back_position of the scene stored in the table (defaults as in
// WheelsetGeometry when the scene omits them).
double running_circle_position(const Table& table, const std::filesystem::path& path) {
  WheelsetGeometry w;
  if (const std::string* text = table.attribute("scene")) {
    try {
      const toml::table scene = toml::parse(*text);
      w.back_to_back = scene["wheelset"]["back_to_back"].value_or(w.back_to_back);
      w.flange_back_position = scene["wheelset"]["flange_back_position"].value_or(w.flange_back_position);
    } catch (const toml::parse_error& e) {
      throw Error(fmt::format("{}: the table's scene text does not parse: {}", path.string(), e.description()));
    }
  }
  return 0.5 * w.back_to_back - w.flange_back_position;
}

}  // namespace

LateralFunctions lateral_functions_from_scene(const Scene& scene, const ConicitySweep& sweep) {
  return lateral_functions_from_solver(make_geometry_solver(scene), scene.name,
                                       scene_title(scene.name, scene.description), sweep);
}

LateralFunctions lateral_functions_from_solver(const ContactGeometrySolver& solver, const std::string& name,
                                               const std::string& title, const ConicitySweep& sweep) {
  RAILTAB_CHECK(std::isfinite(sweep.y_max) && sweep.y_max > 0.0 && sweep.y_max <= kMaxLateralShift,
                "conicity: the y range must be positive and at most {} m, got {} m", kMaxLateralShift, sweep.y_max);
  RAILTAB_CHECK(std::isfinite(sweep.y_step) && sweep.y_step >= 1e-6 && sweep.y_step <= sweep.y_max,
                "conicity: the y step must be between 1e-6 m and the range, got {} m", sweep.y_step);
  LateralFunctions f;
  f.name = name;
  f.title = title;
  f.source = "scene";
  f.roll_mode = sweep.equilibrium_roll ? "equilibrium" : "fixed 0 rad";
  const int n = static_cast<int>(std::ceil(sweep.y_max / sweep.y_step - 1e-9));
  for (int i = -n; i <= n; ++i) {
    const double y = i * sweep.y_step;
    const double roll = sweep.equilibrium_roll ? solver.equilibrium_roll(y) : 0.0;
    const WheelsetContactGeometry g = solver.solve({y, roll});
    const ContactPoint& left = g.wheels[0].points.front();
    const ContactPoint& right = g.wheels[1].points.front();
    add_sample(f, y, roll, left.rolling_radius, right.rolling_radius, left.contact_angle_side,
               right.contact_angle_side);
    if (i == 0) {
      f.e0 = 0.5 * (left.y_track - right.y_track);
      f.r0 = 0.5 * (left.rolling_radius + right.rolling_radius);
    }
  }
  return f;
}

LateralFunctions lateral_functions_from_table(const Table& table, const std::filesystem::path& path) {
  const std::string where = path.string();
  const TableAxis* y_axis = table.axis("y");
  RAILTAB_CHECK(y_axis && y_axis->values.size() >= 3, "{}: conicity needs a y axis of at least 3 nodes", where);
  const std::vector<double>& ys = y_axis->values;
  LateralFunctions f;
  f.source = "table";
  const std::string* name = table.attribute("scene_name");
  f.name = name ? *name : path.stem().string();
  f.title = f.name;

  // Roll: the equilibrium roll dataset, the fixed value, or the node roll = 0 of a roll axis.
  std::vector<double> roll(ys.size(), 0.0);
  std::size_t roll_index = 0;
  const nlohmann::json fixed = nlohmann::json::parse(table.attribute("fixed_axes") ? *table.attribute("fixed_axes") : "{}",
                                                     nullptr, false);
  const TableAxis* roll_axis = table.axis("roll");
  if (roll_axis) {
    const auto& r = roll_axis->values;
    while (roll_index < r.size() && r[roll_index] != 0.0) ++roll_index;
    RAILTAB_CHECK(roll_index < r.size(),
                  "{}: conicity needs the wheelset unrolled or at its equilibrium roll, but roll is an axis "
                  "without the node 0 ({} nodes from {} to {} rad)",
                  where, r.size(), r.front(), r.back());
    f.roll_mode = "fixed 0 rad (roll axis node)";
  } else if (fixed.is_object() && fixed.contains("roll") && fixed["roll"].is_string()) {
    const TableGroup* root = table.group("");
    const TableDataset* eq = root ? root->find("equilibrium_roll") : nullptr;
    RAILTAB_CHECK(eq && eq->values.size() == ys.size(), "{}: roll follows the equilibrium but /equilibrium_roll "
                  "is missing or not one value per y", where);
    roll = eq->values;
    f.roll_mode = "equilibrium";
  } else {
    const double value = fixed.is_object() && fixed.contains("roll") && fixed["roll"].is_number() ? fixed["roll"].get<double>() : 0.0;
    roll.assign(ys.size(), value);
    f.roll_mode = fmt::format("fixed {} rad", value);
  }

  // Per wheel and y: the rolling radius and contact angle of the slot with the smaller separation.
  struct Primary {
    std::vector<double> radius, angle_side, wheel_u;
  };
  auto primary = [&](const std::string& wheel, double sign) {
    const TableGroup* g = table.group(wheel + "/geometry");
    RAILTAB_CHECK(g, "{}: no {}/geometry part", where, wheel);
    const TableDataset* radius = g->find("rolling_radius");
    const TableDataset* angle = g->find("contact_angle");
    const TableDataset* separation = g->find("separation");
    const TableDataset* wheel_y = g->find("wheel_y");
    const TableDataset* status = g->find("status");
    RAILTAB_CHECK(radius && angle && separation && wheel_y && status,
                  "{}: {}/geometry lacks rolling_radius, contact_angle, separation, wheel_y or status", where, wheel);
    const int dy = dimension(*radius, "y"), ds = dimension(*radius, "slot"), dr = dimension(*radius, "roll");
    RAILTAB_CHECK(dy >= 0 && ds >= 0 && radius->shape.size() == radius->axes.size(),
                  "{}: {}/geometry/rolling_radius is not over y and slot", where, wheel);
    std::vector<std::size_t> stride(radius->shape.size(), 1);
    for (int i = static_cast<int>(radius->shape.size()) - 2; i >= 0; --i) stride[i] = stride[i + 1] * radius->shape[i + 1];
    Primary p;
    for (std::size_t iy = 0; iy < ys.size(); ++iy) {
      double best_sep = std::numeric_limits<double>::infinity();
      std::size_t best = 0;
      for (std::size_t is = 0; is < radius->shape[ds]; ++is) {
        std::size_t at = iy * stride[dy] + is * stride[ds];
        if (dr >= 0) at += roll_index * stride[dr];
        if (!(status->status[at] & status::kConverged)) continue;  // an empty slot
        if (separation->values[at] < best_sep) {
          best_sep = separation->values[at];
          best = at;
        }
      }
      RAILTAB_CHECK(std::isfinite(best_sep), "{}: the {} wheel has no contact at y = {} m", where, wheel, ys[iy]);
      p.radius.push_back(radius->values[best]);
      p.angle_side.push_back(sign * angle->values[best]);
      p.wheel_u.push_back(wheel_y->values[best]);
    }
    return p;
  };
  const Primary left = primary("left", 1.0);
  const Primary right = primary("right", -1.0);
  for (std::size_t i = 0; i < ys.size(); ++i) {
    add_sample(f, ys[i], roll[i], left.radius[i], right.radius[i], left.angle_side[i], right.angle_side[i]);
  }
  // e0 and r0 at the node nearest y = 0 (roll there is negligible for e0).
  std::size_t i0 = 0;
  for (std::size_t i = 1; i < ys.size(); ++i) {
    if (std::abs(ys[i]) < std::abs(ys[i0])) i0 = i;
  }
  f.e0 = running_circle_position(table, path) + 0.5 * (left.wheel_u[i0] + right.wheel_u[i0]);
  f.r0 = 0.5 * (left.radius[i0] + right.radius[i0]);
  return f;
}

std::vector<double> default_conicity_amplitudes() {
  std::vector<double> a;
  for (int mm = 1; mm <= 10; ++mm) a.push_back(mm * 1e-3);
  return a;
}

void check_conicity_amplitudes(const std::vector<double>& amplitudes) {
  RAILTAB_CHECK(!amplitudes.empty(), "conicity: no amplitudes given");
  for (double a : amplitudes) {
    RAILTAB_CHECK(std::isfinite(a) && a > 0.0 && a <= kMaxLateralShift,
                  "conicity: amplitude {} m is not a positive lateral motion of at most {} m", a, kMaxLateralShift);
  }
}

ConicityCurve compute_conicity(LateralFunctions functions, const std::vector<double>& amplitudes) {
  check_conicity_amplitudes(amplitudes);
  ConicityCurve curve;
  curve.functions = std::move(functions);
  const LateralFunctions& f = curve.functions;
  const LateralFunction delta_r{f.y, f.delta_r};
  const LateralFunction roll{f.y, f.roll};
  const LateralFunction delta_tan{f.y, f.delta_tan_gamma};
  curve.centre = kinematic_centre(delta_r);
  for (double a : amplitudes) {
    const KinematicOscillation k = kinematic_oscillation(delta_r, a);
    ConicityPoint p{};
    p.amplitude = a;
    // A motion whose turning points jump past this amplitude (Delta r falling through zero beyond
    // the centre, hollow treads) has no oscillation of exactly this amplitude.
    p.conicity = std::abs(k.amplitude - a) <= 1e-9 ? k.conicity : kNaN;
    p.y_min = k.y_min;
    p.y_max = k.y_max;
    p.conicity_regression = regression_conicity(delta_r, a);
    p.wavelength = p.conicity > 0.0 ? 2.0 * std::numbers::pi * std::sqrt(f.e0 * f.r0 / p.conicity) : kNaN;
    p.roll_parameter = f.e0 * harmonic_regression_slope(roll, curve.centre, a);
    p.contact_angle_parameter = 0.5 * f.e0 * harmonic_regression_slope(delta_tan, curve.centre, a);
    curve.points.push_back(p);
  }
  return curve;
}

}  // namespace railtab
