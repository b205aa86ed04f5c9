// SPDX-License-Identifier: Apache-2.0
// The contact kernel's creep and wear loops over the creepage grid of one wheel and load: FASTSIM
// without and with the load coupling, and the exact half-space model.
#include "kernel/creep_loops.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <exception>
#include <vector>

#include "kernel/halfspace_contact.hpp"
#include "kernel/kernel_cells.hpp"

namespace railtab::kernel {
namespace {

// The geometry part's contact angle of each slot (0 for an empty slot): the angle of the slot's
// vertical load share in normalised tables (creep_map::vertical_share).
std::array<double, kSlots> slot_contact_angles(const WheelContactGeometry& geometry) {
  std::array<double, kSlots> out{};
  const SlotAssignment points = assign_slots(geometry);
  for (std::size_t s = 0; s < kSlots; ++s)
    if (points.point[s] >= 0) out[s] = geometry.points[static_cast<std::size_t>(points.point[s])].contact_angle;
  return out;
}

// Normalised coordinates solve the wheel once per slot the creepage-free contact occupies (at
// that slot's creepages, keeping that slot's cells). With the creepage the coupled load can move a
// patch across the slots' boundary angle (the tread-flange hand-over at about 5.59 mm: the patch
// stays on the tread side where the creepage-free one has passed to the flange), into a slot that
// no pass solves: that slot's cells would hold nothing and the wheel's sum over the slots would
// lose the patch. So `solved`'s patches in a slot the creepage-free contact leaves empty join slot
// `pass`, two at most (the larger normal forces, as assign_patch_slots keeps them).
PatchSlots keep_moved_patches(const WheelNormalResult& normal, const PatchSlots& solved, const PatchSlots& uncoupled,
                              std::size_t pass) {
  const std::size_t other = 1 - pass;
  if (uncoupled.occupied(other) || !solved.occupied(other)) return solved;
  PatchSlots kept = solved;
  std::vector<int> patches;
  for (std::size_t s : {pass, other})
    for (int ip : solved.patch[s])
      if (ip >= 0) patches.push_back(ip);
  std::stable_sort(patches.begin(), patches.end(), [&](int a, int b) {
    return normal.patches[static_cast<std::size_t>(a)].normal_force >
           normal.patches[static_cast<std::size_t>(b)].normal_force;
  });
  for (std::size_t k = 0; k < kPatchesPerSlot; ++k) kept.patch[pass][k] = k < patches.size() ? patches[k] : -1;
  kept.patch[other][0] = kept.patch[other][1] = -1;
  kept.dropped[pass] = solved.dropped[pass] + solved.dropped[other] +
                       static_cast<int>(patches.size() > kPatchesPerSlot ? patches.size() - kPatchesPerSlot : 0);
  kept.extra[pass] = solved.extra[pass] | solved.extra[other] | (patches.size() > 1 ? status::kTwoPoint : 0u);
  kept.extra[other] = 0;
  return kept;
}

}  // namespace

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
          if (scales) creep = normalised_forces(creep, creepage, slot_force, k.creep.friction, scales[slot], k.law_spin);
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

// With the load coupling: per creepage the normal contact is re-solved so that normal
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
  // Normalised tables: the creep part's normal_force holds the slot's vertical load share
  // N cos(delta) + Fy sin(delta), delta the geometry part's contact angle of the slot (0 for an
  // empty geometry slot), which stays nearly constant over the creepages where N itself does not
  // (flange: Fy carries load; creep_map.hpp, vertical_share). The lookup recovers N from it.
  const std::array<double, kSlots> slot_angle = per_slot ? slot_contact_angles(geometry) : std::array<double, kSlots>{};
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
              // or converged,lift_off where the creepage-free solution had one (lifted by the
              // coupling).
              const StatusBits bits = uncoupled_slots.occupied(s) ? status::kConverged | status::kLiftOff : 0u;
              out.status(wheel, kCreepPart)[cell] = bits;
              out.status(wheel, kWearPart)[cell] = bits;
              continue;
            }
            auto where = [&] {
              return fmt::format("coupled creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {})",
                                 to_string(geometry.side), state.y, load, xi, eta, phi);
            };
            ContactPatch patch = slot_normal(coupled.normal, slots, s);
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
            const double n = patch.normal_force;
            if (per_slot) {
              patch.normal_force = creep_map::vertical_share(n, creep.fy, slot_angle[s]);
              creep = normalised_forces(creep, creepage, n, k.creep.friction, scales[s], k.law_spin);
            }
            const bool normal_finite =
                store_values(kCreepNormalOutputs, patch, out, wheel, kCreepPart, cell, where, std::size(kCreepOutputs));
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
// contact per creepage, each solve warm-started from the previous creepage of creepage_chain
// (halfspace::RollingState: its grid, pressure and load split), and the creep part's
// normal outputs are written. A node is then the cold solve of railtab eval to within the
// solvers' tolerances, not to the byte. With normalised coordinates (`scales`) one chain per
// occupied slot at that slot's creepages, as solve_creep_coupled; a patch the creepage moves into
// a slot the creepage-free contact leaves empty stays in the solved slot (keep_moved_patches), so
// the sum over the slots keeps every loaded patch. Without the coupling the tangential problem runs on
// `uncoupled` (the load's normal solution), each creepage warm-started from the previous one.
// The creepage order is fixed and a column is computed by one thread, so the bytes do not depend
// on the thread count.
void solve_creep_halfspace(const KernelData& k, const WheelContactGeometry& geometry,
                           const halfspace::WheelHalfspaceResult& uncoupled, const PatchSlots& uncoupled_slots,
                           const ColumnState& state, std::size_t wheel, std::size_t il,
                           const creep_map::Scales* scales, ColumnOutput& out) {
  halfspace::Workspace& workspace = thread_halfspace_workspace();
  thread_local std::vector<double> depth;
  thread_local WearDistribution distribution;  // unused by the exact model's wear (SlotWear needs one)
  const double load = k.grids.load[il];
  const double mu = k.creep.friction;
  const double flange_angle = k.solver.settings().flange_angle;
  // Normalised coordinates: each slot's node is its own creepage (its own scales), so one chain of
  // solves per occupied slot, keeping that slot's outputs (as solve_creep_coupled); the creep
  // part's normal_force is then the slot's vertical load share (creep_map::vertical_share).
  const bool per_slot = scales != nullptr;
  const std::array<double, kSlots> slot_angle = per_slot ? slot_contact_angles(geometry) : std::array<double, kSlots>{};
  const std::size_t ne = k.grids.eta.size(), np = k.grids.phi.size();
  for (std::size_t pass = 0; pass < (per_slot ? kSlots : 1); ++pass) {
    if (per_slot && !uncoupled_slots.occupied(pass)) continue;  // status 0, zeros: no contact
    halfspace::WheelHalfspaceResult result = uncoupled;  // holds the warm start without the coupling
    halfspace::RollingState chain;  // the coupled solves' warm start: the previous creepage's end
    for (std::size_t node : creepage_chain(k.grids.xi.size(), ne, np)) {
      // The right wheel walks the chain mirrored in eta and phi: its patch is the left wheel's
      // mirror image (halfspace/wheel_rail.hpp), so at mirrored states both wheels solve the same
      // sequence of warm-started problems, to the same bytes (engine/mirror.hpp).
      if (geometry.side == Side::right) node = (node / (ne * np) * ne + ne - 1 - node / np % ne) * np + np - 1 - node % np;
      const std::size_t ix = node / (ne * np), ie = node / np % ne, iphi = node % np;
      const std::size_t cells = (il * k.creepages() + node) * kSlots;
      const Creepage creepage = node_creepage(k, ix, ie, iphi, per_slot ? &scales[pass] : nullptr);
      const double xi = creepage.xi, eta = creepage.eta, phi = creepage.phi;
      const std::size_t s_begin = per_slot ? pass : 0, s_end = per_slot ? pass + 1 : kSlots;
      try {
        if (k.coupling.couple) {
          result = halfspace::solve_halfspace_rolling(geometry, load, creepage, mu, k.material, k.halfspace, workspace,
                                                      &chain);
        } else {
          halfspace::solve_halfspace_tangential(result, creepage, mu, k.material, k.halfspace, workspace);
        }
        const WheelNormalResult normal = to_normal_result(result, geometry);
        PatchSlots slots = k.coupling.couple ? assign_patch_slots(normal, geometry.side, flange_angle) : uncoupled_slots;
        if (per_slot) slots = keep_moved_patches(normal, slots, uncoupled_slots, pass);
        for (std::size_t s = s_begin; s < s_end; ++s) {
          const std::size_t cell = cells + s;
          ContactPatch patch = slots.occupied(s) ? slot_normal(normal, slots, s) : ContactPatch{};
          if (!(patch.normal_force > 0.0)) {
            // No loaded patch here: zeros; status 0 where the creepage-free solution had none,
            // else converged,lift_off (as solve_creep and solve_creep_coupled).
            const StatusBits bits = uncoupled_slots.occupied(s) ? status::kConverged | status::kLiftOff : 0u;
            out.status(wheel, kCreepPart)[cell] = bits | (bits ? uncoupled_slots.extra[s] : 0u);
            out.status(wheel, kWearPart)[cell] = bits | (bits ? uncoupled_slots.extra[s] : 0u);
            continue;
          }
          auto where = [&] {
            return fmt::format("half-space creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {})",
                               to_string(geometry.side), state.y, load, xi, eta, phi);
          };
          SlotWear wear{k.wear, distribution, {}};
          FastsimResult creep = sum_slot_creep(
              normal, slots, s,
              [&](std::size_t ip, WearResult* worn) {
                const halfspace::HalfspacePatch& hp = result.patches[ip];
                if (worn) *worn = halfspace_wear(hp, k.creep.speed, k.wear, depth);
                return to_creep_result(hp);
              },
              &wear);
          if (per_slot) {
            const double n = patch.normal_force;
            patch.normal_force = creep_map::vertical_share(n, creep.fy, slot_angle[s]);
            creep = normalised_forces(creep, creepage, n, mu, scales[s], k.law_spin);
          }
          bool normal_finite = true;
          if (k.coupling.couple)
            normal_finite = store_values(kCreepNormalOutputs, patch, out, wheel, kCreepPart, cell, where,
                                         std::size(kCreepOutputs));
          const bool creep_finite = store_values(kCreepOutputs, creep, out, wheel, kCreepPart, cell, where);
          // The patch bits (area_too_small, not_planar, the coupled solve's not_converged) and
          // the tangential solver's (full_slip, not_converged).
          StatusBits bits = creep.status | (patch.status & ~status::kConverged) | slots.extra[s];
          if (bits & status::kNotConverged) bits &= ~status::kConverged;
          out.status(wheel, kCreepPart)[cell] = normal_finite && creep_finite ? bits : non_finite_status(bits);
          store(kWearOutputs, wear.result, wear.result.status | slots.extra[s], out, wheel, kWearPart, cell, where);
        }
      } catch (const std::exception& e) {
        out.failure(fmt::format("half-space creep/wear, {} wheel, y = {} m, load = {} N, creepage ({}, {}, {}): {}",
                                to_string(geometry.side), state.y, load, xi, eta, phi, e.what()));
        for (std::size_t s = s_begin; s < s_end; ++s) {
          out.status(wheel, kCreepPart)[cells + s] = failure_status(state);
          out.status(wheel, kWearPart)[cells + s] = failure_status(state);
        }
        chain.clear();  // the next creepage starts cold
      }
    }
  }
}

std::vector<std::size_t> creepage_chain(std::size_t nxi, std::size_t neta, std::size_t nphi) {
  std::vector<std::size_t> order;
  order.reserve(nxi * neta * nphi);
  for (std::size_t ix = 0; ix < nxi; ++ix)
    for (std::size_t a = 0; a < neta; ++a) {
      const std::size_t ie = ix % 2 == 0 ? a : neta - 1 - a;  // back along eta on odd xi rows
      for (std::size_t b = 0; b < nphi; ++b) {
        const std::size_t ip = (ix * neta + a) % 2 == 0 ? b : nphi - 1 - b;  // and along phi
        order.push_back((ix * neta + ie) * nphi + ip);
      }
    }
  return order;
}

}  // namespace railtab::kernel
