#pragma once
// The pair-level API for host codes: the one header a DEM, DDA or FDEM code includes to get the
// contact of two convex blocks from plain arrays of doubles.
//
//   rockcontact::PairEvaluator contact(params);          // once per thread: owns the workspace
//   for each candidate pair (a, b) of the host's broad phase:
//     const rockcontact::PairContact c = contact.evaluate(a_xy, a_pose, b_xy, b_pose);
//     if (c.has_point) { apply c.force to a at c.point, and -c.force to b at c.point; }
//
// Friction (the tangential force, with its per-pair history) is in pair_friction.hpp.
//
// What it computes is contact::evaluate_pair (potential_contact.hpp): the overlap verdict by the
// entrance block (seed 000 §3.1.2, eq. 9), the intersection polygon IP (Table 3), the normal
// force f = ∮_{∂IP} (phi_a - phi_b) n dL of the shortest-exit distance potential phi = kn d / H
// (eq. 11-20) and its point of application (§3.2.4); plus the penetration depth.
//
// Units: SI per metre of thickness (2D). Lengths m, angles rad, kn Pa, forces N/m, areas m².
//
// Preconditions, checked on every call (a violation throws, see evaluate()):
//   * a polygon is given by its vertices in its own (local) frame, interleaved x0, y0, x1, y1,
//     ...: at least 3 vertices, finite, counter-clockwise, strictly convex (no repeated vertex,
//     no three consecutive vertices on a line). Non-convex blocks are split into convex parts
//     by the host, one call per pair of parts.
//   * a pose places the polygon in the world frame: local v -> (x, y) + R(theta) v. The world
//     vertices are rounded to doubles and then validated, so a polygon with a near-collinear
//     vertex may be valid locally and refused after rotation; theta = 0 adds (x, y) only.
//     Give world coordinates with the identity pose {} when the host already has them.
//
// Cost and memory: an evaluator grows its buffers to the largest pair it has seen and then
// evaluates without allocating under the Float and Filtered policies (Filtered allocates only
// when a predicate falls back to exact GMP arithmetic, which c.fallbacks counts: rare, and
// only on near-degenerate input). Exact computes in GMP rationals and allocates on every call.
//
// Threads: an evaluator is not thread-safe; distinct evaluators are independent (no global
// mutable state; the predicate counters are thread-local), so give each thread its own.

#include <cstdint>
#include <memory>
#include <span>

#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/2d/tolerances.hpp"

namespace rockcontact {

// A rigid placement in the plane: a local point v goes to (x, y) + R(theta) v.
struct Pose2 {
  double x = 0.0;      // m
  double y = 0.0;      // m
  double theta = 0.0;  // rad, counter-clockwise
};

struct PairContactParams {
  double kn = 1.0e7;  // normal penalty, Pa (> 0): phi = kn d / H is a pressure (seed 000 eq. 14)
  double H = 1.0;     // potential length scale, m (> 0)
  kernel::PolicyKind policy = kernel::PolicyKind::filtered;
  kernel::Demarcation demarcation = kernel::Demarcation::exact;
  // Paper demarcation only: edges shorter than small_edge_fraction * H get a virtual node.
  double small_edge_fraction = kernel::default_small_edge_fraction;
};

PairContactParams default_pair_contact_params();

enum class PairStatus : int { separate = 0, touch = 1, overlap = 2 };

// The contact of block a (the contact polygon) with block b (the target polygon).
struct PairContact {
  PairStatus status = PairStatus::separate;  // exact under Filtered and Exact
  double force[2] = {0.0, 0.0};   // normal force on a, N/m, world frame; on b it is -force.
                                  // Zero unless status is overlap.
  double point[2] = {0.0, 0.0};   // contact point (line of action of force), m, world frame;
                                  // meaningful only when has_point
  bool has_point = false;         // true when the blocks overlap and the force is non-zero
  double area = 0.0;              // area of the intersection polygon, m²; 0 unless overlap
  double penetration = 0.0;       // penetration depth, m (>= 0): the minimum translation
                                  // distance that separates a and b; 0 unless overlap
  double length = 0.0;            // contact length L, m: half the perimeter of the intersection
                                  // polygon (the length of a thin face-to-face overlap); the L
                                  // of the cohesion term c L (pair_friction.hpp); 0 unless overlap
  std::uint64_t predicates = 0;   // predicate calls spent on this pair, validation of the two
                                  // polygons included (0 when the counters are compiled out)
  std::uint64_t fallbacks = 0;    // of which re-evaluated exactly (these allocate, in GMP)
};

class PairEvaluator {
 public:
  // Throws std::invalid_argument when kn or H is not finite and > 0, or small_edge_fraction
  // is negative or not finite.
  explicit PairEvaluator(const PairContactParams& params = default_pair_contact_params());
  ~PairEvaluator();
  PairEvaluator(PairEvaluator&&) noexcept;
  PairEvaluator& operator=(PairEvaluator&&) noexcept;
  PairEvaluator(const PairEvaluator&) = delete;
  PairEvaluator& operator=(const PairEvaluator&) = delete;

  // The contact of a (at a_pose) with b (at b_pose). a_xy and b_xy hold 2 n doubles (see the
  // preconditions above). Throws kernel::InvalidPolygon (a std::invalid_argument) naming
  // polygon "a" or "b" and the vertex when a polygon is not valid after its pose is applied,
  // std::invalid_argument when a span has an odd length or a pose is not finite.
  PairContact evaluate(std::span<const double> a_xy, const Pose2& a_pose,
                       std::span<const double> b_xy, const Pose2& b_pose);

  // The intersection polygon of the last evaluate() that returned (m, world frame, CCW); empty
  // unless it said overlap. A refused call leaves it as it was. Valid until the next evaluate().
  std::span<const kernel::Point2> intersection_polygon() const noexcept;

  const PairContactParams& params() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockcontact
