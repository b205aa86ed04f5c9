// SPDX-License-Identifier: Apache-2.0
// Stability map: runs every normal model across y and records the status flags it raises.
#include "charts/stability_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/check.hpp"
#include "table/output_file.hpp"
#include "core/status.hpp"
#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"

namespace railtab {
namespace {

// CSV field: status names are comma-separated by status::describe; use ';' inside a field.
std::string names(StatusBits bits) {
  std::string s = status::describe(bits);
  std::replace(s.begin(), s.end(), ',', ';');
  return s;
}

// Error text as one CSV field (quoted, inner quotes doubled, no line breaks).
std::string csv_quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += "\"\"";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out + "\"";
}

}  // namespace

void write_stability_map_csv(const Scene& scene, const std::filesystem::path& csv,
                             const StabilityMapOptions& options) {
  RAILTAB_CHECK(std::isfinite(options.y_min) && std::isfinite(options.y_max) &&
                    std::isfinite(options.y_step) && options.y_step > 0.0 &&
                    options.y_max >= options.y_min,
                "stability map: y range [{}, {}] m, step {} m is invalid", options.y_min,
                options.y_max, options.y_step);
  RAILTAB_CHECK(!scene.grids.load.empty(), "stability map: the scene has no load grid");
  const double count_f = std::floor((options.y_max - options.y_min) / options.y_step + 1e-9) + 1.0;
  RAILTAB_CHECK(count_f <= 1e6, "stability map: {} y values are too many", count_f);
  const int count = static_cast<int>(count_f);
  std::vector<double> ys(static_cast<std::size_t>(count));
  // Rounded to 1 nm so that grid values print cleanly (0, not 1.7e-18).
  for (int i = 0; i < count; ++i)
    ys[static_cast<std::size_t>(i)] = std::round((options.y_min + i * options.y_step) * 1e9) / 1e9;

  const double load = scene.grids.load[scene.grids.load.size() / 2];
  const ContactGeometrySolver solver = make_geometry_solver(scene);

  struct Variant {
    NormalModel model;
    NegativeCurvature treatment;
  };
  const Variant variants[] = {
      {NormalModel::hertz, scene.normal.negative_curvature},
      {NormalModel::linder, scene.normal.negative_curvature},
      {NormalModel::kik_piotrowski, scene.normal.negative_curvature},
      {NormalModel::stripes_a, NegativeCurvature::shift},
      {NormalModel::stripes_a, NegativeCurvature::clip_and_smooth},
      {NormalModel::stripes_ab, NegativeCurvature::shift},
      {NormalModel::stripes_ab, NegativeCurvature::clip_and_smooth}};

  // Geometry once per (wheel, y); a throw there fails every variant of that point.
  struct GeometryPoint {
    double roll = 0.0;
    WheelContactGeometry geometry;
    std::string error;
  };
  std::vector<GeometryPoint> geo(2 * ys.size());
  for (std::size_t i = 0; i < ys.size(); ++i) {
    double roll = 0.0;
    std::string roll_error;
    try {
      if (scene.equilibrium_roll) roll = solver.equilibrium_roll(ys[i]);
    } catch (const std::exception& e) {
      roll_error = fmt::format("equilibrium roll: {}", e.what());
    }
    for (int w = 0; w < 2; ++w) {
      GeometryPoint& gp = geo[static_cast<std::size_t>(w) * ys.size() + i];
      gp.roll = roll;
      gp.error = roll_error;
      if (!gp.error.empty()) continue;
      try {
        gp.geometry = solver.solve_wheel(w == 0 ? Side::left : Side::right, WheelsetState{ys[i], roll});
      } catch (const std::exception& e) {
        gp.error = fmt::format("geometry: {}", e.what());
      }
    }
  }

  std::ostringstream out;
  out << "variant,model,negative_curvature,wheel,y_m,roll_rad,load_N,status,status_names,patches,"
         "points,normal_force_N,iterations,error\n";
  for (const Variant& v : variants) {
    NormalOptions o = scene.normal;
    o.model = v.model;
    o.negative_curvature = v.treatment;
    const bool stripes = v.model == NormalModel::stripes_a || v.model == NormalModel::stripes_ab;
    const std::string label =
        stripes ? fmt::format("{}/{}", to_string(v.model), to_string(v.treatment)) : to_string(v.model);
    for (int w = 0; w < 2; ++w) {
      for (std::size_t i = 0; i < ys.size(); ++i) {
        const GeometryPoint& gp = geo[static_cast<std::size_t>(w) * ys.size() + i];
        StatusBits bits = 0;
        int patches = 0;
        double force = 0.0;
        int iterations = 0;
        std::string error = gp.error;
        if (error.empty()) {
          const WheelContactGeometry& g = gp.geometry;
          bits = g.status;
          for (const ContactPoint& p : g.points) bits |= p.status;
          try {
            const WheelNormalResult r = solve_normal_for_load(g, load, scene.material, o);
            bits |= r.status;
            for (const ContactPatch& p : r.patches) {
              bits |= p.status;
              force += p.normal_force;
            }
            patches = static_cast<int>(r.patches.size());
            iterations = r.iterations;
          } catch (const std::exception& e) {
            error = fmt::format("normal: {}", e.what());
          }
        }
        if (!error.empty()) bits |= status::kFailed;
        const std::size_t npoints = error.empty() ? gp.geometry.points.size() : 0;
        out << label << ',' << to_string(v.model) << ',' << to_string(v.treatment) << ','
            << (w == 0 ? "left" : "right") << ',' << fmt::format("{:.6g}", ys[i]) << ','
            << fmt::format("{:.9g}", gp.roll) << ',' << fmt::format("{:.9g}", load) << ',' << bits
            << ',' << names(bits) << ',' << patches << ',' << npoints << ','
            << fmt::format("{:.9g}", force) << ',' << iterations << ','
            << (error.empty() ? std::string() : csv_quoted(error)) << '\n';
      }
    }
  }
  write_text_file(csv, out.str());
  RAILTAB_CHECK(!out.fail(), "stability map: writing {} failed", csv.string());
}

}  // namespace railtab
