// SPDX-License-Identifier: Apache-2.0
// Speed against accuracy: for a fixed set of wheel-rail states of a scene, time per evaluation and
// error against a reference of every contact model setting (full chain: geometry -> normal ->
// FASTSIM -> Archard) and of table lookup at several grid resolutions (lookup query only: a
// lookup replaces the whole chain). The measurement only; speed_accuracy_chart.hpp writes the CSVs
// (speed_accuracy_csv.cpp) and draws the charts, `railtab chart` prints the summary. The states are
// read in speed_accuracy_states.cpp. Method: docs/speed-vs-accuracy.md.
//
// States: the right wheel of CONTACT's block C (../shared/reference/blockC_sweep_integer_dy.csv):
// dy = -6..10 mm (our y = -dy), no roll, Fz = 78.5 kN, mu of the row, creepages as CONTACT used
// them (xi = -cksi, eta = +ceta, phi = +cphi; docs/conventions.md). Without the reference file
// the same states with the target creepages, against the finest STRIPES A&B discretisation.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace railtab {

// One wheel-rail state and its reference values (forces on the wheel, contact frame).
struct SaState {
  double dy_mm = 0.0;        // CONTACT's lateral shift (dy > 0: right flange to the gauge corner)
  std::string creep_set;     // a_none, b_long0.001, c_lat0.001, d_spin0.052, e_combined
  double y = 0.0;            // our wheelset y = -dy [m]
  double load = 78.5e3;      // vertical wheel load [N]
  double friction = 0.3;     // mu [-]
  double xi = 0.0, eta = 0.0, phi = 0.0;  // creepages of the wheel relative to the rail [-, -, rad/m]
  bool creep = false;        // has creepage: the creep-force error applies (else normal quantities)
  bool flange = false;       // flange contact (dy >= 7 mm; CONTACT angle about -1.1 rad)
  bool normal_reliable = true;  // false for CONTACT's dy = 7 a_none outlier (README)
  // Reference values (CONTACT, or the fine STRIPES run in the fallback).
  double ref_fx = 0.0, ref_fy = 0.0;  // [N] on the wheel
  double ref_area = 0.0;              // [m2]
  double ref_pmax = 0.0;              // [Pa]
  double ref_angle = 0.0;             // contact angle, track frame [rad]
  double ref_fn = 0.0;                // normal force (sum over patches) [N]
};

// What one evaluation gives (summed over patches/slots: CONTACT has one patch per case).
struct SaOutcome {
  double fx = 0.0, fy = 0.0;  // [N] on the wheel, sum over loaded patches
  double area = 0.0;          // [m2] sum over patches
  double pmax = 0.0;          // [Pa] max over patches
  double angle = 0.0;         // contact angle of the patch with the largest normal force [rad]
  double fn = 0.0;            // [N] normal force, sum over patches (with the load coupling: at the
                              //   state's creepage)
  bool ok = false;            // a loaded contact was found
};

// A model setting: normal model, strips (non-Hertz models), FASTSIM elements per strip.
struct SaModelSetting {
  NormalModel model = NormalModel::stripes_ab;
  int strips = 50;
  int elements = 20;
  std::string label() const;  // e.g. "stripes-ab 50x20", "hertz e20"
};

// A table: y step and creepage grid ("scene" = the scene's xi/eta/phi grids, "fine" = 0.5e-3 /
// 0.5e-3 / 0.025 rad/m steps around the states' creepages).
struct SaTableSetting {
  double y_step = 0.5e-3;     // [m]
  bool fine_creep = false;
  bool exact = false;         // a table of the exact half-space model (else of the scene's model)
  std::string label() const;  // e.g. "table y0.5mm" / "table y0.25mm fine-creep" / "table y0.5mm exact"
};

struct SpeedAccuracyOptions {
  std::filesystem::path reference_csv;       // block C file; empty/absent: fine-STRIPES fallback
  std::vector<double> dy_mm;                 // subset of dy (empty = all of the reference / -6..10)
  std::vector<std::string> creep_sets;       // subset of sets (empty = all five)
  std::vector<SaModelSetting> models;        // empty = default_model_settings()
  std::vector<SaTableSetting> tables;        // empty = default_table_settings(scene); none: set no_tables
  bool no_tables = false;
  bool cubic = true;                         // also time/measure cubic interpolation of each table
  std::filesystem::path work_dir;            // temporary tables go here (required for tables)
  bool keep_tables = false;                  // keep the .h5 files in work_dir
  int repeats = 11;                          // timed runs per state and model (after 1 warm-up)
  int exact_repeats = 3;                     //   at most this many for the exact model (~0.1 s each)
  int lookup_passes = 200;                   // timed passes over all states per table
  int table_threads = 0;                     // threads of the table sweeps (0 = all cores)
  // Reference without CONTACT data: the exact half-space model of the scene (its element_size,
  // normal + steady rolling, src/halfspace); a fast model here gives the older fine-STRIPES one.
  SaModelSetting fallback_reference{NormalModel::halfspace, 0, 0};
};

std::vector<SaModelSetting> default_model_settings();
std::vector<SaTableSetting> default_table_settings(bool exact_scene);  // exact_scene: the scene's model is halfspace
// A few settings only, for smoke runs (railtab chart --quick).
std::vector<SaModelSetting> quick_model_settings();
std::vector<SaTableSetting> quick_table_settings();

// One point of the charts: a model setting or a table (+ interpolation method).
struct SaRow {
  std::string label;
  std::string kind;            // "model" or "lookup"
  std::string family;          // model name, or "lookup-linear" / "lookup-cubic" (+ "-exact": a table of
                               //   the exact model)
  int strips = 0, elements = 0;          // model settings (0 where not applicable)
  double table_y_step = 0.0;             // [m] (lookup rows)
  std::string table_creep_grid;          // "scene" or "fine" (lookup rows)
  double time_us = 0.0;                  // median time per evaluation over all states [us]
  double time_tread_us = 0.0, time_flange_us = 0.0;  // medians over tread / flange states
  double time_geometry_us = 0.0;         // median of the geometry step alone (model rows)
  double err_force = 0.0;                // median relative creep-force error, creep states
  double err_force_p90 = 0.0;            // 90th percentile of the same
  double err_force_tread = 0.0;          // median over tread creep states (dy <= 6 mm)
  double err_force_flange = 0.0;         // median over flange creep states (dy >= 7 mm)
  double err_area = 0.0;                 // median |area/area_ref - 1|, no-creepage states
  double err_pmax = 0.0;                 // median |pmax/pmax_ref - 1|, no-creepage states
  double err_angle_mrad = 0.0;           // median |angle - angle_ref|, no-creepage states [mrad]
  double time_contact_us = 0.0;          // model rows: median of (full chain - geometry) per state
  double err_interp = 0.0;               // lookup rows: median creep-force error against a direct
  double err_interp_p90 = 0.0;           //   evaluation of the table's own model setting (p90 too)
  int n_creep = 0, n_normal = 0, n_failed = 0;  // states used / without a loaded contact
  std::uintmax_t file_bytes = 0;         // table file size (lookup rows) [B]
  std::size_t memory_bytes = 0;          // Table::memory_bytes() (lookup rows) [B]
  bool pareto_all = false, pareto_tread = false, pareto_flange = false;
};

// Per state and row: for speed_accuracy_states.csv.
struct SaStateRow {
  std::size_t row = 0;    // index into SpeedAccuracyResult::rows
  std::size_t state = 0;  // index into SpeedAccuracyResult::states
  SaOutcome out;
  double time_us = 0.0;   // median over repeats [us]
  double err_force = 0.0; // relative creep-force error (creep states), NaN otherwise
};

struct SpeedAccuracyResult {
  bool contact_reference = false;   // true: CONTACT block C; false: options.fallback_reference
  bool exact_reference = false;     // the fallback is the exact half-space model
  std::string reference;            // one line: what the reference is
  std::string setup;                // one line: material, roll, load, ...
  std::vector<SaState> states;
  std::vector<SaRow> rows;
  std::vector<SaStateRow> per_state;
  double seconds = 0.0;             // wall time of the measurement [s]
};

// Runs everything; throws railtab::Error on fatal problems (unreadable reference, no gnuplot is
// not its business).
// Whether CONTACT's block C reference (S1002 on UIC60 at 1:40) describes this scene's pair; when it
// does not, measure_speed_accuracy uses the fallback reference even if the CSV exists.
bool contact_reference_applies(const Scene& scene);

SpeedAccuracyResult measure_speed_accuracy(const Scene& scene, const SpeedAccuracyOptions& options);

// Marks Pareto-optimal points (minimise both); NaN points are never on the front.
std::vector<bool> pareto_front(const std::vector<double>& time, const std::vector<double>& error);

// CSV writers (comment lines start with '#': reference, error measure, timing definition).
void write_speed_accuracy_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path);
void write_states_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path);
void write_table_memory_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path);

// Relative creep-force error |F - F_ref| / |F_ref| (vector difference in the tangent plane).
double force_error(const SaOutcome& out, const SaState& state);

}  // namespace railtab
