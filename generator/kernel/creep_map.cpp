// SPDX-License-Identifier: Apache-2.0
// Normalised creep coordinates (creep_map.hpp): node maps, saturation law, scales, vertical share.
#include "kernel/creep_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tangential/kalker_coefficients.hpp"

namespace railtab::creep_map {
namespace {

double m(double x) { return x / (1.0 + std::abs(x)); }
double m_inverse(double u) { return u / (1.0 - std::abs(u)); }

}  // namespace

Scales scales(const ContactPatch& patch, const Material& material, double friction) {
  const double n = patch.normal_force, area = patch.area;
  if (!(n > 0.0) || !(area > 0.0)) return kNominal;
  // Ellipse ratio a/b: the patch's own semi-axes when the model gives them, else the
  // equal-area ellipse of the patch's lateral extent (strip models report a = b = 0).
  double ratio = 1.0;
  if (patch.semi_axis_a > 0.0 && patch.semi_axis_b > 0.0) {
    ratio = patch.semi_axis_a / patch.semi_axis_b;
  } else if (patch.s_end > patch.s_start) {
    const double b = 0.5 * (patch.s_end - patch.s_start);
    ratio = area / (std::numbers::pi * b * b);
  }
  // Kalker's table ends at a/b = 0.1 and 10 (asymptotes beyond): a scale needs only be smooth.
  ratio = std::clamp(ratio, 0.05, 20.0);
  const KalkerCoefficients k = kalker_coefficients(ratio, material.poisson_ratio);
  const double g = material.shear_modulus();
  const double c2 = area / std::numbers::pi, c = std::sqrt(c2);
  const double mun = friction * n;
  return Scales{3.0 * mun / (g * c2 * k.c11), 3.0 * mun / (g * c2 * k.c22), mun / (g * c2 * c * k.c23)};
}

double physical(double v, double lo, double hi, double s) {
  // The range's ends exactly (the round trip through m loses digits when |q / s| is large).
  if (v <= -1.0) return lo;
  if (v >= 1.0) return hi;
  const double mlo = m(lo / s), mhi = m(hi / s);
  // The middle of the range plus v times its half-width: odd in v when the range is symmetric
  // (mlo = -mhi exactly), so mirrored nodes get mirrored creepages to the last bit.
  return s * m_inverse(0.5 * (mlo + mhi) + 0.5 * v * (mhi - mlo));
}

double coordinate(double q, double lo, double hi, double s) {
  const double mlo = m(lo / s), mhi = m(hi / s);
  return -1.0 + 2.0 * (m(q / s) - mlo) / (mhi - mlo);
}

std::array<double, 2> law(double xi_n, double eta_n, double psi_n, double spin) {
  const double x = xi_n, y = eta_n + psi_n / 3.0, z = spin * psi_n;
  const double r = std::sqrt(x * x + y * y + z * z);  // the lookup's formula (lookup/src/creep_map.hpp)
  if (!(r > 0.0)) return {0.0, 0.0};
  const double w = 1.0 - std::min(r, 1.0);
  const double g = 1.0 - w * w * w;
  return {-g * x / r, -g * y / r};
}

double vertical_share(double normal_force, double fy, double angle) {
  return normal_force * std::cos(angle) + fy * std::sin(angle);
}

std::vector<double> nodes(std::size_t count) {
  std::vector<double> v(count);
  // (2 i - (n - 1)) / (n - 1): an integer over an integer, so node n - 1 - i is node i negated to
  // the last bit (the mirrored sweep needs the eta and phi axes exactly symmetric).
  for (std::size_t i = 0; i < count; ++i)
    v[i] = count > 1 ? (2.0 * static_cast<double>(i) - static_cast<double>(count - 1)) / static_cast<double>(count - 1)
                     : 0.0;
  return v;
}

}  // namespace railtab::creep_map
