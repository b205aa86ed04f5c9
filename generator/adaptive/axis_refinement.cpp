// SPDX-License-Identifier: Apache-2.0
// Generic 1-D grid refinement over a batch sampler (axis_refinement.hpp): midpoint insertion, then
// coarsening; knows nothing of contact.
#include "adaptive/axis_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/check.hpp"

namespace railtab {

std::vector<double> uniform_nodes(double start, double stop, std::size_t intervals) {
  intervals = std::max<std::size_t>(intervals, 1);
  std::vector<double> x;
  for (std::size_t i = 0; i <= intervals; ++i) {
    double f = static_cast<double>(i) / static_cast<double>(intervals);
    x.push_back(i == intervals ? stop : start + f * (stop - start));
  }
  return x;
}

namespace {

// Error of the sample m at xm against the line between (xa, a) and (xb, b), in tolerances.
double line_error(const AxisSample& a, double xa, const AxisSample& b, double xb, const AxisSample& m, double xm) {
  const double t = (xm - xa) / (xb - xa);
  double worst = 0.0;
  for (std::size_t o = 0; o < m.values.size(); ++o) {
    const double tol = std::max({a.tolerance[o], b.tolerance[o], m.tolerance[o]});
    if (!(tol > 0.0)) continue;
    const double line = (1.0 - t) * a.values[o] + t * b.values[o];
    worst = std::max(worst, std::abs(m.values[o] - line) / tol);
  }
  return worst;
}

class Refiner {
 public:
  explicit Refiner(const AxisSampler& sampler) : sampler_(sampler) {}

  void ensure(std::vector<double> x) {
    std::sort(x.begin(), x.end());
    x.erase(std::unique(x.begin(), x.end()), x.end());
    std::vector<double> missing;
    for (double v : x) {
      if (!cache_.count(v)) missing.push_back(v);
    }
    if (missing.empty()) return;
    std::vector<AxisSample> s = sampler_(missing);
    RAILTAB_CHECK(s.size() == missing.size(), "adaptive grid: sampler returned {} samples for {} positions", s.size(),
                  missing.size());
    for (std::size_t i = 0; i < missing.size(); ++i) {
      RAILTAB_CHECK(s[i].values.size() == s[i].tolerance.size(), "adaptive grid: sample without tolerances");
      cache_.emplace(missing[i], std::move(s[i]));
    }
    evaluations_ += missing.size();
  }
  const AxisSample& at(double x) const { return cache_.at(x); }
  std::size_t evaluations() const { return evaluations_; }

  static double mid(double a, double b) { return 0.5 * (a + b); }

  void ensure_midpoints(const std::vector<double>& nodes) {
    std::vector<double> x = nodes;
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) x.push_back(mid(nodes[i], nodes[i + 1]));
    ensure(std::move(x));
  }

  bool jump(double a, double b) const {
    const AxisSample& sa = at(a);
    const AxisSample& sm = at(mid(a, b));
    const AxisSample& sb = at(b);
    return !(sa.regime == sm.regime && sm.regime == sb.regime);
  }
  double error(double a, double b) const {
    return line_error(at(a), a, at(b), b, at(mid(a, b)), mid(a, b));
  }

  // Can node x[i] go? Every cached sample in (x[i-1], x[i+1]) within tolerance, one regime.
  bool removable(double a, double b) const {
    const AxisSample& sa = at(a);
    const AxisSample& sb = at(b);
    if (sa.regime != sb.regime) return false;
    for (auto it = cache_.upper_bound(a); it != cache_.end() && it->first < b; ++it) {
      if (it->second.regime != sa.regime) return false;
      if (line_error(sa, a, sb, b, it->second, it->first) > 1.0) return false;
    }
    return true;
  }

  void statistics(AxisRefinement& r, double min_step, const std::vector<double>& exclude = {}) {
    ensure_midpoints(r.nodes);
    r.worst_error = r.unresolved_error = 0.0;
    r.jumps = r.unmet = 0;
    r.discontinuities.clear();
    for (std::size_t i = 0; i + 1 < r.nodes.size(); ++i) {
      double a = r.nodes[i], b = r.nodes[i + 1];
      if (jump(a, b)) {
        ++r.jumps;
        r.discontinuities.push_back(mid(a, b));
        continue;
      }
      double e = error(a, b);
      bool excluded = std::any_of(exclude.begin(), exclude.end(), [&](double v) { return v >= a && v <= b; });
      if (excluded || (e > 1.0 && 0.5 * (b - a) < min_step)) {  // at min_step and still above: a
        ++r.unmet;                                                //   discontinuity the status does not show
        r.unresolved_error = std::max(r.unresolved_error, e);
        r.discontinuities.push_back(mid(a, b));
        continue;
      }
      if (e > r.worst_error) {
        r.worst_error = e;
        r.worst_error_at = mid(a, b);
      }
    }
    r.evaluations = evaluations_;
  }

 private:
  const AxisSampler& sampler_;
  std::map<double, AxisSample> cache_;
  std::size_t evaluations_ = 0;
};

}  // namespace

nlohmann::json AxisRefinement::to_json() const {
  double smallest = 0.0, largest = 0.0;
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    double h = nodes[i + 1] - nodes[i];
    smallest = i == 0 ? h : std::min(smallest, h);
    largest = std::max(largest, h);
  }
  return {{"axis", axis},         {"nodes", nodes.size()},         {"min_step", smallest},
          {"max_step", largest},  {"worst_midpoint_error", worst_error}, {"worst_at", worst_error_at},
          {"jumps", jumps},       {"unmet", unmet}, {"unmet_worst_error", unresolved_error}, {"met", met()}, {"evaluations", evaluations}};
}

AxisRefinement refine_axis(const AxisSampler& sampler, const AdaptiveAxisSpec& spec, int max_passes) {
  RAILTAB_CHECK(spec.stop > spec.start && spec.min_step > 0.0 && spec.max_step >= spec.min_step,
                "adaptive grid {}: need stop > start and 0 < min_step <= max_step (got {}, {}, {}, {})", spec.axis,
                spec.start, spec.stop, spec.min_step, spec.max_step);
  Refiner f(sampler);
  AxisRefinement r;
  r.axis = spec.axis;
  const double eps = 1e-9 * spec.min_step;
  auto intervals = static_cast<std::size_t>(std::ceil((spec.stop - spec.start) / spec.max_step - 1e-9));
  std::vector<double> x = uniform_nodes(spec.start, spec.stop, intervals);

  // Refinement: bisect every interval above tolerance or across a regime change.
  for (; r.passes < max_passes; ++r.passes) {
    f.ensure_midpoints(x);
    std::vector<double> next{x.front()};
    bool changed = false;
    for (std::size_t i = 0; i + 1 < x.size(); ++i) {
      const double a = x[i], b = x[i + 1];
      const bool splittable = 0.5 * (b - a) >= spec.min_step - eps;
      if (splittable && (f.jump(a, b) || f.error(a, b) > 1.0)) {
        next.push_back(Refiner::mid(a, b));
        changed = true;
      }
      next.push_back(b);
    }
    x.swap(next);
    if (!changed) break;
  }

  // Coarsening: drop every other removable node per pass (non-adjacent, so removals are independent).
  for (int pass = 0; pass < max_passes; ++pass, ++r.passes) {
    std::vector<std::size_t> candidates;
    std::vector<double> merged_mid;
    for (std::size_t i = 1; i + 1 < x.size(); ++i) {
      if (!candidates.empty() && candidates.back() + 1 >= i) continue;
      if (x[i + 1] - x[i - 1] > spec.max_step + eps) continue;
      if (f.jump(x[i - 1], x[i]) || f.jump(x[i], x[i + 1])) continue;
      candidates.push_back(i);
      merged_mid.push_back(Refiner::mid(x[i - 1], x[i + 1]));
    }
    f.ensure(merged_mid);
    std::vector<char> drop(x.size(), 0);
    bool changed = false;
    for (std::size_t i : candidates) {
      if (f.removable(x[i - 1], x[i + 1])) drop[i] = changed = true;
    }
    if (!changed) break;
    std::vector<double> next;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!drop[i]) next.push_back(x[i]);
    }
    x.swap(next);
  }
  r.nodes = x;
  f.statistics(r, spec.min_step);
  return r;
}

AxisRefinement check_axis(const AxisSampler& sampler, const std::string& axis, const std::vector<double>& nodes,
                          const std::vector<double>& exclude) {
  Refiner f(sampler);
  AxisRefinement r;
  r.axis = axis;
  r.nodes = nodes;
  f.statistics(r, 0.0, exclude);
  return r;
}

}  // namespace railtab
