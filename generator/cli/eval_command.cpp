// SPDX-License-Identifier: Apache-2.0
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
#include <string>

#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "cli/number_options.hpp"
#include "normal/normal_model.hpp"
#include "scene/scene.hpp"
#include "eval/state_eval.hpp"
#include "eval/state_json.hpp"
#include "scene/state_rules.hpp"

namespace railtab {
namespace {

struct EvalOptions {
  std::string scene_path = "tables/default.toml";  // scene file
  StateEvalRequest request;                        // the state and overrides (state_eval.hpp)
  bool json = false;                               // JSON instead of text
};

double to_deg(double rad) { return rad * 180.0 / M_PI; }

void print_eval_text(const nlohmann::json& out) {
  const auto& st = out["state"];
  std::cout << fmt::format("scene {}: y = {:.3f} mm, roll = {:.4f} mrad, vertical load {:.1f} kN per wheel, model {}\n",
                           out["scene"].get<std::string>(), st["y"].get<double>() * 1e3,
                           st["roll"].get<double>() * 1e3, st["load"].get<double>() * 1e-3,
                           out["normal_model"].get<std::string>());
  if (st["yaw"].get<double>() != 0.0) std::cout << fmt::format("yaw = {:.4f} mrad\n", st["yaw"].get<double>() * 1e3);
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
    if (w.contains("load_coupling")) {  // the load coupling: normal and creep forces carry the load
      const auto& c = w["load_coupling"];
      // The half-space model's coupled solve does not report its iterations.
      const std::string iterations =
          c.contains("iterations") ? fmt::format("{} iterations, ", c["iterations"].get<int>()) : std::string();
      std::cout << fmt::format("  vertical load {:.2f} kN = normal {:.2f} kN + creep forces {:.2f} kN (load coupling {}, "
                               "{}{})\n",
                               w["vertical_load"].get<double>() * 1e-3, w["vertical_load_normal"].get<double>() * 1e-3,
                               w["vertical_load_tangential"].get<double>() * 1e-3,
                               c["enabled"].get<bool>() ? "on" : "off", iterations, c["status"].get<std::string>());
    }
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
  const nlohmann::json out = state_json(evaluate_state(load_scene(opt.scene_path), opt.request));
  if (opt.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    print_eval_text(out);
  }
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto opt = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand("eval", "Evaluate one wheelset state of a scene (SI units)");
  cmd->add_option("--scene", opt->scene_path, "Scene file (TOML)")->capture_default_str();
  add_number_option(cmd, "--y", opt->request.y, kLateralShiftRule,
                    "Wheelset lateral displacement [m], + to the left (ISO 8855)");
  add_number_option(cmd, "--roll", opt->request.roll, kRollRule,
                    "Wheelset roll relative to the track [rad], + lifts the left wheel (default: the scene's: the "
                    "kinematic equilibrium roll with [grid] equilibrium_roll = true, else its first roll)");
  cmd->add_flag("--equilibrium-roll", opt->request.equilibrium_roll,
                "Use the kinematic equilibrium roll of the rigid wheelset");
  add_number_option(cmd, "--yaw", opt->request.yaw, kYawRule,
                    "Wheelset yaw (angle of attack) relative to the track [rad], + turns the forward axis to the "
                    "left (default: the scene's first yaw, 0 without one)");
  add_number_option(cmd, "--load", opt->request.load, kWheelLoadRule,
                    "Vertical wheel load in track axes [N] (default: scene's first load)");
  cmd->add_option("--model", opt->request.model,
                  "Normal model: hertz|linder|kik-piotrowski|stripes-a|stripes-ab|halfspace (default: scene's)")
      ->check(error_check_validator([](const std::string& name) { parse_normal_model(name); }));  // exit 2
  static constexpr std::array<NumberField, 3> kCreepage{
      {{"xi", kCreepageRule}, {"eta", kCreepageRule}, {"phi", kSpinCreepageRule}}};
  add_number_fields_option(cmd, "--creepage", opt->request.creepage, kCreepage,
                           "Creepages XI,ETA,PHI of the wheel relative to the rail: longitudinal, lateral [-], spin "
                           "[rad/m] (docs/conventions.md); adds fx, fy, mz, slip_fraction, wear_rate");
  add_number_option(cmd, "--mu", opt->request.mu, kFrictionRule, "Coulomb friction coefficient (default: scene's)");
  cmd->add_flag("--json", opt->json, "Print JSON (stable keys, SI units) instead of text");
  add_quiet_flag(cmd);  // eval prints results only; accepted for uniformity
  cmd->callback([opt] { run_eval(*opt); });
}

}  // namespace railtab
