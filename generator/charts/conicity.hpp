// SPDX-License-Identifier: Apache-2.0
// railtab conicity: the wheelset's lateral functions (rolling radius difference, roll, contact angle
// difference) from a scene's rigid geometry or from a generated table, and from them the
// equivalent conicity against amplitude by EN 15302's reference principle and by its regression
// method, with the roll angle and contact angle parameters (geometry/equivalent_conicity.hpp;
// definitions in docs/conventions.md, validation in docs/validation/conicity.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "table/table.hpp"

namespace railtab {

// The functions of y behind the conicity, for one wheel-rail pair.
struct LateralFunctions {
  std::string name;                     // scene name (chart legend, CSV `pair` column)
  std::string title;                    // "name (description)" for the chart title
  std::string source;                   // "scene" (rigid geometry solved here) or "table" (read)
  std::string roll_mode;                // "equilibrium" or "fixed <value> rad"
  std::vector<double> y;                // wheelset lateral displacement, + left (n) [m]
  std::vector<double> roll;             // wheelset roll at each y (n) [rad]
  std::vector<double> delta_r;          // rolling radius difference r_left - r_right (n) [m]
  std::vector<double> delta_tan_gamma;  // tan g_left - tan g_right, side-frame contact angles (n) [-]
  std::vector<double> radius_left;      // rolling radius of the left wheel's primary contact (n) [m]
  std::vector<double> radius_right;     // ... right wheel (n) [m]
  std::vector<double> angle_left;       // contact angle of the left primary contact, side frame (n) [rad]
  std::vector<double> angle_right;      // ... right wheel, side frame (+ towards its flange) (n) [rad]
  double e0 = 0.0;                      // half the lateral distance of the two contacts at y = 0 [m]
  double r0 = 0.0;                      // mean rolling radius at y = 0 [m]
};

// The y sweep of the rigid geometry; the range must cover the turning points of the largest
// amplitude (the centre of an asymmetric pair lies off y = 0).
struct ConicitySweep {
  double y_max = 0.011;         // sweep from -y_max to +y_max [m]
  double y_step = 0.05e-3;      // [m]
  bool equilibrium_roll = true;  // false: roll 0 (Klingel's unrolled wheelset; the default keeps
                                 // both wheels on their rails, whatever the scene's own setting)
};

// The rigid wheelset of `scene` along y (make_geometry_solver).
LateralFunctions lateral_functions_from_scene(const Scene& scene, const ConicitySweep& sweep);

// The same for any solver; `name` and `title` label the pair.
LateralFunctions lateral_functions_from_solver(const ContactGeometrySolver& solver, const std::string& name,
                                               const std::string& title, const ConicitySweep& sweep);

// The geometry part of a table read from `path` (table/table_io.hpp), per wheel the primary
// contact (the geometry slot with the smaller separation). Roll: the table's equilibrium roll, its
// fixed roll, or the node roll = 0 of a roll axis (refused without one). e0 uses the scene's
// wheelset (back_to_back, flange_back_position) stored in the table.
LateralFunctions lateral_functions_from_table(const Table& table, const std::filesystem::path& path);

// The conicity at one amplitude.
struct ConicityPoint {
  double amplitude;                // half the peak-to-peak lateral motion [m]
  double conicity;                 // tan gamma_e, EN 15302 reference principle (wavelength) [-]
  double conicity_regression;      // tan gamma_e, linear regression of Delta r [-]
  double wavelength;               // of the kinematic oscillation, 2 pi sqrt(e0 r0 / conicity) [m]
  double y_min;                    // right turning point of the kinematic oscillation [m]
  double y_max;                    // left turning point [m]
  double roll_parameter;           // sigma: roll = sigma y / e0, regression over the same motion [-]
  double contact_angle_parameter;  // epsilon: Delta tan gamma = 2 epsilon y / e0, same regression [-]
};

struct ConicityCurve {
  LateralFunctions functions;
  double centre = 0.0;               // kinematic centre, Delta r rising through 0 [m]
  std::vector<ConicityPoint> points;  // one per amplitude, in the order given; NaN beyond the samples
};

// The amplitudes of the report when none are given: 1 to 10 mm in 1 mm steps [m].
std::vector<double> default_conicity_amplitudes();

// Throws railtab::Error naming the first amplitude that is not a positive finite lateral motion of
// at most kMaxLateralShift, or when there is none.
void check_conicity_amplitudes(const std::vector<double>& amplitudes);

// Throws railtab::Error for bad amplitudes (above) and when Delta r does not rise through zero (no
// kinematic oscillation).
ConicityCurve compute_conicity(LateralFunctions functions, const std::vector<double>& amplitudes);

}  // namespace railtab
