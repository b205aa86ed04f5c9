// SPDX-License-Identifier: Apache-2.0
// The contact chain at single states for the adaptive grids (contact_probe.hpp): geometry -> normal
// -> FASTSIM with the sweep kernel's slot rules, one state at a time.
#include "adaptive/contact_probe.hpp"

#include <array>

#include "core/check.hpp"
#include "core/status.hpp"
#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "kernel/contact_kernel.hpp"
#include "kernel/halfspace_contact.hpp"
#include "tangential/fastsim_contact.hpp"

namespace railtab {

struct ContactProbe::Data {
  ContactGeometrySolver solver;
  Material material;
  NormalOptions normal;
  CreepConditions creep;
  FastsimOptions fastsim;
  halfspace::HalfspaceOptions halfspace;  // normal model halfspace
  bool equilibrium_roll = false;
  double roll = 0.0;
  double yaw = 0.0;  // the scene's fixed yaw (the probe is not run over a yaw axis) [rad]
};


namespace {

// The geometry part of a wheel: which rigid points occupy the slots (assign_slots, as the kernel).
ContactProbe::Wheel geometry_slots(const WheelContactGeometry& geometry) {
  ContactProbe::Wheel geo;
  const SlotAssignment slots = assign_slots(geometry);
  for (std::size_t s = 0; s < kSlots; ++s) {
    if (slots.extra[s]) geo.slot[s].status |= probe_slot_bits::kGeometryTwo;
    if (slots.point[s] < 0) continue;
    const ContactPoint& p = geometry.points[static_cast<std::size_t>(slots.point[s])];
    if (slots.extra[s]) {  // which of the competing points is kept: a switch is a jump
      bool first = true;
      for (const ContactPoint& q : geometry.points) {
        const std::size_t qs = (q.status & status::kFlangeContact) ? 1 : 0;
        if (qs == s && q.wheel_u < p.wheel_u) first = false;
      }
      if (first) geo.slot[s].status |= probe_slot_bits::kGeometryFirst;
    }
    geo.slot[s].geometry = true;
    geo.slot[s].status |= probe_slot_bits::kGeometry;
    geo.slot[s].contact_angle = p.contact_angle;
    geo.slot[s].rolling_radius = p.rolling_radius;
  }
  return geo;
}

// The loaded patches of a normal result into the slots (as the table stores them: slot_normal).
void add_loaded_slots(ContactProbe::Wheel& loaded, const WheelNormalResult& normal, const PatchSlots& patch_slots) {
  for (std::size_t s = 0; s < kSlots; ++s) {
    if (patch_slots.dropped[s] > 0) loaded.slot[s].status |= probe_slot_bits::kPatchDropped;
    if (!patch_slots.occupied(s)) continue;
    const ContactPatch patch = slot_normal(normal, patch_slots, s);  // as the table stores it
    if (!(patch.normal_force > 0.0)) continue;
    loaded.slot[s].loaded = true;
    loaded.slot[s].status |= probe_slot_bits::kLoaded;
    loaded.slot[s].normal_force = patch.normal_force;
    loaded.slot[s].patch_angle = patch.contact_angle;
    loaded.slot[s].patch_radius = patch.rolling_radius;
    loaded.slot[s].patch_status = patch.status | (normal.status & (status::kConverged | status::kNotConverged));
  }
}

}  // namespace

ContactProbe::ContactProbe(const Scene& scene)
    : data_(new Data{make_geometry_solver(scene), scene.material, scene.normal, creep_conditions(scene),
                     fastsim_options(scene), halfspace_options(scene), scene.equilibrium_roll, scene.grids.roll.front(),
                     fixed_yaw(scene)}) {}
ContactProbe::~ContactProbe() { delete data_; }

double ContactProbe::roll_at(double y) const {
  return data_->equilibrium_roll ? table_equilibrium_roll(data_->solver, y) : data_->roll;
}
double ContactProbe::friction() const { return data_->creep.friction; }

std::vector<std::vector<std::array<ContactProbe::Wheel, 2>>> ContactProbe::evaluate(
    double y, const std::vector<double>& loads, const std::vector<std::array<double, 3>>& creepages) const {
  const Data& k = *data_;
  std::vector<std::vector<std::array<Wheel, 2>>> out(loads.size(),
                                                     std::vector<std::array<Wheel, 2>>(creepages.size()));
  FastsimWorkspace& workspace = thread_fastsim_workspace();
  double roll = 0.0;
  try {
    roll = roll_at(y);
  } catch (const std::exception&) {
    for (auto& l : out)
      for (auto& c : l)
        for (auto& w : c) w.slot[0].status = w.slot[1].status = probe_slot_bits::kFailed;
    return out;
  }
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    const Side side = wheel == 0 ? Side::left : Side::right;
    Wheel geo;  // geometry part, copied into every (load, creepage)
    WheelContactGeometry geometry;
    try {
      geometry = k.solver.solve_wheel(side, WheelsetState{y, roll, k.yaw});
    } catch (const std::exception&) {
      for (auto& l : out)
        for (auto& c : l) c[wheel].slot[0].status = c[wheel].slot[1].status = probe_slot_bits::kFailed;
      continue;
    }
    geo = geometry_slots(geometry);
    for (std::size_t il = 0; il < loads.size(); ++il) {
      Wheel loaded = geo;
      WheelNormalResult normal;
      PatchSlots patch_slots;
      // The exact model: creep forces from its steady rolling solution on the creepage-free normal
      // contact (the probe is uncoupled for every model), warm-started along the probe creepages.
      const bool exact = k.normal.model == NormalModel::halfspace;
      halfspace::WheelHalfspaceResult exact_result;
      try {
        if (exact) {
          exact_result = halfspace::solve_halfspace_for_load(geometry, loads[il], k.material, k.halfspace,
                                                             thread_halfspace_workspace());
          normal = to_normal_result(exact_result, geometry);
        } else {
          normal = solve_normal_for_load(geometry, loads[il], k.material, k.normal);
        }
        patch_slots = assign_patch_slots(normal, side, k.solver.settings().flange_angle);
      } catch (const std::exception&) {
        for (auto& c : out[il]) {
          c[wheel] = geo;
          c[wheel].slot[0].status |= probe_slot_bits::kFailed;
          c[wheel].slot[1].status |= probe_slot_bits::kFailed;
        }
        continue;
      }
      add_loaded_slots(loaded, normal, patch_slots);
      for (std::size_t ic = 0; ic < creepages.size(); ++ic) {
        Wheel w = loaded;
        const auto& c = creepages[ic];
        bool exact_failed = false;
        if (exact) {
          try {
            halfspace::solve_halfspace_tangential(exact_result, Creepage{c[0], c[1], c[2]}, k.creep.friction,
                                                  k.material, k.halfspace, thread_halfspace_workspace());
          } catch (const std::exception&) {
            exact_failed = true;
          }
        }
        for (std::size_t s = 0; s < kSlots; ++s) {
          if (!w.slot[s].loaded) continue;
          try {
            if (exact_failed) throw Error("half-space tangential solve failed");
            const FastsimResult r =
                exact ? sum_slot_creep(normal, patch_slots, s,
                                       [&](std::size_t ip, WearResult*) { return to_creep_result(exact_result.patches[ip]); })
                      : slot_creep(geometry, normal, patch_slots, s, Creepage{c[0], c[1], c[2]}, k.creep, k.material,
                                   k.fastsim, workspace);
            w.slot[s].fx = r.fx;
            w.slot[s].fy = r.fy;
          } catch (const std::exception&) {
            w.slot[s].status |= probe_slot_bits::kFailed;
          }
        }
        out[il][ic][wheel] = w;
      }
    }
  }
  return out;
}

ContactProbe::Wheel ContactProbe::configuration(double y, std::size_t wheel, double load) const {
  const Data& k = *data_;
  Wheel w;
  const Side side = wheel == 0 ? Side::left : Side::right;
  WheelContactGeometry geometry;
  try {
    geometry = k.solver.solve_wheel(side, WheelsetState{y, roll_at(y), k.yaw});
  } catch (const std::exception&) {
    w.slot[0].status = w.slot[1].status = probe_slot_bits::kFailed;
    return w;
  }
  w = geometry_slots(geometry);
  try {
    WheelNormalResult normal;
    if (k.normal.model == NormalModel::halfspace) {
      // The exact result has the candidate patches' reference points; with at most one patch its
      // configuration (slot, loaded, reference radius) is theirs (halfspace::candidate_patches), so
      // the exact normal problem is solved only where two or more patches share the load.
      normal = halfspace::candidate_patches(geometry, load, k.material);
      if (normal.patches.size() > 1)
        normal = to_normal_result(halfspace::solve_halfspace_for_load(geometry, load, k.material, k.halfspace,
                                                                      thread_halfspace_workspace()),
                                  geometry);
    } else {
      normal = solve_normal_for_load(geometry, load, k.material, k.normal);
    }
    add_loaded_slots(w, normal, assign_patch_slots(normal, side, k.solver.settings().flange_angle));
  } catch (const std::exception&) {
    w.slot[0].status |= probe_slot_bits::kFailed;
    w.slot[1].status |= probe_slot_bits::kFailed;
  }
  return w;
}

}  // namespace railtab
