#include "rockcontact/contact/generalized3d/pair_contact3d.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rockcontact/kernel/3d/intersection.hpp"
#include "rockcontact/kernel/3d/overlap.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::contact {

void check_params(const Pair3dParams& params) {
  if (!(std::isfinite(params.kn) && params.kn > 0)) {
    throw std::invalid_argument("kn: expected a finite number > 0 (N/m per constraint), got " + std::to_string(params.kn));
  }
  if (!(std::isfinite(params.tolerance) && params.tolerance >= 0)) {
    throw std::invalid_argument("tolerance: expected a finite number >= 0 (m), got " + std::to_string(params.tolerance));
  }
}

template <kernel::NumberPolicy Policy>
void evaluate_pair3d(const kernel::ConvexPolyhedron& cp, const kernel::ConvexPolyhedron& tp,
                     const Pair3dParams& params, Pair3dResult& out) {
  const kernel::PredicateCounters before = kernel::predicate_counters();
  out.status = kernel::classify_overlap<Policy>(cp, tp);
  const bool overlap = out.status == kernel::Overlap::overlap;
  out.volume = overlap ? kernel::intersection_volume<Policy>(cp, tp) : 0.0;
  out.separation.reset();
  out.penetration.reset();
  out.contact_set.reset();
  if (out.status == kernel::Overlap::separate) out.separation = kernel::separation<Policy>(cp, tp);
  if (overlap) out.penetration = kernel::penetration<Policy>(cp, tp);
  if (out.status == kernel::Overlap::touch) out.contact_set = kernel::contact_set<Policy>(cp, tp);
  out.constraints.clear();
  if (out.status != kernel::Overlap::separate || out.separation->distance < params.tolerance) {
    out.constraints = kernel::contact_constraints<Policy>(cp, tp, params.tolerance);
  }
  const kernel::PredicateCounters spent = kernel::predicate_counters() - before;
  out.predicates = spent.total_calls();
  out.fallbacks = spent.total_fallbacks();
}

kernel::Point3 penalty_force(const kernel::ContactConstraint& c, double kn) {
  const double magnitude = kn * std::max(0.0, -c.gap);
  return {magnitude * c.normal.x, magnitude * c.normal.y, magnitude * c.normal.z};
}

std::string_view to_string(kernel::ConstraintType type) {
  switch (type) {
    case kernel::ConstraintType::vertex_face: return "vertex-face";
    case kernel::ConstraintType::edge_edge: return "edge-edge";
    case kernel::ConstraintType::vertex_edge: return "vertex-edge";
    case kernel::ConstraintType::vertex_vertex: return "vertex-vertex";
  }
  return "?";
}

#define ROCKCONTACT_INSTANTIATE(P)                                                                  \
  template void evaluate_pair3d<kernel::P>(const kernel::ConvexPolyhedron&, const kernel::ConvexPolyhedron&, \
                                           const Pair3dParams&, Pair3dResult&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::contact
