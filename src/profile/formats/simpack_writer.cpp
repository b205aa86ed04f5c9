// SPDX-License-Identifier: Apache-2.0
// The text of a SIMPACK profile file and the check of its file name (simpack_writer.hpp).
#include "profile/formats/simpack_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/check.hpp"

namespace railtab {

std::string simpack_profile_text(ProfileKind kind, std::span<const double> u, std::span<const double> z,
                                 std::string_view comment) {
  RAILTAB_CHECK(u.size() == z.size(), "SIMPACK profile: {} lateral but {} vertical coordinates", u.size(),
                z.size());
  RAILTAB_CHECK(u.size() >= 4, "SIMPACK profile: {} points, a spline needs at least 4", u.size());
  for (std::size_t i = 0; i < u.size(); ++i) {
    RAILTAB_CHECK(std::isfinite(u[i]) && std::isfinite(z[i]), "SIMPACK profile: point {} is not finite ({}, {})",
                  i, u[i], z[i]);
    RAILTAB_CHECK(i == 0 || u[i] > u[i - 1], "SIMPACK profile: lateral coordinate not increasing at point {}", i);
  }
  std::string clean(comment);
  std::replace_if(clean.begin(), clean.end(), [](char c) { return c == '\'' || c == '"' || c == '\n'; }, ' ');
  const bool wheel = kind == ProfileKind::wheel;
  constexpr double kMmPerM = 1e3;
  std::string out = fmt::format(
      "! SIMPACK rail-wheel profile written by railtab\n"
      "! y towards the field side, z downwards, in mm (u = y, z_up = -z in railtab's profile frame)\n"
      "  header.begin\n"
      "    version        =  1   ! Version flag\n"
      "    type           =  {}   ! 0=rail profile, 1=wheel profile\n"
      "  header.end\n"
      "  spline.begin\n"
      "    approx.smooth  = +0.000000000000000e+00   ! Approximation smoothing value\n"
      "    comment        = '{}'   ! Comment\n"
      "    point.dist.min = +0.000000000000000e+00   ! 1: Minimum point distance\n"
      "    shift.y        = +0.000000000000000e+00   ! 2: y shift of data\n"
      "    shift.z        = +0.000000000000000e+00   ! 2: z shift of data\n"
      "    rotate         = +0.000000000000000e+00   ! 3: Rotation angle about x\n"
      "    bound.y.min    = +1.000000000000000e+00   ! 4: y boundary min (min > max: no bound)\n"
      "    bound.y.max    = +0.000000000000000e+00   ! 4: y boundary max\n"
      "    bound.z.min    = +1.000000000000000e+00   ! 4: z boundary min (min > max: no bound)\n"
      "    bound.z.max    = +0.000000000000000e+00   ! 4: z boundary max\n"
      "    mirror.y       =  0   ! 5: y mirror mode (0=no mirroring; 1=mirrored)\n"
      "    mirror.z       =  0   ! 5: z mirror mode (0=no mirroring; 1=mirrored)\n"
      "    inversion      =  0   ! 6: Inversion of data order (0=no inversion; 1=inversion)\n"
      "    units.len.f    = +1.000000000000000e+03   ! 7: Unit factor for lengths (l[User] / l[m])\n"
      "    units.ang.f    = +1.000000000000000e+00   ! 7: Unit factor for angles (a[User] / a[rad])\n"
      "    point.begin\n",
      wheel ? 1 : 0, clean);
  for (std::size_t i = 0; i < u.size(); ++i) {
    // 17 significant digits: the double read back is the double written (before the mm scaling).
    out += fmt::format("      {:+.16e} {:+.16e}\n", u[i] * kMmPerM, -z[i] * kMmPerM);
  }
  out += "    point.end\n  spline.end\n";
  return out;
}

void check_simpack_file_name(const std::filesystem::path& file, ProfileKind kind) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const char* expected = kind == ProfileKind::wheel ? ".prw" : ".prr";
  RAILTAB_CHECK(ext == expected, "{}: a SIMPACK {} profile needs the extension {}", file.string(),
                kind == ProfileKind::wheel ? "wheel" : "rail", expected);
}

}  // namespace railtab
