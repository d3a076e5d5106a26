#pragma once
// The timing loop shared by the pair benchmarks: a pass over a pool of pairs per iteration, so
// every contender is timed on the same pairs, with per-pair time and the fallback rates of the
// staged predicates as counters.

#include <benchmark/benchmark.h>

#include <cstddef>

#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::bench {

// Times `one_pair(i)` for i < count per iteration, after one untimed warm-up pass that also
// grows every workspace. Counters: per_pair (s, shown as ns), interval_rate (calls that
// reached the interval stage, per predicate call), fallback_rate (calls that reached the exact
// stage, per call) and predicates (calls per pair).
template <class OnePair>
void run_passes(benchmark::State& state, std::size_t count, OnePair&& one_pair) {
  for (std::size_t i = 0; i < count; ++i) one_pair(i);
  const kernel::PredicateCounters before = kernel::predicate_counters();
  for (auto _ : state) {
    for (std::size_t i = 0; i < count; ++i) one_pair(i);
    benchmark::ClobberMemory();
  }
  const kernel::PredicateCounters spent = kernel::predicate_counters() - before;
  const double pairs = static_cast<double>(state.iterations()) * static_cast<double>(count);
  const double calls = static_cast<double>(spent.total_calls());
  state.counters["per_pair"] =
      benchmark::Counter(pairs, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["interval_rate"] =
      calls > 0 ? static_cast<double>(spent.total_interval_fallbacks()) / calls : 0.0;
  state.counters["fallback_rate"] =
      calls > 0 ? static_cast<double>(spent.total_fallbacks()) / calls : 0.0;
  state.counters["predicates"] = calls / pairs;
}

}  // namespace rockcontact::bench
