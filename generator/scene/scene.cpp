// SPDX-License-Identifier: Apache-2.0
// Scene files: TOML (toml++) into a Scene. Every key is checked against the list of keys its
// section knows, so a typo is an error, never a silently ignored setting. Errors name the file,
// the line and the dotted key. File format: docs/scenes.md.
#include "scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <tuple>
#include <optional>
#include <set>
#include <sstream>

#include "core/check.hpp"
#include "scene/toml_section.hpp"

namespace railtab {
namespace {

constexpr std::size_t kMaxAxisPoints = 1'000'000;  // guards against a range with a tiny step
// The scene text is stored whole in the table (root attribute `scene`); the lookup refuses a string
// attribute over 1 MiB (lookup/src/hdf5_file.hpp), so a larger scene could never make a table.
constexpr std::size_t kMaxSceneTextBytes = 1'000'000;
constexpr std::size_t kMaxDescriptionBytes = 100'000;  // scene.description: a paragraph, not a file
// Adjacent grid nodes closer than this, relative to max(1, |node|), are refused: the lookup needs
// a finite reciprocal of every cell width, and nodes a few ulps apart cannot be interpolated
// between (y = [0, 5e-324, 1e-323] would make a table the lookup refuses).
constexpr double kMinRelativeSpacing = 1e-12;

using scene_toml::Context;
using scene_toml::fail;
using scene_toml::join;
using scene_toml::non_negative;
using scene_toml::positive;
using scene_toml::Section;
using scene_toml::section;
using scene_toml::type_name;

bool fraction(double v) { return v >= 0.0 && v < 0.5; }

// Plausibility bounds that catch a value typed in the wrong unit (scene values are SI): a gauge of
// 1435 (mm for m) puts every wheel off its rail and a table of failed points, a wheel load of 78.5
// (kN for N) or a Young's modulus of 210 (GPa for Pa) a table of meaningless patches, each without
// another error. The bounds lie far outside any real wheelset and far inside the unit mistake.
bool wheelset_size(double v) { return v > 0.0 && v <= 10.0; }          // gauge, back to back, radius [m]
bool measuring_depth(double v) { return v >= 0.0 && v <= 0.1; }        // [m]
bool within_a_metre(double v) { return std::abs(v) <= 1.0; }           // profile positions [m]
// Moduli and hardness [Pa]: steel is 210e9 and 2.75e9; the upper bound is 50 x diamond's modulus,
// far below where the models' forces and the table's float32 outputs overflow (1e300 did).
bool stiffness(double v) { return v >= 1e6 && v <= 1e13; }

// "1:40" -> 0.025; a number is the tangent itself.
double parse_inclination(const Section& s, const toml::node& n) {
  if (!n.is_string()) {
    double v = s.number(n, "rail_inclination");
    if (v < 0.0 || v > 0.2) fail(s.context(), n.source(), s.dotted("rail_inclination"), "must be a tangent in [0, 0.2]");
    return v;
  }
  std::string text = s.string(n, "rail_inclination");
  auto colon = text.find(':');
  double num = 0.0, den = 0.0;
  bool ok = colon != std::string::npos;
  if (ok) {
    std::istringstream a(text.substr(0, colon)), b(text.substr(colon + 1));
    ok = static_cast<bool>(a >> num) && static_cast<bool>(b >> den) && (a >> std::ws).eof() &&
         (b >> std::ws).eof();
  }
  if (!ok || !(den > 0.0) || num < 0.0 || !std::isfinite(num / den) || num / den > 0.2) {
    fail(s.context(), n.source(), s.dotted("rail_inclination"),
         fmt::format("expected a ratio like \"1:40\" or a tangent, got \"{}\"", text));
  }
  return num / den;
}

// One grid segment: a number, or a range table {start, stop, step} / {start, stop, count}.
void append_segment(const Section& s, const std::string& key, const toml::node& n,
                    std::vector<double>& out) {
  if (!n.is_table()) {
    out.push_back(s.number(n, key));
    return;
  }
  const toml::table& t = *n.as_table();
  for (auto&& [k, v] : t) {
    if (k == "max_step" || k == "min_step") {
      fail(s.context(), k.source(), s.dotted(key) + "." + std::string(k.str()),
           "an adaptive range {start, stop, max_step, min_step} must be the whole axis, not a list element");
    }
    if (k != "start" && k != "stop" && k != "step" && k != "count") {
      fail(s.context(), k.source(), s.dotted(key) + "." + std::string(k.str()),
           "unknown key in a range (known keys: start, stop, step, count)");
    }
  }
  auto get = [&](const char* name) -> double {
    const toml::node* v = t.get(name);
    if (!v) fail(s.context(), n.source(), s.dotted(key) + "." + name, "missing required key of a range");
    return s.number(*v, key + "." + name);
  };
  double start = get("start");
  double stop = get("stop");
  bool has_step = t.contains("step"), has_count = t.contains("count");
  if (has_step == has_count) {
    fail(s.context(), n.source(), s.dotted(key), "a range needs exactly one of step or count");
  }
  if (!(stop > start)) fail(s.context(), n.source(), s.dotted(key), "a range needs stop > start");
  std::size_t count = 0;
  if (has_step) {
    double step = get("step");
    if (!(step > 0.0)) fail(s.context(), t.get("step")->source(), s.dotted(key) + ".step", "must be > 0");
    double intervals = (stop - start) / step;
    if (intervals > static_cast<double>(kMaxAxisPoints)) {
      fail(s.context(), n.source(), s.dotted(key), "range has too many points");
    }
    count = static_cast<std::size_t>(std::floor(intervals + 1e-9)) + 1;
    // With start on the step's lattice the nodes are its points k * step, so that a range and its
    // mirror image (-stop to -start) give the same nodes negated, bit for bit (a mirror-symmetric
    // y grid lets the sweep fill y < 0 by the mirror, engine/mirror.hpp); start itself stays as
    // written.
    const double k0 = std::round(start / step);
    const bool lattice = std::abs(start / step - k0) < 1e-9;
    for (std::size_t i = 0; i < count; ++i) {
      const double di = static_cast<double>(i);
      out.push_back(i == 0 ? start : lattice ? (k0 + di) * step : start + di * step);
    }
    // Snap the end point so that {start, stop, step} with stop on the lattice ends exactly at stop.
    if (std::abs(out.back() - stop) < 1e-9 * step) out.back() = stop;
  } else {
    const toml::node* c = t.get("count");
    auto i = c->as_integer();
    if (!i || i->get() < 2 || i->get() > static_cast<std::int64_t>(kMaxAxisPoints)) {
      fail(s.context(), c->source(), s.dotted(key) + ".count", "must be an integer >= 2");
    }
    count = static_cast<std::size_t>(i->get());
    for (std::size_t j = 0; j < count; ++j) {
      // Endpoints exact; interior points by linear interpolation.
      double f = static_cast<double>(j) / static_cast<double>(count - 1);
      out.push_back(j + 1 == count ? stop : start + f * (stop - start));
    }
  }
}

// A grid axis: number, list of numbers and/or ranges (concatenated, shared end points merged), or
// one range table. The result is strictly increasing.
std::vector<double> parse_axis(const Section& s, const std::string& key, const toml::node& n) {
  std::vector<double> values;
  if (auto arr = n.as_array()) {
    if (arr->empty()) fail(s.context(), n.source(), s.dotted(key), "empty grid");
    for (const toml::node& el : *arr) {
      std::size_t before = values.size();
      append_segment(s, key, el, values);
      // A range that starts where the previous segment ended shares that point.
      if (before > 0 && el.is_table() && values[before] == values[before - 1]) {
        values.erase(values.begin() + static_cast<std::ptrdiff_t>(before));
      }
    }
  } else if (n.is_table() || n.is_number()) {
    append_segment(s, key, n, values);
  } else {
    fail(s.context(), n.source(), s.dotted(key),
         fmt::format("expected a number, a list or a range table, got {}", type_name(n)));
  }
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (!(values[i] > values[i - 1])) {
      fail(s.context(), n.source(), s.dotted(key),
           fmt::format("grid is not strictly increasing ({} after {})", values[i], values[i - 1]));
    }
    const double scale = std::max({1.0, std::abs(values[i]), std::abs(values[i - 1])});
    if (!(values[i] - values[i - 1] >= kMinRelativeSpacing * scale)) {
      fail(s.context(), n.source(), s.dotted(key),
           fmt::format("grid nodes {:g} and {:g} are too close (adjacent nodes must differ by at least {:g} x "
                       "max(1, |node|)): the lookup cannot interpolate between them",
                       values[i - 1], values[i], kMinRelativeSpacing));
    }
  }
  if (values.size() > kMaxAxisPoints) fail(s.context(), n.source(), s.dotted(key), "grid too large");
  return values;
}

bool is_adaptive_range(const toml::node& n) {
  const toml::table* t = n.as_table();
  return t && (t->contains("max_step") || t->contains("min_step"));
}

// An adaptive axis {start, stop, max_step, min_step} ([accuracy] scenes). Returns the spec; the
// starting grid (uniform, step <= max_step) goes into `values`.
AdaptiveAxisSpec parse_adaptive_axis(const Section& s, const std::string& key, const toml::node& n,
                                     bool accuracy_enabled, std::vector<double>& values) {
  const toml::table& t = *n.as_table();
  for (auto&& [k, v] : t) {
    if (k != "start" && k != "stop" && k != "max_step" && k != "min_step") {
      fail(s.context(), k.source(), s.dotted(key) + "." + std::string(k.str()),
           "unknown key in an adaptive range (known keys: start, stop, max_step, min_step)");
    }
  }
  if (!accuracy_enabled) {
    fail(s.context(), n.source(), s.dotted(key),
         "an adaptive range {start, stop, max_step, min_step} needs an [accuracy] section");
  }
  auto get = [&](const char* name) -> double {
    const toml::node* v = t.get(name);
    if (!v) fail(s.context(), n.source(), s.dotted(key) + "." + name, "missing required key of an adaptive range");
    return s.number(*v, key + "." + name);
  };
  AdaptiveAxisSpec a{key, get("start"), get("stop"), get("max_step"), get("min_step")};
  if (!(a.stop > a.start)) fail(s.context(), n.source(), s.dotted(key), "an adaptive range needs stop > start");
  if (!(a.min_step > 0.0)) fail(s.context(), t.get("min_step")->source(), s.dotted(key) + ".min_step", "must be > 0");
  if (!(a.max_step >= a.min_step)) {
    fail(s.context(), t.get("max_step")->source(), s.dotted(key) + ".max_step",
         fmt::format("must be >= min_step ({})", a.min_step));
  }
  if ((a.stop - a.start) / a.min_step > static_cast<double>(kMaxAxisPoints)) {
    fail(s.context(), t.get("min_step")->source(), s.dotted(key) + ".min_step", "too small: range has too many points");
  }
  auto intervals = static_cast<std::size_t>(std::ceil((a.stop - a.start) / a.max_step - 1e-9));
  intervals = std::max<std::size_t>(intervals, 1);
  values.clear();
  for (std::size_t i = 0; i <= intervals; ++i) {
    double f = static_cast<double>(i) / static_cast<double>(intervals);
    values.push_back(i == intervals ? a.stop : a.start + f * (a.stop - a.start));
  }
  return a;
}

// [accuracy] models = ["hertz", "kik-piotrowski", ...]: the normal models the generator may use per y
// region, cheapest first. The reference ([contact] normal_model) is the most accurate by definition,
// so it may only come last; it is appended when not listed.
std::vector<NormalModel> parse_model_choice(const Section& s, const toml::node& n, NormalModel reference) {
  const toml::array* list = n.as_array();
  if (!list || list->empty()) {
    fail(s.context(), n.source(), s.dotted("models"),
         fmt::format("expected a non-empty list of normal model names, cheapest first, got {}",
                     list ? "an empty list" : type_name(n)));
  }
  std::vector<NormalModel> models;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::node& el = *list->get(i);
    const std::string key = fmt::format("models[{}]", i);
    if (!el.is_string()) fail(s.context(), el.source(), s.dotted(key), fmt::format("expected a string, got {}", type_name(el)));
    NormalModel m{};
    try {
      m = parse_normal_model(el.as_string()->get());
    } catch (const Error& e) {
      fail(s.context(), el.source(), s.dotted(key), e.what());
    }
    if (std::find(models.begin(), models.end(), m) != models.end()) {
      fail(s.context(), el.source(), s.dotted(key), fmt::format("'{}' is listed twice", to_string(m)));
    }
    if (m == reference && i + 1 != list->size()) {
      fail(s.context(), el.source(), s.dotted(key),
           fmt::format("'{}' is the reference ([contact] normal_model): it may only be the last (most expensive) "
                       "entry",
                       to_string(m)));
    }
    models.push_back(m);
  }
  if (models.back() != reference) models.push_back(reference);
  return models;
}

// "auto" | "no" | "yes" (MiniProf axis orientation, docs/profiles.md).
AxisMirror parse_axis_mirror(const std::string& text) {
  if (text == "auto") return AxisMirror::automatic;
  if (text == "no") return AxisMirror::no;
  if (text == "yes") return AxisMirror::yes;
  throw Error(fmt::format("'{}' is not one of auto, no, yes", text));
}

ProfileSource parse_profile(const Section& s, const std::string& key, const std::filesystem::path& base_dir,
                            double smoothing) {
  const toml::node& n = s.required(key);
  ProfileSource p;
  p.name = s.string(n, key);
  p.smoothing_length = smoothing;
  if (p.name.empty()) fail(s.context(), n.source(), s.dotted(key), "empty profile name");
  bool builtin = (key == "wheel" && p.name == "s1002") || (key == "rail" && p.name == "uic60");
  if (!builtin) {
    std::filesystem::path file(p.name);
    p.file = file.is_absolute() ? file : base_dir / file;
    if (!std::filesystem::exists(p.file)) {
      fail(s.context(), n.source(), s.dotted(key),
           fmt::format("not a built-in {} profile ({}) and no such file: {}", key,
                       key == "wheel" ? "s1002" : "uic60", p.file.string()));
    }
  }
  return p;
}

// What a section's parser reads besides its own section.
struct SceneInput {
  const toml::table& root;
  const std::filesystem::path& base_dir;  // profile files are relative to the scene file
};

void parse_scene_section(const Section& sc, const SceneInput&, Scene& scene) {
  const Context& ctx = sc.context();
  scene.name = sc.string(sc.required("name"), "name");
  if (scene.name.empty()) fail(ctx, sc.required("name").source(), "scene.name", "must not be empty");
  scene.description = sc.string("description").value_or("");
  if (scene.description.size() > kMaxDescriptionBytes) {
    fail(ctx, sc.required("description").source(), "scene.description",
         fmt::format("{} bytes, above the limit of {}", scene.description.size(), kMaxDescriptionBytes));
  }
}

void parse_profiles(const Section& pr, const SceneInput& in, Scene& scene) {
  double smoothing = pr.number("smoothing", 0.0, non_negative, ">= 0 [m]");
  scene.wheel = parse_profile(pr, "wheel", in.base_dir, smoothing);
  scene.rail = parse_profile(pr, "rail", in.base_dir, smoothing);
  scene.wheel.mirror_y = pr.parse_string("wheel_mirror_y", parse_axis_mirror).value_or(AxisMirror::automatic);
  scene.wheel.mirror_z = pr.parse_string("wheel_mirror_z", parse_axis_mirror).value_or(AxisMirror::automatic);
  scene.rail.mirror_y = pr.parse_string("rail_mirror_y", parse_axis_mirror).value_or(AxisMirror::automatic);
  scene.rail.mirror_z = pr.parse_string("rail_mirror_z", parse_axis_mirror).value_or(AxisMirror::automatic);
  scene.wheel.lateral_shift = pr.number("wheel_shift_y", 0.0);
  if (scene.wheel.lateral_shift != 0.0 && scene.wheel.file.empty()) {
    fail(pr.context(), pr.node("wheel_shift_y")->source(), "profiles.wheel_shift_y",
         "applies to wheel profile files only (the built-in s1002 has its origin on the running circle)");
  }
}

void parse_track(const Section& tr, const SceneInput&, Scene& scene) {
  scene.track.gauge = tr.number("gauge", scene.track.gauge, wheelset_size, "in (0, 10] m (SI: standard gauge is 1.435)");
  scene.track.gauge_measuring_depth =
      tr.number("gauge_measuring_depth", scene.track.gauge_measuring_depth, measuring_depth,
                "in [0, 0.1] m (SI: 14 mm is 0.014)");
  if (const toml::node* n = tr.node("rail_inclination")) scene.track.rail_inclination = parse_inclination(tr, *n);
}

void parse_wheelset(const Section& ws, const SceneInput&, Scene& scene) {
  scene.wheelset.back_to_back = ws.number("back_to_back", scene.wheelset.back_to_back, wheelset_size,
                                           "in (0, 10] m (SI: 1360 mm is 1.360)");
  scene.wheelset.flange_back_position =
      ws.number("flange_back_position", scene.wheelset.flange_back_position, within_a_metre,
                "in [-1, 1] m (SI: -70 mm is -0.070)");
  scene.wheelset.nominal_radius =
      ws.number("nominal_radius", scene.wheelset.nominal_radius, wheelset_size,
                "in (0, 10] m (SI: 460 mm is 0.460)");
}

void parse_geometry(const Section& ge, const SceneInput&, Scene& scene) {
  GeometrySettings& g = scene.geometry;
  g.search_step = ge.number("search_step", g.search_step, positive, "> 0 [m]");
  g.max_separation = ge.number("max_separation", g.max_separation, non_negative, ">= 0 [m]");
  g.band_step = ge.number("band_step", g.band_step, positive, "> 0 [m]");
  g.band_half_width = ge.number("band_half_width", g.band_half_width, positive, "> 0 [m]");
  g.band_max_gap = ge.number("band_max_gap", g.band_max_gap, positive, "> 0 [m]");
  g.flange_angle = ge.number("flange_angle", g.flange_angle, positive, "> 0 [rad]");
  g.near_equal_shift = ge.number("near_equal_shift", g.near_equal_shift, non_negative, ">= 0 [m]");
  g.near_equal_distance = ge.number("near_equal_distance", g.near_equal_distance, non_negative, ">= 0 [m]");
}

void parse_material(const Section& ma, const SceneInput&, Scene& scene) {
  scene.material.youngs_modulus = ma.number("youngs_modulus", scene.material.youngs_modulus, stiffness,
                                                 "in [1e6, 1e13] Pa (SI: 210 GPa is 210e9)");
  scene.material.poisson_ratio = ma.number("poisson_ratio", scene.material.poisson_ratio, fraction, "in [0, 0.5)");
}

void parse_contact(const Section& co, const SceneInput&, Scene& scene) {
  NormalOptions& no = scene.normal;
  if (auto m = co.parse_string("normal_model", parse_normal_model)) no.model = *m;
  if (auto m = co.parse_string("negative_curvature", parse_negative_curvature)) no.negative_curvature = *m;
  no.strips = co.integer("strips", no.strips, 1);
  no.virtual_penetration = co.number("virtual_penetration", no.virtual_penetration, positive, "> 0");
  no.tolerance = co.number("tolerance", no.tolerance, positive, "> 0");
  no.max_iterations = co.integer("max_iterations", no.max_iterations, 1);
  TangentialSettings& ts = scene.tangential;
  ts.friction = co.number("friction", ts.friction, non_negative, ">= 0");
  ts.elements_per_strip = co.integer("elements_per_strip", ts.elements_per_strip, 1);
  ts.spin_per_strip = co.boolean("spin_per_strip", ts.spin_per_strip);
  ts.speed = co.number("speed", ts.speed, positive, "> 0 [m/s]");
  ts.load_coupling = co.boolean("load_coupling", ts.load_coupling);
  // Half-space elements: below 0.05 mm the grids of a flange contact reach millions of elements.
  scene.halfspace.element_size =
      co.number("element_size", scene.halfspace.element_size,
                [](double v) { return v >= 0.05e-3 && v <= 5e-3; }, "in [0.05e-3, 5e-3] [m]");
}

void parse_wear(const Section& we, const SceneInput&, Scene& scene) {
  scene.wear.hardness = we.number("hardness", scene.wear.hardness, stiffness, "in [1e6, 1e13] Pa (SI: 2.75 GPa is 2.75e9)");
  scene.wear.lubrication_factor = we.number("lubrication_factor", scene.wear.lubrication_factor, positive, "> 0");
}

void parse_accuracy(const Section& ac, const SceneInput& in, Scene& scene) {
  const Context& ctx = ac.context();
  AccuracyTargets& acc = scene.accuracy;
  acc.enabled = ac.present();
  acc.creep_force = ac.number("creep_force", 0.0, positive, "> 0 (relative to mu N)");
  acc.contact_angle = ac.number("contact_angle", 0.0, positive, "> 0 [rad]");
  acc.rolling_radius = ac.number("rolling_radius", 0.0, positive, "> 0 [m]");
  acc.normal_force = ac.number("normal_force", 0.0, positive, "> 0 (relative to N)");
  if (acc.enabled && acc.creep_force == 0.0 && acc.contact_angle == 0.0 && acc.rolling_radius == 0.0 &&
      acc.normal_force == 0.0) {
    fail(ctx, in.root.get("accuracy")->source(), "accuracy",
         "needs at least one target (creep_force, contact_angle, rolling_radius, normal_force)");
  }

  if (const toml::node* n = ac.node("models")) acc.models = parse_model_choice(ac, *n, scene.normal.model);
  acc.model_tolerance = ac.number("model_tolerance", 1.0, positive, "> 0 (a multiple of the targets)");
  if (ac.has("model_tolerance") && acc.models.empty()) {
    fail(ctx, ac.node("model_tolerance")->source(), "accuracy.model_tolerance", "needs accuracy.models");
  }
}

// A grid axis, or an adaptive one ([accuracy] scenes) recorded in scene.accuracy.axes.
std::vector<double> grid_axis(const Section& gr, const std::string& key, const toml::node& n, Scene& scene) {
  AccuracyTargets& acc = scene.accuracy;
  if (!is_adaptive_range(n)) return parse_axis(gr, key, n);
  std::vector<double> values;
  acc.axes.push_back(parse_adaptive_axis(gr, key, n, acc.enabled, values));
  return values;
}

// grid.creep_coordinates, grid.creep_knee and grid.creep_law_spin.
void parse_creep_coordinates(const Section& gr, Scene& scene) {
  const Context& ctx = gr.context();
  if (const auto coordinates = gr.string("creep_coordinates")) {
    if (*coordinates != "physical" && *coordinates != "normalised")
      fail(ctx, gr.node("creep_coordinates")->source(), "grid.creep_coordinates",
           "'" + *coordinates + "' is neither \"physical\" nor \"normalised\"");
    scene.creep_normalised = *coordinates == "normalised";
  }
  if (const toml::node* n = gr.node("creep_knee")) {
    // [k_xi, k_eta, k_phi] > 0: the knees of the normalised node maps (scene.hpp, creep_map.hpp).
    const toml::array* a = n->as_array();
    if (!scene.creep_normalised)
      fail(ctx, n->source(), "grid.creep_knee", "needs creep_coordinates = \"normalised\"");
    if (!a || a->size() != 3)
      fail(ctx, n->source(), "grid.creep_knee", "must be an array of three numbers [xi, eta, phi]");
    for (std::size_t i = 0; i < 3; ++i) {
      const std::optional<double> v = (*a)[i].value<double>();
      if (!v || !(*v > 0.0) || !(*v < 1e6))
        fail(ctx, n->source(), "grid.creep_knee", "every knee must be a number > 0 (and < 1e6)");
      scene.creep_knee[i] = *v;
    }
  }
  if (const toml::node* n = gr.node("creep_law_spin")) {
    // >= 0: the spin weight of the saturation law (scene.hpp, creep_map.hpp).
    if (!scene.creep_normalised)
      fail(ctx, n->source(), "grid.creep_law_spin", "needs creep_coordinates = \"normalised\"");
    const std::optional<double> v = n->value<double>();
    if (!v || !(*v >= 0.0) || !(*v < 1e6))
      fail(ctx, n->source(), "grid.creep_law_spin", "must be a number >= 0 (and < 1e6)");
    scene.creep_law_spin = *v;
  }
}

// grid.xi, grid.eta, grid.phi: one node 0 when absent, each within physical creepage.
void parse_creep_axes(const Section& gr, Scene& scene) {
  SceneGrids& grids = scene.grids;
  auto optional_axis = [&](const char* key) -> std::vector<double> {
    const toml::node* n = gr.node(key);
    return n ? grid_axis(gr, key, *n, scene) : std::vector<double>{0.0};
  };
  grids.xi = optional_axis("xi");
  grids.eta = optional_axis("eta");
  grids.phi = optional_axis("phi");
  for (const auto& [key, axis, limit] : {std::tuple{"xi", &grids.xi, kMaxCreepage},
                                         std::tuple{"eta", &grids.eta, kMaxCreepage},
                                         std::tuple{"phi", &grids.phi, kMaxSpinCreepage}}) {
    for (double v : *axis) {
      if (!(std::abs(v) <= limit)) {
        fail(gr.context(), gr.node(key)->source(), std::string("grid.") + key,
             fmt::format("creepage {} is far beyond physical (|{}| <= {} {}; docs/reliability.md)", v, key, limit,
                         key == std::string("phi") ? "1/m" : ""));
      }
    }
  }
}

void parse_grid(const Section& gr, const SceneInput& in, Scene& scene) {
  const Context& ctx = gr.context();
  SceneGrids& grids = scene.grids;
  const AccuracyTargets& acc = scene.accuracy;
  grids.y = grid_axis(gr, "y", gr.required("y"), scene);
  grids.load = grid_axis(gr, "load", gr.required("load"), scene);
  for (double load : grids.load) {
    if (!(load > 0.0)) fail(ctx, gr.node("load")->source(), "grid.load", "loads must be > 0 [N]");
    if (load < kMinWheelLoad) {
      fail(ctx, gr.node("load")->source(), "grid.load",
           fmt::format("a wheel load of {} N is below {} N: loads are in N (SI: 78.5 kN is 78.5e3)", load,
                       kMinWheelLoad));
    }
  }
  for (double y : grids.y) {
    if (!(std::abs(y) <= kMaxLateralShift)) {
      fail(ctx, gr.node("y")->source(), "grid.y",
           fmt::format("|y| = {} m is beyond {} m, off any rail head: y is in m (SI: 10 mm is 0.010)", std::abs(y),
                       kMaxLateralShift));
    }
  }
  scene.equilibrium_roll = gr.boolean("equilibrium_roll", false);
  parse_creep_coordinates(gr, scene);
  if (const toml::node* n = gr.node("roll")) {
    if (scene.equilibrium_roll) {
      fail(ctx, n->source(), "grid.roll", "cannot be given together with equilibrium_roll = true");
    }
    if (is_adaptive_range(*n)) fail(ctx, n->source(), "grid.roll", "roll cannot be adaptive (use a list or equilibrium_roll)");
    grids.roll = parse_axis(gr, "roll", *n);
  } else {
    grids.roll = {0.0};
  }
  if (const toml::node* n = gr.node("yaw")) {
    if (is_adaptive_range(*n)) fail(ctx, n->source(), "grid.yaw", "yaw cannot be adaptive (use a number or a list)");
    // The adaptive grids, contact probe and model choice place y at zero yaw.
    if (acc.enabled) fail(ctx, n->source(), "grid.yaw", "cannot be combined with an [accuracy] section");
    grids.yaw = parse_axis(gr, "yaw", *n);
    for (double v : grids.yaw) {
      if (!(std::abs(v) <= kMaxYaw)) {
        fail(ctx, n->source(), "grid.yaw",
             fmt::format("|yaw| = {} rad is beyond {} rad: yaw is in rad (SI: 10 mrad is 0.010)", std::abs(v), kMaxYaw));
      }
    }
    // Every output of one wheel at given creepages is even in yaw with the FASTSIM-based models
    // (docs/validation/yaw-tables.md), so a list symmetric about 0 that holds 0 is tabulated over
    // its non-negative half and the lookup reads |yaw|. Not for the exact model: its fx at -yaw and
    // +yaw differ (up to 1.3 % of mu N at 10 mrad, YawTable.ExactModelThroughTheTable).
    const std::vector<double>& g = grids.yaw;
    bool symmetric = g.size() >= 3 && scene.normal.model != NormalModel::halfspace;
    for (std::size_t i = 0; symmetric && i < g.size(); ++i) symmetric = g[i] == -g[g.size() - 1 - i];
    if (symmetric && std::find(g.begin(), g.end(), 0.0) != g.end()) {
      grids.yaw.erase(grids.yaw.begin(), grids.yaw.begin() + static_cast<std::ptrdiff_t>(g.size() / 2));
      grids.yaw_even = true;
    }
  }
  parse_creep_axes(gr, scene);
  if (scene.creep_normalised && acc.enabled) {
    // Adaptive grids compare interpolated and direct creep forces on physical creepage nodes.
    fail(ctx, gr.node("creep_coordinates")->source(), "grid.creep_coordinates",
         "\"normalised\" cannot be combined with an [accuracy] section (adaptive grids are physical)");
  }
  if (acc.enabled && acc.axes.empty()) {
    fail(ctx, in.root.get("accuracy")->source(), "accuracy",
         "no grid axis is adaptive: give at least one as {start, stop, max_step, min_step}");
  }
}

// One section of a scene file: its name, its allowed keys and its parser.
struct SceneSection {
  const char* name;
  std::vector<std::string> keys;
  void (*parse)(const Section&, const SceneInput&, Scene&);
};

// The sections in the order they are parsed: contact before accuracy (the model choice starts from
// the normal model), accuracy before grid (adaptive axes need [accuracy]).
const std::vector<SceneSection>& scene_sections() {
  static const std::vector<SceneSection> sections{
      {"scene", {"name", "description"}, parse_scene_section},
      {"profiles",
       {"wheel", "rail", "smoothing", "wheel_mirror_y", "wheel_mirror_z", "rail_mirror_y", "rail_mirror_z",
        "wheel_shift_y"},
       parse_profiles},
      {"track", {"gauge", "gauge_measuring_depth", "rail_inclination"}, parse_track},
      {"wheelset", {"back_to_back", "flange_back_position", "nominal_radius"}, parse_wheelset},
      {"geometry",
       {"search_step", "max_separation", "band_step", "band_half_width", "band_max_gap", "flange_angle",
        "near_equal_shift", "near_equal_distance"},
       parse_geometry},
      {"material", {"youngs_modulus", "poisson_ratio"}, parse_material},
      {"contact",
       {"normal_model", "negative_curvature", "strips", "virtual_penetration", "tolerance", "max_iterations",
        "friction", "elements_per_strip", "spin_per_strip", "speed", "load_coupling", "element_size"},
       parse_contact},
      {"wear", {"hardness", "lubrication_factor"}, parse_wear},
      {"accuracy",
       {"creep_force", "contact_angle", "rolling_radius", "normal_force", "models", "model_tolerance"},
       parse_accuracy},
      {"grid",
       {"y", "roll", "yaw", "load", "xi", "eta", "phi", "equilibrium_roll", "creep_coordinates", "creep_knee",
        "creep_law_spin"},
       parse_grid},
  };
  return sections;
}

}  // namespace

Scene parse_scene(std::string_view toml_text, const std::string& source_name,
                  const std::filesystem::path& base_dir) {
  Context ctx{source_name};
  const toml::table root = scene_toml::parse(toml_text, source_name);

  // The known sections as an unknown one's error lists them (grid before accuracy, as the docs do).
  static const std::vector<std::string> kSections{"scene", "profiles", "track", "wheelset", "geometry",
                                                  "material", "contact", "wear", "grid",
                                                  "accuracy"};
  for (auto&& [key, node] : root) {
    if (std::find(kSections.begin(), kSections.end(), key.str()) == kSections.end()) {
      fail(ctx, key.source(), std::string(key.str()),
           fmt::format("unknown section or key (known sections: {})", join(kSections)));
    }
  }

  Scene scene;
  RAILTAB_CHECK(toml_text.size() <= kMaxSceneTextBytes,
                "{}: the scene is {} bytes, above the limit of {} (a table stores its scene text, and the lookup "
                "refuses a text attribute over 1 MiB)",
                source_name, toml_text.size(), kMaxSceneTextBytes);
  scene.text = std::string(toml_text);
  const SceneInput in{root, base_dir};
  for (const SceneSection& s : scene_sections()) s.parse(section(ctx, root, s.name, s.keys), in, scene);
  return scene;
}

void check_creepage_magnitude(const std::string& what, double xi, double eta, double phi) {
  RAILTAB_CHECK(std::abs(xi) <= kMaxCreepage && std::abs(eta) <= kMaxCreepage && std::abs(phi) <= kMaxSpinCreepage,
                "{}: creepage ({}, {}, {}) is far beyond physical (|xi|, |eta| <= {}; |phi| <= {} 1/m)", what, xi, eta,
                phi, kMaxCreepage, kMaxSpinCreepage);
}

Scene load_scene(const std::filesystem::path& path) {
  Scene scene = parse_scene(scene_toml::read_text(path, "scene file"), path.string(), path.parent_path());
  scene.path = path;
  return scene;
}

}  // namespace railtab
