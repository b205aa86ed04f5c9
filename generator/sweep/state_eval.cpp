// SPDX-License-Identifier: Apache-2.0
// One wheelset state of a scene through the whole chain, as JSON (state_eval.hpp; railtab eval).
#include "sweep/state_eval.hpp"

#include <array>
#include <cmath>

#include "core/check.hpp"
#include "core/number_input.hpp"
#include "scene/state_rules.hpp"
#include "sweep/finite_status.hpp"
#include "sweep/halfspace_contact.hpp"

namespace railtab {
namespace {

struct CreepOutput {
  FastsimResult force;  // creep forces on the wheel
  WearResult wear;      // Archard wear of the same solve
};

struct WheelEval {
  const WheelContactGeometry* geometry = nullptr;
  WheelNormalResult normal;
  std::vector<CreepOutput> creep;  // per patch, empty without --creepage
  bool coupled = false;            // with creepage: the coupled load control ran
  StatusBits coupling_status = 0;  // its verdict (kConverged / kNotConverged)
  int coupling_iterations = 0;     // its normal solves beyond the uncoupled one (-1: not reported,
                                   //   the half-space model's coupled solve does not count them)
  double normal_vertical = 0.0;    // sum N cos g [N]
  double tangential_vertical = 0.0;  // sum fy sin g [N]
};

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
  // A NaN or inf in any number is failed, never converged (finite_status.hpp).
  for (const auto& [key, value] : c.items()) {
    if (value.is_number_float() && !std::isfinite(value.get<double>())) bits = non_finite_status(bits);
  }
  c["status"] = status::describe(bits);
  c["status_bits"] = bits;
  return c;
}

nlohmann::json point_json(const ContactPoint& point, int patch) {
  const bool finite = all_finite({point.wheel_u, point.rail_u, point.y_track, point.z_track, point.contact_angle,
                                  point.rolling_radius, point.separation, point.curvature_a, point.curvature_b});
  const StatusBits bits = finite ? point.status : non_finite_status(point.status);
  return {{"wheel_y", point.wheel_u},         {"rail_y", point.rail_u},
          {"y_track", point.y_track},         {"z_track", point.z_track},
          {"contact_angle", point.contact_angle}, {"rolling_radius", point.rolling_radius},
          {"separation", point.separation},   {"curvature_a", point.curvature_a},
          {"curvature_b", point.curvature_b}, {"patch", patch},
          {"status", status::describe(bits)}, {"status_bits", bits}};
}

// The exact half-space model on one wheel: normal contact, and with a creepage the steady rolling
// solution (creep forces, element wear) of every patch at that creepage. With the scene's
// load_coupling the creep forces carry their share of the vertical load, as for the fast models
// (solve_halfspace_rolling); without it the normal contact comes from the load alone.
void evaluate_halfspace(const Scene& scene, double load, const std::vector<double>* creep, WheelEval& e) {
  const halfspace::HalfspaceOptions options = halfspace_options(scene);
  halfspace::Workspace& workspace = thread_halfspace_workspace();
  halfspace::WheelHalfspaceResult result;
  const double mu = scene.tangential.friction;
  if (creep == nullptr) {
    result = halfspace::solve_halfspace_for_load(*e.geometry, load, scene.material, options, workspace);
  } else {
    const Creepage creepage{(*creep)[0], (*creep)[1], (*creep)[2]};
    if (scene.tangential.load_coupling) {
      result = halfspace::solve_halfspace_rolling(*e.geometry, load, creepage, mu, scene.material, options, workspace);
    } else {
      result = halfspace::solve_halfspace_for_load(*e.geometry, load, scene.material, options, workspace);
      halfspace::solve_halfspace_tangential(result, creepage, mu, scene.material, options, workspace);
    }
  }
  e.normal = to_normal_result(result, *e.geometry);
  if (creep == nullptr) return;
  const WearOptions wear = wear_options(scene);
  std::vector<double> depth;
  e.coupled = true;
  e.coupling_iterations = -1;
  e.coupling_status = result.status & (status::kConverged | status::kNotConverged);
  for (const halfspace::HalfspacePatch& hp : result.patches) {
    CreepOutput c;
    c.force = to_creep_result(hp);
    c.wear = halfspace_wear(hp, scene.tangential.speed, wear, depth);
    e.normal_vertical += hp.normal.normal_force * std::cos(hp.contact_angle);
    e.tangential_vertical += hp.tangential.fy * std::sin(hp.contact_angle);
    e.creep.push_back(c);
  }
}

}  // namespace

nlohmann::json evaluate_state(const Scene& base, const StateEvalRequest& request) {
  // The ranges of the command line's options (scene/state_rules.hpp): Python's evaluate too.
  check_number_input(request.y, "--y", kLateralShiftRule);
  Scene scene = base;
  if (!request.model.empty()) scene.normal.model = parse_normal_model(request.model);
  if (request.mu) {
    check_number_input(*request.mu, "--mu", kFrictionRule);
    scene.tangential.friction = *request.mu;
  }
  const bool with_creep = !request.creepage.empty();
  RAILTAB_CHECK(!with_creep || request.creepage.size() == 3,
                "--creepage takes XI,ETA,PHI (three numbers), got {} value(s)", request.creepage.size());
  for (double c : request.creepage) RAILTAB_CHECK(std::isfinite(c), "--creepage values must be finite, got {}", c);
  if (with_creep) {
    check_creepage_magnitude("--creepage", request.creepage[0], request.creepage[1], request.creepage[2]);
  }
  const ContactGeometrySolver solver = make_geometry_solver(scene);

  double roll = 0.0;
  if (request.roll) {
    check_number_input(*request.roll, "--roll", kRollRule);
    RAILTAB_CHECK(!request.equilibrium_roll, "--roll and --equilibrium-roll exclude each other");
    roll = *request.roll;
  } else if (request.equilibrium_roll || scene.equilibrium_roll) {
    roll = solver.equilibrium_roll(request.y);
  } else if (!scene.grids.roll.empty()) {
    roll = scene.grids.roll.front();
  }
  double load = 0.0;
  if (request.load) {
    load = *request.load;
  } else {
    RAILTAB_CHECK(!scene.grids.load.empty(), "scene '{}' has no load grid: give --load", scene.name);
    load = scene.grids.load.front();
  }
  check_number_input(load, "--load", kWheelLoadRule);
  // 0 is a rigid, unloaded wheelset; between 0 and 1 kN it is a load typed in kN (scene.hpp).
  RAILTAB_CHECK(load == 0.0 || load >= kMinWheelLoad,
                "--load {} N is below {} N: the load is in N (SI: 78.5 kN is 78.5e3)", load, kMinWheelLoad);

  const WheelsetContactGeometry geometry = solver.solve({request.y, roll});
  const FastsimOptions fastsim = fastsim_options(scene);
  const CreepConditions conditions = creep_conditions(scene);
  const WearOptions wear = wear_options(scene);
  std::array<WheelEval, 2> wheels;
  const CoupledLoadOptions coupling = coupled_load_options(scene);
  for (int w = 0; w < 2; ++w) {
    WheelEval& e = wheels[w];
    e.geometry = &geometry.wheels[w];
    if (scene.normal.model == NormalModel::halfspace) {
      evaluate_halfspace(scene, load, with_creep ? &request.creepage : nullptr, e);
      continue;
    }
    e.normal = solve_normal_for_load(*e.geometry, load, scene.material, scene.normal);
    if (!with_creep) continue;
    FastsimWorkspace workspace;
    WearDistribution distribution;
    const Creepage creepage{request.creepage[0], request.creepage[1], request.creepage[2]};
    // The load is carried by normal and creep forces together (issue 14): the normal contact is
    // re-solved at the approach that balances both (tangential/coupled_load.hpp).
    CoupledLoadResult coupled;
    solve_coupled_load(*e.geometry, load, e.normal, scene.material, scene.normal,
                       fastsim_tangential(*e.geometry, [&](std::size_t, const ContactPatch&) { return creepage; },
                                          conditions, scene.material, fastsim, workspace),
                       coupling, coupled);
    e.normal = std::move(coupled.normal);
    e.coupled = true;
    e.coupling_status = coupled.status;
    e.coupling_iterations = coupled.iterations;
    e.normal_vertical = coupled.normal_vertical;
    e.tangential_vertical = coupled.tangential_vertical;
    for (const ContactPatch& patch : e.normal.patches) {
      CreepOutput c;
      c.force = fastsim_contact(*e.geometry, patch, creepage, conditions, scene.material, fastsim, workspace);
      if (patch.normal_force > 0.0) c.wear = archard_wear(workspace, wear, distribution);
      e.creep.push_back(c);
    }
  }

  nlohmann::json out;
  out["scene"] = scene.name;
  out["state"] = {{"y", request.y}, {"roll", roll}, {"load", load}};
  out["normal_model"] = to_string(scene.normal.model);
  if (with_creep) {
    out["creepage"] = {{"xi", request.creepage[0]}, {"eta", request.creepage[1]}, {"phi", request.creepage[2]}};
    out["friction"] = scene.tangential.friction;
    out["spin"] = scene.normal.model == NormalModel::halfspace ? "exact" : to_string(fastsim.spin);
  }
  if (scene.normal.model == NormalModel::halfspace) out["element_size"] = scene.halfspace.element_size;
  out["rolling_radius_difference"] = geometry.rolling_radius_difference;
  out["wheels"] = nlohmann::json::array();
  for (const WheelEval& e : wheels) {
    nlohmann::json wj;
    wj["side"] = to_string(e.geometry->side);
    wj["vertical_approach"] = e.normal.vertical_approach;
    wj["vertical_load"] = e.normal.vertical_load;
    if (e.coupled) {
      // The load balance in track axes: vertical_load_normal + vertical_load_tangential = load.
      wj["vertical_load"] = e.normal_vertical + e.tangential_vertical;
      wj["vertical_load_normal"] = e.normal_vertical;
      wj["vertical_load_tangential"] = e.tangential_vertical;
      wj["load_coupling"] = {{"enabled", scene.tangential.load_coupling},
                             {"status", status::describe(e.coupling_status)}};
      if (e.coupling_iterations >= 0) wj["load_coupling"]["iterations"] = e.coupling_iterations;
    }
    StatusBits wheel_bits = e.geometry->status | e.normal.status | (e.coupled ? e.coupling_status : 0u);
    if (!all_finite({e.normal.vertical_approach, e.normal.vertical_load, e.normal_vertical, e.tangential_vertical})) {
      wheel_bits = non_finite_status(wheel_bits);
    }
    wj["contacts"] = nlohmann::json::array();
    for (std::size_t i = 0; i < e.normal.patches.size(); ++i) {
      const StatusBits solver_bits = e.normal.status & (status::kConverged | status::kNotConverged);
      wj["contacts"].push_back(patch_json(e.normal.patches[i], solver_bits, with_creep ? &e.creep[i] : nullptr));
      // A failed contact makes its wheel failed too: the wheel line never says converged over a NaN.
      if (wj["contacts"].back()["status_bits"].get<StatusBits>() & status::kFailed) {
        wheel_bits = non_finite_status(wheel_bits);
      }
    }
    wj["status"] = status::describe(wheel_bits);
    wj["rigid_points"] = nlohmann::json::array();
    for (std::size_t i = 0; i < e.geometry->points.size(); ++i) {
      const int patch = i < e.normal.point_patch.size() ? e.normal.point_patch[i] : -1;
      wj["rigid_points"].push_back(point_json(e.geometry->points[i], patch));
    }
    out["wheels"].push_back(wj);
  }
  return out;
}

}  // namespace railtab
