// SPDX-License-Identifier: Apache-2.0
// FASTSIM on an elliptic patch and on strips (fastsim.hpp): Kalker's simplified theory.
#include "tangential/fastsim.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/check.hpp"
#include "tangential/kalker_coefficients.hpp"

namespace railtab {

const char* to_string(SpinVariation variation) {
  switch (variation) {
    case SpinVariation::patch_constant: return "patch-constant";
    case SpinVariation::per_strip: return "per-strip";
  }
  return "unknown";
}

namespace {

struct Reference {
  double contact_angle = 0.0;   // gamma_ref, track frame [rad]
  double rolling_radius = 0.0;  // r_ref [m]
};

void check_inputs(const Creepage& c, double mu, double speed, const Material& material,
                  int elements_per_strip) {
  RAILTAB_CHECK(std::isfinite(c.xi) && std::isfinite(c.eta) && std::isfinite(c.phi),
                "fastsim: creepage (xi {}, eta {}, phi {}) must be finite", c.xi, c.eta, c.phi);
  RAILTAB_CHECK(std::isfinite(mu) && mu >= 0.0, "fastsim: friction coefficient {} must be >= 0",
                mu);
  RAILTAB_CHECK(std::isfinite(speed) && speed > 0.0, "fastsim: speed {} m/s must be > 0", speed);
  RAILTAB_CHECK(material.youngs_modulus > 0.0 && material.poisson_ratio >= 0.0 &&
                    material.poisson_ratio <= 0.5,
                "fastsim: material E {} Pa, nu {} invalid", material.youngs_modulus,
                material.poisson_ratio);
  RAILTAB_CHECK(elements_per_strip >= 1 && elements_per_strip <= 100000,
                "fastsim: elements per strip {} must be in [1, 100000]", elements_per_strip);
}

void resize_elements(FastsimWorkspace& ws, int n) {
  const auto un = static_cast<std::size_t>(n);
  ws.x.resize(un);
  ws.pressure.resize(un);
  ws.traction_x.resize(un);
  ws.traction_y.resize(un);
  ws.slip_x.resize(un);
  ws.slip_y.resize(un);
  ws.slip_velocity.resize(un);
  ws.wear_pressure.resize(un);
  ws.slip_distance.resize(un);
}

// The strip-wise solver on ws.strip (filled by the caller; pressure_peak unscaled).
FastsimResult solve(FastsimWorkspace& ws, double normal_force, const Reference& ref,
                    const Creepage& c, double mu, double speed, const Material& material,
                    const FastsimOptions& options) {
  const int n = options.elements_per_strip;
  const int m = ws.strips();
  ws.speed = speed;
  ws.reference_radius = ref.rolling_radius;
  ws.strip_begin.resize(static_cast<std::size_t>(m) + 1);

  // Element layout and unscaled pressures; discrete normal force.
  int total = 0;
  for (int i = 0; i < m; ++i) {
    FastsimStrip& s = ws.strip[static_cast<std::size_t>(i)];
    ws.strip_begin[static_cast<std::size_t>(i)] = total;
    const bool loaded = s.x_lead > s.x_trail && s.pressure_peak > 0.0 && s.width > 0.0;
    s.dx = loaded ? (s.x_lead - s.x_trail) / n : 0.0;
    if (loaded) total += n;
  }
  ws.strip_begin[static_cast<std::size_t>(m)] = total;
  resize_elements(ws, total);

  // Element centres sit at the same relative position u = 1 - (2k+1)/n on every strip, so the
  // pressure shape is tabulated once: [0, n) parabolic 1 - u^2, [n, 2n) semi-elliptic sqrt(1 - u^2).
  ws.shape_scratch.resize(2 * static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double u = 1.0 - (2.0 * k + 1.0) / n;
    const double f = std::max(0.0, 1.0 - u * u);
    ws.shape_scratch[static_cast<std::size_t>(k)] = f;
    ws.shape_scratch[static_cast<std::size_t>(n + k)] = std::sqrt(f);
  }
  double n_discrete = 0.0;
  for (int i = 0; i < m; ++i) {
    const FastsimStrip& s = ws.strip[static_cast<std::size_t>(i)];
    const int e0 = ws.strip_begin[static_cast<std::size_t>(i)];
    const int e1 = ws.strip_begin[static_cast<std::size_t>(i) + 1];
    const double* shape = ws.shape_scratch.data() + (s.parabolic ? 0 : n);
    double sum = 0.0;
    for (int e = e0; e < e1; ++e) {
      const double x = s.x_lead - (e - e0 + 0.5) * s.dx;  // element centre
      const double p = s.pressure_peak * shape[e - e0];
      ws.x[static_cast<std::size_t>(e)] = x;
      ws.pressure[static_cast<std::size_t>(e)] = p;
      sum += p;
    }
    n_discrete += sum * s.dx * s.width;
  }

  FastsimResult r;
  r.status = status::kConverged;
  if (!(n_discrete > 0.0) || !(normal_force > 0.0)) {
    std::fill(ws.traction_x.begin(), ws.traction_x.end(), 0.0);
    std::fill(ws.traction_y.begin(), ws.traction_y.end(), 0.0);
    std::fill(ws.slip_x.begin(), ws.slip_x.end(), 0.0);
    std::fill(ws.slip_y.begin(), ws.slip_y.end(), 0.0);
    std::fill(ws.slip_velocity.begin(), ws.slip_velocity.end(), 0.0);
    std::fill(ws.slip_distance.begin(), ws.slip_distance.end(), 0.0);
    std::fill(ws.pressure.begin(), ws.pressure.end(), 0.0);
    std::fill(ws.wear_pressure.begin(), ws.wear_pressure.end(), 0.0);
    r.status |= status::kLiftOff;
    return r;
  }
  // Scale the bound so that it integrates to the patch's normal force on this grid.
  const double scale = normal_force / n_discrete;
  for (auto& p : ws.pressure) p *= scale;
  for (auto& s : ws.strip) s.pressure_peak *= scale;
  r.normal_force = normal_force;

  const double shear = material.shear_modulus();
  const double nu = material.poisson_ratio;
  const bool per_strip = options.spin == SpinVariation::per_strip;
  const double kappa = per_strip ? (1.0 - c.xi) / ref.rolling_radius : 0.0;  // Omega / V [1/m]
  const double sin_ref = std::sin(ref.contact_angle);
  const double phi_nonkinematic = c.phi + kappa * sin_ref;  // phi - phi_kin,ref [rad/m]

  double fx = 0.0, fy = 0.0, mz = 0.0, area = 0.0, slip_area = 0.0, work = 0.0;
  double last_ratio = -1.0;
  KalkerCoefficients kc;
  for (int i = 0; i < m; ++i) {
    const FastsimStrip& s = ws.strip[static_cast<std::size_t>(i)];
    const int e0 = ws.strip_begin[static_cast<std::size_t>(i)];
    const int e1 = ws.strip_begin[static_cast<std::size_t>(i) + 1];
    if (e0 == e1) continue;
    const double ae = s.ellipse_a, be = s.ellipse_b;
    const double ratio = ae / be;
    if (ratio != last_ratio) {  // Hertz patches: one evaluation for all strips
      kc = kalker_coefficients(ratio, nu);
      last_ratio = ratio;
    }
    const double l1 = 8.0 * ae / (3.0 * kc.c11 * shear);
    const double l2 = 8.0 * ae / (3.0 * kc.c22 * shear);
    const double l3 = std::numbers::pi * ae * std::sqrt(ratio) / (4.0 * kc.c23 * shear);

    double xi_i = c.xi, eta_i = c.eta, phi_i = c.phi, q_i = -c.phi * s.y, cos_d = 1.0;
    if (per_strip) {
      const double d = s.contact_angle - ref.contact_angle;
      cos_d = std::cos(d);
      eta_i = c.eta * cos_d;
      phi_i = phi_nonkinematic - kappa * std::sin(s.contact_angle);
      q_i = -phi_nonkinematic * s.y + kappa * (ref.rolling_radius - s.rolling_radius);
    }
    // Single flexibility for the slip output (CONTACT's creepage-weighted L).
    const double cprime = 3.0 * std::numbers::pi * ae / 32.0;
    const double sp2 = q_i * q_i + phi_i * phi_i * cprime * cprime;
    const double num = xi_i * xi_i + eta_i * eta_i + sp2;
    const double den = xi_i * xi_i / l1 + eta_i * eta_i / l2 + sp2 / l3;
    const double ls = den > 0.0 ? num / den : l1;
    const double ly_factor = ls;  // same flexibility both ways: slip stays opposite to traction

    const double dx = s.dx;
    const double dax = (xi_i / l1 + q_i / l3) * dx;  // adhesion increment along x per step [Pa]
    const double day = eta_i / l2 * dx;
    const double spin_y = phi_i / l3 * dx;
    const double da = dx * s.width;
    const double width = s.width;
    double px = 0.0, py = 0.0, pn = 0.0;  // traction and pressure at the previous sample
    double fxs = 0.0, fys = 0.0, mzs = 0.0;
    for (int e = e0; e < e1; ++e) {
      const auto ue = static_cast<std::size_t>(e);
      const double x = ws.x[ue];
      // Step from the previous sample (the leading edge for the first element) to this centre.
      const double step = e == e0 ? 0.5 : 1.0;  // step length / dx [-]
      const double xmid = x + 0.5 * step * dx;
      const double tx = px - step * dax;
      const double ty = py - step * (day + spin_y * xmid);
      const double pn_new = ws.pressure[ue];
      const double bound = mu * pn_new;
      const double t2 = tx * tx + ty * ty;
      double ux = 0.0, uy = 0.0;  // slip displacement over the step [m]
      double qx = tx, qy = ty;
      if (t2 > bound * bound) {
        const double f = bound / std::sqrt(t2);
        qx = f * tx;
        qy = f * ty;
        ux = ls * (qx - tx);
        uy = ly_factor * (qy - ty);
        slip_area += da;
      }
      // Work and wear pair the slip of a step with the mean traction and pressure over the step
      // (the discrete form of the continuum identity int p.s dx = F.w - L [p^2/2]).
      work -= (0.5 * (px + qx) * ux + 0.5 * (py + qy) * uy) * width;
      const double umag = ux == 0.0 && uy == 0.0 ? 0.0 : std::sqrt(ux * ux + uy * uy);
      ws.traction_x[ue] = qx;
      ws.traction_y[ue] = qy;
      ws.slip_x[ue] = ux / dx;
      ws.slip_y[ue] = uy / dx;
      ws.slip_velocity[ue] = speed * umag / dx;
      ws.slip_distance[ue] = umag;
      ws.wear_pressure[ue] = 0.5 * (pn + pn_new);
      px = qx;
      py = qy;
      pn = pn_new;
      fxs += px;
      fys += py;
      mzs += x * py;
    }
    {
      // The traction returns to zero at the trailing edge, half an element behind the last
      // centre (the bound is zero there): the elastic displacement released, L_s (0 - p*_edge),
      // is slip of the last element, with mean traction p/2 and mean pressure p_n/2. The slip
      // area (slip_fraction) counts only elements at the traction bound.
      const auto ul = static_cast<std::size_t>(e1 - 1);
      const double xe = ws.x[ul] - 0.25 * dx;
      const double ux = -ls * (px - 0.5 * dax);
      const double uy = -ly_factor * (py - 0.5 * (day + spin_y * xe));
      work -= (0.5 * px * ux + 0.5 * py * uy) * width;
      const double ox = ws.slip_x[ul] * dx, oy = ws.slip_y[ul] * dx;  // step slip of the element
      const double omag = std::hypot(ox, oy), emag = std::hypot(ux, uy);
      const double tx = ox + ux, ty = oy + uy;
      const double umag = std::hypot(tx, ty);
      if (omag + emag > 0.0)
        ws.wear_pressure[ul] = (ws.wear_pressure[ul] * omag + 0.5 * pn * emag) / (omag + emag);
      ws.slip_x[ul] = tx / dx;
      ws.slip_y[ul] = ty / dx;
      ws.slip_velocity[ul] = speed * umag / dx;
      ws.slip_distance[ul] = umag;
    }
    area += da * (e1 - e0);
    fx += fxs * da;
    fy += cos_d * fys * da;
    mz += (cos_d * mzs - s.y * fxs) * da;
  }
  r.fx = fx;
  r.fy = fy;
  r.mz = mz;
  r.slip_fraction = area > 0.0 ? slip_area / area : 0.0;
  r.frictional_work = work;
  const double ft = std::hypot(fx, fy);
  if (r.slip_fraction >= 1.0 - 1e-12 || (mu > 0.0 && ft >= (1.0 - 1e-9) * mu * normal_force))
    r.status |= status::kFullSlip;
  return r;
}

}  // namespace

FastsimResult fastsim_patch(const ContactPatch& patch, const PatchPlacement& placement,
                            const Creepage& creepage, double mu, double speed,
                            const Material& material, const FastsimOptions& options,
                            FastsimWorkspace& workspace) {
  check_inputs(creepage, mu, speed, material, options.elements_per_strip);
  RAILTAB_CHECK(std::isfinite(placement.s_reference) &&
                    std::abs(std::abs(placement.lateral_sign) - 1.0) < 1e-12,
                "fastsim_patch: placement s_reference {} m, lateral_sign {} (must be +-1)",
                placement.s_reference, placement.lateral_sign);
  const bool per_strip = options.spin == SpinVariation::per_strip;
  RAILTAB_CHECK(!per_strip || patch.strips.empty() || patch.rolling_radius > 0.0,
                "fastsim_patch: per-strip spin needs the reference rolling radius, got {} m",
                patch.rolling_radius);

  // Fallback half-width for strips without a local ellipse (Linder-like: patch half-width).
  double s_min = 0.0, s_max = 0.0;
  if (!patch.strips.empty()) {
    s_min = patch.strips.front().s - 0.5 * patch.strips.front().width;
    s_max = patch.strips.back().s + 0.5 * patch.strips.back().width;
  }
  const double half_width = 0.5 * (s_max - s_min);

  workspace.strip.resize(patch.strips.size());
  for (std::size_t i = 0; i < patch.strips.size(); ++i) {
    const Strip& in = patch.strips[i];
    FastsimStrip& s = workspace.strip[i];
    s.y = placement.lateral_sign * (in.s - placement.s_reference);
    s.width = in.width;
    s.x_lead = in.x_lead;
    s.x_trail = in.x_trail;
    s.pressure_peak = in.pressure_peak;
    s.parabolic = patch.pressure_shape == StripPressure::parabolic;
    s.ellipse_a = in.ellipse_a > 0.0 ? in.ellipse_a : 0.5 * (in.x_lead - in.x_trail);
    s.ellipse_b = in.ellipse_b > 0.0 ? in.ellipse_b : half_width;
    if (!(s.ellipse_a > 0.0 && s.ellipse_b > 0.0)) s.x_lead = s.x_trail;  // unloaded strip
    s.wheel_u = in.wheel_u;
    s.rolling_radius = in.rolling_radius;
    s.contact_angle = in.contact_angle;
  }
  double radius = patch.rolling_radius;
  if (!(radius > 0.0) && !patch.strips.empty()) {  // no reference radius: mean of the strips
    radius = 0.0;
    for (const Strip& in : patch.strips) radius += in.rolling_radius;
    radius /= static_cast<double>(patch.strips.size());
  }
  const Reference ref{patch.contact_angle, radius};
  return solve(workspace, patch.normal_force, ref, creepage, mu, speed, material, options);
}

FastsimResult fastsim_ellipse(const EllipticPatch& patch, const Creepage& creepage, double mu,
                              double speed, const Material& material, int elements_per_strip,
                              FastsimWorkspace& workspace) {
  check_inputs(creepage, mu, speed, material, elements_per_strip);
  RAILTAB_CHECK(patch.a > 0.0 && patch.b > 0.0 && std::isfinite(patch.a) && std::isfinite(patch.b),
                "fastsim_ellipse: semi-axes a {} m, b {} m must be positive", patch.a, patch.b);
  RAILTAB_CHECK(std::isfinite(patch.du_dy) && std::abs(patch.du_dy) <= 1.0,
                "fastsim_ellipse: du_dy {} must be finite with |du_dy| <= 1", patch.du_dy);
  RAILTAB_CHECK(patch.strips >= 1 && patch.strips <= 100000,
                "fastsim_ellipse: strip count {} must be in [1, 100000]", patch.strips);
  const int m = patch.strips;
  const double dy = 2.0 * patch.b / m;
  const double p0 = 2.0 * patch.normal_force / (std::numbers::pi * patch.a * patch.b);
  workspace.strip.resize(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) {
    FastsimStrip& s = workspace.strip[static_cast<std::size_t>(j)];
    const double y = -patch.b + (j + 0.5) * dy;
    const double f = 1.0 - (y * y) / (patch.b * patch.b);
    const double aj = patch.a * std::sqrt(f);
    s.y = y;
    s.width = dy;
    s.x_lead = aj;
    s.x_trail = -aj;
    s.pressure_peak = p0 * f;
    s.parabolic = true;
    s.ellipse_a = patch.a;
    s.ellipse_b = patch.b;
    s.wheel_u = patch.wheel_u + patch.du_dy * y;
    s.rolling_radius = patch.rolling_radius;
    s.contact_angle = 0.0;
  }
  FastsimOptions options;
  options.elements_per_strip = elements_per_strip;
  const Reference ref{0.0, patch.rolling_radius};
  return solve(workspace, patch.normal_force, ref, creepage, mu, speed, material, options);
}

FastsimWorkspace& thread_fastsim_workspace() {
  thread_local FastsimWorkspace workspace;
  return workspace;
}

}  // namespace railtab
