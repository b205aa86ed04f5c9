// SPDX-License-Identifier: Apache-2.0
// C API over railtab::lookup::Table. No exception crosses this boundary: each entry point
// catches, stores the message in a thread-local string and returns a code.
#include "railtab_lookup.h"

#include <cstddef>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "railtab/lookup.hpp"

struct railtab_lookup_table {
  railtab::lookup::Table table;  // the loaded table
};



namespace {

namespace lk = railtab::lookup;

// The C structs mirror the C++ ones field by field so results are copied with one memcpy.
static_assert(sizeof(railtab_lookup_state) == sizeof(lk::State));
static_assert(sizeof(railtab_lookup_error_estimate) == sizeof(lk::ErrorEstimate));
static_assert(offsetof(railtab_lookup_error_estimate, y_band_start) == offsetof(lk::ErrorEstimate, y_band_start));
static_assert(offsetof(railtab_lookup_error_estimate, model_vs_exact) == offsetof(lk::ErrorEstimate, model_vs_exact));
static_assert(RAILTAB_LOOKUP_NUM_ERR == lk::kErrorQuantities && RAILTAB_LOOKUP_ERR_FY == lk::kErrorFy &&
              RAILTAB_LOOKUP_ERR_CONTACT_ANGLE == lk::kErrorContactAngle);
static_assert(offsetof(railtab_lookup_state, phi) == offsetof(lk::State, phi));
static_assert(offsetof(railtab_lookup_state, yaw) == offsetof(lk::State, yaw));
static_assert(sizeof(railtab_lookup_contact) == sizeof(lk::Contact));
static_assert(offsetof(railtab_lookup_contact, part_status) == offsetof(lk::Contact, part_status));
static_assert(offsetof(railtab_lookup_contact, status) == offsetof(lk::Contact, status));
static_assert(sizeof(railtab_lookup_result) == sizeof(lk::Result));
static_assert(offsetof(railtab_lookup_result, n_slots) == offsetof(lk::Result, n_slots));
static_assert(offsetof(railtab_lookup_result, status) == offsetof(lk::Result, status));
static_assert(int{RAILTAB_LOOKUP_NUM_OUTPUTS} == int{lk::kNumOutputs});
static_assert(int{RAILTAB_LOOKUP_FX} == int{lk::kFx});
static_assert(int{RAILTAB_LOOKUP_WEAR_RATE} == int{lk::kWearRate});
static_assert(RAILTAB_LOOKUP_MAX_SLOTS == lk::kMaxSlots);
static_assert(RAILTAB_LOOKUP_CONVERGED == lk::status::kConverged);
static_assert(RAILTAB_LOOKUP_NOT_CONVERGED == lk::status::kNotConverged);
static_assert(RAILTAB_LOOKUP_TWO_POINT == lk::status::kTwoPoint);
static_assert(RAILTAB_LOOKUP_LIFT_OFF == lk::status::kLiftOff);
static_assert(RAILTAB_LOOKUP_CURVATURE_CLIPPED == lk::status::kCurvatureClipped);
static_assert(RAILTAB_LOOKUP_CURVATURE_SHIFTED == lk::status::kCurvatureShifted);
static_assert(RAILTAB_LOOKUP_FALLBACK_MODEL == lk::status::kFallbackModel);
static_assert(RAILTAB_LOOKUP_FLANGE_CONTACT == lk::status::kFlangeContact);
static_assert(RAILTAB_LOOKUP_NON_HERTZIAN == lk::status::kNonHertzian);
static_assert(RAILTAB_LOOKUP_FULL_SLIP == lk::status::kFullSlip);
static_assert(RAILTAB_LOOKUP_OUT_OF_RANGE == lk::status::kOutOfRange);
static_assert(RAILTAB_LOOKUP_INVALID_INPUT == lk::status::kInvalidInput);
static_assert(RAILTAB_LOOKUP_PROFILE_EDGE == lk::status::kProfileEdge);
static_assert(RAILTAB_LOOKUP_FAILED == lk::status::kFailed);
static_assert(RAILTAB_LOOKUP_AREA_TOO_SMALL == lk::status::kAreaTooSmall);
static_assert(RAILTAB_LOOKUP_NOT_PLANAR == lk::status::kNotPlanar);
static_assert(RAILTAB_LOOKUP_NEAR_EQUAL_MINIMA == lk::status::kNearEqualMinima);
static_assert(RAILTAB_LOOKUP_CURVATURE_STEP == lk::status::kCurvatureStep);
static_assert(RAILTAB_LOOKUP_LOW_CONFIDENCE == lk::status::kLowConfidence);
static_assert(RAILTAB_LOOKUP_NUM_STATUS_BITS == lk::status::kNumBits);
static_assert(RAILTAB_LOOKUP_WEAR == lk::kWear && RAILTAB_LOOKUP_NUM_PARTS == lk::kNumParts);

static_assert(sizeof(railtab_lookup_derivatives) == sizeof(lk::Derivatives));
static_assert(sizeof(railtab_lookup_slot_derivatives) == sizeof(lk::SlotDerivatives));
static_assert(sizeof(railtab_lookup_track_forces) == sizeof(lk::TrackForces));
static_assert(sizeof(railtab_lookup_creep_coefficients) == sizeof(lk::CreepCoefficients));
static_assert(offsetof(railtab_lookup_creep_coefficients, status) == offsetof(lk::CreepCoefficients, status));
static_assert(offsetof(railtab_lookup_creep_coefficients, query_status) == offsetof(lk::CreepCoefficients, query_status));
static_assert(offsetof(railtab_lookup_creep_coefficients, n_slots) == offsetof(lk::CreepCoefficients, n_slots));
static_assert(offsetof(railtab_lookup_track_forces, contact_angle) == offsetof(lk::TrackForces, contact_angle));
static_assert(offsetof(railtab_lookup_track_forces, wheel_lateral) == offsetof(lk::TrackForces, wheel_lateral));
static_assert(offsetof(railtab_lookup_track_forces, y_over_q) == offsetof(lk::TrackForces, y_over_q));
static_assert(int{RAILTAB_LOOKUP_NUM_VARS} == int{lk::kNumVariables});
static_assert(int{RAILTAB_LOOKUP_VAR_PHI} == int{lk::kPhi} && int{RAILTAB_LOOKUP_VAR_LOAD} == int{lk::kLoad});
static_assert(int{RAILTAB_LOOKUP_VAR_YAW} == int{lk::kYaw});

thread_local std::string last_error;

int fail(int code, const char* message) noexcept {
  try {
    last_error = message;
  } catch (...) {  // assigning may allocate; keep the code even if the message is lost
  }
  return code;
}

lk::State to_state(const railtab_lookup_state& s) noexcept {
  return lk::State{s.y, s.roll, s.load, s.xi, s.eta, s.phi, s.yaw};
}

void store(const lk::Result& r, railtab_lookup_result* out) noexcept {
  std::memcpy(out, &r, sizeof(*out));
}

}  // namespace

extern "C" {

int railtab_lookup_open_options(const char* path, int method, unsigned flags,
                                railtab_lookup_table** table) {
  if (table) *table = nullptr;
  if (!path || !table) return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_open: null argument");
  if (method < RAILTAB_LOOKUP_LINEAR || method > RAILTAB_LOOKUP_MONOTONE_CUBIC)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_open: unknown interpolation method");
  if (flags & ~RAILTAB_LOOKUP_REQUIRE_CHECKSUMS)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_open: unknown option flag");
  try {
    lk::LoadOptions options;
    options.method = static_cast<lk::Method>(method);
    options.require_checksums = (flags & RAILTAB_LOOKUP_REQUIRE_CHECKSUMS) != 0;
    *table = new railtab_lookup_table{lk::Table::load(path, options)};
    last_error.clear();
    return RAILTAB_LOOKUP_OK;
  } catch (const lk::LoadError& e) {
    return fail(RAILTAB_LOOKUP_ERROR_LOAD, e.what());
  } catch (const std::bad_alloc&) {
    return fail(RAILTAB_LOOKUP_ERROR_INTERNAL, "railtab_lookup_open: out of memory");
  } catch (const std::exception& e) {
    return fail(RAILTAB_LOOKUP_ERROR_INTERNAL, e.what());
  } catch (...) {
    return fail(RAILTAB_LOOKUP_ERROR_INTERNAL, "railtab_lookup_open: unknown error");
  }
}

int railtab_lookup_open(const char* path, int method, railtab_lookup_table** table) {
  return railtab_lookup_open_options(path, method, 0u, table);
}

int railtab_lookup_query(const railtab_lookup_table* table, int wheel,
                         const railtab_lookup_state* state, railtab_lookup_result* result) {
  if (!table || !state || !result)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query: null argument");
  if (wheel != RAILTAB_LOOKUP_LEFT && wheel != RAILTAB_LOOKUP_RIGHT)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query: wheel must be 0 or 1");
  lk::Result r;
  table->table.query(static_cast<lk::Wheel>(wheel), to_state(*state), r);
  store(r, result);
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_query_derivatives(const railtab_lookup_table* table, int wheel,
                                     const railtab_lookup_state* state, railtab_lookup_result* result,
                                     railtab_lookup_derivatives* derivatives) {
  if (!table || !state || !result || !derivatives)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_derivatives: null argument");
  if (wheel != RAILTAB_LOOKUP_LEFT && wheel != RAILTAB_LOOKUP_RIGHT)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_derivatives: wheel must be 0 or 1");
  if (!table->table.derivatives_supported())
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT,
                "railtab_lookup_query_derivatives: derivatives need a table opened with RAILTAB_LOOKUP_LINEAR "
                "or RAILTAB_LOOKUP_CUBIC, not RAILTAB_LOOKUP_MONOTONE_CUBIC");
  lk::Result r;
  lk::Derivatives d;
  table->table.query_derivatives(static_cast<lk::Wheel>(wheel), to_state(*state), r, d);
  store(r, result);
  std::memcpy(derivatives, &d, sizeof(*derivatives));
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_query_slot_derivatives(const railtab_lookup_table* table, int wheel,
                                          const railtab_lookup_state* state, int slot,
                                          railtab_lookup_contact* contact,
                                          railtab_lookup_slot_derivatives* derivatives) {
  if (!table || !state || !contact || !derivatives)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_slot_derivatives: null argument");
  if (wheel != RAILTAB_LOOKUP_LEFT && wheel != RAILTAB_LOOKUP_RIGHT)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_slot_derivatives: wheel must be 0 or 1");
  if (slot < 0 || slot >= table->table.n_slots())
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_slot_derivatives: slot outside 0 .. n_slots-1");
  if (!table->table.derivatives_supported())
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT,
                "railtab_lookup_query_slot_derivatives: derivatives need a table opened with RAILTAB_LOOKUP_LINEAR "
                "or RAILTAB_LOOKUP_CUBIC, not RAILTAB_LOOKUP_MONOTONE_CUBIC");
  lk::Contact c;
  lk::SlotDerivatives d;
  table->table.query_slot_derivatives(static_cast<lk::Wheel>(wheel), to_state(*state), slot, c, d);
  std::memcpy(contact, &c, sizeof(*contact));
  std::memcpy(derivatives, &d, sizeof(*derivatives));
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_query_creep_coefficients(const railtab_lookup_table* table, int wheel,
                                            const railtab_lookup_state* state,
                                            railtab_lookup_creep_coefficients* coefficients) {
  if (!table || !state || !coefficients)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_creep_coefficients: null argument");
  if (wheel != RAILTAB_LOOKUP_LEFT && wheel != RAILTAB_LOOKUP_RIGHT)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_creep_coefficients: wheel must be 0 or 1");
  lk::CreepCoefficients c;
  if (!table->table.query_creep_coefficients(static_cast<lk::Wheel>(wheel), to_state(*state), c))
    return fail(RAILTAB_LOOKUP_ERROR_NOT_IN_TABLE,
                "railtab_lookup_query_creep_coefficients: the table holds no linear creep coefficients "
                "(format 2.2 or older): regenerate it with railtab generate (format 2.3)");
  std::memcpy(coefficients, &c, sizeof(*coefficients));
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_has_creep_coefficients(const railtab_lookup_table* table) {
  return table && table->table.has_creep_coefficients() ? 1 : 0;
}

int railtab_lookup_yaw_even(const railtab_lookup_table* table) {
  return table && table->table.yaw_even() ? 1 : 0;
}

int railtab_lookup_compute_track_forces(int wheel, const railtab_lookup_result* result,
                                        railtab_lookup_track_forces* forces) {
  if (!result || !forces) return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_compute_track_forces: null argument");
  if (wheel != RAILTAB_LOOKUP_LEFT && wheel != RAILTAB_LOOKUP_RIGHT)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_compute_track_forces: wheel must be 0 or 1");
  lk::Result r;
  std::memcpy(static_cast<void*>(&r), result, sizeof(r));  // the same layout (static_asserts above)
  const lk::TrackForces f = lk::track_forces(static_cast<lk::Wheel>(wheel), r);
  std::memcpy(forces, &f, sizeof(*forces));
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_query_slot(const railtab_lookup_table* table, int wheel,
                              const railtab_lookup_state* state, int slot,
                              railtab_lookup_contact* contact) {
  if (!table || !state || !contact)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_slot: null argument");
  if (wheel != RAILTAB_LOOKUP_LEFT && wheel != RAILTAB_LOOKUP_RIGHT)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_slot: wheel must be 0 or 1");
  if (slot < 0 || slot >= table->table.n_slots())
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT,
                "railtab_lookup_query_slot: slot outside 0 .. n_slots-1");
  lk::Contact c;
  table->table.query_slot(static_cast<lk::Wheel>(wheel), to_state(*state), slot, c);
  std::memcpy(contact, &c, sizeof(*contact));
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_error_estimate_at(const railtab_lookup_table* table, double y, int slot,
                                  railtab_lookup_error_estimate* estimate) {
  if (!table || !estimate) return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_error_estimate_at: null argument");
  if (slot < 0 || slot >= table->table.n_slots())
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_error_estimate_at: slot outside 0 .. n_slots-1");
  lk::ErrorEstimate e;
  table->table.error_estimate(y, slot, e);
  std::memcpy(static_cast<void*>(estimate), &e, sizeof(*estimate));
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_query_batch_checked(const railtab_lookup_table* table, size_t n,
                                       const int* wheels, const railtab_lookup_state* states,
                                       railtab_lookup_result* results, size_t n_results) {
  if (!table || (n > 0 && (!wheels || !states || !results)))
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_batch: null argument");
  if (n_results < n)
    return fail(RAILTAB_LOOKUP_ERROR_BUFFER,
                "railtab_lookup_query_batch: the results buffer holds fewer results than states");
  for (size_t k = 0; k < n; ++k)
    if (wheels[k] != RAILTAB_LOOKUP_LEFT && wheels[k] != RAILTAB_LOOKUP_RIGHT)
      return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT,
                  "railtab_lookup_query_batch: every wheel must be 0 or 1");
  lk::Result r;
  for (size_t k = 0; k < n; ++k) {
    table->table.query(static_cast<lk::Wheel>(wheels[k]), to_state(states[k]), r);
    store(r, &results[k]);
  }
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_query_batch(const railtab_lookup_table* table, size_t n, const int* wheels,
                               const railtab_lookup_state* states,
                               railtab_lookup_result* results) {
  return railtab_lookup_query_batch_checked(table, n, wheels, states, results, n);
}

int railtab_lookup_default_state(const railtab_lookup_table* table, railtab_lookup_state* state) {
  if (!table || !state)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_default_state: null argument");
  const lk::State s = table->table.default_state();
  *state = railtab_lookup_state{s.y, s.roll, s.load, s.xi, s.eta, s.phi, s.yaw};
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_info(const railtab_lookup_table* table, railtab_lookup_table_info* info) {
  if (!table || !info) return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_info: null argument");
  const lk::Table& t = table->table;
  info->path = t.path().c_str();
  info->format_version = t.format_version().c_str();
  info->scene_name = t.scene_name().c_str();
  info->method = static_cast<int>(t.method());
  info->n_axes = static_cast<int>(t.axes().size());
  info->n_fixed = static_cast<int>(t.fixed_axes().size());
  info->n_slots = t.n_slots();
  for (int p = 0; p < lk::kNumParts; ++p) info->has_part[p] = t.has_part(static_cast<lk::Part>(p));
  info->checksums_verified = t.checksums_verified() ? 1 : 0;
  info->memory_bytes = t.memory_bytes();
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_axis(const railtab_lookup_table* table, int index, const char** name,
                        const char** units, size_t* n_nodes, const double** nodes) {
  if (!table) return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_axis: null table");
  const auto& axes = table->table.axes();
  if (index < 0 || static_cast<size_t>(index) >= axes.size())
    return fail(RAILTAB_LOOKUP_ERROR_RANGE, "railtab_lookup_axis: index outside 0 .. n_axes-1");
  const lk::AxisInfo& a = axes[static_cast<size_t>(index)];
  if (name) *name = a.name.c_str();
  if (units) *units = a.units.c_str();
  if (n_nodes) *n_nodes = a.nodes.size();
  if (nodes) *nodes = a.nodes.data();
  return RAILTAB_LOOKUP_OK;
}

int railtab_lookup_fixed_axis(const railtab_lookup_table* table, int index, const char** name,
                              double* value) {
  if (!table) return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_fixed_axis: null table");
  const auto& fixed = table->table.fixed_axes();
  if (index < 0 || static_cast<size_t>(index) >= fixed.size())
    return fail(RAILTAB_LOOKUP_ERROR_RANGE,
                "railtab_lookup_fixed_axis: index outside 0 .. n_fixed-1");
  if (name) *name = fixed[static_cast<size_t>(index)].first.c_str();
  if (value) *value = fixed[static_cast<size_t>(index)].second;
  return RAILTAB_LOOKUP_OK;
}

const char* railtab_lookup_output_name(int output) {
  return lk::output_name(static_cast<lk::Output>(output));
}

const char* railtab_lookup_output_units(int output) {
  return lk::output_units(static_cast<lk::Output>(output));
}

int railtab_lookup_output_part(int output) {
  if (output < 0 || output >= lk::kNumOutputs) return -1;
  return static_cast<int>(lk::output_part(static_cast<lk::Output>(output)));
}

const char* railtab_lookup_part_name(int part) { return lk::part_name(static_cast<lk::Part>(part)); }

const char* railtab_lookup_slot_name(int slot) {
  static const char* const names[RAILTAB_LOOKUP_MAX_SLOTS] = {"tread", "flange", "slot2", "slot3"};
  return (slot >= 0 && slot < RAILTAB_LOOKUP_MAX_SLOTS) ? names[slot] : "?";
}

const char* railtab_lookup_var_name(int var) { return lk::variable_name(var); }

const char* railtab_lookup_status_bit_name(uint32_t bit) { return lk::status::bit_name(bit); }

size_t railtab_lookup_status_text(uint32_t status, char* buf, size_t size) {
  // Built without allocating (no exception can arise): names joined into buf as they fit.
  size_t length = 0;
  auto append = [&](const char* text) {
    for (const char* c = text; *c; ++c, ++length)
      if (buf && length + 1 < size) buf[length] = *c;
  };
  if (status == 0) append("none");
  for (unsigned b = 0; b < 32; ++b) {
    if (!(status & (1u << b))) continue;
    if (length > 0) append(",");
    if (b < static_cast<unsigned>(lk::status::kNumBits)) {
      append(lk::status::bit_name(1u << b));
    } else {
      char name[8] = {'b', 'i', 't', static_cast<char>('0' + b / 10), static_cast<char>('0' + b % 10), 0};
      append(name);
    }
  }
  if (buf && size > 0) buf[length < size ? length : size - 1] = '\0';
  return length;
}

const char* railtab_lookup_version(void) { return lk::library_version(); }

const char* railtab_lookup_format_version(void) { return lk::supported_format_version(); }

void railtab_lookup_close(railtab_lookup_table* table) { delete table; }

const char* railtab_lookup_last_error(void) { return last_error.c_str(); }

}  // extern "C"
