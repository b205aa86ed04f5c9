// SPDX-License-Identifier: Apache-2.0
// Normalised creep coordinates of format 2.1 (docs/table-format.md, "Normalised creep part"):
// the creep and wear parts of a scene with `[grid] creep_coordinates = "normalised"` are
// tabulated over v = (v_xi, v_eta, v_phi) in [-1, 1]^3 instead of the physical creepages, per
// (y, roll, load) node and slot, and the creep forces are stored as F / (mu N) minus a
// saturation law, so that few nodes follow the saturating creep curve.
//
// Per node and slot the normal contact (creepage-free) gives the saturation scales
//   s_xi = 3 mu N / (G c^2 C11),  s_eta = 3 mu N / (G c^2 C22),  s_phi = mu N / (G c^3 C23),
// c^2 = area / pi (= ab for an ellipse), C_ij Kalker's coefficients at the patch's a/b (Hertz and
// Kik-Piotrowski patches: their semi-axes; strip patches: b = half the lateral extent, a from the
// area), so the normalised creepages xi' = xi / s_xi (Kalker's xi' = G c^2 C11 xi / (3 mu N)),
// eta', psi' are ~1 where the creep force saturates. The sweep (contact_kernel.cpp,
// slot_scales) replaces G c^2 C11 etc. by the model's own linear creep coefficients (FASTSIM's
// slopes, the same for a Hertz patch; for the exact half-space model its own steady rolling
// solution in full adhesion, exact_slot_scales), which line up with the bend of strip patches too. Each axis maps its scene range [lo, hi]:
//   m(x) = x / (1 + |x|),  v = -1 + 2 (m(q / s) - m(lo / s)) / (m(hi / s) - m(lo / s)),
// so v = -1 and 1 are the scene's physical limits at every node (out of range means what it
// meant before) and the nodes, uniform in v, are dense where the force bends (|xi'| < 1) and
// sparse in saturation. The lookup has the same functions (lookup/src/creep_map.hpp); test
// CreepMap.GeneratorAndLookupAgree checks that both give the same numbers.
#pragma once

#include <array>
#include <vector>

#include "core/material.hpp"
#include "normal/normal_model.hpp"

namespace railtab::creep_map {

// Scales [xi: 1, eta: 1, phi: rad/m] of one slot's (creepage-free) normal contact.
struct Scales {
  double xi = 1.0, eta = 1.0, phi = 1.0;
};
// `patch` is the slot's summed patch (slot_normal); throws nothing: a patch without area or
// force gives the nominal scales kNominal (an empty slot).
Scales scales(const ContactPatch& patch, const Material& material, double friction);
inline constexpr Scales kNominal{1e-3, 1e-3, 1.0};

// The physical creepage of coordinate v on [lo, hi] at scale s (inverse of coordinate()).
double physical(double v, double lo, double hi, double s);
// The coordinate v in [-1, 1] of physical creepage q in [lo, hi] at scale s.
double coordinate(double q, double lo, double hi, double s);

// The saturation law subtracted from F / (mu N): with x = xi', y = eta' + psi' / 3 (Kalker's
// linear theory: F / (mu N) = -(3 xi', 3 eta' + psi') for small creepage, forces on the wheel),
// r = |(x, y, spin psi')|, g = 1 - (1 - min(r, 1))^3: law = -g (x, y) / r. With spin = 0 (every
// table before the `law_spin` key) exact for FASTSIM on an ellipse under pure longitudinal or
// lateral creepage with a parabolic bound. spin > 0 (`[grid] creep_law_spin`) lets spin use up
// adhesion without a force of its own: in the exact model fx falls with |phi| at constant xi,
// about quadratically, which linear interpolation between few phi nodes misses; the small-creepage
// slope stays Kalker's. The table holds the rest.
std::array<double, 2> law(double xi_n, double eta_n, double psi_n, double spin);

// The slot's vertical load share N cos(angle) + fy sin(angle) [N] (angle: the geometry part's
// contact angle of the slot, track frame) that normalised tables store as the creep part's
// normal_force (creep_map "normal_force": "vertical_share"), and N back from it given
// fy / (mu N) = r_y: N = share / (cos(angle) + mu r_y sin(angle)). The lookup has the inverse
// (lookup/src/creep_map.hpp, normal_from_share).
double vertical_share(double normal_force, double fy, double angle);

// The file's nodes of one normalised axis: `count` values uniform in [-1, 1].
std::vector<double> nodes(std::size_t count);

}  // namespace railtab::creep_map
