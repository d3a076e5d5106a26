#pragma once
// The resultant of the potential difference over the boundary of an intersection polygon
// (seed 000 §3.2, eq. 11, 16-20):
//
//   f = ∮_{∂IP} (phi_CP - phi_TP) n dL,    phi = kn d_exit / H  (potential.hpp)
//
// with n the IP's outward unit normal, and the point pg on the resultant's line of action
// nearest the IP centroid (§3.2.4). Per IP edge: the demarcation points of CP and of TP on it
// (§3.2.3, demarcation.hpp), merged; on an IP edge that lies on CP's boundary phi_CP = 0
// (likewise for TP), so that polygon contributes no points there; between consecutive points
// phi is linear (exactly so in `exact` demarcation), so the trapezoid rule (eq. 16) and the
// closed-form first moment (eq. 17, 20) are exact.
//
// The IP's combinatorics come from compute_intersection_polygon (the policy's predicates).
// Under Float and Filtered the constructions are double (IP crossings certified to ~2^-40 of
// their edge under Filtered, crossing_point.hpp); under Exact the IP vertices, demarcation
// parameters, integrals and moments are exact rationals, and each output number is rounded once.
//
// Units: lengths m, kn Pa, H m; the resultant is a force in N per metre of thickness.

#include <memory>
#include <optional>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/2d/intersection_polygon.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

namespace detail {
template <class FT>
struct ForceScratch;
}  // namespace detail

struct PotentialParams {
  double kn = 1.0;  // Pa
  double H = 1.0;   // m
  Demarcation demarcation = Demarcation::exact;
  double small_edge_length = 0.0;  // m; paper demarcation: shorter edges get a virtual node
};

struct PotentialResultant {
  Vector2 force;               // on CP, N/m; on TP it is -force
  std::optional<Point2> point;  // pg, m; empty when the resultant is zero (or rounding noise)
  double area = 0.0;           // of the IP, m²
};

// Scratch space of the integration, reused across pairs: no allocation once it has grown to
// the largest pair. A copy starts empty (scratch is never shared between copies).
class PotentialWorkspace {
 public:
  PotentialWorkspace();
  ~PotentialWorkspace();
  PotentialWorkspace(const PotentialWorkspace&);
  PotentialWorkspace& operator=(const PotentialWorkspace&);
  PotentialWorkspace(PotentialWorkspace&&) noexcept;
  PotentialWorkspace& operator=(PotentialWorkspace&&) noexcept;

  detail::ForceScratch<double>& scratch() { return *scratch_; }

 private:
  std::unique_ptr<detail::ForceScratch<double>> scratch_;
};

// The resultant over the non-empty symbolic IP `features` of cp and tp; its vertices, rounded
// once each, are written to `ip` (CCW).
template <NumberPolicy Policy>
PotentialResultant integrate_potential(const ConvexPolygon& cp, const ConvexPolygon& tp,
                                       const IntersectionPolygon& features,
                                       const PotentialParams& params,
                                       PotentialWorkspace& workspace, std::vector<Point2>& ip);

}  // namespace rockcontact::kernel
