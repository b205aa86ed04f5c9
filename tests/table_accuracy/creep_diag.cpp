// SPDX-License-Identifier: Apache-2.0
// Diagnostic, not a test (creep interpolation, docs/validation/creep-interpolation.md;
// docs/lookup.md "Accuracy"): where do the creep-force errors of the STRIPES table come from? The
// states and classification of StripesSceneRandomOffGrid; the 8000 direct evaluations cached in a
// file (they do not depend on the table). Prints smooth-cell max/RMS of fx, fy / (mu N) per slot,
// the normalised force and N errors separately, jump cells within 2 % and their misses by distance
// and kind of the nearest jump; for the worst states, the error at the state's exact (y, load)
// (one-point tables: the creepage axes alone) and with one creepage axis refined at a time.
//   creep_diag [cache.bin] [nx ne np] [worst]
// env: DIAG_KNEE="kx ke kp" (scene creep_knee), DIAG_METHOD=1|2 (cubic lookups), DIAG_NO_JUMPS,
// DIAG_NO_DECOMPOSE, DIAG_SLOT=0|1,
//   DIAG_LINE="y load xi eta phi axis" (direct forces along creepage axis 2 xi, 3 eta, 4 phi),
//   DIAG_PROFILE="y load nx ne np" (the stored normalised values of one (y, load) node).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>

#include "accuracy_util.hpp"
#include "adaptive/jump_locator.hpp"

using namespace railtab;
using namespace railtab::accuracy;

namespace {

std::vector<double> linspace(double lo, double hi, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n - 1);
  v.back() = hi;
  return v;
}

void set_counts(Scene& s, std::size_t nx, std::size_t ne, std::size_t np) {
  s.grids.xi = linspace(s.grids.xi.front(), s.grids.xi.back(), nx);
  s.grids.eta = linspace(s.grids.eta.front(), s.grids.eta.back(), ne);
  s.grids.phi = linspace(s.grids.phi.front(), s.grids.phi.back(), np);
}

lk::Table make_lookup(const Scene& scene, bool jumps, std::uintmax_t* bytes, Table* keep = nullptr,
                      ContactJumps* located = nullptr) {
  SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
  if (r.summary.failures) throw std::runtime_error("table: " + r.summary.first_failure);
  Table t = std::move(r.table);
  if (jumps) {
    const ContactJumps j = locate_jumps(scene);
    add_jumps(t, scene, j);
    if (located) *located = j;
  }
  const std::filesystem::path path = temp_table_path("diag");
  write_for_lookup(t, path);
  if (bytes) *bytes = std::filesystem::file_size(path);
  lk::LoadOptions options;  // DIAG_METHOD=1|2: the cubic or monotone cubic lookup (lk::Method)
  if (const char* m = std::getenv("DIAG_METHOD")) options.method = static_cast<lk::Method>(std::atoi(m));
  lk::Table l = lk::Table::load(path.string(), options);
  std::filesystem::remove(path);
  if (keep) *keep = std::move(t);
  return l;
}

// Error / (mu N) of fx, fy (the larger) of a one-(y, load) table with the given creepage counts.
double mini_error(const Scene& base, const Point& p, std::size_t w, std::size_t s, const WheelValues& d,
                  std::size_t nx, std::size_t ne, std::size_t np, int o) {
  Scene one = base;
  one.grids.y = {p.v[kY]};
  one.grids.load = {p.v[kLoad]};
  set_counts(one, nx, ne, np);
  const lk::Table t = make_lookup(one, false, nullptr);
  const lk::Result r = t.query(static_cast<lk::Wheel>(w), to_state(t, p));
  const double mun = base.tangential.friction * d.value[lk::kNormalForce][s];
  return (r.contact[s].value[o] - d.value[o][s]) / mun;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cache = argc > 1 ? argv[1] : "/tmp/s5c_direct.bin";
  Scene scene = load_scene(std::filesystem::path(RAILTAB_SOURCE_DIR) / "tables" / "default_stripes.toml");
  if (const char* line = std::getenv("DIAG_LINE")) {  // "y load xi eta phi axis": direct along one axis
    Point p;
    int axis = 4;
    std::sscanf(line, "%lf %lf %lf %lf %lf %d", &p.v[kY], &p.v[kLoad], &p.v[kXi], &p.v[kEta], &p.v[kPhi], &axis);
    const std::vector<double>& g = axis == 2 ? scene.grids.xi : axis == 3 ? scene.grids.eta : scene.grids.phi;
    std::vector<Point> pts;
    for (int i = 0; i <= 30; ++i) {
      Point q = p;
      q.v[axis] = g.front() + (g.back() - g.front()) * i / 30.0;
      pts.push_back(q);
    }
    const std::vector<Direct> d = evaluate_direct(scene, pts);
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (std::size_t w = 0; w < 2; ++w)
        std::printf("w%zu %8.5f | s0 N %7.0f fx/muN %7.4f fy/muN %7.4f st %5u a %.4f | s1 N %7.0f fx/muN %7.4f fy/muN %7.4f st %5u a %.4f ang %.4f Q %.0f\n", w,
                    pts[i].v[axis], d[i][w].value[lk::kNormalForce][0],
                    d[i][w].value[lk::kFx][0] / (0.3 * d[i][w].value[lk::kNormalForce][0]),
                    d[i][w].value[lk::kFy][0] / (0.3 * d[i][w].value[lk::kNormalForce][0]), d[i][w].status[lk::kCreep][0],
                    d[i][w].value[lk::kSemiAxisA][0], d[i][w].value[lk::kNormalForce][1],
                    d[i][w].value[lk::kFx][1] / (0.3 * d[i][w].value[lk::kNormalForce][1]),
                    d[i][w].value[lk::kFy][1] / (0.3 * d[i][w].value[lk::kNormalForce][1]), d[i][w].status[lk::kCreep][1],
                    d[i][w].value[lk::kSemiAxisA][1], d[i][w].value[lk::kContactAngle][1],
                    d[i][w].value[lk::kNormalForce][1] * std::cos(d[i][w].value[lk::kContactAngle][1]) +
                        d[i][w].value[lk::kFy][1] * std::sin(d[i][w].value[lk::kContactAngle][1]));
    return 0;
  }
  if (const char* prof = std::getenv("DIAG_PROFILE")) {  // "y load nx ne np": stored residuals
    double y, load;
    unsigned a, b, c;
    std::sscanf(prof, "%lf %lf %u %u %u", &y, &load, &a, &b, &c);
    Scene one = scene;
    one.grids.y = {y};
    one.grids.load = {load};
    set_counts(one, a, b, c);
    SweepResult r = run_sweep(one, make_contact_kernel(one), SweepOptions{});
    for (const char* g : {"left/creep", "left/normal"}) {
      const TableGroup* grp = r.table.group(g);
      for (const char* name : {"fx_normalised", "fy_normalised", "normal_force", "creep_scale_xi", "creep_scale_eta", "creep_scale_phi", "slip_fraction"}) {
        const TableDataset* d = grp->find(name);
        if (!d) continue;
        std::printf("%s/%s:", g, name);
        for (std::size_t i = 0; i < d->values.size(); ++i) std::printf(" %.4g", d->values[i]);
        std::printf("\n");
      }
    }
    return 0;
  }
  const std::size_t nx = argc > 4 ? std::stoul(argv[2]) : scene.grids.xi.size();
  const std::size_t ne = argc > 4 ? std::stoul(argv[3]) : scene.grids.eta.size();
  const std::size_t np = argc > 4 ? std::stoul(argv[4]) : scene.grids.phi.size();
  const std::size_t n_worst = argc > 5 ? std::stoul(argv[5]) : 12;
  const std::vector<Point> points = random_states(scene, 4000, 20240611);  // StripesSceneRandomOffGrid's
  std::vector<Direct> direct(points.size());
  {
    std::ifstream in(cache, std::ios::binary);
    if (in && in.read(reinterpret_cast<char*>(direct.data()), static_cast<std::streamsize>(direct.size() * sizeof(Direct)))) {
      std::printf("direct evaluations from %s\n", cache.c_str());
    } else {
      direct = evaluate_direct(scene, points);
      std::ofstream(cache, std::ios::binary)
          .write(reinterpret_cast<const char*>(direct.data()), static_cast<std::streamsize>(direct.size() * sizeof(Direct)));
    }
  }
  set_counts(scene, nx, ne, np);
  if (const char* k = std::getenv("DIAG_KNEE")) std::sscanf(k, "%lf %lf %lf", &scene.creep_knee[0], &scene.creep_knee[1], &scene.creep_knee[2]);
  std::uintmax_t bytes = 0;
  Table table;
  ContactJumps jumps;
  const auto t0 = std::chrono::steady_clock::now();
  const lk::Table lookup = make_lookup(scene, std::getenv("DIAG_NO_JUMPS") == nullptr, &bytes, &table, &jumps);
  std::printf("creepage nodes %zu x %zu x %zu: table %.0f KiB, %.1f s\n", nx, ne, np, static_cast<double>(bytes) / 1024.0,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const TableView view(table);
  const double mu = scene.tangential.friction;
  struct Bad {
    double rel;
    std::size_t i, w, s;
    int o;
  };
  std::vector<Bad> bad;
  double sum[2][2] = {}, mx[2][2] = {}, nsum[2][2] = {}, nmx[2][2] = {}, nnsum[2] = {}, nnmx[2] = {};
  std::size_t n[2] = {}, jump_n[2] = {}, jump_ok[2] = {}, miss[2][4] = {};
  std::map<unsigned, std::size_t> miss_kind[2];
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t w = 0; w < 2; ++w) {
      const lk::Result r = lookup.query(static_cast<lk::Wheel>(w), to_state(lookup, points[i]));
      const PointKinds kinds = classify_point(view, w, points[i], direct[i][w]);
      for (std::size_t s = 0; s < kSlots; ++s) {
        const CellKind kind = kinds.kind[lk::kCreep][s];
        if (kind == CellKind::kJump) {
          double worst = 0.0;
          for (int o : {lk::kFx, lk::kFy}) {
            double nn = std::max(direct[i][w].value[lk::kNormalForce][s], r.contact[s].value[lk::kNormalForce]);
            if (!(nn > 0.0)) nn = points[i].v[kLoad];
            worst = std::max(worst, std::abs(r.contact[s].value[o] - direct[i][w].value[o][s]) / (mu * nn));
          }
          ++jump_n[s];
          jump_ok[s] += worst <= 0.02;
          if (worst > 0.02 && !jumps.wheel[w].empty()) {  // nearest located jump at the load nodes around
            const std::vector<double>& loads = scene.grids.load;
            std::size_t l = static_cast<std::size_t>(std::upper_bound(loads.begin(), loads.end(), points[i].v[kLoad]) - loads.begin());
            l = std::clamp<std::size_t>(l, 1, loads.size() - 1) - 1;
            double dist = 1.0;
            unsigned kind = 0;
            for (std::size_t k : {l, l + 1})
              for (const ContactJump& j : jumps.wheel[w][k])
                if (std::abs(points[i].v[kY] - j.y) < dist) dist = std::abs(points[i].v[kY] - j.y), kind = j.kind;
            const int bucket = dist < 0.05e-3 ? 0 : dist < 0.1e-3 ? 1 : dist < 0.25e-3 ? 2 : 3;
            ++miss[s][bucket];
            ++miss_kind[s][kind & 1023u];
          }
          continue;
        }
        if (kind != CellKind::kSmooth) continue;
        ++n[s];
        for (int o : {lk::kFx, lk::kFy}) {
          const double rel =
              std::abs(r.contact[s].value[o] - direct[i][w].value[o][s]) / (mu * direct[i][w].value[lk::kNormalForce][s]);
          sum[s][o - lk::kFx] += rel * rel;
          // The normalised force alone: lookup F / (mu N_lookup) against direct F / (mu N_direct).
          const double rn = std::abs(r.contact[s].value[o] / (mu * r.contact[s].value[lk::kNormalForce]) -
                                     direct[i][w].value[o][s] / (mu * direct[i][w].value[lk::kNormalForce][s]));
          const double rnn = std::abs(r.contact[s].value[lk::kNormalForce] / direct[i][w].value[lk::kNormalForce][s] - 1.0);
          nsum[s][o - lk::kFx] += rn * rn;
          nmx[s][o - lk::kFx] = std::max(nmx[s][o - lk::kFx], rn);
          if (o == lk::kFx) nnsum[s] += rnn * rnn, nnmx[s] = std::max(nnmx[s], rnn);
          mx[s][o - lk::kFx] = std::max(mx[s][o - lk::kFx], rel);
          bad.push_back({rel, i, w, s, o});
        }
      }
    }
  for (std::size_t s = 0; s < kSlots; ++s)
    std::printf("slot %zu smooth %zu: fx max %.4f rms %.4f | fy max %.4f rms %.4f | jump cells %zu, %.1f %% within 2 %%\n", s,
                n[s], mx[s][0], std::sqrt(sum[s][0] / static_cast<double>(n[s])), mx[s][1],
                std::sqrt(sum[s][1] / static_cast<double>(n[s])), jump_n[s],
                100.0 * static_cast<double>(jump_ok[s]) / static_cast<double>(std::max<std::size_t>(1, jump_n[s])));
  for (std::size_t s = 0; s < kSlots; ++s)
    std::printf("slot %zu normalised force F / (mu N) alone: fx max %.4f rms %.4f | fy max %.4f rms %.4f | N/N_direct - 1: max %.4f rms %.4f\n", s,
                nmx[s][0], std::sqrt(nsum[s][0] / static_cast<double>(n[s])), nmx[s][1],
                std::sqrt(nsum[s][1] / static_cast<double>(n[s])), nnmx[s], std::sqrt(nnsum[s] / static_cast<double>(n[s])));
  for (std::size_t s = 0; s < kSlots; ++s) {
    std::printf("slot %zu jump cells beyond 2 %%: nearest jump < 0.05 mm %zu, 0.05-0.1 %zu, 0.1-0.25 %zu, farther %zu; by kind:",
                s, miss[s][0], miss[s][1], miss[s][2], miss[s][3]);
    for (const auto& [k, c] : miss_kind[s]) std::printf(" %u:%zu", k, c);
    std::printf("\n");
  }
  std::sort(bad.begin(), bad.end(), [](const Bad& a, const Bad& b) { return a.rel > b.rel; });
  if (std::getenv("DIAG_NO_DECOMPOSE")) return 0;
  std::printf("worst states: err  | y load xi eta phi | x' e' p' (state's scales) | v | creep-only  xi-refined "
              "eta-refined phi-refined all-refined (signed, of mu N)\n");
  std::size_t shown = 0;
  std::vector<std::size_t> seen;
  for (const Bad& b : bad) {
    if (shown >= n_worst) break;
    if (std::getenv("DIAG_SLOT") && b.s != std::stoul(std::getenv("DIAG_SLOT"))) continue;
    if (std::find(seen.begin(), seen.end(), b.i * 4 + b.w * 2 + b.s) != seen.end()) continue;
    seen.push_back(b.i * 4 + b.w * 2 + b.s);
    ++shown;
    const Point& p = points[b.i];
    const Point v = view.creep_point(b.w, b.s, p);
    double x[3];
    for (int k = 0; k < 3; ++k) x[k] = p.v[kXi + k] / view.slot_scale(b.w, b.s, k, p);
    const WheelValues& d = direct[b.i][b.w];
    const double e0 = mini_error(scene, p, b.w, b.s, d, nx, ne, np, b.o);
    const double e1 = mini_error(scene, p, b.w, b.s, d, 2 * nx - 1, ne, np, b.o);
    const double e2 = mini_error(scene, p, b.w, b.s, d, nx, 2 * ne - 1, np, b.o);
    const double e3 = mini_error(scene, p, b.w, b.s, d, nx, ne, 2 * np - 1, b.o);
    const double e4 = mini_error(scene, p, b.w, b.s, d, 2 * nx - 1, 2 * ne - 1, 2 * np - 1, b.o);
    std::printf("%s w%zu s%zu %.4f | %.5f %.0f %.5f %.5f %.3f | %.2f %.2f %.2f | %.2f %.2f %.2f | %+.4f %+.4f %+.4f %+.4f %+.4f\n",
                b.o == lk::kFx ? "fx" : "fy", b.w, b.s, b.rel, p.v[kY], p.v[kLoad], p.v[kXi], p.v[kEta], p.v[kPhi], x[0],
                x[1], x[2], v.v[kXi], v.v[kEta], v.v[kPhi], e0, e1, e2, e3, e4);
  }
  return 0;
}
