// SPDX-License-Identifier: Apache-2.0
// Linear creep coefficients of a model by central differences in full adhesion, and Kalker's on
// an equivalent ellipse (linear_creep.hpp).
#include "tangential/linear_creep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/check.hpp"
#include "tangential/kalker_coefficients.hpp"

namespace railtab {

LinearCreep linear_creep(const CreepForces& forces, const std::array<double, 3>& step) {
  LinearCreep out;
  for (int c = 0; c < 3; ++c) {
    RAILTAB_CHECK(step[c] > 0.0 && std::isfinite(step[c]), "linear_creep: step {} of creepage {} must be > 0",
                  step[c], c);
    Creepage plus, minus;
    double* p[] = {&plus.xi, &plus.eta, &plus.phi};
    double* m[] = {&minus.xi, &minus.eta, &minus.phi};
    *p[c] = step[c];
    *m[c] = -step[c];
    const std::array<double, 3> fp = forces(plus), fm = forces(minus);
    for (int f = 0; f < 3; ++f) out.slope[f][c] = (fp[f] - fm[f]) / (2.0 * step[c]);
  }
  return out;
}

LinearCreep kalker_linear_creep(double a, double b, const Material& material) {
  RAILTAB_CHECK(a > 0.0 && b > 0.0, "kalker_linear_creep: semi-axes a = {} m, b = {} m must be > 0", a, b);
  const KalkerCoefficients k = kalker_coefficients(a / b, material.poisson_ratio);
  const double g = material.shear_modulus(), c2 = a * b, c = std::sqrt(c2);
  LinearCreep out;
  out.slope[0][0] = -g * c2 * k.c11;
  out.slope[1][1] = -g * c2 * k.c22;
  out.slope[1][2] = -g * c2 * c * k.c23;
  out.slope[2][1] = g * c2 * c * k.c23;
  return out;
}

std::array<double, 2> equivalent_ellipse(const ContactPatch& patch) {
  if (!(patch.area > 0.0)) return {0.0, 0.0};
  if (patch.semi_axis_a > 0.0 && patch.semi_axis_b > 0.0) return {patch.semi_axis_a, patch.semi_axis_b};
  double lo = 0.0, hi = 0.0;
  bool any = false;
  for (const Strip& s : patch.strips) {
    if (!(s.x_lead > s.x_trail)) continue;
    const double l = s.s - 0.5 * s.width, h = s.s + 0.5 * s.width;
    lo = any ? std::min(lo, l) : l;
    hi = any ? std::max(hi, h) : h;
    any = true;
  }
  if (!any || !(hi > lo)) return {0.0, 0.0};
  const double b = 0.5 * (hi - lo);
  return {patch.area / (std::numbers::pi * b), b};
}

LinearCreep fastsim_linear_creep(const WheelContactGeometry& geometry, const ContactPatch& patch,
                                 const CreepConditions& conditions, const Material& material,
                                 const FastsimOptions& options, FastsimWorkspace& workspace) {
  CreepConditions adhesion = conditions;
  adhesion.friction = kFullAdhesionFriction;
  const CreepForces forces = [&](const Creepage& c) -> std::array<double, 3> {
    const FastsimResult r = fastsim_contact(geometry, patch, c, adhesion, material, options, workspace);
    return {r.fx, r.fy, r.mz};
  };
  // Linear in full adhesion: the steps only need to stay far above rounding.
  return linear_creep(forces, {1e-6, 1e-6, 1e-4});
}

}  // namespace railtab
