// SPDX-License-Identifier: Apache-2.0
// Normal contact of two elastic half-spaces on a grid (normal_solver.hpp): the BCCG solver.
#include "halfspace/normal_solver.hpp"

#include <algorithm>
#include <cmath>

namespace railtab::halfspace {
namespace {

bool usable(const Grid& grid, const std::vector<double>& gap) {
  if (grid.nx < 2 || grid.ny < 2 || !(grid.dx > 0.0) || !(grid.dy > 0.0)) return false;
  if (!std::isfinite(grid.dx) || !std::isfinite(grid.dy)) return false;
  if (gap.size() != static_cast<size_t>(grid.size())) return false;
  return std::all_of(gap.begin(), gap.end(), [](double v) { return std::isfinite(v); });
}

// Contact length of one line of elements (a row along x or a column along y): the contact edge
// is placed between the outermost contact element and its exterior neighbour where p^2, linear
// near a smooth contact edge (p ~ sqrt(distance)), extrapolated from the two outermost contact
// elements reaches zero; the extension is kept within [0, h] of the outermost element centre.
// A line with one contact element counts h. Between contact runs the same at each end.
double line_length(const double* p, int n, int stride, double h) {
  double length = 0.0;
  auto ext = [&](int edge, int inner) {  // extension beyond element `edge` [m]
    if (inner < 0 || inner >= n || !(p[inner * stride] > 0.0)) return 0.5 * h;
    const double pe = p[edge * stride], pi = p[inner * stride];
    const double drop = pi * pi - pe * pe;
    if (!(drop > 0.0)) return h;
    return std::clamp(h * pe * pe / drop, 0.0, h);
  };
  for (int k = 0; k < n;) {
    if (!(p[k * stride] > 0.0)) {
      ++k;
      continue;
    }
    int e = k;
    while (e + 1 < n && p[(e + 1) * stride] > 0.0) ++e;
    length += (e - k) * h + ext(k, k + 1) + ext(e, e - 1);
    k = e + 1;
  }
  return length;
}

void summarise(const Grid& grid, NormalSolution& s) {
  const double dA = grid.element_area();
  double force = 0.0, pmax = 0.0;
  int in_contact = 0;
  bool edge = false;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const double p = s.pressure[grid.index(i, j)];
      if (p <= 0.0) continue;
      force += p;
      pmax = std::max(pmax, p);
      ++in_contact;
      if (i == 0 || j == 0 || i == grid.nx - 1 || j == grid.ny - 1) edge = true;
    }
  s.normal_force = force * dA;
  s.max_pressure = pmax;
  s.area = in_contact * dA;
  double along_x = 0.0, along_y = 0.0;
  for (int j = 0; j < grid.ny; ++j)
    along_x += grid.dy * line_length(s.pressure.data() + grid.index(0, j), grid.nx, 1, grid.dx);
  for (int i = 0; i < grid.nx; ++i)
    along_y += grid.dx * line_length(s.pressure.data() + i, grid.ny, grid.nx, grid.dy);
  s.area_estimate = 0.5 * (along_x + along_y);
  if (edge) s.status |= status::kAreaTooSmall;
  if (in_contact == 0) s.status |= status::kLiftOff;
}

// Polonsky-Keer BCCG; load_control: target is the force, else the approach.
void bccg(const Grid& grid, const std::vector<double>& h, bool load_control, double target,
          const Material& material, const NormalSolverOptions& options, Workspace& w,
          NormalSolution& s) {
  const int n = grid.size();
  const double dA = grid.element_area();
  s.status = 0;
  s.iterations = 0;
  const Spectrum& kernel = w.normal_kernel(grid, material);
  w.u.resize(n);
  w.g.resize(n);
  w.t.assign(n, 0.0);
  w.r.resize(n);
  w.p_old.resize(n);
  std::vector<double>& p = s.pressure;
  // Start: the previous solution when it fits, else a uniform pressure where the gap is below
  // its mean (a first guess of the contact set; CG corrects it).
  bool warm = p.size() == static_cast<size_t>(n) &&
              std::any_of(p.begin(), p.end(), [](double v) { return v > 0.0; });
  if (!warm) {
    const double hmin = *std::min_element(h.begin(), h.end());
    double hmean = 0.0;
    for (double v : h) hmean += v;
    hmean /= n;
    const double level = load_control ? 0.5 * (hmin + hmean) : std::max(target, hmin);
    p.assign(n, 0.0);
    int count = 0;
    for (int k = 0; k < n; ++k)
      if (h[k] <= level) ++count;
    const double p0 = load_control ? target / (std::max(count, 1) * dA) : 1e8;
    for (int k = 0; k < n; ++k)
      if (h[k] <= level) p[k] = p0;
  }
  if (load_control) {  // scale the start to the load
    double sum = 0.0;
    for (double v : p) sum += v;
    for (double& v : p) v *= target / (sum * dA);
  }
  const Spectrum* kernels[1] = {&kernel};
  const Spectrum* fields[1] = {&w.field_a};
  const std::vector<double>& offsets = w.normal_kernel_offsets();
  const int ax = 2 * grid.nx - 1;
  // u = A p is carried from one iteration to the next instead of convolving p again: the step
  // p - tau t has u - tau A t (A t is computed anyway), the few elements clipped at zero or
  // entering the contact are added element by element (the real-space kernel), and the load
  // scaling scales u. A convolution replaces this when many elements change (early iterations)
  // and every `refresh` iterations, so rounding cannot accumulate.
  constexpr int refresh = 16;
  constexpr int max_direct = 48;  // elements; each costs about n multiply-adds
  std::vector<int> changed;
  std::vector<double> change_value;
  bool u_current = false;
  int since_refresh = 0;
  double G_old = 1.0, delta_flag = 0.0, mean_gap = 0.0;
  bool converged = false;
  for (int it = 1; it <= options.max_iterations; ++it) {
    s.iterations = it;
    if (!u_current || since_refresh >= refresh) {
      w.fft.forward(p.data(), w.field_a);
      w.fft.convolve(kernels, fields, 1, w.u.data());
      since_refresh = 0;
    }
    ++since_refresh;
    int nc = 0;
    double gsum = 0.0;
    for (int k = 0; k < n; ++k) {
      w.g[k] = w.u[k] + h[k];
      if (p[k] > 0.0) {
        gsum += w.g[k];
        ++nc;
      }
    }
    if (nc == 0) break;  // lift-off (approach control)
    mean_gap = load_control ? gsum / nc : target;
    double G = 0.0;
    for (int k = 0; k < n; ++k) {
      w.g[k] -= mean_gap;
      if (p[k] > 0.0) G += w.g[k] * w.g[k];
    }
    for (int k = 0; k < n; ++k)
      w.t[k] = p[k] > 0.0 ? w.g[k] + delta_flag * (G / G_old) * w.t[k] : 0.0;
    G_old = G;
    w.fft.forward(w.t.data(), w.field_a);
    w.fft.convolve(kernels, fields, 1, w.r.data());
    double rbar = 0.0;  // w.r - rbar is the search direction's effect on the gap
    if (load_control) {
      double rsum = 0.0;
      for (int k = 0; k < n; ++k)
        if (p[k] > 0.0) rsum += w.r[k];
      rbar = rsum / nc;
    }
    double num = 0.0, den = 0.0;
    for (int k = 0; k < n; ++k)
      if (p[k] > 0.0) {
        num += w.g[k] * w.t[k];
        den += (w.r[k] - rbar) * w.t[k];
      }
    const double tau = den != 0.0 ? num / den : 0.0;
    w.p_old = p;
    bool overlap = false;
    changed.clear();
    change_value.clear();
    for (int k = 0; k < n; ++k) {
      const bool was_in = p[k] > 0.0;
      if (was_in) {
        const double stepped = p[k] - tau * w.t[k];
        p[k] = std::max(0.0, stepped);
        if (stepped < 0.0 && changed.size() <= static_cast<size_t>(max_direct)) {
          changed.push_back(k);  // clipped: differs from the step by -stepped
          change_value.push_back(-stepped);
        }
      }
      if (p[k] == 0.0 && w.g[k] < 0.0) {  // interpenetrating outside the contact set: enters
        p[k] = -tau * w.g[k];
        overlap = true;
        if (changed.size() <= static_cast<size_t>(max_direct)) {
          changed.push_back(k);  // the step left it at 0 (t = 0 outside, or clipped)
          change_value.push_back(p[k]);
        }
      }
    }
    // Clipped then re-entering elements were pushed twice: the values add up to p - stepped.
    u_current = changed.size() <= static_cast<size_t>(max_direct);
    if (u_current) {
      for (int k = 0; k < n; ++k) w.u[k] -= tau * w.r[k];
      for (size_t c = 0; c < changed.size(); ++c) {
        const int kc = changed[c], ic = kc % grid.nx, jc = kc / grid.nx;
        const double v = change_value[c];
        for (int j = 0; j < grid.ny; ++j) {
          const double* row = offsets.data() + static_cast<size_t>(j - jc + grid.ny - 1) * ax +
                              (grid.nx - 1 - ic);
          double* uj = w.u.data() + static_cast<size_t>(j) * grid.nx;
          for (int i = 0; i < grid.nx; ++i) uj[i] += v * row[i];
        }
      }
    }
    delta_flag = overlap ? 0.0 : 1.0;
    double sum = 0.0;
    for (double v : p) sum += v;
    if (load_control && sum > 0.0) {
      const double scale = target / (sum * dA);
      for (double& v : p) v *= scale;
      if (u_current)
        for (double& v : w.u) v *= scale;
    }
    double change = 0.0, total = 0.0;
    for (int k = 0; k < n; ++k) {
      change += std::abs(p[k] - w.p_old[k]);
      total += p[k];
    }
    if (total <= 0.0) break;
    if (change <= options.tolerance * total) {
      converged = true;
      break;
    }
  }
  s.approach = mean_gap;
  s.status |= converged ? status::kConverged : status::kNotConverged;
  summarise(grid, s);
}

}  // namespace

void solve_normal_for_force(const Grid& grid, const std::vector<double>& gap, double normal_force,
                            const Material& material, const NormalSolverOptions& options,
                            Workspace& workspace, NormalSolution& solution) {
  if (!usable(grid, gap) || !(normal_force > 0.0) || !std::isfinite(normal_force)) {
    solution = NormalSolution{};
    solution.status = status::kInvalidInput;
    return;
  }
  bccg(grid, gap, true, normal_force, material, options, workspace, solution);
}

void solve_normal_for_approach(const Grid& grid, const std::vector<double>& gap, double approach,
                               const Material& material, const NormalSolverOptions& options,
                               Workspace& workspace, NormalSolution& solution) {
  if (!usable(grid, gap) || !std::isfinite(approach)) {
    solution = NormalSolution{};
    solution.status = status::kInvalidInput;
    return;
  }
  if (approach <= *std::min_element(gap.begin(), gap.end())) {  // no overlap: no contact
    solution = NormalSolution{};
    solution.pressure.assign(grid.size(), 0.0);
    solution.approach = approach;
    solution.status = status::kConverged | status::kLiftOff;
    return;
  }
  bccg(grid, gap, false, approach, material, options, workspace, solution);
}

}  // namespace railtab::halfspace
