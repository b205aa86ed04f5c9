// Wear post-processing of a simulation, once per wheel revolution, as seed 001 does after its MBS
// runs: at the wheelset's state the core solves geometry, the scene's normal model, FASTSIM and
// Archard/KTH wear for every loaded patch of each wheel, and the radial wear depth per strip is
// accumulated across the wheel profile on a fixed grid of wheel u (wear smeared around the
// circumference). The creepages of each patch come from vehicle::creepage with the patch's own
// contact angle, rolling radius and position, so the wear sees the same kinematics as the dynamics.
#pragma once

#include <vector>

#include "scene.hpp"
#include "vehicle/kinematics.hpp"

namespace railtab {

struct WearGrid {
  double u_min = -0.070;  // first bin edge, wheel-profile u [m]
  double u_max = 0.060;   // last bin edge [m]
  double step = 0.0002;   // bin width [m]
};

class WearAccumulator {
 public:
  // Profiles, models, material, friction and wear settings come from `scene` (its wheel profile
  // is the current, possibly worn, one). Throws railtab::Error for a bad scene or grid.
  WearAccumulator(const Scene& scene, const WearGrid& grid = {});

  // One sample standing for `distance` [m] rolled at this state: wheelset lateral displacement
  // relative to the rails `y_relative` [m] (roll at the kinematic equilibrium), vertical wheel
  // loads [N], and the wheelset motion (speed, yaw, rates, curvature, spin speed) for the
  // creepages. Returns the OR of the status bits of every patch solved. A failing solve is
  // counted (failures()) and adds no wear; it does not throw.
  std::uint32_t sample(double y_relative, const double (&load)[vehicle::kWheels],
                       const vehicle::WheelsetMotion& motion, double distance);

  const std::vector<double>& u() const;                 // bin centres [m]
  const std::vector<double>& depth(int wheel) const;    // accumulated radial depth per bin [m]
  double worn_area(int wheel) const;                    // integral of depth over u [m2]
  double distance() const;                              // sum of sample distances [m]
  int samples() const;
  int failures() const;
  void scale(double factor);                            // multiply every depth (mileage scaling)
};

}  // namespace railtab
