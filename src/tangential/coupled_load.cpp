// SPDX-License-Identifier: Apache-2.0
// Coupled load control: secant on the vertical approach until normal plus tangential vertical
// force equals the prescribed load (coupled_load.hpp).
#include "tangential/coupled_load.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace railtab {

TangentialSolver fastsim_tangential(const WheelContactGeometry& geometry, PatchCreepage creepage,
                                    const CreepConditions& conditions, const Material& material,
                                    const FastsimOptions& options, FastsimWorkspace& workspace) {
  return [&geometry, creepage = std::move(creepage), &conditions, &material, &options, &workspace](
             const WheelNormalResult& normal, std::vector<FastsimResult>& per_patch) {
    per_patch.resize(normal.patches.size());
    for (std::size_t i = 0; i < normal.patches.size(); ++i) {
      const ContactPatch& patch = normal.patches[i];
      per_patch[i] = fastsim_contact(geometry, patch, creepage(i, patch), conditions, material,
                                     options, workspace);
    }
  };
}

double tangential_vertical_force(const WheelNormalResult& normal,
                                 const std::vector<FastsimResult>& creep) {
  double total = 0.0;
  const std::size_t n = std::min(normal.patches.size(), creep.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!(normal.patches[i].normal_force > 0.0)) continue;
    // s = (0, cos g, sin g) in track axes: fy along s has the vertical component fy sin g.
    total += creep[i].fy * std::sin(normal.patches[i].contact_angle);
  }
  return total;
}

namespace {

// The balance in a variable nearly linear in the approach (Hertz: V ~ delta^(3/2)).
double balance_variable(double vertical, double load) {
  return std::copysign(std::cbrt(vertical * vertical), vertical) - std::cbrt(load * load);
}

}  // namespace

void solve_coupled_load(const WheelContactGeometry& geometry, double load,
                        const WheelNormalResult& uncoupled, const Material& material,
                        const NormalOptions& normal_options, const TangentialSolver& tangential,
                        const CoupledLoadOptions& options, CoupledLoadResult& out) {
  out.normal = uncoupled;
  out.iterations = 0;
  auto evaluate_forces = [&]() {
    tangential(out.normal, out.creep);
    out.normal_vertical = out.normal.carried_load;
    out.tangential_vertical = tangential_vertical_force(out.normal, out.creep);
    return out.normal_vertical + out.tangential_vertical;
  };
  double v1 = evaluate_forces();
  out.status = status::kConverged;
  const bool loaded = std::isfinite(load) && load > 0.0 &&
                      !out.normal.patches.empty() && out.normal.vertical_approach > 0.0;
  if (!options.couple || !loaded) return;
  const double f_tol = options.tolerance * load;
  if (std::abs(v1 - load) <= f_tol) return;

  double h_min = std::numeric_limits<double>::infinity();
  for (const ContactPoint& p : geometry.points) h_min = std::min(h_min, std::max(p.separation, 0.0));
  if (!std::isfinite(h_min)) h_min = 0.0;

  double x1 = out.normal.vertical_approach;
  double g1 = balance_variable(v1, load);
  // Second point: the normal load the balance asks for if the creep forces' share scales with the
  // normal load (as near saturation: Wn (1 + T0/Wn0) = Q), reached as Hertz would (delta ~ W^(2/3)).
  const double share = out.tangential_vertical / std::max(out.normal_vertical, 1e-300);
  const double wanted = load / std::max(1.0 + share, 0.05);
  const double ratio = std::clamp(wanted / std::max(out.normal_vertical, 1e-300), 0.05, 20.0);
  double x0 = x1, g0 = g1;
  double next = h_min + (x1 - h_min) * std::cbrt(ratio * ratio);
  double lo = h_min, hi = std::numeric_limits<double>::infinity();  // bracket: g(lo) < 0 < g(hi)
  (g1 < 0.0 ? lo : hi) = x1;

  for (int it = 0; it < options.max_iterations; ++it) {
    x0 = x1;
    g0 = g1;
    x1 = next;
    solve_normal_for_approach(geometry, x1, material, normal_options, out.normal);
    ++out.iterations;
    v1 = evaluate_forces();
    if (std::abs(v1 - load) <= f_tol) return;
    g1 = balance_variable(v1, load);
    (g1 < 0.0 ? lo : hi) = g1 < 0.0 ? std::max(lo, x1) : std::min(hi, x1);
    next = x1 - g1 * (x1 - x0) / (g1 - g0);
    if (!std::isfinite(next) || !(next > lo) || !(next < hi)) {
      // Secant left the bracket: bisect it, or step outward until it closes.
      next = std::isfinite(hi) ? 0.5 * (lo + hi) : lo + 1.5 * (lo - h_min) + 1e-9;
    }
  }
  out.status = status::kNotConverged;  // the last iterate is kept
}

}  // namespace railtab
