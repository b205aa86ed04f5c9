// SPDX-License-Identifier: Apache-2.0
// Speed against accuracy: times and errors of every model setting and of table lookup at the
// states.
#include "speed_accuracy/speed_accuracy.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <railtab/lookup.hpp>
#include <sstream>
#include <toml++/toml.h>

#include "speed_accuracy/speed_accuracy_states.hpp"
#include "core/check.hpp"
#include "kernel/contact_kernel.hpp"
#include "kernel/halfspace_contact.hpp"
#include "adaptive/jump_locator.hpp"
#include "engine/sweep.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

namespace lk = railtab::lookup;
using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// CONTACT block C material (README): E = 210 GPa, nu = 0.28.
constexpr double kContactPoisson = 0.28;
constexpr double kContactYoungs = 210e9;

double us_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::erase_if(v, [](double x) { return !std::isfinite(x); });
  if (v.empty()) return kNaN;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m), v.end());
  double hi = v[m];
  if (v.size() % 2 == 1) return hi;
  return 0.5 * (hi + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(m)));
}

double percentile(std::vector<double> v, double q) {
  std::erase_if(v, [](double x) { return !std::isfinite(x); });
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  const double f = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

// ---------------------------------------------------------------------------------------------
// Scenes derived from the user's: no roll, the states' load and friction, CONTACT's material when
// comparing with CONTACT, and (for tables) the grids. Done on the TOML text so that a table's
// stored scene text describes exactly what was computed.

toml::array to_array(const std::vector<double>& v) {
  toml::array a;
  for (double x : v) a.push_back(x);
  return a;
}

struct Grids {
  std::vector<double> y, xi, eta, phi;
  // The scene's own creepage lists: keep its creep coordinates (normalised nodes, knees, law
  // spin) so that the table is the one `railtab generate` makes of those lists.
  bool scene_creep = false;
};

// The [grid] keys that define how a table stores its creepages (docs/scenes.md).
constexpr const char* kCreepCoordinateKeys[] = {"creep_coordinates", "creep_knee", "creep_law_spin"};

Scene derive_scene(const Scene& base, double load, double friction, bool contact_material, const Grids* grids,
                   const char* normal_model = nullptr) {
  toml::table t = toml::parse(base.text);
  if (contact_material) {
    if (!t.contains("material")) t.insert("material", toml::table{});
    toml::table& m = *t["material"].as_table();
    m.insert_or_assign("youngs_modulus", kContactYoungs);
    m.insert_or_assign("poisson_ratio", kContactPoisson);
  }
  if (!t.contains("contact")) t.insert("contact", toml::table{});
  t["contact"].as_table()->insert_or_assign("friction", friction);
  if (normal_model) t["contact"].as_table()->insert_or_assign("normal_model", normal_model);
  toml::table g;
  if (grids && grids->scene_creep && t["grid"].as_table()) {
    for (const char* key : kCreepCoordinateKeys)
      if (const toml::node* n = t["grid"].as_table()->get(key)) g.insert(key, *n);
  }
  g.insert("y", grids ? to_array(grids->y) : to_array({0.0}));
  g.insert("equilibrium_roll", false);
  g.insert("roll", 0.0);
  g.insert("load", load);
  g.insert("xi", grids ? to_array(grids->xi) : to_array({0.0}));
  g.insert("eta", grids ? to_array(grids->eta) : to_array({0.0}));
  g.insert("phi", grids ? to_array(grids->phi) : to_array({0.0}));
  t.insert_or_assign("grid", std::move(g));
  std::ostringstream text;
  text << "# derived by railtab chart (speed against accuracy) from scene '" << base.name << "'\n" << t << "\n";
  return parse_scene(text.str(), base.name + " (speed-accuracy)",
                     base.path.empty() ? std::filesystem::path{} : base.path.parent_path());
}

// ---------------------------------------------------------------------------------------------
// One evaluation of the full chain.

struct Chain {
  const ContactGeometrySolver* solver = nullptr;
  Material material;
  NormalOptions normal;
  FastsimOptions fastsim;
  CreepConditions creep;
  WearOptions wear;
  CoupledLoadOptions coupling;
  halfspace::HalfspaceOptions halfspace;  // normal model halfspace
};

// The exact half-space model (the reference without CONTACT data): normal and steady rolling, with
// the scene's load coupling as for the fast models.
SaOutcome evaluate_exact(const Chain& c, const WheelContactGeometry& g, const SaState& s) {
  SaOutcome out;
  const Creepage creepage{s.xi, s.eta, s.phi};
  halfspace::Workspace& ws = thread_halfspace_workspace();
  halfspace::WheelHalfspaceResult r;
  if (c.coupling.couple) {
    r = halfspace::solve_halfspace_rolling(g, s.load, creepage, s.friction, c.material, c.halfspace, ws);
  } else {
    r = halfspace::solve_halfspace_for_load(g, s.load, c.material, c.halfspace, ws);
    halfspace::solve_halfspace_tangential(r, creepage, s.friction, c.material, c.halfspace, ws);
  }
  double fmax = -1.0;
  for (const halfspace::HalfspacePatch& p : r.patches) {
    if (!(p.normal.normal_force > 0.0)) continue;
    out.fx += p.tangential.fx;
    out.fy += p.tangential.fy;
    out.fn += p.normal.normal_force;
    out.area += p.normal.area;
    out.pmax = std::max(out.pmax, p.normal.max_pressure);
    if (p.normal.normal_force > fmax) {
      fmax = p.normal.normal_force;
      out.angle = p.contact_angle;
    }
    out.ok = true;
  }
  return out;
}

SaOutcome evaluate(const Chain& c, const SaState& s, FastsimWorkspace& ws, WearDistribution& dist,
                   double& sink) {
  SaOutcome out;
  const WheelContactGeometry g = c.solver->solve_wheel(Side::right, WheelsetState{s.y, 0.0});
  if (c.normal.model == NormalModel::halfspace) return evaluate_exact(c, g, s);
  CreepConditions cc = c.creep;
  cc.friction = s.friction;
  const Creepage creepage{s.xi, s.eta, s.phi};
  // The load is carried by normal and creep forces together (load coupling, scene key
  // load_coupling).
  CoupledLoadResult coupled;
  solve_coupled_load(g, s.load, solve_normal_for_load(g, s.load, c.material, c.normal), c.material, c.normal,
                     fastsim_tangential(g, [&](std::size_t, const ContactPatch&) { return creepage; }, cc,
                                        c.material, c.fastsim, ws),
                     c.coupling, coupled);
  const WheelNormalResult& n = coupled.normal;
  double fmax = -1.0;
  for (const ContactPatch& p : n.patches) {
    if (!(p.normal_force > 0.0)) continue;
    const FastsimResult f = fastsim_contact(g, p, creepage, cc, c.material, c.fastsim, ws);
    const WearResult w = archard_wear(ws, c.wear, dist);
    sink += w.wear_rate;
    out.fx += f.fx;
    out.fy += f.fy;
    out.fn += p.normal_force;
    out.area += p.area;
    out.pmax = std::max(out.pmax, p.max_pressure);
    if (p.normal_force > fmax) {
      fmax = p.normal_force;
      out.angle = p.contact_angle;
    }
    out.ok = true;
  }
  return out;
}

SaOutcome from_lookup(const lk::Result& r) {
  SaOutcome out;
  double fmax = -1.0;
  for (int k = 0; k < r.n_slots; ++k) {
    const lk::Contact& c = r.contact[k];
    const double fn = c.value[lk::kNormalForce];
    if (!(fn > 0.0)) continue;
    out.fn += fn;
    out.fx += c.value[lk::kFx];
    out.fy += c.value[lk::kFy];
    out.area += c.value[lk::kArea];
    out.pmax = std::max(out.pmax, c.value[lk::kMaxPressure]);
    if (fn > fmax) {
      fmax = fn;
      out.angle = c.value[lk::kContactAngle];
    }
    out.ok = true;
  }
  return out;
}

// Errors of one row over the states (fills the err_* and counts).
void summarise_errors(SaRow& row, const std::vector<SaState>& states, const std::vector<SaOutcome>& out,
                      std::vector<double>& err_force_per_state) {
  std::vector<double> all, tread, flange, area, pmax, angle;
  err_force_per_state.assign(states.size(), kNaN);
  for (std::size_t i = 0; i < states.size(); ++i) {
    const SaState& s = states[i];
    if (!out[i].ok) {
      ++row.n_failed;
      continue;
    }
    if (s.creep) {
      const double e = force_error(out[i], s);
      err_force_per_state[i] = e;
      all.push_back(e);
      (s.flange ? flange : tread).push_back(e);
    } else if (s.normal_reliable && s.ref_area > 0.0) {
      area.push_back(std::abs(out[i].area / s.ref_area - 1.0));
      pmax.push_back(std::abs(out[i].pmax / s.ref_pmax - 1.0));
      angle.push_back(std::abs(out[i].angle - s.ref_angle) * 1e3);
    }
  }
  row.err_force = median(all);
  row.err_force_p90 = percentile(all, 0.9);
  row.err_force_tread = median(tread);
  row.err_force_flange = median(flange);
  row.err_area = median(area);
  row.err_pmax = median(pmax);
  row.err_angle_mrad = median(angle);
  row.n_creep = static_cast<int>(all.size());
  row.n_normal = static_cast<int>(area.size());
}

void summarise_times(SaRow& row, const std::vector<SaState>& states, const std::vector<double>& t) {
  std::vector<double> tread, flange;
  for (std::size_t i = 0; i < states.size(); ++i) (states[i].flange ? flange : tread).push_back(t[i]);
  row.time_us = median(t);
  row.time_tread_us = median(tread);
  row.time_flange_us = median(flange);
}

std::vector<double> covering(std::vector<double> grid, double lo, double hi) {
  if (grid.empty() || lo < grid.front()) grid.insert(grid.begin(), lo);
  if (hi > grid.back()) grid.push_back(hi);
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }),
             grid.end());
  return grid;
}

std::vector<double> range(double lo, double hi, double step) {
  std::vector<double> v;
  const int n = static_cast<int>(std::lround((hi - lo) / step));
  for (int i = 0; i <= n; ++i) v.push_back(lo + i * step);
  return v;
}

}  // namespace

double force_error(const SaOutcome& out, const SaState& s) {
  const double ref = std::hypot(s.ref_fx, s.ref_fy);
  if (!(ref > 0.0)) return kNaN;
  return std::hypot(out.fx - s.ref_fx, out.fy - s.ref_fy) / ref;
}

std::vector<bool> pareto_front(const std::vector<double>& time, const std::vector<double>& error) {
  const std::size_t n = time.size();
  std::vector<bool> front(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(time[i]) || !std::isfinite(error[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j) {
      if (j == i || !std::isfinite(time[j]) || !std::isfinite(error[j])) continue;
      dominated = time[j] <= time[i] && error[j] <= error[i] && (time[j] < time[i] || error[j] < error[i]);
    }
    front[i] = !dominated;
  }
  return front;
}

// CONTACT's block C runs are the built-in S1002 wheel on the built-in UIC60 rail at 1:40: a scene
// with other profiles (a measured worn pair) or another cant is compared with the fallback
// reference.
bool contact_reference_applies(const Scene& scene) {
  return scene.wheel.name == "s1002" && scene.wheel.file.empty() && scene.rail.name == "uic60" &&
         scene.rail.file.empty() && scene.track.rail_inclination == 1.0 / 40.0;
}

namespace {

// One measurement's shared state: the scene, the options, the chain every setting starts from,
// the evaluation workspaces and the sink that keeps the timed work observable.
struct Measurement {
  const Scene& scene;
  const SpeedAccuracyOptions& opt;
  SpeedAccuracyResult& res;
  const ContactGeometrySolver& solver;
  Chain base;
  double load = 0.0;
  double friction = 0.0;
  bool have_ref = false;
  FastsimWorkspace ws;
  WearDistribution dist;
  double sink = 0.0;

  std::size_t ns() const { return res.states.size(); }
};

// The chain of the scene the models run on (no roll, CONTACT's material when comparing with CONTACT).
Chain base_chain(const Scene& mscene, const ContactGeometrySolver& solver) {
  Chain base;
  base.solver = &solver;
  base.material = mscene.material;
  base.normal = mscene.normal;
  base.fastsim = fastsim_options(mscene);
  base.creep = creep_conditions(mscene);
  base.wear = wear_options(mscene);
  base.coupling = coupled_load_options(mscene);
  base.halfspace = halfspace_options(mscene);
  return base;
}

// Without CONTACT's results: the reference forces of every state from the exact half-space model
// (default) or a fine fast-model setting.
void fallback_reference(Measurement& m) {
  const SpeedAccuracyOptions& opt = m.opt;
  SpeedAccuracyResult& res = m.res;
  const char* no_contact_reason = contact_reference_applies(m.scene)
                                      ? "no CONTACT reference found"
                                      : "CONTACT's reference is S1002 on UIC60 at 1:40, not this scene's pair";
  Chain c = m.base;
  c.normal.model = opt.fallback_reference.model;
  c.normal.strips = opt.fallback_reference.strips;
  c.fastsim.elements_per_strip = opt.fallback_reference.elements;
  for (SaState& s : res.states) {
    const SaOutcome o = evaluate(c, s, m.ws, m.dist, m.sink);
    s.ref_fx = o.fx;
    s.ref_fy = o.fy;
    s.ref_area = o.area;
    s.ref_pmax = o.pmax;
    s.ref_angle = o.angle;
  }
  res.exact_reference = opt.fallback_reference.model == NormalModel::halfspace;
  res.reference = res.exact_reference
                      ? fmt::format("exact half-space model (railtab, {:g} mm elements; {})",
                                    m.base.halfspace.element_size * 1e3, no_contact_reason)
                      : fmt::format("finest STRIPES ({}; {})", opt.fallback_reference.label(), no_contact_reason);
}

// The geometry step alone per state (reported beside every model row) [us].
std::vector<double> geometry_times(Measurement& m) {
  const std::vector<SaState>& states = m.res.states;
  std::vector<double> tgeo(m.ns());
  for (std::size_t i = 0; i < m.ns(); ++i) {
    std::vector<double> t;
    for (int r = 0; r <= m.opt.repeats; ++r) {
      const Clock::time_point t0 = Clock::now();
      const WheelContactGeometry g = m.solver.solve_wheel(Side::right, WheelsetState{states[i].y, 0.0});
      const double dt = us_since(t0);
      m.sink += g.points.empty() ? 0.0 : g.points.front().rolling_radius;
      if (r > 0) t.push_back(dt);
    }
    tgeo[i] = median(t);
  }
  return tgeo;
}

// One model setting: the full chain per state, 1 warm-up + repeats, median per state; one row.
void measure_model(Measurement& m, const SaModelSetting& setting, const std::vector<double>& tgeo) {
  const SpeedAccuracyOptions& opt = m.opt;
  const std::vector<SaState>& states = m.res.states;
  const std::size_t ns = m.ns();
  Chain c = m.base;
  c.normal.model = setting.model;
  if (setting.strips > 0) c.normal.strips = setting.strips;
  c.fastsim.elements_per_strip = setting.elements;
  SaRow row;
  row.label = setting.label();
  row.kind = "model";
  row.family = to_string(setting.model);
  row.strips = setting.model == NormalModel::hertz ? 0 : setting.strips;
  row.elements = setting.elements;
  row.time_geometry_us = median(tgeo);
  std::vector<SaOutcome> outs(ns);
  std::vector<double> times(ns);
  const int repeats = setting.model == NormalModel::halfspace ? std::min(opt.repeats, opt.exact_repeats) : opt.repeats;
  for (std::size_t i = 0; i < ns; ++i) {
    try {
      outs[i] = evaluate(c, states[i], m.ws, m.dist, m.sink);  // warm-up, and the result
      std::vector<double> t;
      for (int r = 0; r < repeats; ++r) {
        const Clock::time_point t0 = Clock::now();
        const SaOutcome o = evaluate(c, states[i], m.ws, m.dist, m.sink);
        t.push_back(us_since(t0));
        m.sink += o.fx;
      }
      times[i] = median(t);
    } catch (const std::exception&) {
      outs[i] = SaOutcome{};
      times[i] = kNaN;
    }
  }
  summarise_times(row, states, times);
  std::vector<double> tc(ns);
  for (std::size_t i = 0; i < ns; ++i) tc[i] = times[i] - tgeo[i];
  row.time_contact_us = median(tc);
  std::vector<double> e;
  summarise_errors(row, states, outs, e);
  const std::size_t r = m.res.rows.size();
  m.res.rows.push_back(row);
  for (std::size_t i = 0; i < ns; ++i) m.res.per_state.push_back({r, i, outs[i], times[i], e[i]});
}

// The span of the states, which a table's grid must cover.
struct StateSpan {
  double xlo = 0, xhi = 0, elo = 0, ehi = 0, plo = 0, phi_hi = 0, ylo = 1, yhi = -1;
};

StateSpan state_span(const std::vector<SaState>& states) {
  StateSpan r;
  for (const SaState& s : states) {
    r.xlo = std::min(r.xlo, s.xi), r.xhi = std::max(r.xhi, s.xi);
    r.elo = std::min(r.elo, s.eta), r.ehi = std::max(r.ehi, s.eta);
    r.plo = std::min(r.plo, s.phi), r.phi_hi = std::max(r.phi_hi, s.phi);
    r.ylo = std::min(r.ylo, s.y), r.yhi = std::max(r.yhi, s.y);
  }
  return r;
}

// The grids of a table setting around the states.
Grids table_grids(const Scene& scene, const SaTableSetting& ts, const StateSpan& span) {
  Grids g;
  // Nodes shifted by 0.63 mm against the integer-mm states, so that no state sits on a node
  // (there the lookup would show only the creepage interpolation).
  const double h = ts.y_step;
  const double y0 = span.ylo - 0.63e-3 - h * std::floor(0.63e-3 / h) - h;
  for (double y = y0; y < span.yhi + h; y += h) g.y.push_back(std::round(y * 1e9) * 1e-9);
  if (ts.fine_creep) {
    g.xi = covering(range(-0.004, 0.001, 0.0005), span.xlo, span.xhi);
    g.eta = covering(range(-0.001, 0.003, 0.0005), span.elo, span.ehi);
    g.phi = covering(range(-0.05, 0.15, 0.025), span.plo, span.phi_hi);
  } else if (scene.creep_normalised) {
    // Normalised nodes follow from each list's range and count: the scene's lists unchanged
    // (the states lie inside the default scenes' ranges; outside, the lookup flags them).
    g.xi = scene.grids.xi, g.eta = scene.grids.eta, g.phi = scene.grids.phi;
    g.scene_creep = true;
  } else {
    g.xi = covering(scene.grids.xi, span.xlo, span.xhi);
    g.eta = covering(scene.grids.eta, span.elo, span.ehi);
    g.phi = covering(scene.grids.phi, span.plo, span.phi_hi);
    g.scene_creep = true;
  }
  return g;
}

// Per-state lookup times (for the tread/flange split): 32 queries per sample, median of 15 [us].
std::vector<double> lookup_state_times(Measurement& m, const lk::Table& table, const std::vector<lk::State>& qs) {
  lk::Result r;
  std::vector<double> times(m.ns());
  for (std::size_t i = 0; i < m.ns(); ++i) {
    std::vector<double> t;
    for (int p = 0; p < 15; ++p) {
      const Clock::time_point t0 = Clock::now();
      for (int k = 0; k < 32; ++k) {
        table.query(lk::Wheel::kRight, qs[i], r);
        m.sink += r.contact[1].value[lk::kFy];
      }
      t.push_back(us_since(t0) / 32.0);
    }
    times[i] = median(t);
  }
  return times;
}

// One table file read with one lookup method, queried at the states: one row. `own` is the table's
// own model setting evaluated directly (separates interpolation from model error).
void measure_lookup(Measurement& m, const SaTableSetting& ts, const std::filesystem::path& file, lk::Method method,
                    const std::vector<SaOutcome>& own) {
  const std::vector<SaState>& states = m.res.states;
  const std::size_t ns = m.ns();
  const lk::Table table = lk::Table::load(file.string(), lk::LoadOptions{method});
  std::vector<lk::State> qs(ns);
  std::vector<SaOutcome> outs(ns);
  for (std::size_t i = 0; i < ns; ++i) {
    lk::State q = table.default_state();
    q.y = states[i].y;
    q.roll = 0.0;
    q.load = m.load;
    q.xi = states[i].xi;
    q.eta = states[i].eta;
    q.phi = states[i].phi;
    qs[i] = q;
    outs[i] = from_lookup(table.query(lk::Wheel::kRight, q));
  }
  // Timing: passes over all states, median pass time / states (warm-up pass first).
  lk::Result r;
  std::vector<double> pass;
  for (int p = 0; p <= m.opt.lookup_passes; ++p) {
    const Clock::time_point t0 = Clock::now();
    for (std::size_t i = 0; i < ns; ++i) {
      table.query(lk::Wheel::kRight, qs[i], r);
      m.sink += r.contact[0].value[lk::kFx];
    }
    if (p > 0) pass.push_back(us_since(t0) / static_cast<double>(ns));
  }
  const std::vector<double> times = lookup_state_times(m, table, qs);
  SaRow row;
  const bool linear = method == lk::Method::kLinear;
  row.label = ts.label() + (linear ? "" : " cubic");
  row.kind = "lookup";
  row.family = std::string(linear ? "lookup-linear" : "lookup-cubic") + (ts.exact ? "-exact" : "");
  row.table_y_step = ts.y_step;
  row.table_creep_grid = ts.fine_creep ? "fine" : "scene";
  summarise_times(row, states, times);
  row.time_us = median(pass);
  row.file_bytes = std::filesystem::file_size(file);
  row.memory_bytes = table.memory_bytes();
  std::vector<double> e;
  summarise_errors(row, states, outs, e);
  std::vector<double> ei;
  for (std::size_t i = 0; i < ns; ++i) {
    if (!states[i].creep || !own[i].ok) continue;
    SaState d = states[i];
    d.ref_fx = own[i].fx;
    d.ref_fy = own[i].fy;
    ei.push_back(outs[i].ok ? force_error(outs[i], d) : kNaN);
  }
  row.err_interp = median(ei);
  row.err_interp_p90 = percentile(ei, 0.9);
  const std::size_t ri = m.res.rows.size();
  m.res.rows.push_back(row);
  for (std::size_t i = 0; i < ns; ++i) m.res.per_state.push_back({ri, i, outs[i], times[i], e[i]});
}

// Tables: generated in-process with the contact kernel, written under work_dir, loaded by the
// lookup library and queried at the same states.
void measure_tables(Measurement& m) {
  const SpeedAccuracyOptions& opt = m.opt;
  const std::vector<SaState>& states = m.res.states;
  const std::size_t ns = m.ns();
  RAILTAB_CHECK(!opt.work_dir.empty(), "speed-accuracy: tables need a work directory");
  std::filesystem::create_directories(opt.work_dir);
  const StateSpan span = state_span(states);
  const std::vector<SaTableSetting> tables =
      opt.tables.empty() ? default_table_settings(m.scene.normal.model == NormalModel::halfspace) : opt.tables;
  // The tables' own model setting evaluated directly: separates interpolation from model error
  // (the scene's model, and the exact model for the exact tables).
  std::vector<SaOutcome> direct(ns), direct_exact;
  for (std::size_t i = 0; i < ns; ++i) direct[i] = evaluate(m.base, states[i], m.ws, m.dist, m.sink);
  for (const SaTableSetting& ts : tables) {
    if (ts.exact && direct_exact.empty()) {
      Chain c = m.base;
      c.normal.model = NormalModel::halfspace;
      for (std::size_t i = 0; i < ns; ++i) direct_exact.push_back(evaluate(c, states[i], m.ws, m.dist, m.sink));
    }
    const std::vector<SaOutcome>& own = ts.exact ? direct_exact : direct;
    const Grids g = table_grids(m.scene, ts, span);
    const Scene tscene = derive_scene(m.scene, m.load, m.friction, m.have_ref, &g, ts.exact ? "halfspace" : nullptr);
    SweepOptions so;
    so.threads = opt.table_threads;
    SweepResult sr = run_sweep(tscene, make_contact_kernel(tscene), so);
    // Located contact jumps with their one-sided values, as `railtab generate` adds them: the
    // lookup then does not blend across a jump (the product's tables, not a plainer kind).
    add_jumps(sr.table, tscene, locate_jumps(tscene, {}, opt.table_threads), {}, opt.table_threads);
    const std::filesystem::path file = opt.work_dir / fmt::format("speed_accuracy_y{:g}mm{}{}.h5", ts.y_step * 1e3,
                                                                 ts.fine_creep ? "_fine" : "", ts.exact ? "_exact" : "");
    write_table(sr.table, file);
    std::vector<lk::Method> methods{lk::Method::kLinear};
    if (opt.cubic) methods.push_back(lk::Method::kCubic);
    for (lk::Method method : methods) measure_lookup(m, ts, file, method, own);
    if (!opt.keep_tables) std::filesystem::remove(file);
  }
}

// The Pareto fronts of time against error: over all states, tread states, flange states.
void mark_pareto_fronts(std::vector<SaRow>& rows) {
  std::vector<double> t_all, e_all, t_tr, e_tr, t_fl, e_fl;
  for (const SaRow& r : rows) {
    t_all.push_back(r.time_us), e_all.push_back(r.err_force);
    t_tr.push_back(r.time_tread_us), e_tr.push_back(r.err_force_tread);
    t_fl.push_back(r.time_flange_us), e_fl.push_back(r.err_force_flange);
  }
  const std::vector<bool> pa = pareto_front(t_all, e_all), pt = pareto_front(t_tr, e_tr),
                          pf = pareto_front(t_fl, e_fl);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].pareto_all = pa[i];
    rows[i].pareto_tread = pt[i];
    rows[i].pareto_flange = pf[i];
  }
}

}  // namespace

SpeedAccuracyResult measure_speed_accuracy(const Scene& scene, const SpeedAccuracyOptions& opt) {
  const Clock::time_point start = Clock::now();
  SpeedAccuracyResult res;
  const bool have_ref = !opt.reference_csv.empty() && std::filesystem::exists(opt.reference_csv) &&
                        contact_reference_applies(scene);
  res.contact_reference = have_ref;
  res.states = have_ref ? read_contact_states(opt.reference_csv, opt) : target_states(opt, scene);
  const std::vector<SaState>& st0 = res.states;
  const double load = st0.front().load;
  const double friction = st0.front().friction;
  for (const SaState& s : st0) {
    RAILTAB_CHECK(s.load == load && s.friction == friction,
                  "speed-accuracy: states must share load and friction (tables fix them)");
  }

  // The scene the models run on: no roll, CONTACT's material when comparing with CONTACT.
  const Scene mscene = derive_scene(scene, load, friction, have_ref, nullptr);
  const ContactGeometrySolver solver = make_geometry_solver(mscene);
  Measurement m{scene, opt, res, solver, base_chain(mscene, solver), load, friction, have_ref, {}, {}, 0.0};
  res.setup = fmt::format(
      "right wheel, roll 0, Fz {:g} kN, mu {:g}, E {:g} GPa, nu {:g}, spin {}, negative curvature {}, load coupling {}",
      load * 1e-3, friction, mscene.material.youngs_modulus * 1e-9, mscene.material.poisson_ratio,
      mscene.tangential.spin_per_strip ? "per strip" : "patch-constant", to_string(mscene.normal.negative_curvature),
      mscene.tangential.load_coupling ? "on" : "off");

  if (!have_ref) {
    fallback_reference(m);
  } else {
    res.reference = "CONTACT half-space (block C, ../shared/reference)";
  }
  const std::vector<double> tgeo = geometry_times(m);
  const std::vector<SaModelSetting> models = opt.models.empty() ? default_model_settings() : opt.models;
  for (const SaModelSetting& setting : models) measure_model(m, setting, tgeo);
  if (!opt.no_tables) measure_tables(m);
  mark_pareto_fronts(res.rows);
  if (m.sink == 12345.678) res.reference += " ";  // keeps the timed work observable
  res.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return res;
}

}  // namespace railtab
