// SPDX-License-Identifier: Apache-2.0
// Elastic material of wheel and rail (identical materials assumed, as in Hertz and FASTSIM).
#pragma once

namespace railtab {

struct Material {
  double youngs_modulus = 210e9;  // E [Pa]
  double poisson_ratio = 0.3;     // nu [-]

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }  // G [Pa]
  // Combined contact modulus E* = E / (2 (1 - nu^2)) = G / (1 - nu) for two equal bodies [Pa].
  double contact_modulus() const {
    return youngs_modulus / (2.0 * (1.0 - poisson_ratio * poisson_ratio));
  }
};

}  // namespace railtab
