// SPDX-License-Identifier: Apache-2.0
// Simulation scenes: TOML (toml++) into a SimulationScene. As in scene.cpp every key is checked
// against its section's list, so a typo is an error naming file, line and dotted key; the
// checked reading is generator/toml_section.hpp, shared with scene.cpp.
#include "scene/simulation_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/check.hpp"
#include "normal/normal_model.hpp"
#include "scene/toml_section.hpp"

namespace railtab {
namespace {

using scene_toml::Context;
using scene_toml::fail;
using scene_toml::non_negative;
using scene_toml::positive;
using scene_toml::Section;
using scene_toml::table_at;

// A route section as written, before transitions are resolved.
struct RawSection {
  std::string kind;          // "tangent", "transition", "circular"
  double length = 0.0;       // [m]
  double curvature = 0.0;    // circular: 1/radius [1/m]
  double cant = 0.0;         // circular: [m]
};

std::vector<vehicle::TrackSection> resolve_transitions(const Context& file, const std::vector<RawSection>& raw,
                                                       const toml::source_region& where) {
  std::vector<vehicle::TrackSection> out;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    vehicle::TrackSection s;
    s.length = raw[i].length;
    if (raw[i].kind != "transition") {
      s.curvature_start = s.curvature_end = raw[i].curvature;
      s.cant_start = s.cant_end = raw[i].cant;
    } else {
      // A transition ramps from the end of the previous section to the start of the next one
      // (tangent track beyond the ends of the route).
      const bool next_is_transition = i + 1 < raw.size() && raw[i + 1].kind == "transition";
      if (next_is_transition) fail(file, where, "route.section", fmt::format("sections {} and {} are both transitions", i + 1, i + 2));
      s.curvature_start = i > 0 ? out.back().curvature_end : 0.0;
      s.cant_start = i > 0 ? out.back().cant_end : 0.0;
      s.curvature_end = i + 1 < raw.size() ? raw[i + 1].curvature : 0.0;
      s.cant_end = i + 1 < raw.size() ? raw[i + 1].cant : 0.0;
    }
    out.push_back(s);
  }
  return out;
}

void parse_vehicle(const Context& file, const toml::table& root, vehicle::BogieParameters& b) {
  static const std::vector<std::string> kKeys{
      "mass", "yaw_inertia", "primary_lateral_stiffness", "primary_longitudinal_stiffness",
      "primary_lateral_damping", "axlebox_semi_spacing", "semi_wheelbase", "nominal_radius", "running_circle_q",
      "gravity", "frame_mass", "frame_yaw_inertia", "frame_cg_height", "body_mass", "body_cg_height",
      "bogie_semi_spacing", "secondary_lateral_stiffness", "secondary_lateral_damping", "secondary_yaw_stiffness",
      "secondary_yaw_damping"};
  const toml::table* table = table_at(file, root, "vehicle", "vehicle");
  if (table) {
    for (const char* key : {"carried_mass", "cg_height"}) {
      if (const toml::node* n = table->get(key)) {
        fail(file, n->source(), fmt::format("vehicle.{}", key),
             "the bogie vehicle derives each wheelset's carried mass and its height from body_mass, frame_mass, "
             "body_cg_height and frame_cg_height (docs/vehicle-model.md)");
      }
    }
  }
  Section k(file, "vehicle", table, kKeys);
  const char* kPositive = "> 0";
  vehicle::WheelsetParameters& v = b.wheelset;
  v.mass = k.number("mass", v.mass, positive, kPositive);
  v.yaw_inertia = k.number("yaw_inertia", v.yaw_inertia, positive, kPositive);
  v.primary_lateral_stiffness = k.number("primary_lateral_stiffness", v.primary_lateral_stiffness, non_negative, ">= 0");
  v.primary_longitudinal_stiffness =
      k.number("primary_longitudinal_stiffness", v.primary_longitudinal_stiffness, non_negative, ">= 0");
  v.primary_lateral_damping = k.number("primary_lateral_damping", v.primary_lateral_damping, non_negative, ">= 0");
  v.axlebox_semi_spacing = k.number("axlebox_semi_spacing", v.axlebox_semi_spacing, positive, kPositive);
  v.semi_wheelbase = k.number("semi_wheelbase", v.semi_wheelbase, positive, kPositive);
  v.nominal_radius = k.number("nominal_radius", v.nominal_radius, positive, kPositive);
  v.running_circle_q = k.number("running_circle_q", v.running_circle_q, positive, kPositive);
  v.gravity = k.number("gravity", v.gravity, positive, kPositive);
  b.frame_mass = k.number("frame_mass", b.frame_mass, positive, kPositive);
  b.frame_yaw_inertia = k.number("frame_yaw_inertia", b.frame_yaw_inertia, positive, kPositive);
  b.frame_cg_height = k.number("frame_cg_height", b.frame_cg_height, non_negative, ">= 0");
  b.body_mass = k.number("body_mass", b.body_mass, non_negative, ">= 0");
  b.body_cg_height = k.number("body_cg_height", b.body_cg_height, non_negative, ">= 0");
  // The simulated bogie is the car's leading one (+); the trailing wheelset of it stands in for
  // the outer axle running backwards (docs/simulation.md).
  b.bogie_semi_spacing = k.number("bogie_semi_spacing", b.bogie_semi_spacing, non_negative, ">= 0");
  b.secondary_lateral_stiffness =
      k.number("secondary_lateral_stiffness", b.secondary_lateral_stiffness, non_negative, ">= 0");
  b.secondary_lateral_damping = k.number("secondary_lateral_damping", b.secondary_lateral_damping, non_negative, ">= 0");
  b.secondary_yaw_stiffness = k.number("secondary_yaw_stiffness", b.secondary_yaw_stiffness, non_negative, ">= 0");
  b.secondary_yaw_damping = k.number("secondary_yaw_damping", b.secondary_yaw_damping, non_negative, ">= 0");
}

void parse_route(const Context& file, const toml::table& root, SimulationScene& scene) {
  const toml::table* route = table_at(file, root, "route", "route");
  Section k(file, "route", route, {"rail_centre_distance", "section", "irregularity"});
  if (!route) fail(file, {}, "route", "missing required section [route]");
  scene.rail_centre_distance = k.number("rail_centre_distance", 1.5, positive, "> 0");

  const toml::node& sections = k.required("section");
  const toml::array* list = sections.as_array();
  if (!list || list->empty() || !list->is_array_of_tables()) {
    fail(file, sections.source(), "route.section", "expected one or more [[route.section]] tables");
  }
  std::vector<RawSection> raw;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table& t = *list->get(i)->as_table();
    const std::string name = fmt::format("route.section[{}]", i + 1);
    Section s(file, name, &t, {"kind", "length", "radius", "cant"});
    RawSection r;
    r.kind = s.string(s.required("kind"), "kind");
    if (r.kind != "tangent" && r.kind != "transition" && r.kind != "circular") {
      fail(file, s.required("kind").source(), s.dotted("kind"),
           fmt::format("expected \"tangent\", \"transition\" or \"circular\", got \"{}\"", r.kind));
    }
    r.length = s.number("length", 0.0, positive, "> 0", true);
    if (r.kind == "circular") {
      // Radius > 0: a curve to the left (centre at +y), < 0: to the right (docs/conventions.md).
      const double radius = s.number("radius", 0.0, [](double v) { return std::abs(v) >= 10.0; }, "|radius| >= 10 m", true);
      r.curvature = 1.0 / radius;
      r.cant = s.number("cant", 0.0, [](double v) { return v >= 0.0 && v <= 0.25; }, "in [0, 0.25] m");
    } else if (s.node("radius") || s.node("cant")) {
      const toml::node* n = s.node("radius") ? s.node("radius") : s.node("cant");
      fail(file, n->source(), s.dotted(s.node("radius") ? "radius" : "cant"),
           fmt::format("only a circular section has a radius and cant ({} sections take them from their neighbours)",
                       r.kind));
    }
    raw.push_back(r);
  }
  scene.route = resolve_transitions(file, raw, sections.source());

  Section irr(file, "route.irregularity", table_at(file, *route, "irregularity", "route.irregularity"),
           {"amplitude", "wavelength_min", "wavelength_max", "components", "seed"});
  vehicle::Irregularity& g = scene.irregularity;
  g.amplitude = irr.number("amplitude", 0.0, [](double v) { return v >= 0.0 && v <= 0.02; }, "in [0, 0.02] m");
  g.wavelength_min = irr.number("wavelength_min", g.wavelength_min, positive, "> 0");
  g.wavelength_max = irr.number("wavelength_max", g.wavelength_max, positive, "> 0");
  if (g.wavelength_max < g.wavelength_min) {
    fail(file, irr.source(), "route.irregularity.wavelength_max", "must be >= wavelength_min");
  }
  g.components = irr.integer("components", g.components, 1, 1000);
  g.seed = static_cast<unsigned>(irr.integer("seed", static_cast<int>(g.seed), 0, 1'000'000'000));
}

}  // namespace

void check_wear_post_processor(const std::string& name) {
  if (name == "halfspace") return;  // the exact half-space model (simulate/halfspace_wheel_wear.hpp)
  try {
    parse_normal_model(name);
  } catch (const Error&) {
    throw Error(fmt::format("unknown wear post-processor '{}' (expected hertz, linder, "
                            "kik-piotrowski, stripes-a, stripes-ab, halfspace)",
                            name));
  }
}

double SimulationScene::route_length() const {
  double length = 0.0;
  for (const auto& s : route) length += s.length;
  return length;
}

SimulationScene parse_simulation_scene(std::string_view toml_text, const std::string& source_name,
                                       const std::filesystem::path& base_dir) {
  const toml::table root = scene_toml::parse(toml_text, source_name);
  for (auto&& [key, node] : root) {
    const std::string k(key.str());
    if (k != "simulation" && k != "vehicle" && k != "route") {
      fail(Context{source_name}, key.source(), k, "unknown section (known sections: simulation, vehicle, route)");
    }
  }

  const Context file{source_name};
  SimulationScene scene;
  const toml::table* sim = table_at(file, root, "simulation", "simulation");
  if (!sim) fail(file, {}, "simulation", "missing required section [simulation]");
  if (const toml::node* n = sim->get("models")) {
    fail(file, n->source(), "simulation.models",
         "replaced by dynamics_model (the contact model of the vehicle dynamics, default \"hertz\") and "
         "wear_post_processors (the contact models of the wear, e.g. [\"hertz\", \"stripes-a\"]): docs/simulation.md");
  }
  Section k(file, "simulation", sim,
         {"name", "description", "contact_scene", "dynamics_model", "wear_post_processors", "positions", "speed", "time_step", "initial_y",
          "wear_steps", "running_distance", "lubrication_factor", "profile_smoothing", "step_depth_limit",
          "halfspace_sample_every", "trajectory_interval"});
  scene.name = k.node("name") ? k.string(*k.node("name"), "name")
                              : std::filesystem::path(source_name).stem().string();
  // The name is the results' directory under --out: a separator or a dot name would write elsewhere.
  if (scene.name.empty() || scene.name == "." || scene.name == ".." ||
      scene.name.find_first_of("/\\") != std::string::npos) {
    fail(file, k.node("name") ? k.node("name")->source() : toml::source_region{}, "simulation.name",
         fmt::format("must be a plain directory name (results go to OUT/<name>/): no / or \\, not empty, . or .., "
                     "got \"{}\"",
                     scene.name));
  }
  if (k.node("description")) scene.description = k.string(*k.node("description"), "description");

  const toml::node& contact = k.required("contact_scene");
  scene.contact_scene = base_dir / k.string(contact, "contact_scene");
  if (!std::filesystem::is_regular_file(scene.contact_scene)) {
    fail(file, contact.source(), "simulation.contact_scene",
         fmt::format("no such file: {}", scene.contact_scene.string()));
  }
  if (const auto model = k.parse_string("dynamics_model", [](const std::string& m) { return parse_normal_model(m); })) {
    scene.dynamics_model = to_string(*model);
  }
  scene.wear_post_processors =
      k.strings("wear_post_processors", {}, [](const std::string& m) { check_wear_post_processor(m); });
  if (scene.wear_post_processors.empty()) k.required("wear_post_processors");
  scene.positions = k.strings("positions", {"leading"}, [](const std::string& p) {
    RAILTAB_CHECK(p == "leading" || p == "trailing", "expected \"leading\" or \"trailing\", got \"{}\"", p);
  });
  scene.speed = k.number("speed", 0.0, [](double v) { return v > 0.0 && v < 150.0; }, "in (0, 150) m/s", true);
  scene.time_step = k.number("time_step", scene.time_step, [](double v) { return v >= kMinTimeStep && v <= 0.01; },
                             "in [1e-6, 0.01] s");
  scene.initial_y = k.number("initial_y", 0.0, [](double v) { return std::abs(v) <= 0.02; }, "in [-0.02, 0.02] m");
  scene.wear_steps = k.integer("wear_steps", 1, 1, 100);
  scene.running_distance = k.number("running_distance", 0.0, [](double v) { return v > 0.0 && v <= kMaxRunningDistance; },
                                    "in (0, 1e9] m (1e6 km)", true);
  scene.lubrication_factor = k.number("lubrication_factor", 5.5, [](double v) { return v >= 1.0; }, ">= 1");
  scene.profile_smoothing = k.number("profile_smoothing", 0.0, non_negative, ">= 0 m");
  scene.step_depth_limit = k.number("step_depth_limit", 0.0, non_negative, ">= 0 m");
  scene.halfspace_sample_every = k.integer("halfspace_sample_every", 1, 1, 1000);
  scene.trajectory_interval = k.number("trajectory_interval", scene.trajectory_interval, positive, "> 0 m");

  parse_vehicle(file, root, scene.vehicle);
  parse_route(file, root, scene);
  // The RK4 steps of one run over the route: refused up front when a run could not end.
  const double steps = scene.route_length() / scene.speed / scene.time_step;
  if (!(steps <= kMaxDynamicsSteps)) {
    fail(file, k.node("time_step") ? k.node("time_step")->source() : k.source(), "simulation.time_step",
         fmt::format("{} s steps over the route ({} m at {} m/s) are {:.3g} RK4 steps per run, above the limit of "
                     "{:.0e}: raise time_step or shorten the route",
                     scene.time_step, scene.route_length(), scene.speed, steps, kMaxDynamicsSteps));
  }
  return scene;
}

SimulationScene load_simulation_scene(const std::filesystem::path& path) {
  SimulationScene scene =
      parse_simulation_scene(scene_toml::read_text(path, "simulation scene"), path.string(), path.parent_path());
  scene.path = path;
  return scene;
}

}  // namespace railtab
