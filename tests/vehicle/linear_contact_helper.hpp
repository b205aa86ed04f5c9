// SPDX-License-Identifier: Apache-2.0
// A synthetic contact model with closed-form answers, for the vehicle tests: coned wheels on
// knife-edge rails. Rolling radius r = r0 + sigma lambda y (the left wheel grows when the wheelset
// moves left), a contact angle +-delta (towards the flange on both wheels; optionally growing
// towards the flange the wheelset moves to, for a gravitational stiffness), the contact
// fixed in the track (wheel_u = -sigma y), N cos(delta) = Q, tread slot only, and a linear creep
// law fx = -f11 xi, fy = -f22 eta, mz = 0, optionally limited to |(fx, fy)| <= mu N.
#pragma once

#include <cmath>

#include "core/status.hpp"
#include "vehicle/contact_model.hpp"

namespace railtab::vehicle::testing {

class LinearContact : public ContactModel {
 public:
  double r0 = 0.46;          // [m]
  double conicity = 0.1;     // lambda [-]
  double angle = 0.05;       // delta [rad]
  double angle_slope = 0.0;  // d(contact angle)/dy of both wheels [rad/m]: gravitational stiffness
  double f11 = 6.0e6;        // longitudinal creep stiffness [N]
  double f22 = 6.0e6;        // lateral creep stiffness [N]
  double mu = 0.0;           // friction limit; 0: unlimited
  double area = 1.0e-4;      // [m2], the same for both wheels
  int normal_calls = 0;
  int creep_calls = 0;

  void normal(double y, double /*yaw*/, const double (&load)[kWheels],
              WheelContacts (&contacts)[kWheels]) override {
    ++normal_calls;
    for (int w = 0; w < kWheels; ++w) {
      const double sigma = w == 0 ? 1.0 : -1.0;
      SlotContact& c = contacts[w].slot[0];
      c.loaded = load[w] > 0.0;
      c.contact_angle = sigma * angle + angle_slope * y;
      c.rolling_radius = r0 + sigma * conicity * y;
      c.wheel_u = -sigma * y;
      c.normal_force = load[w] / std::cos(c.contact_angle);
      c.area = area;
      c.status = 0;
      contacts[w].slot[1] = SlotContact{};
      normal_force_[w] = c.normal_force;
    }
  }

  void creep(const SlotCreepage (&creepage)[kWheels][kContactSlots],
             SlotForces (&forces)[kWheels][kContactSlots]) override {
    ++creep_calls;
    for (int w = 0; w < kWheels; ++w) {
      SlotForces& f = forces[w][0];
      f = SlotForces{};
      f.fx = -f11 * creepage[w][0].xi;
      f.fy = -f22 * creepage[w][0].eta;
      const double magnitude = std::hypot(f.fx, f.fy);
      const double limit = mu * normal_force_[w];
      if (mu > 0.0 && magnitude > limit) {
        f.fx *= limit / magnitude;
        f.fy *= limit / magnitude;
        f.status = status::kFullSlip;
      }
      forces[w][1] = SlotForces{};
    }
  }

 private:
  double normal_force_[kWheels] = {};
};

}  // namespace railtab::vehicle::testing
