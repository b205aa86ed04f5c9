// SPDX-License-Identifier: Apache-2.0
// Wear post-processing of a simulation, once per wheel revolution, as Enblom and Berg 2008 does after its MBS
// runs: at the wheelset's state the core solves geometry, the scene's normal model, FASTSIM and
// Archard/KTH wear for every loaded patch of each wheel, and the radial wear depth per strip is
// accumulated across the wheel profile on a fixed grid of wheel u (wear smeared around the
// circumference). The creepages of each patch come from vehicle::creepage with the patch's own
// contact angle, rolling radius and position, so the wear sees the same kinematics as the dynamics.
// FASTSIM runs at the simulation's speed (the KTH map depends on the slip velocity), not the
// scene's. Each strip's radial depth is spread over its extent in u by overlap length, so the worn
// area equals Archard's wear rate times distance. docs/wear-evolution.md describes the method.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "vehicle/kinematics.hpp"
#include "simulate/wheel_wear.hpp"

namespace railtab {

struct WearGrid {
  double u_min = -0.070;  // first bin edge, wheel-profile u [m]
  double u_max = 0.060;   // last bin edge [m]
  double step = 0.0002;   // bin width [m]
};

class WearAccumulator {
 public:
  // Profiles, models, material, friction and wear settings come from `scene` (its wheel profile
  // is the current, possibly worn, one); the contact model of the wear is `post_processor`
  // (wheel_wear.hpp), by default the scene's normal model. Throws railtab::Error for a bad
  // scene, post-processor or grid.
  explicit WearAccumulator(const Scene& scene, const WearGrid& grid = {});
  WearAccumulator(const Scene& scene, const std::string& post_processor,
                  const WearGrid& grid = {});

  // One sample standing for `distance` [m] rolled at this state: wheelset lateral displacement
  // relative to the rails `y_relative` [m] (roll at the kinematic equilibrium), the vertical
  // contact force of each wheel [N] (the normal problem is solved for it), and the wheelset motion (speed, yaw, rates, curvature, spin speed) for the
  // creepages. The geometry is at the motion's yaw when the scene tabulates yaw ([grid] yaw with
  // several values, as the dynamics' table), otherwise at the scene's fixed yaw (0 without the key). Returns the OR of the status bits of every patch solved. A failing solve is
  // counted (failures(), once per wheel) and adds no wear for that wheel; the returned bits then
  // carry kFailed. A wheel with zero load adds nothing (kLiftOff). Throws railtab::Error only for
  // bad arguments: a load or distance that is negative or not finite, a speed that is not > 0.
  std::uint32_t sample(double y_relative, const double (&load)[vehicle::kWheels],
                       const vehicle::WheelsetMotion& motion, double distance);

  const std::vector<double>& u() const;                 // bin centres [m]
  const std::vector<double>& depth(int wheel) const;    // accumulated radial depth per bin [m]
  double worn_area(int wheel) const;                    // integral of depth over u [m2]
  double distance() const;                              // sum of sample distances [m]
  int samples() const;
  int failures() const;
  std::uint32_t status_seen() const;  // OR of the status bits of every wheel solved so far
  int not_converged() const;          // wheel solves flagged kNotConverged (best estimate kept) [-]
  void scale(double factor);                            // multiply every depth (mileage scaling)

  // Worn area of strips that fell outside the grid and was therefore NOT added [m2]: should be 0;
  // anything else means the grid is narrower than the contact band.
  double clipped_area(int wheel) const;

 private:
  void add_strip(int wheel, double u_centre, double width_u, double depth);

  ContactGeometrySolver solver_;
  bool yaw_axis_ = false;    // the scene tabulates yaw: the geometry follows the motion's yaw
  double fixed_yaw_ = 0.0;   // otherwise this yaw [rad]
  std::unique_ptr<WheelWear> wheel_wear_;
  WearGrid grid_;
  std::vector<double> u_;
  std::array<std::vector<double>, vehicle::kWheels> depth_;
  std::array<double, vehicle::kWheels> clipped_{};
  double distance_ = 0.0;
  int samples_ = 0;
  int failures_ = 0;
  std::uint32_t status_seen_ = 0;
  int not_converged_ = 0;
  // Reused between samples (it only grows): one accumulator per running simulation.
  std::vector<StripWear> pending_;  // one wheel's strips, added only when its whole chain succeeded
};

}  // namespace railtab
