#define BOOST_TEST_MODULE fuzz_cases
// `rockcontact fuzz-cases` end to end: the file it writes is a `pairs` input whose pairs are
// the generators' bit for bit, with the ids FAMILY-sSEED-iINDEX.

#include <bit>
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "rockcontact/generators/pair_generators.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "run_command.hpp"

namespace dyn = rockcontact::dynamics;
namespace rb = rockcontact::robustness;
using rockcontact::test::quoted;
using rockcontact::test::run_command;

namespace {

const std::string cli = quoted(ROCKCONTACT_CLI);

bool same_bits(const std::vector<rockcontact::kernel::Point2>& a,
               const std::vector<rockcontact::kernel::Point2>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::bit_cast<std::uint64_t>(a[i].x) != std::bit_cast<std::uint64_t>(b[i].x) ||
        std::bit_cast<std::uint64_t>(a[i].y) != std::bit_cast<std::uint64_t>(b[i].y)) {
      return false;
    }
  }
  return true;
}

// The pairs of `input` from `first` on are generate_pair(family, seed, 0 .. count - 1).
void check_family(const dyn::PairsInput& input, std::size_t first, rb::Family family,
                  std::uint64_t seed, std::uint64_t count) {
  BOOST_TEST_REQUIRE(input.pairs.size() >= first + count);
  for (std::uint64_t i = 0; i < count; ++i) {
    const dyn::PairSpec& spec = input.pairs[first + i];
    const rb::PolygonPair pair = rb::generate_pair(family, seed, i);
    BOOST_TEST(spec.id == std::string(rb::to_string(family)) + "-s" + std::to_string(seed) + "-i" +
                              std::to_string(i));
    BOOST_TEST(same_bits(spec.cp, pair.cp), spec.id << ": cp differs from the generator's");
    BOOST_TEST(same_bits(spec.tp, pair.tp), spec.id << ": tp differs from the generator's");
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(one_family_reads_back_bit_for_bit) {
  const auto file = rockcontact::test::fresh_directory("fuzz_cases_one") / "sliver.json";
  BOOST_TEST_REQUIRE(
      run_command(cli + " fuzz-cases --family sliver --count 7 --seed 3 -o " + quoted(file)) == 0);
  const dyn::PairsInput input = dyn::read_pairs_file(file);
  BOOST_TEST(input.kn == 1e7);
  BOOST_TEST(input.H == 1.0);
  BOOST_TEST((input.demarcation == rockcontact::kernel::Demarcation::exact));
  BOOST_TEST(input.pairs.size() == 7u);
  check_family(input, 0, rb::Family::sliver, 3, 7);
}

BOOST_AUTO_TEST_CASE(all_families_in_order_with_kn_and_H) {
  const auto file = rockcontact::test::fresh_directory("fuzz_cases_all") / "all.json";
  BOOST_TEST_REQUIRE(run_command(cli + " fuzz-cases --family all --count 2 --seed 5 --kn 2e9 " +
                                 "--H 0.25 -o " + quoted(file)) == 0);
  const dyn::PairsInput input = dyn::read_pairs_file(file);
  BOOST_TEST(input.kn == 2e9);
  BOOST_TEST(input.H == 0.25);
  BOOST_TEST(input.pairs.size() == 2 * rb::all_families.size());
  for (std::size_t f = 0; f < rb::all_families.size(); ++f) {
    check_family(input, 2 * f, rb::all_families[f], 5, 2);
  }
}

BOOST_AUTO_TEST_CASE(family_list_to_stdout) {
  const auto file = rockcontact::test::fresh_directory("fuzz_cases_list") / "stdout.json";
  BOOST_TEST_REQUIRE(run_command(cli + " fuzz-cases --family near_parallel_ulp,sliver --count 3 " +
                                 "-o - > " + quoted(file) + " 2> /dev/null") == 0);
  const dyn::PairsInput input = dyn::read_pairs_file(file);
  BOOST_TEST(input.pairs.size() == 6u);
  check_family(input, 0, rb::Family::near_parallel_ulp, 1, 3);  // default seed 1
  check_family(input, 3, rb::Family::sliver, 1, 3);
}

BOOST_AUTO_TEST_CASE(unknown_family_exits_2_listing_the_families) {
  const auto dir = rockcontact::test::fresh_directory("fuzz_cases_bad");
  BOOST_TEST(run_command(cli + " fuzz-cases --family sliver,slivers --count 1 -o " +
                         quoted(dir / "x.json") + " 2> " + quoted(dir / "err.txt")) == 2);
  const std::string message = rockcontact::test::read_text(dir / "err.txt");
  BOOST_TEST_MESSAGE(message);
  BOOST_TEST(message.find("--family: unknown family in \"sliver,slivers\"; expected all") !=
             std::string::npos);
  for (const rb::Family family : rb::all_families) {
    BOOST_TEST(message.find(", " + std::string(rb::to_string(family))) != std::string::npos);
  }
  BOOST_TEST(!std::filesystem::exists(dir / "x.json"));
}
