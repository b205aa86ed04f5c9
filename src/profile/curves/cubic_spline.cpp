// SPDX-License-Identifier: Apache-2.0
// Cubic splines through points, interpolating or smoothing (cubic_spline.hpp).
#include "profile/curves/cubic_spline.hpp"

#include <Eigen/Sparse>

#include <algorithm>
#include <utility>

#include "core/check.hpp"

namespace railtab::detail {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Second derivatives of the not-a-knot interpolating spline: the C2 conditions at the interior
// knots plus a continuous third derivative at the second and the second-to-last knot.
std::vector<double> not_a_knot_second_derivatives(const std::vector<double>& u,
                                                  const std::vector<double>& z) {
  const auto n = static_cast<Eigen::Index>(u.size()) - 1;  // number of intervals
  auto h = [&](Eigen::Index i) { return u[static_cast<std::size_t>(i) + 1] - u[static_cast<std::size_t>(i)]; };
  auto zi = [&](Eigen::Index i) { return z[static_cast<std::size_t>(i)]; };
  Triplets t;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  t.emplace_back(0, 0, h(1));
  t.emplace_back(0, 1, -(h(0) + h(1)));
  t.emplace_back(0, 2, h(0));
  for (Eigen::Index i = 1; i < n; ++i) {
    t.emplace_back(i, i - 1, h(i - 1));
    t.emplace_back(i, i, 2.0 * (h(i - 1) + h(i)));
    t.emplace_back(i, i + 1, h(i));
    rhs(i) = 6.0 * ((zi(i + 1) - zi(i)) / h(i) - (zi(i) - zi(i - 1)) / h(i - 1));
  }
  t.emplace_back(n, n - 2, h(n - 1));
  t.emplace_back(n, n - 1, -(h(n - 2) + h(n - 1)));
  t.emplace_back(n, n, h(n - 2));
  Eigen::SparseMatrix<double> a(n + 1, n + 1);
  a.setFromTriplets(t.begin(), t.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(a);
  RAILTAB_CHECK(lu.info() == Eigen::Success, "spline: singular not-a-knot system");
  const Eigen::VectorXd m = lu.solve(rhs);
  return std::vector<double>(m.data(), m.data() + m.size());
}

// Reinsch's smoothing spline (Green & Silverman's formulation): with the tridiagonal Q
// ((n+1) x (n-1)) and R ((n-1) x (n-1)) of the natural spline, solve the pentadiagonal SPD
// system (R + lambda Q^T W^-1 Q) gamma = Q^T z for the interior second derivatives gamma, then
// the smoothed values are z - lambda W^-1 Q gamma. Overwrites z with the smoothed values.
std::vector<double> smoothing_second_derivatives(const std::vector<double>& u, std::vector<double>& z,
                                                 double lambda) {
  const std::size_t n = u.size() - 1;  // intervals; unknowns gamma_1 .. gamma_{n-1}
  std::vector<double> h(n);
  for (std::size_t i = 0; i < n; ++i) h[i] = u[i + 1] - u[i];
  std::vector<double> w(n + 1);
  w[0] = 0.5 * h[0];
  w[n] = 0.5 * h[n - 1];
  for (std::size_t i = 1; i < n; ++i) w[i] = 0.5 * (h[i - 1] + h[i]);

  // Q column j (interior knot i = j + 1) has entries at rows i-1, i, i+1.
  Triplets q_t;
  Triplets r_t;
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const std::size_t i = j + 1;
    const auto col = static_cast<Eigen::Index>(j);
    q_t.emplace_back(static_cast<Eigen::Index>(i - 1), col, 1.0 / h[i - 1]);
    q_t.emplace_back(static_cast<Eigen::Index>(i), col, -1.0 / h[i - 1] - 1.0 / h[i]);
    q_t.emplace_back(static_cast<Eigen::Index>(i + 1), col, 1.0 / h[i]);
    r_t.emplace_back(col, col, (h[i - 1] + h[i]) / 3.0);
    if (j + 2 < n) {
      r_t.emplace_back(col, col + 1, h[i] / 6.0);
      r_t.emplace_back(col + 1, col, h[i] / 6.0);
    }
  }
  const auto rows = static_cast<Eigen::Index>(n + 1);
  const auto cols = static_cast<Eigen::Index>(n - 1);
  Eigen::SparseMatrix<double> q(rows, cols);
  q.setFromTriplets(q_t.begin(), q_t.end());
  Eigen::SparseMatrix<double> r(cols, cols);
  r.setFromTriplets(r_t.begin(), r_t.end());
  Eigen::VectorXd w_inv(rows);
  for (std::size_t i = 0; i <= n; ++i) w_inv(static_cast<Eigen::Index>(i)) = 1.0 / w[i];
  const Eigen::SparseMatrix<double> w_inv_q = w_inv.asDiagonal() * q;
  const Eigen::SparseMatrix<double> a = r + lambda * (q.transpose() * w_inv_q);
  const Eigen::Map<const Eigen::VectorXd> z_vec(z.data(), rows);
  const Eigen::VectorXd rhs = q.transpose() * z_vec;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  ldlt.compute(a);
  RAILTAB_CHECK(ldlt.info() == Eigen::Success, "spline: smoothing system not positive definite");
  const Eigen::VectorXd gamma = ldlt.solve(rhs);
  const Eigen::VectorXd smoothed = z_vec - lambda * (w_inv_q * gamma);
  for (std::size_t i = 0; i <= n; ++i) z[i] = smoothed(static_cast<Eigen::Index>(i));
  std::vector<double> m(n + 1, 0.0);  // natural ends
  for (std::size_t j = 0; j + 1 < n; ++j) m[j + 1] = gamma(static_cast<Eigen::Index>(j));
  return m;
}

}  // namespace

CubicSpline CubicSpline::interpolate(std::vector<double> x, std::vector<double> f) {
  CubicSpline s;
  s.d2f = not_a_knot_second_derivatives(x, f);
  s.x = std::move(x);
  s.f = std::move(f);
  return s;
}

CubicSpline CubicSpline::smooth(std::vector<double> x, std::vector<double> f, double lambda) {
  CubicSpline s;
  s.d2f = smoothing_second_derivatives(x, f, lambda);
  s.x = std::move(x);
  s.f = std::move(f);
  return s;
}

void CubicSpline::eval(double at, double& value, double& d1, double& d2) const {
  // Interval [x_i, x_{i+1}] holding `at`; the last interval is closed at the end.
  const auto it = std::upper_bound(x.begin() + 1, x.end() - 1, at);
  const auto i = static_cast<std::size_t>(it - x.begin()) - 1;
  const double h = x[i + 1] - x[i];
  const double a = x[i + 1] - at;  // distance to the right knot
  const double b = at - x[i];      // distance to the left knot
  const double m0 = d2f[i];
  const double m1 = d2f[i + 1];
  const double c0 = f[i] / h - m0 * h / 6.0;
  const double c1 = f[i + 1] / h - m1 * h / 6.0;
  value = (m0 * a * a * a + m1 * b * b * b) / (6.0 * h) + c0 * a + c1 * b;
  d1 = (m1 * b * b - m0 * a * a) / (2.0 * h) + c1 - c0;
  d2 = (m0 * a + m1 * b) / h;
}

}  // namespace railtab::detail
