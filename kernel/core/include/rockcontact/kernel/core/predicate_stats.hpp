#pragma once
// Thread-local counters of predicate calls and of their fallbacks, per stage.
//
// Every staged predicate (kernel/core/detail/staged_sign.hpp) counts its calls, the calls
// whose double filter could not certify the sign (interval_fallbacks: the interval stage ran)
// and the calls whose interval could not either (fallbacks: the exact stage ran). The counters
// are per thread, cost an increment of a thread-local array, and compile to nothing when
// ROCKCONTACT_PREDICATE_STATS is 0. Read them with predicate_counters(), difference two
// snapshots to attribute work to a block of code.

#include <array>
#include <cstddef>
#include <cstdint>

namespace rockcontact::kernel {

enum class PredicateKind : std::uint8_t {
  cross,          // sign of (p1 - p0) x (q1 - q0)         degree 2
  crossing_side,  // side of a line-line crossing point    degree 4
  crossing_point, // a crossing's coordinates (crossing_point.hpp): a construction filtered like
                  // a predicate, whose fallback constructs exactly
  triple,         // sign of ((p1 - p0) x (q1 - q0)) . (r1 - r0), 3D   degree 3
  plane_side,     // side of a plane at the meeting point of three planes, or of a plane given by
                  // coefficients at an input point (3D, plane.hpp); appended last so that
                  // checkpoints written before it read its count as zero
  count
};
inline constexpr std::size_t predicate_kind_count = static_cast<std::size_t>(PredicateKind::count);

struct PredicateCounters {
  std::array<std::uint64_t, predicate_kind_count> calls{};
  std::array<std::uint64_t, predicate_kind_count> interval_fallbacks{};  // reached the interval stage
  std::array<std::uint64_t, predicate_kind_count> fallbacks{};           // reached the exact stage

  std::uint64_t total_calls() const {
    std::uint64_t sum = 0;
    for (auto c : calls) sum += c;
    return sum;
  }
  std::uint64_t total_interval_fallbacks() const {
    std::uint64_t sum = 0;
    for (auto c : interval_fallbacks) sum += c;
    return sum;
  }
  std::uint64_t total_fallbacks() const {
    std::uint64_t sum = 0;
    for (auto c : fallbacks) sum += c;
    return sum;
  }
  friend PredicateCounters operator-(PredicateCounters a, const PredicateCounters& b) {
    for (std::size_t i = 0; i < predicate_kind_count; ++i) {
      a.calls[i] -= b.calls[i];
      a.interval_fallbacks[i] -= b.interval_fallbacks[i];
      a.fallbacks[i] -= b.fallbacks[i];
    }
    return a;
  }
  PredicateCounters& operator+=(const PredicateCounters& b) {
    for (std::size_t i = 0; i < predicate_kind_count; ++i) {
      calls[i] += b.calls[i];
      interval_fallbacks[i] += b.interval_fallbacks[i];
      fallbacks[i] += b.fallbacks[i];
    }
    return *this;
  }
};

namespace detail {
inline thread_local PredicateCounters thread_counters;

inline void count_call([[maybe_unused]] PredicateKind kind) {
#if ROCKCONTACT_PREDICATE_STATS
  ++thread_counters.calls[static_cast<std::size_t>(kind)];
#endif
}
inline void count_interval_fallback([[maybe_unused]] PredicateKind kind) {
#if ROCKCONTACT_PREDICATE_STATS
  ++thread_counters.interval_fallbacks[static_cast<std::size_t>(kind)];
#endif
}
inline void count_fallback([[maybe_unused]] PredicateKind kind) {
#if ROCKCONTACT_PREDICATE_STATS
  ++thread_counters.fallbacks[static_cast<std::size_t>(kind)];
#endif
}
}  // namespace detail

// A snapshot of this thread's counters (all zero when statistics are compiled out).
inline PredicateCounters predicate_counters() { return detail::thread_counters; }
inline void reset_predicate_counters() { detail::thread_counters = {}; }

}  // namespace rockcontact::kernel
