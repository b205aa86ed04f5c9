// SPDX-License-Identifier: Apache-2.0
// Diagnostic, not a test (docs/validation/exact-tables.md, "Creepage nodes and the balance
// (flange)"): the creepage interpolation of the exact model's tables alone, in flange contact.
// Tables of one (y, load) node (two y nodes 0.01 mm apart, queried at the first: no y
// interpolation) at flange y of the left wheel, 78.5 kN, 0.5 mm elements, against direct
// evaluations at random creepages (cached in a file: they do not depend on the table). Prints
// RMS / median / p90 / p99 / max of |fx, fy error| / (mu N) of the flange slot through the public
// lookup, and through this file's own trilinear interpolation with other ways to get N back from
// the node values (the stored vertical share at the geometry's angle; N itself; 1 / N; the share
// at the angle that holds it most nearly constant over the nodes), so that a form can be measured
// before it is written to a table.
//   flange_probe [cache.bin] [states per y]
// env: NX NE NP (node counts, default the scene's), KX KE KP (knees, default the scene's),
// YS (comma-separated y in mm), LA (a trial law spin weight: the stored values re-interpolated
// with that law, as writing the table with it would give), WORST=1 (the ten worst values of the lookup).
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include "creep_probe.hpp"
using namespace railtab;
using namespace railtab::accuracy;
namespace {
void stats(std::vector<double> v, const char* name) {
  if (v.empty()) { std::printf("%s: none\n", name); return; }
  std::sort(v.begin(), v.end());
  double sq = 0; for (double e : v) sq += e * e;
  auto q = [&](double f) { return v[std::size_t(f * double(v.size() - 1) + 0.5)]; };
  std::printf("%s: rms %.2f median %.2f p90 %.2f p99 %.2f max %.2f %% (n %zu)\n", name, 100 * std::sqrt(sq / double(v.size())),
              100 * q(0.5), 100 * q(0.9), 100 * q(0.99), 100 * q(1.0), v.size());
}
}  // namespace
int main(int argc, char** argv) {
  const std::string cache = argc > 1 ? argv[1] : "flange_probe_direct.bin";
  const std::size_t M = argc > 2 ? std::stoul(argv[2]) : 200;
  Scene scene = probe::probe_scene();
  std::vector<double> ys = {6.55e-3, 6.7e-3, 6.85e-3, 7.0e-3, 7.2e-3, 7.4e-3, 7.8e-3};
  if (const char* s = std::getenv("YS")) {
    ys.clear();
    std::stringstream in(s);
    for (std::string t; std::getline(in, t, ',');) ys.push_back(std::stod(t) * 1e-3);
  }
  const double load = 78.5e3;
  const std::vector<Point> pts = probe::probe_states(scene, ys, load, M, 778);
  const std::vector<Direct> direct = probe::cached_direct(scene, pts, cache);
  const std::size_t nx = std::size_t(probe::env_number("NX", double(scene.grids.xi.size()))), ne = std::size_t(probe::env_number("NE", double(scene.grids.eta.size()))),
                    np = std::size_t(probe::env_number("NP", double(scene.grids.phi.size())));
  scene.creep_knee = {probe::env_number("KX", scene.creep_knee[0]), probe::env_number("KE", scene.creep_knee[1]), probe::env_number("KP", scene.creep_knee[2])};
  scene.grids.xi = probe::even_nodes(scene.grids.xi.front(), scene.grids.xi.back(), nx);
  scene.grids.eta = probe::even_nodes(scene.grids.eta.front(), scene.grids.eta.back(), ne);
  scene.grids.phi = probe::even_nodes(scene.grids.phi.front(), scene.grids.phi.back(), np);
  const double mu = scene.tangential.friction, spin = scene.creep_law_spin, trial = probe::env_number("LA", spin);
  constexpr int kForms = 4;
  const char* form_name[kForms] = {"share at the geometry angle", "N                          ",
                                   "1 / N                      ", "share at the fitted angle  "};
  std::vector<double> errs[kForms], errs_lk, errs_n[kForms], errs_lk_n;
  struct W { double e; std::size_t i; int o; double look, dir, n; };
  std::vector<W> worst;
  double gen_s = 0;
  const std::size_t w = 0, s = 1;  // left wheel, flange slot
  for (std::size_t iy = 0; iy < ys.size(); ++iy) {
    Scene one = scene;
    one.grids.y = {ys[iy], ys[iy] + 1e-5};
    one.grids.load = {load};
    auto t0 = std::chrono::steady_clock::now();
    SweepResult r = run_sweep(one, make_contact_kernel(one), SweepOptions{});
    gen_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    lk::Table lt = load_through_file(r.table, "fprobe");
    const TableView view(r.table);
    const TableGroup* cg = r.table.group("left/creep");
    const TableDataset* fxd = cg->find("fx_normalised");
    const TableDataset* fyd = cg->find("fy_normalised");
    const TableDataset* shd = cg->find("normal_force");
    const TableDataset* ang = r.table.group("left/geometry")->find("contact_angle");
    const std::size_t S = 2;
    auto idx = [&](std::size_t a, std::size_t b, std::size_t c) { return ((a * ne + b) * np + c) * S + s; };
    if (fxd->values.size() != 2 * nx * ne * np * S || ang->values.size() != 2 * S) { std::printf("layout?\n"); return 1; }
    const double g = ang->values[s], cg_ = std::cos(g), sg = std::sin(g);
    const std::vector<double> vx = creep_map::nodes(nx), ve = creep_map::nodes(ne), vp = creep_map::nodes(np);
    // Node values: r_x, r_y (F / (mu N) at the node), N, for the first query's scales (same y, load).
    const Point p0 = pts[iy * M];
    const double sc[3] = {view.slot_scale(w, s, 0, p0), view.slot_scale(w, s, 1, p0), view.slot_scale(w, s, 2, p0)};
    const std::size_t nn = nx * ne * np;
    std::vector<double> rx(nn), ry(nn), nf(nn), res_x(nn), res_y(nn);
    for (std::size_t a = 0; a < nx; ++a)
      for (std::size_t b = 0; b < ne; ++b)
        for (std::size_t c = 0; c < np; ++c) {
          const std::size_t k = (a * ne + b) * np + c;
          const double x = view.physical_creepage(w, s, 0, p0, vx[a]) / sc[0], e = view.physical_creepage(w, s, 1, p0, ve[b]) / sc[1],
                       ph = view.physical_creepage(w, s, 2, p0, vp[c]) / sc[2];
          const auto l = creep_map::law(x, e, ph, spin);
          rx[k] = fxd->values[idx(a, b, c)] + l[0];
          ry[k] = fyd->values[idx(a, b, c)] + l[1];
          const auto lt2 = creep_map::law(x, e, ph, trial);
          res_x[k] = rx[k] - lt2[0];
          res_y[k] = ry[k] - lt2[1];
          nf[k] = shd->values[idx(a, b, c)] / (cg_ + mu * ry[k] * sg);
        }
    // The angle that holds N (cos a + mu r_y sin a) most nearly constant over the nodes (relative spread).
    auto spread = [&](double a) {
      double m = 0, m2 = 0;
      for (std::size_t k = 0; k < nn; ++k) { const double q = nf[k] * (std::cos(a) + mu * ry[k] * std::sin(a)); m += q; m2 += q * q; }
      m /= double(nn); return std::sqrt(std::max(0.0, m2 / double(nn) - m * m)) / m;
    };
    double best = g, best_s = spread(g);
    for (double a = 0.0; a < 1.4; a += 0.0005) if (spread(a) < best_s) { best_s = spread(a); best = a; }
    std::printf("y %.2f mm: scales %.3g %.3g %.3g; geometry angle %.4f rad (share spread %.3f), fitted %.4f rad (spread %.4f); N at zero creepage %.0f N\n",
                ys[iy] * 1e3, sc[0], sc[1], sc[2], g, spread(g), best, best_s, nf[(nx / 2 * ne + ne / 2) * np + np / 2]);
    const double cb = std::cos(best), sb = std::sin(best);
    for (std::size_t k = 0; k < M; ++k) {
      const std::size_t i = iy * M + k;
      const Point& p = pts[i];
      const WheelValues& d = direct[i][w];
      const double N = d.value[lk::kNormalForce][s];
      if (!(N > 0)) continue;
      const Point v = view.creep_point(w, s, p);
      auto cellof = [](const std::vector<double>& gr, double x, std::size_t& lo, double& t) {
        lo = std::min<std::size_t>(std::upper_bound(gr.begin(), gr.end(), x) - gr.begin(), gr.size() - 1);
        lo = lo == 0 ? 0 : lo - 1;
        if (lo + 1 >= gr.size()) lo = gr.size() - 2;
        t = (x - gr[lo]) / (gr[lo + 1] - gr[lo]);
      };
      std::size_t a0, b0, c0; double ta, tb, tc;
      cellof(vx, v.v[kXi], a0, ta); cellof(ve, v.v[kEta], b0, tb); cellof(vp, v.v[kPhi], c0, tc);
      auto interp = [&](auto f) {
        double acc = 0;
        for (int c = 0; c < 8; ++c) {
          const double wgt = ((c & 4) ? ta : 1 - ta) * ((c & 2) ? tb : 1 - tb) * ((c & 1) ? tc : 1 - tc);
          acc += wgt * f((((a0 + ((c >> 2) & 1)) * ne) + b0 + ((c >> 1) & 1)) * np + c0 + (c & 1));
        }
        return acc;
      };
      const auto lq = creep_map::law(p.v[kXi] / sc[0], p.v[kEta] / sc[1], p.v[kPhi] / sc[2], trial);
      const double qx = interp([&](std::size_t k2) { return res_x[k2]; }) + lq[0];
      const double qy = interp([&](std::size_t k2) { return res_y[k2]; }) + lq[1];
      double n_form[kForms];
      n_form[0] = interp([&](std::size_t k2) { return nf[k2] * (cg_ + mu * ry[k2] * sg); }) / (cg_ + mu * qy * sg);
      n_form[1] = interp([&](std::size_t k2) { return nf[k2]; });
      n_form[2] = 1.0 / interp([&](std::size_t k2) { return 1.0 / nf[k2]; });
      n_form[3] = interp([&](std::size_t k2) { return nf[k2] * (cb + mu * ry[k2] * sb); }) / (cb + mu * qy * sb);
      const double dx = d.value[lk::kFx][s], dy = d.value[lk::kFy][s];
      for (int f = 0; f < kForms; ++f) {
        errs[f].push_back(std::abs(qx * mu * n_form[f] - dx) / (mu * N));
        errs[f].push_back(std::abs(qy * mu * n_form[f] - dy) / (mu * N));
        errs_n[f].push_back(std::abs(n_form[f] - N) / N);
      }
      const lk::Result lr = lt.query(static_cast<lk::Wheel>(0), to_state(lt, p));
      errs_lk_n.push_back(std::abs(lr.contact[s].value[lk::kNormalForce] - N) / N);
      for (int o = 0; o < 2; ++o) {
        const double look = lr.contact[s].value[o == 0 ? lk::kFx : lk::kFy], dir = o == 0 ? dx : dy;
        errs_lk.push_back(std::abs(look - dir) / (mu * N));
        worst.push_back({errs_lk.back(), i, o, look, dir, N});
      }
    }
  }
  std::printf("nodes %zu x %zu x %zu (%zu per (y, load)) knee %g %g %g law spin %g (trial %g)  gen %.1f s (%zu y x %zu states)\n", nx, ne, np,
              nx * ne * np, scene.creep_knee[0], scene.creep_knee[1], scene.creep_knee[2], spin, trial, gen_s, ys.size(), M);
  stats(errs_lk, "lookup                               fx, fy / (mu N)");
  for (int f = 0; f < kForms; ++f) stats(errs[f], (std::string("own, N from ") + form_name[f] + " fx, fy / (mu N)").c_str());
  stats(errs_lk_n, "lookup                               N / N");
  for (int f = 0; f < kForms; ++f) stats(errs_n[f], (std::string("own, N from ") + form_name[f] + " N / N").c_str());
  if (std::getenv("WORST")) {
    std::sort(worst.begin(), worst.end(), [](const W& a, const W& b) { return a.e > b.e; });
    for (int k = 0; k < 10 && k < int(worst.size()); ++k) {
      const Point& p = pts[worst[k].i];
      std::printf("  %.4f f%c y %.2f mm xi %.2e eta %.2e phi %.3f lookup %.0f direct %.0f N %.0f\n", worst[k].e, worst[k].o ? 'y' : 'x',
                  p.v[kY] * 1e3, p.v[kXi], p.v[kEta], p.v[kPhi], worst[k].look, worst[k].dir, worst[k].n);
    }
  }
  return 0;
}
