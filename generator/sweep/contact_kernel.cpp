// SPDX-License-Identifier: Apache-2.0
// The sweep's contact kernel: geometry, normal, FASTSIM and wear per (y, roll) column, in slots.
#include "sweep/contact_kernel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "core/check.hpp"
#include "sweep/creep_map.hpp"
#include "sweep/finite_status.hpp"
#include "sweep/halfspace_contact.hpp"
#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "tangential/fastsim_contact.hpp"
#include "wear/archard.hpp"

namespace railtab {
namespace {

// One float64 output of a part: dataset name, units, description, and how to get it from the
// part's per-contact result.
template <class Result>
struct Output {
  const char* name;
  const char* units;
  const char* description;
  double (*get)(const Result&);
};

// Geometry part, per contact point (axes y, roll, slot).
const Output<ContactPoint> kGeometryOutputs[] = {
    {"contact_angle", "rad", "contact angle, track frame, ISO sign (+ towards the flange for the left wheel)",
     [](const ContactPoint& p) { return p.contact_angle; }},
    {"rolling_radius", "m", "wheel rolling radius at the contact point",
     [](const ContactPoint& p) { return p.rolling_radius; }},
    {"wheel_y", "m", "contact position in the wheel profile frame (u)", [](const ContactPoint& p) { return p.wheel_u; }},
    {"rail_y", "m", "contact position in the rail profile frame (u)", [](const ContactPoint& p) { return p.rail_u; }},
    {"separation", "m", "vertical gap still open at rigid contact (0 = touching)",
     [](const ContactPoint& p) { return p.separation; }},
    {"curvature_a", "1/m", "relative curvature A, rolling direction", [](const ContactPoint& p) { return p.curvature_a; }},
    {"curvature_b", "1/m", "relative curvature B, lateral direction", [](const ContactPoint& p) { return p.curvature_b; }},
};

// Normal part, per contact patch (axes y, roll, load, slot).
const Output<ContactPatch> kNormalOutputs[] = {
    {"normal_force", "N", "normal force along the contact normal", [](const ContactPatch& c) { return c.normal_force; }},
    {"approach", "m", "normal approach at the patch reference point", [](const ContactPatch& c) { return c.penetration; }},
    {"area", "m2", "contact area", [](const ContactPatch& c) { return c.area; }},
    {"max_pressure", "Pa", "maximum contact pressure", [](const ContactPatch& c) { return c.max_pressure; }},
    {"a", "m", "rolling semi-axis (elliptic models; 0 for non-elliptic patches)",
     [](const ContactPatch& c) { return c.semi_axis_a; }},
    {"b", "m", "lateral semi-axis (elliptic models; 0 for non-elliptic patches)",
     [](const ContactPatch& c) { return c.semi_axis_b; }},
};

// Normal part, format 2.1 with normalised creep coordinates: the saturation scales of the slot's
// creepage-free contact (sweep/creep_map.hpp), which map the creep part's coordinates to creepages.
const OutputInfo kCreepScaleOutputs[] = {
    {"creep_scale_xi", "1", "longitudinal creepage scale s_xi = 3 mu N / (G c^2 C11) of the creep part's coordinate"},
    {"creep_scale_eta", "1", "lateral creepage scale s_eta = 3 mu N / (G c^2 C22) of the creep part's coordinate"},
    {"creep_scale_phi", "rad/m", "spin creepage scale s_phi = mu N / (G c^3 C23) of the creep part's coordinate"},
};

// Creep part, per loaded patch and creepage (axes y, roll, load, xi, eta, phi, slot).
const Output<FastsimResult> kCreepOutputs[] = {
    {"fx", "N", "longitudinal creep force on the wheel (contact frame x)", [](const FastsimResult& r) { return r.fx; }},
    {"fy", "N", "lateral creep force on the wheel (contact frame s)", [](const FastsimResult& r) { return r.fy; }},
    {"mz", "N m", "spin moment on the wheel about the contact normal", [](const FastsimResult& r) { return r.mz; }},
    {"slip_fraction", "1", "slipping share of the contact area", [](const FastsimResult& r) { return r.slip_fraction; }},
};

// Normal contact of a creep point (creep part, format 1.2): with the load coupling (issue 14) the
// normal contact depends on the creepage, because the creep forces carry part of the vertical load.
const Output<ContactPatch> kCreepNormalOutputs[] = {
    {"normal_force", "N", "normal force along the contact normal at this creepage (load carried by normal and creep forces)",
     [](const ContactPatch& c) { return c.normal_force; }},
    {"approach", "m", "normal approach at the patch reference point at this creepage", [](const ContactPatch& c) { return c.penetration; }},
    {"area", "m2", "contact area at this creepage", [](const ContactPatch& c) { return c.area; }},
    {"max_pressure", "Pa", "maximum contact pressure at this creepage", [](const ContactPatch& c) { return c.max_pressure; }},
};

// Wear part, same grid as creep.
const Output<WearResult> kWearOutputs[] = {
    {"wear_rate", "m2/m", "worn wheel-profile cross-section per rolled distance (Archard, KTH map)",
     [](const WearResult& r) { return r.wear_rate; }},
};

template <class Result, std::size_t N>
PartSpec part_spec(const char* name, std::vector<std::string> inner_axes, const Output<Result> (&outputs)[N]) {
  PartSpec spec{name, std::move(inner_axes), {}};
  for (const Output<Result>& o : outputs) spec.outputs.push_back({o.name, o.units, o.description});
  return spec;
}

// The creep part: creep forces, then (with the load coupling) the normal contact at the creepage.
template <std::size_t N, std::size_t M>
PartSpec creep_part_spec(const Output<FastsimResult> (&creep)[N], const Output<ContactPatch> (&normal)[M],
                         bool coupled) {
  PartSpec spec = part_spec("creep", {"load", "xi", "eta", "phi"}, creep);
  if (coupled)
    for (const Output<ContactPatch>& o : normal) spec.outputs.push_back({o.name, o.units, o.description});
  return spec;
}

// One cell's outputs, written from output index `first` of the part. A NaN or inf in any of them
// writes zeros instead and a failure message naming the output, and returns false: the caller
// then marks the cell failed (non_finite_status), so a non-finite number is never `converged`
// (and the lookup refuses non-finite tables). `where` describes the cell (called only then).
template <class Result, std::size_t N, class Where>
bool store_values(const Output<Result> (&outputs)[N], const Result& result, ColumnOutput& out, std::size_t wheel,
                  std::size_t part, std::size_t cell, Where where, std::size_t first = 0) {
  double values[N];
  bool finite = true;
  for (std::size_t o = 0; o < N; ++o) {
    values[o] = outputs[o].get(result);
    finite = finite && std::isfinite(values[o]);
  }
  for (std::size_t o = 0; o < N; ++o) out.values(wheel, part, first + o)[cell] = finite ? values[o] : 0.0;
  if (!finite) {
    for (std::size_t o = 0; o < N; ++o) {
      if (!std::isfinite(values[o])) {
        out.failure(fmt::format("{}: {} = {} (not finite; stored as 0, status failed)", where(), outputs[o].name,
                                values[o]));
        break;
      }
    }
  }
  return finite;
}

// One cell's outputs and status (failed where an output is not finite).
template <class Result, std::size_t N, class Where>
void store(const Output<Result> (&outputs)[N], const Result& result, StatusBits bits, ColumnOutput& out,
           std::size_t wheel, std::size_t part, std::size_t cell, Where where) {
  const bool finite = store_values(outputs, result, out, wheel, part, cell, where);
  out.status(wheel, part)[cell] = finite ? bits : non_finite_status(bits);
}

constexpr std::size_t kGeometryPart = 0;
constexpr std::size_t kNormalPart = 1;
constexpr std::size_t kCreepPart = 2;
constexpr std::size_t kWearPart = 3;

// A point where the core threw: no values (zeros), and kFailed instead of kConverged.
StatusBits failure_status(const ColumnState& state) {
  bool bad_input = !std::isfinite(state.y) || !std::isfinite(state.roll);
  return status::kFailed | (bad_input ? status::kInvalidInput : 0u);
}

struct KernelData {
  ContactGeometrySolver solver;
  SceneGrids grids;           // load [N] and creepage grids
  Material material;
  NormalOptions normal;
  TangentialSettings tangential;
  CreepConditions creep;
  FastsimOptions fastsim;
  WearOptions wear;
  CoupledLoadOptions coupling;          // couple = false: the creep part has no normal outputs (format 1.0 layout)
  halfspace::HalfspaceOptions halfspace;  // normal model halfspace ([contact] element_size)
  std::vector<NormalModel> model_by_y;  // per node of the scene's y grid (planned model choice); empty = normal.model
  bool normalised = false;              // format 2.1 normalised creep coordinates (creep_map.hpp)
  std::size_t creepages() const { return grids.xi.size() * grids.eta.size() * grids.phi.size(); }
};

// The creepage of creep grid node (ix, ie, ip): the grid's values, or with normalised coordinates
// the physical creepage of the node's v at the slot's scales (an unswept axis keeps its value).
Creepage node_creepage(const KernelData& k, std::size_t ix, std::size_t ie, std::size_t ip,
                       const creep_map::Scales* scales) {
  const SceneGrids& g = k.grids;
  if (!k.normalised || !scales) return Creepage{g.xi[ix], g.eta[ie], g.phi[ip]};
  auto map = [](const std::vector<double>& axis, std::size_t i, double s) {
    if (axis.size() < 2) return axis.front();
    return creep_map::physical(creep_map::nodes(axis.size())[i], axis.front(), axis.back(), s);
  };
  return Creepage{map(g.xi, ix, scales->xi), map(g.eta, ie, scales->eta), map(g.phi, ip, scales->phi)};
}

// Format 2.1: the creep forces stored as F / (mu N) minus the saturation law at the node's
// normalised creepage, mz as mz / (mu N) [m] (creep_map.hpp); N is the creep point's own normal
// force. Zeros stay zeros (no load).
FastsimResult normalised_forces(const FastsimResult& r, const Creepage& c, double normal_force, double friction,
                                const creep_map::Scales& s) {
  FastsimResult out = r;
  if (!(normal_force > 0.0)) return out;
  const double mun = friction * normal_force;
  const std::array<double, 2> law = creep_map::law(c.xi / s.xi, c.eta / s.eta, c.phi / s.phi);
  out.fx = r.fx / mun - law[0];
  out.fy = r.fy / mun - law[1];
  out.mz = r.mz / mun;
  return out;
}

// The normal options at this column (the planned model choice per y node).
NormalOptions uncoupled_options(const KernelData& k, const ColumnState& state) {
  NormalOptions options = k.normal;
  if (!k.model_by_y.empty()) options.model = k.model_by_y[state.iy];
  return options;
}

// Creep forces and wear of one slot's loaded patches (summed, slot_creep) over the creepage grid,
// into the cells of load il. Without the load coupling.
void solve_creep(const KernelData& k, const WheelContactGeometry& geometry, const WheelNormalResult& normal,
                 const PatchSlots& slots, const ColumnState& state, std::size_t wheel, std::size_t il,
                 std::size_t slot, const creep_map::Scales* scales, ColumnOutput& out) {
  FastsimWorkspace& workspace = thread_fastsim_workspace();
  thread_local WearDistribution distribution;
  const StatusBits extra = slots.extra[slot];
  std::size_t c = il * k.creepages();
  const double slot_force = slot_normal(normal, slots, slot).normal_force;
  for (std::size_t ix = 0; ix < k.grids.xi.size(); ++ix) {
    for (std::size_t ie = 0; ie < k.grids.eta.size(); ++ie) {
      for (std::size_t ip = 0; ip < k.grids.phi.size(); ++ip) {
        const std::size_t cell = c++ * kSlots + slot;
        const Creepage creepage = node_creepage(k, ix, ie, ip, scales ? &scales[slot] : nullptr);
        const double xi = creepage.xi, eta = creepage.eta, phi = creepage.phi;
        try {
          SlotWear wear{k.wear, distribution, {}};
          FastsimResult creep = slot_creep(geometry, normal, slots, slot, creepage, k.creep,
                                           k.material, k.fastsim, workspace, &wear);
          if (scales) creep = normalised_forces(creep, creepage, slot_force, k.creep.friction, scales[slot]);
          auto where = [&] {
            return fmt::format("creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {})",
                               to_string(geometry.side), state.y, k.grids.load[il], xi, eta, phi);
          };
          store(kCreepOutputs, creep, creep.status | extra, out, wheel, kCreepPart, cell, where);
          store(kWearOutputs, wear.result, wear.result.status | extra, out, wheel, kWearPart, cell, where);
        } catch (const std::exception& e) {
          out.failure(fmt::format("creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {}): {}",
                                  to_string(geometry.side), state.y, k.grids.load[il], xi, eta, phi, e.what()));
          out.status(wheel, kCreepPart)[cell] = failure_status(state);
          out.status(wheel, kWearPart)[cell] = failure_status(state);
        }
      }
    }
  }
}

// With the load coupling (issue 14): per creepage the normal contact is re-solved so that normal
// and creep forces together carry the load (tangential/coupled_load.hpp), starting from the
// creepage-free solution `uncoupled` of load il; every loaded patch of the wheel gets the grid's
// creepage (the table has one creepage per slot, shared by the slots in two-point contact). Both
// slots' creep and wear cells and the creep part's normal outputs of that creepage are written.
void solve_creep_coupled(const KernelData& k, const WheelContactGeometry& geometry,
                         const WheelNormalResult& uncoupled, const PatchSlots& uncoupled_slots,
                         const ColumnState& state, std::size_t wheel, std::size_t il,
                         const creep_map::Scales* scales, ColumnOutput& out) {
  FastsimWorkspace& workspace = thread_fastsim_workspace();
  thread_local WearDistribution distribution;
  thread_local CoupledLoadResult coupled;
  const double load = k.grids.load[il];
  const double flange_angle = k.solver.settings().flange_angle;
  // Physical coordinates: one coupled solve per creepage gives both slots. Normalised ones
  // (format 2.1): each slot's node is its own creepage (its own scales), so one coupled solve per
  // slot, keeping that slot's outputs; a slot without a creepage-free patch gets status 0.
  const bool per_slot = scales != nullptr;
  for (std::size_t pass = 0; pass < (per_slot ? kSlots : 1); ++pass) {
  if (per_slot && !uncoupled_slots.occupied(pass)) continue;  // status 0, zeros: no contact
  std::size_t c = il * k.creepages();
  for (std::size_t ix = 0; ix < k.grids.xi.size(); ++ix) {
    for (std::size_t ie = 0; ie < k.grids.eta.size(); ++ie) {
      for (std::size_t ip = 0; ip < k.grids.phi.size(); ++ip) {
        const std::size_t cells = c++ * kSlots;
        const Creepage creepage = node_creepage(k, ix, ie, ip, per_slot ? &scales[pass] : nullptr);
        const double xi = creepage.xi, eta = creepage.eta, phi = creepage.phi;
        try {
          solve_coupled_load(geometry, load, uncoupled, k.material, uncoupled_options(k, state),
                             fastsim_tangential(geometry, [&](std::size_t, const ContactPatch&) { return creepage; },
                                                k.creep, k.material, k.fastsim, workspace),
                             k.coupling, coupled);
          const StatusBits not_converged = (coupled.normal.status | coupled.status) & status::kNotConverged;
          const PatchSlots slots = assign_patch_slots(coupled.normal, geometry.side, flange_angle);
          for (std::size_t s = per_slot ? pass : 0; s < (per_slot ? pass + 1 : kSlots); ++s) {
            const std::size_t cell = cells + s;
            if (!slots.occupied(s)) {
              // No patch here at this creepage: zeros; status 0 (no contact) as in the normal part,
              // or converged,lift_off where the creepage-free solution had one (lifted by the coupling).
              const StatusBits bits = uncoupled_slots.occupied(s) ? status::kConverged | status::kLiftOff : 0u;
              out.status(wheel, kCreepPart)[cell] = bits;
              out.status(wheel, kWearPart)[cell] = bits;
              continue;
            }
            auto where = [&] {
              return fmt::format("coupled creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {})",
                                 to_string(geometry.side), state.y, load, xi, eta, phi);
            };
            const ContactPatch patch = slot_normal(coupled.normal, slots, s);
            const bool normal_finite =
                store_values(kCreepNormalOutputs, patch, out, wheel, kCreepPart, cell, where, std::size(kCreepOutputs));
            SlotWear wear{k.wear, distribution, {}};
            // One patch on the wheel: the coupled solve's last FASTSIM solve was this patch at this
            // creepage and is still in the workspace, so its result and wear are slot_creep's
            // without solving it again (the same bytes; one FASTSIM solve of 3-4 per point saved).
            const bool reuse = coupled.normal.patches.size() == 1 && coupled.creep.size() == 1 &&
                               coupled.normal.patches[0].normal_force > 0.0;
            if (reuse) wear.result = archard_wear(workspace, k.wear, distribution);
            FastsimResult creep =
                reuse ? coupled.creep[0]
                      : slot_creep(geometry, coupled.normal, slots, s, creepage, k.creep, k.material, k.fastsim,
                                   workspace, &wear);
            if (per_slot) creep = normalised_forces(creep, creepage, patch.normal_force, k.creep.friction, scales[s]);
            const bool creep_finite = store_values(kCreepOutputs, creep, out, wheel, kCreepPart, cell, where);
            // Status: the creep forces' bits as without the coupling, plus not_converged when the
            // coupled solve (or a normal solve in it) missed its tolerance; failed if not finite.
            const StatusBits creep_bits =
                (not_converged ? creep.status & ~status::kConverged : creep.status) | slots.extra[s] | not_converged;
            out.status(wheel, kCreepPart)[cell] =
                normal_finite && creep_finite ? creep_bits : non_finite_status(creep_bits);
            store(kWearOutputs, wear.result, wear.result.status | slots.extra[s], out, wheel, kWearPart, cell, where);
          }
        } catch (const std::exception& e) {
          out.failure(fmt::format("coupled normal/creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {}): {}",
                                  to_string(geometry.side), state.y, load, xi, eta, phi, e.what()));
          for (std::size_t s = per_slot ? pass : 0; s < (per_slot ? pass + 1 : kSlots); ++s) {
            out.status(wheel, kCreepPart)[cells + s] = failure_status(state);
            out.status(wheel, kWearPart)[cells + s] = failure_status(state);
          }
        }
      }
    }
  }
  }
}

// The exact half-space model: per creepage the steady rolling solution of every patch of the wheel
// (one creepage for all, as solve_creep_coupled), both slots' creep and wear cells of load il.
// With the load coupling (scene load_coupling, the same meaning as for the fast models: the creep
// forces carry their share of the vertical load) solve_halfspace_rolling re-solves the normal
// contact per creepage, from cold (the same call as railtab eval, so a node is reproduced exactly;
// a warm start from the previous creepage through the public calls was measured slower: 82 s
// against 70 s CPU on 3 columns of the default grid), and the creep part's normal outputs are
// written. Without it the tangential problem runs on `uncoupled` (the load's normal solution),
// each creepage warm-started from the previous one of the sweep; the creepage order is fixed and
// a column is computed by one thread, so the bytes do not depend on the thread count.
void solve_creep_halfspace(const KernelData& k, const WheelContactGeometry& geometry,
                           const halfspace::WheelHalfspaceResult& uncoupled, const PatchSlots& uncoupled_slots,
                           const ColumnState& state, std::size_t wheel, std::size_t il, ColumnOutput& out) {
  halfspace::Workspace& workspace = thread_halfspace_workspace();
  thread_local std::vector<double> depth;
  thread_local WearDistribution distribution;  // unused by the exact model's wear (SlotWear needs one)
  const double load = k.grids.load[il];
  const double mu = k.creep.friction;
  const double flange_angle = k.solver.settings().flange_angle;
  halfspace::WheelHalfspaceResult result = uncoupled;  // holds the warm start without the coupling
  std::size_t c = il * k.creepages();
  for (double xi : k.grids.xi) {
    for (double eta : k.grids.eta) {
      for (double phi : k.grids.phi) {
        const std::size_t cells = c++ * kSlots;
        const Creepage creepage{xi, eta, phi};
        try {
          if (k.coupling.couple) {
            result = halfspace::solve_halfspace_rolling(geometry, load, creepage, mu, k.material, k.halfspace, workspace);
          } else {
            halfspace::solve_halfspace_tangential(result, creepage, mu, k.material, k.halfspace, workspace);
          }
          const WheelNormalResult normal = to_normal_result(result, geometry);
          const PatchSlots slots =
              k.coupling.couple ? assign_patch_slots(normal, geometry.side, flange_angle) : uncoupled_slots;
          for (std::size_t s = 0; s < kSlots; ++s) {
            const std::size_t cell = cells + s;
            const ContactPatch patch = slots.occupied(s) ? slot_normal(normal, slots, s) : ContactPatch{};
            if (!(patch.normal_force > 0.0)) {
              // No loaded patch here: zeros; status 0 where the creepage-free solution had none, else
              // converged,lift_off (as solve_creep and solve_creep_coupled).
              const StatusBits bits = uncoupled_slots.occupied(s) ? status::kConverged | status::kLiftOff : 0u;
              out.status(wheel, kCreepPart)[cell] = bits | (bits ? uncoupled_slots.extra[s] : 0u);
              out.status(wheel, kWearPart)[cell] = bits | (bits ? uncoupled_slots.extra[s] : 0u);
              continue;
            }
            auto where = [&] {
              return fmt::format("half-space creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {})",
                                 to_string(geometry.side), state.y, load, xi, eta, phi);
            };
            bool normal_finite = true;
            if (k.coupling.couple)
              normal_finite = store_values(kCreepNormalOutputs, patch, out, wheel, kCreepPart, cell, where,
                                           std::size(kCreepOutputs));
            SlotWear wear{k.wear, distribution, {}};
            const FastsimResult creep = sum_slot_creep(
                normal, slots, s,
                [&](std::size_t ip, WearResult* worn) {
                  const halfspace::HalfspacePatch& hp = result.patches[ip];
                  if (worn) *worn = halfspace_wear(hp, k.creep.speed, k.wear, depth);
                  return to_creep_result(hp);
                },
                &wear);
            const bool creep_finite = store_values(kCreepOutputs, creep, out, wheel, kCreepPart, cell, where);
            // The patch bits (area_too_small, not_planar, the coupled solve's not_converged) and the
            // tangential solver's (full_slip, not_converged).
            StatusBits bits = creep.status | (patch.status & ~status::kConverged) | slots.extra[s];
            if (bits & status::kNotConverged) bits &= ~status::kConverged;
            out.status(wheel, kCreepPart)[cell] = normal_finite && creep_finite ? bits : non_finite_status(bits);
            store(kWearOutputs, wear.result, wear.result.status | slots.extra[s], out, wheel, kWearPart, cell, where);
          }
        } catch (const std::exception& e) {
          out.failure(fmt::format("half-space creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {}): {}",
                                  to_string(geometry.side), state.y, load, xi, eta, phi, e.what()));
          for (std::size_t s = 0; s < kSlots; ++s) {
            out.status(wheel, kCreepPart)[cells + s] = failure_status(state);
            out.status(wheel, kWearPart)[cells + s] = failure_status(state);
          }
        }
      }
    }
  }
}

// Every cell of a part for load il (or all loads) gets the failure status.
void fail_cells(ColumnOutput& out, std::size_t wheel, std::size_t part, std::size_t begin, std::size_t end,
                StatusBits bits) {
  for (std::size_t c = begin; c < end; ++c) out.status(wheel, part)[c] = bits;
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

void solve_wheel_column(const KernelData& k, const ColumnState& state, std::size_t wheel, ColumnOutput& out) {
  const Side side = wheel == 0 ? Side::left : Side::right;
  const std::size_t nload = k.grids.load.size();
  const std::size_t ncreep = nload * k.creepages() * kSlots;  // creep/wear cells of the column
  WheelContactGeometry geometry;
  try {
    geometry = k.solver.solve_wheel(side, WheelsetState{state.y, state.roll});
  } catch (const std::exception& e) {
    out.failure(fmt::format("geometry, {} wheel, y = {} m, roll = {} rad: {}", to_string(side), state.y,
                            state.roll, e.what()));
    fail_cells(out, wheel, kGeometryPart, 0, kSlots, failure_status(state));
    fail_cells(out, wheel, kNormalPart, 0, nload * kSlots, failure_status(state));
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
      const std::size_t per_load = k.creepages() * kSlots;
      fail_cells(out, wheel, kCreepPart, il * per_load, (il + 1) * per_load, failure_status(state));
      fail_cells(out, wheel, kWearPart, il * per_load, (il + 1) * per_load, failure_status(state));
      continue;
    }
    const StatusBits solver_bits = normal.status & (status::kConverged | status::kNotConverged);
    const PatchSlots patch_slots = assign_patch_slots(normal, side, k.solver.settings().flange_angle);
    // Format 2.1: the saturation scales of each slot's creepage-free contact; an empty slot takes
    // the other slot's (or nominal ones), so that cells next to it map creepages sensibly.
    creep_map::Scales scales[kSlots];
    if (k.normalised) {
      for (std::size_t s = 0; s < kSlots; ++s)
        if (patch_slots.occupied(s)) scales[s] = slot_scales(k, geometry, normal, patch_slots, s);
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
      }
      if (normal.patches.empty() || k.creepages() == 0) continue;
      if (exact)
        solve_creep_halfspace(k, geometry, exact_result, patch_slots, state, wheel, il, out);
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

SweepKernel make_contact_kernel(const Scene& scene) {
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
  auto data = std::make_shared<const KernelData>(KernelData{make_geometry_solver(scene), scene.grids, scene.material,
                                                            scene.normal, scene.tangential, creep, fastsim, wear,
                                                            coupled_load_options(scene), halfspace_options(scene),
                                                            model_by_y, scene.creep_normalised});
  SweepKernel kernel;
  kernel.parts.push_back(part_spec("geometry", {}, kGeometryOutputs));
  kernel.parts.push_back(part_spec("normal", {"load"}, kNormalOutputs));
  if (scene.creep_normalised)
    for (const OutputInfo& o : kCreepScaleOutputs) kernel.parts.back().outputs.push_back(o);
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
  kernel.equilibrium_roll = [data](double y) { return data->solver.equilibrium_roll(y); };
  kernel.compute = [data](const ColumnState& state, ColumnOutput& out) {
    for (std::size_t wheel = 0; wheel < 2; ++wheel) solve_wheel_column(*data, state, wheel, out);
  };
  return kernel;
}

}  // namespace railtab
