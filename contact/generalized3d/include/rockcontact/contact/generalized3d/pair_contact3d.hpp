#pragma once
// The contact of two convex polyhedra, every kernel query of a pair at once: the contract of
// `rockcontact pairs` in 3D (dynamics/io/pairs_io.hpp) and of the 3D pair call of the C API.
//
//   status        classify_overlap: separate | touch | overlap, exact under Filtered/Exact/Checked
//   volume        of the intersection polyhedron, m³ (intersection.hpp); 0 unless overlap
//   separation    distance and closest points, m, when separate (distance.hpp)
//   penetration   minimum translation distance and its unit direction, when overlapping
//                 (penetration.hpp): translating tp by depth * normal makes the pair touch
//   contact_set   the corners of cp ∩ tp, when touching (contact_set.hpp)
//   constraints   the generalized contact constraints of seed 001 §2 (contact_constraints.hpp),
//                 for pairs that touch, overlap or are closer than `tolerance`
// and the penalty force a constraint carries (seed 001 §3.3, the normal spring):
//   force on tp = kn max(0, -gap) normal, its opposite acting on cp.

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "rockcontact/kernel/3d/contact_constraints.hpp"
#include "rockcontact/kernel/3d/contact_set.hpp"
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/distance.hpp"
#include "rockcontact/kernel/3d/penetration.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/overlap.hpp"

namespace rockcontact::contact {

struct Pair3dParams {
  double kn = 1e9;         // normal penalty, N/m per constraint (> 0)
  double tolerance = 0.0;  // m (>= 0): separate pairs closer than this get their constraints
};

struct Pair3dResult {
  kernel::Overlap status = kernel::Overlap::separate;
  double volume = 0.0;  // m³
  std::optional<kernel::Separation> separation;
  std::optional<kernel::Penetration> penetration;
  std::optional<kernel::ContactSet> contact_set;
  std::vector<kernel::ContactConstraint> constraints;
  std::uint64_t predicates = 0;  // predicate calls spent on the pair (0 with counters compiled out)
  std::uint64_t fallbacks = 0;   // of which re-evaluated exactly
};

// Throws std::invalid_argument naming the field when kn is not finite and > 0 or tolerance is
// not finite and >= 0.
void check_params(const Pair3dParams& params);

// Fills `out` (reusing its storage); the parameters as check_params requires.
template <kernel::NumberPolicy Policy>
void evaluate_pair3d(const kernel::ConvexPolyhedron& cp, const kernel::ConvexPolyhedron& tp,
                     const Pair3dParams& params, Pair3dResult& out);

// The penalty force of a constraint on tp, N: kn max(0, -gap) normal.
kernel::Point3 penalty_force(const kernel::ContactConstraint& constraint, double kn);

// "vertex-face", "edge-edge", "vertex-edge" or "vertex-vertex": the names of the pairs format.
std::string_view to_string(kernel::ConstraintType type);

}  // namespace rockcontact::contact
