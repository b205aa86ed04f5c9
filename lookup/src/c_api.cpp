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
static_assert(offsetof(railtab_lookup_state, phi) == offsetof(lk::State, phi));
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
static_assert(RAILTAB_LOOKUP_OUT_OF_RANGE == lk::status::kOutOfRange);
static_assert(RAILTAB_LOOKUP_INVALID_INPUT == lk::status::kInvalidInput);

thread_local std::string last_error;

int fail(int code, const char* message) noexcept {
  try {
    last_error = message;
  } catch (...) {  // assigning may allocate; keep the code even if the message is lost
  }
  return code;
}

lk::State to_state(const railtab_lookup_state& s) noexcept {
  return lk::State{s.y, s.roll, s.load, s.xi, s.eta, s.phi};
}

void store(const lk::Result& r, railtab_lookup_result* out) noexcept {
  std::memcpy(out, &r, sizeof(*out));
}

}  // namespace

extern "C" {

int railtab_lookup_open(const char* path, int method, railtab_lookup_table** table) {
  if (table) *table = nullptr;
  if (!path || !table) return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_open: null argument");
  if (method < RAILTAB_LOOKUP_LINEAR || method > RAILTAB_LOOKUP_MONOTONE_CUBIC)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_open: unknown interpolation method");
  try {
    lk::LoadOptions options;
    options.method = static_cast<lk::Method>(method);
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

int railtab_lookup_query_batch(const railtab_lookup_table* table, size_t n, const int* wheels,
                               const railtab_lookup_state* states,
                               railtab_lookup_result* results) {
  if (!table || (n > 0 && (!wheels || !states || !results)))
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_query_batch: null argument");
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

int railtab_lookup_default_state(const railtab_lookup_table* table, railtab_lookup_state* state) {
  if (!table || !state)
    return fail(RAILTAB_LOOKUP_ERROR_ARGUMENT, "railtab_lookup_default_state: null argument");
  const lk::State s = table->table.default_state();
  *state = railtab_lookup_state{s.y, s.roll, s.load, s.xi, s.eta, s.phi};
  return RAILTAB_LOOKUP_OK;
}

void railtab_lookup_close(railtab_lookup_table* table) { delete table; }

const char* railtab_lookup_last_error(void) { return last_error.c_str(); }

}  // extern "C"
