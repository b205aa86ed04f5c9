// SPDX-License-Identifier: Apache-2.0
// The exact half-space model on a wheel-rail contact (wheel_rail.hpp): patches, grids, load control, wear.
#include "halfspace/wheel_rail.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/check.hpp"
#include "normal/normal_model.hpp"
#include "wear/kth_wear_map.hpp"

namespace railtab::halfspace {

struct PlaneSample {  // one band sample seen in the patch's tangent plane
  double y;           // contact-frame lateral coordinate [m]
  double h;           // gap along the reference normal [m]
  double A;           // rolling-direction relative curvature [1/m]
  double angle;       // side-frame contact angle [rad]
  double x;           // longitudinal position of the gap's minimum along x (the wheel's
                      // silhouette), from the reference point; 0 without yaw [m]
};
struct PlaneSamples {  // RollingState's: the samples of each patch of its result
  std::vector<std::vector<PlaneSample>> patches;
};

namespace {

// Band samples of [s_lo, s_hi] in the plane of the reference (index i_ref interpolated at s_ref).
std::vector<PlaneSample> plane_samples(const WheelContactGeometry& g, double s_ref, double g_ref,
                                       double s_lo, double s_hi) {
  const int nb = static_cast<int>(g.band.size());
  if (nb < 2) return {};
  // Reference point on the rail surface, interpolated in s.
  const double t = (s_ref - g.band.front().s) / g.band_step;
  const int k0 = std::clamp(static_cast<int>(std::floor(t)), 0, nb - 2);
  const double f = std::clamp(t - k0, 0.0, 1.0);
  const double q_ref = (1 - f) * g.band[k0].q + f * g.band[k0 + 1].q;
  const double z_ref = (1 - f) * g.band[k0].z + f * g.band[k0 + 1].z;
  const bool yawed = g.wheel_yaw != 0.0;
  const double x_ref = yawed ? (1 - f) * g.band[k0].x_track + f * g.band[k0 + 1].x_track : 0.0;
  const double tq = std::cos(g_ref), tz = std::sin(g_ref);  // tangent towards the field side
  std::vector<PlaneSample> out;
  for (const BandSample& b : g.band) {
    if (b.s < s_lo || b.s > s_hi) continue;
    PlaneSample p;
    p.y = (b.q - q_ref) * tq + (b.z - z_ref) * tz;  // towards the field side (wheel_rail.hpp)
    p.h = b.gap / std::cos(b.contact_angle_side - g_ref);
    p.A = std::cos(b.contact_angle_side - g.wheel_roll) / (2.0 * b.rolling_radius);
    p.angle = b.contact_angle_side;
    p.x = 0.0;
    if (yawed) {  // the strip's gap is smallest on the wheel's silhouette, curved by Euler's k_x
      p.A = 0.5 * b.curvature_rolling;
      p.x = b.x_track - x_ref;
    }
    out.push_back(p);
  }
  std::sort(out.begin(), out.end(), [](const PlaneSample& a, const PlaneSample& b) {
    return a.y < b.y;
  });
  return out;
}

// Linear interpolation of the samples at y; false outside their range.
bool sample_at(const std::vector<PlaneSample>& s, double y, PlaneSample* out) {
  if (s.size() < 2 || y < s.front().y || y > s.back().y) return false;
  auto it = std::lower_bound(s.begin(), s.end(), y,
                             [](const PlaneSample& a, double v) { return a.y < v; });
  if (it == s.begin()) ++it;
  const PlaneSample& b = *it;
  const PlaneSample& a = *(it - 1);
  const double f = b.y > a.y ? (y - a.y) / (b.y - a.y) : 0.0;
  *out = {y, a.h + f * (b.h - a.h), a.A + f * (b.A - a.A), a.angle + f * (b.angle - a.angle),
          a.x + f * (b.x - a.x)};
  return true;
}

// Grid and gap of a yawed patch: each strip's gap is smallest at its own x (the wheel's
// silhouette leads or lags by r tan(gamma_w) tan(yaw)), so the rigid overlap is sheared along x;
// the grid covers the overlap of every strip, h(x, y) = h(y) + A(y) (x - x(y))^2.
void build_yawed_grid(const std::vector<PlaneSample>& samples, double delta_n, double grow,
                      double ylo, double yhi, double half_length, const HalfspaceOptions& o,
                      HalfspacePatch& hp);

// Grid and gap of a patch: rigid overlap at the normal approach delta_n, widened by `grow`.
void build_grid(const WheelContactGeometry& geometry, const ContactPatch& np, double delta_n,
                double grow, const HalfspaceOptions& o, HalfspacePatch& hp,
                std::vector<PlaneSample>& samples) {
  const double width = std::max(np.s_end - np.s_start, 4 * o.element_size);
  const double pad = grow * width + 2 * o.element_size;
  samples = plane_samples(geometry, np.band_s, hp.contact_angle_side, np.s_start - pad,
                          np.s_end + pad);
  // Lateral extent: where the rigid overlap is positive, widened.
  double ylo = 0, yhi = 0, half_length = 0;
  bool any = false;
  for (const PlaneSample& p : samples) {
    if (p.h >= delta_n) continue;
    ylo = any ? std::min(ylo, p.y) : p.y;
    yhi = any ? std::max(yhi, p.y) : p.y;
    half_length = std::max(half_length, std::sqrt((delta_n - p.h) / p.A));
    any = true;
  }
  if (!any) {  // no overlap at this approach: a small area around the reference
    ylo = -2 * o.element_size;
    yhi = 2 * o.element_size;
    half_length = 2 * o.element_size;
  }
  if (geometry.wheel_yaw != 0.0) {
    build_yawed_grid(samples, delta_n, grow, ylo, yhi, half_length, o, hp);
    return;
  }
  const double wy = yhi - ylo;
  ylo -= grow * wy + o.element_size;
  yhi += grow * wy + o.element_size;
  half_length = half_length * (1 + grow) + o.element_size;
  Grid& gr = hp.grid;
  gr.dx = gr.dy = o.element_size;
  gr.nx = 2 * static_cast<int>(std::ceil(half_length / gr.dx)) + 1;
  gr.ny = std::max(3, static_cast<int>(std::ceil((yhi - ylo) / gr.dy)) + 1);
  gr.x0 = -(gr.nx / 2) * gr.dx;
  gr.y0 = ylo;
  hp.gap.assign(gr.size(), 1.0);  // outside the band: far apart
  for (int j = 0; j < gr.ny; ++j) {
    PlaneSample p;
    if (!sample_at(samples, gr.y(j), &p)) continue;
    for (int i = 0; i < gr.nx; ++i) hp.gap[gr.index(i, j)] = p.h + p.A * gr.x(i) * gr.x(i);
  }
}

void build_yawed_grid(const std::vector<PlaneSample>& samples, double delta_n, double grow,
                      double ylo, double yhi, double half_length, const HalfspaceOptions& o,
                      HalfspacePatch& hp) {
  double xlo = -half_length, xhi = half_length;  // no overlap: around the reference
  bool any = false;
  for (const PlaneSample& p : samples) {
    if (p.h >= delta_n) continue;
    const double l = std::sqrt((delta_n - p.h) / p.A);
    xlo = any ? std::min(xlo, p.x - l) : p.x - l;
    xhi = any ? std::max(xhi, p.x + l) : p.x + l;
    any = true;
  }
  const double wx = xhi - xlo, wy = yhi - ylo;
  xlo -= 0.5 * grow * wx + o.element_size;
  xhi += 0.5 * grow * wx + o.element_size;
  ylo -= grow * wy + o.element_size;
  yhi += grow * wy + o.element_size;
  Grid& gr = hp.grid;
  gr.dx = gr.dy = o.element_size;
  const int i0 = static_cast<int>(std::floor(xlo / gr.dx));  // element centres on multiples of dx
  gr.nx = std::max(3, static_cast<int>(std::ceil(xhi / gr.dx)) - i0 + 1);
  gr.ny = std::max(3, static_cast<int>(std::ceil((yhi - ylo) / gr.dy)) + 1);
  gr.x0 = i0 * gr.dx;
  gr.y0 = ylo;
  hp.gap.assign(gr.size(), 1.0);  // outside the band: far apart
  for (int j = 0; j < gr.ny; ++j) {
    PlaneSample p;
    if (!sample_at(samples, gr.y(j), &p)) continue;
    for (int i = 0; i < gr.nx; ++i) {
      const double dx = gr.x(i) - p.x;
      hp.gap[gr.index(i, j)] = p.h + p.A * dx * dx;
    }
  }
}

// A field of grid `from` on grid `to` (the same element size): each element of `to` takes the
// value of the element of `from` whose centre is nearest to its own (coordinates from each grid's
// reference point), 0 outside `from`. The warm chain's start across a grid placed again
// (wheel_rail.hpp, RollingState): the field keeps its place relative to the reference instead
// of shifting with the grid's corner, or being dropped when the grid's size changes.
std::vector<double> on_grid(const Grid& from, const std::vector<double>& v, const Grid& to) {
  std::vector<double> out(static_cast<size_t>(to.size()), 0.0);
  if (v.size() != static_cast<size_t>(from.size()) || from.dx != to.dx || from.dy != to.dy) return out;
  for (int j = 0; j < to.ny; ++j) {
    const int jf = static_cast<int>(std::lround((to.y(j) - from.y0) / from.dy));
    if (jf < 0 || jf >= from.ny) continue;
    for (int i = 0; i < to.nx; ++i) {
      const int i_f = static_cast<int>(std::lround((to.x(i) - from.x0) / from.dx));
      if (i_f >= 0 && i_f < from.nx) out[static_cast<size_t>(to.index(i, j))] = v[static_cast<size_t>(from.index(i_f, jf))];
    }
  }
  return out;
}

// Start of the load-controlled BCCG where no previous pressure fits the grid: Hertz's shape
// from the gap, p ~ sqrt(level - h), level halfway from the gap's minimum to the normal approach
// dn of the normal layer (for a paraboloid gap exactly Hertz's distribution: the contact is where
// the rigid overlap exceeds half the approach); the solver scales it to the load. Left empty
// (the solver's own start) when dn does not reach the gap. The solution does not depend on the
// start; the iterations do (central case: 52 -> 47).
void hertz_like_start(const std::vector<double>& gap, double dn, std::vector<double>& p) {
  if (gap.empty()) return;
  const double hmin = *std::min_element(gap.begin(), gap.end());
  if (!(dn > hmin)) return;
  const double level = hmin + 0.5 * (dn - hmin);
  p.resize(gap.size());
  for (size_t k = 0; k < gap.size(); ++k) p[k] = std::sqrt(std::max(0.0, level - gap[k]));
}

// Contact-angle spread over the lateral extent of the contact.
double angle_spread(const HalfspacePatch& hp, const std::vector<PlaneSample>& samples) {
  double lo = 1e9, hi = -1e9;
  for (int j = 0; j < hp.grid.ny; ++j) {
    bool loaded = false;
    for (int i = 0; i < hp.grid.nx && !loaded; ++i)
      loaded = hp.normal.pressure[hp.grid.index(i, j)] > 0.0;
    PlaneSample p;
    if (!loaded || !sample_at(samples, hp.grid.y(j), &p)) continue;
    lo = std::min(lo, p.angle);
    hi = std::max(hi, p.angle);
  }
  return hi >= lo ? hi - lo : 0.0;
}

// The tangential problem on the bounding box of the contact only (tractions vanish outside it,
// and the slip matters only inside): a smaller FFT than the potential area's, the same numbers.
// Results are copied back to the patch's grid; the warm start comes from there too. `creepage`
// in the contact frame: solved in the patch's axes (track_sign), fy and mz returned in the contact
// frame.
void solve_on_contact_box(HalfspacePatch& hp, const RollingCreepage& creepage, double mu,
                          const Material& material, const TangentialSolverOptions& o,
                          Workspace& ws) {
  const double sign = hp.track_sign;
  const RollingCreepage c{creepage.xi, sign * creepage.eta, sign * creepage.phi};
  const Grid& g = hp.grid;
  int i0 = g.nx, i1 = -1, j0 = g.ny, j1 = -1;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      if (hp.normal.pressure[g.index(i, j)] > 0.0) {
        i0 = std::min(i0, i);
        i1 = std::max(i1, i);
        j0 = std::min(j0, j);
        j1 = std::max(j1, j);
      }
  TangentialSolution& full = hp.tangential;
  const bool warm = full.traction_x.size() == static_cast<size_t>(g.size());
  if (i1 < 0) {  // no contact: no traction
    solve_tangential(g, hp.normal.pressure, c, mu, material, o, ws, full);
    full.fy *= sign;
    full.mz *= sign;
    return;
  }
  Grid box;
  box.nx = std::max(2, i1 - i0 + 1);
  box.ny = std::max(2, j1 - j0 + 1);
  i0 = std::min(i0, g.nx - box.nx);
  j0 = std::min(j0, g.ny - box.ny);
  box.dx = g.dx;
  box.dy = g.dy;
  box.x0 = g.x(i0);
  box.y0 = g.y(j0);
  std::vector<double> pressure(box.size());
  TangentialSolution part;
  if (warm) {
    part.traction_x.resize(box.size());
    part.traction_y.resize(box.size());
  }
  for (int j = 0; j < box.ny; ++j)
    for (int i = 0; i < box.nx; ++i) {
      const int k = g.index(i0 + i, j0 + j), b = box.index(i, j);
      pressure[b] = hp.normal.pressure[k];
      if (warm) {
        part.traction_x[b] = full.traction_x[k];
        part.traction_y[b] = full.traction_y[k];
      }
    }
  solve_tangential(box, pressure, c, mu, material, o, ws, part);
  full.traction_x.assign(g.size(), 0.0);
  full.traction_y.assign(g.size(), 0.0);
  full.slip_x.assign(g.size(), 0.0);
  full.slip_y.assign(g.size(), 0.0);
  full.state.assign(g.size(), 0);
  if (part.traction_x.size() == static_cast<size_t>(box.size()))
    for (int j = 0; j < box.ny; ++j)
      for (int i = 0; i < box.nx; ++i) {
        const int k = g.index(i0 + i, j0 + j), b = box.index(i, j);
        full.traction_x[k] = part.traction_x[b];
        full.traction_y[k] = part.traction_y[b];
        full.slip_x[k] = part.slip_x[b];
        full.slip_y[k] = part.slip_y[b];
        full.state[k] = part.state[b];
      }
  full.fx = part.fx;
  full.fy = sign * part.fy;
  full.mz = sign * part.mz;
  full.slip_area = part.slip_area;
  full.frictional_work = part.frictional_work;
  full.sweeps = part.sweeps;
  full.status = part.status;
}

}  // namespace

namespace {

// Longitudinal position and lead of a patch's reference point (band interpolated at s).
void reference_x(const WheelContactGeometry& g, double s, HalfspacePatch& hp) {
  const int nb = static_cast<int>(g.band.size());
  if (nb < 2) return;
  const double t = (s - g.band.front().s) / g.band_step;
  const int k0 = std::clamp(static_cast<int>(std::floor(t)), 0, nb - 2);
  const double f = std::clamp(t - k0, 0.0, 1.0);
  hp.x_track = (1 - f) * g.band[k0].x_track + f * g.band[k0 + 1].x_track;
  hp.x_wheel = (1 - f) * g.band[k0].x_wheel + f * g.band[k0 + 1].x_wheel;
}

WheelHalfspaceResult solve_for_load(const WheelContactGeometry& geometry, double load,
                                    const Material& material, const HalfspaceOptions& o,
                                    Workspace& ws, const WheelHalfspaceResult* previous,
                                    std::vector<std::vector<PlaneSample>>* samples_out = nullptr,
                                    bool remap = false);

// The normal layer that finds the patches and places their references: STRIPES A&B with
// CONTACT's patch combination.
NormalOptions candidate_options() {
  NormalOptions no;
  no.model = NormalModel::stripes_ab;
  no.combine_patches = true;
  return no;
}

// Placements of the references at the solved approach (solve_for_load) before it gives up and
// keeps the last: the secant takes 2-4 where the angle moves fastest (flange, 100-180 kN).
constexpr int kReferenceRounds = 8;

}  // namespace

WheelNormalResult candidate_patches(const WheelContactGeometry& geometry, double load,
                                    const Material& material) {
  return solve_normal_for_load(geometry, load, material, candidate_options());
}

WheelHalfspaceResult solve_halfspace_for_load(const WheelContactGeometry& geometry,
                                              double load, const Material& material,
                                              const HalfspaceOptions& o, Workspace& ws) {
  return solve_for_load(geometry, load, material, o, ws, nullptr);
}

namespace {

// Flags of the solved patches (planarity, flange contact, area, convergence) into r.status;
// `solver` is the load iteration's own status.
void finish_patches(WheelHalfspaceResult& r, const std::vector<std::vector<PlaneSample>>& samples,
                    const HalfspaceOptions& o, StatusBits solver) {
  const int np = static_cast<int>(r.patches.size());
  r.status = solver;
  for (int k = 0; k < np; ++k) {
    HalfspacePatch& hp = r.patches[k];
    hp.contact_angle_spread = angle_spread(hp, samples[k]);
    hp.status = hp.normal.status;
    if (hp.contact_angle_spread > o.planar_angle_limit) hp.status |= status::kNotPlanar;
    if (hp.contact_angle_side > 0.35) hp.status |= status::kFlangeContact;  // as GeometrySettings
    r.status |= hp.status & ~status::kConverged;
    if (!(hp.normal.status & status::kConverged)) r.status &= ~status::kConverged;
  }
  if (np > 1) r.status |= status::kTwoPoint;
}

// previous: a result of the same geometry whose pressures start the solve where the grids match.
// samples_out: the band samples of each patch in its plane (for resolve_on_kept_grid).
WheelHalfspaceResult solve_for_load(const WheelContactGeometry& geometry, double load,
                                    const Material& material, const HalfspaceOptions& o,
                                    Workspace& ws, const WheelHalfspaceResult* previous,
                                    std::vector<std::vector<PlaneSample>>* samples_out, bool remap) {
  RAILTAB_CHECK(std::isfinite(load) && load >= 0.0,
                "halfspace: vertical load must be finite and >= 0, got {}", load);
  RAILTAB_CHECK(o.element_size > 0.0 && std::isfinite(o.element_size),
                "halfspace: element_size must be > 0, got {}", o.element_size);
  WheelHalfspaceResult r;
  WheelNormalResult first = candidate_patches(geometry, load, material);
  r.vertical_approach = first.vertical_approach;
  if (first.patches.empty() || load == 0.0) {
    r.status = status::kLiftOff | (first.status & status::kInvalidInput);
    return r;
  }
  const double sigma = outward_sign(geometry.side);
  // The reference point of each patch from the overlap runs of `first` (its band_s, angles, radius).
  auto place_references = [&] {
    for (size_t k = 0; k < first.patches.size(); ++k) {
      const ContactPatch& np = first.patches[k];
      HalfspacePatch& hp = r.patches[k];
      hp.band_s = np.band_s;
      hp.contact_angle = np.contact_angle;
      hp.contact_angle_side = sigma * np.contact_angle;
      hp.rolling_radius = np.rolling_radius;
      hp.wheel_u = np.wheel_u;
      hp.rail_u = np.rail_u;
      if (geometry.wheel_yaw != 0.0) reference_x(geometry, np.band_s, hp);
    }
  };
  std::vector<std::vector<PlaneSample>> samples(first.patches.size());
  for (size_t k = 0; k < first.patches.size(); ++k) {
    HalfspacePatch hp;
    hp.track_sign = track_sign(geometry.side);
    if (previous && previous->patches.size() == first.patches.size()) {
      hp.grid = previous->patches[k].grid;  // kept (warm start) when the new grid is the same
      hp.normal.pressure = previous->patches[k].normal.pressure;
    }
    r.patches.push_back(std::move(hp));
  }
  place_references();
  const int np = static_cast<int>(r.patches.size());
  // Solve every patch at the vertical approach dz (approach control), or the single patch for its
  // share of the load; grow a grid whose edge the contact reaches. keep_pressure: a pressure held
  // on the patch starts the solve on the new grid at the same coordinates (from the reference).
  bool keep_pressure = remap;
  auto solve_all = [&](double dz, bool single_load) {
    for (int k = 0; k < np; ++k) {
      HalfspacePatch& hp = r.patches[k];
      const double c = std::cos(hp.contact_angle_side);
      for (int growth = 0; growth <= o.max_growth; ++growth) {
        const double grow = o.margin * std::pow(1.5, growth) + (growth > 0 ? 0.5 * growth : 0.0);
        const Grid before = hp.grid;
        build_grid(geometry, first.patches[k], dz * c, grow, o, hp, samples[k]);
        if (keep_pressure && !hp.normal.pressure.empty()) {
          hp.normal.pressure = on_grid(before, hp.normal.pressure, hp.grid);
          if (std::none_of(hp.normal.pressure.begin(), hp.normal.pressure.end(), [](double v) { return v > 0.0; }))
            hp.normal.pressure.clear();
        } else if (!(before.nx == hp.grid.nx && before.ny == hp.grid.ny)) {
          hp.normal.pressure.clear();
        }
        if (single_load && hp.normal.pressure.empty())
          hertz_like_start(hp.gap, dz * c, hp.normal.pressure);
        if (single_load)
          solve_normal_for_force(hp.grid, hp.gap, load / c, material, o.normal, ws,
                                 hp.normal);
        else
          solve_normal_for_approach(hp.grid, hp.gap, dz * c, material, o.normal, ws, hp.normal);
        if (!(hp.normal.status & status::kAreaTooSmall)) break;
      }
    }
  };
  auto load_of = [&] {
    double fz = 0.0;
    for (const HalfspacePatch& hp : r.patches)
      fz += hp.normal.normal_force * std::cos(hp.contact_angle_side);
    return fz;
  };
  // The load at the references placed: the vertical approach that carries it. One patch: its
  // share; several: the secant on their common vertical approach, from `start`.
  auto solve_load = [&](double start) {
    if (np == 1) {
      solve_all(start, true);
      r.vertical_approach = r.patches[0].normal.approach / std::cos(r.patches[0].contact_angle_side);
      return StatusBits{status::kConverged};
    }
    double d0 = start, d1 = 1.02 * start;
    solve_all(d0, false);
    double f0 = load_of() - load;
    solve_all(d1, false);
    double f1 = load_of() - load;
    bool ok = false;
    for (int it = 0; it < 30; ++it) {
      if (std::abs(f1) <= o.load_tolerance * load) {
        ok = true;
        break;
      }
      if (f1 == f0) break;
      const double d2 = std::max(0.5 * d1, d1 - f1 * (d1 - d0) / (f1 - f0));
      d0 = d1;
      f0 = f1;
      d1 = d2;
      solve_all(d1, false);
      f1 = load_of() - load;
    }
    r.vertical_approach = d1;
    return StatusBits{ok ? status::kConverged : status::kNotConverged};
  };
  // The references at the approach solved for (wheel_rail.hpp, "Reference points"): placed again
  // from the overlap runs at the exact vertical approach until the approach they give agrees with
  // the one they were placed at (secant on the difference). A solve that follows another of the
  // same patches (a later round of the coupled solve, the next creepage of a table's chain) places
  // them first at that one's exact approach scaled to the new load as a Hertzian approach (load^2/3).
  if (previous && previous->patches.size() == first.patches.size() && previous->carried_load > 0.0 &&
      previous->vertical_approach > 0.0) {
    WheelNormalResult at = solve_normal_for_approach(
        geometry, previous->vertical_approach * std::pow(load / previous->carried_load, 2.0 / 3.0), material,
        candidate_options());
    if (at.patches.size() == first.patches.size()) {
      first = std::move(at);
      place_references();
    }
  }
  StatusBits solver = solve_load(first.vertical_approach);
  double x0 = 0.0, f0 = 0.0;  // the placement before and its miss (none yet: a plain step)
  for (int it = 0; it < kReferenceRounds && solver == status::kConverged; ++it) {
    const double x1 = first.vertical_approach, f1 = r.vertical_approach - x1;
    if (std::abs(f1) <= o.reference_tolerance * r.vertical_approach) break;
    const double x2 = std::clamp(it > 0 && f1 != f0 ? x1 - f1 * (x1 - x0) / (f1 - f0) : x1 + f1, 0.5 * x1, 2.0 * x1);
    WheelNormalResult at = solve_normal_for_approach(geometry, x2, material, candidate_options());
    if (at.patches.size() != first.patches.size()) break;  // the runs change here: keep the last
    first = std::move(at);
    place_references();
    keep_pressure = true;
    solver = solve_load(r.vertical_approach);
    x0 = x1;
    f0 = f1;
  }
  r.carried_load = load_of();
  finish_patches(r, samples, o, solver);
  if (samples_out != nullptr) *samples_out = std::move(samples);
  return r;
}

// A later round of the coupled solve (solve_halfspace_rolling) on the previous round's patch:
// the same reference, grid and gap, only the normal load changed (by the change of the
// tangential vertical part), the pressure warm-started. Saves the STRIPES pre-solve and, above
// all, keeps the grid: a grid rebuilt for the new approach differs by an element or a fraction of
// one in its lateral origin, which throws away the warm starts of both problems and the kernels.
// Only for one tread patch (not kFlangeContact) whose load moves by at most kKeepGridLoadChange
// and whose contact stays off the grid's edge; false: not done, r unchanged. In flange contact
// the load moves by up to a third between rounds and the reference and grid are placed again
// each round, as before (kept there, dy = 7 mm of block C moved from 22 to 25 % of mu N off
// CONTACT's: the case CONTACT's README calls unreliable, but a change all the same).
constexpr double kKeepGridLoadChange = 0.1;
bool resolve_on_kept_grid(WheelHalfspaceResult& r,
                          const std::vector<std::vector<PlaneSample>>& samples,
                          double load, const Material& material,
                          const HalfspaceOptions& o, Workspace& ws, const EarlierPressure* earlier = nullptr) {
  if (r.patches.size() != 1 || samples.size() != 1 || !(load > 0.0)) return false;
  const HalfspacePatch& old = r.patches[0];
  if (!(old.normal.status & status::kConverged) || (old.normal.status & status::kAreaTooSmall) ||
      (old.status & status::kFlangeContact))
    return false;
  if (std::abs(load - r.carried_load) > kKeepGridLoadChange * r.carried_load)
    return false;
  HalfspacePatch hp = old;  // reference, grid, gap; the pressure is the warm start
  const double c = std::cos(hp.contact_angle_side);
  // With an earlier pressure on this grid at another load, the start is extrapolated linearly in
  // the load from the two (clipped at zero), where it is no further than twice their distance.
  if (earlier != nullptr && earlier->pressure.size() == hp.normal.pressure.size()) {
    const double f = (load - r.carried_load) / (r.carried_load - earlier->load);
    if (std::isfinite(f) && std::abs(f) <= 2.0)
      for (std::size_t k = 0; k < hp.normal.pressure.size(); ++k)
        hp.normal.pressure[k] =
            std::max(0.0, hp.normal.pressure[k] + f * (hp.normal.pressure[k] - earlier->pressure[k]));
  }
  solve_normal_for_force(hp.grid, hp.gap, load / c, material, o.normal, ws, hp.normal);
  if (hp.normal.status & (status::kAreaTooSmall | status::kInvalidInput)) return false;
  r.patches[0] = std::move(hp);
  r.vertical_approach = r.patches[0].normal.approach / c;
  r.carried_load = r.patches[0].normal.normal_force * c;
  finish_patches(r, samples, o, status::kConverged);
  return true;
}

}  // namespace

void solve_halfspace_tangential(WheelHalfspaceResult& result, const Creepage& c, double mu,
                                const Material& material, const HalfspaceOptions& o,
                                Workspace& ws) {
  for (HalfspacePatch& hp : result.patches) {
    solve_on_contact_box(hp, {c.xi, c.eta, c.phi}, mu, material, o.tangential, ws);
    const StatusBits t = hp.tangential.status;
    hp.status = (hp.status & ~(status::kConverged | status::kNotConverged | status::kFullSlip)) |
                (t & (status::kNotConverged | status::kFullSlip | status::kInvalidInput));
    if ((hp.normal.status & status::kConverged) && (t & status::kConverged))
      hp.status |= status::kConverged;
    else
      hp.status |= status::kNotConverged;
  }
}

WheelHalfspaceResult solve_halfspace_rolling(const WheelContactGeometry& geometry,
                                             double load, const Creepage& creepage,
                                             double mu, const Material& material,
                                             const HalfspaceOptions& o, Workspace& ws,
                                             RollingState* state) {
  WheelHalfspaceResult r;
  // Warm (wheel_rail.hpp, RollingState): the previous solve of the chain is where the rounds start.
  const bool warm = state != nullptr && !state->result.patches.empty() && state->samples != nullptr;
  auto tangential_vertical = [](const WheelHalfspaceResult& res) {
    double tz = 0.0;
    for (const HalfspacePatch& hp : res.patches) tz += hp.tangential.fy * std::sin(hp.contact_angle);
    return tz;
  };
  // One round: normal for the load F_z - tz, then tangential; returns the new tz.
  // A loose round (the first, and those after a round that missed the balance by more than
  // loose_round_residual F_z) only has to give tz to the accuracy of a secant step, and the start
  // of the next round: its tangential and normal problems are solved to looser tolerances
  // (measured on block C: a third fewer tangential steps over the first two rounds; normal 1e-4:
  // median case 20 -> 17 ms CPU, no force of block C moved by 0.5 N). A converged result always
  // comes from a round at the full tolerances (solve_load_fixed_point accepts no loose round).
  constexpr double kFirstRoundTolerance = 1e-3;
  constexpr double kFirstRoundNormalTolerance = 1e-4;
  constexpr double kFirstRoundReferenceTolerance = 1e-2;  // 0.1 degree in flange contact
  HalfspaceOptions first_round = o;
  first_round.tangential.tolerance = std::max(o.tangential.tolerance, kFirstRoundTolerance);
  first_round.normal.tolerance = std::max(o.normal.tolerance, kFirstRoundNormalTolerance);
  first_round.reference_tolerance = std::max(o.reference_tolerance, kFirstRoundReferenceTolerance);
  std::vector<std::vector<PlaneSample>> samples;  // of the round that built the grids
  double start = 0.0;
  if (warm) {
    r = state->result;
    // The tangential problem starts from zero traction, as a cold one: the neighbour's tractions
    // (another creepage, often the other sign of spin) took 1.6 times the solver steps (measured on
    // the default creepage grid at y = 0 and 7 mm, 2100 solves: 73 against 45 per tread solve).
    for (HalfspacePatch& hp : r.patches) hp.tangential = TangentialSolution{};
    samples = state->samples->patches;
    // The tz its last normal solve was made for: the first round's normal problem is then already
    // solved (a warm pressure one solver check away), only the tangential one sees the new creepage.
    start = load - state->result.carried_load;
  }
  // Warm: the kept grid's pressure at the load before the last change (a predictor's second point).
  EarlierPressure earlier = warm ? state->earlier : EarlierPressure{};
  // A warm solve's full rounds: to the table's need (wheel_rail.hpp), a cold one's to o's.
  HalfspaceOptions full_round = o;
  if (warm) {
    full_round.normal.tolerance = std::max(o.normal.tolerance, o.warm_normal_tolerance);
    full_round.tangential.tolerance = std::max(o.tangential.tolerance, o.warm_tangential_tolerance);
  }
  auto round = [&](double tz, bool loose) {
    const HalfspaceOptions& oo = loose ? first_round : full_round;
    const double normal_load = std::max(0.0, load - tz);  // the normal part's share
    // A later round: on the previous grid when it still fits (tractions warm-started there).
    EarlierPressure before;
    const bool moved = warm && r.patches.size() == 1 && normal_load != r.carried_load;
    if (moved) before = {r.patches[0].normal.pressure, r.carried_load};
    if (!r.patches.empty() && resolve_on_kept_grid(r, samples, normal_load, material, oo, ws, warm ? &earlier : nullptr)) {
      if (moved) earlier = std::move(before);
      solve_halfspace_tangential(r, creepage, mu, material, oo, ws);
      return tangential_vertical(r);
    }
    WheelHalfspaceResult next = solve_for_load(geometry, normal_load, material, oo, ws,
                                               r.patches.empty() ? nullptr : &r, &samples, warm);
    if (next.patches.size() == r.patches.size())  // warm start from the previous round
      for (size_t k = 0; k < next.patches.size(); ++k) {
        const Grid& prior = r.patches[k].grid;
        TangentialSolution& t = r.patches[k].tangential;
        if (warm && t.traction_x.size() == static_cast<size_t>(prior.size())) {  // where they were
          next.patches[k].tangential.traction_x = on_grid(prior, t.traction_x, next.patches[k].grid);
          next.patches[k].tangential.traction_y = on_grid(prior, t.traction_y, next.patches[k].grid);
        } else if (next.patches[k].grid.nx == prior.nx && next.patches[k].grid.ny == prior.ny) {
          next.patches[k].tangential = std::move(t);
        }
      }
    solve_halfspace_tangential(next, creepage, mu, material, oo, ws);
    r = std::move(next);
    return tangential_vertical(r);
  };
  // Loose later rounds only along a warm chain (wheel_rail.hpp): a cold solve stays railtab eval's
  // and the error map's reference, bit for bit.
  const double loose_above = warm ? o.loose_round_residual : std::numeric_limits<double>::infinity();
  const double jump_width = warm ? o.jump_bracket : 0.0;  // the same for the stall stop
  const bool converged =
      solve_load_fixed_point(load, round, [&r] { return r.patches.empty(); }, start, loose_above, jump_width);
  if (state != nullptr) {
    if (converged && !r.patches.empty()) {  // a chain continues only from a converged solve
      state->result = r;
      state->earlier = std::move(earlier);
      state->samples = std::make_shared<const PlaneSamples>(PlaneSamples{samples});
    } else {
      state->clear();
    }
  }
  if (!converged) mark_not_converged(r);
  return r;
}

bool solve_load_fixed_point(double load, const std::function<double(double, bool)>& round,
                            const std::function<bool()>& stop_after_first, double start, double loose_above,
                            double jump_width) {
  const double tolerance = 1e-4 * load;
  // The tz of the latest full round whose balance missed high (g > 0) and low (g < 0). Missing on
  // both sides within jump_width * tolerance (0.5) in tz takes |dg/dtz| > 4, while a balance that
  // varies continuously has |dg/dtz| = |dT/dtz - 1| <= 1 + mu tan g (about 1.8 at mu = 0.3 and a
  // 70 degree flange): the balance jumps between them (a grid placed again one element over), and
  // no round can meet it.
  double high = std::numeric_limits<double>::quiet_NaN(), low = high;
  auto jumps = [&](double t, double g, bool was_loose) {
    if (was_loose) return false;
    (g > 0.0 ? high : low) = t;
    return std::abs(high - low) < jump_width * tolerance;  // false while either is NaN
  };
  double t0 = start, g0 = round(t0, true) - t0;  // fixed point tz = T(tz): root of g = T(tz) - tz
  if (stop_after_first()) return true;
  bool loose = std::abs(g0) > loose_above * load;
  double t1 = t0 + g0, g1 = round(t1, loose) - t1;
  bool ok = !loose && std::abs(g1) <= tolerance;
  for (int it = 0; it < 18 && !ok; ++it) {
    if (jumps(t1, g1, loose)) return false;
    const double t2 = g1 != g0 ? t1 - g1 * (t1 - t0) / (g1 - g0) : t1 + g1;
    loose = std::abs(g1) > loose_above * load;
    t0 = t1;
    g0 = g1;
    t1 = t2;
    g1 = round(t1, loose) - t1;
    ok = !loose && std::abs(g1) <= tolerance;
  }
  return ok;
}

void mark_not_converged(WheelHalfspaceResult& r) {
  r.status = (r.status & ~status::kConverged) | status::kNotConverged;
  for (HalfspacePatch& hp : r.patches) hp.status = (hp.status & ~status::kConverged) | status::kNotConverged;
}

double archard_wear_per_pass(const HalfspacePatch& hp, double speed, const WearOptions& wear,
                             std::vector<double>& depth) {
  const Grid& g = hp.grid;
  depth.assign(g.size(), 0.0);
  double section = 0.0;
  if (hp.tangential.slip_x.size() != static_cast<size_t>(g.size())) return 0.0;
  for (int k = 0; k < g.size(); ++k) {
    const double p = hp.normal.pressure[k];
    const double s = std::hypot(hp.tangential.slip_x[k], hp.tangential.slip_y[k]);
    if (!(p > 0.0) || !(s > 0.0)) continue;
    const double kw = kth_wear_coefficient(wear.map, p, speed * s, wear.lubrication);
    depth[k] = kw * p * s * g.dx / wear.map.hardness;
    section += depth[k] * g.dy;
  }
  return section;
}

}  // namespace railtab::halfspace
