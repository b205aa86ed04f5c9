// SPDX-License-Identifier: Apache-2.0
// Smooths a wear depth distribution and removes it from the wheel profile (the next profile).
#include "simulate/worn_profile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/check.hpp"
#include "profile/formats/simpack_writer.hpp"
#include "table/output_file.hpp"

namespace railtab {
namespace {

// Bin spacing of `u` (bin centres); they must be uniformly spaced so that the worn area is
// step * sum(depth), the same definition as WearAccumulator::worn_area.
double uniform_step(const std::vector<double>& u, const std::string& what) {
  RAILTAB_CHECK(u.size() >= 2, "{}: at least 2 wear bins needed, got {}", what, u.size());
  for (double v : u) RAILTAB_CHECK(std::isfinite(v), "{}: wear bin position is not finite ({})", what, v);
  const double step = (u.back() - u.front()) / static_cast<double>(u.size() - 1);
  RAILTAB_CHECK(step > 0.0, "{}: wear bin positions must increase", what);
  for (std::size_t i = 1; i < u.size(); ++i) {
    RAILTAB_CHECK(std::abs(u[i] - u[i - 1] - step) <= 1e-6 * step,
                  "{}: wear bins must be uniformly spaced ({} m between bins {} and {}, mean {} m)", what,
                  u[i] - u[i - 1], i - 1, i, step);
  }
  return step;
}

// Depth at `x` from the bin values: linear between bin centres, the end value inside the end
// bins' outer halves, 0 beyond the grid.
double depth_at(const std::vector<double>& u, const std::vector<double>& depth, double step, double x) {
  if (x < u.front() - 0.5 * step || x > u.back() + 0.5 * step) return 0.0;
  if (x <= u.front()) return depth.front();
  if (x >= u.back()) return depth.back();
  const auto i = std::min(u.size() - 2, static_cast<std::size_t>((x - u.front()) / step));
  const double t = std::clamp((x - u[i]) / step, 0.0, 1.0);
  return depth[i] + t * (depth[i + 1] - depth[i]);
}

}  // namespace

// Triangular kernel of base `smoothing_length` (weight 1 - |du| / (L/2)) rather than a plain
// moving average: same support, but a narrow wear peak becomes a continuous tent instead of a
// box with steps at its ends, and the spline through the written profile does not ring at such
// steps. Each bin SCATTERS its area over its neighbours, normalised by the kernel weights that
// fall inside the grid, so the area is kept exactly also near the grid ends; in the interior this
// is the ordinary (symmetric) convolution.
std::vector<double> smooth_depth(const std::vector<double>& u, const std::vector<double>& depth,
                                 double smoothing_length) {
  RAILTAB_CHECK(u.size() == depth.size(), "smooth_depth: {} bin positions but {} depths", u.size(), depth.size());
  RAILTAB_CHECK(std::isfinite(smoothing_length) && smoothing_length >= 0.0,
                "smooth_depth: smoothing length must be finite and >= 0 m, got {}", smoothing_length);
  for (double d : depth) RAILTAB_CHECK(std::isfinite(d), "smooth_depth: wear depth is not finite ({})", d);
  const double step = uniform_step(u, "smooth_depth");
  const double half = 0.5 * smoothing_length;
  const auto reach = static_cast<std::ptrdiff_t>(std::floor(half / step));
  if (reach < 1) return depth;  // the kernel covers no neighbour

  const auto n = static_cast<std::ptrdiff_t>(u.size());
  const auto kernel = [&](std::ptrdiff_t i, std::ptrdiff_t j) {
    return 1.0 - static_cast<double>(std::abs(i - j)) * step / half;
  };
  std::vector<double> out(depth.size(), 0.0);
  for (std::ptrdiff_t j = 0; j < n; ++j) {
    const double d = depth[static_cast<std::size_t>(j)];
    if (d == 0.0) continue;
    const std::ptrdiff_t lo = std::max<std::ptrdiff_t>(0, j - reach);
    const std::ptrdiff_t hi = std::min(n - 1, j + reach);
    double weight = 0.0;
    for (std::ptrdiff_t i = lo; i <= hi; ++i) weight += kernel(i, j);
    for (std::ptrdiff_t i = lo; i <= hi; ++i) out[static_cast<std::size_t>(i)] += d * kernel(i, j) / weight;
  }
  return out;
}

void write_worn_profile(const Profile& wheel, const std::vector<double>& u, const std::vector<double>& depth,
                        double smoothing_length, const std::filesystem::path& file, double step) {
  const std::string name = file.string();
  RAILTAB_CHECK(u.size() == depth.size(), "worn profile {}: {} bin positions but {} depths", name, u.size(),
                depth.size());
  for (double d : depth) RAILTAB_CHECK(std::isfinite(d), "worn profile {}: wear depth is not finite ({})", name, d);
  RAILTAB_CHECK(std::isfinite(smoothing_length) && smoothing_length >= 0.0,
                "worn profile {}: smoothing length must be finite and >= 0 m, got {}", name, smoothing_length);
  RAILTAB_CHECK(std::isfinite(step) && step > 0.0, "worn profile {}: step must be > 0 m, got {}", name, step);
  const double bin = uniform_step(u, "worn profile " + name);
  const std::vector<double> smoothed = smooth_depth(u, depth, smoothing_length);

  // Nodes at `step` from u_min, and u_max itself (replacing a last node closer than step/1000,
  // which would make a near-duplicate point).
  std::vector<double> nodes;
  const double u0 = wheel.u_min(), u1 = wheel.u_max();
  for (std::size_t k = 0;; ++k) {
    const double x = u0 + static_cast<double>(k) * step;
    if (x >= u1 - 1e-3 * step) break;
    nodes.push_back(x);
  }
  nodes.push_back(u1);
  RAILTAB_CHECK(nodes.size() >= 4, "worn profile {}: step {} m leaves fewer than 4 points on [{}, {}] m", name,
                step, u0, u1);

  std::vector<double> worn;  // z of the worn wheel at the nodes [m]
  {
    std::ostringstream out;
    out << fmt::format("# worn wheel profile from '{}', radial wear smoothed over {:g} mm (railtab)\n", wheel.name(),
                       smoothing_length * 1e3);
    out << "# lateral [mm] (+ field side), vertical [mm] (+ down, r - r_nominal); docs/profiles.md\n";
    for (double x : nodes) {
      // The wheel's z is -(r - r0); wear lowers r by the radial depth, so z rises by it.
      worn.push_back(wheel.eval(x).z + depth_at(u, smoothed, bin, x));
      out << fmt::format("{:.9f} {:.9f}\n", x * 1e3, -worn.back() * 1e3);
    }
    write_text_file(file, out.str());  // through a locked, synced temporary (table/output_file.hpp)
  }
  // The same points as a SIMPACK wheel profile, for tools that do not read the two-column form.
  std::filesystem::path simpack = file;
  simpack.replace_extension(".prw");
  write_text_file(simpack, simpack_profile_text(ProfileKind::wheel, nodes, worn,
                                                fmt::format("worn {} (railtab simulate), wear smoothed over {:g} mm",
                                                            wheel.name(), smoothing_length * 1e3)));
}

}  // namespace railtab
