/* rockcontact.h: the C API of rockcontact, for C, Fortran (iso_c_binding) and any language with
 * a C foreign-function interface. It wraps the pair-level C++ API
 * (rockcontact/contact/pair_contact.hpp; read it for the method and the preconditions):
 *
 *   rockcontact_params params;
 *   rockcontact_default_params(&params);             kn = 1e7 Pa, H = 1 m, Filtered, exact
 *   params.kn = 1e8;
 *   rockcontact_evaluator* contact;
 *   if (rockcontact_evaluator_create(&params, &contact) != ROCKCONTACT_OK) {
 *     fprintf(stderr, "%s\n", rockcontact_last_error());
 *   }
 *   rockcontact_pair_result r;
 *   int status = rockcontact_evaluate_pair(contact, a_xy, a_n, a_pose, b_xy, b_n, b_pose, &r);
 *   ...
 *   rockcontact_evaluator_destroy(contact);
 *
 * Units: SI per metre of thickness. Lengths m, angles rad, kn Pa, forces N/m, areas m².
 *
 * Errors: every function that can fail returns a rockcontact_error; on failure it writes
 * nothing to its outputs and rockcontact_last_error() gives the message, which names the
 * polygon ("a" or "b"), the vertex and what was expected. No C++ exception crosses this
 * boundary.
 *
 * Memory and threads: an evaluator owns its workspace; after the first pairs it evaluates
 * without allocating under ROCKCONTACT_POLICY_FLOAT and ROCKCONTACT_POLICY_FILTERED (see
 * pair_contact.hpp). One evaluator must not be used by two threads at once; distinct
 * evaluators may run concurrently. The last-error message is per thread.
 *
 * ABI: the structs below hold only int32_t, int64_t and double, in an order without padding
 * surprises, so a Fortran `type, bind(C)` with integer(c_int32_t), integer(c_int64_t) and
 * real(c_double) components in the same order matches them. */
#ifndef ROCKCONTACT_H
#define ROCKCONTACT_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rockcontact_error {
  ROCKCONTACT_OK = 0,
  ROCKCONTACT_ERROR_INVALID_ARGUMENT = 1, /* a null pointer, a count < 3, a non-finite pose,
                                             a parameter out of range */
  ROCKCONTACT_ERROR_INVALID_POLYGON = 2,  /* not a strictly convex CCW polygon (after its pose) */
  ROCKCONTACT_ERROR_OUT_OF_MEMORY = 3,
  ROCKCONTACT_ERROR_INTERNAL = 4          /* a bug: please report it with the message */
} rockcontact_error;

enum {
  ROCKCONTACT_POLICY_FLOAT = 0,    /* plain double: fast, may be wrong on degenerate input */
  ROCKCONTACT_POLICY_FILTERED = 1, /* exact decisions, double constructions: the default */
  ROCKCONTACT_POLICY_EXACT = 2     /* GMP rationals, rounded once: the reference */
};

enum {
  ROCKCONTACT_DEMARCATION_EXACT = 0, /* the true kinks of the potential: exact integration */
  ROCKCONTACT_DEMARCATION_PAPER = 1  /* the paper's bisector construction (seed 000 §3.2.3) */
};

enum { ROCKCONTACT_SEPARATE = 0, ROCKCONTACT_TOUCH = 1, ROCKCONTACT_OVERLAP = 2 };

typedef struct rockcontact_params {
  double kn;                  /* normal penalty, Pa, > 0 */
  double H;                   /* potential length scale, m, > 0 */
  double small_edge_fraction; /* paper demarcation only: short-edge threshold as a fraction of H */
  int32_t policy;             /* ROCKCONTACT_POLICY_* */
  int32_t demarcation;        /* ROCKCONTACT_DEMARCATION_* */
} rockcontact_params;

typedef struct rockcontact_pair_result {
  int32_t status;      /* ROCKCONTACT_SEPARATE, _TOUCH or _OVERLAP */
  int32_t has_point;   /* 1 when the blocks overlap with a non-zero force, else 0 */
  double force[2];     /* normal force on a, N/m, world frame; on b it is -force */
  double point[2];     /* contact point, m, world frame; meaningful only when has_point */
  double area;         /* intersection polygon area, m² */
  double penetration;  /* minimum translation distance separating a and b, m; 0 unless overlap */
  int64_t predicates;  /* predicate calls spent on the pair */
  int64_t fallbacks;   /* of which re-evaluated exactly */
} rockcontact_pair_result;

typedef struct rockcontact_evaluator rockcontact_evaluator; /* opaque */

/* The library version, "MAJOR.MINOR.PATCH". */
const char* rockcontact_version(void);

/* kn = 1e7 Pa, H = 1 m, small_edge_fraction = 0.1, Filtered, exact demarcation. */
void rockcontact_default_params(rockcontact_params* params);

/* Creates an evaluator; *out is set only on success. Fails with INVALID_ARGUMENT on a null
 * pointer, an unknown policy or demarcation, kn or H not finite and > 0. */
rockcontact_error rockcontact_evaluator_create(const rockcontact_params* params,
                                               rockcontact_evaluator** out);

/* Destroys an evaluator; a null pointer is ignored. */
void rockcontact_evaluator_destroy(rockcontact_evaluator* evaluator);

/* The contact of polygon a with polygon b. a_xy holds 2 * a_count doubles, the local vertex
 * coordinates x0, y0, x1, y1, ... counter-clockwise and strictly convex; a_pose holds x, y
 * (m) and theta (rad): local v -> (x, y) + R(theta) v; a null pose is the identity (a_xy are
 * then world coordinates). The same for b. */
rockcontact_error rockcontact_evaluate_pair(rockcontact_evaluator* evaluator,
                                            const double* a_xy, int32_t a_count,
                                            const double* a_pose, const double* b_xy,
                                            int32_t b_count, const double* b_pose,
                                            rockcontact_pair_result* result);

/* The intersection polygon of the evaluator's last successful rockcontact_evaluate_pair (m,
 * world frame, counter-clockwise; no vertex unless it said ROCKCONTACT_OVERLAP). Sets *count to
 * the number of vertices and, when it is at most `capacity`, writes x0, y0, x1, y1, ... into xy
 * (2 * capacity doubles); otherwise writes nothing to xy and fails with INVALID_ARGUMENT, so a
 * caller can ask with capacity 0 first. xy may be null when capacity is 0. */
rockcontact_error rockcontact_intersection_polygon(const rockcontact_evaluator* evaluator,
                                                   double* xy, int32_t capacity, int32_t* count);

/* The message of the last failed call on this thread ("" if none): NUL-terminated, valid
 * until the next call into the library on this thread. */
const char* rockcontact_last_error(void);

/* A short fixed description of an error code, e.g. "invalid polygon". */
const char* rockcontact_error_string(rockcontact_error code);

#ifdef __cplusplus
}
#endif

#endif /* ROCKCONTACT_H */
