// libFuzzer target: the `pairs` input reader (dynamics/pairs_io.hpp) and the pair evaluation
// behind `rockcontact pairs`.
//
// The bytes are the document. read_pairs_file either returns a PairsInput or throws InputError
// with a message "<file>: <path>: <problem>"; any other exception, a crash, a sanitizer report
// or a hang (libFuzzer's -timeout) is a failure. An accepted document must hold what the format
// promises (kn and H finite and > 0, unique ids), and is then evaluated by run_pairs the way
// the CLI does, output serialised with dump(2) included: a polygon error must end up in its
// pair's result, never escape. The evaluation runs under Filtered whatever the document asks
// for: the Exact force costs milliseconds per pair, and Filtered against Exact is
// fuzz_pair_kernel's job.

#include <cmath>
#include <cstdint>
#include <exception>
#include <set>
#include <string>

#include "json_target.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace {

namespace rd = rockcontact::dynamics;
namespace rf = rockcontact::fuzz;
constexpr const char* target = "fuzz_pairs_json";

void check_accepted(const rd::PairsInput& input) {
  if (!(std::isfinite(input.kn) && input.kn > 0.0 && std::isfinite(input.H) && input.H > 0.0)) {
    rf::fail(target, "accepted a document with kn or H not finite and > 0");
  }
  std::set<std::string> ids;
  for (const rd::PairSpec& pair : input.pairs) {
    if (!ids.insert(pair.id).second) rf::fail(target, "accepted a duplicate id");
  }
}

void check_output(const rd::PairsInput& input, const nlohmann::ordered_json& output) {
  const auto& results = output.at("results");
  if (results.size() != input.pairs.size()) rf::fail(target, "run_pairs lost or added a result");
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (results[i].at("id") != input.pairs[i].id) rf::fail(target, "run_pairs reordered the results");
    if (results[i].at("status") == "error" && results[i].at("error").get<std::string>().empty()) {
      rf::fail(target, "a pair's error without a message");
    }
  }
  output.dump(2);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static rf::ScratchFile scratch("fuzz_pairs_json");
  const std::filesystem::path& file = scratch.write({data, size});
  try {
    const rd::PairsInput input = rd::read_pairs_file(file);
    check_accepted(input);
    rd::PairsOverrides overrides;
    overrides.policy = rockcontact::kernel::PolicyKind::filtered;
    check_output(input, rd::run_pairs(input, overrides));
  } catch (const rd::InputError& e) {
    rf::check_input_error(target, e, file);
  } catch (const std::exception& e) {
    rf::fail(target, std::string("an exception other than InputError: ") + e.what());
  }
  return 0;
}
