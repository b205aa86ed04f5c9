// SPDX-License-Identifier: Apache-2.0
// Diagnostic, not a test (docs/validation/exact-tables.md, "Creepage nodes and the law"): the
// creepage interpolation of the exact model's tables alone, on the tread. Tables of one (y, load)
// node (two y nodes 0.01 mm apart, queried at the first: no y interpolation) at seven tread y,
// 78.5 kN, 0.5 mm elements, against direct evaluations at 300 random creepages per y (cached in a
// file: they do not depend on the table). Prints RMS / median / p90 / p99 / max of |fx, fy error| /
// (mu N) of the left wheel's tread slot, through the public lookup and through this file's own
// trilinear interpolation in the coordinates v of F / (mu N) minus a trial law (the same numbers
// when the trial law is the stored one), so that a law can be tried without writing its tables.
//   tread_probe [cache.bin] [states per y]
// env: NX NE NP (node counts, default 7 5 3), KX KE KP (knees, default 1 3 4), STORED_SPIN (the
// scene's creep_law_spin), LAW=1 LA=w (trial law: spin weight w), WORST=1 (the ten worst values).
#include <cstdio>
#include <cstdlib>
#include <functional>
#include "creep_probe.hpp"
using namespace railtab;
using namespace railtab::accuracy;
namespace {
// A law: F / (mu N) (fx, fy) at the normalised creepages (xi', eta', psi').
using Law = std::function<void(double, double, double, double*)>;
void law_base(double x, double e, double p, double* o) { auto l = creep_map::law(x, e, p, probe::env_number("STORED_SPIN", 0.0)); o[0] = l[0]; o[1] = l[1]; }
}  // namespace
int main(int argc, char** argv) {
  const std::string cache = argc > 1 ? argv[1] : "tread_probe_direct.bin";
  const std::size_t M = argc > 2 ? std::stoul(argv[2]) : 300;
  Scene scene = probe::probe_scene();
  const std::vector<double> ys = {-2.3e-3, -0.6e-3, 0.3e-3, 0.6e-3, 0.85e-3, 2.7e-3, 4.4e-3};
  const double load = 78.5e3;
  const std::vector<Point> pts = probe::probe_states(scene, ys, load, M, 777);
  const std::vector<Direct> direct = probe::cached_direct(scene, pts, cache);
  const std::size_t nx = std::size_t(probe::env_number("NX", 7)), ne = std::size_t(probe::env_number("NE", 5)), np = std::size_t(probe::env_number("NP", 3));
  scene.creep_law_spin = probe::env_number("STORED_SPIN", 0.0);
  scene.creep_knee = {probe::env_number("KX", 1), probe::env_number("KE", 3), probe::env_number("KP", 4)};
  scene.grids.xi = probe::even_nodes(scene.grids.xi.front(), scene.grids.xi.back(), nx);
  scene.grids.eta = probe::even_nodes(scene.grids.eta.front(), scene.grids.eta.back(), ne);
  scene.grids.phi = probe::even_nodes(scene.grids.phi.front(), scene.grids.phi.back(), np);
  const double mu = scene.tangential.friction;
  const int lawid = int(probe::env_number("LAW", 0));
  const double A = probe::env_number("LA", 0.0);
  Law law2 = law_base;
  if (lawid == 1) {  // spin adds to the magnitude: r_t = |(x, y, A p)|; direction (x, y)
    law2 = [A](double x, double e, double p, double* o) {
      const double y = e + p / 3.0, r = std::sqrt(x * x + y * y), rt = std::sqrt(x * x + y * y + A * A * p * p);
      if (!(rt > 0)) { o[0] = o[1] = 0; return; }
      const double w = 1.0 - std::min(rt, 1.0), g = 1.0 - w * w * w;
      o[0] = -g * x / rt; o[1] = -g * y / rt; (void)r;
    };
  }
  std::vector<double> errs, errs_lk;
  struct W { double e; std::size_t i; int o; };
  std::vector<W> worst;
  double gen_s = 0;
  for (std::size_t iy = 0; iy < ys.size(); ++iy) {
    Scene one = scene;
    one.grids.y = {ys[iy], ys[iy] + 1e-5};
    one.grids.load = {load};
    auto t0 = std::chrono::steady_clock::now();
    SweepResult r = run_sweep(one, make_contact_kernel(one), SweepOptions{});
    gen_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    lk::Table lt = load_through_file(r.table, "probe");
    const TableView view(r.table);
    const TableGroup* cg = r.table.group("left/creep");
    const TableDataset* fxd = cg->find("fx_normalised");
    const TableDataset* fyd = cg->find("fy_normalised");
    // strides: last dims ... xi, eta, phi, slot
    const std::size_t S = 2;
    auto idx = [&](std::size_t a, std::size_t b, std::size_t c, std::size_t s) { return ((a * ne + b) * np + c) * S + s; };  // y node 0 first
    if (fxd->values.size() != 2 * nx * ne * np * S) { std::printf("layout?\n"); return 1; }
    const std::vector<double> vx = creep_map::nodes(nx), ve = creep_map::nodes(ne), vp = creep_map::nodes(np);
    for (std::size_t k = 0; k < M; ++k) {
      const std::size_t i = iy * M + k;
      const Point& p = pts[i];
      const std::size_t w = 0, s = 0;  // left wheel, tread
      const WheelValues& d = direct[i][w];
      const double N = d.value[lk::kNormalForce][s];
      if (!(N > 0)) continue;
      const double sc[3] = {view.slot_scale(w, s, 0, p), view.slot_scale(w, s, 1, p), view.slot_scale(w, s, 2, p)};
      const Point v = view.creep_point(w, s, p);
      // residual at nodes under law2
      auto res = [&](std::size_t a, std::size_t b, std::size_t c, int o) {
        const double x = view.physical_creepage(w, s, 0, p, vx[a]) / sc[0], e = view.physical_creepage(w, s, 1, p, ve[b]) / sc[1],
                     ph = view.physical_creepage(w, s, 2, p, vp[c]) / sc[2];
        double l1[2], l2[2];
        law_base(x, e, ph, l1);
        law2(x, e, ph, l2);
        const double st = (o == 0 ? fxd : fyd)->values[idx(a, b, c, s)];
        return st + l1[o] - l2[o];
      };
      auto cellof = [](const std::vector<double>& g, double x, std::size_t& lo, double& t) {
        lo = std::min<std::size_t>(std::upper_bound(g.begin(), g.end(), x) - g.begin(), g.size() - 1);
        lo = lo == 0 ? 0 : lo - 1;
        if (lo + 1 >= g.size()) lo = g.size() - 2;
        t = (x - g[lo]) / (g[lo + 1] - g[lo]);
      };
      std::size_t a0, b0, c0; double ta, tb, tc;
      cellof(vx, v.v[kXi], a0, ta); cellof(ve, v.v[kEta], b0, tb); cellof(vp, v.v[kPhi], c0, tc);
      double lq[2];
      law2(p.v[kXi] / sc[0], p.v[kEta] / sc[1], p.v[kPhi] / sc[2], lq);
      const lk::Result lr = lt.query(static_cast<lk::Wheel>(0), to_state(lt, p));
      for (int o = 0; o < 2; ++o) {
        double f = 0;
        for (int c = 0; c < 8; ++c) {
          const double wgt = ((c & 4) ? ta : 1 - ta) * ((c & 2) ? tb : 1 - tb) * ((c & 1) ? tc : 1 - tc);
          f += wgt * res(a0 + ((c >> 2) & 1), b0 + ((c >> 1) & 1), c0 + (c & 1), o);
        }
        f += lq[o];
        const double dn = d.value[o == 0 ? lk::kFx : lk::kFy][s] / (mu * N);
        errs.push_back(std::abs(f - dn));
        worst.push_back({std::abs(f - dn), i, o});
        errs_lk.push_back(std::abs(lr.contact[s].value[o == 0 ? lk::kFx : lk::kFy] - d.value[o == 0 ? lk::kFx : lk::kFy][s]) / (mu * N));
      }
    }
  }
  auto stats = [](std::vector<double> v, const char* name) {
    std::sort(v.begin(), v.end());
    double sq = 0; for (double e : v) sq += e * e;
    auto q = [&](double f) { return v[std::size_t(f * double(v.size() - 1) + 0.5)]; };
    std::printf("%s: rms %.2f median %.2f p90 %.2f p99 %.2f max %.2f %% (n %zu)\n", name, 100 * std::sqrt(sq / double(v.size())),
                100 * q(0.5), 100 * q(0.9), 100 * q(0.99), 100 * q(1.0), v.size());
  };
  std::printf("nodes %zu x %zu x %zu knee %g %g %g stored law spin %g, trial law %d spin %g  gen %.1f s (%zu y)\n", nx, ne, np,
              scene.creep_knee[0], scene.creep_knee[1], scene.creep_knee[2], scene.creep_law_spin, lawid, A, gen_s, ys.size());
  stats(errs, "own interpolation, trial law");
  stats(errs_lk, "lookup, stored law          ");
  if (std::getenv("WORST")) {
    std::sort(worst.begin(), worst.end(), [](const W& a, const W& b) { return a.e > b.e; });
    for (int k = 0; k < 10; ++k) {
      const Point& p = pts[worst[k].i];
      std::printf("  %.4f f%c y %.2f mm xi %.2e eta %.2e phi %.3f\n", worst[k].e, worst[k].o ? 'y' : 'x', p.v[kY] * 1e3, p.v[kXi], p.v[kEta], p.v[kPhi]);
    }
  }
  return 0;
}
