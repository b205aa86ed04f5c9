// SPDX-License-Identifier: Apache-2.0
// vehicle::ContactModel over a contact table (railtab::lookup): what a simulation does every step.
// normal() is one batch query of both wheels at zero creepage, creep() one query_slot per loaded
// slot at its own creepage. Queries the table flags out of range or invalid are counted (per
// axis too), never hidden: the simulation reports them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <railtab/lookup.hpp>

#include "vehicle/contact_model.hpp"

namespace railtab {

// How often the table was asked outside its grid (clamped) or with NaN/inf.
struct LookupCounts {
  std::uint64_t queries = 0;        // table queries (a batch of two wheels counts 2) [-]
  std::uint64_t out_of_range = 0;   // queries flagged kOutOfRange [-]
  std::uint64_t invalid_input = 0;  // queries flagged kInvalidInput [-]
  // Queries whose variable lay outside its axis, per state variable (y, load, xi, eta, phi, yaw).
  std::array<std::uint64_t, 6> outside_axis{};
};
inline constexpr int kLookupVariables = 6;
inline constexpr const char* kLookupVariableNames[kLookupVariables] = {"y", "load", "xi", "eta", "phi", "yaw"};

class LookupContactModel final : public vehicle::ContactModel {
 public:
  // The table must tabulate y; roll must follow the equilibrium or be fixed (the wheelset model
  // has no roll degree of freedom). Throws railtab::Error naming the table otherwise.
  explicit LookupContactModel(lookup::Table table);

  // A table with a yaw axis is queried at the wheelset's `yaw` (clamped to the axis and counted
  // when outside it); a table without one at its own fixed yaw, whatever `yaw` is.
  void normal(double y, double yaw, const double (&load)[vehicle::kWheels],
              vehicle::WheelContacts (&contacts)[vehicle::kWheels]) override;
  void creep(const vehicle::SlotCreepage (&creepage)[vehicle::kWheels][vehicle::kContactSlots],
             vehicle::SlotForces (&forces)[vehicle::kWheels][vehicle::kContactSlots]) override;

  const LookupCounts& counts() const { return counts_; }
  const lookup::Table& table() const { return table_; }
  bool has_yaw_axis() const { return !yaw_nodes_.empty(); }

 private:
  // Rigid contact point of one slot at one y node of the table.
  struct GeometryNode {
    bool present = false;          // the slot has a contact point at this node
    double contact_angle = 0.0;    // [rad]
    double rolling_radius = 0.0;   // [m]
    double wheel_u = 0.0;          // [m]
  };
  // The slot's geometry at (y, yaw): linear in y between the nodes where the slot has a point, then
  // linear in yaw between the two yaw planes that have one. False: no point in reach.
  bool geometry_at(int wheel, int slot, double y, double yaw, vehicle::SlotContact& out) const;
  bool geometry_in_plane(int wheel, int slot, std::size_t plane, double y, GeometryNode& out) const;
  void count(const lookup::State& state, lookup::StatusBits query_bits);

  lookup::Table table_;
  lookup::State base_;                        // fixed axes at their values
  std::vector<double> y_nodes_;               // the table's y axis [m]
  std::vector<double> yaw_nodes_;             // the table's yaw axis [rad]; empty: yaw is fixed
  bool yaw_even_ = false;                     // the axis is the half yaw >= 0 of a symmetric one: read at |yaw|
  std::array<std::vector<double>, kLookupVariables> range_;  // per variable: {min, max} of its axis, empty if fixed
  // [wheel][slot][yaw node * y nodes + y node] (one yaw plane without a yaw axis): the geometry
  // part read at the nodes, so that a slot present at only one corner of a cell keeps that
  // corner's point instead of being averaged with zeros (a rolling radius of r/2 would make
  // nonsense creepages).
  std::vector<GeometryNode> geometry_[vehicle::kWheels][vehicle::kContactSlots];
  lookup::State state_[vehicle::kWheels];     // the last normal() states
  bool loaded_[vehicle::kWheels][vehicle::kContactSlots] = {};
  LookupCounts counts_;
};

}  // namespace railtab
