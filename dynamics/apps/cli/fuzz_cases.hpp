#pragma once
// `rockcontact fuzz-cases`: pairs from the robustness generators (robustness_tests/
// pair_generators.hpp) written as a `pairs` input document (pairs_io.hpp), to feed our kernel
// and someone else's with the same nasty cases.
//
// A pair's id is its recipe: "FAMILY-sSEED-iINDEX" (e.g. "sliver-s1-i17") is generate_pair(
// FAMILY, SEED, INDEX), so a case found in a comparison is regenerated from its id alone, and
// the input schema stays as it is (a pair has no room for the recipe text: unknown fields are
// errors). The document is {"kn", "H", "demarcation": "exact", "pairs"}, one pair per line;
// doubles are written in nlohmann-json's shortest round-trip form, so reading the file gives
// the generated polygons bit for bit.

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "rockcontact/generators/pair_generators.hpp"

namespace rockcontact::cli {

struct FuzzCases {
  std::vector<robustness::Family> families;
  std::uint64_t count = 0;  // pairs of each family, indices 0 .. count - 1
  std::uint64_t seed = 1;
  double kn = 1e7;  // Pa
  double H = 1.0;   // m
};

// "all" (every family, in robustness::all_families order) or family names separated by commas
// ("sliver,near_parallel_ulp"), in the order given; nullopt if a name is not a family.
std::optional<std::vector<robustness::Family>> parse_families(std::string_view names);

// "all" and every family name, comma-separated: what --family accepts, for messages.
std::string family_choices();

std::string case_id(robustness::Family family, std::uint64_t seed, std::uint64_t index);

// Writes the document; returns the number of pairs written.
std::uint64_t write_fuzz_cases(std::ostream& out, const FuzzCases& cases);

}  // namespace rockcontact::cli
