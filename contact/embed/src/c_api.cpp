// The C API (rockcontact.h) over PairEvaluator (pair_contact.hpp), evaluate_pair_friction
// (pair_friction.hpp) and, in 3D, evaluate_pair3d (generalized3d/pair_contact3d.hpp). Every entry point catches
// every exception and turns it into an error code plus a per-thread message: nothing unwinds
// into C or Fortran frames.

#include "rockcontact.h"

#include <cmath>
#include <exception>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/contact/embed/pair_contact.hpp"
#include "rockcontact/contact/generalized3d/pair_contact3d.hpp"
#include "rockcontact/contact/embed/pair_friction.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/version.hpp"

// The layouts rockcontact.h promises (no implicit padding; Fortran's bind(C) types match them).
static_assert(sizeof(rockcontact_pair_result) == 80);
static_assert(sizeof(rockcontact_friction_params) == 32);
static_assert(sizeof(rockcontact_friction_state) == 56);
static_assert(sizeof(rockcontact_friction_result) == 32);
static_assert(sizeof(rockcontact_params3d) == 24);
static_assert(sizeof(rockcontact_pair3d_result) == 80);
static_assert(sizeof(rockcontact_constraint3d) == 112);

struct rockcontact_evaluator {
  rockcontact::PairEvaluator pairs;
};

struct rockcontact_evaluator3d {
  rockcontact::kernel::PolicyKind policy;
  rockcontact::contact::Pair3dParams params;
  rockcontact::contact::Pair3dResult result;
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
  } catch (const rockcontact::kernel::InvalidPolyhedron& e) {
    return fail(ROCKCONTACT_ERROR_INVALID_POLYHEDRON, e.what());
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

rockcontact::kernel::PolicyKind to_policy(int32_t policy) {
  namespace rk = rockcontact::kernel;
  switch (policy) {
    case ROCKCONTACT_POLICY_FLOAT: return rk::PolicyKind::float_;
    case ROCKCONTACT_POLICY_FILTERED: return rk::PolicyKind::filtered;
    case ROCKCONTACT_POLICY_EXACT: return rk::PolicyKind::exact;
    case ROCKCONTACT_POLICY_CHECKED: return rk::PolicyKind::checked;
    default:
      throw std::invalid_argument("params.policy: expected ROCKCONTACT_POLICY_FLOAT (0), _FILTERED "
                                  "(1), _EXACT (2) or _CHECKED (3), got " + std::to_string(policy));
  }
}

rockcontact::PairContactParams to_cpp(const rockcontact_params& p) {
  namespace rk = rockcontact::kernel;
  rockcontact::PairContactParams out;
  out.kn = p.kn;
  out.H = p.H;
  out.small_edge_fraction = p.small_edge_fraction;
  out.policy = to_policy(p.policy);
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

// A polyhedron argument, after the checks the kernel cannot make on raw pointers; the kernel
// validates the rest (index ranges, closure, convexity) and names the face and vertex.
rockcontact::kernel::ConvexPolyhedron polyhedron(const char* name, const double* xyz, int32_t count,
                                                 const int32_t* face_sizes, const int32_t* faces,
                                                 int32_t face_count) {
  const std::string block = std::string("polyhedron ") + name;
  if (count < 0 || face_count < 0) throw std::invalid_argument(block + ": negative vertex or face count");
  if ((xyz == nullptr && count > 0) || ((face_sizes == nullptr || faces == nullptr) && face_count > 0)) {
    throw std::invalid_argument(block + ": null vertex or face array");
  }
  std::vector<rockcontact::kernel::Point3> vertices(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < vertices.size(); ++i) vertices[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  std::vector<rockcontact::kernel::ConvexPolyhedron::Face> loops(static_cast<std::size_t>(face_count));
  std::size_t next = 0;
  for (std::size_t f = 0; f < loops.size(); ++f) {
    if (face_sizes[f] < 0) throw std::invalid_argument(block + ": face " + std::to_string(f) + " has a negative size");
    for (int32_t k = 0; k < face_sizes[f]; ++k, ++next) {
      if (faces[next] < 0) {
        throw std::invalid_argument(block + ": face " + std::to_string(f) + " has a negative vertex index");
      }
      loops[f].push_back(static_cast<std::uint32_t>(faces[next]));
    }
  }
  return rockcontact::kernel::ConvexPolyhedron::make(name, std::move(vertices), std::move(loops));
}

int32_t to_c(rockcontact::kernel::ConstraintType type) {
  using T = rockcontact::kernel::ConstraintType;
  switch (type) {
    case T::vertex_face: return ROCKCONTACT_VERTEX_FACE;
    case T::edge_edge: return ROCKCONTACT_EDGE_EDGE;
    case T::vertex_edge: return ROCKCONTACT_VERTEX_EDGE;
    case T::vertex_vertex: return ROCKCONTACT_VERTEX_VERTEX;
  }
  return -1;
}

void copy3(const rockcontact::kernel::Point3& p, double* out) {
  out[0] = p.x;
  out[1] = p.y;
  out[2] = p.z;
}

// The capacity protocol of the array getters: *count always, the items only when they fit.
template <class Write>
rockcontact_error write_array(const char* function, std::size_t size, int32_t capacity, int32_t* count,
                              Write write) {
  *count = static_cast<int32_t>(size);
  if (*count > capacity) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + std::to_string(size) +
                                                        " items, capacity is " + std::to_string(capacity));
  }
  for (std::size_t k = 0; k < size; ++k) write(k);
  return ROCKCONTACT_OK;
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
  return write_array("rockcontact_intersection_polygon", ip.size(), capacity, count, [&](std::size_t k) {
    xy[2 * k] = ip[k].x;
    xy[2 * k + 1] = ip[k].y;
  });
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

void rockcontact_default_params3d(rockcontact_params3d* params) {
  if (params == nullptr) return;
  const rockcontact::contact::Pair3dParams d;
  params->kn = d.kn;
  params->tolerance = d.tolerance;
  params->policy = ROCKCONTACT_POLICY_FILTERED;
  params->reserved = 0;
}

rockcontact_error rockcontact_evaluator3d_create(const rockcontact_params3d* params,
                                                 rockcontact_evaluator3d** out) {
  last_error.clear();
  if (params == nullptr || out == nullptr) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, "rockcontact_evaluator3d_create: null argument");
  }
  try {
    rockcontact::contact::Pair3dParams cpp;
    cpp.kn = params->kn;
    cpp.tolerance = params->tolerance;
    rockcontact::contact::check_params(cpp);
    *out = new rockcontact_evaluator3d{to_policy(params->policy), cpp, {}};
    return ROCKCONTACT_OK;
  } catch (...) {
    return from_exception();
  }
}

void rockcontact_evaluator3d_destroy(rockcontact_evaluator3d* evaluator) { delete evaluator; }

rockcontact_error rockcontact_evaluate_pair3d(rockcontact_evaluator3d* evaluator, const double* a_xyz,
                                              int32_t a_count, const int32_t* a_face_sizes,
                                              const int32_t* a_faces, int32_t a_face_count,
                                              const double* b_xyz, int32_t b_count,
                                              const int32_t* b_face_sizes, const int32_t* b_faces,
                                              int32_t b_face_count, rockcontact_pair3d_result* result) {
  last_error.clear();
  if (evaluator == nullptr || result == nullptr) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, "rockcontact_evaluate_pair3d: null argument");
  }
  try {
    const auto a = polyhedron("a", a_xyz, a_count, a_face_sizes, a_faces, a_face_count);
    const auto b = polyhedron("b", b_xyz, b_count, b_face_sizes, b_faces, b_face_count);
    rockcontact::contact::Pair3dResult& r = evaluator->result;
    rockcontact::kernel::with_policy(evaluator->policy, [&](auto policy) {
      rockcontact::contact::evaluate_pair3d<decltype(policy)>(a, b, evaluator->params, r);
    });
    *result = rockcontact_pair3d_result{};
    result->status = static_cast<int32_t>(r.status);
    result->constraint_count = static_cast<int32_t>(r.constraints.size());
    result->volume = r.volume;
    result->distance = r.separation ? r.separation->distance : -1.0;
    if (r.penetration) {
      result->depth = r.penetration->depth;
      copy3(r.penetration->normal, result->normal);
    }
    result->contact_set_dimension = r.contact_set ? r.contact_set->dimension : -1;
    result->contact_set_count = r.contact_set ? static_cast<int32_t>(r.contact_set->vertices.size()) : 0;
    result->predicates = static_cast<int64_t>(r.predicates);
    result->fallbacks = static_cast<int64_t>(r.fallbacks);
    return ROCKCONTACT_OK;
  } catch (...) {
    evaluator->result = {};
    return from_exception();
  }
}

rockcontact_error rockcontact_pair3d_constraints(const rockcontact_evaluator3d* evaluator,
                                                 rockcontact_constraint3d* out, int32_t capacity,
                                                 int32_t* count) {
  last_error.clear();
  if (evaluator == nullptr || count == nullptr || (out == nullptr && capacity > 0)) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, "rockcontact_pair3d_constraints: null argument");
  }
  const auto& constraints = evaluator->result.constraints;
  return write_array("rockcontact_pair3d_constraints", constraints.size(), capacity, count, [&](std::size_t k) {
    const auto& c = constraints[k];
    out[k].type = to_c(c.type);
    out[k].reserved = 0;
    copy3(c.point_cp, out[k].point_a);
    copy3(c.point_tp, out[k].point_b);
    copy3(c.normal, out[k].normal);
    out[k].gap = c.gap;
    copy3(rockcontact::contact::penalty_force(c, evaluator->params.kn), out[k].force);
  });
}

rockcontact_error rockcontact_pair3d_contact_set(const rockcontact_evaluator3d* evaluator, double* xyz,
                                                 int32_t capacity, int32_t* count) {
  last_error.clear();
  if (evaluator == nullptr || count == nullptr || (xyz == nullptr && capacity > 0)) {
    return fail(ROCKCONTACT_ERROR_INVALID_ARGUMENT, "rockcontact_pair3d_contact_set: null argument");
  }
  const auto& set = evaluator->result.contact_set;
  const std::size_t size = set ? set->vertices.size() : 0;
  return write_array("rockcontact_pair3d_contact_set", size, capacity, count,
                     [&](std::size_t k) { copy3(set->vertices[k], xyz + 3 * k); });
}

const char* rockcontact_last_error(void) { return last_error.c_str(); }

const char* rockcontact_error_string(rockcontact_error code) {
  switch (code) {
    case ROCKCONTACT_OK: return "ok";
    case ROCKCONTACT_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case ROCKCONTACT_ERROR_INVALID_POLYGON: return "invalid polygon";
    case ROCKCONTACT_ERROR_OUT_OF_MEMORY: return "out of memory";
    case ROCKCONTACT_ERROR_INTERNAL: return "internal error";
    case ROCKCONTACT_ERROR_INVALID_POLYHEDRON: return "invalid polyhedron";
  }
  return "unknown error code";
}

}  // extern "C"
