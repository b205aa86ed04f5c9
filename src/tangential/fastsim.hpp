// SPDX-License-Identifier: Apache-2.0
// FASTSIM (Kalker 1982): the simplified theory of rolling contact, on an elliptic patch and
// strip-wise on the non-elliptic patches of the normal layer (Linder, Kik-Piotrowski, STRIPES).
//
// Frames and signs (docs/conventions.md): creepages are the rigid slip of the WHEEL relative to the
// RAIL per unit rolling distance in the contact frame (x rolling, s lateral = n x x, n rail into
// wheel); tractions and forces act ON THE WHEEL. Rigid slip at (x, y): w_x = xi - phi*y,
// w_y = eta + phi*x, y the lateral coordinate along s measured from the patch reference point.
//
// Method, per lateral strip i (centre y_i, width dy_i, leading edge x_lead, trailing x_trail):
//  - flexibilities from the strip's local ellipse (a_e, b_e): L1 = 8a_e/(3 C11 G),
//    L2 = 8a_e/(3 C22 G), L3 = pi a_e sqrt(a_e/b_e)/(4 C23 G) (Kalker). Hertz: every strip carries
//    the patch ellipse; Linder: a_e = strip half-length, b_e = patch half-width; STRIPES: the
//    strip's own virtual ellipse. The normal layer fills Strip::ellipse_a/b accordingly.
//  - n equal elements of length dx, traction sampled at the element centres (midpoint rule: exact
//    for the linear adhesion traction; sampling at the element ends, as the original FASTSIM does,
//    loses half of the last element and biases the linear-theory force by 1/n); march from x_lead
//    (traction 0) over steps h (dx/2 for the first, then dx): trial traction
//    p* = p - h (xi_i/L1 + q_i/L3, eta_i/L2 + phi_i x_mid/L3); traction bound mu*p_n(x) with the
//    strip's pressure shape (semi-elliptic or parabolic), scaled so that the discrete normal force
//    equals the patch's normal force (so |F| -> mu*N exactly in full slip); if |p*| exceeds the
//    bound the element slips and p = bound * p*/|p*|.
//  - forces: traction samples times dx*dy.
//  - slip in a slipping element: s = L_s (p - p*)/h [-], opposite to the traction (Coulomb),
//    with L_s the creepage-weighted single flexibility of CONTACT,
//    L_s = (xi^2 + eta^2 + q^2 + (phi c')^2) / (xi^2/L1 + eta^2/L2 + (q^2 + (phi c')^2)/L3),
//    c' = 3 pi a_e / 32. Exact (s = w - L du/dx) for pure longitudinal or pure lateral creepage.
//    The slip displacement of a step, L_s (p - p*) [m], is the sliding distance of the element;
//    per rolling distance s = displacement/dx, slip velocity V|s| [m/s]. The step's slip is paired
//    with the mean traction and mean pressure over the step (wear_pressure), the discrete form of
//    int p.s dx = F.w - L[p^2/2]; the traction drops to zero at the trailing edge and the elastic
//    displacement released there is slip of the strip's last element. So the friction work equals
//    -F.w for pure creepage up to O(1/n^2), as in the continuum, and so does Archard wear.
//
// Spin and longitudinal creepage across strips (SpinVariation):
//  - patch_constant (default; Kalker, CONTACT's planar patch): phi_i = phi, eta_i = eta,
//    xi_i = xi, q_i = -phi*y_i. The linear variation of the rolling radius across a planar patch
//    (r = r_ref - y sin(gamma)) is already the -phi*y term of the kinematic spin, so no separate
//    rolling-radius term is added (it would count the same slip twice).
//  - per_strip (STRIPES): each strip lies in its own tangent plane (contact angle gamma_i). The
//    wheel has ONE angular velocity Omega = V (1 - xi)/r_ref, so its kinematic spin at strip i is
//    -Omega sin(gamma_i)/V; the prescribed spin minus the kinematic spin at the reference point
//    (yaw-rate part etc.) stays uniform: phi_i = phi + (1 - xi)(sin(gamma_ref) - sin(gamma_i))/r_ref.
//    (The form phi + sin(g_ref)/r_ref - sin(g_i)/r_i differs from this by O(dr/r) < 1 %: the wheel
//    does not spin faster where its radius is smaller.) The longitudinal slip at the strip centre
//    is taken from the true rolling radius, q_i = -(phi - phi_kin,ref) y_i + (1 - xi)(r_ref - r_i)/r_ref,
//    in place of the planar -phi*y_i, again counted once; eta_i = eta cos(gamma_i - gamma_ref)
//    (the rigid lateral slip projected on the strip's rotated tangent plane); strip forces are
//    rotated back to the reference frame (the part along n_ref is dropped). On a planar patch
//    (all gamma_i equal, r_i = r_ref - y_i sin(gamma)) both variants coincide exactly.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/material.hpp"
#include "core/status.hpp"
#include "normal/normal_model.hpp"

namespace railtab {

struct Creepage {
  double xi = 0.0;   // longitudinal creepage, wheel minus rail, per rolling distance [-]
  double eta = 0.0;  // lateral creepage along s [-]
  double phi = 0.0;  // spin creepage about n at the patch reference point [rad/m]
};

enum class SpinVariation {
  patch_constant,  // one spin over a planar patch (Kalker, CONTACT)
  per_strip,       // spin and rolling radius follow each strip's contact angle (STRIPES)
};
const char* to_string(SpinVariation variation);

struct FastsimOptions {
  int elements_per_strip = 20;                           // steps along x per strip [-]
  SpinVariation spin = SpinVariation::patch_constant;    // see the header comment
};

// Where the patch sits in its contact frame: the normal layer's strips carry band arc length s
// (+ towards the field side of the rail), the contact frame's lateral axis is s = n x x (close to
// track +y for both wheels). Lateral coordinate of a strip: y = lateral_sign * (s - s_reference).
struct PatchPlacement {
  double s_reference = 0.0;   // band arc length of the patch reference point [m]
  double lateral_sign = 1.0;  // +1 left wheel, -1 right wheel (= outward_sign(side)) [-]
};
inline PatchPlacement placement_of(const WheelContactGeometry& geometry,
                                   const ContactPatch& patch) {
  PatchPlacement p;
  p.lateral_sign = outward_sign(geometry.side);
  // The patch's own reference point (the overlap reference of its run, normal_model.hpp).
  if (std::isfinite(patch.band_s)) p.s_reference = patch.band_s;
  return p;
}

// Elliptic patch for the classical FASTSIM (parabolic traction bound, Kalker 1982).
struct EllipticPatch {
  double a = 0.0;                // semi-axis along the rolling direction x [m]
  double b = 0.0;                // semi-axis along s [m]
  double normal_force = 0.0;     // [N]
  int strips = 40;               // lateral strips over [-b, b] [-]
  double rolling_radius = 0.46;  // wheel radius, used only to convert wear per pass to per metre [m]
  double wheel_u = 0.0;          // wheel-profile coordinate of the centre, for wear output [m]
  // d(wheel u)/d(lateral y along s) at the centre: sigma cos(beta), beta the contact angle
  // relative to the wheel axle, sigma = +1 left / -1 right wheel (s points towards -u on the right
  // wheel). The ellipse covers 2 b |du/dy| of the wheel profile; archard_wear reads the mapping
  // from the strips' wheel_u, so the wear lands on the profile where the patch lies. [-]
  double du_dy = 1.0;
};

struct FastsimResult {
  double fx = 0.0;               // creep force on the wheel along x [N]
  double fy = 0.0;               // creep force on the wheel along s [N]
  double mz = 0.0;               // spin moment on the wheel about n at the reference point [N m]
  double normal_force = 0.0;     // normal force the traction bound integrates to [N]
  double slip_fraction = 0.0;    // slipping area / contact area [-]
  double frictional_work = 0.0;  // sum of traction . slip over the patch, per rolling distance [J/m]
  StatusBits status = 0;         // kConverged; kFullSlip when every element slips or |F| = mu*N;
                                 // kLiftOff when the patch carries no load
};

// One strip as solved (copied from the patch or built for an ellipse), lateral order kept.
struct FastsimStrip {
  double y = 0.0;               // lateral coordinate of the strip centre, contact frame [m]
  double width = 0.0;           // strip width along s [m]
  double x_lead = 0.0;          // leading edge [m]
  double x_trail = 0.0;         // trailing edge [m]
  double pressure_peak = 0.0;   // peak pressure after scaling to the patch's normal force [Pa]
  bool parabolic = false;       // pressure shape along x: parabolic, else semi-elliptic
  double ellipse_a = 0.0;       // local ellipse semi-axes for the flexibilities [m]
  double ellipse_b = 0.0;       //   (rolling, lateral) [m]
  double wheel_u = 0.0;         // wheel-profile coordinate of the strip centre [m]
  double rolling_radius = 0.0;  // wheel radius at the strip centre [m]
  double contact_angle = 0.0;   // contact angle of the strip, track frame [rad]
  double dx = 0.0;              // element length along x [m]
};

// Per-thread scratch and per-element output of the last solve. Vectors only grow, so repeated
// solves of similar size do not allocate. Element e of strip i: strip_begin[i] <= e < strip_begin[i+1].
struct FastsimWorkspace {
  std::vector<FastsimStrip> strip;      // per strip (m)
  std::vector<int> strip_begin;         // first element of each strip plus an end marker (m + 1)
  // per element (sampled at the element centre x)
  std::vector<double> x;                // position along x [m]
  std::vector<double> pressure;         // normal pressure used for the bound (scaled) [Pa]
  std::vector<double> traction_x;       // shear stress on the wheel along x [Pa]
  std::vector<double> traction_y;       // shear stress on the wheel along the strip's s [Pa]
  std::vector<double> slip_x;           // micro-slip along x per rolling distance [-]
  std::vector<double> slip_y;           // micro-slip along s per rolling distance [-]
  std::vector<double> slip_velocity;    // |slip| * V [m/s]
  std::vector<double> slip_distance;    // sliding distance of a material point in the element [m]
  std::vector<double> wear_pressure;    // mean normal pressure while that sliding happens [Pa]
  std::vector<double> shape_scratch;    // pressure shape at the element centres (scratch) [-]
  double speed = 0.0;                   // rolling speed V of the last solve [m/s]
  double reference_radius = 0.0;        // rolling radius at the reference point (distance per
                                        //   wheel revolution / 2 pi) of the last solve [m]

  int strips() const { return static_cast<int>(strip.size()); }
  int elements() const { return strip_begin.empty() ? 0 : strip_begin.back(); }
};

// Strip-wise FASTSIM on a patch of the normal layer. mu >= 0, speed > 0 [m/s].
FastsimResult fastsim_patch(const ContactPatch& patch, const PatchPlacement& placement,
                            const Creepage& creepage, double mu, double speed,
                            const Material& material, const FastsimOptions& options,
                            FastsimWorkspace& workspace);

// Classical FASTSIM on an ellipse with Kalker's parabolic pressure 2N/(pi a b)(1 - x2/a2 - y2/b2).
FastsimResult fastsim_ellipse(const EllipticPatch& patch, const Creepage& creepage, double mu,
                              double speed, const Material& material, int elements_per_strip,
                              FastsimWorkspace& workspace);

// A workspace owned by the calling thread, for callers without their own.
FastsimWorkspace& thread_fastsim_workspace();

}  // namespace railtab
