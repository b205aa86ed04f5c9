// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the stability suite (tests/stability/): the S1002/UIC60 1:40 solver, the list of
// normal-model variants every test runs, finiteness checks over every number a result carries,
// bitwise comparison of two results (the "same answer run twice" check), FASTSIM + Archard wear on
// top of a normal result, and the continuity measure used by the y sweeps.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/material.hpp"
#include "core/status.hpp"
#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "profile/standard/s1002.hpp"
#include "profile/standard/uic60.hpp"
#include "tangential/fastsim_contact.hpp"
#include "wear/archard.hpp"

namespace railtab::stability {

// Moderate discretisation: the point here is robustness, not accuracy (the suite must stay fast).
inline constexpr int kStrips = 20;
inline constexpr int kElements = 12;
inline constexpr double kLoad = 78.5e3;  // default wheel load of the shipped scenes [N]

// Every normal model, STRIPES with both negative-curvature treatments.
struct Variant {
  NormalModel model;
  NegativeCurvature treatment;
  std::string label;
};

inline std::vector<Variant> all_variants() {
  return {{NormalModel::hertz, NegativeCurvature::shift, "hertz"},
          {NormalModel::linder, NegativeCurvature::shift, "linder"},
          {NormalModel::kik_piotrowski, NegativeCurvature::shift, "kik-piotrowski"},
          {NormalModel::stripes_a, NegativeCurvature::shift, "stripes-a/shift"},
          {NormalModel::stripes_a, NegativeCurvature::clip_and_smooth, "stripes-a/clip"},
          {NormalModel::stripes_ab, NegativeCurvature::shift, "stripes-ab/shift"},
          {NormalModel::stripes_ab, NegativeCurvature::clip_and_smooth, "stripes-ab/clip"}};
}

inline NormalOptions options_for(const Variant& v) {
  NormalOptions o;
  o.model = v.model;
  o.negative_curvature = v.treatment;
  o.strips = kStrips;
  return o;
}

inline const ContactGeometrySolver& s1002_uic60() {
  static const ContactGeometrySolver solver = [] {
    const ProfilePtr wheel = make_s1002_profile();
    const ProfilePtr rail = make_uic60_profile();
    return ContactGeometrySolver(wheel, rail, wheel, rail, TrackGeometry{}, WheelsetGeometry{});
  }();
  return solver;
}

inline bool finite(double x) { return std::isfinite(x); }

// Every number of a normal result is finite; forces, areas, pressures are >= 0; the patch and
// pairing structure is consistent. Returns a description of the first violation ("" when none).
inline std::string normal_violation(const WheelContactGeometry& g, const WheelNormalResult& r) {
  if (!finite(r.vertical_approach)) return "vertical_approach not finite";
  if (!finite(r.carried_load) || r.carried_load < 0.0) return "carried_load bad";
  if (r.point_patch.size() != g.points.size()) return "point_patch size";
  for (int k : r.point_patch)
    if (k < -1 || k >= static_cast<int>(r.patches.size())) return "point_patch index";
  if (r.patches.empty() && !(r.status & status::kLiftOff)) return "no patch but no lift_off flag";
  if (r.patches.size() > 1 && !(r.status & status::kTwoPoint)) return "several patches, no two_point";
  for (const ContactPatch& p : r.patches) {
    const double v[] = {p.normal_force, p.penetration, p.area,        p.max_pressure, p.semi_axis_a,
                        p.semi_axis_b,  p.band_s,      p.contact_angle, p.rolling_radius,
                        p.wheel_u,      p.rail_u,      p.s_start,     p.s_end};
    for (double x : v)
      if (!finite(x)) return "patch field not finite";
    if (p.normal_force < 0.0 || p.area < 0.0 || p.max_pressure < 0.0) return "negative patch value";
    if (!(p.rolling_radius > 0.0)) return "rolling radius <= 0";
    for (const Strip& s : p.strips) {
      const double w[] = {s.s,      s.width,   s.wheel_u,       s.rail_u,    s.contact_angle,
                          s.rolling_radius, s.x_lead, s.x_trail, s.pressure_peak,
                          s.ellipse_a, s.ellipse_b};
      for (double x : w)
        if (!finite(x)) return "strip field not finite";
      if (s.pressure_peak < 0.0 || s.width < 0.0) return "negative strip value";
    }
  }
  return "";
}

// Bitwise identity of two normal results (memcmp of every double: +0/-0 and NaN payloads count).
inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline bool bitwise_equal(const WheelNormalResult& a, const WheelNormalResult& b) {
  if (a.status != b.status || a.iterations != b.iterations || a.point_patch != b.point_patch ||
      a.patches.size() != b.patches.size() || !same_bits(a.vertical_approach, b.vertical_approach) ||
      !same_bits(a.carried_load, b.carried_load))
    return false;
  for (std::size_t i = 0; i < a.patches.size(); ++i) {
    const ContactPatch& p = a.patches[i];
    const ContactPatch& q = b.patches[i];
    if (p.status != q.status || p.points != q.points || p.point_index != q.point_index ||
        p.strips.size() != q.strips.size())
      return false;
    const double pv[] = {p.normal_force, p.penetration, p.area, p.max_pressure, p.semi_axis_a,
                         p.semi_axis_b, p.band_s, p.contact_angle, p.rolling_radius, p.s_start,
                         p.s_end};
    const double qv[] = {q.normal_force, q.penetration, q.area, q.max_pressure, q.semi_axis_a,
                         q.semi_axis_b, q.band_s, q.contact_angle, q.rolling_radius, q.s_start,
                         q.s_end};
    for (std::size_t k = 0; k < std::size(pv); ++k)
      if (!same_bits(pv[k], qv[k])) return false;
    if (!p.strips.empty() &&
        std::memcmp(p.strips.data(), q.strips.data(), p.strips.size() * sizeof(Strip)) != 0)
      return false;
  }
  return true;
}

inline bool bitwise_equal(const FastsimResult& a, const FastsimResult& b) {
  return a.status == b.status && same_bits(a.fx, b.fx) && same_bits(a.fy, b.fy) &&
         same_bits(a.mz, b.mz) && same_bits(a.normal_force, b.normal_force) &&
         same_bits(a.slip_fraction, b.slip_fraction) && same_bits(a.frictional_work, b.frictional_work);
}

// FASTSIM and Archard wear on one loaded patch.
struct CreepWear {
  FastsimResult creep;
  WearResult wear;
};

inline CreepWear creep_and_wear(const WheelContactGeometry& g, const ContactPatch& patch,
                                const Creepage& c, double mu = 0.3,
                                SpinVariation spin = SpinVariation::patch_constant) {
  CreepConditions cond;
  cond.friction = mu;
  cond.ellipse_strips = kStrips;
  FastsimOptions fo;
  fo.elements_per_strip = kElements;
  fo.spin = spin;
  FastsimWorkspace& ws = thread_fastsim_workspace();
  thread_local WearDistribution dist;
  CreepWear out;
  out.creep = fastsim_contact(g, patch, c, cond, Material{}, fo, ws);
  out.wear = archard_wear(ws, WearOptions{}, dist);
  return out;
}

// Finite creep and wear, |F| <= mu N (relative slack 1e-9: the traction bound integrates to N
// exactly, so only rounding may exceed it), wear >= 0. "" when fine.
inline std::string creep_violation(const ContactPatch& patch, const CreepWear& cw, double mu) {
  const FastsimResult& f = cw.creep;
  const double v[] = {f.fx, f.fy, f.mz, f.normal_force, f.slip_fraction, f.frictional_work};
  for (double x : v)
    if (!finite(x)) return "creep result not finite";
  const double ft = std::hypot(f.fx, f.fy);
  if (ft > mu * patch.normal_force * (1.0 + 1e-9) + 1e-12) return "|F| > mu N";
  if (f.slip_fraction < 0.0 || f.slip_fraction > 1.0 + 1e-12) return "slip fraction outside [0, 1]";
  const WearResult& w = cw.wear;
  const double u[] = {w.wear_rate, w.volume_rate, w.max_depth_rate, w.seizure_fraction};
  for (double x : u)
    if (!finite(x) || x < 0.0) return "wear result not finite or negative";
  return "";
}

// Scalar summary of a wheel's normal result used by the continuity checks.
struct Summary {
  int patches = 0;
  StatusBits bits = 0;       // status without kConverged (solver bookkeeping) and the jump flags
  bool near_equal = false;   // the geometry flags near_equal_minima (the primary point may jump)
  bool curvature_step = false;  // the geometry flags curvature_step (B at a point steps)
  double normal = 0.0;       // sum of patch normal forces [N]
  double lateral = 0.0;      // sum of N_i sin(gamma_i), side-frame sign: lateral (flange) force [N]
  double area = 0.0;         // total area [m2]
  double approach = 0.0;     // vertical approach [m]
  double max_angle = 0.0;    // largest side-frame reference angle of the loaded patches [rad]
  double point_b = 0.0;      // B of the primary geometric point [1/m]
  int points = 0;            // rigid contact points of the geometry
  double point_angle = 0.0;  // side-frame contact angle of the primary geometric point [rad]
};

inline Summary summarise(const WheelContactGeometry& g, const WheelNormalResult& r) {
  Summary s;
  const double sigma = outward_sign(g.side);
  s.patches = static_cast<int>(r.patches.size());
  // Geometry flags count too: a rigid contact point appearing (kTwoPoint of the geometry) changes
  // the point-based models' answer by construction.
  // near_equal_minima and curvature_step are kept apart (Summary::near_equal, curvature_step): a
  // bit that differs exempts a step, and the continuity tests written before the flags existed
  // keep their exemptions unchanged.
  s.bits = (r.status | g.status) &
           ~(status::kConverged | status::kNearEqualMinima | status::kCurvatureStep);
  s.near_equal = (g.status & status::kNearEqualMinima) != 0;
  s.curvature_step = (g.status & status::kCurvatureStep) != 0;
  s.points = static_cast<int>(g.points.size());
  s.approach = r.vertical_approach;
  s.max_angle = -10.0;
  for (const ContactPatch& p : r.patches) {
    const double a = sigma * p.contact_angle;
    s.normal += p.normal_force;
    s.lateral += p.normal_force * std::sin(a);
    s.area += p.area;
    s.max_angle = std::max(s.max_angle, a);
  }
  if (!g.points.empty()) {
    s.point_b = g.points.front().curvature_b;
    s.point_angle = g.points.front().contact_angle_side;
  }
  return s;
}

// Continuity measure for a quantity Q(y) sampled at uniform steps dy (0.05 mm in the sweeps):
// step k (between y_k and y_k+1) is a JUMP when
//     |dQ_k| > 4 * S_k + 1e-3 * max|Q|,
// S_k = the largest of the nearest non-exempt steps, up to two on each side within three steps
// (+-0.15 mm): the step may not exceed four times the local slope estimated from its neighbours.
// A kink (slope discontinuity) keeps |dQ_k| between its neighbours and passes; a step of the
// function fails. Two steps per side keep the estimate honest next to an extremum (where one
// neighbouring step is ~0) and next to an exempt step. The floor, 0.1 % of the sweep's magnitude,
// covers flat stretches. Steps where the solution legitimately changes character are exempt:
// `exempt(k)` (patch or point count, status bits, or a contact-angle jump between the samples).
// Returns the first bad step or -1.
// `confirm(k)` (the overload with three arguments) is asked about each step the measure suspects;
// only a confirmed step is returned (refined_jump below confirms by refinement).
template <class Exempt, class Confirm>
int first_jump(const std::vector<double>& q, Exempt exempt, Confirm confirm) {
  const int n = static_cast<int>(q.size());
  if (n < 3) return -1;
  double scale = 0.0;
  for (double x : q) scale = std::max(scale, std::abs(x));
  std::vector<double> d(n - 1);
  for (int k = 0; k + 1 < n; ++k) d[k] = std::abs(q[k + 1] - q[k]);
  for (int k = 0; k + 1 < n; ++k) {
    if (exempt(k)) continue;
    double slope = 0.0;
    for (int dir : {-1, 1}) {
      int used = 0;
      for (int j = k + dir; j >= 0 && j + 1 < n && std::abs(j - k) <= 3 && used < 2; j += dir) {
        if (exempt(j)) continue;
        slope = std::max(slope, d[j]);
        ++used;
      }
    }
    if (d[k] > 4.0 * slope + 1e-3 * scale && confirm(k)) return k;
  }
  return -1;
}
template <class Exempt>
int first_jump(const std::vector<double>& q, Exempt exempt) {
  return first_jump(q, exempt, [](int) { return true; });
}

// Confirmation of a suspected step by refinement. The neighbour-slope measure above confuses
// "steep" with "discontinuous": a smooth change that is steep only between two samples (next to
// an extremum or an exempt step, where there is no neighbouring slope to compare) fails it. So a
// suspected step [ya, yb] with |dQ| = d0 is halved kRefineHalvings = 5 times, each time keeping
// the half with the larger change, and is a JUMP only when the kept sub-step (1/32 of the step:
// 1.6 um on the 0.05 mm sweeps) still changes by more than kJumpKeeps = 25 % of d0.
// Why these numbers: where Q is continuously differentiable, the kept sub-step is at most
// max|Q'| (yb - ya) / 32, so a continuous change is called a jump only when its slope peaks at
// more than 8x its mean over the step, i.e. a feature narrower than ~1/8 of the step (a tanh of
// width < ~h/30 is a step at this resolution). A jump of height J: the half holding it changes
// by >= J minus the smooth part; if the jump falls exactly on a midpoint and the value there is
// between the two sides, each side holds a part and the larger (>= J/2) then persists at the end
// of the kept half at every level. The measure only suspects steps with d0 > 4 S (S ~ the smooth
// change per step), so J > 0.75 d0 and the kept sub-step is >= J/2 > 0.37 d0 > 25 % for every
// jump it would have reported. (A 50 % threshold would miss that midpoint case: ratio 0.5.)
// `eval(y)` gives Q at y (the samples at ya and yb must give the sampled values);
// `exempt_between(a, b)` is true when the samples at a and b differ in character (the
// exemptions of the measure): when the kept half is exempt, the change is located at a flagged
// or character change and the step is exempt like one of the sweep's own steps.
inline constexpr int kRefineHalvings = 5;
inline constexpr double kJumpKeeps = 0.25;
// refined_step_ratio returns the kept sub-step / d0 (0 when the kept half is exempt).
template <class Eval, class ExemptBetween>
double refined_step_ratio(Eval eval, double ya, double yb, ExemptBetween exempt_between) {
  double a = ya, b = yb, qa = eval(ya), qb = eval(yb);
  const double d0 = std::abs(qb - qa);
  for (int i = 0; i < kRefineHalvings; ++i) {
    const double m = 0.5 * (a + b);
    const double qm = eval(m);
    if (std::abs(qm - qa) >= std::abs(qb - qm)) {
      b = m;
      qb = qm;
    } else {
      a = m;
      qa = qm;
    }
    if (exempt_between(a, b)) return 0.0;
  }
  return d0 > 0.0 ? std::abs(qb - qa) / d0 : 0.0;
}
template <class Eval, class ExemptBetween>
bool refined_jump(Eval eval, double ya, double yb, ExemptBetween exempt_between) {
  return refined_step_ratio(eval, ya, yb, exempt_between) > kJumpKeeps;
}

// The geometry/character change that exempts a step from the continuity check: the number of
// loaded patches or of rigid contact points or the status bits differ, or the contact angle of the
// primary rigid point jumps by more than 0.05 rad (the contact jumps, e.g. from the flange root
// onto the flank). The patches' reference angle is an output and is not an exemption.
inline bool character_change(const Summary& a, const Summary& b) {
  return a.patches != b.patches || a.points != b.points || a.bits != b.bits ||
         std::abs(a.point_angle - b.point_angle) > 0.05;
}


// Iteration bound of the load control: bracket expansion (<= 80) plus Brent (<= max_iterations)
// plus a few evaluations around them. A result above it would mean an unbounded loop.
inline int iteration_bound(const NormalOptions& o) { return o.max_iterations + 90; }

// One sweep sample: geometry, normal result and its summary.
struct Sample {
  double y = 0.0;
  WheelContactGeometry geometry;
  WheelNormalResult normal;
  Summary summary;
};

// Solves `side` at (y, roll) for every y of the sweep with variant v and load control; checks at
// every sample: finite/consistent normal result (normal_violation), bounded iterations, a second
// solve is bitwise identical, and FASTSIM + Archard on every loaded patch (creepage c) are finite
// with |F| <= mu N and themselves bitwise repeatable.
inline std::vector<Sample> sweep(const ContactGeometrySolver& solver, Side side, const Variant& v,
                                 const std::vector<double>& ys, double roll = 0.0,
                                 double load = kLoad, Creepage c = {1e-3, 1e-3, 0.1}) {
  std::vector<Sample> out;
  const NormalOptions o = options_for(v);
  for (double y : ys) {
    Sample s;
    s.y = y;
    s.geometry = solver.solve_wheel(side, WheelsetState{y, roll});
    s.normal = solve_normal_for_load(s.geometry, load, Material{}, o);
    const std::string where = v.label + " " + to_string(side) + " y = " + std::to_string(y * 1e3) +
                              " mm roll = " + std::to_string(roll) + " load = " + std::to_string(load);
    const std::string bad = normal_violation(s.geometry, s.normal);
    EXPECT_EQ(bad, "") << where;
    EXPECT_LE(s.normal.iterations, iteration_bound(o)) << where;
    EXPECT_TRUE(s.normal.status & (status::kConverged | status::kNotConverged)) << where;
    const WheelNormalResult again = solve_normal_for_load(s.geometry, load, Material{}, o);
    EXPECT_TRUE(bitwise_equal(s.normal, again)) << "not repeatable: " << where;
    for (const ContactPatch& p : s.normal.patches) {
      if (!(p.normal_force > 0.0)) continue;
      const CreepWear cw = creep_and_wear(s.geometry, p, c);
      EXPECT_EQ(creep_violation(p, cw, 0.3), "") << where;
      const CreepWear cw2 = creep_and_wear(s.geometry, p, c);
      EXPECT_TRUE(bitwise_equal(cw.creep, cw2.creep)) << "creep not repeatable: " << where;
      EXPECT_TRUE(same_bits(cw.wear.wear_rate, cw2.wear.wear_rate)) << "wear not repeatable: " << where;
    }
    s.summary = summarise(s.geometry, s.normal);
    out.push_back(std::move(s));
  }
  return out;
}

inline std::vector<double> grid(double from, double to, double step) {
  std::vector<double> ys;
  const int n = static_cast<int>(std::lround((to - from) / step));
  for (int i = 0; i <= n; ++i) ys.push_back(from + i * step);
  return ys;
}

// Continuity (first_jump with character_change exemptions) of the total normal force, the lateral
// force sum N_i sin(gamma_i), the total area and the vertical approach along a sweep. `with_area`
// false skips the area (Hertz: the area follows the point's curvature, which jumps where the
// profiles' radii change). `exempt_near_equal` also exempts a step when either sample carries
// near_equal_minima (the primary point may jump there) or curvature_step (B at a point steps where
// it crosses a profile radius transition): the measured worn profiles' "continuity in y except at
// flagged jumps"; off by default so that the two-point and transition tests keep checking them.
// `refine(y)`, when given, solves the sweep's case at any y (a Summary); every suspected step is
// then confirmed by refinement (refined_jump) before it fails the test.
inline constexpr bool kExemptNearEqualMinima = true;
using RefineFn = std::function<Summary(double)>;
inline void expect_continuous(const std::vector<Sample>& s, const std::string& what,
                              bool with_area = true, bool exempt_near_equal = false,
                              const RefineFn& refine = {}) {
  auto differ = [&](const Summary& a, const Summary& b) {
    const bool flagged = a.near_equal || b.near_equal || a.curvature_step || b.curvature_step;
    return character_change(a, b) || (exempt_near_equal && flagged);
  };
  auto exempt = [&](int k) { return differ(s[k].summary, s[k + 1].summary); };
  std::map<double, Summary> solved;  // the sweep's samples and the refinement's midpoints
  for (const Sample& x : s) solved.emplace(x.y, x.summary);
  auto at = [&](double y) -> const Summary& {
    auto it = solved.find(y);
    if (it == solved.end()) it = solved.emplace(y, refine(y)).first;
    return it->second;
  };
  auto check = [&](const char* name, double Summary::*field) {
    std::vector<double> q;
    for (const Sample& x : s) q.push_back(x.summary.*field);
    auto confirm = [&](int j) {
      if (!refine) return true;
      const double r = refined_step_ratio([&](double y) { return at(y).*field; }, s[j].y, s[j + 1].y,
                                          [&](double a, double b) { return differ(at(a), at(b)); });
      std::printf("[ info ] %s: %s step %.6g -> %.6g between y = %.3f and %.3f mm refined to 1/%d: "
                  "%.3f of the step\n", what.c_str(), name, q[j], q[j + 1], s[j].y * 1e3,
                  s[j + 1].y * 1e3, 1 << kRefineHalvings, r);
      return r > kJumpKeeps;
    };
    const int k = first_jump(q, exempt, confirm);
    EXPECT_EQ(k, -1) << what << ": " << name << " jumps between y = " << s[k < 0 ? 0 : k].y * 1e3
                     << " and " << s[k < 0 ? 0 : k + 1].y * 1e3 << " mm: " << q[k < 0 ? 0 : k]
                     << " -> " << q[k < 0 ? 0 : k + 1];
  };
  check("normal force", &Summary::normal);
  check("lateral force", &Summary::lateral);
  check("vertical approach", &Summary::approach);
  if (with_area) check("area", &Summary::area);
}


// Variants by label (for tests that single out the ones with a known failure).
inline std::vector<Variant> variants_named(std::initializer_list<const char*> labels) {
  std::vector<Variant> out;
  for (const Variant& v : all_variants())
    for (const char* l : labels)
      if (v.label == l) out.push_back(v);
  return out;
}
inline std::vector<Variant> variants_except(std::initializer_list<const char*> labels) {
  std::vector<Variant> out;
  for (const Variant& v : all_variants()) {
    bool skip = false;
    for (const char* l : labels) skip = skip || v.label == l;
    if (!skip) out.push_back(v);
  }
  return out;
}

}  // namespace railtab::stability
