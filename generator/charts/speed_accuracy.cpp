#include "charts/speed_accuracy.hpp"

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

#include "core/check.hpp"
#include "sweep/contact_kernel.hpp"
#include "sweep/sweep.hpp"
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
// States

struct CreepTarget {
  const char* name;
  double cksi, ceta, cphi;  // CONTACT's targets
};
constexpr CreepTarget kCreepSets[] = {{"a_none", 0, 0, 0},
                                      {"b_long0.001", 0.001, 0, 0},
                                      {"c_lat0.001", 0, 0.001, 0},
                                      {"d_spin0.052", 0, 0, 0.052},
                                      {"e_combined", 0.003, 0.002, 0.1}};

bool wanted(const std::vector<std::string>& sets, const std::string& s) {
  return sets.empty() || std::find(sets.begin(), sets.end(), s) != sets.end();
}
bool wanted(const std::vector<double>& dys, double dy) {
  return dys.empty() || std::any_of(dys.begin(), dys.end(), [dy](double d) { return std::abs(d - dy) < 1e-9; });
}

void classify(SaState& s) {
  s.y = -s.dy_mm * 1e-3;
  s.flange = s.dy_mm >= 6.5;  // CONTACT: flange contact from dy = 6.5 mm
  s.creep = s.xi != 0.0 || s.eta != 0.0 || s.phi != 0.0;
  if (s.creep_set == "a_none") s.creep = false;  // CONTACT's tiny residual creepages are not a case
}

std::vector<SaState> read_contact_states(const std::filesystem::path& path, const SpeedAccuracyOptions& opt) {
  std::ifstream in(path);
  RAILTAB_CHECK(in.good(), "cannot read {}", path.string());
  std::string line;
  std::getline(in, line);
  std::map<std::string, std::size_t> col;
  {
    std::stringstream ss(line);
    std::string name;
    for (std::size_t i = 0; std::getline(ss, name, ','); ++i) col[name] = i;
  }
  for (const char* need : {"dy_mm", "creep_set", "mu", "fz_prescribed_N", "cksi", "ceta", "cphi_rad_per_m",
                           "fx_N", "fs_N", "area_mm2", "pmax_MPa", "contact_angle_rad"}) {
    RAILTAB_CHECK(col.count(need) == 1, "{}: column '{}' missing", path.string(), need);
  }
  std::map<std::pair<double, std::string>, SaState> by_key;  // the file repeats the dy = -6 rows
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    auto num = [&](const char* name) { return std::stod(f.at(col.at(name))); };
    SaState s;
    s.dy_mm = num("dy_mm");
    s.creep_set = f.at(col.at("creep_set"));
    if (!wanted(opt.dy_mm, s.dy_mm) || !wanted(opt.creep_sets, s.creep_set)) continue;
    s.friction = num("mu");
    s.load = num("fz_prescribed_N");
    // Conventions (docs/conventions.md), right wheel: xi = -cksi, eta = +ceta, phi = +cphi,
    // fx = -fx_N, fy = +fs_N. The creepages CONTACT actually used, not the targets.
    s.xi = -num("cksi");
    s.eta = num("ceta");
    s.phi = num("cphi_rad_per_m");
    s.ref_fx = -num("fx_N");
    s.ref_fy = num("fs_N");
    s.ref_area = num("area_mm2") * 1e-6;
    s.ref_pmax = num("pmax_MPa") * 1e6;
    s.ref_angle = num("contact_angle_rad");
    classify(s);
    s.normal_reliable = !(s.creep_set == "a_none" && std::abs(s.dy_mm - 7.0) < 1e-9);  // README outlier
    by_key[{s.dy_mm, s.creep_set}] = s;
  }
  std::vector<SaState> states;
  for (const auto& [key, s] : by_key) states.push_back(s);
  RAILTAB_CHECK(!states.empty(), "{}: no block C state matches the selection", path.string());
  return states;
}

std::vector<SaState> target_states(const SpeedAccuracyOptions& opt, const Scene& scene) {
  std::vector<SaState> states;
  for (int dy = -6; dy <= 10; ++dy) {
    if (!wanted(opt.dy_mm, dy)) continue;
    for (const CreepTarget& c : kCreepSets) {
      if (!wanted(opt.creep_sets, c.name)) continue;
      SaState s;
      s.dy_mm = dy;
      s.creep_set = c.name;
      s.friction = scene.tangential.friction;
      s.xi = -c.cksi;
      s.eta = c.ceta;
      s.phi = c.cphi;
      classify(s);
      states.push_back(s);
    }
  }
  RAILTAB_CHECK(!states.empty(), "speed-accuracy: no state matches the selection");
  return states;
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
};

Scene derive_scene(const Scene& base, double load, double friction, bool contact_material, const Grids* grids) {
  toml::table t = toml::parse(base.text);
  if (contact_material) {
    if (!t.contains("material")) t.insert("material", toml::table{});
    toml::table& m = *t["material"].as_table();
    m.insert_or_assign("youngs_modulus", kContactYoungs);
    m.insert_or_assign("poisson_ratio", kContactPoisson);
  }
  if (!t.contains("contact")) t.insert("contact", toml::table{});
  t["contact"].as_table()->insert_or_assign("friction", friction);
  toml::table g;
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
};

SaOutcome evaluate(const Chain& c, const SaState& s, FastsimWorkspace& ws, WearDistribution& dist,
                   double& sink) {
  SaOutcome out;
  const WheelContactGeometry g = c.solver->solve_wheel(Side::right, WheelsetState{s.y, 0.0});
  const WheelNormalResult n = solve_normal_for_load(g, s.load, c.material, c.normal);
  CreepConditions cc = c.creep;
  cc.friction = s.friction;
  double fmax = -1.0;
  for (const ContactPatch& p : n.patches) {
    if (!(p.normal_force > 0.0)) continue;
    const FastsimResult f = fastsim_contact(g, p, Creepage{s.xi, s.eta, s.phi}, cc, c.material, c.fastsim, ws);
    const WearResult w = archard_wear(ws, c.wear, dist);
    sink += w.wear_rate;
    out.fx += f.fx;
    out.fy += f.fy;
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

std::string SaModelSetting::label() const {
  if (model == NormalModel::hertz) return fmt::format("hertz e{}", elements);
  return fmt::format("{} {}x{}", to_string(model), strips, elements);
}

std::string SaTableSetting::label() const {
  return fmt::format("table y{:g}mm{}", y_step * 1e3, fine_creep ? " fine-creep" : "");
}

std::vector<SaModelSetting> default_model_settings() {
  std::vector<SaModelSetting> v;
  for (int e : {10, 20, 40}) v.push_back({NormalModel::hertz, 0, e});
  for (NormalModel m : {NormalModel::linder, NormalModel::kik_piotrowski}) {
    v.push_back({m, 10, 20});
    v.push_back({m, 25, 20});
    v.push_back({m, 50, 10});
    v.push_back({m, 50, 20});
    v.push_back({m, 50, 40});
    v.push_back({m, 100, 20});
  }
  for (NormalModel m : {NormalModel::stripes_a, NormalModel::stripes_ab})
    for (int s : {10, 25, 50, 100})
      for (int e : {10, 20, 40}) v.push_back({m, s, e});
  return v;
}

std::vector<SaTableSetting> default_table_settings() {
  return {{2e-3, false}, {1e-3, false}, {0.5e-3, false}, {0.25e-3, false}, {0.5e-3, true}, {0.25e-3, true}};
}

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

SpeedAccuracyResult measure_speed_accuracy(const Scene& scene, const SpeedAccuracyOptions& opt) {
  const Clock::time_point start = Clock::now();
  SpeedAccuracyResult res;
  const bool have_ref = !opt.reference_csv.empty() && std::filesystem::exists(opt.reference_csv);
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
  Chain base;
  base.solver = &solver;
  base.material = mscene.material;
  base.normal = mscene.normal;
  base.fastsim = fastsim_options(mscene);
  base.creep = creep_conditions(mscene);
  base.wear = wear_options(mscene);
  res.setup = fmt::format(
      "right wheel, roll 0, Fz {:g} kN, mu {:g}, E {:g} GPa, nu {:g}, spin {}, negative curvature {}", load * 1e-3,
      friction, mscene.material.youngs_modulus * 1e-9, mscene.material.poisson_ratio,
      mscene.tangential.spin_per_strip ? "per strip" : "patch-constant", to_string(mscene.normal.negative_curvature));

  FastsimWorkspace ws;
  WearDistribution dist;
  double sink = 0.0;
  const std::size_t ns = res.states.size();

  if (!have_ref) {
    // Fallback reference: the finest STRIPES A&B discretisation.
    Chain c = base;
    c.normal.model = opt.fallback_reference.model;
    c.normal.strips = opt.fallback_reference.strips;
    c.fastsim.elements_per_strip = opt.fallback_reference.elements;
    for (SaState& s : res.states) {
      const SaOutcome o = evaluate(c, s, ws, dist, sink);
      s.ref_fx = o.fx;
      s.ref_fy = o.fy;
      s.ref_area = o.area;
      s.ref_pmax = o.pmax;
      s.ref_angle = o.angle;
    }
    res.reference = fmt::format("finest STRIPES ({}; no CONTACT reference found)", opt.fallback_reference.label());
  } else {
    res.reference = "CONTACT half-space (block C, ../shared/reference)";
  }
  const std::vector<SaState>& states = res.states;

  // Geometry step alone (reported beside every model row).
  std::vector<double> tgeo(ns);
  for (std::size_t i = 0; i < ns; ++i) {
    std::vector<double> t;
    for (int r = 0; r <= opt.repeats; ++r) {
      const Clock::time_point t0 = Clock::now();
      const WheelContactGeometry g = solver.solve_wheel(Side::right, WheelsetState{states[i].y, 0.0});
      const double dt = us_since(t0);
      sink += g.points.empty() ? 0.0 : g.points.front().rolling_radius;
      if (r > 0) t.push_back(dt);
    }
    tgeo[i] = median(t);
  }
  const double time_geometry = median(tgeo);

  // Models: the full chain per state, 1 warm-up + repeats, median per state.
  const std::vector<SaModelSetting> models = opt.models.empty() ? default_model_settings() : opt.models;
  for (const SaModelSetting& m : models) {
    Chain c = base;
    c.normal.model = m.model;
    if (m.strips > 0) c.normal.strips = m.strips;
    c.fastsim.elements_per_strip = m.elements;
    SaRow row;
    row.label = m.label();
    row.kind = "model";
    row.family = to_string(m.model);
    row.strips = m.model == NormalModel::hertz ? 0 : m.strips;
    row.elements = m.elements;
    row.time_geometry_us = time_geometry;
    std::vector<SaOutcome> outs(ns);
    std::vector<double> times(ns);
    for (std::size_t i = 0; i < ns; ++i) {
      try {
        outs[i] = evaluate(c, states[i], ws, dist, sink);  // warm-up, and the result
        std::vector<double> t;
        for (int r = 0; r < opt.repeats; ++r) {
          const Clock::time_point t0 = Clock::now();
          const SaOutcome o = evaluate(c, states[i], ws, dist, sink);
          t.push_back(us_since(t0));
          sink += o.fx;
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
    const std::size_t r = res.rows.size();
    res.rows.push_back(row);
    for (std::size_t i = 0; i < ns; ++i) res.per_state.push_back({r, i, outs[i], times[i], e[i]});
  }

  // Tables: generated in-process with the contact kernel, written under work_dir, loaded by the
  // lookup library and queried at the same states.
  if (!opt.no_tables) {
    RAILTAB_CHECK(!opt.work_dir.empty(), "speed-accuracy: tables need a work directory");
    std::filesystem::create_directories(opt.work_dir);
    double xlo = 0, xhi = 0, elo = 0, ehi = 0, plo = 0, phi_hi = 0, ylo = 1, yhi = -1;
    for (const SaState& s : states) {
      xlo = std::min(xlo, s.xi), xhi = std::max(xhi, s.xi);
      elo = std::min(elo, s.eta), ehi = std::max(ehi, s.eta);
      plo = std::min(plo, s.phi), phi_hi = std::max(phi_hi, s.phi);
      ylo = std::min(ylo, s.y), yhi = std::max(yhi, s.y);
    }
    const std::vector<SaTableSetting> tables = opt.tables.empty() ? default_table_settings() : opt.tables;
    // The tables' own model setting evaluated directly: separates interpolation from model error.
    std::vector<SaOutcome> direct(ns);
    for (std::size_t i = 0; i < ns; ++i) direct[i] = evaluate(base, states[i], ws, dist, sink);
    for (const SaTableSetting& ts : tables) {
      Grids g;
      // Nodes shifted by 0.63 mm against the integer-mm states, so that no state sits on a node
      // (there the lookup would show only the creepage interpolation).
      const double h = ts.y_step;
      const double y0 = ylo - 0.63e-3 - h * std::floor(0.63e-3 / h) - h;
      for (double y = y0; y < yhi + h; y += h) g.y.push_back(std::round(y * 1e9) * 1e-9);
      if (ts.fine_creep) {
        g.xi = covering(range(-0.004, 0.001, 0.0005), xlo, xhi);
        g.eta = covering(range(-0.001, 0.003, 0.0005), elo, ehi);
        g.phi = covering(range(-0.05, 0.15, 0.025), plo, phi_hi);
      } else {
        g.xi = covering(scene.grids.xi, xlo, xhi);
        g.eta = covering(scene.grids.eta, elo, ehi);
        g.phi = covering(scene.grids.phi, plo, phi_hi);
      }
      const Scene tscene = derive_scene(scene, load, friction, have_ref, &g);
      SweepOptions so;
      so.threads = opt.table_threads;
      const SweepResult sr = run_sweep(tscene, make_contact_kernel(tscene), so);
      const std::filesystem::path file =
          opt.work_dir / fmt::format("speed_accuracy_y{:g}mm{}.h5", h * 1e3, ts.fine_creep ? "_fine" : "");
      write_table(sr.table, file);
      const std::uintmax_t file_bytes = std::filesystem::file_size(file);
      std::vector<lk::Method> methods{lk::Method::kLinear};
      if (opt.cubic) methods.push_back(lk::Method::kCubic);
      for (lk::Method method : methods) {
        const lk::Table table = lk::Table::load(file.string(), lk::LoadOptions{method});
        std::vector<lk::State> qs(ns);
        std::vector<SaOutcome> outs(ns);
        for (std::size_t i = 0; i < ns; ++i) {
          lk::State q = table.default_state();
          q.y = states[i].y;
          q.roll = 0.0;
          q.load = load;
          q.xi = states[i].xi;
          q.eta = states[i].eta;
          q.phi = states[i].phi;
          qs[i] = q;
          outs[i] = from_lookup(table.query(lk::Wheel::kRight, q));
        }
        // Timing: passes over all states, median pass time / states (warm-up pass first).
        lk::Result r;
        std::vector<double> pass;
        std::vector<std::vector<double>> per(ns);
        for (int p = 0; p <= opt.lookup_passes; ++p) {
          const Clock::time_point t0 = Clock::now();
          for (std::size_t i = 0; i < ns; ++i) {
            table.query(lk::Wheel::kRight, qs[i], r);
            sink += r.contact[0].value[lk::kFx];
          }
          if (p > 0) pass.push_back(us_since(t0) / static_cast<double>(ns));
        }
        // Per-state times (for the tread/flange split): 32 queries per sample.
        std::vector<double> times(ns);
        for (std::size_t i = 0; i < ns; ++i) {
          std::vector<double> t;
          for (int p = 0; p < 15; ++p) {
            const Clock::time_point t0 = Clock::now();
            for (int k = 0; k < 32; ++k) {
              table.query(lk::Wheel::kRight, qs[i], r);
              sink += r.contact[1].value[lk::kFy];
            }
            t.push_back(us_since(t0) / 32.0);
          }
          times[i] = median(t);
        }
        SaRow row;
        const bool linear = method == lk::Method::kLinear;
        row.label = ts.label() + (linear ? "" : " cubic");
        row.kind = "lookup";
        row.family = linear ? "lookup-linear" : "lookup-cubic";
        row.table_y_step = h;
        row.table_creep_grid = ts.fine_creep ? "fine" : "scene";
        summarise_times(row, states, times);
        row.time_us = median(pass);
        row.file_bytes = file_bytes;
        row.memory_bytes = table.memory_bytes();
        std::vector<double> e;
        summarise_errors(row, states, outs, e);
        std::vector<double> ei;
        for (std::size_t i = 0; i < ns; ++i) {
          if (!states[i].creep || !direct[i].ok) continue;
          SaState d = states[i];
          d.ref_fx = direct[i].fx;
          d.ref_fy = direct[i].fy;
          ei.push_back(outs[i].ok ? force_error(outs[i], d) : kNaN);
        }
        row.err_interp = median(ei);
        row.err_interp_p90 = percentile(ei, 0.9);
        const std::size_t ri = res.rows.size();
        res.rows.push_back(row);
        for (std::size_t i = 0; i < ns; ++i) res.per_state.push_back({ri, i, outs[i], times[i], e[i]});
      }
      if (!opt.keep_tables) std::filesystem::remove(file);
    }
  }

  // Pareto fronts.
  std::vector<double> t_all, e_all, t_tr, e_tr, t_fl, e_fl;
  for (const SaRow& r : res.rows) {
    t_all.push_back(r.time_us), e_all.push_back(r.err_force);
    t_tr.push_back(r.time_tread_us), e_tr.push_back(r.err_force_tread);
    t_fl.push_back(r.time_flange_us), e_fl.push_back(r.err_force_flange);
  }
  const std::vector<bool> pa = pareto_front(t_all, e_all), pt = pareto_front(t_tr, e_tr),
                          pf = pareto_front(t_fl, e_fl);
  for (std::size_t i = 0; i < res.rows.size(); ++i) {
    res.rows[i].pareto_all = pa[i];
    res.rows[i].pareto_tread = pt[i];
    res.rows[i].pareto_flange = pf[i];
  }
  if (sink == 12345.678) res.reference += " ";  // keeps the timed work observable
  res.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return res;
}

namespace {
std::string num(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("nan"); }

void header_comments(std::ostream& out, const SpeedAccuracyResult& r) {
  out << "# railtab chart: speed against accuracy (docs/speed-vs-accuracy.md)\n";
  out << "# reference: " << r.reference << "\n";
  out << "# set-up: " << r.setup << "\n";
  out << "# error measure: err_force = |F - F_ref| / |F_ref|, F = (fx, fy) creep force on the wheel summed over "
         "patches, states with creepage; medians (p90 = 90th percentile); tread = dy <= 6 mm, flange = dy >= 7 mm; "
         "err_area, err_pmax = |q/q_ref - 1| and err_angle = |angle - angle_ref| on states without creepage "
         "(CONTACT's dy = 7 mm a_none outlier excluded)\n";
  out << "# time: models = full chain geometry + normal + FASTSIM + Archard per state (median of repeats after a "
         "warm-up, then median over states), time_geometry = the geometry step alone; lookups = Table::query of "
         "both slots of the right wheel; one thread, steady_clock\n";
}
}  // namespace

void write_speed_accuracy_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path) {
  std::ofstream out(path);
  RAILTAB_CHECK(out.good(), "cannot write {}", path.string());
  header_comments(out, result);
  out << "label,kind,family,strips,elements,table_y_step_mm,table_creep_grid,time_us,time_tread_us,"
         "time_flange_us,time_geometry_us,time_contact_us,err_force,err_force_p90,err_force_tread,err_force_flange,err_area,"
         "err_pmax,err_angle_mrad,n_creep,n_normal,n_failed,table_file_bytes,table_memory_bytes,pareto_all,"
         "pareto_tread,pareto_flange,err_interp,err_interp_p90,reference\n";
  for (const SaRow& r : result.rows) {
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                       r.label, r.kind, r.family, r.strips, r.elements, num(r.table_y_step * 1e3),
                       r.table_creep_grid, num(r.time_us), num(r.time_tread_us), num(r.time_flange_us),
                       num(r.time_geometry_us), num(r.time_contact_us), num(r.err_force), num(r.err_force_p90), num(r.err_force_tread),
                       num(r.err_force_flange), num(r.err_area), num(r.err_pmax), num(r.err_angle_mrad), r.n_creep,
                       r.n_normal, r.n_failed, r.file_bytes, r.memory_bytes, int(r.pareto_all),
                       int(r.pareto_tread), int(r.pareto_flange), num(r.err_interp), num(r.err_interp_p90),
                       result.contact_reference ? "contact" : "stripes");
  }
}

void write_states_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path) {
  std::ofstream out(path);
  RAILTAB_CHECK(out.good(), "cannot write {}", path.string());
  header_comments(out, result);
  out << "label,dy_mm,y_m,creep_set,xi,eta,phi_rad_per_m,flange,fx_N,fy_N,ref_fx_N,ref_fy_N,err_force,area_m2,"
         "ref_area_m2,pmax_Pa,ref_pmax_Pa,contact_angle_rad,ref_contact_angle_rad,time_us\n";
  for (const SaStateRow& p : result.per_state) {
    const SaState& s = result.states[p.state];
    out << fmt::format("{},{:g},{:g},{},{:.6g},{:.6g},{:.6g},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                       result.rows[p.row].label, s.dy_mm, s.y, s.creep_set, s.xi, s.eta, s.phi, int(s.flange),
                       num(p.out.fx), num(p.out.fy), num(s.ref_fx), num(s.ref_fy), num(p.err_force), num(p.out.area),
                       num(s.ref_area), num(p.out.pmax), num(s.ref_pmax), num(p.out.angle), num(s.ref_angle),
                       num(p.time_us));
  }
}

void write_table_memory_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path) {
  std::ofstream out(path);
  RAILTAB_CHECK(out.good(), "cannot write {}", path.string());
  header_comments(out, result);
  out << "label,method,table_y_step_mm,table_creep_grid,table_file_bytes,table_memory_bytes,time_us,err_force,"
         "err_force_p90,err_force_tread,err_force_flange,err_area,err_angle_mrad,err_interp,err_interp_p90\n";
  for (const SaRow& r : result.rows) {
    if (r.kind != "lookup") continue;
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.label,
                       r.family == "lookup-linear" ? "linear" : "cubic", num(r.table_y_step * 1e3),
                       r.table_creep_grid, r.file_bytes, r.memory_bytes, num(r.time_us), num(r.err_force),
                       num(r.err_force_p90), num(r.err_force_tread), num(r.err_force_flange), num(r.err_area),
                       num(r.err_angle_mrad), num(r.err_interp), num(r.err_interp_p90));
  }
}

}  // namespace railtab
