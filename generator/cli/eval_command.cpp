// railtab eval: one wheelset state of a scene, human-readable or JSON (stable keys, SI units).
// Per wheel: the loaded contact patches ("contacts": normal contact and, with --creepage, creep
// forces and wear) and the rigid contact points of the geometry ("rigid_points").
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/check.hpp"
#include "scene/scene.hpp"

namespace railtab {
namespace {

struct EvalOptions {
  std::string scene_path = "tables/default.toml";  // scene file
  double y = 0.0;                                  // wheelset lateral displacement [m]
  std::optional<double> roll;                      // roll [rad]; default: scene's choice
  bool equilibrium_roll = false;                   // use the kinematic equilibrium roll
  std::optional<double> load;                      // vertical wheel load [N]
  std::string model;                               // normal model override
  std::vector<double> creepage;                    // xi, eta [-], phi [rad/m]; empty: no creep
  std::optional<double> mu;                        // friction override [-]
  bool json = false;                               // JSON instead of text
};

struct CreepOutput {
  FastsimResult force;  // creep forces on the wheel
  WearResult wear;      // Archard wear of the same solve
};

struct WheelEval {
  const WheelContactGeometry* geometry = nullptr;
  WheelNormalResult normal;
  std::vector<CreepOutput> creep;  // per patch, empty without --creepage
};

double to_deg(double rad) { return rad * 180.0 / M_PI; }

nlohmann::json patch_json(const ContactPatch& patch, StatusBits solver_bits, const CreepOutput* creep) {
  nlohmann::json c;
  c["wheel_y"] = patch.wheel_u;
  c["rail_y"] = patch.rail_u;
  c["contact_angle"] = patch.contact_angle;
  c["rolling_radius"] = patch.rolling_radius;
  c["model"] = to_string(patch.model);
  c["normal_force"] = patch.normal_force;
  c["approach"] = patch.penetration;
  c["area"] = patch.area;
  c["max_pressure"] = patch.max_pressure;
  if (patch.model == NormalModel::hertz) {
    c["a"] = patch.semi_axis_a;
    c["b"] = patch.semi_axis_b;
  }
  c["rigid_point"] = patch.point_index;
  StatusBits bits = patch.status | solver_bits;  // as in the table: the load control's verdict too
  if (creep != nullptr) {
    c["fx"] = creep->force.fx;
    c["fy"] = creep->force.fy;
    c["mz"] = creep->force.mz;
    c["slip_fraction"] = creep->force.slip_fraction;
    c["wear_rate"] = creep->wear.wear_rate;
    bits |= creep->force.status;
  }
  c["status"] = status::describe(bits);
  c["status_bits"] = bits;
  return c;
}

nlohmann::json point_json(const ContactPoint& point, int patch) {
  return {{"wheel_y", point.wheel_u},         {"rail_y", point.rail_u},
          {"y_track", point.y_track},         {"z_track", point.z_track},
          {"contact_angle", point.contact_angle}, {"rolling_radius", point.rolling_radius},
          {"separation", point.separation},   {"curvature_a", point.curvature_a},
          {"curvature_b", point.curvature_b}, {"patch", patch},
          {"status", status::describe(point.status)}, {"status_bits", point.status}};
}

void print_text(const nlohmann::json& out) {
  const auto& st = out["state"];
  std::cout << fmt::format("scene {}: y = {:.3f} mm, roll = {:.4f} mrad, vertical load {:.1f} kN per wheel, model {}\n",
                           out["scene"].get<std::string>(), st["y"].get<double>() * 1e3,
                           st["roll"].get<double>() * 1e3, st["load"].get<double>() * 1e-3,
                           out["normal_model"].get<std::string>());
  if (out.contains("creepage")) {
    const auto& c = out["creepage"];
    std::cout << fmt::format("creepage xi = {:g}, eta = {:g}, phi = {:g} rad/m, mu = {:g} (forces on the wheel)\n",
                             c["xi"].get<double>(), c["eta"].get<double>(), c["phi"].get<double>(),
                             out["friction"].get<double>());
  }
  std::cout << fmt::format("rolling radius difference r_left - r_right = {:.4f} mm\n",
                           out["rolling_radius_difference"].get<double>() * 1e3);
  for (const auto& w : out["wheels"]) {
    std::cout << fmt::format("\n{} wheel: vertical approach {:.4f} mm, status {}\n", w["side"].get<std::string>(),
                             w["vertical_approach"].get<double>() * 1e3, w["status"].get<std::string>());
    std::cout << "  loaded patches  wheel_y  rail_y   angle    r_roll       N  approach   area   p_max";
    const bool creep = out.contains("creepage");
    std::cout << (creep ? "      fx      fy      mz  slip  wear_rate" : "") << "  status\n";
    std::cout << "                     [mm]    [mm]   [deg]      [mm]    [kN]      [mm]  [mm2]   [MPa]";
    std::cout << (creep ? "    [kN]    [kN]   [N m]   [-]  [mm2/km]" : "") << "\n";
    int i = 0;
    for (const auto& c : w["contacts"]) {
      std::cout << fmt::format("  {:>14} {:>8.3f} {:>7.3f} {:>7.3f} {:>9.4f} {:>7.2f} {:>9.5f} {:>6.1f} {:>7.0f}", i++,
                               c["wheel_y"].get<double>() * 1e3, c["rail_y"].get<double>() * 1e3,
                               to_deg(c["contact_angle"].get<double>()), c["rolling_radius"].get<double>() * 1e3,
                               c["normal_force"].get<double>() * 1e-3, c["approach"].get<double>() * 1e3,
                               c["area"].get<double>() * 1e6, c["max_pressure"].get<double>() * 1e-6);
      if (creep) {
        std::cout << fmt::format(" {:>7.3f} {:>7.3f} {:>7.2f} {:>5.2f} {:>10.4g}", c["fx"].get<double>() * 1e-3,
                                 c["fy"].get<double>() * 1e-3, c["mz"].get<double>(),
                                 c["slip_fraction"].get<double>(), c["wear_rate"].get<double>() * 1e9);
      }
      std::cout << "  " << c["status"].get<std::string>() << "\n";
    }
    std::cout << "  rigid points   wheel_y  rail_y   angle    r_roll     sep  patch  status\n";
    i = 0;
    for (const auto& p : w["rigid_points"]) {
      std::cout << fmt::format("  {:>14} {:>8.3f} {:>7.3f} {:>7.3f} {:>9.4f} {:>7.4f} {:>6}  {}\n", i++,
                               p["wheel_y"].get<double>() * 1e3, p["rail_y"].get<double>() * 1e3,
                               to_deg(p["contact_angle"].get<double>()), p["rolling_radius"].get<double>() * 1e3,
                               p["separation"].get<double>() * 1e3, p["patch"].get<int>(),
                               p["status"].get<std::string>());
    }
  }
}

void run_eval(const EvalOptions& opt) {
  RAILTAB_CHECK(std::isfinite(opt.y), "--y must be finite, got {}", opt.y);
  Scene scene = load_scene(opt.scene_path);
  if (!opt.model.empty()) scene.normal.model = parse_normal_model(opt.model);
  if (opt.mu) {
    RAILTAB_CHECK(std::isfinite(*opt.mu) && *opt.mu >= 0.0, "--mu must be finite and >= 0, got {}", *opt.mu);
    scene.tangential.friction = *opt.mu;
  }
  const bool with_creep = !opt.creepage.empty();
  RAILTAB_CHECK(!with_creep || opt.creepage.size() == 3,
                "--creepage takes XI,ETA,PHI (three numbers), got {} value(s)", opt.creepage.size());
  for (double c : opt.creepage) RAILTAB_CHECK(std::isfinite(c), "--creepage values must be finite, got {}", c);
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
  const FastsimOptions fastsim = fastsim_options(scene);
  const CreepConditions conditions = creep_conditions(scene);
  const WearOptions wear = wear_options(scene);
  std::array<WheelEval, 2> wheels;
  for (int w = 0; w < 2; ++w) {
    WheelEval& e = wheels[w];
    e.geometry = &geometry.wheels[w];
    e.normal = solve_normal_for_load(*e.geometry, load, scene.material, scene.normal);
    if (!with_creep) continue;
    FastsimWorkspace workspace;
    WearDistribution distribution;
    const Creepage creepage{opt.creepage[0], opt.creepage[1], opt.creepage[2]};
    for (const ContactPatch& patch : e.normal.patches) {
      CreepOutput c;
      c.force = fastsim_contact(*e.geometry, patch, creepage, conditions, scene.material, fastsim, workspace);
      if (patch.normal_force > 0.0) c.wear = archard_wear(workspace, wear, distribution);
      e.creep.push_back(c);
    }
  }

  nlohmann::json out;
  out["scene"] = scene.name;
  out["state"] = {{"y", opt.y}, {"roll", roll}, {"load", load}};
  out["normal_model"] = to_string(scene.normal.model);
  if (with_creep) {
    out["creepage"] = {{"xi", opt.creepage[0]}, {"eta", opt.creepage[1]}, {"phi", opt.creepage[2]}};
    out["friction"] = scene.tangential.friction;
    out["spin"] = to_string(fastsim.spin);
  }
  out["rolling_radius_difference"] = geometry.rolling_radius_difference;
  out["wheels"] = nlohmann::json::array();
  for (const WheelEval& e : wheels) {
    nlohmann::json wj;
    wj["side"] = to_string(e.geometry->side);
    wj["vertical_approach"] = e.normal.vertical_approach;
    wj["vertical_load"] = e.normal.vertical_load;
    wj["status"] = status::describe(e.geometry->status | e.normal.status);
    wj["contacts"] = nlohmann::json::array();
    for (std::size_t i = 0; i < e.normal.patches.size(); ++i) {
      const StatusBits solver_bits = e.normal.status & (status::kConverged | status::kNotConverged);
      wj["contacts"].push_back(patch_json(e.normal.patches[i], solver_bits, with_creep ? &e.creep[i] : nullptr));
    }
    wj["rigid_points"] = nlohmann::json::array();
    for (std::size_t i = 0; i < e.geometry->points.size(); ++i) {
      const int patch = i < e.normal.point_patch.size() ? e.normal.point_patch[i] : -1;
      wj["rigid_points"].push_back(point_json(e.geometry->points[i], patch));
    }
    out["wheels"].push_back(wj);
  }
  if (opt.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    print_text(out);
  }
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
  cmd->add_option("--creepage", opt->creepage,
                  "Creepages XI,ETA,PHI of the wheel relative to the rail: longitudinal, lateral [-], spin "
                  "[rad/m] (docs/conventions.md); adds fx, fy, mz, slip_fraction, wear_rate")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--mu", opt->mu, "Coulomb friction coefficient (default: scene's)");
  cmd->add_flag("--json", opt->json, "Print JSON (stable keys, SI units) instead of text");
  cmd->callback([opt] { run_eval(*opt); });
}

}  // namespace railtab
