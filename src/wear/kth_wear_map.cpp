// SPDX-License-Identifier: Apache-2.0
// The KTH wear map (kth_wear_map.hpp): wear coefficient by pressure and sliding speed.
#include "wear/kth_wear_map.hpp"

#include <cmath>
#include <string>

#include "core/check.hpp"

namespace railtab {

const char* to_string(Lubrication lubrication) {
  switch (lubrication) {
    case Lubrication::dry: return "dry";
    case Lubrication::natural: return "natural";
    case Lubrication::lubricated: return "lubricated";
  }
  return "unknown";
}

Lubrication parse_lubrication(std::string_view name) {
  if (name == "dry") return Lubrication::dry;
  if (name == "natural") return Lubrication::natural;
  if (name == "lubricated") return Lubrication::lubricated;
  throw Error("unknown lubrication '" + std::string(name) +
              "' (expected dry, natural or lubricated)");
}

const char* to_string(KthRegion region) {
  switch (region) {
    case KthRegion::mild: return "mild";
    case KthRegion::severe: return "severe";
    case KthRegion::oxidative: return "oxidative";
    case KthRegion::seizure: return "seizure";
  }
  return "unknown";
}

void validate(const KthWearMap& m) {
  const double v[] = {m.k1, m.k2, m.k3, m.k4, m.hardness, m.seizure_ratio, m.velocity_severe,
                      m.velocity_oxidative, m.factor_natural, m.factor_lubricated};
  for (double x : v)
    RAILTAB_CHECK(std::isfinite(x) && x >= 0.0, "KTH wear map: entry {} must be finite and >= 0",
                  x);
  RAILTAB_CHECK(m.hardness > 0.0 && m.seizure_ratio > 0.0, "KTH wear map: H {} Pa, ratio {}",
                m.hardness, m.seizure_ratio);
  RAILTAB_CHECK(m.velocity_severe <= m.velocity_oxidative,
                "KTH wear map: severe threshold {} m/s above oxidative threshold {} m/s",
                m.velocity_severe, m.velocity_oxidative);
  RAILTAB_CHECK(m.factor_natural > 0.0 && m.factor_lubricated > 0.0,
                "KTH wear map: lubrication factors {} and {} must be > 0", m.factor_natural,
                m.factor_lubricated);
}

KthRegion kth_region(const KthWearMap& m, double pressure, double slip_velocity) {
  const double p = std::abs(pressure), v = std::abs(slip_velocity);
  if (p >= m.seizure_ratio * m.hardness) return KthRegion::seizure;
  if (v < m.velocity_severe) return KthRegion::mild;
  if (v <= m.velocity_oxidative) return KthRegion::severe;
  return KthRegion::oxidative;
}

double kth_wear_coefficient(const KthWearMap& m, double pressure, double slip_velocity,
                            Lubrication lubrication) {
  double k = 0.0;
  switch (kth_region(m, pressure, slip_velocity)) {
    case KthRegion::mild: k = m.k1; break;
    case KthRegion::severe: k = m.k2; break;
    case KthRegion::oxidative: k = m.k3; break;
    case KthRegion::seizure: k = m.k4; break;
  }
  switch (lubrication) {
    case Lubrication::dry: return k;
    case Lubrication::natural: return k / m.factor_natural;
    case Lubrication::lubricated: return k / m.factor_lubricated;
  }
  return k;
}

}  // namespace railtab
