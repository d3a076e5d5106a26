// The C API (rockcontact.h) over PairEvaluator (pair_contact.hpp) and evaluate_pair_friction
// (pair_friction.hpp). Every entry point catches
// every exception and turns it into an error code plus a per-thread message: nothing unwinds
// into C or Fortran frames.

#include "rockcontact.h"

#include <cmath>
#include <exception>
#include <new>
#include <span>
#include <stdexcept>
#include <string>

#include "rockcontact/contact/embed/pair_contact.hpp"
#include "rockcontact/contact/embed/pair_friction.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/version.hpp"

// The layouts rockcontact.h promises (no implicit padding; Fortran's bind(C) types match them).
static_assert(sizeof(rockcontact_pair_result) == 80);
static_assert(sizeof(rockcontact_friction_params) == 32);
static_assert(sizeof(rockcontact_friction_state) == 56);
static_assert(sizeof(rockcontact_friction_result) == 32);

struct rockcontact_evaluator {
  rockcontact::PairEvaluator pairs;
};

namespace {

thread_local std::string last_error;

rockcontact_error fail(rockcontact_error code, std::string message) {
  last_error = std::move(message);
  return code;
}

// The code and message of the exception in flight; called only from a catch (...) block.
rockcontact_error from_exception() {
  try {
    throw;
  } catch (const rockcontact::kernel::InvalidPolygon& e) {
    return fail(ROCKCONTACT_ERROR_INVALID_POLYGON, e.what());
  } catch (const std::invalid_argument& e) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, e.what());
  } catch (const std::bad_alloc&) {
    return fail(ROCKCONTACT_ERROR_OUT_OF_MEMORY, "out of memory");
  } catch (const std::exception& e) {
    return fail(ROCKCONTACT_ERROR_INTERNAL, std::string("internal error: ") + e.what());
  } catch (...) {
    return fail(ROCKCONTACT_ERROR_INTERNAL, "internal error: unknown exception");
  }
}

rockcontact::PairContactParams to_cpp(const rockcontact_params& p) {
  namespace rk = rockcontact::kernel;
  rockcontact::PairContactParams out;
  out.kn = p.kn;
  out.H = p.H;
  out.small_edge_fraction = p.small_edge_fraction;
  switch (p.policy) {
    case ROCKCONTACT_POLICY_FLOAT: out.policy = rk::PolicyKind::float_; break;
    case ROCKCONTACT_POLICY_FILTERED: out.policy = rk::PolicyKind::filtered; break;
    case ROCKCONTACT_POLICY_EXACT: out.policy = rk::PolicyKind::exact; break;
    case ROCKCONTACT_POLICY_CHECKED: out.policy = rk::PolicyKind::checked; break;
    default:
      throw std::invalid_argument("params.policy: expected ROCKCONTACT_POLICY_FLOAT (0), _FILTERED "
                                  "(1), _EXACT (2) or _CHECKED (3), got " + std::to_string(p.policy));
  }
  switch (p.demarcation) {
    case ROCKCONTACT_DEMARCATION_EXACT: out.demarcation = rk::Demarcation::exact; break;
    case ROCKCONTACT_DEMARCATION_PAPER: out.demarcation = rk::Demarcation::paper; break;
    default:
      throw std::invalid_argument("params.demarcation: expected ROCKCONTACT_DEMARCATION_EXACT (0) "
                                  "or _PAPER (1), got " + std::to_string(p.demarcation));
  }
  return out;
}

// A polygon argument as a span, after the checks the C++ API cannot make on a raw pointer.
std::span<const double> polygon(const char* name, const double* xy, int32_t count) {
  if (xy == nullptr) throw std::invalid_argument(std::string("polygon ") + name + ": null vertex array");
  if (count < 3) {
    throw std::invalid_argument(std::string("polygon ") + name + ": needs at least 3 vertices, got " +
                                std::to_string(count));
  }
  return {xy, 2 * static_cast<std::size_t>(count)};
}

rockcontact::PairFrictionParams to_cpp(const rockcontact_friction_params& p) {
  rockcontact::PairFrictionParams out;
  out.kt = p.kt;
  out.friction_angle_deg = p.friction_angle_deg;
  out.cohesion = p.cohesion;
  switch (p.model) {
    case ROCKCONTACT_FRICTION_ELASTOPLASTIC:
      out.model = rockcontact::contact::FrictionModel::elastoplastic;
      break;
    case ROCKCONTACT_FRICTION_PAPER: out.model = rockcontact::contact::FrictionModel::paper; break;
    default:
      throw std::invalid_argument("friction_params.model: expected ROCKCONTACT_FRICTION_ELASTOPLASTIC "
                                  "(0) or _PAPER (1), got " + std::to_string(p.model));
  }
  return out;
}

// The fields of a pair result that friction reads.
rockcontact::PairContact to_cpp(const rockcontact_pair_result& r) {
  rockcontact::PairContact out;
  out.has_point = r.has_point != 0;
  out.force[0] = r.force[0];
  out.force[1] = r.force[1];
  out.length = r.length;
  return out;
}

rockcontact::PairFrictionState to_cpp(const rockcontact_friction_state& s) {
  rockcontact::PairFrictionState out;
  out.record.displacement = {s.displacement[0], s.displacement[1]};
  out.record.force = {s.force[0], s.force[1]};
  out.record.normal = {s.normal[0], s.normal[1]};
  out.record.sliding = s.sliding != 0;
  out.in_contact = s.in_contact != 0;
  return out;
}

void to_c(const rockcontact::PairFrictionState& s, rockcontact_friction_state& out) {
  out.displacement[0] = s.record.displacement.x;
  out.displacement[1] = s.record.displacement.y;
  out.force[0] = s.record.force.x;
  out.force[1] = s.record.force.y;
  out.normal[0] = s.record.normal.x;
  out.normal[1] = s.record.normal.y;
  out.sliding = s.record.sliding ? 1 : 0;
  out.in_contact = s.in_contact ? 1 : 0;
}

rockcontact::Pose2 pose(const double* p) {
  return p == nullptr ? rockcontact::Pose2{} : rockcontact::Pose2{p[0], p[1], p[2]};
}

}  // namespace

extern "C" {

const char* rockcontact_version(void) { return ROCKCONTACT_VERSION_STRING; }

void rockcontact_default_params(rockcontact_params* params) {
  if (params == nullptr) return;
  const rockcontact::PairContactParams d = rockcontact::default_pair_contact_params();
  params->kn = d.kn;
  params->H = d.H;
  params->small_edge_fraction = d.small_edge_fraction;
  params->policy = ROCKCONTACT_POLICY_FILTERED;
  params->demarcation = ROCKCONTACT_DEMARCATION_EXACT;
}

rockcontact_error rockcontact_evaluator_create(const rockcontact_params* params,
                                               rockcontact_evaluator** out) {
  last_error.clear();
  if (params == nullptr || out == nullptr) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, "rockcontact_evaluator_create: null argument");
  }
  try {
    *out = new rockcontact_evaluator{rockcontact::PairEvaluator(to_cpp(*params))};
    return ROCKCONTACT_OK;
  } catch (...) {
    return from_exception();
  }
}

void rockcontact_evaluator_destroy(rockcontact_evaluator* evaluator) { delete evaluator; }

rockcontact_error rockcontact_evaluate_pair(rockcontact_evaluator* evaluator, const double* a_xy,
                                            int32_t a_count, const double* a_pose,
                                            const double* b_xy, int32_t b_count,
                                            const double* b_pose, rockcontact_pair_result* result) {
  last_error.clear();
  if (evaluator == nullptr || result == nullptr) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, "rockcontact_evaluate_pair: null argument");
  }
  try {
    const rockcontact::PairContact c =
        evaluator->pairs.evaluate(polygon("a", a_xy, a_count), pose(a_pose),
                                  polygon("b", b_xy, b_count), pose(b_pose));
    result->status = static_cast<int32_t>(c.status);
    result->has_point = c.has_point ? 1 : 0;
    result->force[0] = c.force[0];
    result->force[1] = c.force[1];
    result->point[0] = c.point[0];
    result->point[1] = c.point[1];
    result->area = c.area;
    result->penetration = c.penetration;
    result->predicates = static_cast<int64_t>(c.predicates);
    result->fallbacks = static_cast<int64_t>(c.fallbacks);
    result->length = c.length;
    return ROCKCONTACT_OK;
  } catch (...) {
    return from_exception();
  }
}

rockcontact_error rockcontact_intersection_polygon(const rockcontact_evaluator* evaluator,
                                                   double* xy, int32_t capacity, int32_t* count) {
  last_error.clear();
  if (evaluator == nullptr || count == nullptr || (xy == nullptr && capacity > 0)) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, "rockcontact_intersection_polygon: null argument");
  }
  const std::span<const rockcontact::kernel::Point2> ip = evaluator->pairs.intersection_polygon();
  *count = static_cast<int32_t>(ip.size());
  if (*count > capacity) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT,
                "rockcontact_intersection_polygon: the polygon has " + std::to_string(*count) +
                    " vertices, capacity is " + std::to_string(capacity));
  }
  for (std::size_t k = 0; k < ip.size(); ++k) {
    xy[2 * k] = ip[k].x;
    xy[2 * k + 1] = ip[k].y;
  }
  return ROCKCONTACT_OK;
}

void rockcontact_default_friction_params(rockcontact_friction_params* params) {
  if (params == nullptr) return;
  const rockcontact::PairFrictionParams d = rockcontact::default_pair_friction_params();
  params->kt = d.kt;
  params->friction_angle_deg = d.friction_angle_deg;
  params->cohesion = d.cohesion;
  params->model = ROCKCONTACT_FRICTION_ELASTOPLASTIC;
  params->reserved = 0;
}

rockcontact_error rockcontact_evaluate_friction(const rockcontact_friction_params* params,
                                                const rockcontact_pair_result* contact,
                                                const double* increment,
                                                rockcontact_friction_state* state,
                                                rockcontact_friction_result* result) {
  last_error.clear();
  if (params == nullptr || contact == nullptr || increment == nullptr || state == nullptr ||
      result == nullptr) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, "rockcontact_evaluate_friction: null argument");
  }
  try {
    rockcontact::PairFrictionState next = to_cpp(*state);
    const rockcontact::PairFriction f = rockcontact::evaluate_pair_friction(
        next, to_cpp(*contact), {increment[0], increment[1]}, to_cpp(*params));
    to_c(next, *state);
    result->force[0] = f.force[0];
    result->force[1] = f.force[1];
    result->dissipated = f.dissipated;
    result->sliding = f.sliding ? 1 : 0;
    result->reserved = 0;
    return ROCKCONTACT_OK;
  } catch (...) {
    return from_exception();
  }
}

const char* rockcontact_last_error(void) { return last_error.c_str(); }

const char* rockcontact_error_string(rockcontact_error code) {
  switch (code) {
    case ROCKCONTACT_OK: return "ok";
    case ROCKCONTACT_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case ROCKCONTACT_ERROR_INVALID_POLYGON: return "invalid polygon";
    case ROCKCONTACT_ERROR_OUT_OF_MEMORY: return "out of memory";
    case ROCKCONTACT_ERROR_INTERNAL: return "internal error";
  }
  return "unknown error code";
}

}  // extern "C"
