#include "rockcontact/contact/potential2d/potential_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::contact {

void check_params(const PotentialContactParams& params) {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(params.kn)) {
    throw std::invalid_argument("potential contact: kn must be finite and > 0 (Pa), got " +
                                std::to_string(params.kn));
  }
  if (!positive(params.H)) {
    throw std::invalid_argument("potential contact: H must be finite and > 0 (m), got " +
                                std::to_string(params.H));
  }
  if (!(params.small_edge_fraction >= 0.0) || !std::isfinite(params.small_edge_fraction)) {
    throw std::invalid_argument("potential contact: small_edge_fraction must be finite and >= 0");
  }
}

namespace {

// evaluate_pair without the check of the parameters (the callers' business).
template <kernel::NumberPolicy Policy>
void evaluate_checked(const ConvexPolygon& cp, const ConvexPolygon& tp,
                      const PotentialContactParams& params, PairWorkspace& workspace,
                      PairResult& out) {
  const kernel::PredicateCounters before = kernel::predicate_counters();
  out.ip.clear();
  out.area = 0.0;
  out.force = {};
  out.point.reset();
  // The clip decides the verdict too (intersection_polygon.hpp), equal to classify_overlap's
  // under Filtered and Exact, so the pair is classified once.
  out.status = kernel::compute_intersection_polygon<Policy>(cp, tp, out.ip_features, workspace.clip);
  if (!out.ip_features.empty()) {
    const kernel::PotentialParams potential{params.kn, params.H, params.demarcation,
                                            params.small_edge_fraction * params.H};
    const kernel::PotentialResultant r = kernel::integrate_potential<Policy>(
        cp, tp, out.ip_features, potential, workspace.force, out.ip);
    out.area = r.area;
    out.force = r.force;
    out.point = r.point;
  }
  const kernel::PredicateCounters spent = kernel::predicate_counters() - before;
  out.predicates = spent.total_calls();
  out.fallbacks = spent.total_fallbacks();
}

}  // namespace

template <kernel::NumberPolicy Policy>
void evaluate_pair(const ConvexPolygon& cp, const ConvexPolygon& tp,
                   const PotentialContactParams& params, PairWorkspace& workspace, PairResult& out) {
  check_params(params);
  evaluate_checked<Policy>(cp, tp, params, workspace, out);
}

void PotentialContactMethod::evaluate(const ConvexPolygon& cp, const ConvexPolygon& tp,
                                      const PotentialContactParams& params,
                                      PairWorkspace& workspace, PairResult& out) const {
  kernel::with_policy(policy_, [&](auto p) {
    evaluate_checked<decltype(p)>(cp, tp, params, workspace, out);
  });
}

double PotentialContactMethod::penetration_depth(const ConvexPolygon& cp, const ConvexPolygon& tp) {
  return kernel::compute_penetration_depth<kernel::Filtered>(cp, tp);
}

double PotentialContactMethod::separation(const ConvexPolygon& cp, const ConvexPolygon& tp) {
  const kernel::EntranceBlock e = kernel::compute_entrance_block<kernel::Filtered>(cp, tp);
  return e.status == Overlap::separate ? e.distance : 0.0;
}

PairResult evaluate_pair(kernel::PolicyKind policy, const ConvexPolygon& cp, const ConvexPolygon& tp,
                         const PotentialContactParams& params) {
  check_params(params);
  PairResult result;
  PairWorkspace workspace;
  PotentialContactMethod(policy).evaluate(cp, tp, params, workspace, result);
  return result;
}

#define ROCKCONTACT_INSTANTIATE(P)                                                       \
  template void evaluate_pair<kernel::P>(const ConvexPolygon&, const ConvexPolygon&,     \
                                         const PotentialContactParams&, PairWorkspace&, \
                                         PairResult&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::contact
