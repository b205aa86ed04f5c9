// SPDX-License-Identifier: Apache-2.0
// One evaluated state as the JSON document of railtab eval --json (state_json.hpp).
#include "eval/state_json.hpp"

namespace railtab {
namespace {

nlohmann::json contact_json(const EvaluatedContact& contact, bool with_creep) {
  const ContactPatch& patch = contact.patch;
  nlohmann::json c;
  c["wheel_y"] = patch.wheel_u;
  c["rail_y"] = patch.rail_u;
  c["contact_angle"] = patch.contact_angle;
  c["rolling_radius"] = patch.rolling_radius;
  c["model"] = to_string(patch.model);
  c["normal_force"] = patch.normal_force;
  c["approach"] = patch.penetration;
  c["area"] = patch.area;
  c["max_pressure"] = patch.max_pressure;
  if (patch.model == NormalModel::hertz) {
    c["a"] = patch.semi_axis_a;
    c["b"] = patch.semi_axis_b;
  }
  c["rigid_point"] = patch.point_index;
  if (with_creep) {
    c["fx"] = contact.force.fx;
    c["fy"] = contact.force.fy;
    c["mz"] = contact.force.mz;
    c["slip_fraction"] = contact.force.slip_fraction;
    c["wear_rate"] = contact.wear.wear_rate;
  }
  c["status"] = status::describe(contact.status);
  c["status_bits"] = contact.status;
  return c;
}

nlohmann::json point_json(const EvaluatedPoint& p) {
  const ContactPoint& point = p.point;
  return {{"wheel_y", point.wheel_u},         {"rail_y", point.rail_u},
          {"y_track", point.y_track},         {"z_track", point.z_track},
          {"contact_angle", point.contact_angle}, {"rolling_radius", point.rolling_radius},
          {"separation", point.separation},   {"curvature_a", point.curvature_a},
          {"curvature_b", point.curvature_b}, {"patch", p.patch},
          {"status", status::describe(p.status)}, {"status_bits", p.status}};
}

}  // namespace

nlohmann::json state_json(const StateEvaluation& e) {
  nlohmann::json out;
  out["scene"] = e.scene;
  out["state"] = {{"y", e.y}, {"roll", e.roll}, {"yaw", e.yaw}, {"load", e.load}};
  out["normal_model"] = to_string(e.normal_model);
  if (e.with_creep) {
    out["creepage"] = {{"xi", e.creepage[0]}, {"eta", e.creepage[1]}, {"phi", e.creepage[2]}};
    out["friction"] = e.friction;
    out["spin"] = e.spin;
  }
  if (e.element_size) out["element_size"] = *e.element_size;
  out["rolling_radius_difference"] = e.rolling_radius_difference;
  out["wheels"] = nlohmann::json::array();
  for (const EvaluatedWheel& w : e.wheels) {
    nlohmann::json wj;
    wj["side"] = to_string(w.side);
    wj["vertical_approach"] = w.vertical_approach;
    wj["vertical_load"] = w.carried_load;
    if (w.coupled) {
      // The load balance in track axes: vertical_load_normal + vertical_load_tangential = load.
      wj["vertical_load_normal"] = w.vertical_load_normal;
      wj["vertical_load_tangential"] = w.vertical_load_tangential;
      wj["load_coupling"] = {{"enabled", e.load_coupling}, {"status", status::describe(w.coupling_status)}};
      if (w.coupling_iterations >= 0) wj["load_coupling"]["iterations"] = w.coupling_iterations;
    }
    wj["contacts"] = nlohmann::json::array();
    for (const EvaluatedContact& c : w.contacts) wj["contacts"].push_back(contact_json(c, e.with_creep));
    wj["status"] = status::describe(w.status);
    wj["rigid_points"] = nlohmann::json::array();
    for (const EvaluatedPoint& p : w.rigid_points) wj["rigid_points"].push_back(point_json(p));
    out["wheels"].push_back(wj);
  }
  return out;
}

}  // namespace railtab
