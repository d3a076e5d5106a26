#pragma once
// The 3D pair queries that the 3D campaign (pair3d_campaign.hpp), the 3D fuzz target
// (fuzz/fuzz_pair_kernel3d.cpp) and the 3D benchmark (bench/pair3d_bench.cpp) run on each
// pair: one function per policy, so a new query (intersection volume, distance, penetration,
// contact set, constraints) is added here once, as a field of Pair3dResult, a line of
// evaluate_pair3d and a line of staged_differences, and every harness checks it.
//
// Today: the overlap verdict (kernel/3d/overlap.hpp), exact under Filtered, Exact and Checked,
// so the staged policies must match Exact bit for bit.

#include <string>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/overlap.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/overlap.hpp"

namespace rockcontact::robustness {

struct Pair3dResult {
  kernel::Overlap verdict = kernel::Overlap::separate;
};

// Every query of the pair (a, b) under Policy. Checked throws PolicyDisagreement when a
// predicate's staged sign differs from its independent exact evaluation.
template <kernel::NumberPolicy Policy>
Pair3dResult evaluate_pair3d(const kernel::ConvexPolyhedron& a, const kernel::ConvexPolyhedron& b) {
  Pair3dResult r;
  r.verdict = kernel::classify_overlap<Policy>(a, b);
  return r;
}

// What the contract forbids between a staged policy's (Filtered, Checked) result and Exact's,
// as text naming each difference; empty when they agree. Combinatorial answers must be equal;
// a constructed quantity would be compared here against its derived error bound.
inline std::string staged_differences(const Pair3dResult& staged, const Pair3dResult& exact) {
  std::string out;
  if (staged.verdict != exact.verdict) {
    out += "verdict " + std::string(kernel::to_string(staged.verdict)) + " != Exact's " +
           std::string(kernel::to_string(exact.verdict)) + "; ";
  }
  return out;
}

// What must hold between the results of (a, b) and (b, a) under one policy; empty when it
// does. The verdict is symmetric.
inline std::string swap_differences(const Pair3dResult& ab, const Pair3dResult& ba) {
  std::string out;
  if (ab.verdict != ba.verdict) {
    out += "verdict(a, b) " + std::string(kernel::to_string(ab.verdict)) + " != verdict(b, a) " +
           std::string(kernel::to_string(ba.verdict)) + "; ";
  }
  return out;
}

}  // namespace rockcontact::robustness
