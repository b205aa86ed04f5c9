// SPDX-License-Identifier: Apache-2.0
// Steady rolling with Coulomb friction on a grid (tangential_solver.hpp): Kalker's exact theory.
#include "halfspace/tangential_solver.hpp"

#include <algorithm>
#include <cmath>

namespace railtab::halfspace {
namespace {

// Local problem of one element in slip: s = s0 - g D e, e = s/|s|, D = diag(dxx, dyy) > 0.
// s_i = s0_i sigma / (sigma + g d_i) with sigma = |s| the root of
// sum s0_i^2 / (sigma + g d_i)^2 = 1 (decreasing and convex in sigma). Newton starts from the
// root with D replaced by its mean along s0, d = (dxx s0x^2 + dyy s0y^2) / |s0|^2 (the root itself
// when dxx = dyy; off by second order in (dxx - dyy) otherwise), kept above the lower bound
// |s0| - g max(d_i): a step from above the root of a convex decreasing function lands below it,
// and from there Newton converges monotonically and quadratically: a step below 1e-7 of
// sigma + g dxx leaves an error of about 3 (1e-7)^2 of it, so the loop stops there (it stopped at
// 1e-14, one more iteration for nothing). This is the solver's innermost loop (about a quarter of
// a table's time): per call 2.2 (tread) and 2.4 (flange) iterations, where the lower bound and the
// 1e-14 stop took 4.5 (a table column each, BM_CreepageColumnWarm), each with 3 divisions instead
// of 5. Returns the traction p = -g s / sigma.
void slip_traction(double s0x, double s0y, double g, double dxx, double dyy, double* px,
                   double* py) {
  const double s0sq = s0x * s0x + s0y * s0y;
  const double s0 = std::sqrt(s0sq);
  const double lower = std::max(0.0, s0 - g * std::max(dxx, dyy));
  double sigma = s0sq > 0.0 ? std::max(lower, s0 - g * (dxx * s0x * s0x + dyy * s0y * s0y) / s0sq) : lower;
  for (int k = 0; k < 60; ++k) {
    const double rx = 1.0 / (sigma + g * dxx), ry = 1.0 / (sigma + g * dyy);
    const double fx = s0x * rx, fy = s0y * ry;
    const double f = fx * fx + fy * fy - 1.0;
    const double df = -2.0 * (fx * fx * rx + fy * fy * ry);
    const double next = std::max(lower, sigma - f / df);
    const double step = next - sigma;
    sigma = next;
    if (!(std::abs(step) > 1e-7 * (sigma + g * dxx))) break;
  }
  *px = -g * s0x / (sigma + g * dxx);
  *py = -g * s0y / (sigma + g * dyy);
}

// Dot product with four partial sums: the adds of one sum wait on each other (no reordering
// without -ffast-math), four independent ones keep the pipeline busy. Deterministic (fixed
// order for a given length).
double dot(const double* a, const double* b, int n) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int k = 0;
  for (; k + 4 <= n; k += 4) {
    s0 += a[k] * b[k];
    s1 += a[k + 1] * b[k + 1];
    s2 += a[k + 2] * b[k + 2];
    s3 += a[k + 3] * b[k + 3];
  }
  for (; k < n; ++k) s0 += a[k] * b[k];
  return (s0 + s1) + (s2 + s3);
}

}  // namespace

void solve_tangential(const Grid& grid, const std::vector<double>& pressure,
                      const RollingCreepage& creepage, double mu, const Material& material,
                      const TangentialSolverOptions& options, Workspace& w,
                      TangentialSolution& out) {
  const int n = grid.size();
  out.status = 0;
  out.sweeps = 0;
  out.fx = out.fy = out.mz = out.slip_area = out.frictional_work = 0.0;
  const bool ok = pressure.size() == static_cast<size_t>(n) && n > 0 && std::isfinite(mu) &&
                  mu >= 0.0 && std::isfinite(creepage.xi) && std::isfinite(creepage.eta) &&
                  std::isfinite(creepage.phi) &&
                  std::all_of(pressure.begin(), pressure.end(),
                              [](double p) { return std::isfinite(p) && p >= 0.0; });
  if (!ok) {
    out.status = status::kInvalidInput;
    return;
  }
  // The Gauss-Seidel sweeps use A / dx between every pair of contact elements (exact).
  // (The upwind coupling needs the kernel at the element behind: a window of at least 1.)
  const int window = options.window < 0 ? std::max(grid.nx, grid.ny) : options.window;
  const TangentialKernels K =
      w.tangential_kernels(grid, material, options.upwind ? std::max(window, 1) : window);
  const NearKernel& near = options.steady_sweep ? *K.near_b : *K.near;
  const double dxx = near.at(near.xx, 0, 0), dyy = near.at(near.yy, 0, 0);
  std::vector<double>& px = out.traction_x;
  std::vector<double>& py = out.traction_y;
  if (px.size() != static_cast<size_t>(n) || py.size() != static_cast<size_t>(n)) {
    px.assign(n, 0.0);
    py.assign(n, 0.0);
  }
  out.slip_x.resize(n);
  out.slip_y.resize(n);
  out.state.assign(n, 0);
  std::vector<double>& sx = out.slip_x;
  std::vector<double>& sy = out.slip_y;
  double force_bound = 0.0;
  for (int k = 0; k < n; ++k) {
    if (!(pressure[k] > 0.0)) px[k] = py[k] = 0.0;  // warm start on a changed contact
    force_bound += mu * pressure[k];
  }
  Spectrum& spx = w.field_a;
  Spectrum& spy = w.field_b;
  auto convolve = [&](const Spectrum* kxx, const Spectrum* kxy, const Spectrum* kyy, double* ox,
                      double* oy) {
    const Spectrum* f[2] = {&spx, &spy};
    const Spectrum* k1[2] = {kxx, kxy};
    K.fft->convolve(k1, f, 2, ox);
    const Spectrum* k2[2] = {kxy, kyy};
    K.fft->convolve(k2, f, 2, oy);
  };
  // Contact elements in sweep order: row by row, each from the leading edge backwards.
  std::vector<int> list;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = grid.nx - 1; i >= 0; --i)
      if (pressure[grid.index(i, j)] > 0.0) list.push_back(grid.index(i, j));
  const int m = static_cast<int>(list.size());
  std::vector<int> pos(n, -1);  // grid index -> position in list
  for (int a = 0; a < m; ++a) pos[list[a]] = a;
  const int W = options.window;
  std::vector<double> lsx(m), lsy(m), lpx(m), lpy(m);
  // Spin parts of the rigid slip of each contact element (list order), the same in every step.
  std::vector<double> spin_x(m), spin_y(m);
  for (int a = 0; a < m; ++a) {
    const int k = list[a], i = k % grid.nx, j = k / grid.nx;
    spin_x[a] = creepage.phi * grid.y(j);
    spin_y[a] = creepage.phi * grid.x(i);
  }
  // With one sweep and no neighbours coupled, the slip update after an element's own step is
  // never read again: skipped. The upwind coupling alone (window 0) updates only the element
  // behind in the same row, the next one in the sweep order.
  const bool upwind_only = options.upwind && W == 0;
  const bool couple = W != 0 || upwind_only || options.max_inner_sweeps > 1;
  const double bxx_behind = upwind_only ? near.at(near.xx, -1, 0) : 0.0;
  const double bxy_behind = upwind_only ? near.at(near.xy, -1, 0) : 0.0;
  const double byy_behind = upwind_only ? near.at(near.yy, -1, 0) : 0.0;
  // One rolling step Phi: the tractions p (list order) -> the tractions p' that satisfy the
  // element conditions with the displacements of p at the previous position frozen,
  // s = w + B p + A (p' - p) / dx, by Gauss-Seidel (convex: converges).
  int slipping_now = 0, slipping_before = -1;
  auto rolling_step = [&](std::vector<double>& qx, std::vector<double>& qy) {
    std::fill(px.begin(), px.end(), 0.0);
    std::fill(py.begin(), py.end(), 0.0);
    for (int a = 0; a < m; ++a) {
      px[list[a]] = qx[a];
      py[list[a]] = qy[a];
    }
    K.fft->forward(px.data(), spx);
    K.fft->forward(py.data(), spy);
    convolve(K.bxx, K.bxy, K.byy, sx.data(), sy.data());
    for (int a = 0; a < m; ++a) {
      lsx[a] = sx[list[a]] + creepage.xi - spin_x[a];
      lsy[a] = sy[list[a]] + creepage.eta + spin_y[a];
    }
    double total = 0.0;
    for (int sweep = 0; sweep < options.max_inner_sweeps; ++sweep) {
      slipping_now = 0;
      double change = 0.0;
      total = 0.0;
      for (int a = 0; a < m; ++a) {
        const int k = list[a];
        const double g = mu * pressure[k];
        const double s0x = lsx[a] - dxx * qx[a], s0y = lsy[a] - dyy * qy[a];
        double nx = -s0x / dxx, ny = -s0y / dyy;  // adhesion: s = 0
        if (nx * nx + ny * ny > g * g) {
          slip_traction(s0x, s0y, g, dxx, dyy, &nx, &ny);
          ++slipping_now;
        }
        const double dpx = nx - qx[a], dpy = ny - qy[a];
        qx[a] = nx;
        qy[a] = ny;
        total += std::abs(nx) + std::abs(ny);
        if (dpx == 0.0 && dpy == 0.0) continue;
        change += std::abs(dpx) + std::abs(dpy);
        if (!couple) continue;
        const int i = k % grid.nx, j = k / grid.nx;
        if (upwind_only) {
          const int b = i > 0 ? pos[k - 1] : -1;
          if (b >= 0) {
            lsx[b] += bxx_behind * dpx + bxy_behind * dpy;
            lsy[b] += bxy_behind * dpx + byy_behind * dpy;
          }
        } else if (W < 0) {
          for (int b = 0; b < m; ++b) {
            const int kb = list[b];
            const int di = kb % grid.nx - i, dj = kb / grid.nx - j;
            const double axx = near.at(near.xx, di, dj), axy = near.at(near.xy, di, dj);
            const double ayy = near.at(near.yy, di, dj);
            lsx[b] += axx * dpx + axy * dpy;
            lsy[b] += axy * dpx + ayy * dpy;
          }
        } else {
          for (int jj = std::max(0, j - W); jj <= std::min(grid.ny - 1, j + W); ++jj)
            for (int ii = std::max(0, i - W); ii <= std::min(grid.nx - 1, i + W); ++ii) {
              const int b = pos[grid.index(ii, jj)];
              if (b < 0) continue;
              const double axx = near.at(near.xx, ii - i, jj - j);
              const double axy = near.at(near.xy, ii - i, jj - j);
              const double ayy = near.at(near.yy, ii - i, jj - j);
              lsx[b] += axx * dpx + axy * dpy;
              lsy[b] += axy * dpx + ayy * dpy;
            }
        }
      }
      if (change <= options.inner_tolerance * total) break;
    }
  };
  // Fixed point p = Phi(p) (the steady state), accelerated by Anderson mixing (options.anderson_depth): the
  // plain iteration is transient rolling, which forgets its start only as material crosses the
  // patch.
  const int depth = std::max(0, options.anderson_depth);
  const int len = 2 * m;
  std::vector<double> x(len, 0.0), fx(len), x_prev, f_prev;
  // History in a ring of `depth` slots: dF the change of the update's residual, dG = dX +
  // mixing dF (the only form in which dX enters the step), gram = dF^T dF.
  std::vector<double> dF(static_cast<size_t>(depth) * len), dG(static_cast<size_t>(depth) * len);
  std::vector<double> gram(static_cast<size_t>(depth) * depth);
  int stored = 0, newest = -1;  // slots in use; slot of the newest difference
  for (int a = 0; a < m; ++a) {
    x[a] = px[list[a]];
    x[m + a] = py[list[a]];
  }
  bool converged = force_bound <= 0.0 || m == 0;  // no friction or no load: no traction
  std::vector<double> qx(m), qy(m), M, rhs, gamma, fdot(depth, 0.0);  // fdot: dF_slot . f
  std::vector<int> order(depth);  // slots oldest first
  for (int step = 1; step <= options.max_steps && !converged; ++step) {
    out.sweeps = step;
    for (int a = 0; a < m; ++a) {
      qx[a] = x[a];
      qy[a] = x[m + a];
    }
    rolling_step(qx, qy);
    double fnorm = 0.0, pnorm = 0.0;
    for (int a = 0; a < m; ++a) {
      fx[a] = qx[a] - x[a];
      fx[m + a] = qy[a] - x[m + a];
      fnorm += std::abs(fx[a]) + std::abs(fx[m + a]);
      pnorm += std::abs(qx[a]) + std::abs(qy[a]);
    }
    if (fnorm <= options.tolerance * pnorm) {
      converged = true;
      x.assign(qx.begin(), qx.end());
      x.insert(x.end(), qy.begin(), qy.end());
      break;
    }
    // A change of the slip set changes the map: the history no longer describes it.
    if (options.restart_on_slip_change && slipping_now != slipping_before) {
      stored = 0;
      x_prev.clear();
    }
    slipping_before = slipping_now;
    if (!x_prev.empty() && depth > 0) {
      const int slot = (newest + 1) % depth;  // the oldest when full
      newest = slot;
      stored = std::min(stored + 1, depth);
      double* df = dF.data() + static_cast<size_t>(slot) * len;
      double* dg = dG.data() + static_cast<size_t>(slot) * len;
      for (int k = 0; k < len; ++k) {
        df[k] = fx[k] - f_prev[k];
        dg[k] = (x[k] - x_prev[k]) + options.mixing * df[k];
      }
      const double self = dot(df, df, len), with_f = dot(df, fx.data(), len);
      for (int a = 0; a < stored; ++a) {
        const int sa = (slot - a + depth) % depth;
        if (sa == slot) continue;
        const double* other = dF.data() + static_cast<size_t>(sa) * len;
        const double sum = dot(other, df, len);
        gram[static_cast<size_t>(sa) * depth + slot] = gram[static_cast<size_t>(slot) * depth + sa] = sum;
        // dF_a . f = dF_a . f_prev + dF_a . (f - f_prev): the right-hand side of the least
        // squares problem without another pass over the history.
        fdot[sa] += sum;
      }
      gram[static_cast<size_t>(slot) * depth + slot] = self;
      fdot[slot] = with_f;
    }
    x_prev = x;
    f_prev = fx;
    const int h = stored;
    gamma.assign(h, 0.0);
    if (h > 0) {  // least squares min |f - dF gamma| by the normal equations, oldest first
      for (int a = 0; a < h; ++a) order[a] = (newest - (h - 1 - a) + depth) % depth;
      M.assign(static_cast<size_t>(h) * h, 0.0);
      rhs.assign(h, 0.0);
      for (int a = 0; a < h; ++a) {
        for (int b = 0; b < h; ++b) M[a * h + b] = gram[static_cast<size_t>(order[a]) * depth + order[b]];
        rhs[a] = fdot[order[a]];
        M[a * h + a] *= 1.0 + 1e-10;
      }
      for (int c = 0; c < h; ++c) {  // Gaussian elimination with partial pivoting
        int piv = c;
        for (int r = c + 1; r < h; ++r)
          if (std::abs(M[r * h + c]) > std::abs(M[piv * h + c])) piv = r;
        for (int b = 0; b < h; ++b) std::swap(M[c * h + b], M[piv * h + b]);
        std::swap(rhs[c], rhs[piv]);
        if (M[c * h + c] == 0.0) continue;
        for (int r = c + 1; r < h; ++r) {
          const double f = M[r * h + c] / M[c * h + c];
          for (int b = c; b < h; ++b) M[r * h + b] -= f * M[c * h + b];
          rhs[r] -= f * rhs[c];
        }
      }
      for (int c = h - 1; c >= 0; --c) {
        double sum = rhs[c];
        for (int b = c + 1; b < h; ++b) sum -= M[c * h + b] * gamma[b];
        gamma[c] = M[c * h + c] != 0.0 ? sum / M[c * h + c] : 0.0;
      }
    }
    for (int k = 0; k < len; ++k) x[k] += options.mixing * fx[k];
    for (int a = 0; a < h; ++a) {
      const double* dg = dG.data() + static_cast<size_t>(order[a]) * len;
      const double ga = gamma[a];
      for (int k = 0; k < len; ++k) x[k] -= ga * dg[k];
    }
  }
  if (!converged) {  // keep a feasible state: one more rolling step from the last iterate
    for (int a = 0; a < m; ++a) {
      qx[a] = x[a];
      qy[a] = x[m + a];
    }
    if (m > 0 && force_bound > 0.0) rolling_step(qx, qy);
    x.assign(qx.begin(), qx.end());
    x.insert(x.end(), qy.begin(), qy.end());
  }
  std::fill(px.begin(), px.end(), 0.0);
  std::fill(py.begin(), py.end(), 0.0);
  for (int a = 0; a < m; ++a) {
    px[list[a]] = x[a];
    py[list[a]] = x[m + a];
  }
  // Final slip from the final tractions (exact), forces and states.
  K.fft->forward(px.data(), spx);
  K.fft->forward(py.data(), spy);
  convolve(K.bxx, K.bxy, K.byy, sx.data(), sy.data());
  const double dA = grid.element_area();
  int loaded = 0, slipping = 0;
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const int k = grid.index(i, j);
      sx[k] += creepage.xi - creepage.phi * grid.y(j);
      sy[k] += creepage.eta + creepage.phi * grid.x(i);
      if (!(pressure[k] > 0.0)) {
        sx[k] = sy[k] = 0.0;
        continue;
      }
      ++loaded;
      const double g = mu * pressure[k];
      // Slip when the traction sits on the bound (to rounding); adhesion elements have s = 0.
      const bool slip = std::hypot(px[k], py[k]) >= g * (1.0 - 1e-9);
      out.state[k] = slip ? 2 : 1;
      if (slip) {
        ++slipping;
      } else {
        sx[k] = sy[k] = 0.0;
      }
      out.fx += px[k] * dA;
      out.fy += py[k] * dA;
      out.mz += (grid.x(i) * py[k] - grid.y(j) * px[k]) * dA;
      out.frictional_work -= (px[k] * sx[k] + py[k] * sy[k]) * dA;
    }
  out.slip_area = slipping * dA;
  out.status |= converged ? status::kConverged : status::kNotConverged;
  if (loaded > 0 && slipping == loaded) out.status |= status::kFullSlip;
}

}  // namespace railtab::halfspace
