// railtab eval: one wheelset state of a scene, human-readable or JSON (stable keys, SI units).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "commands.hpp"
#include "core/check.hpp"
#include "normal/normal_model.hpp"
#include "scene.hpp"

namespace railtab {
namespace {

struct EvalOptions {
  std::string scene_path = "tables/default.toml";  // scene file
  double y = 0.0;                                  // wheelset lateral displacement [m]
  std::optional<double> roll;                      // roll [rad]; default: scene's choice
  bool equilibrium_roll = false;                   // use the kinematic equilibrium roll
  std::optional<double> load;                      // vertical wheel load [N]
  std::string model;                               // normal model override
  bool json = false;                               // JSON instead of text
};

nlohmann::json contact_json(const ContactPoint& point, const ContactPatch* patch) {
  nlohmann::json c;
  c["wheel_y"] = point.wheel_u;
  c["rail_y"] = point.rail_u;
  c["y_track"] = point.y_track;
  c["z_track"] = point.z_track;
  c["contact_angle"] = point.contact_angle;
  c["rolling_radius"] = point.rolling_radius;
  c["separation"] = point.separation;
  c["curvature_a"] = point.curvature_a;
  c["curvature_b"] = point.curvature_b;
  StatusBits bits = point.status;
  if (patch != nullptr) {
    c["model"] = to_string(patch->model);
    c["normal_force"] = patch->normal_force;
    c["approach"] = patch->penetration;
    c["area"] = patch->area;
    c["max_pressure"] = patch->max_pressure;
    if (patch->semi_axis_a > 0.0 && patch->semi_axis_b > 0.0) {
      c["a"] = patch->semi_axis_a;
      c["b"] = patch->semi_axis_b;
    }
    bits |= patch->status;
  }
  c["status"] = status::describe(bits);
  c["status_bits"] = bits;
  return c;
}

void print_text(const EvalOptions& opt, double roll, double load,
                const WheelsetContactGeometry& geometry,
                const std::array<WheelNormalResult, 2>& normal) {
  std::cout << fmt::format("state: y = {:.3f} mm, roll = {:.5f} mrad, vertical load = {:.1f} kN per wheel\n",
                           opt.y * 1e3, roll * 1e3, load * 1e-3);
  std::cout << fmt::format("rolling radius difference r_left - r_right = {:.4f} mm\n",
                           geometry.rolling_radius_difference * 1e3);
  for (int w = 0; w < 2; ++w) {
    const WheelContactGeometry& wheel = geometry.wheels[w];
    const WheelNormalResult& result = normal[w];
    std::cout << fmt::format("\n{} wheel: {} contact(s), vertical approach {:.4f} mm, status {}\n",
                             to_string(wheel.side), wheel.points.size(),
                             result.vertical_approach * 1e3, status::describe(result.status | wheel.status));
    std::cout << fmt::format("  {:>3} {:>9} {:>9} {:>9} {:>10} {:>8} {:>9} {:>9} {:>8} {:>8} {:>7} {:>7}  {}\n",
                             "#", "wheel_y", "rail_y", "angle", "r_roll", "sep", "N", "approach",
                             "area", "p_max", "a", "b", "status");
    std::cout << fmt::format("  {:>3} {:>9} {:>9} {:>9} {:>10} {:>8} {:>9} {:>9} {:>8} {:>8} {:>7} {:>7}\n",
                             "", "[mm]", "[mm]", "[deg]", "[mm]", "[mm]", "[kN]", "[mm]", "[mm2]",
                             "[MPa]", "[mm]", "[mm]");
    for (std::size_t i = 0; i < wheel.points.size(); ++i) {
      const ContactPoint& p = wheel.points[i];
      const ContactPatch& patch = result.patches.at(i);
      std::cout << fmt::format(
          "  {:>3} {:>9.3f} {:>9.3f} {:>9.4f} {:>10.4f} {:>8.4f} {:>9.3f} {:>9.5f} {:>8.2f} {:>8.1f} {:>7.3f} {:>7.3f}  {}\n",
          i, p.wheel_u * 1e3, p.rail_u * 1e3, p.contact_angle * 180.0 / M_PI,
          p.rolling_radius * 1e3, p.separation * 1e3, patch.normal_force * 1e-3,
          patch.penetration * 1e3, patch.area * 1e6, patch.max_pressure * 1e-6,
          patch.semi_axis_a * 1e3, patch.semi_axis_b * 1e3, status::describe(p.status | patch.status));
    }
  }
}

void run_eval(const EvalOptions& opt) {
  RAILTAB_CHECK(std::isfinite(opt.y), "--y must be finite, got {}", opt.y);
  Scene scene = load_scene(opt.scene_path);
  if (!opt.model.empty()) scene.normal.model = parse_normal_model(opt.model);
  const ContactGeometrySolver solver = make_geometry_solver(scene);

  double roll = 0.0;
  if (opt.roll) {
    RAILTAB_CHECK(std::isfinite(*opt.roll), "--roll must be finite, got {}", *opt.roll);
    RAILTAB_CHECK(!opt.equilibrium_roll, "--roll and --equilibrium-roll exclude each other");
    roll = *opt.roll;
  } else if (opt.equilibrium_roll || scene.equilibrium_roll) {
    roll = solver.equilibrium_roll(opt.y);
  } else if (!scene.grids.roll.empty()) {
    roll = scene.grids.roll.front();
  }
  double load = 0.0;
  if (opt.load) {
    load = *opt.load;
  } else {
    RAILTAB_CHECK(!scene.grids.load.empty(), "scene '{}' has no load grid: give --load", scene.name);
    load = scene.grids.load.front();
  }
  RAILTAB_CHECK(std::isfinite(load) && load >= 0.0, "--load must be finite and >= 0 N, got {}", load);

  const WheelsetContactGeometry geometry = solver.solve({opt.y, roll});
  std::array<WheelNormalResult, 2> normal;
  for (int w = 0; w < 2; ++w) {
    normal[w] = solve_normal_for_load(geometry.wheels[w], load, scene.material, scene.normal);
  }

  if (!opt.json) {
    print_text(opt, roll, load, geometry, normal);
    return;
  }
  nlohmann::json out;
  out["scene"] = scene.name;
  out["state"] = {{"y", opt.y}, {"roll", roll}, {"load", load}};
  out["normal_model"] = to_string(scene.normal.model);
  out["rolling_radius_difference"] = geometry.rolling_radius_difference;
  out["wheels"] = nlohmann::json::array();
  for (int w = 0; w < 2; ++w) {
    const WheelContactGeometry& wheel = geometry.wheels[w];
    nlohmann::json wj;
    wj["side"] = to_string(wheel.side);
    wj["vertical_approach"] = normal[w].vertical_approach;
    wj["vertical_load"] = normal[w].vertical_load;
    wj["status"] = status::describe(wheel.status | normal[w].status);
    wj["contacts"] = nlohmann::json::array();
    for (std::size_t i = 0; i < wheel.points.size(); ++i) {
      const ContactPatch* patch = i < normal[w].patches.size() ? &normal[w].patches[i] : nullptr;
      wj["contacts"].push_back(contact_json(wheel.points[i], patch));
    }
    out["wheels"].push_back(wj);
  }
  std::cout << out.dump(2) << "\n";
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto opt = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand("eval", "Evaluate one wheelset state of a scene (SI units)");
  cmd->add_option("--scene", opt->scene_path, "Scene file (TOML)")->capture_default_str();
  cmd->add_option("--y", opt->y, "Wheelset lateral displacement [m], + to the left (ISO 8855)")
      ->capture_default_str();
  cmd->add_option("--roll", opt->roll, "Wheelset roll relative to the track [rad], + lifts the left wheel");
  cmd->add_flag("--equilibrium-roll", opt->equilibrium_roll,
                "Use the kinematic equilibrium roll of the rigid wheelset");
  cmd->add_option("--load", opt->load, "Vertical wheel load in track axes [N] (default: scene's first load)");
  cmd->add_option("--model", opt->model,
                  "Normal model: hertz|linder|kik-piotrowski|stripes-a|stripes-ab (default: scene's)");
  cmd->add_flag("--json", opt->json, "Print JSON (stable keys, SI units) instead of text");
  cmd->callback([opt] { run_eval(*opt); });
}

}  // namespace railtab
