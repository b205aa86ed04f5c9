// SPDX-License-Identifier: Apache-2.0
// ContactModel over a contact table: interpolates the table with railtab::lookup every step.
#include "simulate/lookup_contact_model.hpp"

#include <algorithm>
#include <cmath>

#include "core/check.hpp"

namespace railtab {
namespace {

namespace lk = railtab::lookup;

constexpr int kY = 0, kLoad = 1, kXi = 2, kEta = 3, kPhi = 4, kYaw = 5;

double variable(const lk::State& s, int v) {
  switch (v) {
    case kY: return s.y;
    case kLoad: return s.load;
    case kXi: return s.xi;
    case kEta: return s.eta;
    case kPhi: return s.phi;
    default: return s.yaw;
  }
}

// Cell of x in increasing `nodes` (x clamped to them): the lower node's index and the weight of
// the upper one.
void locate(const std::vector<double>& nodes, double x, std::size_t& i, double& t) {
  const std::size_t n = nodes.size();
  i = 0;
  t = 0.0;
  if (n < 2) return;
  const double xc = std::clamp(x, nodes.front(), nodes.back());
  i = static_cast<std::size_t>(std::upper_bound(nodes.begin(), nodes.end(), xc) - nodes.begin());
  i = std::clamp<std::size_t>(i, 1, n - 1) - 1;
  t = (xc - nodes[i]) / (nodes[i + 1] - nodes[i]);
}

int variable_index(const std::string& name) {
  for (int v = 0; v < kLookupVariables; ++v) {
    if (name == kLookupVariableNames[v]) return v;
  }
  return -1;
}

}  // namespace

LookupContactModel::LookupContactModel(lk::Table table)
    : table_(std::move(table)), base_(table_.default_state()), yaw_even_(table_.yaw_even()) {
  RAILTAB_CHECK(table_.n_slots() >= vehicle::kContactSlots, "{}: the table has {} contact slots, the simulation needs {}",
                table_.path(), table_.n_slots(), vehicle::kContactSlots);
  RAILTAB_CHECK(table_.has_part(lk::kGeometry) && table_.has_part(lk::kNormal) && table_.has_part(lk::kCreep),
                "{}: the table lacks the geometry, normal or creep part", table_.path());
  for (const lk::AxisInfo& axis : table_.axes()) {
    RAILTAB_CHECK(axis.name != "roll",
                  "{}: roll is a table axis; the wheelset model has no roll degree of freedom, so the simulation "
                  "needs a table with equilibrium_roll = true (or one fixed roll)",
                  table_.path());
    const int v = variable_index(axis.name);
    if (v < 0 || axis.nodes.empty()) continue;
    range_[static_cast<std::size_t>(v)] = {axis.nodes.front(), axis.nodes.back()};
    if (v == kY) y_nodes_ = axis.nodes;
    if (v == kYaw) yaw_nodes_ = axis.nodes;
  }
  RAILTAB_CHECK(!y_nodes_.empty(), "{}: the table does not tabulate y", table_.path());

  // The geometry part depends on y and yaw only (roll follows y): read it at every node. At a node
  // the interpolation weight of the neighbour is 0, so the values are the node's own.
  const std::size_t planes = std::max<std::size_t>(yaw_nodes_.size(), 1);
  for (int w = 0; w < vehicle::kWheels; ++w) {
    for (std::size_t j = 0; j < planes; ++j) {
      for (double y : y_nodes_) {
        lk::State s = base_;
        s.y = y;
        if (!yaw_nodes_.empty()) s.yaw = yaw_nodes_[j];
        if (!range_[kLoad].empty()) s.load = range_[kLoad][0];
        const lk::Result r = table_.query(static_cast<lk::Wheel>(w), s);
        for (int slot = 0; slot < vehicle::kContactSlots; ++slot) {
          const lk::Contact& c = r.contact[slot];
          GeometryNode node;
          node.present = c.value[lk::kRollingRadius] > 0.0;  // an empty slot is all zeros
          node.contact_angle = c.value[lk::kContactAngle];
          node.rolling_radius = c.value[lk::kRollingRadius];
          node.wheel_u = c.value[lk::kWheelY];
          geometry_[w][slot].push_back(node);
        }
      }
    }
  }
}

bool LookupContactModel::geometry_in_plane(int wheel, int slot, std::size_t plane, double y,
                                           GeometryNode& out) const {
  const std::size_t n = y_nodes_.size();
  const GeometryNode* g = geometry_[wheel][slot].data() + plane * n;
  std::size_t i = 0;
  double t = 0.0;
  locate(y_nodes_, y, i, t);
  const GeometryNode& a = g[i];
  const GeometryNode& b = g[std::min(i + 1, n - 1)];
  if (a.present && b.present) {
    out.present = true;
    out.contact_angle = a.contact_angle + t * (b.contact_angle - a.contact_angle);
    out.rolling_radius = a.rolling_radius + t * (b.rolling_radius - a.rolling_radius);
    out.wheel_u = a.wheel_u + t * (b.wheel_u - a.wheel_u);
    return true;
  }
  if (b.present) out = b;
  else if (a.present) out = a;
  return out.present;  // false: no point in this slot at either node
}

bool LookupContactModel::geometry_at(int wheel, int slot, double y, double yaw, vehicle::SlotContact& out) const {
  std::size_t j = 0;
  double t = 0.0;
  locate(yaw_nodes_, yaw_even_ ? std::abs(yaw) : yaw, j, t);
  GeometryNode a, b;
  const bool has_a = geometry_in_plane(wheel, slot, j, y, a);
  const bool has_b = yaw_nodes_.size() > 1 && geometry_in_plane(wheel, slot, j + 1, y, b);
  if (has_a && has_b) {
    a.contact_angle += t * (b.contact_angle - a.contact_angle);
    a.rolling_radius += t * (b.rolling_radius - a.rolling_radius);
    a.wheel_u += t * (b.wheel_u - a.wheel_u);
  } else if (has_b) {
    a = b;
  } else if (!has_a) {
    return false;  // the caller falls back
  }
  out.contact_angle = a.contact_angle;
  out.rolling_radius = a.rolling_radius;
  out.wheel_u = a.wheel_u;
  return true;
}

void LookupContactModel::count(const lk::State& state, lk::StatusBits query_bits) {
  ++counts_.queries;
  if (query_bits & lk::status::kOutOfRange) {
    ++counts_.out_of_range;
    for (std::size_t v = 0; v < kLookupVariables; ++v) {
      if (range_[v].empty()) continue;
      double x = variable(state, static_cast<int>(v));
      if (v == kYaw && yaw_even_) x = std::abs(x);  // the table reads |yaw|
      if (x < range_[v][0] || x > range_[v][1]) ++counts_.outside_axis[v];
    }
  }
  if (query_bits & lk::status::kInvalidInput) ++counts_.invalid_input;
}

void LookupContactModel::normal(double y, double yaw, const double (&load)[vehicle::kWheels],
                                vehicle::WheelContacts (&contacts)[vehicle::kWheels]) {
  lk::Query queries[vehicle::kWheels];
  lk::Result results[vehicle::kWheels];
  if (yaw_nodes_.empty()) yaw = base_.yaw;  // the table's one yaw
  for (int w = 0; w < vehicle::kWheels; ++w) {
    lk::State s = base_;
    s.y = y;
    s.yaw = yaw;
    s.load = load[w];  // a fixed load queried off its value is flagged out of range: reported
    // Zero creepage where the table tabulates it (the normal part does not depend on it).
    if (!range_[kXi].empty()) s.xi = 0.0;
    if (!range_[kEta].empty()) s.eta = 0.0;
    if (!range_[kPhi].empty()) s.phi = 0.0;
    state_[w] = s;
    queries[w] = {static_cast<lk::Wheel>(w), s};
  }
  table_.query(queries, results);

  for (int w = 0; w < vehicle::kWheels; ++w) {
    count(state_[w], results[w].status);
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot) {
      const lk::Contact& c = results[w].contact[slot];
      vehicle::SlotContact& out = contacts[w].slot[slot];
      out = {};
      out.normal_force = c.value[lk::kNormalForce];
      out.area = c.value[lk::kArea];
      out.status = c.status;
      out.loaded = out.normal_force > 0.0;
      loaded_[w][slot] = out.loaded;
      if (!out.loaded) continue;
      // A loaded patch whose rigid point sits in the other slot (its overlap reference crossed
      // the flange angle): the point it grew from.
      if (!geometry_at(w, slot, y, yaw, out) && !geometry_at(w, 1 - slot, y, yaw, out)) {
        // no point in either slot: the table's own interpolation
        out.contact_angle = c.value[lk::kContactAngle];
        out.rolling_radius = c.value[lk::kRollingRadius];
        out.wheel_u = c.value[lk::kWheelY];
      }
    }
  }
}

void LookupContactModel::creep(const vehicle::SlotCreepage (&creepage)[vehicle::kWheels][vehicle::kContactSlots],
                               vehicle::SlotForces (&forces)[vehicle::kWheels][vehicle::kContactSlots]) {
  for (int w = 0; w < vehicle::kWheels; ++w) {
    for (int slot = 0; slot < vehicle::kContactSlots; ++slot) {
      vehicle::SlotForces& f = forces[w][slot];
      f = {};
      if (!loaded_[w][slot]) continue;
      lk::State s = state_[w];
      // Always the true creepage: a table with a fixed creepage flags the query out of range.
      s.xi = creepage[w][slot].xi;
      s.eta = creepage[w][slot].eta;
      s.phi = creepage[w][slot].phi;
      lk::Contact c;
      table_.query_slot(static_cast<lk::Wheel>(w), s, slot, c);
      // query_slot folds the query bits into the slot status.
      count(s, c.status & (lk::status::kOutOfRange | lk::status::kInvalidInput));
      f.fx = c.value[lk::kFx];
      f.fy = c.value[lk::kFy];
      f.mz = c.value[lk::kMz];
      f.status = c.part_status[lk::kCreep] | (c.status & (lk::status::kOutOfRange | lk::status::kInvalidInput));
    }
  }
}

}  // namespace railtab
