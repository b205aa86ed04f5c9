// SPDX-License-Identifier: Apache-2.0
// Load control: the vertical approach that carries a given vertical wheel load (bracketing and
// root finding on the summed patch loads), then the patches at that approach.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/check.hpp"
#include "core/root_find.hpp"
#include "normal/normal_internal.hpp"
#include "geometry/overlap_reference.hpp"

namespace railtab {

WheelNormalResult solve_normal_for_load(const WheelContactGeometry& geometry, double load,
                                        const Material& material, const NormalOptions& options) {
  WheelNormalResult r;
  solve_normal_for_load(geometry, load, material, options, r);
  return r;
}

void solve_normal_for_load(const WheelContactGeometry& geometry, double load,
                           const Material& material, const NormalOptions& options,
                           WheelNormalResult& r) {
  detail::check_options(options);
  if (!std::isfinite(load)) {
    r = detail::lift_off(geometry, status::kInvalidInput);
    return;
  }
  if (geometry.points.empty() || load <= 0.0) {
    r = detail::lift_off(geometry, status::kConverged);
    return;
  }
  detail::Workspace& w = detail::thread_workspace();
  detail::prepare(geometry, material, options, w);

  // Hertz, one loaded point: closed form. N = W / cos(gamma) at the least separated point k;
  // exact when the resulting approach leaves every other point unloaded (dz <= h_j).
  {
    bool all_hertz = true;
    int k = 0;
    for (std::size_t i = 0; i < w.points.size(); ++i) {
      const detail::PointContext& p = w.points[i];
      all_hertz = all_hertz && p.model == NormalModel::hertz && p.hertz_valid;
      if (p.h < w.points[k].h) k = static_cast<int>(i);
    }
    if (all_hertz) {
      const detail::PointContext& pk = w.points[k];
      const double AB = pk.A0 + pk.B0;
      const double c =
          std::cbrt(3.0 * load / pk.cos_ref / (4.0 * material.contact_modulus() * AB));
      const double dz = pk.h + pk.hz.r * AB * c * c / pk.cos_ref;
      bool single = dz > pk.h;
      for (std::size_t i = 0; i < w.points.size(); ++i)
        single = single && (static_cast<int>(i) == k || dz <= w.points[i].h);
      if (single && detail::fill_single_hertz(geometry, material, options, w, dz, r) &&
          std::abs(r.carried_load - load) <= 2.0 * options.tolerance * load) {
        r.iterations = 1;  // one evaluation, no iteration
        r.status |= status::kConverged;
        return;
      }
    }
  }

  // Load control in the variable W^(2/3): nearly linear in delta_z (Hertz: W ~ delta^(3/2)), so
  // Brent's inverse interpolation converges in a few steps; W is monotone in delta_z, which keeps
  // the bracket valid.
  const double target = std::cbrt(load * load);
  int evaluations = 0;
  double h_min = std::numeric_limits<double>::infinity();
  for (const auto& p : w.points) h_min = std::min(h_min, p.h);
  double x_last[2] = {h_min, h_min}, f_last[2] = {-target, -target};  // the two latest evaluations
  auto f = [&](double dz) {
    ++evaluations;
    const double W = detail::carried_load(geometry, material, options, w, dz);
    const double fx = std::cbrt(W * W) - target;
    x_last[0] = x_last[1];
    f_last[0] = f_last[1];
    x_last[1] = dz;
    f_last[1] = fx;
    return fx;
  };
  // First guess: Hertz at the primary point (or 0.1 mm of approach).
  const detail::PointContext& p0 = w.points.front();
  double delta_n = 1e-4;
  if (p0.hertz_valid) {
    const double A = p0.A0, B = p0.B0;
    const double c = std::cbrt(3.0 * load / p0.cos_ref /
                               (4.0 * material.contact_modulus() * (A + B)));
    delta_n = p0.hz.r * (A + B) * c * c;
  }
  double lo = h_min, flo = -target;
  double hi = p0.h + delta_n / p0.cos_ref;
  if (!(hi > lo)) hi = lo + 1e-6;
  double fhi = f(hi);
  int expansions = 0;
  while (fhi < 0.0 && expansions < 80) {
    // Too little load: extrapolate W^(2/3) linearly from (h_min, 0) through the guess, 5 % beyond
    // (one step usually brackets the root), never further than doubling the approach.
    const double doubled = h_min + 2.0 * (hi - h_min);
    double next = h_min + 1.05 * (hi - h_min) * target / (fhi + target);
    if (!(next > hi) || !(next < doubled)) next = doubled;
    lo = hi;
    flo = fhi;
    hi = next;
    fhi = f(hi);
    ++expansions;
  }
  if (fhi < 0.0) {  // cannot carry the load within any sensible approach
    detail::fill(geometry, material, options, w, hi, r);
    r.iterations = evaluations;
    r.status |= status::kNotConverged;
    return;
  }
  const double f_tol = (2.0 / 3.0) * options.tolerance * target;
  // x tolerance far below what the load tolerance needs, relative to the bracket (approaches
  // span 1e-13 m at 1 nN to 1e-4 m at 150 kN), so that f_tol decides.
  const double x_tol = 1e-14 * (hi - h_min);
  // Brent to 1e-5 of the load, then one secant step through its two latest evaluations, confirmed
  // by the final fill (which evaluates the model anyway): from 1e-5 the superlinear step lands far
  // inside the tolerance, so Brent's own confirming evaluation is saved. A miss (the fill's load
  // outside the tolerance) falls back to Brent at the full tolerance.
  const double loose = std::max(f_tol, 1e-5 * target);
  auto root = brent_root(f, lo, hi, flo, fhi, x_tol, loose, options.max_iterations);
  double x = root.x;
  if (root.converged && std::abs(root.fx) > f_tol && f_last[1] != f_last[0]) {
    const double step = f_last[1] * (x_last[1] - x_last[0]) / (f_last[1] - f_last[0]);
    const double xs = x_last[1] - step;
    if (std::isfinite(xs) && xs > lo && xs < hi) x = xs;
  }
  detail::fill(geometry, material, options, w, x, r);
  auto within = [&](double factor) {
    return std::abs(r.carried_load - load) <= factor * options.tolerance * load;
  };
  if (x != root.x && !within(1.0)) {
    root = brent_root(f, lo, hi, flo, fhi, x_tol, f_tol, options.max_iterations);
    detail::fill(geometry, material, options, w, root.x, r);
  }
  r.iterations = evaluations;
  r.status |= within(2.0) ? status::kConverged : status::kNotConverged;
}

}  // namespace railtab
