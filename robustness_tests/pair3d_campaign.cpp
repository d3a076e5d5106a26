#include "pair3d_campaign.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>
#include <thread>

#include "pair3d_queries.hpp"
#include "rockcontact/kernel/3d/tolerances.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/policy_disagreement.hpp"

namespace rockcontact::robustness {
namespace {

namespace rk = kernel;
using rk::Overlap;

void keep(Family3dStats& stats, const PolyhedronPair& pair, const std::string& what) {
  if (stats.reproducers.size() < 64) stats.reproducers.push_back(pair.recipe + ": " + what);
}

void violation(Family3dStats& stats, Property3d p, const PolyhedronPair& pair, const std::string& what) {
  ++stats.violations[static_cast<std::size_t>(p)];
  keep(stats, pair, std::string(to_string(p)) + ": " + what);
}

// Checked on (a, b) and (b, a); a PolicyDisagreement is counted and ends the case.
std::optional<std::pair<Pair3dResult, Pair3dResult>> run_checked(const PolyhedronPair& pair, Family3dStats& stats) {
  try {
    return std::pair{evaluate_pair3d<rk::Checked>(pair.a, pair.b), evaluate_pair3d<rk::Checked>(pair.b, pair.a)};
  } catch (const rk::PolicyDisagreement& e) {
    ++stats.checked_disagreements;
    keep(stats, pair, std::string("Checked: ") + e.what());
    return std::nullopt;
  }
}

// The constraints of an overlapping pair against its exact penetration depth (the kernel's
// under Exact, rounded once): at least one closed, none deeper than the depth plus the kernel's
// penetration_slack of the pair's size (the slack its own comparison uses) and 64 ulps of it
// (the rounding of a gap in a frame at cp's first vertex, measured within 4 ulps).
void check_constraints(const PolyhedronPair& pair, const Pair3dResult& result, const std::string& policy,
                       Family3dStats& stats) {
  if (result.verdict != Overlap::overlap || !result.queries.penetration) return;
  const double depth = result.queries.penetration->depth;
  const double slack = (rk::penetration_slack + 64 * 0x1p-52) * 2.0 * result.size;
  const auto& cs = result.queries.constraints;
  if (std::none_of(cs.begin(), cs.end(), [](const rk::ContactConstraint& c) { return c.gap <= 0.0; })) {
    violation(stats, Property3d::held, pair, policy + ": overlapping by " + std::to_string(depth) +
                                                 " m with no closed constraint");
  }
  for (const rk::ContactConstraint& c : cs) {
    if (c.gap < -(depth + slack)) {
      violation(stats, Property3d::within_depth, pair,
                policy + ": a " + std::string(contact::to_string(c.type)) + " constraint's gap " +
                    std::to_string(c.gap) + " m is deeper than the penetration depth " + std::to_string(depth) + " m");
      break;
    }
  }
}

void check_case(const PolyhedronPair& pair, Family3dStats& stats) {
  const Pair3dResult exact = evaluate_pair3d<rk::Exact>(pair.a, pair.b);
  const Pair3dResult exact_swapped = evaluate_pair3d<rk::Exact>(pair.b, pair.a);
  ++stats.verdicts[static_cast<std::size_t>(exact.verdict)];

  const rk::PredicateCounters before = rk::predicate_counters();
  const Pair3dResult filtered = evaluate_pair3d<rk::Filtered>(pair.a, pair.b);
  stats.filtered_counters += rk::predicate_counters() - before;
  std::string diff = staged_differences(filtered, exact);
  if (const auto checked = run_checked(pair, stats)) {
    diff += staged_differences(checked->first, exact) + staged_differences(checked->second, exact_swapped);
    const std::string swap = swap_differences(checked->first, checked->second);
    if (!swap.empty()) violation(stats, Property3d::swap, pair, "Checked: " + swap);
  }
  if (!diff.empty()) {
    ++stats.staged_differences;
    keep(stats, pair, "staged vs Exact: " + diff);
  }
  const std::string swap = swap_differences(exact, exact_swapped);
  if (!swap.empty()) violation(stats, Property3d::swap, pair, "Exact: " + swap);
  if (pair.expected) {
    ++stats.with_expected;
    if (exact.verdict != *pair.expected) {
      violation(stats, Property3d::expected_verdict, pair,
                "Exact says " + std::string(rk::to_string(exact.verdict)) + ", the construction " +
                    std::string(rk::to_string(*pair.expected)));
    }
  }

  check_constraints(pair, exact, "Exact", stats);
  check_constraints(pair, filtered, "Filtered", stats);

  try {
    if (evaluate_pair3d<rk::Float>(pair.a, pair.b).verdict != exact.verdict) ++stats.float_verdict;
  } catch (const std::exception&) {
    ++stats.float_exceptions;
  }
}

void run_case(const Campaign3dOptions& options, Family3d family, std::uint64_t index, Family3dStats& stats) {
  ++stats.cases;
  std::string recipe = std::string(to_string(family)) + " seed " + std::to_string(options.seed) + " index " +
                       std::to_string(index);
  try {
    const PolyhedronPair pair = generate_pair3d(family, options.seed, index);
    recipe = pair.recipe;
    check_case(pair, stats);
  } catch (const std::exception& e) {
    ++stats.crashes;
    if (stats.reproducers.size() < 64) stats.reproducers.push_back(recipe + ": crash: " + e.what());
  }
}

void merge(Family3dStats& into, const Family3dStats& part, std::size_t reproducer_limit) {
  into.cases += part.cases;
  for (std::size_t i = 0; i < 3; ++i) into.verdicts[i] += part.verdicts[i];
  into.with_expected += part.with_expected;
  into.float_verdict += part.float_verdict;
  into.float_exceptions += part.float_exceptions;
  into.checked_disagreements += part.checked_disagreements;
  into.staged_differences += part.staged_differences;
  into.crashes += part.crashes;
  for (std::size_t i = 0; i < property3d_count; ++i) into.violations[i] += part.violations[i];
  into.filtered_counters += part.filtered_counters;
  into.seconds += part.seconds;
  for (const std::string& r : part.reproducers) {
    if (into.reproducers.size() < reproducer_limit) into.reproducers.push_back(r);
  }
}

struct Unit {
  std::size_t family_slot;
  std::size_t begin;
  std::size_t end;
};

double rate(std::uint64_t part, std::uint64_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

}  // namespace

std::string_view to_string(Property3d property) {
  switch (property) {
    case Property3d::expected_verdict: return "expected_verdict";
    case Property3d::swap: return "swap";
    case Property3d::held: return "held";
    case Property3d::within_depth: return "within_depth";
    case Property3d::count: break;
  }
  return "?";
}

std::size_t Family3dStats::property_violations() const {
  std::size_t sum = 0;
  for (std::size_t v : violations) sum += v;
  return sum;
}

double Family3dStats::interval_fallback_rate() const {
  return rate(filtered_counters.total_interval_fallbacks(), filtered_counters.total_calls());
}

double Family3dStats::fallback_rate() const {
  return rate(filtered_counters.total_fallbacks(), filtered_counters.total_calls());
}

Family3dStats Campaign3dResult::total() const {
  Family3dStats sum;
  for (const Family3dStats& f : families) merge(sum, f, 0);
  return sum;
}

Campaign3dResult run_campaign3d(const Campaign3dOptions& options) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const std::size_t chunk = std::max<std::size_t>(options.chunk, 1);
  std::vector<Unit> units;
  for (std::size_t slot = 0; slot < options.families.size(); ++slot) {
    for (std::size_t begin = 0; begin < options.cases_per_family; begin += chunk) {
      units.push_back({slot, begin, std::min(begin + chunk, options.cases_per_family)});
    }
  }
  std::vector<Family3dStats> parts(units.size());
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    for (std::size_t i = next++; i < units.size(); i = next++) {
      const Unit& unit = units[i];
      const Clock::time_point unit_start = Clock::now();
      for (std::size_t index = unit.begin; index < unit.end; ++index) {
        run_case(options, options.families[unit.family_slot], index, parts[i]);
      }
      parts[i].seconds = std::chrono::duration<double>(Clock::now() - unit_start).count();
    }
  };
  const unsigned threads = std::max(1u, options.threads);
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();

  // Merged in unit order: counts and reproducers do not depend on the thread schedule.
  Campaign3dResult result;
  result.options = options;
  for (Family3d family : options.families) {
    result.families.emplace_back();
    result.families.back().family = family;
  }
  for (std::size_t i = 0; i < units.size(); ++i) {
    merge(result.families[units[i].family_slot], parts[i], options.reproducers_per_family);
  }
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

namespace {

std::string table_row(std::string_view name, const Family3dStats& s) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "| %s | %zu | %zu / %zu / %zu | %zu | %zu | %zu | %zu | %.2e / %.2e | %zu | %.1f |\n",
                std::string(name).c_str(), s.cases, s.verdicts[0], s.verdicts[1], s.verdicts[2], s.with_expected,
                s.float_verdict + s.float_exceptions, s.disagreements(), s.crashes, s.interval_fallback_rate(),
                s.fallback_rate(), s.property_violations(), s.seconds);
  return buffer;
}

}  // namespace

std::string format_table3d(const Campaign3dResult& result) {
  std::string out =
      "| family | cases | separate / touch / overlap (Exact) | with expected verdict | Float wrong verdict | "
      "disagreements (Checked, Filtered vs Exact) | crashes | Filtered fallback rate (interval / exact) | "
      "property violations | seconds |\n|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const Family3dStats& f : result.families) out += table_row(to_string(f.family), f);
  out += table_row("**total**", result.total());
  char buffer[256];
  std::snprintf(buffer, sizeof buffer,
                "\nseed %llu, %zu cases per family, %u thread(s), %.1f s wall (the seconds column is thread time)\n",
                static_cast<unsigned long long>(result.options.seed), result.options.cases_per_family,
                result.options.threads, result.wall_seconds);
  return out + buffer;
}

std::string format_details3d(const Campaign3dResult& result) {
  std::string out;
  for (const Family3dStats& f : result.families) {
    for (std::size_t i = 0; i < property3d_count; ++i) {
      if (f.violations[i] == 0) continue;
      out += std::string(to_string(f.family)) + ": " + std::to_string(f.violations[i]) + " violations of " +
             std::string(to_string(static_cast<Property3d>(i))) + "\n";
    }
    for (const std::string& r : f.reproducers) out += "reproducer: " + r + "\n";
  }
  return out;
}

}  // namespace rockcontact::robustness
