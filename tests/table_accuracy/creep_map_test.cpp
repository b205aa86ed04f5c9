// SPDX-License-Identifier: Apache-2.0
// The normalised creep coordinates of format 2.1 exist twice, in the generator
// (generator/kernel/creep_map.hpp) and in the lookup (lookup/src/creep_map.hpp, which links
// nothing of the generator): both must give the same numbers, and the map must be what
// docs/table-format.md says.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "accuracy_util.hpp"
#include "creep_map.hpp"  // lookup/src
#include "kernel/creep_map.hpp"
#include "tangential/kalker_coefficients.hpp"

namespace railtab {
namespace {

TEST(CreepMap, GeneratorAndLookupAgree) {
  const double ranges[][2] = {{-0.004, 0.004}, {-0.3, 0.3}, {0.0, 0.01}, {-0.002, 0.006}};
  for (const auto& r : ranges) {
    for (double s : {1e-5, 1e-3, 7e-3, 0.2, 3.0}) {
      for (int i = 0; i <= 40; ++i) {
        const double v = -1.0 + 2.0 * i / 40.0;
        const double q = creep_map::physical(v, r[0], r[1], s);
        EXPECT_GE(q, r[0] - 1e-15);
        EXPECT_LE(q, r[1] + 1e-15);
        // Round trip, and the lookup's coordinate of the generator's creepage.
        EXPECT_NEAR(creep_map::coordinate(q, r[0], r[1], s), v, 1e-9);
        EXPECT_NEAR(lookup::detail::creep_coordinate(q, r[0], r[1], s), creep_map::coordinate(q, r[0], r[1], s), 1e-12);
      }
      EXPECT_DOUBLE_EQ(creep_map::physical(-1.0, r[0], r[1], s), r[0]);
      EXPECT_DOUBLE_EQ(creep_map::physical(1.0, r[0], r[1], s), r[1]);
    }
  }
  for (double x : {-3.0, -0.7, 0.0, 1e-4, 0.3, 0.99, 1.0, 2.5})
    for (double y : {-1.2, 0.0, 0.4})
      for (double p : {-0.5, 0.0, 2.0})
        for (double spin : {0.0, 1.0}) {
          const std::array<double, 2> g = creep_map::law(x, y, p, spin);
          double l[2];
          lookup::detail::creep_law(x, y, p, spin, l);
          EXPECT_EQ(g[0], l[0]);
          EXPECT_EQ(g[1], l[1]);
          EXPECT_LE(std::hypot(g[0], g[1]), 1.0 + 1e-15);  // |F| <= mu N
        }
}

// Nodes uniform in v are dense near zero creepage and sparse in saturation: on a range reaching
// 10 times the saturation creepage, half the nodes lie below about the saturation creepage.
TEST(CreepMap, NodesFollowTheSaturation) {
  const std::vector<double> v = creep_map::nodes(9);
  ASSERT_EQ(v.front(), -1.0);
  ASSERT_EQ(v[4], 0.0);
  ASSERT_EQ(v.back(), 1.0);
  const double s = 1e-3, hi = 10 * s;
  EXPECT_LT(creep_map::physical(v[6], -hi, hi, s), 1.3 * s);
  EXPECT_GT(creep_map::physical(v[7], -hi, hi, s), 2.0 * s);
}

// The law is Kalker's linear theory at small creepage: F / (mu N) = -(3 xi', 3 eta' + psi').
// With a spin weight too: spin then uses up adhesion only beyond the linear range.
TEST(CreepMap, LawIsLinearTheoryAtSmallCreepage) {
  const double e = 1e-6;
  for (double spin : {0.0, 1.0}) {
    EXPECT_NEAR(creep_map::law(e, 0, 0, spin)[0], -3 * e, 1e-11);
    EXPECT_NEAR(creep_map::law(0, e, 0, spin)[1], -3 * e, 1e-11);
    EXPECT_NEAR(creep_map::law(0, 0, e, spin)[1], -e, 1e-11);
    EXPECT_NEAR(creep_map::law(e, 0, e, spin)[0], -3 * e, 1e-11);
    EXPECT_DOUBLE_EQ(creep_map::law(5.0, 0, 0, spin)[0], -1.0);  // full slip
  }
}

// The spin weight lowers the longitudinal law under spin (the exact model's fx falls with |phi|
// at constant xi), evenly in the sign of spin, and leaves it unchanged without spin.
TEST(CreepMap, SpinWeightUsesUpAdhesion) {
  const double x = 0.4, p = 0.6;
  EXPECT_EQ(creep_map::law(x, 0, 0, 1.0)[0], creep_map::law(x, 0, 0, 0.0)[0]);
  EXPECT_GT(creep_map::law(x, -p / 3, p, 1.0)[0], creep_map::law(x, -p / 3, p, 0.0)[0] + 0.05);
  EXPECT_EQ(creep_map::law(x, p / 3, -p, 1.0)[0], creep_map::law(x, -p / 3, p, 1.0)[0]);
}

// The derivatives of the forces in N (denormalise_creep_gradient, the lookup's query_derivatives)
// against central differences of denormalise_creep along each normalised creepage, with and
// without the spin weight, below and beyond saturation (r = 1), with the vertical share.
TEST(CreepMap, LawGradientMatchesDifferences) {
  using namespace lookup::detail;
  CreepMap map;
  map.friction = 0.3;
  map.vertical_share = true;
  const double angle = 0.05, stored[3] = {0.02, -0.03, 1e-4};  // fx, fy residuals, mz / (mu N)
  auto forces = [&](const double xn[3], double out[lookup::kNumOutputs]) {
    for (int o = 0; o < lookup::kNumOutputs; ++o) out[o] = 0.0;
    out[lookup::kContactAngle] = angle;
    out[lookup::kNormalForce] = 7e4;  // the vertical share
    out[lookup::kFx] = stored[0], out[lookup::kFy] = stored[1], out[lookup::kMz] = stored[2];
    denormalise_creep(map, xn, std::cos(angle), std::sin(angle), out);
  };
  for (double spin : {0.0, 1.0})
    for (const auto& x : {std::array<double, 3>{0.3, -0.2, 0.5}, std::array<double, 3>{1.2, 0.4, -0.9},
                          std::array<double, 3>{-0.1, 0.05, -0.6}}) {
      map.law_spin = spin;
      double dxn[3][kNumVars] = {};
      for (int k = 0; k < 3; ++k) dxn[k][kVarXi + k] = 1.0;  // d xn / d variable: identity on the creepages
      // The stored values (before denormalise_creep), constant: only the law moves.
      double st[lookup::kNumOutputs] = {};
      st[lookup::kContactAngle] = angle, st[lookup::kNormalForce] = 7e4;
      st[lookup::kFx] = stored[0], st[lookup::kFy] = stored[1], st[lookup::kMz] = stored[2];
      double d2[lookup::kNumOutputs][kNumVars] = {};
      denormalise_creep_gradient(map, x.data(), dxn, st, std::cos(angle), std::sin(angle), d2);
      for (int k = 0; k < 3; ++k) {
        const double h = 1e-6;
        std::array<double, 3> p = x, m = x;
        p[static_cast<std::size_t>(k)] += h, m[static_cast<std::size_t>(k)] -= h;
        double fp[lookup::kNumOutputs], fm[lookup::kNumOutputs];
        forces(p.data(), fp);
        forces(m.data(), fm);
        for (int o : {lookup::kNormalForce, lookup::kFx, lookup::kFy})
          EXPECT_NEAR(d2[o][kVarXi + k], (fp[o] - fm[o]) / (2 * h), 1e-5 * 7e4)
              << "spin " << spin << " output " << o << " creepage " << k << " at " << x[0] << ", " << x[1] << ", " << x[2];
      }
    }
}

// The vertical load share the generator stores (creep part normal_force, "vertical_share") gives
// back N in the lookup, for tread and flange angles of both wheels and either sign of fy.
TEST(CreepMap, VerticalShareGivesBackTheNormalForce) {
  const double mu = 0.3;
  for (double angle : {0.0, 0.03, -0.03, 1.16, -1.16})
    for (double ry : {-0.9, -0.2, 0.0, 0.5, 0.95}) {
      const double n = 150e3, fy = ry * mu * n;
      const double share = creep_map::vertical_share(n, fy, angle);
      EXPECT_NEAR(lookup::detail::normal_from_share(share, angle, mu * ry), n, 1e-9 * n) << angle << " " << ry;
    }
  // Flange, 66 deg: the share changes far less than N when fy carries part of the load.
  EXPECT_NEAR(creep_map::vertical_share(100281.0, 0.7663 * 0.3 * 100281.0, 1.1585),
              creep_map::vertical_share(200158.0, -0.3556 * 0.3 * 200158.0, 1.1585), 0.015 * 61300.0);
}

// The reader guard of creep_map keys a reader must apply (docs/table-format.md, "Normalised creep
// part"): a table whose law has spin (law_spin) names the key in coordinates, so readers from
// before the key, which accept only "normalised", refuse it; one that requires a key this reader
// does not know is refused with a message naming the key; a table without such keys keeps
// coordinates "normalised" (its bytes).
TEST(CreepMap, TableRequiringAnUnknownKeyIsRefused) {
  auto table_with_spin = [](double spin) {
    const Scene scene = parse_scene(R"(
[scene]
name = "required-keys"
[profiles]
wheel = "s1002"
rail = "uic60"
[grid]
y = [0.0, 0.002]
roll = 0.0
load = 78.5e3
xi = [-0.004, 0.004]
eta = [-0.004, 0.004]
phi = [-0.3, 0.3]
creep_coordinates = "normalised"
)" + (spin != 0.0 ? "creep_law_spin = " + std::to_string(spin) + "\n" : std::string()),
                                              "required-keys.toml");
    SweepResult r = run_sweep(scene, make_contact_kernel(scene), SweepOptions{});
    EXPECT_EQ(r.summary.failures, 0u) << r.summary.first_failure;
    return std::move(r.table);
  };
  auto load_error = [](const Table& table) -> std::string {
    // The writer loads what it wrote through the lookup before it keeps it, so the lookup's
    // refusal comes from either.
    const std::filesystem::path path = accuracy::temp_table_path("required_keys");
    std::string error;
    try {
      accuracy::write_for_lookup(table, path);
      const lookup::Table t = lookup::Table::load(path.string());
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::filesystem::remove(path);
    return error;
  };
  const std::string plain = *table_with_spin(0.0).attribute("creep_map");
  EXPECT_NE(plain.find(R"("coordinates":"normalised",)"), std::string::npos) << plain;
  Table spin = table_with_spin(1.0);
  const std::string text = *spin.attribute("creep_map");
  const std::string required = R"("coordinates":"normalised+law_spin")";
  ASSERT_NE(text.find(required), std::string::npos) << text;
  EXPECT_EQ(load_error(spin), "");
  // A key this reader does not know.
  std::string unknown = text;
  unknown.replace(unknown.find(required), required.size(), R"("coordinates":"normalised+law_spin+slot_nodes")");
  spin.set_attribute("creep_map", unknown);
  const std::string error = load_error(spin);
  EXPECT_NE(error.find("requires key 'slot_nodes', which this reader does not know"), std::string::npos) << error;
  // A required key the map lacks, and a malformed list.
  std::string missing = text;
  missing.erase(missing.find(R"(,"law_spin")"), std::string(R"(,"law_spin":1.0)").size());
  spin.set_attribute("creep_map", missing);
  EXPECT_NE(load_error(spin).find("coordinates require key 'law_spin', which is missing"), std::string::npos)
      << missing;
  std::string malformed = text;
  malformed.replace(malformed.find(required), required.size(), R"("coordinates":"normalised_law_spin")");
  spin.set_attribute("creep_map", malformed);
  EXPECT_NE(load_error(spin).find("coordinates must be \"normalised\""), std::string::npos);
}

// The scales of an elliptic patch are Kalker's: s_xi = 3 mu N / (G ab C11) etc.
TEST(CreepMap, ScalesOfAnEllipseAreKalkers) {
  ContactPatch p;
  p.normal_force = 78.5e3;
  p.semi_axis_a = 6e-3;
  p.semi_axis_b = 4e-3;
  p.area = std::numbers::pi * p.semi_axis_a * p.semi_axis_b;
  Material m;
  m.youngs_modulus = 210e9;
  m.poisson_ratio = 0.3;
  const creep_map::Scales s = creep_map::scales(p, m, 0.3);
  const KalkerCoefficients k = kalker_coefficients(1.5, 0.3);
  const double g = m.shear_modulus(), ab = 24e-6;
  EXPECT_NEAR(s.xi, 3 * 0.3 * 78.5e3 / (g * ab * k.c11), 1e-12 * s.xi);
  EXPECT_NEAR(s.eta, 3 * 0.3 * 78.5e3 / (g * ab * k.c22), 1e-12 * s.eta);
  EXPECT_NEAR(s.phi, 0.3 * 78.5e3 / (g * ab * std::sqrt(ab) * k.c23), 1e-12 * s.phi);
  ContactPatch empty;
  EXPECT_EQ(creep_map::scales(empty, m, 0.3).xi, creep_map::kNominal.xi);
}

}  // namespace
}  // namespace railtab
