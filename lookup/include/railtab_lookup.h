/* railtab lookup, C API: load a wheel-rail contact table once, query it from any thread.
 *
 * Minimal surface over railtab::lookup (railtab/lookup.hpp): an opaque handle, open / query /
 * query batch / close, and a thread-local last-error string. Nothing throws across this
 * boundary: every function returns RAILTAB_LOOKUP_OK or an error code, and
 * railtab_lookup_last_error() says why (the file and the problem) on the calling thread.
 *
 * Out-of-range and NaN/inf states are NOT errors: the query succeeds, clamps to the table edge
 * (RAILTAB_LOOKUP_OUT_OF_RANGE in status) or returns zeros (RAILTAB_LOOKUP_INVALID_INPUT).
 * The result layout is identical to the C++ railtab::lookup::Result (checked at compile time).
 */
#ifndef RAILTAB_LOOKUP_H
#define RAILTAB_LOOKUP_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Return codes. */
#define RAILTAB_LOOKUP_OK 0
#define RAILTAB_LOOKUP_ERROR_LOAD 1     /* table could not be loaded (see last error) */
#define RAILTAB_LOOKUP_ERROR_ARGUMENT 2 /* null pointer, unknown wheel or method */
#define RAILTAB_LOOKUP_ERROR_INTERNAL 3 /* unexpected failure, e.g. out of memory */

/* Interpolation methods (railtab::lookup::Method). */
#define RAILTAB_LOOKUP_LINEAR 0         /* multilinear, the default */
#define RAILTAB_LOOKUP_CUBIC 1          /* tensor cubic Hermite, exact for quadratics */
#define RAILTAB_LOOKUP_MONOTONE_CUBIC 2 /* cubic Hermite, Fritsch-Carlson limited slopes */

/* Wheels. */
#define RAILTAB_LOOKUP_LEFT 0
#define RAILTAB_LOOKUP_RIGHT 1

/* Status bits (same values as src/core/status.hpp). */
#define RAILTAB_LOOKUP_CONVERGED (1u << 0)
#define RAILTAB_LOOKUP_NOT_CONVERGED (1u << 1)
#define RAILTAB_LOOKUP_TWO_POINT (1u << 2)
#define RAILTAB_LOOKUP_LIFT_OFF (1u << 3)
#define RAILTAB_LOOKUP_FLANGE_CONTACT (1u << 7)
#define RAILTAB_LOOKUP_FULL_SLIP (1u << 9)
#define RAILTAB_LOOKUP_OUT_OF_RANGE (1u << 10)
#define RAILTAB_LOOKUP_INVALID_INPUT (1u << 11)

/* Output indices into railtab_lookup_contact.value (railtab::lookup::Output). */
enum {
  RAILTAB_LOOKUP_CONTACT_ANGLE = 0, /* [rad] */
  RAILTAB_LOOKUP_ROLLING_RADIUS,    /* [m] */
  RAILTAB_LOOKUP_WHEEL_Y,           /* [m] */
  RAILTAB_LOOKUP_RAIL_Y,            /* [m] */
  RAILTAB_LOOKUP_SEPARATION,        /* [m] */
  RAILTAB_LOOKUP_CURVATURE_A,       /* [1/m] */
  RAILTAB_LOOKUP_CURVATURE_B,       /* [1/m] */
  RAILTAB_LOOKUP_NORMAL_FORCE,      /* [N] */
  RAILTAB_LOOKUP_APPROACH,          /* [m] */
  RAILTAB_LOOKUP_AREA,              /* [m2] */
  RAILTAB_LOOKUP_MAX_PRESSURE,      /* [Pa] */
  RAILTAB_LOOKUP_SEMI_AXIS_A,       /* [m] */
  RAILTAB_LOOKUP_SEMI_AXIS_B,       /* [m] */
  RAILTAB_LOOKUP_FX,                /* [N] on the wheel */
  RAILTAB_LOOKUP_FY,                /* [N] */
  RAILTAB_LOOKUP_MZ,                /* [N m] */
  RAILTAB_LOOKUP_SLIP_FRACTION,     /* [1] */
  RAILTAB_LOOKUP_WEAR_RATE,         /* [m2/m] */
  RAILTAB_LOOKUP_NUM_OUTPUTS
};
#define RAILTAB_LOOKUP_MAX_SLOTS 4
#define RAILTAB_LOOKUP_NUM_PARTS 4 /* geometry, normal, creep, wear */

/* State of one wheel-rail pair, SI. Untabulated variables must hold the table's fixed value. */
typedef struct railtab_lookup_state {
  double y;    /* [m] wheelset lateral displacement, + left */
  double roll; /* [rad] wheelset roll relative to track */
  double load; /* [N] vertical wheel load */
  double xi;   /* [1] longitudinal creepage */
  double eta;  /* [1] lateral creepage */
  double phi;  /* [rad/m] spin creepage */
} railtab_lookup_state;

typedef struct railtab_lookup_contact {
  double value[RAILTAB_LOOKUP_NUM_OUTPUTS];         /* outputs; 0 for parts not in the table */
  uint32_t part_status[RAILTAB_LOOKUP_NUM_PARTS];   /* per part, corner statuses combined */
  uint32_t status;                                  /* all parts combined + query bits */
  uint32_t reserved;                                /* explicit padding */
} railtab_lookup_contact;

typedef struct railtab_lookup_result {
  railtab_lookup_contact contact[RAILTAB_LOOKUP_MAX_SLOTS]; /* slots 0 .. n_slots-1 */
  int n_slots;                                              /* contact slots in the table */
  uint32_t status; /* query bits: RAILTAB_LOOKUP_OUT_OF_RANGE, RAILTAB_LOOKUP_INVALID_INPUT */
} railtab_lookup_result;

typedef struct railtab_lookup_table railtab_lookup_table; /* opaque */

/* Loads `path` with `method`; on success *table is a handle to close with
 * railtab_lookup_close, on failure *table is NULL. */
int railtab_lookup_open(const char* path, int method, railtab_lookup_table** table);

/* One wheel: `wheel` is RAILTAB_LOOKUP_LEFT or RAILTAB_LOOKUP_RIGHT. Thread-safe, lock-free. */
int railtab_lookup_query(const railtab_lookup_table* table, int wheel,
                         const railtab_lookup_state* state, railtab_lookup_result* result);

/* One contact slot only (0 = tread, 1 = flange): *contact receives what railtab_lookup_query
 * would put in result->contact[slot] (query bits included in contact->status), reading only
 * that slot's data. RAILTAB_LOOKUP_ERROR_ARGUMENT for a slot outside 0 .. n_slots-1. */
int railtab_lookup_query_slot(const railtab_lookup_table* table, int wheel,
                              const railtab_lookup_state* state, int slot,
                              railtab_lookup_contact* contact);

/* n states at once (e.g. both wheels of every wheelset): results[k] for wheels[k], states[k]. */
int railtab_lookup_query_batch(const railtab_lookup_table* table, size_t n, const int* wheels,
                               const railtab_lookup_state* states,
                               railtab_lookup_result* results);

/* A state with the table's fixed (untabulated) variables at their fixed values, others 0:
 * start from it and set what the table tabulates. */
int railtab_lookup_default_state(const railtab_lookup_table* table, railtab_lookup_state* state);

/* Frees the table; NULL is allowed. */
void railtab_lookup_close(railtab_lookup_table* table);

/* Message of the last failed call on this thread ("" if none). Valid until the next call. */
const char* railtab_lookup_last_error(void);

#ifdef __cplusplus
}
#endif

#endif /* RAILTAB_LOOKUP_H */
