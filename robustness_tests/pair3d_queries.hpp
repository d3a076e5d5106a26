#pragma once
// The 3D pair queries that the 3D campaign (pair3d_campaign.hpp), the 3D fuzz target
// (fuzz/fuzz_pair_kernel3d.cpp) and the 3D benchmark (bench/pair3d_bench.cpp) run on each pair:
// every query of the `pairs` contract at once, contact::evaluate_pair3d (the verdict, the
// intersection volume, distance, penetration, contact set and the generalized contact
// constraints at tolerance 0).
//
// What the staged policies must give, against Exact:
//   * combinatorics equal: the verdict, the contact set's dimension and corner count, and for
//     every constraint its type and its two features (they follow exact decisions only);
//   * the intersection volume within 1e-9 relative or 1e-12 of the cube of the pair's size:
//     Filtered's volume carries a bound on its error and is kept only within 2^-31 relative or
//     2^-41 size³ of the exact one (else it is made closer, or exact: halfspace_polyhedron.hpp),
//     half the tolerance, so it holds against Exact and between two staged volumes.
// The distance and the penetration depth are not compared here: Filtered chooses their features
// in double, and near parallel closest edges its error grows beyond any fixed tolerance
// (distance.hpp and penetration.hpp state the bounds). They are checked against the exact
// contact3d reference (kernel/3d/tests, dynamics/tests/pairs3d_io_test.cpp) instead.
// Under swapping the pair: the same verdict and the volume within the same tolerance.

#include <algorithm>
#include <cmath>
#include <string>

#include "rockcontact/contact/generalized3d/pair_contact3d.hpp"
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/overlap.hpp"

namespace rockcontact::robustness {

struct Pair3dResult {
  kernel::Overlap verdict = kernel::Overlap::separate;
  contact::Pair3dResult queries;  // every query of the pair
  double size = 0.0;              // the largest bounding-box extent of the pair, m
};

inline double pair_size(const kernel::ConvexPolyhedron& a, const kernel::ConvexPolyhedron& b) {
  kernel::Point3 lo = a[0], hi = a[0];
  for (const auto* p : {&a, &b}) {
    for (const kernel::Point3& v : p->vertices()) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    }
  }
  return std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
}

// Every query of the pair (a, b) under Policy. Checked throws PolicyDisagreement when a
// predicate's staged sign differs from its independent exact evaluation.
template <kernel::NumberPolicy Policy>
Pair3dResult evaluate_pair3d(const kernel::ConvexPolyhedron& a, const kernel::ConvexPolyhedron& b) {
  Pair3dResult r;
  contact::evaluate_pair3d<Policy>(a, b, contact::Pair3dParams{}, r.queries);
  r.verdict = r.queries.status;
  r.size = pair_size(a, b);
  return r;
}

namespace detail {

// "name x != y; " when |x - y| exceeds 1e-9 |y| + 1e-12 scale.
inline std::string value_difference(const char* name, double x, double y, double scale) {
  if (std::abs(x - y) <= 1e-9 * std::abs(y) + 1e-12 * scale) return {};
  return std::string(name) + " " + std::to_string(x) + " != " + std::to_string(y) + "; ";
}

// The volumes of two results of the same pair (in either order).
inline std::string value_differences(const Pair3dResult& x, const Pair3dResult& y) {
  return value_difference("volume", x.queries.volume, y.queries.volume, std::pow(y.size, 3));
}

}  // namespace detail

// What the contract forbids between a staged policy's (Filtered, Checked) result and Exact's,
// as text naming each difference; empty when they agree.
inline std::string staged_differences(const Pair3dResult& staged, const Pair3dResult& exact) {
  std::string out;
  if (staged.verdict != exact.verdict) {
    return "verdict " + std::string(kernel::to_string(staged.verdict)) + " != Exact's " +
           std::string(kernel::to_string(exact.verdict)) + "; ";
  }
  const auto& s = staged.queries;
  const auto& e = exact.queries;
  if (s.contact_set.has_value() != e.contact_set.has_value() ||
      (s.contact_set && (s.contact_set->dimension != e.contact_set->dimension ||
                         s.contact_set->vertices.size() != e.contact_set->vertices.size()))) {
    out += "contact set differs from Exact's; ";
  }
  bool same_constraints = s.constraints.size() == e.constraints.size();
  for (std::size_t i = 0; same_constraints && i < s.constraints.size(); ++i) {
    same_constraints = s.constraints[i].type == e.constraints[i].type &&
                       s.constraints[i].cp_feature == e.constraints[i].cp_feature &&
                       s.constraints[i].tp_feature == e.constraints[i].tp_feature;
  }
  if (!same_constraints) out += "constraints differ from Exact's in number, type or features; ";
  return out + detail::value_differences(staged, exact);
}

// What must hold between the results of (a, b) and (b, a) under one policy; empty when it does.
inline std::string swap_differences(const Pair3dResult& ab, const Pair3dResult& ba) {
  if (ab.verdict != ba.verdict) {
    return "verdict(a, b) " + std::string(kernel::to_string(ab.verdict)) + " != verdict(b, a) " +
           std::string(kernel::to_string(ba.verdict)) + "; ";
  }
  return detail::value_differences(ab, ba);
}

}  // namespace rockcontact::robustness
