#pragma once
// The generators' random numbers (shared by pair_generators.cpp and pair3d_generators.cpp):
// splitmix64's seed mixing and an mt19937_64 with distributions written out, so a stream is
// the same on every platform.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

namespace rockcontact::robustness::detail {

// splitmix64's finaliser (Steele, Lea, Flood 2014): decorrelates the engine seeds of
// neighbouring (seed, family, index) triples.
inline std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Random numbers with distributions written out here: std::uniform_real_distribution and
// friends are implementation-defined, the raw mt19937_64 sequence is not. Every draw is a
// statement of its own or the only draw of its full expression: the order in which a call's
// arguments or an overloaded operator's operands are evaluated is unspecified (GCC goes right
// to left, Clang left to right), and the stream must not depend on it.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  // Uniform on [0, 1): the top 53 bits of one draw, scaled exactly.
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  bool chance(double p) { return unit() < p; }
  double sign() { return chance(0.5) ? 1.0 : -1.0; }

  // Uniform on {lo, ..., hi}, by rejection of the draws below 2^64 mod range (no modulo bias).
  std::int64_t integer(std::int64_t lo, std::int64_t hi) {
    const std::uint64_t range = static_cast<std::uint64_t>(hi - lo) + 1;
    const std::uint64_t threshold = (0 - range) % range;
    std::uint64_t draw = engine_();
    while (draw < threshold) draw = engine_();
    return lo + static_cast<std::int64_t>(draw % range);
  }
  std::size_t index(std::size_t size) {
    return static_cast<std::size_t>(integer(0, static_cast<std::int64_t>(size) - 1));
  }

  // (1 + u) 2^e with e uniform in [lo_exponent, hi_exponent]: log-uniform to within a factor
  // of two per octave; ldexp scales exactly.
  double octaves(int lo_exponent, int hi_exponent) {
    const auto exponent = static_cast<int>(integer(lo_exponent, hi_exponent));
    return std::ldexp(1.0 + unit(), exponent);
  }

  // Log-uniform on [lo, hi] (0 < lo < hi) in the same sense: octaves() over the octaves that
  // meet [lo, hi], draws outside it rejected (ilogb is exact).
  double log_uniform(double lo, double hi) {
    for (;;) {
      const double x = octaves(std::ilogb(lo), std::ilogb(hi));
      if (lo <= x && x <= hi) return x;
    }
  }

  // A raw draw, for the seed of a base pair.
  std::uint64_t bits() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace rockcontact::robustness::detail
