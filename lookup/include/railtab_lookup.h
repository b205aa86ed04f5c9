// SPDX-License-Identifier: Apache-2.0
/* railtab lookup, C API: load a wheel-rail contact table once, query it from any thread.
 *
 * Surface over railtab::lookup (railtab/lookup.hpp): an opaque handle, open / query / query
 * batch / close, introspection (axes, fixed axes, slots, parts, outputs, versions), status bit
 * names, and a thread-local last-error string. Nothing throws across this boundary: every
 * function returns RAILTAB_LOOKUP_OK or an error code, and railtab_lookup_last_error() says why
 * (the file and the problem) on the calling thread.
 *
 * Link (docs/lookup.md): with CMake, find_package(railtab) and railtab::lookup; from plain C,
 *   cc sim.c $(pkg-config --cflags --libs railtab_lookup)
 * (the static library needs -lstdc++ -lm and HDF5; pkg-config lists them).
 *
 * Out-of-range and NaN/inf states are NOT errors: the query succeeds, clamps to the table edge
 * (RAILTAB_LOOKUP_OUT_OF_RANGE in status) or returns zeros (RAILTAB_LOOKUP_INVALID_INPUT).
 * The result layout is identical to the C++ railtab::lookup::Result (checked at compile time).
 */
#ifndef RAILTAB_LOOKUP_H
#define RAILTAB_LOOKUP_H

#include <stddef.h>
#include <stdint.h>

#include "railtab/lookup_export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Return codes. */
#define RAILTAB_LOOKUP_OK 0
#define RAILTAB_LOOKUP_ERROR_LOAD 1     /* table could not be loaded (see last error) */
#define RAILTAB_LOOKUP_ERROR_ARGUMENT 2 /* null pointer, unknown wheel or method */
#define RAILTAB_LOOKUP_ERROR_INTERNAL 3 /* unexpected failure, e.g. out of memory */
#define RAILTAB_LOOKUP_ERROR_BUFFER 4   /* an output buffer is too short (nothing written) */
#define RAILTAB_LOOKUP_ERROR_RANGE 5    /* an index (axis, fixed axis, slot) out of range */
#define RAILTAB_LOOKUP_ERROR_NOT_IN_TABLE 6 /* the table does not hold what was asked (creep
                                              coefficients of a table before format 2.3) */

/* Load options for railtab_lookup_open_options (bit flags). */
#define RAILTAB_LOOKUP_REQUIRE_CHECKSUMS 1u /* refuse tables without dataset checksums */

/* Interpolation methods (railtab::lookup::Method). */
#define RAILTAB_LOOKUP_LINEAR 0         /* multilinear, the default */
#define RAILTAB_LOOKUP_CUBIC 1          /* tensor cubic Hermite, exact for quadratics */
#define RAILTAB_LOOKUP_MONOTONE_CUBIC 2 /* cubic Hermite, Fritsch-Carlson limited slopes */

/* Wheels. */
#define RAILTAB_LOOKUP_LEFT 0
#define RAILTAB_LOOKUP_RIGHT 1

/* Status bits (same values as src/core/status.hpp and railtab::lookup::status); names as in
 * the table files: railtab_lookup_status_bit_name / railtab_lookup_status_text. */
#define RAILTAB_LOOKUP_CONVERGED (1u << 0)         /* solver met its tolerance (all corners) */
#define RAILTAB_LOOKUP_NOT_CONVERGED (1u << 1)     /* iteration limit hit at some node */
#define RAILTAB_LOOKUP_TWO_POINT (1u << 2)         /* more than one contact on this wheel */
#define RAILTAB_LOOKUP_LIFT_OFF (1u << 3)          /* no contact at this load/approach */
#define RAILTAB_LOOKUP_CURVATURE_CLIPPED (1u << 4) /* negative/small B clipped */
#define RAILTAB_LOOKUP_CURVATURE_SHIFTED (1u << 5) /* negative/small B shifted upward */
#define RAILTAB_LOOKUP_FALLBACK_MODEL (1u << 6)    /* the chosen model failed; a simpler ran */
#define RAILTAB_LOOKUP_FLANGE_CONTACT (1u << 7)    /* contact angle beyond the tread range */
#define RAILTAB_LOOKUP_NON_HERTZIAN (1u << 8)      /* A or B <= 0: Hertz invalid */
#define RAILTAB_LOOKUP_FULL_SLIP (1u << 9)         /* tangential force saturated at mu*N */
#define RAILTAB_LOOKUP_OUT_OF_RANGE (1u << 10)     /* query clamped to the table edge */
#define RAILTAB_LOOKUP_INVALID_INPUT (1u << 11)    /* NaN/inf in the query: outputs are 0 */
#define RAILTAB_LOOKUP_PROFILE_EDGE (1u << 12)     /* contact band reached a profile end */
#define RAILTAB_LOOKUP_FAILED (1u << 13)           /* the core threw at a node: outputs 0 */
#define RAILTAB_LOOKUP_AREA_TOO_SMALL (1u << 14)   /* half-space: contact reached the potential area's edge */
#define RAILTAB_LOOKUP_NOT_PLANAR (1u << 15)       /* half-space: contact angle varies across the patch */
#define RAILTAB_LOOKUP_NEAR_EQUAL_MINIMA (1u << 16) /* geometry: two near-equal rigid gap minima, the point may jump */
#define RAILTAB_LOOKUP_CURVATURE_STEP (1u << 17)   /* geometry: a profile radius transition at the point: B steps */
#define RAILTAB_LOOKUP_LOW_CONFIDENCE (1u << 18)   /* the query's cell spans a change the table does not resolve */
#define RAILTAB_LOOKUP_NUM_STATUS_BITS 19

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

/* Parts (railtab::lookup::Part). */
#define RAILTAB_LOOKUP_GEOMETRY 0
#define RAILTAB_LOOKUP_NORMAL 1
#define RAILTAB_LOOKUP_CREEP 2
#define RAILTAB_LOOKUP_WEAR 3

/* State of one wheel-rail pair, SI. Untabulated variables must hold the table's fixed value. */
typedef struct railtab_lookup_state {
  double y;    /* [m] wheelset lateral displacement, + left */
  double roll; /* [rad] wheelset roll relative to track */
  double load; /* [N] vertical wheel load */
  double xi;   /* [1] longitudinal creepage */
  double eta;  /* [1] lateral creepage */
  double phi;  /* [rad/m] spin creepage */
  double yaw;  /* [rad] wheelset yaw (angle of attack) relative to track, + forward axis to the
                  left; last, so older positional initialisers keep their meaning (yaw 0) */
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

/* State variables as indices (railtab::lookup::Variable): the last index of
 * railtab_lookup_derivatives.d; names by railtab_lookup_var_name. */
enum {
  RAILTAB_LOOKUP_VAR_Y = 0, /* [m] */
  RAILTAB_LOOKUP_VAR_ROLL,  /* [rad] */
  RAILTAB_LOOKUP_VAR_LOAD,  /* [N] */
  RAILTAB_LOOKUP_VAR_XI,    /* [1] */
  RAILTAB_LOOKUP_VAR_ETA,   /* [1] */
  RAILTAB_LOOKUP_VAR_PHI,   /* [rad/m] */
  RAILTAB_LOOKUP_VAR_YAW,   /* [rad] (last, as in the state struct) */
  RAILTAB_LOOKUP_NUM_VARS
};

/* Partial derivatives of every output of every slot with respect to each state variable, exact
 * for the table's interpolant, SI (output units per variable unit): d[slot][output][var], e.g.
 * d[0][RAILTAB_LOOKUP_FX][RAILTAB_LOOKUP_VAR_XI] in N. 0 for a variable the table does not
 * tabulate or that was clamped to the table's range (docs/lookup.md, "Derivatives"). */
typedef struct railtab_lookup_derivatives {
  double d[RAILTAB_LOOKUP_MAX_SLOTS][RAILTAB_LOOKUP_NUM_OUTPUTS][RAILTAB_LOOKUP_NUM_VARS];
} railtab_lookup_derivatives;

/* One slot's derivatives (railtab_lookup_query_slot_derivatives): railtab_lookup_derivatives.d[slot]. */
typedef struct railtab_lookup_slot_derivatives {
  double d[RAILTAB_LOOKUP_NUM_OUTPUTS][RAILTAB_LOOKUP_NUM_VARS];
} railtab_lookup_slot_derivatives;

/* Forces of the rail on one wheel in track axes (x forward, y left, z up), from one query result
 * (railtab::lookup::TrackForces; docs/conventions.md, "Track-frame forces and Y/Q"). Per loaded
 * slot (normal force > 0), with g its contact angle: lateral = -N sin g + fy cos g, vertical =
 * N cos g + fy sin g; a loaded slot without its rigid point (rolling radius 0) takes the other
 * slot's angle. y_force (Y) and q_force (Q) are the wheel's forces ON ITS RAIL: Y + towards that
 * rail's field side (flange contact: Y > 0 on either wheel), Q + down. */
typedef struct railtab_lookup_track_forces {
  double lateral[RAILTAB_LOOKUP_MAX_SLOTS];       /* [N] per slot, on the wheel along track y */
  double vertical[RAILTAB_LOOKUP_MAX_SLOTS];      /* [N] per slot, on the wheel along track z */
  double contact_angle[RAILTAB_LOOKUP_MAX_SLOTS]; /* [rad] per slot: the angle rotated with */
  double wheel_lateral;                           /* [N] sum over the slots */
  double wheel_vertical;                          /* [N] sum over the slots */
  double y_force;                                 /* [N] Y = -sigma wheel_lateral (sigma +1 left, -1 right) */
  double q_force;                                 /* [N] Q = wheel_vertical */
  double y_over_q;                                /* [1] Y / Q; 0 when Q <= 0 */
} railtab_lookup_track_forces;

/* Linear creep coefficients of every slot (railtab::lookup::CreepCoefficients; tables of format
 * 2.3, docs/lookup.md "Linear creep coefficients"): k[slot][force][creepage] = d force / d creepage
 * at zero creepage in full adhesion, force RAILTAB_LOOKUP_CREEP_FX/_FY/_MZ (on the wheel),
 * creepage RAILTAB_LOOKUP_VAR_XI/_ETA/_PHI minus RAILTAB_LOOKUP_VAR_XI. Units: fx, fy per xi or
 * eta N; per phi N m; mz per xi or eta N m; per phi N m2. */
enum { RAILTAB_LOOKUP_CREEP_FX = 0, RAILTAB_LOOKUP_CREEP_FY = 1, RAILTAB_LOOKUP_CREEP_MZ = 2 };
typedef struct railtab_lookup_creep_coefficients {
  double k[RAILTAB_LOOKUP_MAX_SLOTS][3][3]; /* [slot][force][creepage]; 0 for an empty slot */
  uint32_t status[RAILTAB_LOOKUP_MAX_SLOTS]; /* per slot: the normal part's status at the state */
  uint32_t query_status; /* RAILTAB_LOOKUP_OUT_OF_RANGE, RAILTAB_LOOKUP_INVALID_INPUT */
  int n_slots;           /* contact slots in the table */
} railtab_lookup_creep_coefficients;

typedef struct railtab_lookup_table railtab_lookup_table; /* opaque */

/* Loads `path` with `method`; on success *table is a handle to close with
 * railtab_lookup_close, on failure *table is NULL. A shard file (`railtab generate --shard`),
 * a corrupt file or one that fails a checksum is RAILTAB_LOOKUP_ERROR_LOAD, and so is a format-1.0
 * table (no metadata checksums). A table with checksummed metadata but no dataset checksums
 * (another tool's) loads with info.checksums_verified = 0. */
RAILTAB_LOOKUP_API int railtab_lookup_open(const char* path, int method, railtab_lookup_table** table);
/* As railtab_lookup_open with option flags (RAILTAB_LOOKUP_REQUIRE_CHECKSUMS). */
RAILTAB_LOOKUP_API int railtab_lookup_open_options(const char* path, int method, unsigned flags,
                                railtab_lookup_table** table);

/* One wheel: `wheel` is RAILTAB_LOOKUP_LEFT or RAILTAB_LOOKUP_RIGHT. Thread-safe, lock-free. */
RAILTAB_LOOKUP_API int railtab_lookup_query(const railtab_lookup_table* table, int wheel,
                         const railtab_lookup_state* state, railtab_lookup_result* result);

/* One contact slot only (0 = tread, 1 = flange): *contact receives what railtab_lookup_query
 * would put in result->contact[slot] (query bits included in contact->status), reading only
 * that slot's data. RAILTAB_LOOKUP_ERROR_ARGUMENT for a slot outside 0 .. n_slots-1. */
RAILTAB_LOOKUP_API int railtab_lookup_query_slot(const railtab_lookup_table* table, int wheel,
                              const railtab_lookup_state* state, int slot,
                              railtab_lookup_contact* contact);

/* As railtab_lookup_query, plus the partial derivatives of every output. Tables opened with
 * RAILTAB_LOOKUP_LINEAR or RAILTAB_LOOKUP_CUBIC; with RAILTAB_LOOKUP_MONOTONE_CUBIC it returns
 * RAILTAB_LOOKUP_ERROR_ARGUMENT (the last error says so) and writes nothing. */
RAILTAB_LOOKUP_API int railtab_lookup_query_derivatives(const railtab_lookup_table* table, int wheel,
                                     const railtab_lookup_state* state, railtab_lookup_result* result,
                                     railtab_lookup_derivatives* derivatives);

/* One slot's twin of railtab_lookup_query_derivatives (as railtab_lookup_query_slot is
 * railtab_lookup_query's): `contact` and `derivatives` receive its contact[slot] and d[slot],
 * reading only that slot's records. RAILTAB_LOOKUP_ERROR_ARGUMENT for a slot outside
 * 0 .. n_slots-1, a bad wheel or a RAILTAB_LOOKUP_MONOTONE_CUBIC table. */
RAILTAB_LOOKUP_API int railtab_lookup_query_slot_derivatives(const railtab_lookup_table* table, int wheel,
                                          const railtab_lookup_state* state, int slot,
                                          railtab_lookup_contact* contact,
                                          railtab_lookup_slot_derivatives* derivatives);

/* The linear creep coefficients of `wheel` at the state's (y, roll, load) (its creepages are not
 * used). RAILTAB_LOOKUP_ERROR_NOT_IN_TABLE, nothing written, for a table without them (format 2.2
 * and older; the last error says so); railtab_lookup_has_creep_coefficients tells beforehand
 * (1 yes, 0 no or a null table). */
RAILTAB_LOOKUP_API int railtab_lookup_query_creep_coefficients(const railtab_lookup_table* table, int wheel,
                                            const railtab_lookup_state* state,
                                            railtab_lookup_creep_coefficients* coefficients);
RAILTAB_LOOKUP_API int railtab_lookup_has_creep_coefficients(const railtab_lookup_table* table);

/* 1 when the table stores the non-negative half of a symmetric yaw axis (root attribute
 * yaw_symmetry = "even", docs/table-format.md): railtab_lookup_axis lists yaw from 0 and a query
 * reads |yaw| (-yaw gives +yaw's values). 0 otherwise (no yaw axis, a whole one) or a null table. */
RAILTAB_LOOKUP_API int railtab_lookup_yaw_even(const railtab_lookup_table* table);

/* Track-frame forces and Y/Q of `wheel` from `result` (a railtab_lookup_query of that wheel):
 * railtab::lookup::track_forces. RAILTAB_LOOKUP_ERROR_ARGUMENT for a null pointer or a bad wheel. */
RAILTAB_LOOKUP_API int railtab_lookup_compute_track_forces(int wheel, const railtab_lookup_result* result,
                                        railtab_lookup_track_forces* forces);

/* n states at once (e.g. both wheels of every wheelset): results[k] for wheels[k], states[k].
 * `results` must hold n results. */
RAILTAB_LOOKUP_API int railtab_lookup_query_batch(const railtab_lookup_table* table, size_t n, const int* wheels,
                               const railtab_lookup_state* states,
                               railtab_lookup_result* results);
/* As railtab_lookup_query_batch with the capacity of `results`: n_results < n is
 * RAILTAB_LOOKUP_ERROR_BUFFER and nothing is written (never a silent truncation). */
RAILTAB_LOOKUP_API int railtab_lookup_query_batch_checked(const railtab_lookup_table* table, size_t n,
                                       const int* wheels, const railtab_lookup_state* states,
                                       railtab_lookup_result* results, size_t n_results);

/* A state with the table's fixed (untabulated) variables at their fixed values, others 0:
 * start from it and set what the table tabulates. */
RAILTAB_LOOKUP_API int railtab_lookup_default_state(const railtab_lookup_table* table, railtab_lookup_state* state);

/* ---- Introspection. Strings and node arrays stay valid until railtab_lookup_close. ---- */

typedef struct railtab_lookup_table_info {
  const char* path;            /* file it was loaded from */
  const char* format_version;  /* e.g. "2.0" */
  const char* scene_name;      /* "" if absent */
  int method;                  /* RAILTAB_LOOKUP_LINEAR, ... */
  int n_axes;                  /* tabulated state variables: railtab_lookup_axis 0 .. n_axes-1 */
  int n_fixed;                 /* fixed ones: railtab_lookup_fixed_axis 0 .. n_fixed-1 */
  int n_slots;                 /* contact slots (0 = tread, 1 = flange) */
  int has_part[RAILTAB_LOOKUP_NUM_PARTS]; /* 1 if the table holds geometry, normal, creep, wear */
  int checksums_verified;      /* 1: every dataset and the metadata were checksum-verified */
  size_t memory_bytes;         /* interpolation data in memory */
} railtab_lookup_table_info;

RAILTAB_LOOKUP_API int railtab_lookup_info(const railtab_lookup_table* table, railtab_lookup_table_info* info);

/* ---- Error estimate (format 2.3, group /error_map; docs/lookup.md "Error estimate"). ----
 * The measured errors of the region (y band x slot) holding y: RMS and maximum over the region's
 * samples, indexed RAILTAB_LOOKUP_ERR_*: fx, fy [% of mu N], mz [% of mu N c, c = sqrt(area/pi)],
 * normal force [% of N], contact angle [rad]; NaN where the region has no sample. */
#define RAILTAB_LOOKUP_ERR_FX 0
#define RAILTAB_LOOKUP_ERR_FY 1
#define RAILTAB_LOOKUP_ERR_MZ 2
#define RAILTAB_LOOKUP_ERR_NORMAL_FORCE 3
#define RAILTAB_LOOKUP_ERR_CONTACT_ANGLE 4
#define RAILTAB_LOOKUP_NUM_ERR 5
typedef struct railtab_lookup_error_stats {
  double samples;                       /* wheel-state pairs with the slot loaded (0: none) */
  double rms[RAILTAB_LOOKUP_NUM_ERR];
  double max[RAILTAB_LOOKUP_NUM_ERR];
} railtab_lookup_error_stats;
typedef struct railtab_lookup_error_estimate {
  int available;       /* 1: the table has an error map and y lies in one of its bands */
  int exact_measured;  /* 1: model_vs_exact holds the model against the exact half-space model */
  int same_model;      /* 1: the table's model is the exact one (nothing to compare; not a zero) */
  int reserved;
  double y_band_start, y_band_end;              /* [m] the band holding y */
  railtab_lookup_error_stats table_vs_model;    /* the table (linear lookup) against its model */
  railtab_lookup_error_stats model_vs_exact;    /* the model against the exact model */
} railtab_lookup_error_estimate;
/* Fills `estimate` (available 0 when the table has no error map or y is NaN or outside its
 * bands: still RAILTAB_LOOKUP_OK). RAILTAB_LOOKUP_ERROR_ARGUMENT for a null pointer or a slot
 * outside 0 .. n_slots-1. */
RAILTAB_LOOKUP_API int railtab_lookup_error_estimate_at(const railtab_lookup_table* table, double y, int slot,
                                                     railtab_lookup_error_estimate* estimate);

/* Tabulated axis `index` (file order): name ("y", "roll", "yaw", "load", "xi", "eta", "phi"), units
 * (the file's attribute, "" if absent), node count and nodes (strictly increasing, SI). Any of
 * the output pointers may be NULL. RAILTAB_LOOKUP_ERROR_RANGE for an index outside the axes. */
RAILTAB_LOOKUP_API int railtab_lookup_axis(const railtab_lookup_table* table, int index, const char** name,
                        const char** units, size_t* n_nodes, const double** nodes);

/* Fixed (untabulated) variable `index`: name and its value, SI (roll following the
 * equilibrium is neither an axis nor fixed). */
RAILTAB_LOOKUP_API int railtab_lookup_fixed_axis(const railtab_lookup_table* table, int index, const char** name,
                              double* value);

/* Static names (never NULL; "?" or "" for a value out of range): output dataset name and
 * units, the part an output belongs to (-1 if out of range), part group name, slot name
 * ("tread", "flange"). */
RAILTAB_LOOKUP_API const char* railtab_lookup_output_name(int output);
RAILTAB_LOOKUP_API const char* railtab_lookup_output_units(int output);
RAILTAB_LOOKUP_API int railtab_lookup_output_part(int output);
RAILTAB_LOOKUP_API const char* railtab_lookup_part_name(int part);
RAILTAB_LOOKUP_API const char* railtab_lookup_slot_name(int slot);
/* Name of a state variable ("y", "roll", "load", "xi", "eta", "phi", "yaw"; "?" out of range). */
RAILTAB_LOOKUP_API const char* railtab_lookup_var_name(int var);

/* Name of one status bit ("converged", "two_point", ...; "unknown" if not a single defined bit). */
RAILTAB_LOOKUP_API const char* railtab_lookup_status_bit_name(uint32_t bit);
/* Comma-separated names of the set bits ("converged,two_point"; "none" for 0) into buf, NUL
 * terminated. Returns the length of the full text (as snprintf): a return >= size means buf was
 * too short and holds a truncated, still terminated, text. buf may be NULL when size is 0. */
RAILTAB_LOOKUP_API size_t railtab_lookup_status_text(uint32_t status, char* buf, size_t size);

/* Library version ("0.1.0") and the newest table format it reads ("2.1"). */
RAILTAB_LOOKUP_API const char* railtab_lookup_version(void);
RAILTAB_LOOKUP_API const char* railtab_lookup_format_version(void);

/* Frees the table; NULL is allowed. */
RAILTAB_LOOKUP_API void railtab_lookup_close(railtab_lookup_table* table);

/* Message of the last failed call on this thread ("" if none). Valid until the next call. */
RAILTAB_LOOKUP_API const char* railtab_lookup_last_error(void);

#ifdef __cplusplus
}
#endif

#endif /* RAILTAB_LOOKUP_H */
