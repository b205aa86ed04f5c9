// SPDX-License-Identifier: Apache-2.0
// The sweep's contact kernel: geometry, normal, FASTSIM and wear per (y, roll, yaw) column, in slots.
#include "kernel/contact_kernel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "core/check.hpp"
#include "kernel/creep_map.hpp"
#include "kernel/finite_status.hpp"
#include "kernel/creep_loops.hpp"
#include "kernel/halfspace_contact.hpp"
#include "kernel/kernel_cells.hpp"
#include "geometry/contact_geometry.hpp"
#include "halfspace/patch_linear_creep.hpp"
#include "normal/normal_model.hpp"
#include "tangential/fastsim_contact.hpp"
#include "wear/archard.hpp"

namespace railtab {
// The kernel's cells and creep loops (kernel_cells.hpp, creep_loops.hpp).
using namespace kernel;

namespace {

// Every cell of a part for load il (or all loads) gets the failure status.
void fail_cells(ColumnOutput& out, std::size_t wheel, std::size_t part, std::size_t begin, std::size_t end,
                StatusBits bits) {
  for (std::size_t c = begin; c < end; ++c) out.status(wheel, part)[c] = bits;
}

// Format 2.1: failed normal cells [begin, end) keep the nominal saturation scales, as an empty
// slot does. The lookup refuses a scale that is not > 0 (it divides by it), so with the zeros a
// single failed column made the whole table unloadable.
void fail_scales(const KernelData& k, ColumnOutput& out, std::size_t wheel, std::size_t begin, std::size_t end) {
  if (!k.normalised) return;
  const double values[3] = {creep_map::kNominal.xi, creep_map::kNominal.eta, creep_map::kNominal.phi};
  for (std::size_t j = 0; j < 3; ++j) {
    double* scale = out.values(wheel, kNormalPart, std::size(kNormalOutputs) + j);
    for (std::size_t c = begin; c < end; ++c) scale[c] = values[j];
  }
}

// Format 2.1: the saturation scales of a slot's creepage-free contact. Kalker's (creep_map::scales:
// c^2 = area / pi, C_ij at the patch's a/b) set the size of the probe creepages; the scales are
// then those of the model's own linear creep coefficients, -dF/d(creepage) of FASTSIM on the slot's
// patches at a creepage of 1e-3 of Kalker's scale (s_xi = 3 mu N / k_xx, s_eta = 3 mu N / k_yy,
// s_phi = mu N / k_y,phi): for a Hertz patch the same as Kalker's up to FASTSIM's discretisation,
// for strip patches (STRIPES, Linder), whose strips' own ellipses make them stiffer than the
// equal-area ellipse, the creepage at which that model's force actually bends, so the saturation
// law of the stored forces lines up with it. Kalker's stays where a slope is not positive.
creep_map::Scales slot_scales(const KernelData& k, const WheelContactGeometry& geometry,
                              const WheelNormalResult& normal, const PatchSlots& slots, std::size_t slot) {
  const ContactPatch patch = slot_normal(normal, slots, slot);
  creep_map::Scales s = creep_map::scales(patch, k.material, k.creep.friction);
  const double mun = k.creep.friction * patch.normal_force;
  if (!(mun > 0.0)) return s;
  FastsimWorkspace& workspace = thread_fastsim_workspace();
  auto force = [&](const Creepage& c) {
    try {
      return slot_creep(geometry, normal, slots, slot, c, k.creep, k.material, k.fastsim, workspace);
    } catch (const std::exception&) {
      return FastsimResult{};  // keep Kalker's scale; the creep points report the failure
    }
  };
  const double ex = 1e-3 * s.xi, ee = 1e-3 * s.eta, ep = 1e-3 * s.phi;
  const double kxx = -force(Creepage{ex, 0.0, 0.0}).fx / ex;
  const double kyy = -force(Creepage{0.0, ee, 0.0}).fy / ee;
  const double kyp = -force(Creepage{0.0, 0.0, ep}).fy / ep;
  if (kxx > 0.0 && std::isfinite(kxx)) s.xi = 3.0 * mun / kxx;
  if (kyy > 0.0 && std::isfinite(kyy)) s.eta = 3.0 * mun / kyy;
  if (kyp > 0.0 && std::isfinite(kyp)) s.phi = mun / kyp;
  return s;
}

// Index of the first creep_coefficient_* output in the normal part (after the creep scales of
// normalised tables).
std::size_t first_coefficient_output(const KernelData& k) {
  return std::size(kNormalOutputs) + (k.normalised ? std::size(kCreepScaleOutputs) : 0);
}

// A slot's linear creep coefficients (slot_linear_creep), or the message of their failure.
struct SlotCreep {
  LinearCreep coefficients;
  std::string error;  // empty: computed
};
SlotCreep slot_creep(const KernelData& k, const WheelContactGeometry& geometry, const WheelNormalResult& normal,
                     const halfspace::WheelHalfspaceResult* exact, const PatchSlots& slots, std::size_t s) {
  SlotCreep r;
  try {
    r.coefficients = slot_linear_creep(geometry, normal, exact, slots, s, k.creep, k.material, k.fastsim, k.halfspace);
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

// The slot's linear creep coefficients into the normal part's cell (zeros for a slot without a
// loaded patch): `known` when the caller has them already (the exact model's scales use the same),
// else computed here. A failed computation stores zeros and marks the cell failed, with a message.
// Without k.creep_coefficients the cell keeps zeros and nothing is computed.
void store_creep_coefficients(const KernelData& k, const WheelContactGeometry& geometry, const WheelNormalResult& normal,
                              const halfspace::WheelHalfspaceResult* exact, const PatchSlots& slots, std::size_t s,
                              ColumnOutput& out, std::size_t wheel, std::size_t cell, double y, double load,
                              const SlotCreep* known = nullptr) {
  if (!k.creep_coefficients) return;
  const SlotCreep computed = known ? SlotCreep{} : slot_creep(k, geometry, normal, exact, slots, s);
  const SlotCreep& r = known ? *known : computed;
  if (!r.error.empty()) {
    out.failure(fmt::format("linear creep coefficients, {} wheel, y = {} m, load = {} N, slot {}: {}",
                            to_string(geometry.side), y, load, s, r.error));
    out.status(wheel, kNormalPart)[cell] = non_finite_status(out.status(wheel, kNormalPart)[cell]);
    return;
  }
  const LinearCreep& c = r.coefficients;
  bool finite = true;
  for (const auto& row : c.slope)
    for (double v : row) finite = finite && std::isfinite(v);
  const std::size_t first = first_coefficient_output(k);
  for (std::size_t f = 0; f < 3; ++f)
    for (std::size_t q = 0; q < 3; ++q) out.values(wheel, kNormalPart, first + f * 3 + q)[cell] = finite ? c.slope[f][q] : 0.0;
  if (!finite) {
    out.failure(fmt::format("linear creep coefficients, {} wheel, y = {} m, load = {} N, slot {}: not finite "
                            "(stored as 0, status failed)", to_string(geometry.side), y, load, s));
    out.status(wheel, kNormalPart)[cell] = non_finite_status(out.status(wheel, kNormalPart)[cell]);
  }
}

// The exact model's scales of a slot: as slot_scales, with the exact model's own linear creep
// coefficients (slot_linear_creep: halfspace::patch_linear_creep, its steady rolling solution in full
// adhesion on each of the slot's solved patches, the slopes summed over them), so the nodes
// gather where the exact creep forces bend, for tread, flange and spin alike. Kalker's scale stays
// where a slope is not positive or a solve fails (the creep points report their own failures).
// `creep`: the slot's slot_creep on the exact result.
creep_map::Scales exact_slot_scales(const KernelData& k, const WheelNormalResult& normal, const PatchSlots& slots,
                                    std::size_t slot, const SlotCreep& creep) {
  const ContactPatch patch = slot_normal(normal, slots, slot);
  creep_map::Scales s = creep_map::scales(patch, k.material, k.creep.friction);
  const double mun = k.creep.friction * patch.normal_force;
  if (!(mun > 0.0) || !creep.error.empty()) return s;
  const LinearCreep& c = creep.coefficients;
  const double kxx = -c.slope[0][0], kyy = -c.slope[1][1], kyp = -c.slope[1][2];
  if (kxx > 0.0 && std::isfinite(kxx)) s.xi = 3.0 * mun / kxx;
  if (kyy > 0.0 && std::isfinite(kyy)) s.eta = 3.0 * mun / kyy;
  if (kyp > 0.0 && std::isfinite(kyp)) s.phi = mun / kyp;
  return s;
}

void solve_wheel_column(const KernelData& k, const ColumnState& state, std::size_t wheel, ColumnOutput& out) {
  const Side side = wheel == 0 ? Side::left : Side::right;
  const std::size_t nload = k.grids.load.size();
  const std::size_t ncreep = nload * k.creepages() * kSlots;  // creep/wear cells of the column
  WheelContactGeometry geometry;
  try {
    geometry = k.solver.solve_wheel(side, WheelsetState{state.y, state.roll, state.yaw});
  } catch (const std::exception& e) {
    out.failure(fmt::format("geometry, {} wheel, y = {} m, roll = {} rad: {}", to_string(side), state.y,
                            state.roll, e.what()));
    fail_cells(out, wheel, kGeometryPart, 0, kSlots, failure_status(state));
    fail_cells(out, wheel, kNormalPart, 0, nload * kSlots, failure_status(state));
    fail_scales(k, out, wheel, 0, nload * kSlots);
    fail_cells(out, wheel, kCreepPart, 0, ncreep, failure_status(state));
    fail_cells(out, wheel, kWearPart, 0, ncreep, failure_status(state));
    return;
  }
  const SlotAssignment slots = assign_slots(geometry);
  const StatusBits wheel_bits = geometry.status & (status::kTwoPoint | status::kProfileEdge);
  for (std::size_t s = 0; s < kSlots; ++s) {
    if (slots.point[s] < 0) continue;  // empty slot: zeros, status 0
    const ContactPoint& p = geometry.points[static_cast<std::size_t>(slots.point[s])];
    store(kGeometryOutputs, p, p.status | status::kConverged | wheel_bits | slots.extra[s], out, wheel, kGeometryPart, s,
          [&] { return fmt::format("geometry, {} wheel, y = {} m, roll = {} rad", to_string(side), state.y, state.roll); });
  }

  const NormalOptions normal_options = uncoupled_options(k, state);
  const bool exact = normal_options.model == NormalModel::halfspace;
  for (std::size_t il = 0; il < nload; ++il) {
    WheelNormalResult normal;
    halfspace::WheelHalfspaceResult exact_result;  // the half-space model's own result (exact only)
    try {
      if (exact) {
        exact_result = halfspace::solve_halfspace_for_load(geometry, k.grids.load[il], k.material, k.halfspace,
                                                           thread_halfspace_workspace());
        normal = to_normal_result(exact_result, geometry);
      } else {
        normal = solve_normal_for_load(geometry, k.grids.load[il], k.material, normal_options);
      }
    } catch (const std::exception& e) {
      out.failure(fmt::format("normal, {} wheel, y = {} m, roll = {} rad, load = {} N: {}", to_string(side),
                              state.y, state.roll, k.grids.load[il], e.what()));
      fail_cells(out, wheel, kNormalPart, il * kSlots, (il + 1) * kSlots, failure_status(state));
      fail_scales(k, out, wheel, il * kSlots, (il + 1) * kSlots);
      const std::size_t per_load = k.creepages() * kSlots;
      fail_cells(out, wheel, kCreepPart, il * per_load, (il + 1) * per_load, failure_status(state));
      fail_cells(out, wheel, kWearPart, il * per_load, (il + 1) * per_load, failure_status(state));
      continue;
    }
    const StatusBits solver_bits = normal.status & (status::kConverged | status::kNotConverged);
    const PatchSlots patch_slots = assign_patch_slots(normal, side, k.solver.settings().flange_angle);
    // Format 2.1: the saturation scales of each slot's creepage-free contact; an empty slot takes
    // the other slot's (or nominal ones), so that cells next to it map creepages sensibly.
    // The exact model's scales come from its linear creep coefficients, which the normal part also
    // stores: computed once per slot (each is six steady rolling solves per patch).
    creep_map::Scales scales[kSlots];
    std::array<SlotCreep, kSlots> exact_creep;
    std::array<bool, kSlots> exact_creep_known{};
    if (k.normalised) {
      for (std::size_t s = 0; s < kSlots; ++s) {
        if (!patch_slots.occupied(s)) continue;
        if (exact) {
          exact_creep[s] = slot_creep(k, geometry, normal, &exact_result, patch_slots, s);
          exact_creep_known[s] = true;
          scales[s] = exact_slot_scales(k, normal, patch_slots, s, exact_creep[s]);
        } else {
          scales[s] = slot_scales(k, geometry, normal, patch_slots, s);
        }
      }
      for (std::size_t s = 0; s < kSlots; ++s)
        if (!patch_slots.occupied(s))
          scales[s] = patch_slots.occupied(1 - s) ? scales[1 - s] : creep_map::kNominal;
      for (std::size_t s = 0; s < kSlots; ++s) {
        const double values[3] = {scales[s].xi, scales[s].eta, scales[s].phi};
        for (std::size_t j = 0; j < 3; ++j)
          out.values(wheel, kNormalPart, std::size(kNormalOutputs) + j)[il * kSlots + s] = values[j];
      }
    }
    const creep_map::Scales* slot_scales = k.normalised ? scales : nullptr;
    if (exact || (k.coupling.couple && k.creepages() > 0)) {
      // The normal part keeps the creepage-free solution; the creep part gets its own per creepage.
      for (std::size_t s = 0; s < kSlots; ++s) {
        if (!patch_slots.occupied(s)) continue;
        const ContactPatch patch = slot_normal(normal, patch_slots, s);
        store(kNormalOutputs, patch, patch.status | solver_bits | patch_slots.extra[s], out, wheel, kNormalPart,
              il * kSlots + s, [&] {
                return fmt::format("normal, {} wheel, y = {} m, roll = {} rad, load = {} N", to_string(side), state.y,
                                   state.roll, k.grids.load[il]);
              });
        store_creep_coefficients(k, geometry, normal, exact ? &exact_result : nullptr, patch_slots, s, out, wheel,
                                 il * kSlots + s, state.y, k.grids.load[il],
                                 exact_creep_known[s] ? &exact_creep[s] : nullptr);
      }
      if (normal.patches.empty() || k.creepages() == 0) continue;
      if (exact)
        solve_creep_halfspace(k, geometry, exact_result, patch_slots, state, wheel, il, slot_scales, out);
      else
        solve_creep_coupled(k, geometry, normal, patch_slots, state, wheel, il, slot_scales, out);
      continue;
    }
    for (std::size_t s = 0; s < kSlots; ++s) {
      if (!patch_slots.occupied(s)) continue;  // no loaded patch in this slot: zeros, status 0
      const ContactPatch patch = slot_normal(normal, patch_slots, s);  // the sum of the slot's patches
      store(kNormalOutputs, patch, patch.status | solver_bits | patch_slots.extra[s], out, wheel, kNormalPart,
            il * kSlots + s, [&] {
              return fmt::format("normal, {} wheel, y = {} m, roll = {} rad, load = {} N", to_string(side), state.y,
                                 state.roll, k.grids.load[il]);
            });
      store_creep_coefficients(k, geometry, normal, nullptr, patch_slots, s, out, wheel, il * kSlots + s, state.y,
                               k.grids.load[il]);
      // Creep and wear on top of this normal result; an unloaded slot has none (zeros, lift_off).
      if (!(patch.normal_force > 0.0)) {
        const std::size_t per_load = k.creepages();
        for (std::size_t c = il * per_load; c < (il + 1) * per_load; ++c) {
          out.status(wheel, kCreepPart)[c * kSlots + s] = status::kConverged | status::kLiftOff | patch_slots.extra[s];
          out.status(wheel, kWearPart)[c * kSlots + s] = status::kConverged | status::kLiftOff | patch_slots.extra[s];
        }
        continue;
      }
      solve_creep(k, geometry, normal, patch_slots, state, wheel, il, s, slot_scales, out);
    }
  }
}

}  // namespace

PatchSlots assign_patch_slots(const WheelNormalResult& normal, Side side, double flange_angle) {
  PatchSlots a;
  auto force = [&](int i) { return normal.patches[static_cast<std::size_t>(i)].normal_force; };
  for (std::size_t i = 0; i < normal.patches.size(); ++i) {
    const ContactPatch& patch = normal.patches[i];
    const double angle_side = outward_sign(side) * patch.contact_angle;
    const std::size_t slot = angle_side > flange_angle ? 1 : 0;
    int(&kept)[kPatchesPerSlot] = a.patch[slot];
    const int index = static_cast<int>(i);
    if (kept[0] < 0) {
      kept[0] = index;
      continue;
    }
    a.extra[slot] |= status::kTwoPoint;
    if (kept[1] >= 0) ++a.dropped[slot];  // a third patch: the one with the smallest force goes
    if (patch.normal_force > force(kept[0])) {
      kept[1] = kept[0];
      kept[0] = index;
    } else if (kept[1] < 0 || patch.normal_force > force(kept[1])) {
      kept[1] = index;
    }
  }
  return a;
}

ContactPatch slot_normal(const WheelNormalResult& normal, const PatchSlots& slots, std::size_t slot) {
  RAILTAB_CHECK(slot < kSlots && slots.occupied(slot), "slot_normal: slot {} holds no patch", slot);
  ContactPatch sum = normal.patches[static_cast<std::size_t>(slots.patch[slot][0])];
  const int second = slots.patch[slot][1];
  if (second < 0) return sum;
  const ContactPatch& q = normal.patches[static_cast<std::size_t>(second)];
  sum.normal_force += q.normal_force;
  sum.area += q.area;
  sum.max_pressure = std::max(sum.max_pressure, q.max_pressure);
  sum.status |= q.status;
  return sum;
}

FastsimResult slot_creep(const WheelContactGeometry& geometry, const WheelNormalResult& normal,
                         const PatchSlots& slots, std::size_t slot, const Creepage& creepage,
                         const CreepConditions& conditions, const Material& material, const FastsimOptions& options,
                         FastsimWorkspace& workspace, SlotWear* wear) {
  return sum_slot_creep(
      normal, slots, slot,
      [&](std::size_t ip, WearResult* worn) {
        const FastsimResult r = fastsim_contact(geometry, normal.patches[ip], creepage, conditions, material, options,
                                                workspace);
        if (worn) *worn = archard_wear(workspace, wear->options, wear->distribution);
        return r;
      },
      wear);
}

FastsimResult sum_slot_creep(const WheelNormalResult& normal, const PatchSlots& slots, std::size_t slot,
                             const PatchCreep& solve_patch, SlotWear* wear) {
  RAILTAB_CHECK(slot < kSlots, "slot_creep: slot {} of {}", slot, kSlots);
  FastsimResult total;
  WearResult worn;
  double area = 0.0, slip_area = 0.0, seizure_volume = 0.0;
  int loaded = 0;
  for (int ip : slots.patch[slot]) {
    if (ip < 0) continue;
    const ContactPatch& patch = normal.patches[static_cast<std::size_t>(ip)];
    if (!(patch.normal_force > 0.0)) continue;
    WearResult w;
    const FastsimResult r = solve_patch(static_cast<std::size_t>(ip), wear ? &w : nullptr);
    area += patch.area;
    slip_area += r.slip_fraction * patch.area;
    seizure_volume += w.seizure_fraction * w.volume_rate;
    if (loaded++ == 0) {  // one patch: its results unchanged
      total = r;
      worn = w;
      continue;
    }
    total.fx += r.fx;
    total.fy += r.fy;
    total.mz += r.mz;
    total.normal_force += r.normal_force;
    total.frictional_work += r.frictional_work;
    total.slip_fraction = area > 0.0 ? slip_area / area : std::max(total.slip_fraction, r.slip_fraction);
    total.status |= r.status;
    worn.wear_rate += w.wear_rate;
    worn.volume_rate += w.volume_rate;
    worn.max_depth_rate = std::max(worn.max_depth_rate, w.max_depth_rate);
    worn.seizure_fraction = worn.volume_rate > 0.0 ? seizure_volume / worn.volume_rate : 0.0;
    worn.status |= w.status;
  }
  if (loaded == 0) {
    total.status = status::kConverged | status::kLiftOff;
    worn.status = status::kConverged | status::kLiftOff;
  }
  if (wear) wear->result = worn;
  return total;
}

LinearCreep slot_linear_creep(const WheelContactGeometry& geometry, const WheelNormalResult& normal,
                              const halfspace::WheelHalfspaceResult* exact, const PatchSlots& slots, std::size_t slot,
                              const CreepConditions& conditions, const Material& material,
                              const FastsimOptions& fastsim, const halfspace::HalfspaceOptions& halfspace) {
  RAILTAB_CHECK(slot < kSlots, "slot_linear_creep: slot {} of {}", slot, kSlots);
  LinearCreep sum;
  for (int ip : slots.patch[slot]) {
    if (ip < 0) continue;
    const std::size_t i = static_cast<std::size_t>(ip);
    if (!(normal.patches[i].normal_force > 0.0)) continue;
    LinearCreep c;
    if (exact) {
      RAILTAB_CHECK(i < exact->patches.size(), "slot_linear_creep: patch {} of {} exact patches", i,
                    exact->patches.size());
      const halfspace::HalfspacePatch& hp = exact->patches[i];
      c = halfspace::patch_linear_creep(hp.grid, hp.normal.pressure, material, halfspace.tangential,
                                        thread_halfspace_workspace(), hp.track_sign);
    } else {
      c = fastsim_linear_creep(geometry, normal.patches[i], conditions, material, fastsim, thread_fastsim_workspace());
    }
    for (int f = 0; f < 3; ++f)
      for (int q = 0; q < 3; ++q) sum.slope[f][q] += c.slope[f][q];
  }
  return sum;
}

SlotAssignment assign_slots(const WheelContactGeometry& geometry) {
  SlotAssignment a;
  for (std::size_t i = 0; i < geometry.points.size(); ++i) {
    const ContactPoint& p = geometry.points[i];
    std::size_t slot = (p.status & status::kFlangeContact) ? 1 : 0;
    int& current = a.point[slot];
    if (current < 0) {
      current = static_cast<int>(i);
      continue;
    }
    a.extra[slot] |= status::kTwoPoint;
    if (p.separation < geometry.points[static_cast<std::size_t>(current)].separation) current = static_cast<int>(i);
  }
  return a;
}

namespace {

// Root attribute creep_map of a table with normalised creep coordinates (format 2.1): the
// physical range of every swept creepage axis and the friction coefficient of F / (mu N).
nlohmann::json creep_map_attribute(const Scene& scene) {
  nlohmann::json j;
  // "normalised", then "+<key>" for each key below that a reader must apply to read the forces
  // right (docs/table-format.md): readers from before a key accept only "normalised" and so refuse
  // the table instead of misreading it. Without such keys the attribute keeps its bytes.
  j["coordinates"] = scene.creep_law_spin != 0.0 ? "normalised+law_spin" : "normalised";
  j["friction"] = scene.tangential.friction;
  // The creep part's normal_force is the vertical load share (creep_map.hpp, vertical_share).
  if (scene.tangential.load_coupling) j["normal_force"] = "vertical_share";
  const std::vector<double>* grids[3] = {&scene.grids.xi, &scene.grids.eta, &scene.grids.phi};
  const char* names[3] = {"xi", "eta", "phi"};
  for (std::size_t i = 0; i < 3; ++i) {
    const std::vector<double>& g = *grids[i];
    if (g.size() < 2) continue;
    const std::string name = names[i];
    j[name + "_min"] = g.front();
    j[name + "_max"] = g.back();
    // Written only when not 1, so tables of scenes without creep_knee keep their bytes.
    const double knee = scene.creep_knee[i];
    if (knee != 1.0) j[name + "_knee"] = knee;
  }
  // Written only when not 0, so tables of scenes without creep_law_spin keep their bytes.
  if (scene.creep_law_spin != 0.0) j["law_spin"] = scene.creep_law_spin;
  return j;
}

// Format 2.1: the creep and wear parts' coordinate of each creepage axis, uniform in [-1, 1]
// (creep_map.hpp); the physical range is in the root attribute creep_map.
std::vector<TableAxis> normalised_creep_axes(const Scene& scene) {
  std::vector<TableAxis> axes;
  const std::vector<double>* grids[3] = {&scene.grids.xi, &scene.grids.eta, &scene.grids.phi};
  const char* names[3] = {"xi", "eta", "phi"};
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string name = names[i];
    axes.push_back(TableAxis{name, std::string(1, '1'),
                             "normalised " + name + " coordinate v in [-1, 1]: v = -1 + 2 (m(q/s) - m(lo/s)) / "
                             "(m(hi/s) - m(lo/s)), m(x) = x/(1+|x|), s the normal part's creep_scale_" + name +
                             ", [lo, hi] the physical range in the root attribute creep_map",
                             creep_map::nodes(grids[i]->size()), false});
  }
  return axes;
}

// Whether an output changes sign under the mirror that swaps the wheels: the lateral ones (an
// angle about x, a force along s, a moment about n) and the creep coefficients that pair an odd
// force with an even creepage or the reverse (xi is even, eta and phi are odd).
bool mirror_odd(const std::string& name) {
  for (const char* odd : {"contact_angle", "fy", "mz", "fy_normalised", "mz_normalised", "creep_coefficient_fx_eta",
                          "creep_coefficient_fx_phi", "creep_coefficient_fy_xi", "creep_coefficient_mz_xi"})
    if (name == odd) return true;
  return false;
}

}  // namespace

double table_equilibrium_roll(const ContactGeometrySolver& solver, double y) {
  return y < 0.0 ? -solver.equilibrium_roll(-y) : solver.equilibrium_roll(y);
}

PointCost contact_point_cost(const Scene& scene) {
  if (scene.normal.model != NormalModel::halfspace) return kFastPointCost;
  // The exact model's solves scale with the elements of a patch, 1 / element_size^2.
  const double ratio = kExactPointCostElementSize / scene.halfspace.element_size;
  return {kExactPointCost.low * ratio * ratio, kExactPointCost.high * ratio * ratio};
}

SweepKernel make_contact_kernel(const Scene& scene) { return make_contact_kernel(scene, make_geometry_solver(scene)); }

SweepKernel make_contact_kernel(const Scene& scene, const ContactGeometrySolver& geometry, bool creep_coefficients) {
  const FastsimOptions fastsim = fastsim_options(scene);
  const CreepConditions creep = creep_conditions(scene);
  const WearOptions wear = wear_options(scene);
  // [accuracy] models: the normal model chosen per y node (docs/adaptive-grids.md).
  const AccuracyTargets& accuracy = scene.accuracy;
  std::vector<NormalModel> model_by_y;
  if (!accuracy.model_by_y.empty()) {
    RAILTAB_CHECK(accuracy.model_by_y.size() == scene.grids.y.size(),
                  "contact kernel: a model choice for {} y nodes but the y grid has {}", accuracy.model_by_y.size(),
                  scene.grids.y.size());
    for (std::size_t i : accuracy.model_by_y) {
      RAILTAB_CHECK(i < accuracy.models.size(), "contact kernel: model index {} of {} models", i, accuracy.models.size());
      model_by_y.push_back(accuracy.models[i]);
    }
  }
  auto data = std::make_shared<const KernelData>(KernelData{geometry, scene.grids, scene.material,
                                                            scene.normal, scene.tangential, creep, fastsim, wear,
                                                            coupled_load_options(scene), halfspace_options(scene),
                                                            model_by_y, scene.creep_normalised, scene.creep_knee,
                                                            scene.creep_law_spin, creep_coefficients});
  SweepKernel kernel;
  kernel.parts.push_back(part_spec("geometry", {}, kGeometryOutputs));
  kernel.parts.push_back(part_spec("normal", {"load"}, kNormalOutputs));
  if (scene.creep_normalised)
    for (const OutputInfo& o : kCreepScaleOutputs) kernel.parts.back().outputs.push_back(o);
  for (const OutputInfo& o : kCreepCoefficientOutputs) kernel.parts.back().outputs.push_back(o);
  kernel.parts.push_back(creep_part_spec(kCreepOutputs, kCreepNormalOutputs, scene.tangential.load_coupling));
  if (scene.creep_normalised) {
    // Format 2.1: stored forces are normalised (creep_map.hpp); the lookup scales them back to N.
    std::vector<OutputInfo>& o = kernel.parts.back().outputs;
    // Other names than fx, fy, mz, so that a reader that does not know format 2.1 refuses the
    // table (missing fx) instead of returning normalised numbers as forces.
    o[0] = {"fx_normalised", "1",
            "fx / (mu N) minus the saturation law's x component at this node's normalised creepage "
            "(N the creep point's normal force; docs/table-format.md, normalised creep part)"};
    o[1] = {"fy_normalised", "1", "fy / (mu N) minus the saturation law's y component at this node's normalised creepage"};
    o[2] = {"mz_normalised", "m", "mz / (mu N): spin moment on the wheel divided by mu N"};
  }
  kernel.parts.push_back(part_spec("wear", {"load", "xi", "eta", "phi"}, kWearOutputs));
  kernel.points_per_column = scene.grids.load.size() * data->creepages();
  const NormalOptions& n = scene.normal;
  kernel.models = {
      {"normal", to_string(n.model)},
      {"negative_curvature", to_string(n.negative_curvature)},
      {"strips", n.strips},
      {"virtual_penetration", n.virtual_penetration},
      {"normal_tolerance", n.tolerance},
      {"flange_angle", scene.geometry.flange_angle},
      {"youngs_modulus", scene.material.youngs_modulus},
      {"poisson_ratio", scene.material.poisson_ratio},
      {"tangential", n.model == NormalModel::halfspace ? "halfspace-exact" : "fastsim-strips"},
      {"load_coupling", scene.tangential.load_coupling},
      {"spin", to_string(fastsim.spin)},
      {"elements_per_strip", fastsim.elements_per_strip},
      {"friction", scene.tangential.friction},
      {"speed", scene.tangential.speed},
      {"wear", "archard-kth"},
      {"hardness", scene.wear.hardness},
      {"lubrication_factor", scene.wear.lubrication_factor},
  };
  const bool any_exact = n.model == NormalModel::halfspace ||
                         std::find(model_by_y.begin(), model_by_y.end(), NormalModel::halfspace) != model_by_y.end();
  if (any_exact) kernel.models["element_size"] = scene.halfspace.element_size;
  if (!model_by_y.empty()) {
    // The planned choice is data, not status: kFallbackModel stays reserved for failures.
    nlohmann::json names = nlohmann::json::array();
    std::string legend;
    for (std::size_t i = 0; i < accuracy.models.size(); ++i) {
      names.push_back(to_string(accuracy.models[i]));
      legend += fmt::format("{}{} = {}", i ? ", " : "", i, to_string(accuracy.models[i]));
    }
    kernel.models["normal_models"] = names;
    kernel.models["normal_model_choice"] = "per y node, root dataset normal_model_index; `normal` is the reference";
    SweepKernel::PerYOutput index{{"normal_model_index", "1",
                                   fmt::format("normal model used at this y (planned choice, [accuracy] models): "
                                               "index into models.normal_models: {}",
                                               legend)},
                                  {}};
    index.values.assign(accuracy.model_by_y.begin(), accuracy.model_by_y.end());
    kernel.per_y.push_back(std::move(index));
  }
  if (scene.creep_normalised) {
    kernel.own_axes = normalised_creep_axes(scene);
    kernel.attributes.emplace_back("creep_map", creep_map_attribute(scene).dump());
  }
  kernel.point_cost = contact_point_cost(scene);
  // Both wheels are one code path on shared profiles (docs/conventions.md, side frame), so the
  // mirror swaps them exactly (with the equilibrium roll exactly odd: table_equilibrium_roll),
  // checked to the last bit for STRIPES, Linder, Kik-Piotrowski and the exact model (tests/
  // generator/generate/mirror_test.cpp). Not for Hertz: its ellipse's FASTSIM at spin +-phi
  // differs in the last bits.
  kernel.mirror_symmetric = true;
  for (NormalModel m : model_by_y.empty() ? std::vector<NormalModel>{n.model} : model_by_y)
    kernel.mirror_symmetric = kernel.mirror_symmetric && m != NormalModel::hertz;
  for (PartSpec& part : kernel.parts)
    for (OutputInfo& o : part.outputs) o.odd = mirror_odd(o.name);
  kernel.equilibrium_roll = [data](double y) { return table_equilibrium_roll(data->solver, y); };
  kernel.compute = [data](const ColumnState& state, ColumnOutput& out) {
    for (std::size_t wheel = 0; wheel < 2; ++wheel)
      if (state.wheels & (1u << wheel)) solve_wheel_column(*data, state, wheel, out);
  };
  return kernel;
}

}  // namespace railtab
