// SPDX-License-Identifier: Apache-2.0
// ContactProbe: the contact chain of a scene at single states, for placing adaptive grid nodes
// and for checking tables against direct evaluation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene/scene.hpp"

namespace railtab {

// Bits of ContactProbe::Slot::status.
namespace probe_slot_bits {
constexpr std::uint32_t kGeometry = 1u << 0;       // a geometric point in the slot
constexpr std::uint32_t kGeometryTwo = 1u << 1;    // two points competed for the slot
constexpr std::uint32_t kLoaded = 1u << 2;         // a loaded patch in the slot
constexpr std::uint32_t kPatchDropped = 1u << 3;   // a third patch was dropped from the slot (its load is missing)
constexpr std::uint32_t kFailed = 1u << 4;         // the core threw
constexpr std::uint32_t kGeometryFirst = 1u << 5;  // of two points in the slot, the kept one has the smaller wheel u
// A slot's values are the sum of its up to two patches (slot_normal, slot_creep), so a second patch
// appearing in a slot with ~0 load is continuous and carries no marker; a patch moving between the
// slots (its angle crossing flange_angle) shows as kLoaded changing when it enters or leaves an
// empty slot, else as an error at min_step (an unmet interval).
}  // namespace probe_slot_bits

// The direct contact chain of a scene at single states (geometry -> normal -> FASTSIM), as the
// sweep kernel computes it (same core calls, same slot assignment). Thread-safe.
class ContactProbe {
 public:
  explicit ContactProbe(const Scene& scene);
  ~ContactProbe();
  ContactProbe(const ContactProbe&) = delete;
  ContactProbe& operator=(const ContactProbe&) = delete;

  struct Slot {
    bool geometry = false;        // a geometric contact point is in this slot
    double contact_angle = 0.0;   // [rad]
    double rolling_radius = 0.0;  // [m]
    bool loaded = false;          // a loaded patch is in this slot
    double normal_force = 0.0;    // [N]
    double patch_angle = 0.0;     // contact angle of the loaded patch's reference point [rad]
    double patch_radius = 0.0;    // rolling radius of the loaded patch's reference point [m]
    std::uint32_t patch_status = 0;  // status bits of the loaded patch (src/core/status.hpp)
    double fx = 0.0, fy = 0.0;    // creep forces on the wheel [N]
    std::uint32_t status = 0;     // geometry and patch slot bits (kTwoPoint, occupancy)
  };
  struct Wheel {
    Slot slot[2];                 // 0 tread, 1 flange
  };
  // Both wheels at (y, roll of the scene at y, load, creepage). loads/creepages: several at once on
  // one geometry; result [load][creepage][wheel].
  std::vector<std::vector<std::array<Wheel, 2>>> evaluate(double y, const std::vector<double>& loads,
                                                           const std::vector<std::array<double, 3>>& creepages) const;
  // The contact configuration of one wheel (0 left, 1 right) at (y, roll of the scene at y, load)
  // without creep forces (fx = fy = 0): the slots' geometry and loaded-patch bits, contact angles
  // and rolling radii as evaluate() gives them. normal_force and patch_status are the normal
  // model's, except for the exact model in a state with at most one patch, where they are the
  // candidate patch's (halfspace::candidate_patches: same patch, slot and reference point, no
  // exact solve). For the contact-jump locator.
  Wheel configuration(double y, std::size_t wheel, double load) const;
  double roll_at(double y) const;   // equilibrium roll or the roll grid's first value [rad]
  double friction() const;          // mu [-]

 private:
  struct Data;
  Data* data_;
};

}  // namespace railtab
