#pragma once
// The 3D pair campaign: every generated pair (generators/.../pair3d_generators.hpp) run through
// the 3D pair queries (pair3d_queries.hpp: every query of the pairs contract) under Float, Filtered,
// Checked and Exact, the properties below checked on every case and tallied per family.
// pair3d_properties_test.cpp runs a slice of it in CI; robustness_table3d runs it at full size
// (10^6 pairs) and prints the markdown table of the README.
//
// Checked on every case (pair = generate_pair3d(family, seed, index)):
//   Policy agreement. Checked (Filtered's staged predicates, each sign also evaluated exactly
//     on its own: a PolicyDisagreement is a disagreement) and Filtered give Exact's result
//     (staged_differences). Float's verdict is compared with Exact's and counted, not asserted.
//   Properties, of the Exact result:
//     * expected_verdict: the verdict the generator's construction implies, where it implies
//       one (the touching families and their gap/push variants, offset_1e6 pairs the snap left
//       unchanged);
//     * swap: the verdict of (b, a) equals that of (a, b) (under Checked and Exact).
//   Fallback rates: the predicate counters (predicate_stats.hpp) around the Filtered run:
//     calls that reached the interval stage and the exact stage.
// Crashes: any exception but PolicyDisagreement under Checked, Filtered or Exact is caught,
// counted, and its message kept as a reproducer (the recipe regenerates the pair).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rockcontact/generators/pair3d_generators.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::robustness {

enum class Property3d : std::uint8_t {
  expected_verdict,  // the construction's verdict, where it implies one
  swap,              // verdict(b, a) == verdict(a, b)
  held,              // an overlapping pair has a closed constraint (gap <= 0)
  within_depth,      // no constraint deeper than the pair's penetration depth (+ rounding)
  count
};
inline constexpr std::size_t property3d_count = static_cast<std::size_t>(Property3d::count);
std::string_view to_string(Property3d property);

inline constexpr std::uint64_t default_campaign3d_seed = 0x5eed'2026'1125ull;

struct Campaign3dOptions {
  std::uint64_t seed = default_campaign3d_seed;
  std::size_t cases_per_family = 250;
  unsigned threads = 1;
  // Cases per unit of work handed to a thread; results do not depend on it or on `threads`.
  std::size_t chunk = 250;
  std::size_t reproducers_per_family = 5;
  std::vector<Family3d> families{all_families3d.begin(), all_families3d.end()};
};

struct Family3dStats {
  Family3d family = Family3d::random;
  std::size_t cases = 0;
  std::array<std::size_t, 3> verdicts{};  // under Exact: separate, touch, overlap
  std::size_t with_expected = 0;          // cases whose construction implies a verdict
  // Float against Exact (measured, not asserted).
  std::size_t float_verdict = 0;
  std::size_t float_exceptions = 0;
  // Each must be zero.
  std::size_t checked_disagreements = 0;  // PolicyDisagreement thrown under Checked
  std::size_t staged_differences = 0;     // Checked's or Filtered's result differs from Exact's
  std::size_t crashes = 0;
  std::array<std::size_t, property3d_count> violations{};
  kernel::PredicateCounters filtered_counters;  // the Filtered run of (a, b)
  double seconds = 0.0;                         // thread time spent on this family's cases
  std::vector<std::string> reproducers;

  std::size_t disagreements() const { return checked_disagreements + staged_differences; }
  std::size_t property_violations() const;
  double interval_fallback_rate() const;  // interval-stage entries / calls; 0 without calls
  double fallback_rate() const;           // exact-stage entries / calls; 0 without calls
};

struct Campaign3dResult {
  Campaign3dOptions options;
  std::vector<Family3dStats> families;  // in options.families order
  double wall_seconds = 0.0;

  Family3dStats total() const;  // every family merged (family field meaningless)
};

// Runs the campaign on options.threads threads; every count and reproducer is the same for
// any thread count and chunk size (times aside).
Campaign3dResult run_campaign3d(const Campaign3dOptions& options);

// family | cases | separate / touch / overlap | with expected verdict | Float wrong verdict |
// disagreements | crashes | fallback rate (interval / exact) | property violations | seconds,
// plus a total row and a line with the run's parameters.
std::string format_table3d(const Campaign3dResult& result);
// Violations by property and the kept reproducers.
std::string format_details3d(const Campaign3dResult& result);

}  // namespace rockcontact::robustness
