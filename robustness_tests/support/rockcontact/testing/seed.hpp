#pragma once
// Seeds of randomised tests: a fixed default, overridable with ROCKCONTACT_TEST_SEED, always
// printed, so any failure can be replayed.

#include <boost/test/unit_test.hpp>

#include <cstdint>
#include <cstdlib>
#include <string>

namespace rockcontact::testing {

// Unit roundoff of double, round to nearest.
inline constexpr double unit_roundoff = 0x1p-53;

inline std::uint64_t seed_for(const std::string& test, std::uint64_t fallback) {
  const char* env = std::getenv("ROCKCONTACT_TEST_SEED");
  const std::uint64_t seed = env != nullptr ? std::strtoull(env, nullptr, 10) : fallback;
  BOOST_TEST_MESSAGE(test << ": seed " << seed << " (override with ROCKCONTACT_TEST_SEED)");
  return seed;
}

}  // namespace rockcontact::testing
