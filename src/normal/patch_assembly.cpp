// SPDX-License-Identifier: Apache-2.0
// Patch assembly: the loaded points' contributions grouped by rigid-overlap run and merged into
// the wheel's contact patches (fill), with the single-Hertz shortcut.

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

namespace railtab::detail {

namespace {

// Reference of one rigid-overlap run (geometry/overlap_reference.cpp, default options: squared
// weighting; the constant factor of the weight cancels), found by expanding from a seed sample.
struct RunReference {
  int a = 0, b = -1;                 // first and last band sample of the run
  double s_start = 0.0, s_end = 0.0;
  double band_s = 0.0, rail_u = 0.0, wheel_u = 0.0, angle_side = 0.0, radius = 0.0;
  bool clipped = false;
};

bool rigid_run(const WheelContactGeometry& g, Workspace& ws, double dz, int seed,
               RunReference* out) {
  const std::vector<BandSample>& band = g.band;
  const int n = static_cast<int>(band.size());
  if (seed < 0 || seed >= n) return false;
  double* d = ws.v.data();      // rigid normal overlap per sample (scratch)
  double* c = ws.cosb.data();   // cos of the sample's angle (scratch)
  auto eval = [&](int i) {
    c[i] = band_cos(band[i].contact_angle_side);
    d[i] = dz * c[i] - band[i].gap;
    return d[i];
  };
  if (!(eval(seed) > 0.0)) return false;
  // Expansion: cos g >= 1 - g^2/2 makes dz (1 - g^2/2) - gap > 0 a cheap sufficient test; the
  // exact overlap is evaluated only where it fails (near the ends of the run).
  auto inside = [&](int i) {
    const BandSample& bs = band[i];
    if (dz * (1.0 - 0.5 * bs.contact_angle_side * bs.contact_angle_side) - bs.gap > 0.0) return true;
    return bs.gap < dz && eval(i) > 0.0;
  };
  int a = seed, b = seed;
  while (a > 0 && inside(a - 1)) --a;
  while (b + 1 < n && inside(b + 1)) ++b;
  if (a > 0) eval(a - 1);
  if (b + 1 < n) eval(b + 1);
  // Weight per unit s: p^(5/2) cos g with p = d / cos g (the factor of the weight cancels).
  double* wt = ws.weight.data();
  for (int j = a; j <= b; ++j) eval(j);
  int j0 = a;
#if defined(__SSE2__)
  // Two samples per step: the scalar loop is bound by the latency of divsd/sqrtsd (std::sqrt must
  // also keep errno, which stops the compiler from vectorising it).
  for (; j0 + 1 <= b; j0 += 2) {
    const __m128d cc = _mm_loadu_pd(c + j0);
    const __m128d p = _mm_div_pd(_mm_loadu_pd(d + j0), cc);
    _mm_storeu_pd(wt + j0, _mm_mul_pd(_mm_mul_pd(_mm_mul_pd(p, p), _mm_sqrt_pd(p)), cc));
  }
#endif
  for (int j = j0; j <= b; ++j) {
    const double p = d[j] / c[j];
    wt[j] = p * p * std::sqrt(p) * c[j];
  }
  // Trapezoids on the uniform band: interior samples full weight, the two ends half.
  double sum_w = 0.0, sum_wq = 0.0, sum_wa = 0.0;
  if (b > a) {
    for (int j = a; j <= b; ++j) {
      const BandSample& p = band[j];
      sum_w += wt[j];
      sum_wq += wt[j] * p.q;
      sum_wa += wt[j] * p.contact_angle_side;
    }
    const double ends[2] = {wt[a], wt[b]};
    sum_w -= 0.5 * (ends[0] + ends[1]);
    sum_wq -= 0.5 * (ends[0] * band[a].q + ends[1] * band[b].q);
    sum_wa -= 0.5 * (ends[0] * band[a].contact_angle_side + ends[1] * band[b].contact_angle_side);
    const double step = g.band_step;
    sum_w *= step;
    sum_wq *= step;
    sum_wa *= step;
  }
  constexpr double e = 2.5;
  auto end_cell = [&](int k, int m) {
    const double dk = d[k], dm = d[m];
    const double h = band[m].s - band[k].s;
    const double len = h * dk / (dk - dm);
    const double part = wt[k] * std::abs(len) / (e + 1.0);
    const double t = len / (e + 2.0) / h;
    sum_w += part;
    sum_wq += part * (band[k].q + t * (band[m].q - band[k].q));
    sum_wa += part * (band[k].contact_angle_side + t * (band[m].contact_angle_side - band[k].contact_angle_side));
    return band[k].s + len;
  };
  RunReference& r = *out;
  r = RunReference{};
  r.a = a;
  r.b = b;
  if (a > 0) {
    r.s_start = end_cell(a, a - 1);
  } else {
    r.s_start = band[a].s;
    r.clipped = true;
  }
  if (b + 1 < n) {
    r.s_end = end_cell(b, b + 1);
  } else {
    r.s_end = band[b].s;
    r.clipped = true;
  }
  double q = band[a].q;
  r.angle_side = band[a].contact_angle_side;
  if (sum_w > 0.0) {
    q = sum_wq / sum_w;
    r.angle_side = sum_wa / sum_w;
  }
  // Band point at the weighted q (q grows with s along the band).
  int j = a;
  if (q <= band.front().q) {
    j = 0;
  } else if (q >= band.back().q) {
    j = n - 1;
  } else {
    const auto it = std::partition_point(band.begin(), band.end(),
                                         [q](const BandSample& x) { return x.q <= q; });
    j = static_cast<int>(it - band.begin()) - 1;
  }
  const BandSample& lo = band[j];
  const BandSample& hi = band[std::min(j + 1, n - 1)];
  const double t = (j + 1 < n && hi.q > lo.q) ? std::clamp((q - lo.q) / (hi.q - lo.q), 0.0, 1.0) : 0.0;
  auto mix = [t](double x, double y) { return x + t * (y - x); };
  r.band_s = mix(lo.s, hi.s);
  r.rail_u = mix(lo.rail_u, hi.rail_u);
  r.wheel_u = mix(lo.wheel_u, hi.wheel_u);
  r.radius = mix(lo.rolling_radius, hi.rolling_radius);
  return true;
}

// Merges the contributions parts[k] (k in members, ascending band s) into one patch.
ContactPatch merge_parts(const WheelContactGeometry& g, std::vector<ContactPatch>& parts,
                         const std::vector<int>& members) {
  if (members.size() == 1) return std::move(parts[members.front()]);
  ContactPatch out;
  double length = 0.0;
  std::size_t nstrips = 0;
  for (int k : members) nstrips += parts[k].strips.size();
  out.strips.reserve(nstrips);
  for (int k : members) {
    ContactPatch& p = parts[k];
    out.normal_force += p.normal_force;
    out.area += p.area;
    out.max_pressure = std::max(out.max_pressure, p.max_pressure);
    out.status |= p.status;
    out.strips.insert(out.strips.end(), p.strips.begin(), p.strips.end());
    if (p.strips.empty()) {
      length = std::max(length, 2.0 * p.semi_axis_a);
    } else {
      for (const Strip& st : p.strips) length = std::max(length, st.x_lead - st.x_trail);
    }
  }
  std::sort(out.strips.begin(), out.strips.end(),
            [](const Strip& x, const Strip& y) { return x.s < y.s; });
  const ContactPatch& first = parts[members.front()];
  out.model = first.model;
  out.pressure_shape = first.pressure_shape;
  out.status &= ~status::kLiftOff;
  (void)g;
  // Equivalent ellipse of the merged patch (area and length/width kept, as Kik-Piotrowski's).
  double s_lo = std::numeric_limits<double>::infinity(), s_hi = -s_lo;
  for (int k : members) {
    const ContactPatch& p = parts[k];
    if (!p.strips.empty()) {
      s_lo = std::min(s_lo, p.strips.front().s - 0.5 * p.strips.front().width);
      s_hi = std::max(s_hi, p.strips.back().s + 0.5 * p.strips.back().width);
    } else {
      s_lo = std::min(s_lo, p.band_s - p.semi_axis_b);
      s_hi = std::max(s_hi, p.band_s + p.semi_axis_b);
    }
  }
  const double width = s_hi - s_lo;
  if (out.area > 0.0 && length > 0.0 && width > 0.0) {
    out.semi_axis_a = std::sqrt(out.area / std::numbers::pi) * std::sqrt(length / width);
    out.semi_axis_b = std::sqrt(out.area / std::numbers::pi) * std::sqrt(width / length);
  }
  return out;
}

// Reference of a Hertz patch of one point: the ellipse centre, i.e. the rigid contact point; its
// lateral extent is the ellipse's, band_s -+ b (kProfileEdge when that leaves the band).
void set_ellipse_reference(const WheelContactGeometry& g, const ContactPoint& cp,
                           ContactPatch& patch) {
  patch.band_s = cp.band_s;
  patch.contact_angle = cp.contact_angle;
  patch.rolling_radius = cp.rolling_radius;
  patch.wheel_u = cp.wheel_u;
  patch.rail_u = cp.rail_u;
  patch.s_start = cp.band_s - patch.semi_axis_b;
  patch.s_end = cp.band_s + patch.semi_axis_b;
  if (g.band.size() >= 2 && (patch.s_start < g.band.front().s || patch.s_end > g.band.back().s))
    patch.status |= status::kProfileEdge;
}

}  // namespace

// One loaded point running Hertz: its patch is the ellipse at the point whatever the grouping
// (an unloaded point has a larger separation, so it is never the patch's point_index), so no band
// scan is needed. Writes r in place (its vectors keep their capacity); false: not that case.
bool fill_single_hertz(const WheelContactGeometry& g, const Material& m, const NormalOptions& o,
                       Workspace& w, double dz, WheelNormalResult& r) {
  const int np = static_cast<int>(w.points.size());
  int k = -1;
  for (int i = 0; i < np; ++i) {
    if (!(dz > w.points[i].h)) continue;
    if (k >= 0) return false;
    k = i;
  }
  if (k < 0 || w.points[k].model != NormalModel::hertz) return false;
  r.patches.resize(1);
  ContactPatch& patch = r.patches.front();
  const PatchSums sums = evaluate(g, m, o, w.points[k], w, dz, &patch);
  if (!(sums.normal > 0.0)) return false;
  r.vertical_approach = dz;
  r.carried_load = sums.vertical;
  r.iterations = 0;
  r.status = 0;
  for (const PointContext& p : w.points) r.status |= p.flags;  // as the unloaded parts report
  r.status = (r.status | patch.status) & ~status::kLiftOff;
  r.point_patch.assign(np, -1);
  r.point_patch[k] = 0;
  patch.points = 1;
  patch.point_index = k;
  set_ellipse_reference(g, g.points[k], patch);
  return true;
}

namespace {

WheelNormalResult fill_general(const WheelContactGeometry& g, const Material& m,
                               const NormalOptions& o, Workspace& w, double dz) {
  WheelNormalResult r;
  r.vertical_approach = dz;
  const int np = static_cast<int>(w.points.size());
  r.point_patch.assign(np, -1);
  std::vector<ContactPatch> parts(np);
  std::vector<int> loaded_points;
  for (int i = 0; i < np; ++i) {
    const PatchSums s = evaluate(g, m, o, w.points[i], w, dz, &parts[i]);
    r.carried_load += s.vertical;
    if (s.normal > 0.0) loaded_points.push_back(i);
    r.status |= parts[i].status & ~status::kLiftOff;
  }
  if (loaded_points.empty()) {
    r.status |= status::kLiftOff;
    return r;
  }
  // STRIPES points evaluated by their run's lead (one strip set, stripes.cpp) belong to its patch.
  for (int i = 0; i < np; ++i) {
    const int lead = w.points[i].stripes_lead;
    if (lead >= 0 && lead != i && parts[lead].normal_force > 0.0 &&
        std::find(loaded_points.begin(), loaded_points.end(), i) == loaded_points.end())
      loaded_points.push_back(i);
  }
  // Rigid overlap runs holding the loaded points.
  struct Group {
    RunReference ref;
    bool has_ref = false;
    std::vector<int> members;  // loaded contributions
    int key = -1;              // Hertz: PointContext::run_group of the members
  };
  std::vector<Group> groups;
  const double half_step = 0.5 * g.band_step;
  auto contains = [&](const Group& gr, double s) {
    return gr.has_ref && s >= gr.ref.s_start - half_step && s <= gr.ref.s_end + half_step;
  };
  if (o.combine_patches && g.band.size() >= 2) {
    for (const OverlapReference& ref : overlap_references(g, dz, contact_patch_rules())) {
      Group gr;
      gr.has_ref = true;
      gr.ref.s_start = ref.s_start;
      gr.ref.s_end = ref.s_end;
      gr.ref.band_s = ref.band_s;
      gr.ref.rail_u = ref.rail_u;
      gr.ref.wheel_u = ref.wheel_u;
      gr.ref.angle_side = ref.contact_angle_side;
      gr.ref.radius = ref.rolling_radius;
      gr.ref.clipped = ref.clipped;
      groups.push_back(std::move(gr));
    }
  }
  // Hertz points: grouped by run_weights' runs (positive overlap at the saddles between them), no
  // band scan; the patch of several ellipses is referred to their force-weighted centre below.
  auto hertz_grouped = [&](int i) {
    return !o.combine_patches && w.points[i].model == NormalModel::hertz &&
           w.points[i].run_group >= 0;
  };
  for (int i : loaded_points) {
    if (!hertz_grouped(i)) continue;
    Group* home = nullptr;
    for (Group& gr : groups)
      if (gr.key == w.points[i].run_group) home = &gr;
    if (!home) {
      groups.emplace_back();
      home = &groups.back();
      home->key = w.points[i].run_group;
    }
    home->members.push_back(i);
  }
  for (Group& gr : groups) {
    if (gr.key < 0 || gr.members.size() < 2) continue;
    // Centre of force of the ellipses (each centred at its point); extent: their union.
    double sum = 0.0, s = 0.0, angle = 0.0, radius = 0.0, wu = 0.0, ru = 0.0;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int k : gr.members) {
      const ContactPoint& cp = g.points[k];
      const double f = parts[k].normal_force;
      sum += f;
      s += f * cp.band_s;
      angle += f * cp.contact_angle_side;
      radius += f * cp.rolling_radius;
      wu += f * cp.wheel_u;
      ru += f * cp.rail_u;
      lo = std::min(lo, cp.band_s - parts[k].semi_axis_b);
      hi = std::max(hi, cp.band_s + parts[k].semi_axis_b);
    }
    gr.ref.band_s = s / sum;
    gr.ref.angle_side = angle / sum;
    gr.ref.radius = radius / sum;
    gr.ref.wheel_u = wu / sum;
    gr.ref.rail_u = ru / sum;
    gr.ref.s_start = lo;
    gr.ref.s_end = hi;
    gr.ref.clipped = g.band.size() >= 2 && (lo < g.band.front().s || hi > g.band.back().s);
    gr.has_ref = true;
  }
  for (int i : loaded_points) {
    if (hertz_grouped(i)) continue;
    const double s = g.points[i].band_s;
    Group* home = nullptr;
    for (Group& gr : groups)
      if (contains(gr, s)) home = &gr;
    if (!home) {
      Group gr;
      gr.has_ref = !o.combine_patches && rigid_run(g, w, dz, w.points[i].i0, &gr.ref);
      groups.push_back(std::move(gr));
      home = &groups.back();
    }
    home->members.push_back(i);
  }
  std::erase_if(groups, [](const Group& gr) { return gr.members.empty(); });
  // A Hertz patch of one point is its ellipse: the reference is the point (ellipse centre).
  auto hertz_ellipse = [&](const Group& gr) {
    return gr.members.size() == 1 && w.points[gr.members.front()].model == NormalModel::hertz;
  };
  auto group_s = [&](const Group& gr) {
    return gr.has_ref && !hertz_ellipse(gr) ? gr.ref.band_s : g.points[gr.members.front()].band_s;
  };
  std::sort(groups.begin(), groups.end(),
            [&](const Group& x, const Group& y) { return group_s(x) < group_s(y); });
  const double sigma = outward_sign(g.side);
  r.patches.reserve(groups.size());
  for (const Group& gr : groups) {
    const int pi = static_cast<int>(r.patches.size());
    // Points inside the run: the loaded members and any unloaded point within the extent.
    int best = gr.members.front();
    for (int i = 0; i < np; ++i) {
      const bool member = std::find(gr.members.begin(), gr.members.end(), i) != gr.members.end();
      if (!member && !contains(gr, g.points[i].band_s)) continue;
      if (member) r.point_patch[i] = pi;
      if (g.points[i].separation < g.points[best].separation) best = i;
    }
    std::vector<int> members = gr.members;
    std::sort(members.begin(), members.end(),
              [&](int x, int y) { return g.points[x].band_s < g.points[y].band_s; });
    // The patch takes model, pressure shape and penetration from its least separated member.
    int lead = members.front();
    for (int k : members)
      if (g.points[k].separation < g.points[lead].separation) lead = k;
    const double penetration = parts[lead].penetration;
    const NormalModel model = parts[lead].model;
    ContactPatch patch = merge_parts(g, parts, members);
    patch.model = model;
    patch.penetration = penetration;
    patch.points = static_cast<int>(members.size());
    patch.point_index = best;
    if (hertz_ellipse(gr)) {
      set_ellipse_reference(g, g.points[lead], patch);
    } else if (gr.has_ref) {
      patch.band_s = gr.ref.band_s;
      patch.contact_angle = sigma * gr.ref.angle_side;
      patch.rolling_radius = gr.ref.radius;
      patch.wheel_u = gr.ref.wheel_u;
      patch.rail_u = gr.ref.rail_u;
      patch.s_start = gr.ref.s_start;
      patch.s_end = gr.ref.s_end;
      if (gr.ref.clipped) patch.status |= status::kProfileEdge;
    } else {  // no sampled overlap run: the geometric point is the reference
      const ContactPoint& cp = g.points[lead];
      patch.band_s = cp.band_s;
      patch.contact_angle = cp.contact_angle;
      patch.rolling_radius = cp.rolling_radius;
      patch.wheel_u = cp.wheel_u;
      patch.rail_u = cp.rail_u;
      patch.s_start = patch.strips.empty() ? cp.band_s - patch.semi_axis_b
                                           : patch.strips.front().s - 0.5 * patch.strips.front().width;
      patch.s_end = patch.strips.empty() ? cp.band_s + patch.semi_axis_b
                                         : patch.strips.back().s + 0.5 * patch.strips.back().width;
    }
    r.patches.push_back(std::move(patch));
  }
  if (r.patches.size() > 1) r.status |= status::kTwoPoint;
  return r;
}

}  // namespace

void fill(const WheelContactGeometry& g, const Material& m, const NormalOptions& o, Workspace& w,
          double dz, WheelNormalResult& out) {
  run_weights(g, w, dz);
  if (fill_single_hertz(g, m, o, w, dz, out)) return;
  out = fill_general(g, m, o, w, dz);
}

}  // namespace railtab::detail
