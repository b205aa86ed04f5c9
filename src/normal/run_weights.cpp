// SPDX-License-Identifier: Apache-2.0
// Overlap-run weights of the point models: how points sharing one run of rigid overlap share its
// load (normal_internal.hpp, "Overlap-run weights").

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

bool uses_run_weight(const PointContext& p) {
  return (p.model == NormalModel::hertz || p.model == NormalModel::linder) && p.hertz_valid;
}

}  // namespace

// Sets PointContext::weight of every point for approach dz (normal_internal.hpp, run weights).
void run_weights(const WheelContactGeometry& g, Workspace& w, double dz) {
  for (PointContext& p : w.points) {
    p.weight = 1.0;
    p.run_group = -1;
  }
  const int n = static_cast<int>(w.order.size());
  int k0 = 0;
  while (k0 < n) {
    // Component [k0, k1]: consecutive weighted, loaded points joined by positive saddle overlap.
    int k1 = k0;
    auto penetration = [&](int k) {
      const PointContext& p = w.points[w.order[k]];
      return (dz - p.h) * p.cos_ref;
    };
    auto saddle_overlap = [&](int k) {  // between order[k] and order[k + 1]
      const BandSample& b = g.band[w.saddle[k]];
      return dz * band_cos(b.contact_angle_side) - b.gap;
    };
    auto joinable = [&](int k) {
      const PointContext& p = w.points[w.order[k]];
      return uses_run_weight(p) && dz > p.h;
    };
    if (joinable(k0))
      while (k1 + 1 < n && joinable(k1 + 1) && saddle_overlap(k1) > 0.0) ++k1;
    for (int k = k0; k <= k1; ++k) w.points[w.order[k]].run_group = k0;
    if (k1 > k0) {
      double prominence_sum = 0.0;
      for (int k = k0; k <= k1; ++k) {
        double ds = 0.0;
        if (k > k0) ds = std::max(ds, saddle_overlap(k - 1));
        if (k < k1) ds = std::max(ds, saddle_overlap(k));
        const double d = penetration(k);
        PointContext& p = w.points[w.order[k]];
        p.weight = std::max(d - ds, 0.0);  // prominence for now
        prominence_sum += p.weight;
      }
      const double m = k1 - k0 + 1;
      for (int k = k0; k <= k1; ++k) {
        PointContext& p = w.points[w.order[k]];
        const double prominence = p.weight, d = penetration(k);
        const double t = std::clamp(prominence / d, 0.0, 1.0);
        const double share = prominence_sum > 0.0 ? prominence / prominence_sum : 1.0 / m;
        p.weight = std::clamp(t + (1.0 - t) * share, 0.0, 1.0);
      }
    }
    k0 = k1 + 1;
  }
  // STRIPES: consecutive loaded points joined by positive rigid overlap at their saddles form one
  // run, evaluated once by its lead (the largest penetration), stripes_patch.
  for (PointContext& p : w.points) {
    p.stripes_lead = p.grp_k0 = p.grp_k1 = -1;
    p.sweight = 1.0;
    p.sblend = 1.0;
  }
  k0 = 0;
  while (k0 < n) {
    auto joinable = [&](int k) {
      const PointContext& p = w.points[w.order[k]];
      return is_stripes(p.model) && dz > p.h;
    };
    auto saddle_overlap = [&](int k) {
      const BandSample& b = g.band[w.saddle[k]];
      return dz * band_cos(b.contact_angle_side) - b.gap;
    };
    int k1 = k0;
    if (joinable(k0))
      while (k1 + 1 < n && joinable(k1 + 1) && saddle_overlap(k1) > 0.0) ++k1;
    if (k1 > k0) {
      int lead = w.order[k0];
      double best = -std::numeric_limits<double>::infinity();
      for (int k = k0; k <= k1; ++k) {
        const PointContext& p = w.points[w.order[k]];
        const double d = (dz - p.h) * p.cos_ref;
        if (d > best) {
          best = d;
          lead = w.order[k];
        }
      }
      double prominence_sum = 0.0;
      for (int k = k0; k <= k1; ++k) {
        PointContext& p = w.points[w.order[k]];
        p.stripes_lead = lead;
        p.grp_k0 = k0;
        p.grp_k1 = k1;
        double ds = 0.0;
        if (k > k0) ds = std::max(ds, saddle_overlap(k - 1));
        if (k < k1) ds = std::max(ds, saddle_overlap(k));
        p.sweight = std::max((dz - p.h) * p.cos_ref - ds, 0.0);  // prominence for now
        prominence_sum += p.sweight;
      }
      // Blend from the per-point patches (the run just joined: saddle overlap 0) to the one-run
      // patch (saddle overlap >= the smallest prominence, e.g. a ripple's): continuous in dz and y.
      double ds_max = 0.0, p_min = std::numeric_limits<double>::infinity();
      for (int k = k0; k < k1; ++k) ds_max = std::max(ds_max, saddle_overlap(k));
      for (int k = k0; k <= k1; ++k) p_min = std::min(p_min, w.points[w.order[k]].sweight);
      const double blend = ds_max >= p_min ? 1.0 : ds_max / p_min;
      const double count = k1 - k0 + 1;
      for (int k = k0; k <= k1; ++k) {
        PointContext& p = w.points[w.order[k]];
        p.sblend = blend;
        const double prominence = p.sweight, d = (dz - p.h) * p.cos_ref;
        const double t = std::clamp(prominence / d, 0.0, 1.0);
        const double share = prominence_sum > 0.0 ? prominence / prominence_sum : 1.0 / count;
        p.sweight = std::clamp(t + (1.0 - t) * share, 0.0, 1.0);
      }
    }
    k0 = k1 + 1;
  }
}

}  // namespace railtab::detail
