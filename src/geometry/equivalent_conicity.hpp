// SPDX-License-Identifier: Apache-2.0
// Equivalent conicity of a wheelset on track against the amplitude of its lateral motion (EN 15302,
// UIC 519 before it), from the rolling radius difference function Delta r(y) sampled along y:
// by the standard's reference principle (the wavelength of the free wheelset's nonlinear kinematic
// oscillation, Klingel) and by the linear regression of Delta r over a harmonic motion (the
// standard's annex method). The same regression gives the linear parameters of any other function
// of y (roll angle, contact angle difference). Definitions and signs: docs/conventions.md.
#pragma once

#include <vector>

namespace railtab {

// A function of the wheelset's lateral displacement y [m], sampled on a strictly increasing grid and
// interpolated linearly between the samples (the interpolant the methods below integrate exactly).
struct LateralFunction {
  std::vector<double> y;      // lateral displacement, track frame, + left, strictly increasing [m]
  std::vector<double> value;  // the function at each y (same size as y) [its unit]
};

// The kinematic oscillation of a free wheelset at one amplitude: y'' = -Delta r(y) / (2 e0 r0)
// along the track, between the turning points y_min and y_max (Delta r's integral
// S(y) = int_{y_centre}^{y} Delta r takes the same value at both). Its wavelength is
// lambda = 2 pi sqrt(e0 r0 / conicity); the conicity does not depend on e0 and r0.
struct KinematicOscillation {
  double amplitude = 0.0;  // half the peak-to-peak lateral motion, (y_max - y_min) / 2 [m]
  double y_min = 0.0;      // right turning point [m]
  double y_max = 0.0;      // left turning point [m]
  double conicity = 0.0;   // tan gamma_e: the cone slope of a conical wheelset with the same
                           // wavelength at this amplitude [-]
};

// Centre of the kinematic motion [m]: the y where Delta r rises through zero (negative to its
// right, positive to its left, so the rolling radii steer the wheelset back), the crossing nearest
// to y = 0. Throws railtab::Error when Delta r never rises through zero within the samples (no
// restoring rolling radius difference: no kinematic oscillation).
double kinematic_centre(const LateralFunction& delta_r);

// The oscillation of amplitude `amplitude` [m] (> 0) about kinematic_centre(delta_r), by the
// standard's reference principle: the wavelength from integrating the nonlinear equation over one
// cycle. The integral is exact for the linear interpolant up to a quadrature of relative error
// below 1e-9 (tests/geometry/equivalent_conicity_test.cpp). Returns conicity = NaN when a turning
// point lies beyond the sampled range (the amplitude needs samples further out). Throws
// railtab::Error for fewer than 3 samples, a non-increasing or non-finite y, a non-finite value.
KinematicOscillation kinematic_oscillation(const LateralFunction& delta_r, double amplitude);

// Slope of the least-squares line through f over the harmonic motion y = centre + amplitude sin(t),
// t uniform over one period (the motion's own distribution of y, so the fit is the first harmonic
// of f: the describing function), with an intercept [unit of f / m]. NaN when the motion leaves the
// sampled range. Same input checks as above.
double harmonic_regression_slope(const LateralFunction& f, double centre, double amplitude);

// The standard's linear regression method: half the regression slope of Delta r [-].
double regression_conicity(const LateralFunction& delta_r, double amplitude);

// Linear value of f at y by linear interpolation of the samples; NaN outside the sampled range.
double interpolate_lateral(const LateralFunction& f, double y);

}  // namespace railtab
