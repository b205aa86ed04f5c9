// SPDX-License-Identifier: Apache-2.0
// ContactModel evaluating geometry, normal model and FASTSIM at every call (the reference).
#include "simulate/direct_contact_model.hpp"

#include <exception>

#include "core/check.hpp"
#include "kernel/contact_kernel.hpp"
#include "tangential/coupled_load.hpp"

namespace railtab {

DirectContactModel::DirectContactModel(const Scene& scene)
    : solver_(make_geometry_solver(scene)),
      material_(scene.material),
      normal_options_(scene.normal),
      creep_conditions_(creep_conditions(scene)),
      fastsim_options_(fastsim_options(scene)),
      coupling_(coupled_load_options(scene)),
      halfspace_options_(halfspace_options(scene)),
      yaw_axis_(scene.grids.yaw.size() > 1),
      fixed_yaw_(fixed_yaw(scene)) {}

void DirectContactModel::normal(double y, double yaw, const double (&load)[vehicle::kWheels],
                                vehicle::WheelContacts (&contacts)[vehicle::kWheels]) {
  const double psi = yaw_axis_ ? yaw : fixed_yaw_;
  double roll = 0.0;
  bool roll_ok = true;
  try {
    roll = table_equilibrium_roll(solver_, y);  // as the sweep does for equilibrium-roll tables
  } catch (const std::exception&) {
    roll_ok = false;
  }
  for (int w = 0; w < vehicle::kWheels; ++w) {
    const Side side = w == 0 ? Side::left : Side::right;
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot) {
      contacts[w].slot[slot] = {};
      loaded_[w][slot] = false;
    }
    patches_[w] = {};
    load_[w] = load[w];
    try {
      if (!roll_ok) throw Error("no equilibrium roll");
      geometry_[w] = solver_.solve_wheel(side, WheelsetState{y, roll, psi});
      if (normal_options_.model == NormalModel::halfspace) {
        exact_[w] = halfspace::solve_halfspace_for_load(geometry_[w], load[w], material_, halfspace_options_,
                                                        thread_halfspace_workspace());
        normal_[w] = to_normal_result(exact_[w], geometry_[w]);
      } else {
        solve_normal_for_load(geometry_[w], load[w], material_, normal_options_, normal_[w]);
      }
    } catch (const std::exception&) {
      ++failures_;
      for (int slot = 0; slot < vehicle::kContactSlots; ++slot) contacts[w].slot[slot].status = status::kFailed;
      continue;
    }
    const SlotAssignment points = assign_slots(geometry_[w]);
    patches_[w] = assign_patch_slots(normal_[w], side, solver_.settings().flange_angle);
    const PatchSlots& patches = patches_[w];
    const StatusBits solver_bits = normal_[w].status & (status::kConverged | status::kNotConverged);
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot) {
      const auto s = static_cast<std::size_t>(slot);
      if (!patches.occupied(s)) continue;
      const ContactPatch patch = slot_normal(normal_[w], patches, s);  // the sum of the slot's patches
      vehicle::SlotContact& out = contacts[w].slot[slot];
      out.normal_force = patch.normal_force;
      out.area = patch.area;
      out.loaded = patch.normal_force > 0.0;
      out.status = patch.status | solver_bits | patches.extra[slot];
      if (!out.loaded) continue;
      loaded_[w][slot] = true;
      // Geometry of the slot's rigid point, as the table's geometry part holds it; a patch whose
      // point sits in the other slot takes that point (the lookup model does the same).
      int point = points.point[slot] >= 0 ? points.point[slot] : points.point[1 - slot];
      if (point >= 0) {
        const ContactPoint& p = geometry_[w].points[static_cast<std::size_t>(point)];
        out.contact_angle = p.contact_angle;
        out.rolling_radius = p.rolling_radius;
        out.wheel_u = p.wheel_u;
      } else {
        out.contact_angle = patch.contact_angle;
        out.rolling_radius = patch.rolling_radius;
        out.wheel_u = patch.wheel_u;
      }
    }
  }
}

void DirectContactModel::creep(const vehicle::SlotCreepage (&creepage)[vehicle::kWheels][vehicle::kContactSlots],
                               vehicle::SlotForces (&forces)[vehicle::kWheels][vehicle::kContactSlots]) {
  FastsimWorkspace& workspace = thread_fastsim_workspace();
  for (int w = 0; w < vehicle::kWheels; ++w) {
    if (normal_options_.model == NormalModel::halfspace) {
      creep_exact(w, creepage[w], forces[w]);
      continue;
    }
    if (coupling_.couple && (loaded_[w][0] || loaded_[w][1])) {
      creep_coupled(w, creepage[w], forces[w], workspace);
      continue;
    }
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot) {
      vehicle::SlotForces& f = forces[w][slot];
      f = {};
      if (!loaded_[w][slot]) continue;
      const vehicle::SlotCreepage& c = creepage[w][slot];
      try {
        const FastsimResult r = slot_creep(geometry_[w], normal_[w], patches_[w], static_cast<std::size_t>(slot),
                                           Creepage{c.xi, c.eta, c.phi}, creep_conditions_, material_,
                                           fastsim_options_, workspace);
        f.fx = r.fx;
        f.fy = r.fy;
        f.mz = r.mz;
        f.status = r.status;
      } catch (const std::exception&) {
        ++failures_;
        f.status = status::kFailed;
      }
    }
  }
}

void DirectContactModel::creep_exact(int w, const vehicle::SlotCreepage (&creepage)[vehicle::kContactSlots],
                                     vehicle::SlotForces (&forces)[vehicle::kContactSlots]) {
  for (int slot = 0; slot < vehicle::kContactSlots; ++slot) forces[slot] = {};
  if (!loaded_[w][0] && !loaded_[w][1]) return;
  const PatchSlots& before = patches_[w];
  // Each patch at the creepage of the slot it sat in after normal() (by patch index, as creep_coupled).
  auto slot_creepage = [&](int slot) {
    const vehicle::SlotCreepage& c = creepage[slot];
    return Creepage{c.xi, c.eta, c.phi};
  };
  auto creepage_of = [&](std::size_t i, const halfspace::HalfspacePatch&) {
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot)
      for (int ip : before.patch[slot])
        if (ip == static_cast<int>(i)) return slot_creepage(slot);
    return Creepage{};
  };
  const bool same_creepage =
      !(loaded_[w][0] && loaded_[w][1]) ||
      (creepage[0].xi == creepage[1].xi && creepage[0].eta == creepage[1].eta && creepage[0].phi == creepage[1].phi);
  const double mu = creep_conditions_.friction;
  halfspace::Workspace& workspace = thread_halfspace_workspace();
  try {
    halfspace::WheelHalfspaceResult result;
    if (coupling_.couple && same_creepage) {  // the table's call
      const Creepage c = slot_creepage(loaded_[w][0] ? 0 : 1);
      result = halfspace::solve_halfspace_rolling(geometry_[w], load_[w], c, mu, material_, halfspace_options_,
                                                  workspace);
    } else if (coupling_.couple) {
      result = solve_halfspace_rolling_per_patch(geometry_[w], load_[w], creepage_of, mu, material_,
                                                 halfspace_options_, true, workspace);
    } else {
      solve_halfspace_tangential_per_patch(exact_[w], creepage_of, mu, material_, halfspace_options_, workspace);
      result = exact_[w];
    }
    const WheelNormalResult normal = to_normal_result(result, geometry_[w]);
    const PatchSlots slots =
        coupling_.couple ? assign_patch_slots(normal, geometry_[w].side, solver_.settings().flange_angle) : before;
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot) {
      const auto s = static_cast<std::size_t>(slot);
      if (!loaded_[w][slot] || !slots.occupied(s)) continue;
      const FastsimResult r = sum_slot_creep(
          normal, slots, s, [&](std::size_t ip, WearResult*) { return to_creep_result(result.patches[ip]); });
      const ContactPatch patch = slot_normal(normal, slots, s);
      vehicle::SlotForces& f = forces[slot];
      f.fx = r.fx;
      f.fy = r.fy;
      f.mz = r.mz;
      if (coupling_.couple) f.normal_force = patch.normal_force;
      f.status = r.status | (patch.status & ~status::kConverged);
      if (f.status & status::kNotConverged) f.status &= ~status::kConverged;
    }
  } catch (const std::exception&) {
    ++failures_;
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot)
      if (loaded_[w][slot]) forces[slot].status = status::kFailed;
  }
}

void DirectContactModel::creep_coupled(int w, const vehicle::SlotCreepage (&creepage)[vehicle::kContactSlots],
                                       vehicle::SlotForces (&forces)[vehicle::kContactSlots],
                                       FastsimWorkspace& workspace) {
  for (int slot = 0; slot < vehicle::kContactSlots; ++slot) forces[slot] = {};
  const PatchSlots& before = patches_[w];
  // Each patch at the creepage of the slot it sat in after normal().
  auto patch_creepage = [&](std::size_t i, const ContactPatch&) {
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot)
      for (int ip : before.patch[slot])
        if (ip == static_cast<int>(i)) {
          const vehicle::SlotCreepage& c = creepage[slot];
          return Creepage{c.xi, c.eta, c.phi};
        }
    return Creepage{};
  };
  try {
    solve_coupled_load(geometry_[w], load_[w], normal_[w], material_, normal_options_,
                       fastsim_tangential(geometry_[w], patch_creepage, creep_conditions_, material_,
                                          fastsim_options_, workspace),
                       coupling_, coupled_);
    const PatchSlots slots = assign_patch_slots(coupled_.normal, geometry_[w].side, solver_.settings().flange_angle);
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot) {
      const auto s = static_cast<std::size_t>(slot);
      if (!loaded_[w][slot] || !slots.occupied(s)) continue;
      const vehicle::SlotCreepage& c = creepage[slot];
      const FastsimResult r = slot_creep(geometry_[w], coupled_.normal, slots, s, Creepage{c.xi, c.eta, c.phi},
                                         creep_conditions_, material_, fastsim_options_, workspace);
      vehicle::SlotForces& f = forces[slot];
      f.fx = r.fx;
      f.fy = r.fy;
      f.mz = r.mz;
      f.normal_force = slot_normal(coupled_.normal, slots, s).normal_force;
      f.status = r.status | (coupled_.status & status::kNotConverged);
    }
  } catch (const std::exception&) {
    ++failures_;
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot)
      if (loaded_[w][slot]) forces[slot].status = status::kFailed;
  }
}

}  // namespace railtab
