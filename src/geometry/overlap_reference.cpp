// SPDX-License-Identifier: Apache-2.0
// Loaded-patch references from the gap band (see overlap_reference.hpp for the rules and for how
// they follow CONTACT's contact search).
#include "geometry/overlap_reference.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"

namespace railtab {

OverlapOptions contact_patch_rules() {
  OverlapOptions o;
  o.combine_distance = 8e-3;
  o.separate_angle = 3.14159265358979323846;
  o.turn_distance = 12e-3;
  return o;
}

namespace {

// Band quantities linearly interpolated between samples i and i+1 at fraction t in [0, 1].
struct BandPoint {
  double s, rail_u, wheel_u, q, z, angle, gap, radius;
};

BandPoint lerp(const BandSample& a, const BandSample& b, double t) {
  auto mix = [t](double x, double y) { return x + t * (y - x); };
  return {mix(a.s, b.s),         mix(a.rail_u, b.rail_u), mix(a.wheel_u, b.wheel_u),
          mix(a.q, b.q),         mix(a.z, b.z),           mix(a.contact_angle_side, b.contact_angle_side),
          mix(a.gap, b.gap),     mix(a.rolling_radius, b.rolling_radius)};
}

// Band point at arc length s (clamped to the band).
BandPoint band_at_s(const std::vector<BandSample>& band, double s) {
  if (band.size() == 1 || s <= band.front().s) return lerp(band.front(), band.front(), 0.0);
  if (s >= band.back().s) return lerp(band.back(), band.back(), 0.0);
  const auto it = std::partition_point(band.begin(), band.end(),
                                       [s](const BandSample& b) { return b.s <= s; });
  const BandSample& hi = *it;
  const BandSample& lo = *(it - 1);
  return lerp(lo, hi, (s - lo.s) / (hi.s - lo.s));
}

// Band point at side-frame lateral q; q grows with s along the band (the rail branch used rises
// with u towards the field side), so the inverse is a search plus linear interpolation.
BandPoint band_at_q(const std::vector<BandSample>& band, double q) {
  if (band.size() == 1 || q <= band.front().q) return lerp(band.front(), band.front(), 0.0);
  if (q >= band.back().q) return lerp(band.back(), band.back(), 0.0);
  const auto it = std::partition_point(band.begin(), band.end(),
                                       [q](const BandSample& b) { return b.q <= q; });
  const BandSample& hi = *it;
  const BandSample& lo = *(it - 1);
  return lerp(lo, hi, (q - lo.q) / (hi.q - lo.q));
}

struct Weighting {
  double exponent;  // e in w = k p^e
  double factor;    // k [m^(1/2)]
  // Weight per unit band length at normal overlap d > 0 and contact angle g: vertical
  // interpenetration p = d / cos(g), lateral step dy = cos(g) ds.
  double per_s(double d, double angle) const {
    const double c = std::cos(angle);
    return factor * std::pow(d / c, exponent) * c;
  }
};

// Distance in the (q, z) plane between the inner end of the outer patch and the outer end of
// the inner one (CONTACT: between ysta of the outer and yend of the inner).
double facing_distance(const std::vector<BandSample>& band, const OverlapReference& outer,
                       const OverlapReference& inner) {
  const BandPoint a = band_at_s(band, outer.s_start);
  const BandPoint b = band_at_s(band, inner.s_end);
  return std::hypot(a.q - b.q, a.z - b.z);
}

}  // namespace

std::vector<OverlapReference> overlap_references(const WheelContactGeometry& geometry,
                                                 double vertical_approach,
                                                 const OverlapOptions& options) {
  RAILTAB_CHECK(std::isfinite(vertical_approach),
                "overlap reference: vertical approach = {} is not finite", vertical_approach);
  RAILTAB_CHECK(std::isfinite(options.nominal_radius) && options.nominal_radius > 0.0,
                "overlap reference: nominal_radius = {} must be finite and > 0", options.nominal_radius);
  std::vector<OverlapReference> out;
  const std::vector<BandSample>& band = geometry.band;
  const std::size_t n = band.size();
  if (!(vertical_approach > 0.0) || n == 0) return out;

  const double dz = vertical_approach;
  const double sqrt_2r = std::sqrt(2.0 * options.nominal_radius);
  const Weighting w = options.weighting == OverlapWeighting::squared
                          ? Weighting{2.5, 16.0 / 15.0 * sqrt_2r}
                          : Weighting{1.5, 4.0 / 3.0 * sqrt_2r};
  auto overlap = [&](std::size_t i) { return dz * std::cos(band[i].contact_angle_side) - band[i].gap; };

  // 1. One entry per run of positive overlap: weighted q and angle, weight, extent.
  std::size_t i = 0;
  while (i < n) {
    if (!(overlap(i) > 0.0)) {
      ++i;
      continue;
    }
    const std::size_t a = i;
    std::size_t b = i;
    double d_max = overlap(a);
    while (b + 1 < n && overlap(b + 1) > 0.0) {
      ++b;
      d_max = std::max(d_max, overlap(b));
    }
    double sum_w = 0.0, sum_wq = 0.0, sum_wa = 0.0;
    for (std::size_t j = a; j < b; ++j) {  // trapezoids between samples inside the run
      const BandSample& p = band[j];
      const BandSample& r = band[j + 1];
      const double w0 = w.per_s(overlap(j), p.contact_angle_side);
      const double w1 = w.per_s(overlap(j + 1), r.contact_angle_side);
      const double half = 0.5 * (r.s - p.s);
      sum_w += half * (w0 + w1);
      sum_wq += half * (w0 * p.q + w1 * r.q);
      sum_wa += half * (w0 * p.contact_angle_side + w1 * r.contact_angle_side);
    }
    // Cell between the last overlapping sample k and its neighbour m outside the run: the
    // overlap falls linearly to zero at length L from k, the weight as (1 - x/L)^e, so the cell
    // adds w_k L/(e+1) with its centroid L/(e+2) from k. Returns the zero crossing's s.
    auto end_cell = [&](std::size_t k, std::size_t m) {
      const double dk = overlap(k);
      const double dm = overlap(m);
      const double h = band[m].s - band[k].s;  // signed
      const double len = h * dk / (dk - dm);
      const double part = w.per_s(dk, band[k].contact_angle_side) * std::abs(len) / (w.exponent + 1.0);
      const double t = len / (w.exponent + 2.0) / h;
      sum_w += part;
      sum_wq += part * (band[k].q + t * (band[m].q - band[k].q));
      sum_wa += part * (band[k].contact_angle_side + t * (band[m].contact_angle_side - band[k].contact_angle_side));
      return band[k].s + len;
    };
    OverlapReference ref{};
    ref.clipped = false;
    if (a > 0) {
      ref.s_start = end_cell(a, a - 1);
    } else {
      ref.s_start = band[a].s;
      ref.clipped = true;
    }
    if (b + 1 < n) {
      ref.s_end = end_cell(b, b + 1);
    } else {
      ref.s_end = band[b].s;
      ref.clipped = true;
    }
    if (sum_w > 0.0) {
      ref.q = sum_wq / sum_w;
      ref.contact_angle_side = sum_wa / sum_w;
    } else {  // a lone sample at the band end: nothing to integrate
      ref.q = band[a].q;
      ref.contact_angle_side = band[a].contact_angle_side;
    }
    ref.total_weight = sum_w;
    ref.max_overlap = d_max;
    ref.runs = 1;
    out.push_back(ref);
    i = b + 1;
  }

  // 2. Combination (CONTACT combine_cpatches): walk from the field side (largest q, the back)
  // inwards; the current outer patch absorbs its inner neighbour when their facing ends are
  // within combine_distance and their angles within separate_angle. Absorbed entries get runs = 0.
  if (options.combine_distance > 0.0 && out.size() > 1) {
    std::size_t cur = out.size() - 1;
    for (std::size_t k = out.size() - 1; k-- > 0;) {
      OverlapReference& outer = out[cur];
      OverlapReference& inner = out[k];
      const double dist = facing_distance(band, outer, inner);
      const double dangle = outer.contact_angle_side - inner.contact_angle_side;
      if (dist > options.combine_distance || std::abs(dangle) > options.separate_angle) {
        cur = k;
        continue;
      }
      const double total = outer.total_weight + inner.total_weight;
      const double f = total > 0.0 ? inner.total_weight / total : 0.5;
      outer.q += f * (inner.q - outer.q);
      outer.contact_angle_side += f * (inner.contact_angle_side - outer.contact_angle_side);
      outer.total_weight = total;
      outer.max_overlap = std::max(outer.max_overlap, inner.max_overlap);
      outer.s_start = std::min(outer.s_start, inner.s_start);
      outer.s_end = std::max(outer.s_end, inner.s_end);
      outer.runs += inner.runs;
      outer.clipped = outer.clipped || inner.clipped;
      inner.runs = 0;
    }
    out.erase(std::remove_if(out.begin(), out.end(), [](const OverlapReference& r) { return r.runs == 0; }),
              out.end());
  }

  // 3. Angle blending of neighbours kept apart (CONTACT turn_cpatch_refangle), from the original
  // angles of each pair.
  if (options.turn_distance > options.combine_distance && out.size() > 1) {
    double orig_outer = out.back().contact_angle_side;
    for (std::size_t k = out.size() - 1; k-- > 0;) {
      OverlapReference& outer = out[k + 1];
      OverlapReference& inner = out[k];
      const double orig_inner = inner.contact_angle_side;
      const double dist = facing_distance(band, outer, inner);
      if (std::abs(orig_outer - orig_inner) <= options.separate_angle && dist >= options.combine_distance &&
          dist <= options.turn_distance) {
        const double total = outer.total_weight + inner.total_weight;
        const double combined =
            total > 0.0 ? (orig_outer * outer.total_weight + orig_inner * inner.total_weight) / total
                        : 0.5 * (orig_outer + orig_inner);
        const double fac = (options.turn_distance - dist) / (options.turn_distance - options.combine_distance);
        outer.contact_angle_side += fac * (combined - orig_outer);
        inner.contact_angle_side += fac * (combined - orig_inner);
      }
      orig_outer = orig_inner;
    }
  }

  // 4. The reference point: the rail point at the weighted q and the facing wheel point there.
  const double sigma = outward_sign(geometry.side);
  const double theta = geometry.wheel_roll;
  for (OverlapReference& ref : out) {
    const BandPoint p = band_at_q(band, ref.q);
    ref.band_s = p.s;
    ref.rail_u = p.rail_u;
    ref.wheel_u = p.wheel_u;
    ref.z = p.z;
    ref.y_track = sigma * ref.q;
    ref.contact_angle = sigma * ref.contact_angle_side;
    ref.rolling_radius = p.radius;
    ref.overlap = dz * std::cos(p.angle) - p.gap;
    // The facing wheel point sits at P + gap n - dz e_z after the approach; projected on the
    // wheel's radial direction (sin t, -cos t) the rail point P lies nearer the axle by
    // dz cos(t) - gap cos(g - t), the local radial overlap.
    ref.loaded_rolling_radius = p.radius - (dz * std::cos(theta) - p.gap * std::cos(p.angle - theta));
  }
  return out;
}

}  // namespace railtab
