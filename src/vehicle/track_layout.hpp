// SPDX-License-Identifier: Apache-2.0
// The track a simulated wheelset runs on: a sequence of sections (tangent, transition, circular)
// along the centreline, each with curvature and cant ramping linearly over its length (a clothoid
// with a linear cant ramp for transitions), plus a lateral irregularity of both rails.
// Sign: curvature > 0 for a curve to the LEFT (centre at +y), cant > 0 raises the outer rail.
// The outer rail at each end of a section is the one outside the curve there: the sign of that
// end's curvature decides (right rail for > 0, left rail for < 0; an end with zero curvature takes
// the other end's side). The signed cant (+ right rail up) then ramps linearly between the ends,
// so a reverse transition (left curve into right curve) passes through zero cant. Cant on a
// section with zero curvature at both ends has no outer rail and throws.
#pragma once

#include <vector>

namespace railtab::vehicle {

struct TrackSection {
  double length = 0.0;            // along the centreline [m], > 0
  double curvature_start = 0.0;   // 1/R at the start [1/m]
  double curvature_end = 0.0;     // 1/R at the end [1/m]
  double cant_start = 0.0;        // superelevation height of the outer rail at the start [m]
  double cant_end = 0.0;          // ... at the end [m]
};

// Lateral alignment irregularity of both rails (the rails move together): a sum of `components`
// sinusoids with wavelengths spread log-uniformly over [wavelength_min, wavelength_max] (evenly
// in log, both ends included), random phases from `seed` (std::mt19937: the same on every
// platform), amplitudes in proportion to sqrt(wavelength) (a displacement PSD falling as
// 1/wavenumber^2), then all scaled so that the largest |y_irr| over the route, sampled every
// 0.25 m, is `amplitude`. amplitude = 0: perfect track.
struct Irregularity {
  double amplitude = 0.0;          // [m]
  double wavelength_min = 10.0;    // [m]
  double wavelength_max = 60.0;    // [m]
  int components = 8;
  unsigned seed = 1;
};

// The track at one position s along the centreline.
struct TrackPoint {
  double curvature = 0.0;          // kappa [1/m]
  double cant_angle = 0.0;         // SIGNED: g sin(cant_angle) is gravity along track +y, i.e.
                                   // +asin(cant / rail_centre_distance) in a left curve (right
                                   // rail raised), - in a right curve [rad]
  double lateral_irregularity = 0.0;  // lateral shift of both rails, track y [m]
  double curvature_rate = 0.0;     // dkappa/ds [1/m2] (transitions)
};

class TrackLayout {
 public:
  // Throws railtab::Error for an empty route, a non-positive or non-finite length, non-finite
  // curvature or cant, or rail_centre_distance <= 0; for |cant| >= rail_centre_distance, cant
  // with no curve direction (see above); for an irregularity with amplitude < 0 or non-finite, or
  // amplitude > 0 with components < 1 or not 0 < wavelength_min <= wavelength_max.
  TrackLayout(std::vector<TrackSection> sections, Irregularity irregularity,
              double rail_centre_distance = 1.5);

  TrackPoint at(double s) const;  // s clamped to [0, length()]
  double length() const;          // [m]
  const std::vector<TrackSection>& sections() const;

 private:
  std::vector<TrackSection> sections_;
  std::vector<double> section_start_;  // cumulative start of each section [m]
  Irregularity irregularity_;
  std::vector<double> wavenumber_, phase_, weight_;  // irregularity components
  std::vector<double> signed_cant_start_, signed_cant_end_;  // per section, + right rail up [m]
  double irregularity_at(double s) const;
  double rail_centre_distance_;
  double length_ = 0.0;
};

}  // namespace railtab::vehicle
