// SPDX-License-Identifier: Apache-2.0
// railtab::lookup: load a wheel-rail contact table (docs/table-format.md) once, then interpolate
// it from any number of threads inside a simulation's time-stepping loop.
//
// Self-contained on purpose: a simulation links only this library, so this header pulls in
// neither Eigen, oneTBB nor HDF5, and nothing from railtab's core library.
//
//   auto table = railtab::lookup::Table::load("default.h5");          // throws LoadError
//   railtab::lookup::State s = table.default_state();                  // fixed axes filled in,
//   s.y = 0.003; s.load = 78500; s.xi = 1e-3;                           // tabulated ones at 0
//   railtab::lookup::Result r;
//   table.query(railtab::lookup::Wheel::kLeft, s, r);                  // never throws, no locks
//   double fx = r.contact[0].value[railtab::lookup::kFx];
//   railtab::lookup::Contact tread;                                    // or one slot only:
//   table.query_slot(railtab::lookup::Wheel::kLeft, s, 0, tread);
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "railtab/lookup_export.h"

namespace railtab::lookup {

using StatusBits = std::uint32_t;

// Status bits. The values MATCH src/core/status.hpp (railtab::status), mirrored here because the
// lookup must not depend on the core library; tests/lookup/status_bits_test.cpp checks them.
namespace status {
inline constexpr StatusBits kConverged = 1u << 0;         // solver met its tolerance (all corners)
inline constexpr StatusBits kNotConverged = 1u << 1;      // iteration limit hit at some node
inline constexpr StatusBits kTwoPoint = 1u << 2;          // more than one contact on this wheel
inline constexpr StatusBits kLiftOff = 1u << 3;           // no contact at this load/approach
inline constexpr StatusBits kCurvatureClipped = 1u << 4;  // negative/small B clipped
inline constexpr StatusBits kCurvatureShifted = 1u << 5;  // negative/small B shifted upward
inline constexpr StatusBits kFallbackModel = 1u << 6;     // the chosen model failed; a simpler ran
inline constexpr StatusBits kFlangeContact = 1u << 7;     // contact angle beyond the tread range
inline constexpr StatusBits kNonHertzian = 1u << 8;       // A or B <= 0: Hertz invalid
inline constexpr StatusBits kFullSlip = 1u << 9;          // tangential force saturated at mu*N
inline constexpr StatusBits kOutOfRange = 1u << 10;       // query clamped to the table edge, or a
                                                          // fixed axis queried off its value
inline constexpr StatusBits kInvalidInput = 1u << 11;     // NaN/inf in the query: outputs are 0
inline constexpr StatusBits kProfileEdge = 1u << 12;      // contact band reached a profile end
inline constexpr StatusBits kFailed = 1u << 13;           // the core threw at a node: outputs 0
inline constexpr StatusBits kAreaTooSmall = 1u << 14;     // half-space: contact reached the potential area's edge
inline constexpr StatusBits kNotPlanar = 1u << 15;        // half-space: contact angle varies across the patch
inline constexpr StatusBits kNearEqualMinima = 1u << 16;  // geometry: two near-equal rigid gap minima,
                                                          // the contact point may jump between them
inline constexpr StatusBits kCurvatureStep = 1u << 17;    // geometry: a profile radius transition at
                                                          // the point: B and the point models step
inline constexpr StatusBits kLowConfidence = 1u << 18;    // the query's cell spans a change the table
                                                          // does not resolve (docs/lookup.md)
inline constexpr int kNumBits = 19;                       // bits 0 .. kNumBits-1 are defined

// Name of one bit as in the table files and `railtab inspect` ("converged", "two_point", ...;
// "unknown" for a value that is not a single defined bit).
RAILTAB_LOOKUP_API const char* bit_name(StatusBits bit) noexcept;
// Comma-separated names of the set bits, e.g. "converged,two_point"; "none" for 0; undefined
// bits as "bit20".
RAILTAB_LOOKUP_API std::string describe(StatusBits bits);
}  // namespace status

// Contact slot limit. Format 1.0 writes 2 slots (0 = tread, 1 = flange); a table with more than
// kMaxSlots slots is rejected at load.
inline constexpr int kMaxSlots = 4;

// Wheels: index 0 = left, 1 = right (docs/conventions.md).
enum class Wheel : int { kLeft = 0, kRight = 1 };

// Parts of a table (docs/table-format.md), in file order.
enum Part : int { kGeometry = 0, kNormal = 1, kCreep = 2, kWear = 3, kNumParts = 4 };

// Every output of every part, as indices into Contact::value. The order and names are those of
// docs/table-format.md; the C API uses the same numbers (RAILTAB_LOOKUP_*).
enum Output : int {
  kContactAngle = 0,   // [rad] geometry
  kRollingRadius = 1,  // [m]
  kWheelY = 2,         // [m] contact's u in the wheel profile frame
  kRailY = 3,          // [m] contact's u in the rail profile frame
  kSeparation = 4,     // [m]
  kCurvatureA = 5,     // [1/m]
  kCurvatureB = 6,     // [1/m]
  kNormalForce = 7,    // [N] normal
  kApproach = 8,       // [m]
  kArea = 9,           // [m2]
  kMaxPressure = 10,   // [Pa]
  kSemiAxisA = 11,     // [m] dataset `a`
  kSemiAxisB = 12,     // [m] dataset `b`
  kFx = 13,            // [N] creep, on the wheel
  kFy = 14,            // [N]
  kMz = 15,            // [N m]
  kSlipFraction = 16,  // [1]
  kWearRate = 17,      // [m2/m] wear
  kNumOutputs = 18
};

// Dataset name of an output in the table file ("contact_angle", ..., "wear_rate").
RAILTAB_LOOKUP_API const char* output_name(Output output);
// Part of an output, and the part's group name in the file ("geometry", ...).
RAILTAB_LOOKUP_API Part output_part(Output output);
RAILTAB_LOOKUP_API const char* part_name(Part part);

// The state of one wheel-rail pair. A table tabulates some of these (its axes) and fixes the
// others (root attribute fixed_axes); a fixed variable must be queried at its fixed value, else
// the result is flagged kOutOfRange. Table::default_state() fills in the fixed values.
struct State {
  double y = 0.0;     // [m] wheelset lateral displacement, track frame, + left
  double roll = 0.0;  // [rad] wheelset roll relative to track
  double load = 0.0;  // [N] vertical wheel load
  double xi = 0.0;    // [1] longitudinal creepage
  double eta = 0.0;   // [1] lateral creepage
  double phi = 0.0;   // [rad/m] spin creepage
  // [rad] wheelset yaw (angle of attack) relative to track, + turns the forward axis to the left.
  // Last, so that positional initialisation written before yaw existed keeps its meaning; in the
  // files yaw sits after roll (docs/table-format.md). A table without yaw holds yaw 0 only.
  double yaw = 0.0;
};

// Interpolated outputs of one contact slot.
struct Contact {
  double value[kNumOutputs] = {};            // outputs indexed by Output; 0 for absent parts
  StatusBits part_status[kNumParts] = {};    // per part: corner statuses combined (see Result)
  StatusBits status = 0;                     // all present parts combined, plus query bits
  std::uint32_t reserved = 0;                // explicit padding (same layout as the C struct)
};

// One query's answer. Status is not interpolated: for each part and slot, the trouble bits are
// the OR over the 2^D corner nodes of the interpolation cell, and kConverged and kFullSlip are set
// only if set at every corner (an AND). Conservative on purpose: an interpolated value is only as good
// as the worst node it is built from, and a cell half in lift-off must not look like a clean
// contact. Jumps (tread -> flange) live in separate slots and in status, they are not smoothed.
struct Result {
  Contact contact[kMaxSlots];  // slots 0 .. n_slots-1 (0 = tread, 1 = flange); others untouched
  int n_slots = 0;             // number of contact slots in the table
  StatusBits status = 0;       // query bits only: kOutOfRange, kInvalidInput
};

// State variables as indices (the order of State and of the table's axes): the second index of
// Derivatives::d. The C API uses the same numbers (RAILTAB_LOOKUP_VAR_*).
// kYaw is last for the same reason as State::yaw.
enum Variable : int { kY = 0, kRoll = 1, kLoad = 2, kXi = 3, kEta = 4, kPhi = 5, kYaw = 6, kNumVariables = 7 };
// Name of a state variable as in the table files ("y", "roll", "load", "xi", "eta", "phi", "yaw";
// "?" out of range).
RAILTAB_LOOKUP_API const char* variable_name(int variable) noexcept;

// Partial derivatives of every output of every slot with respect to each state variable: the
// exact derivatives of the interpolant the query evaluates (docs/lookup.md, "Derivatives"), in
// SI: output units per variable unit (fx per xi in N, fy per y in N/m, mz per phi in N m / (rad/m)).
// Zero for a variable the table does not tabulate, for a variable clamped to the table's range
// (the value does not change there), for parts the table does not hold and for invalid input.
struct Derivatives {
  double d[kMaxSlots][kNumOutputs][kNumVariables] = {};  // [slot][Output][Variable]
};

// The same for one slot (Table::query_slot_derivatives): Derivatives::d[slot].
struct SlotDerivatives {
  double d[kNumOutputs][kNumVariables] = {};  // [Output][Variable]
};

// Forces of the rail on one wheel in track axes (x forward, y left, z up; docs/conventions.md,
// "Track-frame forces and Y/Q"), from one query result: the table stores each slot's normal force N
// along the contact normal n = (0, -sin g, cos g) and its creep force fy along s = (0, cos g, sin g),
// g the slot's contact angle in the track frame; fx is along track x already. Per loaded slot
// (normal force > 0): lateral = -N sin g + fy cos g, vertical = N cos g + fy sin g. A loaded slot
// whose rigid point sits in the other slot (rolling radius 0: a hand-over, docs/lookup.md "Low
// confidence") is rotated with the other slot's angle, as the loop of docs/lookup.md does.
struct TrackForces {
  double lateral[kMaxSlots] = {};        // [N] per slot: on the wheel along track y (+ left)
  double vertical[kMaxSlots] = {};       // [N] per slot: on the wheel along track z (+ up)
  double contact_angle[kMaxSlots] = {};  // [rad] per slot: the angle g rotated with (0: empty slot)
  double wheel_lateral = 0.0;            // [N] sum of lateral over the slots
  double wheel_vertical = 0.0;           // [N] sum of vertical over the slots
  // Y and Q of the derailment criteria, forces of the wheel ON ITS RAIL: Y lateral, + towards that
  // rail's field side (outward: + y for the left rail, - y for the right), so flange contact gives
  // Y > 0 on either wheel: y_force = -sigma wheel_lateral, sigma = +1 left, -1 right. Q vertical,
  // + down: q_force = wheel_vertical.
  double y_force = 0.0;                  // [N] Y
  double q_force = 0.0;                  // [N] Q
  double y_over_q = 0.0;                 // [1] Y / Q; 0 when Q <= 0 (no loaded slot, invalid input)
};

// Track-frame forces and Y/Q of `wheel` from `result` (a query of that wheel). Never throws; a bad
// wheel gives all zeros.
RAILTAB_LOOKUP_API TrackForces track_forces(Wheel wheel, const Result& result) noexcept;

// Linear creep coefficients of every slot (tables of format 2.3; docs/lookup.md "Linear creep
// coefficients", docs/conventions.md): k[slot][f][c] = d f / d c at zero creepage in full adhesion,
// f = 0 fx, 1 fy, 2 mz (on the wheel), c = 0 xi, 1 eta, 2 phi (Variable - kXi), from the table's
// own model, interpolated over (y, roll, load) and one-sided at located contact jumps. Units: fx,
// fy per xi or eta N; fx, fy per phi N m (N per rad/m); mz per xi or eta N m; mz per phi N m2. On an
// elliptic patch k[s][0][0] = -G c^2 C11, k[s][1][1] = -G c^2 C22, k[s][1][2] = -G c^3 C23.
struct CreepCoefficients {
  double k[kMaxSlots][3][3] = {};      // [slot][force][creepage], see above; 0 for an empty slot
  StatusBits status[kMaxSlots] = {};   // per slot: the normal part's status at the state, as
                                       // query()'s contact[slot].part_status[kNormal]
  StatusBits query_status = 0;         // query bits as Result::status: kOutOfRange (clamped to
                                       // the table's edge), kInvalidInput (coefficients 0)
  int n_slots = 0;                     // contact slots in the table
};

// One item of a batch query (e.g. both wheels of every wheelset).
struct Query {
  Wheel wheel = Wheel::kLeft;  // which wheel-rail pair
  State state;                 // its state
};

// Interpolation method, chosen once at load.
enum class Method : int {
  kLinear = 0,          // multilinear (default): C0, exact for affine functions, 2^D corners
  kCubic = 1,           // tensor-product cubic Hermite, 3-point slopes: C1, exact for
                        // quadratics, 4^D nodes (~20x the cost of linear in 4-D)
  kMonotoneCubic = 2,   // as kCubic with Fritsch-Carlson limited slopes: C1, no overshoot
                        // where the data are monotone along an axis
};

struct LoadOptions {
  Method method = Method::kLinear;  // interpolation method for every part
  // Refuse a table without dataset checksums (another tool's; format 1.0 is always refused) instead of loading it with
  // Table::checksums_verified() false. docs/table-format.md, "Integrity".
  bool require_checksums = false;
  // Load a shard (`railtab generate --shard I/N`, root attribute `shard`) as the table of its own
  // y range instead of refusing it: what the generator's writers use to check a shard they wrote
  // or are about to merge. A simulation loads the merged table.
  bool accept_shard = false;
};

// Any problem while loading a table: missing/truncated/corrupt file, unknown major version,
// missing dataset or attribute, wrong shape or type. what() names the file and the problem.
class RAILTAB_LOOKUP_API LoadError : public std::runtime_error {
 public:
  LoadError(std::string path, const std::string& problem);
  const std::string& path() const noexcept { return path_; }  // the file being loaded

 private:
  std::string path_;
};

// One tabulated axis (a dimension scale under /axes).
struct AxisInfo {
  std::string name;            // "y", "roll", "yaw", "load", "xi", "eta" or "phi"
  std::vector<double> nodes;   // strictly increasing grid nodes, SI units
  std::string units;           // the axis's `units` attribute ("m", "rad", ...; "" if absent)
};

// SI units of an output ("rad", "m", "N", ...), of a state variable by name ("y" -> "m"; "" for
// an unknown name), and the name of a contact slot (0 "tread", 1 "flange", else "slot<k>").
RAILTAB_LOOKUP_API const char* output_units(Output output);
RAILTAB_LOOKUP_API const char* state_units(const std::string& variable);
RAILTAB_LOOKUP_API std::string slot_name(int slot);

// The table's measured error where a query lands (format 2.3, group /error_map; docs/lookup.md
// "Error estimate"): the region (y band x slot) holding y, with the RMS and maximum errors of its
// samples. Quantities in the order fx, fy [% of mu N], mz [% of mu N c, c = sqrt(area / pi)],
// normal force [% of N], contact angle [rad]; NaN where the region has no sample.
inline constexpr int kErrorQuantities = 5;
enum ErrorQuantity : int { kErrorFx = 0, kErrorFy = 1, kErrorMz = 2, kErrorNormalForce = 3, kErrorContactAngle = 4 };
struct ErrorStats {
  double samples = 0.0;             // wheel-state pairs with the slot loaded (0: none)
  double rms[kErrorQuantities] = {};
  double max[kErrorQuantities] = {};
};
struct ErrorEstimate {
  int available = 0;        // 1: the table has an error map and y lies in one of its bands
  int exact_measured = 0;   // 1: model_vs_exact holds the model against the exact half-space model
  int same_model = 0;       // 1: the table's model is the exact one (nothing to compare; not a zero)
  int reserved = 0;         // explicit padding (same layout as the C struct)
  double y_band_start = 0.0, y_band_end = 0.0;  // [m] the band holding y
  ErrorStats table_vs_model;  // the table (linear lookup) against its own model
  ErrorStats model_vs_exact;  // the model against the exact model (exact_measured)
};

// Version of this library ("0.1.0"), and the newest table format it reads and writes ("2.3").
RAILTAB_LOOKUP_API const char* library_version() noexcept;
RAILTAB_LOOKUP_API const char* supported_format_version() noexcept;

namespace detail {
struct TableData;  // internal, immutable after load (lookup/src/table_data.hpp)
}

// A loaded table. Immutable: every const member is safe to call from any number of threads at
// once without locks. Cheap to copy (shares the data).
class RAILTAB_LOOKUP_API Table {
 public:
  // Reads the whole file into memory, laid out for the query path. Throws LoadError.
  static Table load(const std::string& path, const LoadOptions& options = {});

  // Interpolates every output of every slot of `wheel` at `state`. Never throws, allocates
  // nothing, never extrapolates: out-of-range variables are clamped to the table edge and flagged
  // kOutOfRange; a NaN/inf in a variable the table uses gives zeros and kInvalidInput.
  void query(Wheel wheel, const State& state, Result& result) const noexcept;
  Result query(Wheel wheel, const State& state) const noexcept;

  // One contact slot only (0 = tread, 1 = flange): `contact` receives exactly what
  // query(wheel, state).contact[slot] would hold, including the query bits kOutOfRange and
  // kInvalidInput in contact.status, at about half the cost of query() on a 2-slot table (it
  // reads only that slot's records). A slot outside 0 .. n_slots()-1 or a bad wheel gives zeros
  // and kInvalidInput. Never throws, allocates nothing.
  void query_slot(Wheel wheel, const State& state, int slot, Contact& contact) const noexcept;
  Contact query_slot(Wheel wheel, const State& state, int slot) const noexcept;

  // query() plus the partial derivatives of every output (Derivatives): `result` receives exactly
  // what query() gives. Linear and cubic methods; returns false for kMonotoneCubic (its limited
  // slopes are not differentiated: `derivatives` all 0, `result` still filled; see
  // derivatives_supported()). Never throws, allocates nothing.
  bool query_derivatives(Wheel wheel, const State& state, Result& result,
                         Derivatives& derivatives) const noexcept;
  bool derivatives_supported() const noexcept;  // method() is kLinear or kCubic

  // One slot's twin of query_derivatives (as query_slot is query's): `contact` and `derivatives`
  // receive exactly query_derivatives' contact[slot] and d[slot], reading only that slot's
  // records. A slot outside 0 .. n_slots()-1 or a bad wheel gives zeros and kInvalidInput. Returns
  // false for kMonotoneCubic (derivatives all 0). Never throws, allocates nothing.
  bool query_slot_derivatives(Wheel wheel, const State& state, int slot, Contact& contact,
                              SlotDerivatives& derivatives) const noexcept;

  // The linear creep coefficients of `wheel` at the state's (y, roll, load); its creepages are
  // not used (the coefficients are at zero creepage). Returns false, with `out` zeroed, when the
  // table holds none (format 2.2 and older: has_creep_coefficients() false). Out-of-range and
  // invalid states are flagged as by query(). Never throws, allocates nothing.
  bool query_creep_coefficients(Wheel wheel, const State& state, CreepCoefficients& out) const noexcept;
  bool has_creep_coefficients() const noexcept;
  // The stored error map at (y, slot) (ErrorEstimate): false, and `estimate` with available 0,
  // when the table has no error map (before format 2.3), y is NaN or outside its bands, or the
  // slot is outside 0 .. n_slots()-1. Never throws, allocates nothing.
  bool error_estimate(double y, int slot, ErrorEstimate& estimate) const noexcept;
  bool has_error_map() const noexcept;

  // Batch: results[k] = query(queries[k]). Returns false, and touches nothing, when
  // results.size() < queries.size() (a short buffer is an error, not a silent truncation);
  // extra results are untouched.
  bool query(std::span<const Query> queries, std::span<Result> results) const noexcept;

  const std::string& path() const;            // file it was loaded from
  Method method() const;                      // interpolation method
  int n_slots() const;                        // contact slots in the table
  bool has_part(Part part) const;             // whether the table holds this part
  const std::vector<AxisInfo>& axes() const;  // tabulated axes, in file order
  // Untabulated state variables and their fixed values, e.g. {"roll",0.0}, {"load",78500.0}.
  const std::vector<std::pair<std::string, double>>& fixed_axes() const;
  State default_state() const;                // fixed values filled in, tabulated ones at 0
  const std::string& format_version() const;  // e.g. "1.0"
  const std::string& scene_name() const;      // root attribute scene_name ("" if absent)
  std::size_t memory_bytes() const;           // size of the interpolation data
  // Whether every dataset carried HDF5's Fletcher32 checksum and the metadata theirs (format
  // 1.1 tables): then a corrupt byte is a load error. False for a table with checksummed metadata
  // but no dataset checksums (another tool's), which loads unverified unless
  // LoadOptions::require_checksums (format 1.0 is refused; docs/table-format.md, "Integrity").
  bool checksums_verified() const;
  // Whether the yaw axis holds the non-negative half of a symmetric one (root attribute
  // yaw_symmetry = "even", docs/table-format.md): axes() lists yaw from 0, a query reads |yaw|.
  bool yaw_even() const;

 private:
  explicit Table(std::shared_ptr<const detail::TableData> data);
  std::shared_ptr<const detail::TableData> data_;  // shared, never modified after load
};

}  // namespace railtab::lookup
