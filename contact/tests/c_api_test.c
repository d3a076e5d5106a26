/* The C API (rockcontact.h) from a C program: the closed form "corner" of
 * potential_contact_test.cpp through posed local rectangles (CP = [0,2]x[0,1],
 * TP = [1.25,4]x[0.25,2]: f = kn/H (-1/2, -7/16), contact point (369/226, 557/904), IP area
 * 9/16, penetration 0.75, all to 1e-12 relative: the inputs are dyadic, so only the
 * integration rounds; the IP's corners exactly), the identity pose, and every error path: the code, and a message that
 * names what was wrong. Exit status 0 when every check passes. */
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

  for (policy = ROCKCONTACT_POLICY_FLOAT; policy <= ROCKCONTACT_POLICY_EXACT; ++policy) {
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

  if (failures == 0) printf("c_api_test: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
