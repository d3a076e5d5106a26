#define BOOST_TEST_MODULE robustness_pair3d_properties

// The CI slice of the 3D pair campaign (pair3d_campaign.hpp lists every property): seed
// ROCKCONTACT_CAMPAIGN_SEED (unset: a fixed default), ROCKCONTACT_ROBUSTNESS_CASES cases per
// family (default below). Asserted per family: no PolicyDisagreement under Checked, Checked and
// Filtered give Exact's results, no case throws, no property is violated (the constructed
// verdict, the swap symmetry). Float's wrong verdicts are measured and printed, not asserted.
// The full run (10^6 pairs) is the robustness_table3d executable.

#include <boost/test/unit_test.hpp>

#include <cstdio>
#include <cstdlib>

#include "pair3d_campaign.hpp"

namespace {

namespace rb = rockcontact::robustness;

// 250 cases per family, 12 families: 3000 pairs (time in the README).
constexpr std::size_t default_cases_per_family = 250;

}  // namespace

BOOST_AUTO_TEST_CASE(staged_agrees_with_exact_and_every_property_holds) {
  rb::Campaign3dOptions options;
  const char* seed = std::getenv("ROCKCONTACT_CAMPAIGN_SEED");
  options.seed = seed != nullptr && *seed != '\0' ? std::strtoull(seed, nullptr, 10) : rb::default_campaign3d_seed;
  const char* cases = std::getenv("ROCKCONTACT_ROBUSTNESS_CASES");
  options.cases_per_family = cases != nullptr ? std::strtoull(cases, nullptr, 10) : default_cases_per_family;
  BOOST_TEST_MESSAGE("3D pair campaign: seed " << options.seed << ", " << options.cases_per_family
                                               << " cases per family (ROCKCONTACT_CAMPAIGN_SEED, "
                                                  "ROCKCONTACT_ROBUSTNESS_CASES)");
  const rb::Campaign3dResult result = rb::run_campaign3d(options);
  std::printf("%s\n%s", rb::format_table3d(result).c_str(), rb::format_details3d(result).c_str());
  std::fflush(stdout);

  for (const rb::Family3dStats& f : result.families) {
    BOOST_TEST_CONTEXT(rb::to_string(f.family)) {
      BOOST_TEST(f.cases == options.cases_per_family);
      BOOST_TEST(f.checked_disagreements == 0u);
      BOOST_TEST(f.staged_differences == 0u);
      BOOST_TEST(f.crashes == 0u);
      for (std::size_t i = 0; i < rb::property3d_count; ++i) {
        BOOST_TEST_CONTEXT(rb::to_string(static_cast<rb::Property3d>(i))) { BOOST_TEST(f.violations[i] == 0u); }
      }
    }
  }
  // The expected-verdict property must have had something to check, in all three verdicts.
  const rb::Family3dStats total = result.total();
  BOOST_TEST(total.with_expected > options.cases_per_family);
  for (std::size_t v : total.verdicts) BOOST_TEST(v > 0u);
}
