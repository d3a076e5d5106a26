/* The C API (rockcontact.h) from a C program: the closed form "corner" of
 * potential_contact_test.cpp through posed local rectangles (CP = [0,2]x[0,1],
 * TP = [1.25,4]x[0.25,2]: f = kn/H (-1/2, -7/16), contact point (369/226, 557/904), IP area
 * 9/16, penetration 0.75, all to 1e-12 relative: the inputs are dyadic, so only the
 * integration rounds; the IP's corners exactly), the identity pose, and every error path: the code, and a message that
 * names what was wrong. Then friction (rockcontact_evaluate_friction) on a 1 m square pressed
 * d = 2^-10 m into the top of a 4 m x 1 m base, whose normal force kn (2 d - d²) / H and contact
 * length 1 + d are closed forms (pair_friction_test.cpp), pushed along the face by 2^-13 m
 * steps: stick at -kt δ, slide at F tan 30°, dissipate limit × push, reset on separation; to
 * 1e-10 relative (a handful of roundings on the 1e-12 force, as in pair_friction_test.cpp).
 * Exit status 0 when every check passes. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rockcontact.h"

static int failures = 0;

static void check(int ok, const char* what) {
  if (!ok) {
    ++failures;
    fprintf(stderr, "FAILED: %s\n", what);
  }
}

static int close_to(double actual, double expected) {
  return fabs(actual - expected) <= 1e-12 * fabs(expected);
}

static int message_has(const char* text) { return strstr(rockcontact_last_error(), text) != NULL; }

static int near(double actual, double expected, double scale) {
  return fabs(actual - expected) <= 1e-10 * scale;
}

/* Friction through the C API; see the file comment. */
static void check_friction(void) {
  const double kn = 1.0e7, d = 1.0 / 1024.0, push = 1.0 / 8192.0;
  const double block[] = {-0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5, 0.5};
  const double base[] = {-2.0, -0.5, 2.0, -0.5, 2.0, 0.5, -2.0, 0.5};
  const double fn = kn * (2.0 * d - d * d), limit = fn * tan(atan(1.0) * 4.0 / 6.0);
  const double step[] = {push, 0.0}, bad_step[] = {NAN, 0.0};
  rockcontact_params params;
  rockcontact_friction_params friction;
  rockcontact_friction_state state = {0};
  rockcontact_friction_result t;
  rockcontact_pair_result r;
  rockcontact_evaluator* contact = NULL;
  int k;

  rockcontact_default_params(&params);
  params.kn = kn;
  check(rockcontact_evaluator_create(&params, &contact) == ROCKCONTACT_OK, "friction: create");
  rockcontact_default_friction_params(&friction);
  check(friction.kt == 1.0e7 && friction.friction_angle_deg == 0.0 && friction.cohesion == 0.0 &&
            friction.model == ROCKCONTACT_FRICTION_ELASTOPLASTIC,
        "default friction parameters");
  friction.friction_angle_deg = 30.0;
  for (k = 0; k <= 11; ++k) {
    const double pose[] = {k * push, 1.0 - d, 0.0};
    check(rockcontact_evaluate_pair(contact, block, 4, pose, base, 4, NULL, &r) == ROCKCONTACT_OK &&
              r.has_point == 1 && near(r.force[1], fn, fn) && near(r.length, 1.0 + d, 1.0),
          "friction: pressed block, F = kn (2 d - d²) / H, L = 1 + d");
    check(rockcontact_evaluate_friction(&friction, &r, step, &state, &t) == ROCKCONTACT_OK,
          "friction: evaluate");
    if (k == 0) check(t.force[0] == 0.0 && t.sliding == 0, "friction: a new contact, unstretched");
    if (k == 1) {
      check(near(t.force[0], -friction.kt * push, limit) && t.sliding == 0 && t.dissipated == 0.0,
            "friction: stick at -kt push");
    }
    if (k == 11) {
      check(near(t.force[0], -limit, limit) && near(t.force[1], 0.0, limit) && t.sliding == 1 &&
                near(t.dissipated, limit * push, limit * push),
            "friction: slide at F tan 30, dissipating limit x push");
    }
  }

  /* Bad input: the code, the field in the message, nothing written. */
  {
    const rockcontact_friction_state kept = state;
    rockcontact_friction_params bad = friction;
    bad.kt = -1.0;
    check(rockcontact_evaluate_friction(&bad, &r, step, &state, &t) ==
                  ROCKCONTACT_ERROR_INVALID_ARGUMENT && message_has("kt must be finite and > 0"),
          "friction: negative kt refused");
    bad = friction;
    bad.model = 5;
    check(rockcontact_evaluate_friction(&bad, &r, step, &state, &t) ==
                  ROCKCONTACT_ERROR_INVALID_ARGUMENT && message_has("friction_params.model"),
          "friction: unknown model refused");
    check(rockcontact_evaluate_friction(&friction, &r, bad_step, &state, &t) ==
                  ROCKCONTACT_ERROR_INVALID_ARGUMENT && message_has("increment"),
          "friction: non-finite increment refused");
    check(rockcontact_evaluate_friction(&friction, &r, step, NULL, &t) ==
              ROCKCONTACT_ERROR_INVALID_ARGUMENT,
          "friction: null state refused");
    check(memcmp(&kept, &state, sizeof state) == 0, "friction: a refusal leaves the state");
  }

  /* Separation: no force, and the state is zero again. */
  {
    const double lifted[] = {0.0, 1.0 + d, 0.0};
    const rockcontact_friction_state zero = {0};
    check(rockcontact_evaluate_pair(contact, block, 4, lifted, base, 4, NULL, &r) == ROCKCONTACT_OK &&
              r.has_point == 0,
          "friction: lifted block separates");
    check(rockcontact_evaluate_friction(&friction, &r, step, &state, &t) == ROCKCONTACT_OK &&
              t.force[0] == 0.0 && t.force[1] == 0.0 && t.sliding == 0 &&
              memcmp(&zero, &state, sizeof state) == 0,
          "friction: separation resets the state");
  }
  rockcontact_evaluator_destroy(contact);
}

/* 3D: a 0.5 m cube pressed d = 2^-10 m into the top of a unit cube (all coordinates dyadic, so
 * every result is exact or one rounding away): overlap, intersection volume 0.25 d, penetration d
 * straight up, four vertex-face constraints at the small cube's base corners with gap -d and
 * force kn d up on b; then lifted by 2^-3 m: separate at distance 2^-3 - d, constraints only
 * within the tolerance; then the error paths. */
static void check_3d(void) {
  const double d = 1.0 / 1024.0, kn = 1.0e9;
  const double a_xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  double b_xyz[24];
  const int32_t sizes[] = {4, 4, 4, 4, 4, 4};
  const int32_t faces[] = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
  int32_t inverted[24];
  rockcontact_params3d params;
  rockcontact_evaluator3d* contact = NULL;
  rockcontact_pair3d_result r;
  rockcontact_constraint3d c[8];
  double corners[3 * 8];
  int32_t count = -1;
  int k;

  for (k = 0; k < 8; ++k) {
    b_xyz[3 * k] = 0.25 + 0.5 * a_xyz[3 * k];
    b_xyz[3 * k + 1] = 0.25 + 0.5 * a_xyz[3 * k + 1];
    b_xyz[3 * k + 2] = 1.0 - d + 0.5 * a_xyz[3 * k + 2];
  }
  rockcontact_default_params3d(&params);
  check(params.kn == 1.0e9 && params.tolerance == 0.0 && params.policy == ROCKCONTACT_POLICY_FILTERED,
        "3d: default params");
  params.tolerance = 0.25;
  check(rockcontact_evaluator3d_create(&params, &contact) == ROCKCONTACT_OK, "3d: create");
  check(rockcontact_evaluate_pair3d(contact, a_xyz, 8, sizes, faces, 6, b_xyz, 8, sizes, faces, 6, &r) ==
            ROCKCONTACT_OK,
        "3d: evaluate");
  check(r.status == ROCKCONTACT_OVERLAP && close_to(r.volume, 0.25 * d) && close_to(r.depth, d) &&
            r.normal[0] == 0.0 && r.normal[1] == 0.0 && r.normal[2] == 1.0 && r.distance == -1.0 &&
            r.contact_set_dimension == -1 && r.contact_set_count == 0,
        "3d: overlap, volume d/4, penetration d up");
  check(r.constraint_count == 4, "3d: four constraints");
  check(rockcontact_pair3d_constraints(contact, NULL, 0, &count) == ROCKCONTACT_ERROR_INVALID_ARGUMENT &&
            count == 4,
        "3d: constraint count asked with capacity 0");
  check(rockcontact_pair3d_constraints(contact, c, 8, &count) == ROCKCONTACT_OK && count == 4, "3d: constraints");
  for (k = 0; k < 4; ++k) {
    check(c[k].type == ROCKCONTACT_VERTEX_FACE && c[k].normal[2] == 1.0 && close_to(c[k].gap, -d) &&
              close_to(c[k].force[2], kn * d) && c[k].force[0] == 0.0 && c[k].point_a[2] == 1.0 &&
              c[k].point_b[2] == 1.0 - d,
          "3d: vertex-face constraint at a base corner, gap -d, force kn d");
  }
  for (k = 0; k < 8; ++k) b_xyz[3 * k + 2] += 0.125;
  check(rockcontact_evaluate_pair3d(contact, a_xyz, 8, sizes, faces, 6, b_xyz, 8, sizes, faces, 6, &r) ==
                ROCKCONTACT_OK &&
            r.status == ROCKCONTACT_SEPARATE && close_to(r.distance, 0.125 - d) && r.constraint_count == 4,
        "3d: separate at 1/8 - d, constraints within the tolerance");
  check(rockcontact_pair3d_contact_set(contact, corners, 8, &count) == ROCKCONTACT_OK && count == 0,
        "3d: no contact set when separate");

  for (k = 0; k < 24; ++k) inverted[k] = faces[k];
  inverted[1] = 1, inverted[3] = 3; /* the bottom 0 3 2 1 reversed: 0 1 2 3, clockwise from outside */
  check(rockcontact_evaluate_pair3d(contact, a_xyz, 8, sizes, inverted, 6, b_xyz, 8, sizes, faces, 6, &r) ==
                ROCKCONTACT_ERROR_INVALID_POLYHEDRON &&
            message_has("polyhedron 'a'") && message_has("face"),
        "3d: a face the wrong way round is refused, naming the block and face");
  check(rockcontact_evaluate_pair3d(contact, a_xyz, -1, sizes, faces, 6, b_xyz, 8, sizes, faces, 6, &r) ==
                ROCKCONTACT_ERROR_INVALID_ARGUMENT &&
            message_has("polyhedron a"),
        "3d: a negative count refused");
  rockcontact_evaluator3d_destroy(contact);
  params.tolerance = -1.0;
  contact = NULL;
  check(rockcontact_evaluator3d_create(&params, &contact) == ROCKCONTACT_ERROR_INVALID_ARGUMENT &&
            contact == NULL && message_has("tolerance"),
        "3d: a negative tolerance refused");
  check(strcmp(rockcontact_error_string(ROCKCONTACT_ERROR_INVALID_POLYHEDRON), "invalid polyhedron") == 0,
        "3d: error string");
}

int main(void) {
  const double kn = 2.0e7, H = 0.5, scale = kn / H;
  const double a_xy[] = {-1.0, -0.5, 1.0, -0.5, 1.0, 0.5, -1.0, 0.5};
  const double b_xy[] = {-1.375, -0.875, 1.375, -0.875, 1.375, 0.875, -1.375, 0.875};
  const double a_pose[] = {1.0, 0.5, 0.0};
  const double b_pose[] = {2.625, 1.125, 0.0};
  const double clockwise[] = {0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0};
  rockcontact_params params;
  rockcontact_evaluator* contact = NULL;
  rockcontact_pair_result r;
  int policy;

  check(strlen(rockcontact_version()) >= 5, "version string");
  rockcontact_default_params(&params);
  check(params.kn == 1.0e7 && params.H == 1.0 && params.policy == ROCKCONTACT_POLICY_FILTERED &&
            params.demarcation == ROCKCONTACT_DEMARCATION_EXACT,
        "default parameters");
  params.kn = kn;
  params.H = H;

  for (policy = ROCKCONTACT_POLICY_FLOAT; policy <= ROCKCONTACT_POLICY_CHECKED; ++policy) {
    params.policy = policy;
    check(rockcontact_evaluator_create(&params, &contact) == ROCKCONTACT_OK, "create");
    check(rockcontact_evaluate_pair(contact, a_xy, 4, a_pose, b_xy, 4, b_pose, &r) == ROCKCONTACT_OK,
          "evaluate the corner pair");
    check(r.status == ROCKCONTACT_OVERLAP && r.has_point == 1, "corner: overlap with a point");
    check(close_to(r.area, 9.0 / 16.0), "corner: area 9/16");
    check(close_to(r.force[0], -0.5 * scale) && close_to(r.force[1], -7.0 / 16.0 * scale),
          "corner: force kn/H (-1/2, -7/16)");
    check(close_to(r.point[0], 369.0 / 226.0) && close_to(r.point[1], 557.0 / 904.0),
          "corner: point (369/226, 557/904)");
    check(close_to(r.penetration, 0.75), "corner: penetration 0.75");
    check(r.predicates > 0 && r.fallbacks >= 0, "corner: predicate counts");
    {
      /* The IP is [1.25, 2] x [0.25, 1]: four corners, CCW, in some rotation. */
      double ip[8] = {0};
      int32_t count = -1;
      int k, found = 0;
      check(rockcontact_intersection_polygon(contact, NULL, 0, &count) ==
                    ROCKCONTACT_ERROR_INVALID_ARGUMENT && count == 4,
            "corner: IP size asked with capacity 0");
      check(rockcontact_intersection_polygon(contact, ip, 4, &count) == ROCKCONTACT_OK && count == 4,
            "corner: IP vertices");
      for (k = 0; k < 4; ++k) {
        found += (ip[2 * k] == 1.25 || ip[2 * k] == 2.0) && (ip[2 * k + 1] == 0.25 || ip[2 * k + 1] == 1.0);
      }
      check(found == 4 && (ip[2] - ip[0]) * (ip[5] - ip[1]) - (ip[3] - ip[1]) * (ip[4] - ip[0]) > 0.0,
            "corner: IP = [1.25, 2] x [0.25, 1], counter-clockwise");
    }
    rockcontact_evaluator_destroy(contact);
    contact = NULL;
  }

  /* The identity pose (null): world coordinates. A unit square touching a shifted one. */
  params.policy = ROCKCONTACT_POLICY_FILTERED;
  check(rockcontact_evaluator_create(&params, &contact) == ROCKCONTACT_OK, "create");
  {
    const double left[] = {0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0};
    const double right[] = {1.0, 0.25, 2.0, 0.25, 2.0, 1.25, 1.0, 1.25};
    check(rockcontact_evaluate_pair(contact, left, 4, NULL, right, 4, NULL, &r) == ROCKCONTACT_OK &&
              r.status == ROCKCONTACT_TOUCH && r.has_point == 0 && r.force[0] == 0.0 &&
              r.area == 0.0 && r.penetration == 0.0,
          "touching squares, identity poses");
  }

  /* Errors: the code, a message naming the culprit, and the result left untouched. */
  r.area = -1.0;
  check(rockcontact_evaluate_pair(contact, clockwise, 4, NULL, b_xy, 4, b_pose, &r) ==
                ROCKCONTACT_ERROR_INVALID_POLYGON &&
            message_has("polygon a") && message_has("counter-clockwise") && r.area == -1.0,
        "clockwise polygon a refused");
  check(rockcontact_evaluate_pair(contact, a_xy, 2, NULL, b_xy, 4, NULL, &r) ==
                ROCKCONTACT_ERROR_INVALID_ARGUMENT &&
            message_has("polygon a: needs at least 3 vertices, got 2"),
        "two vertices refused");
  check(rockcontact_evaluate_pair(contact, a_xy, 4, NULL, NULL, 4, NULL, &r) ==
                ROCKCONTACT_ERROR_INVALID_ARGUMENT && message_has("polygon b: null vertex array"),
        "null vertex array refused");
  {
    const double bad_pose[] = {0.0, NAN, 0.0};
    check(rockcontact_evaluate_pair(contact, a_xy, 4, bad_pose, b_xy, 4, NULL, &r) ==
                  ROCKCONTACT_ERROR_INVALID_ARGUMENT && message_has("pose"),
          "non-finite pose refused");
  }
  check(rockcontact_evaluate_pair(NULL, a_xy, 4, NULL, b_xy, 4, NULL, &r) ==
            ROCKCONTACT_ERROR_INVALID_ARGUMENT,
        "null evaluator refused");
  check(rockcontact_evaluate_pair(contact, a_xy, 4, a_pose, b_xy, 4, b_pose, &r) == ROCKCONTACT_OK &&
            rockcontact_last_error()[0] == '\0' && close_to(r.area, 9.0 / 16.0),
        "the evaluator works after refusals, and the message is cleared");
  rockcontact_evaluator_destroy(contact);
  rockcontact_evaluator_destroy(NULL);

  params.kn = -1.0;
  contact = NULL;
  check(rockcontact_evaluator_create(&params, &contact) == ROCKCONTACT_ERROR_INVALID_ARGUMENT &&
            contact == NULL && message_has("kn"),
        "negative kn refused");
  params.kn = kn;
  params.policy = 7;
  check(rockcontact_evaluator_create(&params, &contact) == ROCKCONTACT_ERROR_INVALID_ARGUMENT &&
            message_has("params.policy"),
        "unknown policy refused");
  check(strcmp(rockcontact_error_string(ROCKCONTACT_ERROR_INVALID_POLYGON), "invalid polygon") == 0,
        "error string");

  check_friction();
  check_3d();

  if (failures == 0) printf("c_api_test: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
