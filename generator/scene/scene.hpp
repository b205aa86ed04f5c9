// SPDX-License-Identifier: Apache-2.0
// A scene: everything a contact table needs (profiles, track, wheelset, material, models, grids),
// read from a TOML file in tables/. The file format is documented in docs/scenes.md.
#pragma once

#include <array>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/material.hpp"
#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"
#include "profile/formats/profile_io.hpp"
#include "tangential/coupled_load.hpp"
#include "tangential/fastsim_contact.hpp"
#include "wear/archard.hpp"

namespace railtab {

struct ProfileSource {
  std::string name;        // built-in name ("s1002", "uic60") or a file path as written in the scene
  std::filesystem::path file;  // resolved file path (relative to the scene file); empty for built-ins
  double smoothing_length = 0.0;  // smoothing of measured profiles, 0 = interpolate [m]
  AxisMirror mirror_y = AxisMirror::automatic;  // MiniProf lateral axis (profile/formats/profile_io.hpp)
  AxisMirror mirror_z = AxisMirror::automatic;  // MiniProf vertical axis
  double lateral_shift = 0.0;     // added to the file's lateral coordinate (wheel_shift_y) [m]
};

struct TangentialSettings {
  double friction = 0.3;          // Coulomb coefficient mu [-]
  int elements_per_strip = 20;    // FASTSIM cells along each strip [-]
  bool spin_per_strip = false;    // spin follows the local contact angle (STRIPES) [-]
  double speed = 20.0;            // rolling speed, for slip velocities and wear [m/s]
  bool load_coupling = true;      // the creep forces' vertical share in the load balance (the
                                  //   load coupling, tangential/coupled_load.hpp); false: normal
                                  //   from the load alone
};

// The exact half-space model (normal_model = "halfspace", src/halfspace/wheel_rail.hpp).
struct HalfspaceSettings {
  double element_size = 0.3e-3;   // square elements of the potential contact area [m]
};

struct WearSettings {
  double hardness = 2.75e9;       // H of the wheel material [Pa]
  double lubrication_factor = 5.5;  // k_dry is divided by this (5.5 natural, 11 lubricated) [-]
};

// The grids of a table. An axis with one value is not tabulated (fixed); the table records it.
struct SceneGrids {
  std::vector<double> y;     // wheelset lateral displacement [m]
  std::vector<double> roll;  // roll angle [rad]
  std::vector<double> yaw;   // yaw angle (angle of attack) [rad]; empty: the scene has no yaw key
                             //   (the yaw-free table, format 2.3); one value: fixed; more: an axis
  bool yaw_even = false;     // the scene's yaw list was symmetric about 0 and held 0: `yaw` keeps its
                             //   non-negative half and the table records yaw_symmetry = "even"
  std::vector<double> load;  // vertical wheel load [N]
  std::vector<double> xi;    // longitudinal creepage [-]
  std::vector<double> eta;   // lateral creepage [-]
  std::vector<double> phi;   // spin creepage [rad/m]
};

// An axis whose nodes the generator places from accuracy targets (docs/adaptive-grids.md): in the
// scene `[grid] y = {start, stop, max_step, min_step}`, allowed only with an [accuracy] section.
struct AdaptiveAxisSpec {
  std::string axis;        // "y", "load", "xi", "eta" or "phi"
  double start = 0.0;      // first node [axis units]
  double stop = 0.0;       // last node [axis units]
  double max_step = 0.0;   // largest node spacing; the starting grid is uniform at <= max_step [axis units]
  double min_step = 0.0;   // smallest node spacing; contact jumps are refined to it [axis units]
};

// The [accuracy] section: interpolation error targets at the midpoints between grid nodes. A
// target of 0 is not checked.
struct AccuracyTargets {
  bool enabled = false;          // the scene has an [accuracy] section
  double creep_force = 0.0;      // |(fx, fy) error| relative to mu * N of the patch [-]
  double contact_angle = 0.0;    // absolute [rad]
  double rolling_radius = 0.0;   // absolute [m]
  double normal_force = 0.0;     // relative to N of the patch [-]
  std::vector<AdaptiveAxisSpec> axes;  // adaptive axes in state-axis order (y, load, xi, eta, phi)
  // Per-region model choice (docs/adaptive-grids.md): the normal models the generator may use,
  // cheapest first, always ending with the reference [contact] normal_model; empty = the reference
  // everywhere (no `models` key).
  std::vector<NormalModel> models;
  double model_tolerance = 1.0;  // the model choice accepts deviations from the reference up to this
                                 //   multiple of each target [-]
  // The choice per node of grids.y: index into `models`, filled by build_adaptive_grids; empty =
  // the reference everywhere.
  std::vector<std::size_t> model_by_y;
};

struct Scene {
  std::string name;             // [scene] name
  std::string description;      // [scene] description
  std::string text;             // the full TOML text, stored in every table
  std::filesystem::path path;   // where it was read from (empty when parsed from a string)
  ProfileSource wheel;
  ProfileSource rail;
  TrackGeometry track;
  WheelsetGeometry wheelset;
  GeometrySettings geometry;
  Material material;
  NormalOptions normal;
  TangentialSettings tangential;
  HalfspaceSettings halfspace;
  WearSettings wear;
  bool equilibrium_roll = false;  // roll follows the kinematic equilibrium instead of the roll grid
  // [grid] creep_coordinates = "normalised": the creep and wear parts are tabulated over
  // normalised creepage coordinates (format 2.1, kernel/creep_map.hpp); the creepage lists then
  // give the range (first and last value) and the node count. false = "physical" (the default).
  bool creep_normalised = false;
  // [grid] creep_knee = [k_xi, k_eta, k_phi] (normalised coordinates only, default 1): the knee of
  // each axis's node map m(x) = x / (k + |x|), x the normalised creepage (creep_map.hpp); a larger
  // k spreads the nodes more evenly over the range (an axis that does not saturate inside it).
  std::array<double, 3> creep_knee = {1.0, 1.0, 1.0};
  // [grid] creep_law_spin (normalised coordinates only, default 0): the spin weight of the
  // saturation law subtracted from the stored forces (creep_map.hpp, law).
  double creep_law_spin = 0.0;
  SceneGrids grids;              // adaptive axes hold their starting grid until build_adaptive_grids
  AccuracyTargets accuracy;      // [accuracy]; enabled = false without the section
};

// The yaw of a scene whose yaw is not an axis: its one value, 0 for a scene without the key (the
// contact probe, the contact jumps and the error map solve at it).
inline double fixed_yaw(const Scene& scene) { return scene.grids.yaw.size() == 1 ? scene.grids.yaw.front() : 0.0; }

// Parse a scene file. Unknown keys, missing required keys, wrong types, empty or non-monotonic
// grids throw railtab::Error naming the file, the key and (where known) the line.
Scene load_scene(const std::filesystem::path& path);
Scene parse_scene(std::string_view toml_text, const std::string& source_name,
                  const std::filesystem::path& base_dir = {});

// Creepages far beyond anything physical are refused (scene grids, eval): a locked wheel slides at
// |xi| = 1, and a spin of 1000 1/m would need a 1 mm rolling radius. Beyond ~1e154 the models'
// squares overflow to inf and NaN (docs/reliability.md).
inline constexpr double kMaxCreepage = 10.0;        // |xi|, |eta| [-]
inline constexpr double kMaxSpinCreepage = 1000.0;  // |phi| [1/m]

// A vertical wheel load below this is a load typed in kN (scene grids, eval --load): railtab's
// profiles are full-size railway profiles, whose wheel loads are tens of kN [N].
inline constexpr double kMinWheelLoad = 1e3;
// A wheelset lateral displacement beyond this is off any rail head: a y typed in mm [m].
inline constexpr double kMaxLateralShift = 0.1;

// Throws railtab::Error naming `what` when |xi| or |eta| exceeds kMaxCreepage or |phi| exceeds
// kMaxSpinCreepage.
void check_creepage_magnitude(const std::string& what, double xi, double eta, double phi);

// Build the profiles and the geometry solver a scene describes.
ContactGeometrySolver make_geometry_solver(const Scene& scene);

// The tangential and wear model settings a scene describes (one mapping for eval and the sweep).
FastsimOptions fastsim_options(const Scene& scene);
CreepConditions creep_conditions(const Scene& scene);
CoupledLoadOptions coupled_load_options(const Scene& scene);
WearOptions wear_options(const Scene& scene);  // throws railtab::Error for an invalid wear map

}  // namespace railtab
