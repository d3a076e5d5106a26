/* rockcontact.h: the C API of rockcontact, for C, Fortran (iso_c_binding) and any language with
 * a C foreign-function interface. It wraps the pair-level C++ API
 * (rockcontact/contact/embed/pair_contact.hpp and, for friction, pair_friction.hpp; read them for the
 * method and the preconditions):
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
 * Friction: the host keeps one rockcontact_friction_state per contacting pair, zeroed when the
 * pair starts touching, and after each rockcontact_evaluate_pair of that pair calls
 *   rockcontact_evaluate_friction(&friction_params, &r, increment, &state, &t);
 * to get the tangential force t.force (applied with r.force at r.point). See
 * rockcontact_evaluate_friction below.
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
 * surprises (int32_t fields come in pairs or are followed by an explicit `reserved` one, so every
 * struct's size is a multiple of 8 with no implicit padding), so a Fortran `type, bind(C)` with
 * integer(c_int32_t), integer(c_int64_t) and real(c_double) components in the same order matches
 * them. New members are appended at the end of a struct; that changes its size, so a host must
 * be recompiled against the header of the library it links (docs/CHANGELOG.md lists such
 * changes). */
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
  ROCKCONTACT_ERROR_INTERNAL = 4,         /* a bug: please report it with the message */
  ROCKCONTACT_ERROR_INVALID_POLYHEDRON = 5 /* 3D: not a valid convex polyhedron (the message names
                                              the block "a" or "b", the face and the vertex) */
} rockcontact_error;

enum {
  ROCKCONTACT_POLICY_FLOAT = 0,    /* plain double: fast, may be wrong on degenerate input */
  ROCKCONTACT_POLICY_FILTERED = 1, /* exact decisions, double constructions: the default */
  ROCKCONTACT_POLICY_EXACT = 2,    /* exact rationals, rounded once: the reference */
  ROCKCONTACT_POLICY_CHECKED = 3   /* filtered, every sign also checked exactly; a disagreement
                                      is ROCKCONTACT_ERROR_INTERNAL with the predicate's input */
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
  double length;       /* contact length L, m: half the perimeter of the intersection polygon
                          (the L of the cohesion term); 0 unless overlap */
} rockcontact_pair_result;

enum {
  ROCKCONTACT_FRICTION_ELASTOPLASTIC = 0, /* persistent tangential spring, capped: the default */
  ROCKCONTACT_FRICTION_PAPER = 1          /* the paper's stick/slide law (seed 000 eq. 24-26) */
};

typedef struct rockcontact_friction_params {
  double kt;                 /* tangential penalty, N/m per metre of thickness, finite > 0 */
  double friction_angle_deg; /* phi, degrees, in [0, 90) */
  double cohesion;           /* c, Pa, finite >= 0 */
  int32_t model;             /* ROCKCONTACT_FRICTION_* */
  int32_t reserved;          /* explicit padding; ignored */
} rockcontact_friction_params;

/* The friction history of one contacting pair, stored by the host between calls (an array of
 * them beside its contact list, say). Opaque but copyable: move it with its pair, never edit
 * its fields. All zero (memset, `= {0}`) is a new contact: in stick, nothing stretched. */
typedef struct rockcontact_friction_state {
  double displacement[2]; /* the law's stretch or accumulated displacement, m */
  double force[2];        /* the last tangential force on a, N/m */
  double normal[2];       /* the unit normal of the last evaluation (elastoplastic) */
  int32_t sliding;        /* 1 when the last evaluation was at the limit */
  int32_t in_contact;     /* 1 once a call has found the pair in contact */
} rockcontact_friction_state;

typedef struct rockcontact_friction_result {
  double force[2];   /* tangential force on a, N/m, world frame, at the contact point; on b it
                        is -force */
  double dissipated; /* energy the slip dissipated since the previous call, J/m */
  int32_t sliding;   /* 1 when |force| is at the limit |f_n| tan(phi) + c L, else 0 */
  int32_t reserved;  /* explicit padding; written as 0 */
} rockcontact_friction_result;

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

/* kt = 1e7 N/m per metre of thickness, phi = 0 (frictionless), no cohesion, elastoplastic. */
void rockcontact_default_friction_params(rockcontact_friction_params* params);

/* The friction of a pair at the evaluation `contact` (the result of rockcontact_evaluate_pair
 * just made for that pair), given the pair's stored `state` and the relative displacement
 * increment of the contact point since the previous call: increment[2] = Δu_a(p) - Δu_b(p), the
 * displacement of a's material point at the previous contact point p minus b's, m, world frame
 * (for instance (v_a(p) - v_b(p)) dt). Writes the force to *result and updates *state:
 *   - contact->has_point = 1, first call (state zero): the spring starts unstretched; the
 *     increment is ignored;
 *   - contact->has_point = 1 after that: the state moves by the increment, and the force is the
 *     law's (pair_friction.hpp, friction.hpp), at most |f_n| tan(phi) + c L;
 *   - contact->has_point = 0: the pair has separated; the state is reset to zero and the force
 *     is zero. The host may as well drop the state.
 * Fails with INVALID_ARGUMENT, writing nothing to *state or *result, on a null pointer, an
 * unknown model, kt not finite and > 0, phi not in [0, 90), a cohesion not finite and >= 0, a
 * non-finite increment or contact force, or a contact length not finite and >= 0; the message
 * names the field. */
rockcontact_error rockcontact_evaluate_friction(const rockcontact_friction_params* params,
                                                const rockcontact_pair_result* contact,
                                                const double* increment,
                                                rockcontact_friction_state* state,
                                                rockcontact_friction_result* result);

/* The message of the last failed call on this thread ("" if none): NUL-terminated, valid
 * until the next call into the library on this thread. */
const char* rockcontact_last_error(void);

/* A short fixed description of an error code, e.g. "invalid polygon". */
const char* rockcontact_error_string(rockcontact_error code);

/* ---- 3D: convex polyhedra (rockcontact/contact/generalized3d/pair_contact3d.hpp) ----------
 *
 *   rockcontact_params3d params;
 *   rockcontact_default_params3d(&params);           kn = 1e9 N/m, tolerance 0, Filtered
 *   rockcontact_evaluator3d* contact;
 *   rockcontact_evaluator3d_create(&params, &contact);
 *   rockcontact_pair3d_result r;
 *   rockcontact_evaluate_pair3d(contact, a_xyz, a_count, a_face_sizes, a_faces, a_face_count,
 *                               b_xyz, ..., &r);
 *   rockcontact_constraint3d c[16]; int32_t n;
 *   rockcontact_pair3d_constraints(contact, c, 16, &n);   the r.constraint_count constraints
 *   rockcontact_evaluator3d_destroy(contact);
 *
 * A polyhedron is given in world coordinates, m: xyz holds 3 * count doubles x0, y0, z0, x1, ...;
 * face_sizes[f] is the number of vertices of face f and faces lists the faces' vertex indices
 * (0-based) one face after the other, each face counter-clockwise seen from outside. Units: SI
 * (lengths m, volumes m³, kn N/m per constraint, forces N). */
typedef struct rockcontact_params3d {
  double kn;         /* normal penalty, N/m per constraint, > 0 */
  double tolerance;  /* m, >= 0: separate pairs closer than this get their constraints */
  int32_t policy;    /* ROCKCONTACT_POLICY_* */
  int32_t reserved;  /* explicit padding; ignored */
} rockcontact_params3d;

enum {
  ROCKCONTACT_VERTEX_FACE = 0,  /* constraint types (seed 001 §2) */
  ROCKCONTACT_EDGE_EDGE = 1,
  ROCKCONTACT_VERTEX_EDGE = 2,
  ROCKCONTACT_VERTEX_VERTEX = 3
};

typedef struct rockcontact_pair3d_result {
  int32_t status;                /* ROCKCONTACT_SEPARATE, _TOUCH or _OVERLAP */
  int32_t constraint_count;      /* constraints, read with rockcontact_pair3d_constraints */
  double volume;                 /* of the intersection, m³; 0 unless overlap */
  double distance;               /* m when separate, else -1 */
  double depth;                  /* penetration depth, m, when overlapping, else 0 */
  double normal[3];              /* unit direction translating b by depth makes the pair touch
                                    (from a towards b); 0 unless overlap */
  int32_t contact_set_dimension; /* 0, 1 or 2 when touching, else -1 */
  int32_t contact_set_count;     /* corners, read with rockcontact_pair3d_contact_set */
  int64_t predicates;            /* predicate calls spent on the pair */
  int64_t fallbacks;             /* of which re-evaluated exactly */
} rockcontact_pair3d_result;

typedef struct rockcontact_constraint3d {
  int32_t type;        /* ROCKCONTACT_VERTEX_FACE, _EDGE_EDGE, _VERTEX_EDGE or _VERTEX_VERTEX */
  int32_t reserved;    /* explicit padding; written as 0 */
  double point_a[3];   /* contact point on a, m */
  double point_b[3];   /* contact point on b, m */
  double normal[3];    /* unit normal of the contact plane, from a towards b */
  double gap;          /* (point_b - point_a) . normal, m; negative = penetration */
  double force[3];     /* penalty force on b, N: kn max(0, -gap) normal; on a it is -force */
} rockcontact_constraint3d;

typedef struct rockcontact_evaluator3d rockcontact_evaluator3d; /* opaque */

/* kn = 1e9 N/m per constraint, tolerance 0, Filtered. */
void rockcontact_default_params3d(rockcontact_params3d* params);

/* Creates a 3D evaluator; *out is set only on success. Fails with INVALID_ARGUMENT on a null
 * pointer, an unknown policy, kn not finite and > 0 or tolerance not finite and >= 0. */
rockcontact_error rockcontact_evaluator3d_create(const rockcontact_params3d* params,
                                                 rockcontact_evaluator3d** out);

/* Destroys a 3D evaluator; a null pointer is ignored. */
void rockcontact_evaluator3d_destroy(rockcontact_evaluator3d* evaluator);

/* The contact of polyhedron a with polyhedron b (world coordinates, see above). Fails with
 * INVALID_POLYHEDRON when a block is not a valid convex polyhedron, INVALID_ARGUMENT on a null
 * pointer or a negative count. */
rockcontact_error rockcontact_evaluate_pair3d(rockcontact_evaluator3d* evaluator,
                                              const double* a_xyz, int32_t a_count,
                                              const int32_t* a_face_sizes, const int32_t* a_faces,
                                              int32_t a_face_count, const double* b_xyz,
                                              int32_t b_count, const int32_t* b_face_sizes,
                                              const int32_t* b_faces, int32_t b_face_count,
                                              rockcontact_pair3d_result* result);

/* The constraints of the evaluator's last successful rockcontact_evaluate_pair3d. Sets *count
 * and, when it is at most `capacity`, writes them to out; otherwise writes nothing to out and
 * fails with INVALID_ARGUMENT (ask with capacity 0 first; out may then be null). */
rockcontact_error rockcontact_pair3d_constraints(const rockcontact_evaluator3d* evaluator,
                                                 rockcontact_constraint3d* out, int32_t capacity,
                                                 int32_t* count);

/* The corners of the contact set of the last successful rockcontact_evaluate_pair3d (none
 * unless it said ROCKCONTACT_TOUCH), as x0, y0, z0, x1, ... in xyz (3 * capacity doubles); the
 * capacity protocol of rockcontact_pair3d_constraints. */
rockcontact_error rockcontact_pair3d_contact_set(const rockcontact_evaluator3d* evaluator,
                                                 double* xyz, int32_t capacity, int32_t* count);

#ifdef __cplusplus
}
#endif

#endif /* ROCKCONTACT_H */
