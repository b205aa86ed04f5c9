// SPDX-License-Identifier: Apache-2.0
// Plausibility checks of a profile read from a file (profile_checks.hpp): units, orientation, extent.
#include "profile/formats/profile_checks.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/check.hpp"

namespace railtab {
namespace {

constexpr double kMm = 1e-3;

struct Sample {
  double u, z;
};

// The curve at n + 1 points evenly spaced in its parameter.
std::vector<Sample> sample_curve(const Profile& p, int n) {
  std::vector<Sample> out(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const double t = i == n ? p.t_max() : p.t_min() + (p.t_max() - p.t_min()) * i / n;
    const CurveSample c = p.curve(t);
    out[static_cast<std::size_t>(i)] = {c.y, c.z};
  }
  return out;
}

void check_range(double value, double lo, double hi, const std::string& what, const char* quantity,
                 const char* body) {
  RAILTAB_CHECK(value >= lo && value <= hi,
                "{}: {} {:.6g} m is not plausible for a {} profile (expected {} to {} m): wrong "
                "length unit (SIMPACK units.len.f, two-column and MiniProf files are in mm)?",
                what, quantity, value, body, lo, hi);
}

std::size_t index_of_max_z(const std::vector<Sample>& s) {
  return static_cast<std::size_t>(
      std::max_element(s.begin(), s.end(), [](const Sample& a, const Sample& b) { return a.z < b.z; }) -
      s.begin());
}

// Largest depth below z_top reached by the samples [first, last).
double depth_reached(const std::vector<Sample>& s, std::size_t first, std::size_t last, double z_top) {
  double depth = 0.0;
  for (std::size_t i = first; i < last; ++i) depth = std::max(depth, z_top - s[i].z);
  return depth;
}

void check_wheel(const Profile& p, const std::vector<Sample>& s, const std::string& what) {
  RAILTAB_CHECK(p.u_min() < 0.0 && p.u_max() > 0.0,
                "{}: the running circle u = 0 lies outside the wheel's range [{:.2f}, {:.2f}] mm: "
                "wrong lateral origin? (shift it: scene profiles.wheel_shift_y, -0.070 m for a file "
                "whose y = 0 is the flange back)",
                what, p.u_min() / kMm, p.u_max() / kMm);
  const double z0 = p.eval(0.0).z;
  const auto lowest = std::min_element(s.begin(), s.end(), [](const Sample& a, const Sample& b) {
    return a.z < b.z;
  });
  const std::size_t i_high = index_of_max_z(s);
  const bool high_inside = i_high > s.size() / 50 && i_high + s.size() / 50 < s.size() - 1;
  const bool flange_on_inner_part = lowest->u - p.u_min() < p.u_max() - lowest->u;
  RAILTAB_CHECK(lowest->u < 0.0 || !flange_on_inner_part,
                "{}: the flange (lowest point, u = {:.2f} mm) lies on the field side of u = 0 "
                "although it is on the inner part of the profile [{:.2f}, {:.2f}] mm: the lateral "
                "origin is not on the running circle (measured from the flange back?); shift the "
                "profile so that u = 0 is on the running circle (scene profiles.wheel_shift_y, "
                "read option lateral_shift: -0.070 m for a file whose y = 0 is the flange back)",
                what, lowest->u / kMm, p.u_min() / kMm, p.u_max() / kMm);
  const double flange = z0 - lowest->z;
  if (flange < 10 * kMm && high_inside && s[i_high].z - z0 >= 10 * kMm) {
    throw Error(fmt::format("{}: the flange points up ({:.2f} mm above the running circle at u = "
                            "{:.2f} mm): vertical axis upside down (mirror.z / mirror_z)?",
                            what, (s[i_high].z - z0) / kMm, s[i_high].u / kMm));
  }
  RAILTAB_CHECK(flange >= 10 * kMm,
                "{}: no flange: the lowest point is {:.2f} mm below the running circle (a wheel "
                "profile needs a flange at least 10 mm high)",
                what, flange / kMm);
  RAILTAB_CHECK(lowest->u < 0.0,
                "{}: the flange (lowest point, u = {:.2f} mm) is on the field side of the running "
                "circle; it must be at u < 0: lateral axis mirrored (mirror.y / mirror_y)?",
                what, lowest->u / kMm);
}

void check_rail(const std::vector<Sample>& s, const std::string& what) {
  const std::size_t i_top = index_of_max_z(s);
  const std::size_t margin = s.size() / 100;
  RAILTAB_CHECK(i_top > margin && i_top + margin < s.size() - 1,
                "{}: the highest point (u = {:.2f} mm) is at an end of the rail profile, not on "
                "its head: vertical axis upside down (mirror.z / mirror_z)?",
                what, s[i_top].u / kMm);
  const double gauge_depth = depth_reached(s, 0, i_top, s[i_top].z);
  const double field_depth = depth_reached(s, i_top + 1, s.size(), s[i_top].z);
  RAILTAB_CHECK(!(gauge_depth < 14 * kMm && field_depth >= 14 * kMm),
                "{}: the gauge side (u < {:.2f} mm) reaches only {:.2f} mm below the top but the "
                "field side {:.2f} mm: lateral axis mirrored (mirror.y / mirror_y)?",
                what, s[i_top].u / kMm, gauge_depth / kMm, field_depth / kMm);
}

// Midpoint spread of horizontal chords 1..12 mm below the top after turning by -beta.
double asymmetry(const std::vector<Sample>& s, double beta) {
  const double c = std::cos(beta), sn = std::sin(beta);
  std::vector<Sample> r(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) r[i] = {c * s[i].u + sn * s[i].z, -sn * s[i].u + c * s[i].z};
  const std::size_t top = index_of_max_z(r);
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (double d = 1 * kMm; d <= 12 * kMm + 1e-12; d += 0.5 * kMm) {
    const double level = r[top].z - d;
    auto crossing = [&](long step) {
      for (long i = static_cast<long>(top); i + step >= 0 && i + step < static_cast<long>(r.size()); i += step) {
        const Sample& a = r[static_cast<std::size_t>(i)];
        const Sample& b = r[static_cast<std::size_t>(i + step)];
        if (b.z < level) return a.u + (b.u - a.u) * (a.z - level) / (a.z - b.z);
      }
      return HUGE_VAL;
    };
    const double g = crossing(-1), f = crossing(+1);
    if (!std::isfinite(g) || !std::isfinite(f)) return HUGE_VAL;  // the head is not that deep
    lo = std::min(lo, 0.5 * (g + f));
    hi = std::max(hi, 0.5 * (g + f));
  }
  return hi - lo;
}

}  // namespace

void check_plausible_profile(const Profile& p, const std::string& what) {
  const std::vector<Sample> s = sample_curve(p, 2000);
  double z_lo = HUGE_VAL, z_hi = -HUGE_VAL;
  for (const Sample& x : s) {
    z_lo = std::min(z_lo, x.z);
    z_hi = std::max(z_hi, x.z);
  }
  if (p.kind() == ProfileKind::wheel) {
    check_range(p.u_max() - p.u_min(), 0.03, 0.3, what, "width", "wheel");
    check_range(z_hi - z_lo, 0.005, 0.2, what, "height", "wheel");
    check_wheel(p, s, what);
  } else {
    check_range(p.u_max() - p.u_min(), 0.02, 0.25, what, "width", "rail");
    check_range(z_hi - z_lo, 0.002, 0.25, what, "height", "rail");
    check_rail(s, what);
  }
}

ApparentCant apparent_cant(const Profile& rail) {
  const std::vector<Sample> s = sample_curve(rail, 4000);
  // Golden section on beta in [-0.1, 0.1] rad (a cant of 1:10 either way covers every track).
  const double ratio = 0.5 * (3.0 - std::sqrt(5.0));
  double a = -0.1, b = 0.1;
  double x1 = a + ratio * (b - a), x2 = b - ratio * (b - a);
  double f1 = asymmetry(s, x1), f2 = asymmetry(s, x2);
  while (b - a > 1e-5) {
    if (f1 < f2) {
      b = x2; x2 = x1; f2 = f1;
      x1 = a + ratio * (b - a);
      f1 = asymmetry(s, x1);
    } else {
      a = x1; x1 = x2; f1 = f2;
      x2 = b - ratio * (b - a);
      f2 = asymmetry(s, x2);
    }
  }
  const double beta = 0.5 * (a + b);
  return {beta, asymmetry(s, beta), asymmetry(s, 0.0)};
}

}  // namespace railtab
