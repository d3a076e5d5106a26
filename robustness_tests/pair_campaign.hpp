#pragma once
// The pair campaign: every generated pair (robustness_tests/generators/include/rockcontact/generators/pair_generators.hpp) run through
// the overlap verdict, the intersection polygon IP and the potential contact force under the
// three number policies, with the properties below checked on every case and tallied per
// family. pair_properties_test.cpp runs a deterministic slice of it in CI; robustness_table
// runs it at nightly size (>= 10^6 cases) and prints the markdown table of the README.
//
// Checked on every case (pair = rb::generate_pair(family, seed, index)):
//   Policy agreement. Filtered (run under Checked: every sign also evaluated exactly on its
//     own, a disagreement counted here) and Exact give the same verdict (classify_overlap) and
//     the same symbolic IP (IpVertex and IpEdge labels); Filtered's constructed crossings are within
//     crossing_bound() of Exact's, its input vertices bitwise equal. Float's verdict and IP
//     labels are compared with Exact's and counted, not asserted.
//   IP properties, decided exactly (GMP) on the exact IP: the vertices named by the Exact
//     labels, crossings constructed here as rationals by Cramer's rule (independently of the
//     kernel's construction):
//     * the IP is non-empty exactly when the verdict is `overlap`;
//     * strictly convex and CCW: every vertex is strictly left of every edge it is not on;
//     * inside both polygons: no vertex is strictly right of any CP or TP edge line;
//     * every IP edge labelled "on CP edge i" (TP edge j) has both ends on that line;
//     * area(IP) <= min(area(CP), area(TP));
//     * the Exact policy's constructed points are these exact vertices rounded to a nearest
//       double.
//     What this cannot assert for rounded points: a rounded vertex (Exact's or Filtered's) is
//     not on its edge lines and may lie outside a polygon by its rounding error, so "inside"
//     and "convex" are asserted for the exact vertices only. For Filtered's points the
//     campaign asserts the next best thing: each is within crossing_bound() of Exact's (hence
//     of the exact vertex, per coordinate), so it lies within that distance of both polygons.
//   Invariances, under Filtered on every case:
//     * translation by (2^20, -2^20) of the pair snapped to a grid that makes it exact
//       (2^-31 for pairs near the origin): same verdict and IP labels;
//     * rotation by 90 degrees, (x, y) -> (-y, x), exact in floating point: same verdict and
//       IP labels, force rotated within force_bound() of both pairs;
//     * swapping cp and tp: same verdict, force negated within the two force bounds;
//     * continuity at touch: a pair touching under Exact has zero force; pushed into contact
//       by h d (h = 2^-8, 2^-16, 2^-24 m, d a unit-ish direction into the overlap), its force
//       obeys |f| <= (kn/H) min(2 area(IP), h |d| min(perimeter(CP), perimeter(TP))) plus
//       force_bound(): it vanishes at least linearly in h (derivation at continuity_bound in
//       pair_campaign.cpp).
//   Every `exact_force_stride`-th case also runs the force under Exact (~1-3 ms a pair):
//     * Filtered's force within force_bound() of Exact's, same status and IP labels;
//     * rotation and swap bitwise: Exact's rotated force is the rotated force, its swapped
//       force the negated force, with equal areas;
//     * paper vs exact demarcation (seed 000 §3.2.3), both under Exact: the relative force
//       difference |f_paper - f_exact| / |f_exact|, the paper's approximation error, measured.
// Crashes: any exception thrown while checking a case under Filtered or Exact is caught,
// counted, and its message kept as a reproducer.
//
// Reproducers: the first few failures of each family are kept as text: what failed, the
// pair's recipe (family, seed, index and its parameters) and its coordinates with %.17g.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rockcontact/generators/pair_generators.hpp"
#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/intersection_polygon.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::robustness {

// ---- error bounds of Filtered constructions against Exact ---------------------------------

// Per-coordinate bound (m) on |Filtered crossing - Exact crossing| of IP vertex `v` (a
// crossing), given both constructed points. Derived in pair_campaign.cpp.
struct CrossingBound {
  double x;
  double y;
};
CrossingBound crossing_bound(const kernel::ConvexPolygon& cp, const kernel::ConvexPolygon& tp,
                             const kernel::IpVertex& v, const Point2& filtered, const Point2& exact);

// Bound (N/m, per component) on |Filtered force - Exact force| of a pair whose Filtered and
// Exact IP labels are `ip`; `filtered` and `exact` are the IP points constructed under each
// policy. Derived in pair_campaign.cpp.
double force_bound(const kernel::ConvexPolygon& cp, const kernel::ConvexPolygon& tp,
                   const kernel::IntersectionPolygon& ip, std::span<const Point2> filtered,
                   std::span<const Point2> exact, const contact::PotentialContactParams& params);

// ---- the campaign --------------------------------------------------------------------------

enum class Property : std::uint8_t {
  ip_matches_verdict,  // IP non-empty exactly when the verdict is overlap (Filtered and Exact)
  ip_convex_ccw,       // exact IP strictly convex, counter-clockwise
  ip_inside_both,      // exact IP vertices in CP and in TP
  ip_edge_labels,      // an IP edge on CP/TP edge i has both ends on that edge's line
  ip_area,             // area(IP) <= min(area(CP), area(TP)), exactly
  exact_rounding,      // Exact's constructed points are the exact vertices rounded to nearest
  translation,         // verdict and IP labels unchanged by an exact translation
  rotation,            // ... by the exact rotation (x, y) -> (-y, x); force rotated
  swap,                // f(tp, cp) = -f(cp, tp), verdict symmetric
  touch_continuity,    // force -> 0 at least linearly as a touching pair is pushed in
  count
};
inline constexpr std::size_t property_count = static_cast<std::size_t>(Property::count);
std::string_view to_string(Property property);

inline constexpr std::uint64_t default_campaign_seed = 0x5eed'2024'0611ull;

struct CampaignOptions {
  std::uint64_t seed = default_campaign_seed;
  std::size_t cases_per_family = 1000;
  // The Exact force (and its rotated, swapped and paper-mode twins) on cases whose index is a
  // multiple of this; 1 runs it on every case.
  std::size_t exact_force_stride = 4;
  unsigned threads = 1;
  // Cases per unit of work handed to a thread; results do not depend on it or on `threads`.
  std::size_t chunk = 500;
  std::size_t reproducers_per_family = 5;
  std::vector<Family> families{all_families.begin(), all_families.end()};
  contact::PotentialContactParams params = contact::default_potential_contact_params();
};

struct FamilyStats {
  Family family = Family::random;
  std::size_t cases = 0;
  std::array<std::size_t, 3> verdicts{};  // under Exact: separate, touch, overlap
  // Float against Exact (measured, not asserted).
  std::size_t float_verdict = 0;       // different verdict
  std::size_t float_ip = 0;            // different IP labels
  std::size_t float_inconsistent = 0;  // Float's IP non-empty != (Float's verdict == overlap)
  std::size_t float_exceptions = 0;    // Float threw
  // Filtered against Exact (each must be zero).
  std::size_t filtered_verdict = 0;
  std::size_t filtered_ip = 0;      // IP labels, also of evaluate_pair and pushed pairs
  std::size_t filtered_points = 0;  // a crossing outside crossing_bound, a vertex not copied
  std::size_t filtered_force = 0;   // a force outside force_bound, or a force without overlap
  std::size_t crashes = 0;
  std::array<std::size_t, property_count> violations{};
  kernel::PredicateCounters filtered_counters;  // Filtered classify + clip of the pair
  std::size_t crossings = 0;            // IP crossings compared with crossing_bound
  std::size_t exact_force_cases = 0;    // overlapping cases whose force ran under Exact
  double worst_crossing_ratio = 0.0;    // max over crossings of error / crossing_bound
  double worst_force_ratio = 0.0;       // max over Exact-force cases of error / force_bound
  std::size_t touch_pushes = 0;         // pushed touching pairs whose force was checked
  std::size_t touch_push_overlaps = 0;  // of which overlapping
  double worst_continuity_ratio = 0.0;  // max |f| / (kn/H h |d| min perimeter)
  std::vector<double> paper_error;      // |f_paper - f_exact| / |f_exact| per Exact-force case
  double seconds = 0.0;                 // thread time spent on this family's cases
  std::vector<std::string> reproducers;

  std::size_t float_disagreements() const { return float_verdict + float_ip + float_exceptions; }
  std::size_t filtered_disagreements() const {
    return filtered_verdict + filtered_ip + filtered_points + filtered_force;
  }
  std::size_t property_violations() const;
  double interval_fallback_rate() const;  // Filtered interval-stage entries / calls; 0 without calls
  double fallback_rate() const;           // Filtered exact-stage entries / calls; 0 without calls
  double paper_error_max() const;    // 0 without samples
  double paper_error_median() const;
  double paper_error_p99() const;            // 99th percentile
  std::size_t paper_error_nonzero() const;   // samples where paper and exact differ at all
};

struct CampaignResult {
  CampaignOptions options;
  std::vector<FamilyStats> families;  // in options.families order
  double wall_seconds = 0.0;

  FamilyStats total() const;  // every family merged (family field meaningless)
};

// Runs the campaign on options.threads threads. Deterministic: every count, ratio and
// reproducer is the same for any thread count and chunk size (times aside).
CampaignResult run_campaign(const CampaignOptions& options);

// The markdown table: family | cases | Float disagreements | Filtered disagreements | crashes |
// fallback rate (interval / exact) | paper-vs-exact force error | property violations | seconds,
// plus a total row.
std::string format_table(const CampaignResult& result);
// Per-family details: verdict counts, comparisons made, worst error/bound ratios, touch pushes,
// violations by property; then every kept reproducer.
std::string format_details(const CampaignResult& result);

}  // namespace rockcontact::robustness
