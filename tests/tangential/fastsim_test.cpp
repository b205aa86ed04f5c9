// SPDX-License-Identifier: Apache-2.0
// Tests of FASTSIM on elliptic patches and strips (src/tangential/fastsim.hpp).
#include "tangential/fastsim.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/check.hpp"
#include "normal/hertz.hpp"
#include "tangential/kalker_coefficients.hpp"
#include "tangential/patch_test_helper.hpp"

namespace railtab::fastsim_test {  // own namespace: unity builds compile several test files as one
namespace {

using test::elliptic_patch;

Material contact_material() {  // the reference's steel: E 210 GPa, nu 0.28 (G 82.03 GPa)
  Material m;
  m.youngs_modulus = 210e9;
  m.poisson_ratio = 0.28;
  return m;
}

struct LinearCase {
  double B;  // lateral relative curvature [1/m], A = 1/(2*0.46)
};

// Kalker's linear theory at vanishing creepage, on Hertz patches of three shapes, with both the
// strip-wise solver (Hertz semi-elliptic bound) and the classical elliptic one.
TEST(Fastsim, LinearTheoryAtSmallCreepage) {
  const Material mat = contact_material();
  const double G = mat.shear_modulus();
  const double A = 1.0 / (2.0 * 0.46);
  for (double ratio_AB : {1.0, 0.2, 0.05, 5.0}) {
    const HertzContact h = hertz_for_force(A, A / ratio_AB, 78e3, mat);
    const double c2 = h.a * h.b, c = std::sqrt(c2);
    const KalkerCoefficients kc = kalker_coefficients(h.a / h.b, mat.poisson_ratio);
    const ContactPatch patch = elliptic_patch(h.a, h.b, 78e3, 60);
    FastsimOptions opt;
    opt.elements_per_strip = 40;
    FastsimWorkspace ws;
    const double xi = 1e-7, eta = 1e-7, phi = 1e-5;
    const double fx_lin = -G * c2 * kc.c11 * xi;
    const double fy_lin = -G * c2 * kc.c22 * eta;
    const double fs_lin = -G * c2 * c * kc.c23 * phi;
    const FastsimResult rx = fastsim_patch(patch, {}, {xi, 0, 0}, 0.3, 20.0, mat, opt, ws);
    const FastsimResult ry = fastsim_patch(patch, {}, {0, eta, 0}, 0.3, 20.0, mat, opt, ws);
    const FastsimResult rs = fastsim_patch(patch, {}, {0, 0, phi}, 0.3, 20.0, mat, opt, ws);
    EllipticPatch ep{h.a, h.b, 78e3, 60};
    const FastsimResult ex = fastsim_ellipse(ep, {xi, 0, 0}, 0.3, 20.0, mat, 40, ws);
    const FastsimResult ey = fastsim_ellipse(ep, {0, eta, 0}, 0.3, 20.0, mat, 40, ws);
    const FastsimResult es = fastsim_ellipse(ep, {0, 0, phi}, 0.3, 20.0, mat, 40, ws);
    std::printf("[measured] linear A/B=%.2f a/b=%.3f: dev fx %+.3f%% fy %+.3f%% spin-fy %+.3f%%"
                " | ellipse %+.3f%% %+.3f%% %+.3f%%\n",
                ratio_AB, h.a / h.b, 100 * (rx.fx / fx_lin - 1), 100 * (ry.fy / fy_lin - 1),
                100 * (rs.fy / fs_lin - 1), 100 * (ex.fx / fx_lin - 1), 100 * (ey.fy / fy_lin - 1),
                100 * (es.fy / fs_lin - 1));
    EXPECT_NEAR(rx.fx / fx_lin, 1.0, 0.01);
    EXPECT_NEAR(ry.fy / fy_lin, 1.0, 0.01);
    EXPECT_NEAR(rs.fy / fs_lin, 1.0, 0.01);
    EXPECT_NEAR(ex.fx / fx_lin, 1.0, 0.01);
    EXPECT_NEAR(ey.fy / fy_lin, 1.0, 0.01);
    EXPECT_NEAR(es.fy / fs_lin, 1.0, 0.01);
    EXPECT_NEAR(rx.fy, 0.0, 1e-9 * std::abs(rx.fx));  // no cross-coupling for pure xi
    EXPECT_EQ(rx.slip_fraction < 0.1, true);
    // Signs on the wheel: braking creepage gives a backward force (docs/conventions.md).
    EXPECT_LT(rx.fx, 0.0);
    EXPECT_LT(ry.fy, 0.0);
    EXPECT_LT(rs.fy, 0.0);
  }
}

// |F| grows monotonically to mu*N and never exceeds it, for several creepage directions.
TEST(Fastsim, SaturatesMonotonicallyAtMuN) {
  const Material mat = contact_material();
  const HertzContact h = hertz_for_force(1.087, 1.087 / 0.3, 78e3, mat);
  const double mu = 0.3, N = 78e3;
  const double c = std::sqrt(h.a * h.b);
  for (StripPressure shape : {StripPressure::semi_elliptic, StripPressure::parabolic}) {
    const ContactPatch patch = elliptic_patch(h.a, h.b, N, 40, shape);
    const double dirs[][3] = {{1, 0, 0}, {0, 1, 0}, {0.6, 0.8, 0}, {0.5, 0.5, 0.5 / c},
                              {0, 0, 1.0 / c}};
    FastsimWorkspace ws;
    for (const auto& d : dirs) {
      double prev = 0.0;
      FastsimResult last;
      for (double t = 1e-6; t < 2.0; t *= 1.25) {
        last = fastsim_patch(patch, {}, {t * d[0], t * d[1], t * d[2]}, mu, 20.0, mat, {}, ws);
        const double f = std::hypot(last.fx, last.fy);
        ASSERT_LE(f, mu * N * (1.0 + 1e-12));
        // Monotone for translational creepage. With spin, FASTSIM's three flexibilities turn
        // the traction direction with the creepage level and |F| may peak before full slip.
        if (d[2] == 0.0) {
          EXPECT_GE(f, prev * (1.0 - 1e-9)) << "t " << t << " dir " << d[0] << "," << d[1];
        }
        prev = f;
      }
      if (d[2] == 0.0) {
        EXPECT_NEAR(prev, mu * N, 1e-6 * mu * N);
        EXPECT_TRUE(last.status & status::kFullSlip);
      } else {  // spin keeps the force below mu*N, but everything slides
        EXPECT_GT(prev, 0.0);
        EXPECT_GT(last.slip_fraction, 0.99);
      }
    }
  }
}

TEST(Fastsim, DiscretisationConverges) {
  const Material mat = contact_material();
  const HertzContact h = hertz_for_force(1.087, 1.087 / 0.3, 78e3, mat);
  const ContactPatch patch = elliptic_patch(h.a, h.b, 78e3, 50);
  const Creepage cr{1e-3, 5e-4, 0.05};
  FastsimWorkspace ws;
  FastsimOptions opt;
  opt.elements_per_strip = 640;
  const FastsimResult ref = fastsim_patch(patch, {}, cr, 0.3, 20.0, mat, opt, ws);
  double prev_err = 1e300;
  for (int n : {10, 20, 40, 80, 160}) {
    opt.elements_per_strip = n;
    const FastsimResult r = fastsim_patch(patch, {}, cr, 0.3, 20.0, mat, opt, ws);
    const double err = std::hypot(r.fx - ref.fx, r.fy - ref.fy) / std::hypot(ref.fx, ref.fy);
    std::printf("[measured] convergence n=%d: |dF|/|F| = %.4f%%, slip fraction %.3f\n", n,
                100 * err, r.slip_fraction);
    EXPECT_LT(err, prev_err * 1.05);
    if (n == FastsimOptions{}.elements_per_strip) {
      EXPECT_LT(err, 0.01);  // the default
    }
    prev_err = err;
  }
}

TEST(Fastsim, OddInCreepage) {
  const Material mat = contact_material();
  const ContactPatch patch = elliptic_patch(5e-3, 7e-3, 60e3, 30);
  FastsimWorkspace ws;
  for (const Creepage c : {Creepage{1e-3, 2e-3, 0.1}, Creepage{-4e-3, 1e-4, -0.3}}) {
    const FastsimResult p = fastsim_patch(patch, {}, c, 0.3, 20.0, mat, {}, ws);
    const FastsimResult m =
        fastsim_patch(patch, {}, {-c.xi, -c.eta, -c.phi}, 0.3, 20.0, mat, {}, ws);
    EXPECT_NEAR(p.fx, -m.fx, 1e-9 * std::abs(p.fx) + 1e-9);
    EXPECT_NEAR(p.fy, -m.fy, 1e-9 * std::abs(p.fy) + 1e-9);
    EXPECT_NEAR(p.mz, -m.mz, 1e-9 * std::abs(p.mz) + 1e-12);
  }
  // Mirror in the lateral direction: eta and phi change sign with y, xi does not.
}

// Per-element outputs: slip opposes traction; frictional work equals F.creepage for pure xi.
TEST(Fastsim, SlipOutputsAreConsistent) {
  const Material mat = contact_material();
  const ContactPatch patch = elliptic_patch(4e-3, 6e-3, 50e3, 30);
  FastsimWorkspace ws;
  const double V = 25.0;
  const FastsimResult r = fastsim_patch(patch, {}, {2e-3, 0, 0}, 0.3, V, mat, {}, ws);
  int slipping = 0;
  for (int e = 0; e < ws.elements(); ++e) {
    const auto u = static_cast<std::size_t>(e);
    if (ws.slip_velocity[u] > 0.0) {
      ++slipping;
      EXPECT_LE(ws.traction_x[u] * ws.slip_x[u] + ws.traction_y[u] * ws.slip_y[u], 0.0);
      EXPECT_NEAR(ws.slip_velocity[u], V * std::hypot(ws.slip_x[u], ws.slip_y[u]), 1e-12);
    }
  }
  EXPECT_GT(slipping, 0);
  // Steady rolling, traction zero at both strip ends: friction work per metre = -F . w.
  std::printf("[measured] friction work %.6g J/m vs -F.w %.6g J/m\n", r.frictional_work,
              -r.fx * 2e-3);
  EXPECT_NEAR(r.frictional_work, -r.fx * 2e-3, 0.01 * std::abs(r.fx * 2e-3));
}

// Per-strip spin reduces exactly to the patch-constant one on a planar patch with the kinematic
// spin of a rolling wheel, and differs on a curved patch (Sichani et al. 2014).
TEST(Fastsim, PerStripSpinVariant) {
  const Material mat = contact_material();
  const double gamma = -0.035, r0 = 0.46;
  ContactPatch patch = elliptic_patch(5.5e-3, 7.5e-3, 78.5e3, 50, StripPressure::parabolic,
                                      gamma, r0);
  const double phi_kin = -std::sin(gamma) / r0;  // xi = 0
  FastsimWorkspace ws;
  FastsimOptions planar, curved;
  curved.spin = SpinVariation::per_strip;
  const Creepage c{0.0, 0.0, phi_kin};
  const FastsimResult a = fastsim_patch(patch, {}, c, 0.3, 20.0, mat, planar, ws);
  const FastsimResult b = fastsim_patch(patch, {}, c, 0.3, 20.0, mat, curved, ws);
  EXPECT_NEAR(a.fx, b.fx, 1e-6 * std::hypot(a.fx, a.fy));
  EXPECT_NEAR(a.fy, b.fy, 1e-6 * std::hypot(a.fx, a.fy));
  // Curve the patch like the crown of a right rail (radius 0.3 m; s towards the gauge side, where
  // the ISO contact angle of the right wheel grows negative): gamma_i = gamma - y/0.3, and the
  // wheel radius follows the rise of the surface, r_i = r0 - integral of sin(gamma) ds.
  const double k = -1.0 / 0.3;
  for (Strip& s : patch.strips) {
    s.contact_angle = gamma + k * s.s;
    s.rolling_radius = r0 - (std::cos(gamma) - std::cos(s.contact_angle)) / k;
  }
  const FastsimResult p = fastsim_patch(patch, {}, c, 0.3, 20.0, mat, planar, ws);
  const FastsimResult q = fastsim_patch(patch, {}, c, 0.3, 20.0, mat, curved, ws);
  std::printf("[measured] curved patch pure kinematic spin %.4f rad/m: patch-constant fx %.0f fy"
              " %.0f |F| %.0f N; per-strip fx %.0f fy %.0f |F| %.0f N\n",
              phi_kin, p.fx, p.fy, std::hypot(p.fx, p.fy), q.fx, q.fy, std::hypot(q.fx, q.fy));
  EXPECT_NE(std::hypot(p.fx, p.fy), std::hypot(q.fx, q.fy));
}

TEST(Fastsim, LateralOrientationOfTheRightWheel) {
  // The same patch solved as a right wheel (band s runs against the contact frame's s axis):
  // the spin lever arm flips, so fx from spin with an offset reference point changes sign.
  const Material mat = contact_material();
  const ContactPatch patch = elliptic_patch(5e-3, 7e-3, 60e3, 30);
  FastsimWorkspace ws;
  const FastsimResult l = fastsim_patch(patch, {2e-3, 1.0}, {0, 0, 0.5}, 0.3, 20.0, mat, {}, ws);
  const FastsimResult r = fastsim_patch(patch, {2e-3, -1.0}, {0, 0, 0.5}, 0.3, 20.0, mat, {}, ws);
  EXPECT_NEAR(l.fx, -r.fx, 1e-9 * std::abs(l.fx));
  EXPECT_NEAR(l.fy, r.fy, 1e-9 * std::abs(l.fy));
}

TEST(Fastsim, UnloadedAndInvalid) {
  const Material mat = contact_material();
  ContactPatch empty;
  FastsimWorkspace ws;
  const FastsimResult r = fastsim_patch(empty, {}, {1e-3, 0, 0}, 0.3, 20.0, mat, {}, ws);
  EXPECT_TRUE(r.status & status::kLiftOff);
  EXPECT_EQ(r.fx, 0.0);
  const ContactPatch patch = elliptic_patch(5e-3, 7e-3, 60e3, 10);
  EXPECT_THROW(fastsim_patch(patch, {}, {std::nan(""), 0, 0}, 0.3, 20.0, mat, {}, ws), Error);
  EXPECT_THROW(fastsim_patch(patch, {}, {0, 0, 0}, -0.1, 20.0, mat, {}, ws), Error);
  EXPECT_THROW(fastsim_patch(patch, {}, {0, 0, 0}, 0.3, 0.0, mat, {}, ws), Error);
}

}  // namespace
}  // namespace railtab::fastsim_test
