#include "sweep/adaptive_grid.hpp"

#include <fmt/format.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "core/check.hpp"
#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "sweep/contact_kernel.hpp"
#include "sweep/model_choice.hpp"
#include "tangential/fastsim_contact.hpp"

namespace railtab {
namespace {

// ---------------------------------------------------------------------------------------------
// Generic 1-D refinement

std::vector<double> uniform_nodes(double start, double stop, std::size_t intervals) {
  intervals = std::max<std::size_t>(intervals, 1);
  std::vector<double> x;
  for (std::size_t i = 0; i <= intervals; ++i) {
    double f = static_cast<double>(i) / static_cast<double>(intervals);
    x.push_back(i == intervals ? stop : start + f * (stop - start));
  }
  return x;
}

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
          {"jumps", jumps},       {"unmet", unmet}, {"unmet_worst_error", unresolved_error},                {"evaluations", evaluations}};
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

// ---------------------------------------------------------------------------------------------
// The contact chain at single states

struct ContactProbe::Data {
  ContactGeometrySolver solver;
  Material material;
  NormalOptions normal;
  CreepConditions creep;
  FastsimOptions fastsim;
  bool equilibrium_roll = false;
  double roll = 0.0;
};

namespace {
namespace slot_bits {
constexpr std::uint32_t kGeometry = 1u << 0;       // a geometric point in the slot
constexpr std::uint32_t kGeometryTwo = 1u << 1;    // two points competed for the slot
constexpr std::uint32_t kLoaded = 1u << 2;         // a loaded patch in the slot
constexpr std::uint32_t kPatchDropped = 1u << 3;   // a third patch was dropped from the slot (its load is missing)
constexpr std::uint32_t kFailed = 1u << 4;         // the core threw
constexpr std::uint32_t kGeometryFirst = 1u << 5;  // of two points in the slot, the kept one has the smaller wheel u
// A slot's values are the sum of its up to two patches (slot_normal, slot_creep), so a second patch
// appearing in a slot with ~0 load is continuous and carries no marker; a patch moving between the
// slots (its angle crossing flange_angle) shows as kLoaded changing when it enters or leaves an
// empty slot, else as an error at min_step (an unmet interval).
}  // namespace slot_bits
}  // namespace

ContactProbe::ContactProbe(const Scene& scene)
    : data_(new Data{make_geometry_solver(scene), scene.material, scene.normal, creep_conditions(scene),
                     fastsim_options(scene), scene.equilibrium_roll, scene.grids.roll.front()}) {}
ContactProbe::~ContactProbe() { delete data_; }

double ContactProbe::roll_at(double y) const { return data_->equilibrium_roll ? data_->solver.equilibrium_roll(y) : data_->roll; }
double ContactProbe::friction() const { return data_->creep.friction; }

std::vector<std::vector<std::array<ContactProbe::Wheel, 2>>> ContactProbe::evaluate(
    double y, const std::vector<double>& loads, const std::vector<std::array<double, 3>>& creepages) const {
  const Data& k = *data_;
  std::vector<std::vector<std::array<Wheel, 2>>> out(loads.size(),
                                                     std::vector<std::array<Wheel, 2>>(creepages.size()));
  FastsimWorkspace& workspace = thread_fastsim_workspace();
  double roll = 0.0;
  try {
    roll = roll_at(y);
  } catch (const std::exception&) {
    for (auto& l : out)
      for (auto& c : l)
        for (auto& w : c) w.slot[0].status = w.slot[1].status = slot_bits::kFailed;
    return out;
  }
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    const Side side = wheel == 0 ? Side::left : Side::right;
    Wheel geo;  // geometry part, copied into every (load, creepage)
    WheelContactGeometry geometry;
    try {
      geometry = k.solver.solve_wheel(side, WheelsetState{y, roll});
    } catch (const std::exception&) {
      for (auto& l : out)
        for (auto& c : l) c[wheel].slot[0].status = c[wheel].slot[1].status = slot_bits::kFailed;
      continue;
    }
    const SlotAssignment slots = assign_slots(geometry);
    for (std::size_t s = 0; s < kSlots; ++s) {
      if (slots.extra[s]) geo.slot[s].status |= slot_bits::kGeometryTwo;
      if (slots.point[s] < 0) continue;
      const ContactPoint& p = geometry.points[static_cast<std::size_t>(slots.point[s])];
      if (slots.extra[s]) {  // which of the competing points is kept: a switch is a jump
        bool first = true;
        for (const ContactPoint& q : geometry.points) {
          const std::size_t qs = (q.status & status::kFlangeContact) ? 1 : 0;
          if (qs == s && q.wheel_u < p.wheel_u) first = false;
        }
        if (first) geo.slot[s].status |= slot_bits::kGeometryFirst;
      }
      geo.slot[s].geometry = true;
      geo.slot[s].status |= slot_bits::kGeometry;
      geo.slot[s].contact_angle = p.contact_angle;
      geo.slot[s].rolling_radius = p.rolling_radius;
    }
    for (std::size_t il = 0; il < loads.size(); ++il) {
      Wheel loaded = geo;
      WheelNormalResult normal;
      PatchSlots patch_slots;
      try {
        normal = solve_normal_for_load(geometry, loads[il], k.material, k.normal);
        patch_slots = assign_patch_slots(normal, side, k.solver.settings().flange_angle);
      } catch (const std::exception&) {
        for (auto& c : out[il]) {
          c[wheel] = geo;
          c[wheel].slot[0].status |= slot_bits::kFailed;
          c[wheel].slot[1].status |= slot_bits::kFailed;
        }
        continue;
      }
      for (std::size_t s = 0; s < kSlots; ++s) {
        if (patch_slots.dropped[s] > 0) loaded.slot[s].status |= slot_bits::kPatchDropped;
        if (!patch_slots.occupied(s)) continue;
        const ContactPatch patch = slot_normal(normal, patch_slots, s);  // as the table stores it
        if (!(patch.normal_force > 0.0)) continue;
        loaded.slot[s].loaded = true;
        loaded.slot[s].status |= slot_bits::kLoaded;
        loaded.slot[s].normal_force = patch.normal_force;
        loaded.slot[s].patch_angle = patch.contact_angle;
        loaded.slot[s].patch_radius = patch.rolling_radius;
        loaded.slot[s].patch_status = patch.status | (normal.status & (status::kConverged | status::kNotConverged));
      }
      for (std::size_t ic = 0; ic < creepages.size(); ++ic) {
        Wheel w = loaded;
        for (std::size_t s = 0; s < kSlots; ++s) {
          if (!w.slot[s].loaded) continue;
          try {
            const auto& c = creepages[ic];
            const FastsimResult r = slot_creep(geometry, normal, patch_slots, s, Creepage{c[0], c[1], c[2]}, k.creep,
                                               k.material, k.fastsim, workspace);
            w.slot[s].fx = r.fx;
            w.slot[s].fy = r.fy;
          } catch (const std::exception&) {
            w.slot[s].status |= slot_bits::kFailed;
          }
        }
        out[il][ic][wheel] = w;
      }
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Samplers of the contact chain

namespace {

struct AxisRange {
  double lo = 0.0, hi = 0.0;
};

AxisRange range_of(const Scene& scene, const std::string& axis) {
  for (const AdaptiveAxisSpec& a : scene.accuracy.axes) {
    if (a.axis == axis) return {a.start, a.stop};
  }
  const SceneGrids& g = scene.grids;
  const std::vector<double>& v = axis == "y" ? g.y : axis == "load" ? g.load : axis == "xi" ? g.xi : axis == "eta" ? g.eta : g.phi;
  return {v.front(), v.back()};
}

// Representative lateral positions: both ends (flange of one wheel each) and the centre (tread).
std::vector<double> y_representatives(const Scene& scene) {
  AxisRange r = range_of(scene, "y");
  std::vector<double> y{r.lo, std::clamp(0.0, r.lo, r.hi), r.hi};
  y.erase(std::unique(y.begin(), y.end()), y.end());
  return y;
}

std::vector<double> load_representatives(const Scene& scene) {
  AxisRange r = range_of(scene, "load");
  return r.hi > r.lo ? std::vector<double>{r.lo, r.hi} : std::vector<double>{r.lo};
}

// Creepage probe level of an axis: `fraction` of the way from 0 to the end of larger magnitude when
// the range holds 0, else from its start; the fixed value of an untabulated axis.
double creep_level(const Scene& scene, const std::string& axis, double fraction) {
  AxisRange r = range_of(scene, axis);
  if (r.hi == r.lo) return r.lo;
  if (r.lo > 0.0 || r.hi < 0.0) return r.lo + fraction * (r.hi - r.lo);
  return fraction * (std::abs(r.lo) > std::abs(r.hi) ? r.lo : r.hi);
}

// The creepage "zero" of an axis: 0 clamped into its range.
double creep_zero(const Scene& scene, const std::string& axis) {
  AxisRange r = range_of(scene, axis);
  return std::clamp(0.0, r.lo, r.hi);
}

// Creepages at which y and load are refined: each creepage alone and combined, at a quarter of range.
std::vector<std::array<double, 3>> creep_probes(const Scene& scene) {
  const double x = creep_level(scene, "xi", 0.25), e = creep_level(scene, "eta", 0.25),
               p = creep_level(scene, "phi", 0.25);
  const double x0 = creep_zero(scene, "xi"), e0 = creep_zero(scene, "eta"), p0 = creep_zero(scene, "phi");
  std::vector<std::array<double, 3>> c{{x, e0, p0}, {x0, e, p0}, {x0, e0, p}, {x, e, p}};
  std::sort(c.begin(), c.end());
  c.erase(std::unique(c.begin(), c.end()), c.end());
  return c;
}

// Parallel batch over positions, deterministic (each position into its own result slot).
template <class F>
std::vector<AxisSample> batch(const std::vector<double>& x, int threads, F f) {
  std::vector<AxisSample> out(x.size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, x.size(), [&](std::size_t i) { out[i] = f(x[i]); });
  });
  return out;
}

struct Targets {
  double creep, angle, radius, normal, mu;
};

// Append the outputs of one wheel-slot result.
void add_geometry(AxisSample& s, const ContactProbe::Slot& slot, const Targets& t) {
  s.values.push_back(slot.contact_angle);
  s.tolerance.push_back(slot.geometry ? t.angle : 0.0);
  s.values.push_back(slot.rolling_radius);
  s.tolerance.push_back(slot.geometry ? t.radius : 0.0);
}
void add_normal(AxisSample& s, const ContactProbe::Slot& slot, const Targets& t) {
  s.values.push_back(slot.normal_force);
  s.tolerance.push_back(t.normal * slot.normal_force);
}
void add_creep(AxisSample& s, const ContactProbe::Slot& slot, const Targets& t) {
  for (double f : {slot.fx, slot.fy}) {
    s.values.push_back(f);
    s.tolerance.push_back(t.creep * t.mu * slot.normal_force);
  }
}

}  // namespace

AxisSampler contact_axis_sampler(const Scene& scene, const ContactProbe& probe, const std::string& axis, int threads) {
  const AccuracyTargets& a = scene.accuracy;
  const Targets t{a.creep_force, a.contact_angle, a.rolling_radius, a.normal_force, probe.friction()};
  const std::vector<double> ys = y_representatives(scene);
  const std::vector<double> loads = load_representatives(scene);
  const std::vector<std::array<double, 3>> probes = creep_probes(scene);
  const ContactProbe* p = &probe;

  if (axis == "y") {
    return [=](const std::vector<double>& x) {
      return batch(x, threads, [&](double y) {
        AxisSample s;
        auto r = p->evaluate(y, loads, probes);
        for (std::size_t w = 0; w < 2; ++w) {
          for (std::size_t sl = 0; sl < kSlots; ++sl) {
            add_geometry(s, r[0][0][w].slot[sl], t);
            s.regime.push_back(r[0][0][w].slot[sl].status & (slot_bits::kGeometry | slot_bits::kGeometryTwo));
          }
        }
        for (std::size_t il = 0; il < loads.size(); ++il) {
          for (std::size_t ic = 0; ic < probes.size(); ++ic) {
            for (std::size_t w = 0; w < 2; ++w) {
              for (std::size_t sl = 0; sl < kSlots; ++sl) {
                const ContactProbe::Slot& slot = r[il][ic][w].slot[sl];
                if (ic == 0) add_normal(s, slot, t);
                add_creep(s, slot, t);
                s.regime.push_back(slot.status);
              }
            }
          }
        }
        return s;
      });
    };
  }
  if (axis == "load") {
    return [=](const std::vector<double>& x) {
      return batch(x, threads, [&](double load) {
        AxisSample s;
        for (double y : ys) {
          auto r = p->evaluate(y, {load}, probes);
          for (std::size_t ic = 0; ic < probes.size(); ++ic) {
            for (std::size_t w = 0; w < 2; ++w) {
              for (std::size_t sl = 0; sl < kSlots; ++sl) {
                const ContactProbe::Slot& slot = r[0][ic][w].slot[sl];
                if (ic == 0) add_normal(s, slot, t);
                add_creep(s, slot, t);
                s.regime.push_back(slot.status);
              }
            }
          }
        }
        return s;
      });
    };
  }
  RAILTAB_CHECK(axis == "xi" || axis == "eta" || axis == "phi", "adaptive grid: axis '{}' cannot be adaptive", axis);
  // Creepage axes: the other two creepages at 0 and at half their range (each combination).
  const std::size_t k = axis == "xi" ? 0 : axis == "eta" ? 1 : 2;
  const char* names[3] = {"xi", "eta", "phi"};
  std::vector<std::array<double, 3>> others{{0, 0, 0}};
  for (std::size_t j = 0; j < 3; ++j) {
    if (j == k) continue;
    const double level = creep_level(scene, names[j], 0.5);
    std::vector<std::array<double, 3>> next;
    for (auto c : others) {
      c[j] = creep_zero(scene, names[j]);
      next.push_back(c);
      if (level != c[j]) {
        c[j] = level;
        next.push_back(c);
      }
    }
    others = next;
  }
  return [=](const std::vector<double>& x) {
    return batch(x, threads, [&](double value) {
      AxisSample s;
      std::vector<std::array<double, 3>> creeps = others;
      for (auto& c : creeps) c[k] = value;
      for (double y : ys) {
        auto r = p->evaluate(y, loads, creeps);
        for (std::size_t il = 0; il < loads.size(); ++il) {
          for (std::size_t ic = 0; ic < creeps.size(); ++ic) {
            for (std::size_t w = 0; w < 2; ++w) {
              for (std::size_t sl = 0; sl < kSlots; ++sl) {
                add_creep(s, r[il][ic][w].slot[sl], t);
                s.regime.push_back(r[il][ic][w].slot[sl].status);
              }
            }
          }
        }
      }
      return s;
    });
  };
}

static std::vector<double>& grid_of(SceneGrids& g, const std::string& axis) {
  if (axis == "y") return g.y;
  if (axis == "load") return g.load;
  if (axis == "xi") return g.xi;
  if (axis == "eta") return g.eta;
  RAILTAB_CHECK(axis == "phi", "adaptive grid: unknown axis '{}'", axis);
  return g.phi;
}

static nlohmann::json model_choice_text(const AccuracyTargets& a) {
  if (a.models.empty()) return "none (the scene's model everywhere)";
  nlohmann::json names = nlohmann::json::array();
  for (NormalModel m : a.models) names.push_back(to_string(m));
  return {{"models", names}, {"per", "y node"}, {"model_tolerance", a.model_tolerance}, {"dataset", "normal_model_index"}};
}

nlohmann::json AdaptiveGridSummary::targets_json(const Scene& scene) const {
  const AccuracyTargets& a = scene.accuracy;
  nlohmann::json specs = nlohmann::json::array();
  for (const AdaptiveAxisSpec& s : a.axes) {
    specs.push_back({{"axis", s.axis}, {"start", s.start}, {"stop", s.stop}, {"max_step", s.max_step},
                    {"min_step", s.min_step}});
  }
  return {{"creep_force", a.creep_force},         {"creep_force_units", "relative to mu N"},
          {"contact_angle", a.contact_angle},     {"rolling_radius", a.rolling_radius},
          {"normal_force", a.normal_force},       {"normal_force_units", "relative to N"},
          {"estimate", "midpoint between neighbouring nodes, linear interpolation"},
          {"model_choice", model_choice_text(a)},
          {"axes", specs}};
}

nlohmann::json AdaptiveGridSummary::achieved_json() const {
  nlohmann::json axes_json = nlohmann::json::array();
  double worst = 0.0;
  for (const AxisRefinement& r : axes) {
    axes_json.push_back(r.to_json());
    worst = std::max(worst, r.worst_error);
  }
  nlohmann::json out = {{"worst_midpoint_error", worst}, {"units", "fraction of the target (<= 1: met)"},
                        {"axes", axes_json}, {"seconds", seconds}};
  if (!model_choice.is_null()) out["model_choice"] = model_choice;
  return out;
}

AdaptiveGridSummary build_adaptive_grids(Scene& scene, int threads) {
  AdaptiveGridSummary summary;
  if (!scene.accuracy.enabled) return summary;
  const auto start = std::chrono::steady_clock::now();
  ContactProbe probe(scene);
  for (const AdaptiveAxisSpec& spec : scene.accuracy.axes) {
    AxisSampler sampler = contact_axis_sampler(scene, probe, spec.axis, threads);
    summary.axes.push_back(refine_axis(sampler, spec));
  }
  for (const AxisRefinement& r : summary.axes) grid_of(scene.grids, r.axis) = r.nodes;
  // The model choice runs on the final grids: one model per y node of the table.
  if (!scene.accuracy.models.empty()) {
    ModelChoice choice = choose_models(scene, threads);
    scene.accuracy.model_by_y = choice.by_y;
    summary.model_choice = choice.to_json();
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

// ---------------------------------------------------------------------------------------------
// Adaptive against uniform

namespace {

std::size_t tabulated_points(const Scene& scene, const SceneGrids& g) {
  std::size_t n = g.y.size() * g.load.size() * g.xi.size() * g.eta.size() * g.phi.size();
  if (!scene.equilibrium_roll) n *= g.roll.size();
  return n;
}

std::size_t table_bytes(const Scene& scene, const SceneGrids& g) {
  const std::size_t column = scene.equilibrium_roll ? 1 : g.roll.size();
  const std::size_t creep = g.load.size() * g.xi.size() * g.eta.size() * g.phi.size();
  // Outputs per part of the contact kernel (contact_kernel.cpp): geometry 7, normal 6, creep 4, wear 1;
  // each part also has a uint32 status; two wheels and two slots.
  const std::size_t per_column = 2 * kSlots * ((7 * 8 + 4) + g.load.size() * (6 * 8 + 4) + creep * (4 * 8 + 4 + 8 + 4));
  return g.y.size() * column * per_column + (scene.equilibrium_roll ? 8 * g.y.size() : 0);
}

// Bracket of v on a grid: lower index and weight of the upper node (clamped).
std::pair<std::size_t, double> bracket(const std::vector<double>& g, double v) {
  if (g.size() == 1) return {0, 0.0};
  auto it = std::upper_bound(g.begin(), g.end(), v);
  std::size_t i = it == g.begin() ? 0 : static_cast<std::size_t>(it - g.begin()) - 1;
  i = std::min(i, g.size() - 2);
  return {i, std::clamp((v - g[i]) / (g[i + 1] - g[i]), 0.0, 1.0)};
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::round(q * static_cast<double>(v.size() - 1)))];
}

struct StateErrors {
  double creep[2] = {-1, -1}, normal[2] = {-1, -1}, angle[2] = {-1, -1};  // per wheel; -1 = not measured
  bool smooth[2] = {true, true};  // every corner of the cell in the direct state's regime (no jump inside)
};

// Multilinear interpolation of the contact chain on grid g at the state, against direct evaluation.
// node_probe: per y node of g, the probe that gives its values (empty: `probe` everywhere).
StateErrors state_errors(const ContactProbe& probe, const SceneGrids& g, const std::vector<const ContactProbe*>& node_probe,
                         double y, double load, const std::array<double, 3>& c,
                         const std::array<ContactProbe::Wheel, 2>& direct) {
  auto [iy, wy] = bracket(g.y, y);
  auto [il, wl] = bracket(g.load, load);
  auto [ix, wx] = bracket(g.xi, c[0]);
  auto [ie, we] = bracket(g.eta, c[1]);
  auto [ip, wp] = bracket(g.phi, c[2]);
  auto node = [](const std::vector<double>& v, std::size_t i, int k) { return v[std::min(i + static_cast<std::size_t>(k), v.size() - 1)]; };
  std::vector<double> loads{node(g.load, il, 0), node(g.load, il, 1)};
  std::vector<std::array<double, 3>> creeps;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int d = 0; d < 2; ++d) creeps.push_back({node(g.xi, ix, a), node(g.eta, ie, b), node(g.phi, ip, d)});
  ContactProbe::Wheel interp[2]{};
  bool tread_everywhere[2] = {true, true};
  bool smooth_cell[2] = {true, true};
  for (int ky = 0; ky < 2; ++ky) {
    const std::size_t jy = std::min(iy + static_cast<std::size_t>(ky), g.y.size() - 1);
    const ContactProbe& values = node_probe.empty() ? probe : *node_probe[jy];
    auto r = values.evaluate(g.y[jy], loads, creeps);
    for (int kl = 0; kl < 2; ++kl) {
      for (std::size_t kc = 0; kc < creeps.size(); ++kc) {
        const int a = static_cast<int>(kc >> 2), b = static_cast<int>((kc >> 1) & 1), d = static_cast<int>(kc & 1);
        const double w = (ky ? wy : 1 - wy) * (kl ? wl : 1 - wl) * (a ? wx : 1 - wx) * (b ? we : 1 - we) * (d ? wp : 1 - wp);
        for (std::size_t wh = 0; wh < 2; ++wh) {
          for (std::size_t s = 0; s < kSlots; ++s) {
            const ContactProbe::Slot& n = r[static_cast<std::size_t>(kl)][kc][wh].slot[s];
            interp[wh].slot[s].fx += w * n.fx;
            interp[wh].slot[s].fy += w * n.fy;
            interp[wh].slot[s].normal_force += w * n.normal_force;
            interp[wh].slot[s].contact_angle += w * n.contact_angle;
            if (s == 0 && !n.geometry && w > 0) tread_everywhere[wh] = false;
            if (n.status != direct[wh].slot[s].status) smooth_cell[wh] = false;
          }
        }
      }
    }
  }
  StateErrors e;
  for (std::size_t wh = 0; wh < 2; ++wh) {
    e.smooth[wh] = smooth_cell[wh];
    double n_total = 0.0, df2 = 0.0, dn2 = 0.0;
    for (std::size_t s = 0; s < kSlots; ++s) {
      const ContactProbe::Slot& d = direct[wh].slot[s];
      const ContactProbe::Slot& i = interp[wh].slot[s];
      n_total += d.normal_force;
      df2 += std::pow(i.fx - d.fx, 2) + std::pow(i.fy - d.fy, 2);
      dn2 += std::pow(i.normal_force - d.normal_force, 2);
    }
    if (n_total > 0.0) {
      e.creep[wh] = std::sqrt(df2) / (probe.friction() * n_total);
      e.normal[wh] = std::sqrt(dn2) / n_total;
    }
    if (tread_everywhere[wh] && direct[wh].slot[0].geometry) {
      e.angle[wh] = std::abs(interp[wh].slot[0].contact_angle - direct[wh].slot[0].contact_angle);
    }
  }
  return e;
}

}  // namespace

GridComparison compare_adaptive_with_uniform(const Scene& base, std::size_t states, unsigned seed, int threads,
                                             const std::vector<std::pair<std::string, SceneGrids>>& others) {
  RAILTAB_CHECK(base.accuracy.enabled, "compare: the scene {} has no [accuracy] section", base.name);
  GridComparison cmp;
  Scene adaptive = base;
  AdaptiveGridSummary summary = build_adaptive_grids(adaptive, threads);
  ContactProbe probe(base);

  cmp.adaptive.name = "adaptive";
  cmp.adaptive.grids = adaptive.grids;
  cmp.uniform.name = "uniform";
  cmp.uniform.grids = adaptive.grids;
  for (std::size_t i = 0; i < summary.axes.size(); ++i) {
    const AdaptiveAxisSpec& spec = base.accuracy.axes[i];
    const AxisRefinement& r = summary.axes[i];
    cmp.adaptive.worst_midpoint.push_back(r.worst_error);
    // The fewest uniform intervals whose worst midpoint error is at most the adaptive grid's.
    AxisSampler sampler = contact_axis_sampler(base, probe, spec.axis, threads);
    auto ok = [&](std::size_t n) {
      return check_axis(sampler, spec.axis, uniform_nodes(spec.start, spec.stop, n), r.discontinuities).worst_error <=
             r.worst_error;
    };
    // Like the adaptive grid, the uniform one keeps step <= max_step: n >= n0.
    const std::size_t cap = static_cast<std::size_t>(std::ceil((spec.stop - spec.start) / spec.min_step)) * 2;
    const auto n0 = static_cast<std::size_t>(std::ceil((spec.stop - spec.start) / spec.max_step - 1e-9));
    std::size_t hi = n0;
    while (hi < cap && !ok(hi)) hi *= 2;
    std::size_t lo = hi == n0 ? n0 - 1 : hi / 2;  // fails (or below n0)
    while (hi - lo > 1) {
      std::size_t m = (lo + hi) / 2;
      (ok(m) ? hi : lo) = m;
    }
    std::vector<double> nodes = uniform_nodes(spec.start, spec.stop, hi);
    cmp.uniform.worst_midpoint.push_back(check_axis(sampler, spec.axis, nodes, r.discontinuities).worst_error);
    grid_of(cmp.uniform.grids, spec.axis) = nodes;
  }
  for (const auto& [name, grids] : others) {
    GridComparison::Grid g;
    g.name = name;
    g.grids = grids;
    for (std::size_t i = 0; i < summary.axes.size(); ++i) {
      const std::string& axis = base.accuracy.axes[i].axis;
      AxisSampler sampler = contact_axis_sampler(base, probe, axis, threads);
      g.worst_midpoint.push_back(check_axis(sampler, axis, grid_of(g.grids, axis), summary.axes[i].discontinuities).worst_error);
    }
    cmp.others.push_back(std::move(g));
  }
  // The per-y model choice on the adaptive grids: node values from each node's model.
  std::vector<std::unique_ptr<ContactProbe>> model_probes;
  if (!adaptive.accuracy.model_by_y.empty()) {
    GridComparison::Grid g;
    g.name = "adaptive, models";
    g.grids = adaptive.grids;
    for (std::size_t i : adaptive.accuracy.model_by_y) g.model_by_y.push_back(adaptive.accuracy.models[i]);
    g.worst_midpoint = cmp.adaptive.worst_midpoint;  // same grids; the midpoint check uses the reference
    cmp.others.push_back(std::move(g));
    for (NormalModel m : adaptive.accuracy.models) {
      Scene variant = base;
      variant.normal.model = m;
      model_probes.push_back(std::make_unique<ContactProbe>(variant));
    }
  }
  std::vector<GridComparison::Grid*> all{&cmp.adaptive, &cmp.uniform};
  for (GridComparison::Grid& g : cmp.others) all.push_back(&g);
  std::vector<std::vector<const ContactProbe*>> node_probes(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) {
    GridComparison::Grid* g = all[k];
    g->points = tabulated_points(base, g->grids);
    g->bytes = table_bytes(base, g->grids);
    for (NormalModel m : g->model_by_y) {
      const auto at = std::find(adaptive.accuracy.models.begin(), adaptive.accuracy.models.end(), m);
      node_probes[k].push_back(model_probes[static_cast<std::size_t>(at - adaptive.accuracy.models.begin())].get());
    }
  }

  // Random off-grid states over the box of the axes, fixed seed.
  std::mt19937 rng(seed);
  auto draw = [&](const std::string& axis) {
    AxisRange r = range_of(base, axis);
    return std::uniform_real_distribution<double>(r.lo, r.hi)(rng);
  };
  struct State {
    double y, load;
    std::array<double, 3> c;
  };
  std::vector<State> drawn(states);
  for (State& s : drawn) s = {draw("y"), draw("load"), {draw("xi"), draw("eta"), draw("phi")}};
  std::vector<std::vector<StateErrors>> errors(states, std::vector<StateErrors>(all.size()));
  tbb::task_arena arena(threads > 0 ? threads : tbb::info::default_concurrency());
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, states, [&](std::size_t i) {
      const State& s = drawn[i];
      auto direct = probe.evaluate(s.y, {s.load}, {s.c})[0][0];
      for (std::size_t k = 0; k < all.size(); ++k) {
        errors[i][k] = state_errors(probe, all[k]->grids, node_probes[k], s.y, s.load, s.c, direct);
      }
    });
  });
  cmp.states = states;
  for (std::size_t k = 0; k < all.size(); ++k) {
    GridComparison::Grid& g = *all[k];
    std::vector<double> creep, normal, angle, creep_smooth;
    for (const auto& e : errors) {
      for (int w = 0; w < 2; ++w) {
        if (e[k].creep[w] >= 0 && e[k].smooth[w]) creep_smooth.push_back(e[k].creep[w]);
        if (e[k].creep[w] >= 0) creep.push_back(e[k].creep[w]);
        if (e[k].normal[w] >= 0) normal.push_back(e[k].normal[w]);
        if (e[k].angle[w] >= 0) angle.push_back(e[k].angle[w]);
      }
    }
    g.creep_median = quantile(creep, 0.5);
    g.creep_p90 = quantile(creep, 0.9);
    g.creep_max = quantile(creep, 1.0);
    g.smooth_share = creep.empty() ? 0.0 : static_cast<double>(creep_smooth.size()) / static_cast<double>(creep.size());
    g.smooth_creep_p90 = quantile(creep_smooth, 0.9);
    g.smooth_creep_max = quantile(creep_smooth, 1.0);
    g.normal_median = quantile(normal, 0.5);
    g.normal_p90 = quantile(normal, 0.9);
    g.normal_max = quantile(normal, 1.0);
    g.angle_median = quantile(angle, 0.5);
    g.angle_max = quantile(angle, 1.0);
  }
  return cmp;
}

std::string GridComparison::text() const {
  std::string out = fmt::format("{} random states (both wheels each), errors against direct evaluation\n", states);
  out += fmt::format("{:<17} {:>5} {:>5} {:>5} {:>5} {:>5} {:>10} {:>10} | {:>24} | {:>8} {:>8} {:>8} | {:>6} {:>8} {:>8} | {:>8} {:>8} {:>8} | {:>9} {:>9}\n",
                     "grid", "ny", "nload", "nxi", "neta", "nphi", "points", "MiB", "worst midpoint/target",
                     "F med%", "F p90%", "F max%", "smooth", "sF p90%", "sF max%", "N med%", "N p90%", "N max%", "ang med", "ang max");
  std::vector<const Grid*> all{&adaptive, &uniform};
  for (const Grid& g : others) all.push_back(&g);
  for (const Grid* g : all) {
    std::string mids;
    for (double m : g->worst_midpoint) mids += fmt::format("{}{:.2f}", mids.empty() ? "" : " ", m);
    out += fmt::format("{:<17} {:>5} {:>5} {:>5} {:>5} {:>5} {:>10} {:>10.2f} | {:>24} | {:>8.3f} {:>8.3f} {:>8.2f} | {:>5.0f}% {:>8.3f} {:>8.2f} | {:>8.3f} {:>8.3f} {:>8.2f} | {:>9.2e} {:>9.2e}\n",
                       g->name, g->grids.y.size(), g->grids.load.size(), g->grids.xi.size(), g->grids.eta.size(),
                       g->grids.phi.size(), g->points, static_cast<double>(g->bytes) / 1048576.0, mids,
                       100 * g->creep_median, 100 * g->creep_p90, 100 * g->creep_max, 100 * g->smooth_share,
                       100 * g->smooth_creep_p90, 100 * g->smooth_creep_max, 100 * g->normal_median,
                       100 * g->normal_p90, 100 * g->normal_max, g->angle_median, g->angle_max);
  }
  return out;
}

}  // namespace railtab
