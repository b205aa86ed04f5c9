// SPDX-License-Identifier: Apache-2.0
// One wheelset state of a scene through the whole chain, as a typed result (state_eval.hpp; railtab
// eval).
#include "eval/state_eval.hpp"

#include <array>
#include <cmath>

#include "core/check.hpp"
#include "core/number_input.hpp"
#include "scene/state_rules.hpp"
#include "kernel/contact_kernel.hpp"
#include "kernel/finite_status.hpp"
#include "kernel/halfspace_contact.hpp"

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

// The patch's status as the table has it (the load control's verdict too), failed when a number
// is not finite (finite_status.hpp).
StatusBits contact_status(const ContactPatch& patch, StatusBits solver_bits, const CreepOutput* creep) {
  StatusBits bits = patch.status | solver_bits;
  bool finite = all_finite({patch.wheel_u, patch.rail_u, patch.contact_angle, patch.rolling_radius,
                            patch.normal_force, patch.penetration, patch.area, patch.max_pressure});
  if (patch.model == NormalModel::hertz) finite = finite && all_finite({patch.semi_axis_a, patch.semi_axis_b});
  if (creep != nullptr) {
    bits |= creep->force.status;
    finite = finite && all_finite({creep->force.fx, creep->force.fy, creep->force.mz, creep->force.slip_fraction,
                                   creep->wear.wear_rate});
  }
  return finite ? bits : non_finite_status(bits);
}

EvaluatedPoint evaluated_point(const ContactPoint& point, int patch) {
  const bool finite = all_finite({point.wheel_u, point.rail_u, point.y_track, point.z_track, point.contact_angle,
                                  point.rolling_radius, point.separation, point.curvature_a, point.curvature_b});
  return {point, patch, finite ? point.status : non_finite_status(point.status)};
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

StateEvaluation evaluate_state(const Scene& base, const StateEvalRequest& request) {
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
    roll = table_equilibrium_roll(solver, request.y);  // as the table's (odd in y)
  } else if (!scene.grids.roll.empty()) {
    roll = scene.grids.roll.front();
  }
  double yaw = scene.grids.yaw.empty() ? 0.0 : scene.grids.yaw.front();
  if (request.yaw) {
    check_number_input(*request.yaw, "--yaw", kYawRule);
    yaw = *request.yaw;
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

  const WheelsetContactGeometry geometry = solver.solve({request.y, roll, yaw});
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
    // The load is carried by normal and creep forces together (load coupling): the normal contact
    // is re-solved at the approach that balances both (tangential/coupled_load.hpp).
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

  StateEvaluation out;
  out.scene = scene.name;
  out.y = request.y;
  out.roll = roll;
  out.yaw = yaw;
  out.load = load;
  out.normal_model = scene.normal.model;
  out.with_creep = with_creep;
  if (with_creep) {
    out.creepage = {request.creepage[0], request.creepage[1], request.creepage[2]};
    out.friction = scene.tangential.friction;
    out.spin = scene.normal.model == NormalModel::halfspace ? "exact" : to_string(fastsim.spin);
  }
  if (scene.normal.model == NormalModel::halfspace) out.element_size = scene.halfspace.element_size;
  out.load_coupling = scene.tangential.load_coupling;
  out.rolling_radius_difference = geometry.rolling_radius_difference;
  for (std::size_t w = 0; w < 2; ++w) {
    const WheelEval& e = wheels[w];
    EvaluatedWheel& wheel = out.wheels[w];
    wheel.side = e.geometry->side;
    wheel.vertical_approach = e.normal.vertical_approach;
    wheel.carried_load = e.normal.carried_load;
    if (e.coupled) {
      // The load balance in track axes: vertical_load_normal + vertical_load_tangential = load.
      wheel.coupled = true;
      wheel.carried_load = e.normal_vertical + e.tangential_vertical;
      wheel.vertical_load_normal = e.normal_vertical;
      wheel.vertical_load_tangential = e.tangential_vertical;
      wheel.coupling_status = e.coupling_status;
      wheel.coupling_iterations = e.coupling_iterations;
    }
    StatusBits wheel_bits = e.geometry->status | e.normal.status | (e.coupled ? e.coupling_status : 0u);
    if (!all_finite({e.normal.vertical_approach, e.normal.carried_load, e.normal_vertical, e.tangential_vertical})) {
      wheel_bits = non_finite_status(wheel_bits);
    }
    const StatusBits solver_bits = e.normal.status & (status::kConverged | status::kNotConverged);
    for (std::size_t i = 0; i < e.normal.patches.size(); ++i) {
      EvaluatedContact c;
      c.patch = e.normal.patches[i];
      if (with_creep) {
        c.force = e.creep[i].force;
        c.wear = e.creep[i].wear;
      }
      c.status = contact_status(c.patch, solver_bits, with_creep ? &e.creep[i] : nullptr);
      // A failed contact makes its wheel failed too: the wheel line never says converged over a
      // NaN.
      if (c.status & status::kFailed) wheel_bits = non_finite_status(wheel_bits);
      wheel.contacts.push_back(c);
    }
    wheel.status = wheel_bits;
    for (std::size_t i = 0; i < e.geometry->points.size(); ++i) {
      const int patch = i < e.normal.point_patch.size() ? e.normal.point_patch[i] : -1;
      wheel.rigid_points.push_back(evaluated_point(e.geometry->points[i], patch));
    }
  }
  return out;
}

}  // namespace railtab
