#pragma once
// Normal contact of two convex polygons by the shortest-exit distance potential
// (seed 000 §3.2, eq. 11-20).
//
//   f_CP = ∮_{∂IP} (phi_CP - phi_TP) n dL                                          (eq. 11)
//
// with IP the intersection polygon, n its outward unit normal and phi = kn d_exit / H the
// potential of each polygon (eq. 14). Steps, per pair:
//   1. overlap verdict by the entrance block (eq. 9);            kernel/entrance_block.hpp
//   2. IP by clipping TP with CP's edge half-planes (Table 3);     kernel/intersection_polygon.hpp
//   3. the integral of the potential difference over the IP's boundary (eq. 11, 16-20) and the
//      contact point pg on the resultant's line of action (§3.2.4); kernel/potential_integral.hpp
//
// The combinatorics (verdict, IP vertices, which edge each IP edge lies on) follow the policy's
// predicates. Under Float and Filtered the constructions are double; under Exact they are
// exact rationals (edge lengths, the only irrational quantity, at 256 bits) and each output
// number is rounded once.
//
// Units: lengths m, kn Pa (force per unit thickness per unit length per unit penetration
// depth, divided by H: phi = kn d / H is a pressure), forces N per metre of thickness.

#include <cstdint>
#include <optional>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/2d/intersection_polygon.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/2d/potential_integral.hpp"
#include "rockcontact/kernel/2d/tolerances.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::contact {

using kernel::ConvexPolygon;
using kernel::Demarcation;
using kernel::Overlap;
using kernel::Point2;
using kernel::Vector2;

struct PotentialContactParams {
  double kn = 1.0e7;  // normal penalty, Pa (seed 000 eq. 14)
  double H = 1.0;     // potential length scale, m (> 0)
  Demarcation demarcation = Demarcation::exact;
  // Paper demarcation only: edges shorter than small_edge_fraction * H get a virtual node.
  double small_edge_fraction = kernel::default_small_edge_fraction;
};

inline PotentialContactParams default_potential_contact_params() { return {}; }

// Throws std::invalid_argument unless kn and H are finite and > 0 and small_edge_fraction is
// finite and >= 0. evaluate_pair checks this on every call; callers that hold parameters
// check them once, up front.
void check_params(const PotentialContactParams& params);

struct PairResult {
  Overlap status = Overlap::separate;
  kernel::IntersectionPolygon ip_features;  // symbolic IP: stable ids of every vertex and edge
  std::vector<Point2> ip;                   // IP vertices, m, CCW; empty unless `overlap`
  double area = 0.0;                        // IP area, m²
  Vector2 force;                            // normal force on CP, N/m; on TP it is -force
  std::optional<Point2> point;              // contact point pg, m; empty when force is zero
  std::uint64_t predicates = 0;             // predicate calls spent on this pair
  std::uint64_t fallbacks = 0;              // of which re-evaluated exactly
};

// Scratch space reused across pairs: no allocation once it has grown to the largest pair.
struct PairWorkspace {
  kernel::ClipWorkspace clip;
  kernel::PotentialWorkspace force;
};

// Throws std::invalid_argument when params are not finite and positive (kn, H).
template <kernel::NumberPolicy Policy>
void evaluate_pair(const ConvexPolygon& cp, const ConvexPolygon& tp,
                   const PotentialContactParams& params, PairWorkspace& workspace, PairResult& out);

// Convenience: the policy chosen at run time, fresh workspace.
PairResult evaluate_pair(kernel::PolicyKind policy, const ConvexPolygon& cp, const ConvexPolygon& tp,
                         const PotentialContactParams& params = default_potential_contact_params());

// The potential contact as a method a simulation or a tool holds: the number policy chosen
// once, at run time, here, and every geometric query the engine needs of a pair of convex
// parts behind it, so that the engine calls the contact layer only. Const and safe to share
// between threads: each thread passes its own workspace.
class PotentialContactMethod {
 public:
  explicit PotentialContactMethod(kernel::PolicyKind policy) : policy_(policy) {}
  kernel::PolicyKind policy() const { return policy_; }

  // evaluate_pair under the method's policy. The parameters are not checked here: the holder
  // checks each set once, with check_params, before its first use.
  void evaluate(const ConvexPolygon& cp, const ConvexPolygon& tp,
                const PotentialContactParams& params, PairWorkspace& workspace,
                PairResult& out) const;

  // The minimum translation distance of cp and tp when they overlap, else 0 (m). Always by
  // the filtered predicates: it is a monitor, not part of the force.
  static double penetration_depth(const ConvexPolygon& cp, const ConvexPolygon& tp);

  // The distance between cp and tp when they are apart, else 0 (m); filtered predicates.
  static double separation(const ConvexPolygon& cp, const ConvexPolygon& tp);

 private:
  kernel::PolicyKind policy_;
};

}  // namespace rockcontact::contact
