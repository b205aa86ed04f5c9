// SPDX-License-Identifier: Apache-2.0
// Equivalent conicity from a sampled Delta r(y): the kinematic oscillation's wavelength (EN 15302's
// reference principle) and the harmonic linear regression (its annex method).
//
// Reference principle. A free wheelset rolling without slip obeys y'' = -Delta r(y) / (2 e0 r0)
// (Klingel), so (y')^2 = (C - S(y)) / (e0 r0) with S(y) = int_{y_c}^{y} Delta r dy and C = S at both
// turning points. One wavelength is lambda = 2 int_{y_min}^{y_max} dy / y' = 2 sqrt(e0 r0) I with
// I = int dy / sqrt(C - S(y)), and a cone of slope g has lambda = 2 pi sqrt(e0 r0 / g), so the
// equivalent conicity is g = (pi / I)^2: e0 and r0 cancel. Delta r is interpolated linearly, so S
// is piecewise quadratic and the turning points follow exactly from the quadratic of their cell.
// I has 1/sqrt singularities at both turning points; the substitution y = y_turn -+ L s^2 removes
// them and a composite Gauss-Legendre rule integrates the smooth remainder.
#include "geometry/equivalent_conicity.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/check.hpp"

namespace railtab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_samples(const LateralFunction& f, const char* what) {
  RAILTAB_CHECK(f.y.size() == f.value.size(), "equivalent conicity: {} has {} y samples but {} values", what,
                f.y.size(), f.value.size());
  RAILTAB_CHECK(f.y.size() >= 3, "equivalent conicity: {} needs at least 3 samples along y, got {}", what,
                f.y.size());
  for (std::size_t i = 0; i < f.y.size(); ++i) {
    RAILTAB_CHECK(std::isfinite(f.y[i]) && std::isfinite(f.value[i]),
                  "equivalent conicity: {} sample {} is not finite (y = {}, value = {})", what, i, f.y[i], f.value[i]);
    RAILTAB_CHECK(i == 0 || f.y[i] > f.y[i - 1], "equivalent conicity: {} y samples must increase (y[{}] = {} after {})",
                  what, i, f.y[i], f.y[i - 1]);
  }
}

// Index k of the cell [y_k, y_k+1] holding y (clamped to the first and last cell).
std::size_t cell_of(const std::vector<double>& y, double x) {
  const auto it = std::upper_bound(y.begin(), y.end(), x);
  const std::size_t k = it == y.begin() ? 0 : static_cast<std::size_t>(it - y.begin()) - 1;
  return std::min(k, y.size() - 2);
}

// S(y) = int_{y_c}^{y} Delta r for the linear interpolant: its node values and the exact
// quadratic inside each cell.
class DeltaRIntegral {
 public:
  DeltaRIntegral(const LateralFunction& dr, double centre) : y_(dr.y), d_(dr.value), s_(dr.y.size(), 0.0) {
    for (std::size_t i = 1; i < y_.size(); ++i) s_[i] = s_[i - 1] + 0.5 * (d_[i - 1] + d_[i]) * (y_[i] - y_[i - 1]);
    const double at_centre = (*this)(centre);
    for (double& s : s_) s -= at_centre;
    centre_cell_ = cell_of(y_, centre);
    centre_ = centre;
  }

  double operator()(double y) const { return in_cell(cell_of(y_, y), y); }

  // First y beyond the centre (direction +1: increasing y, -1: decreasing) where S reaches `level`
  // (> 0); NaN when it does not within the samples.
  double first_crossing(double level, int direction) const {
    const long last = static_cast<long>(y_.size()) - 2;
    for (long k = static_cast<long>(centre_cell_); k >= 0 && k <= last; k += direction) {
      const auto cell = static_cast<std::size_t>(k);
      // The part of the cell on the walking side of the centre.
      const double lo = (cell == centre_cell_ && direction > 0) ? centre_ : y_[cell];
      const double hi = (cell == centre_cell_ && direction < 0) ? centre_ : y_[cell + 1];
      const double root = crossing_in_cell(cell, level, lo, hi, direction);
      if (!std::isnan(root)) return root;
    }
    return kNaN;
  }

  // Largest S reached walking from the centre in `direction` within the samples: at a node or
  // inside a cell where Delta r falls through zero (a maximum of S).
  double max_level(int direction) const {
    double best = 0.0;
    for (std::size_t i = 0; i < y_.size(); ++i) {
      if ((direction > 0) == (y_[i] > centre_)) best = std::max(best, s_[i]);
    }
    for (std::size_t k = 0; k + 1 < y_.size(); ++k) {
      if (!(d_[k] > 0.0 && d_[k + 1] < 0.0)) continue;
      const double y_zero = y_[k] + d_[k] / (d_[k] - d_[k + 1]) * (y_[k + 1] - y_[k]);
      if ((direction > 0) == (y_zero > centre_)) best = std::max(best, in_cell(k, y_zero));
    }
    return best;
  }

 private:
  double in_cell(std::size_t k, double y) const {
    const double t = y - y_[k];
    const double slope = (d_[k + 1] - d_[k]) / (y_[k + 1] - y_[k]);
    return s_[k] + t * (d_[k] + 0.5 * slope * t);
  }

  // The crossing of S = level inside [lo, hi] of cell k met first when walking in `direction`.
  double crossing_in_cell(std::size_t k, double level, double lo, double hi, int direction) const {
    const double a = 0.5 * (d_[k + 1] - d_[k]) / (y_[k + 1] - y_[k]);
    const double b = d_[k];
    const double c = s_[k] - level;
    std::array<double, 2> roots = {kNaN, kNaN};
    if (a == 0.0) {
      if (b != 0.0) roots[0] = -c / b;
    } else {
      const double disc = b * b - 4.0 * a * c;
      if (disc >= 0.0) {
        const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        roots = {q / a, q != 0.0 ? c / q : kNaN};
      }
    }
    double best = kNaN;
    for (double t : roots) {
      const double y = y_[k] + t;
      if (std::isnan(t) || y < lo || y > hi) continue;
      if (std::isnan(best) || (direction > 0 ? y < best : y > best)) best = y;
    }
    return best;
  }

  const std::vector<double>& y_;
  const std::vector<double>& d_;
  std::vector<double> s_;  // S at the nodes [m^2]
  std::size_t centre_cell_ = 0;
  double centre_ = 0.0;
};

// int_{a}^{b} dy / sqrt(level - S(y)) where S(turn) = level at the end `turn` (a or b) and
// S < level inside, via y = turn -+ L s^2 (L = b - a), composite 5-point Gauss-Legendre in s.
double half_period_integral(const DeltaRIntegral& s_of_y, double level, double turn, double other) {
  static constexpr std::array<double, 5> kNode = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                                  0.5384693101056831, 0.9061798459386640};
  static constexpr std::array<double, 5> kWeight = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                                    0.4786286704993665, 0.2369268850561891};
  constexpr int kPanels = 400;
  const double length = other - turn;  // signed
  double sum = 0.0;
  for (int p = 0; p < kPanels; ++p) {
    const double mid = (p + 0.5) / kPanels;
    const double half = 0.5 / kPanels;
    for (std::size_t j = 0; j < kNode.size(); ++j) {
      const double s = mid + half * kNode[j];
      const double y = turn + length * s * s;
      const double gap = std::max(level - s_of_y(y), std::numeric_limits<double>::min());
      sum += kWeight[j] * half * 2.0 * std::abs(length) * s / std::sqrt(gap);
    }
  }
  return sum;
}

}  // namespace

double interpolate_lateral(const LateralFunction& f, double y) {
  if (!(y >= f.y.front() && y <= f.y.back())) return kNaN;
  const std::size_t k = cell_of(f.y, y);
  const double w = (y - f.y[k]) / (f.y[k + 1] - f.y[k]);
  return f.value[k] + w * (f.value[k + 1] - f.value[k]);
}

double kinematic_centre(const LateralFunction& delta_r) {
  check_samples(delta_r, "Delta r");
  const std::vector<double>& y = delta_r.y;
  const std::vector<double>& d = delta_r.value;
  double best = kNaN;
  for (std::size_t k = 0; k + 1 < y.size(); ++k) {
    // Rising through zero: d_k <= 0 < d_k+1 (a zero node counts once, for the cell it starts).
    if (!(d[k] <= 0.0 && d[k + 1] > 0.0)) continue;
    const double zero = y[k] + (-d[k]) / (d[k + 1] - d[k]) * (y[k + 1] - y[k]);
    if (std::isnan(best) || std::abs(zero) < std::abs(best)) best = zero;
  }
  RAILTAB_CHECK(!std::isnan(best),
                "equivalent conicity: Delta r does not rise through zero between y = {} and {} m: no kinematic "
                "oscillation (Delta r from {} to {} m)",
                y.front(), y.back(), d.front(), d.back());
  return best;
}

KinematicOscillation kinematic_oscillation(const LateralFunction& delta_r, double amplitude) {
  RAILTAB_CHECK(std::isfinite(amplitude) && amplitude > 0.0,
                "equivalent conicity: amplitude must be a positive number of metres, got {}", amplitude);
  const double centre = kinematic_centre(delta_r);
  const DeltaRIntegral s_of_y(delta_r, centre);
  KinematicOscillation out;
  out.amplitude = amplitude;
  out.conicity = kNaN;
  auto half_width = [&](double level, double& y_min, double& y_max) {
    y_max = s_of_y.first_crossing(level, +1);
    y_min = s_of_y.first_crossing(level, -1);
    return 0.5 * (y_max - y_min);
  };
  // (y_max - y_min)/2 grows with the level C (the first crossings move outwards): bisect on C.
  // The highest level both sides reach (a hair below, so that rounding cannot lose its crossing).
  const double top = std::min(s_of_y.max_level(+1), s_of_y.max_level(-1)) * (1.0 - 1e-12);
  double y_min = kNaN, y_max = kNaN;
  if (!(top > 0.0) || !(half_width(top, y_min, y_max) >= amplitude)) {
    out.y_min = y_min;
    out.y_max = y_max;
    return out;  // the motion leaves the sampled range
  }
  double lo = 0.0, hi = top;
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (half_width(mid, y_min, y_max) >= amplitude ? hi : lo) = mid;
  }
  half_width(hi, y_min, y_max);
  out.y_min = y_min;
  out.y_max = y_max;
  out.amplitude = 0.5 * (y_max - y_min);
  const double integral = half_period_integral(s_of_y, hi, y_max, centre) + half_period_integral(s_of_y, hi, y_min, centre);
  out.conicity = std::pow(std::numbers::pi / integral, 2);
  return out;
}

double harmonic_regression_slope(const LateralFunction& f, double centre, double amplitude) {
  check_samples(f, "the regressed function");
  RAILTAB_CHECK(std::isfinite(amplitude) && amplitude > 0.0 && std::isfinite(centre),
                "equivalent conicity: regression needs a finite centre and a positive amplitude, got {} and {} m",
                centre, amplitude);
  // Equal steps in phase sample y with the density of the harmonic motion, 1 / (pi sqrt(A^2 - y^2)).
  constexpr int kSamples = 3600;
  double sy = 0.0, sf = 0.0, syy = 0.0, syf = 0.0;
  for (int k = 0; k < kSamples; ++k) {
    const double y = centre + amplitude * std::sin(2.0 * std::numbers::pi * (k + 0.5) / kSamples);
    const double v = interpolate_lateral(f, y);
    if (std::isnan(v)) return kNaN;
    sy += y;
    sf += v;
    syy += y * y;
    syf += y * v;
  }
  const double n = kSamples;
  return (syf - sy * sf / n) / (syy - sy * sy / n);
}

double regression_conicity(const LateralFunction& delta_r, double amplitude) {
  return 0.5 * harmonic_regression_slope(delta_r, kinematic_centre(delta_r), amplitude);
}

}  // namespace railtab
