// rockcontact: the command-line driver. One pair of functions per subcommand: `add_<name>`
// declares its options and registers `run_<name>` as its callback, which CLI11 calls once the
// command line is parsed; the callback's return value is the exit status.
//
// Exit status: 0 success (pairs with an invalid polygon are results, not failures), 2 malformed
// input, bad flags or an output file that cannot be written, 1 an unexpected internal error.

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "rockcontact/dynamics/pairs_io.hpp"
#include "rockcontact/dynamics/pairs_summary.hpp"
#include "rockcontact/kernel/demarcation.hpp"
#include "rockcontact/kernel/number_policy.hpp"

namespace {

namespace dyn = rockcontact::dynamics;
namespace kernel = rockcontact::kernel;

constexpr int exit_ok = 0;
constexpr int exit_internal_error = 1;
constexpr int exit_bad_input = 2;

struct PairsOptions {
  std::string input;
  std::string output;  // empty: no JSON; "-": JSON on stdout, summary on stderr
  std::string policy;
  std::string demarcation;
};

// A command line that cannot be carried out as given (an output path that cannot be written).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void write_json(const std::string& target, const nlohmann::ordered_json& document) {
  if (target == "-") {
    std::cout << document.dump(2) << '\n';
    return;
  }
  std::ofstream file(target);
  file << document.dump(2) << '\n';
  if (!file.flush()) throw UsageError("cannot write " + target + ": " + std::strerror(errno));
}

int run_pairs(const PairsOptions& options) {
  const dyn::PairsInput input = dyn::read_pairs_file(options.input);
  dyn::PairsOverrides overrides;
  if (!options.policy.empty()) overrides.policy = kernel::parse_policy(options.policy);
  if (!options.demarcation.empty())
    overrides.demarcation = kernel::parse_demarcation(options.demarcation);
  const nlohmann::ordered_json document = dyn::run_pairs(input, overrides);
  if (!options.output.empty()) write_json(options.output, document);
  std::ostream& summary = options.output == "-" ? std::cerr : std::cout;
  dyn::write_pairs_summary(summary, document);
  if (!options.output.empty() && options.output != "-")
    summary << "JSON written to " << options.output << '\n';
  return exit_ok;
}

void add_pairs(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<PairsOptions>();
  CLI::App* sub = app.add_subcommand(
      "pairs", "Evaluate the contact of polygon pairs read from JSON under a number policy");
  sub->add_option("input", options->input, "Input JSON: kn, H, pairs [{id, cp, tp}]")->required();
  sub->add_option("-o,--output", options->output,
                  "Write the result document as JSON ('-' for stdout)");
  sub->add_option("--policy", options->policy,
                  "Number policy, overrides the file's (default filtered)")
      ->check(CLI::IsMember({"float", "filtered", "exact"}));
  sub->add_option("--demarcation", options->demarcation,
                  "Demarcation points, overrides the file's (default exact)")
      ->check(CLI::IsMember({"paper", "exact"}));
  sub->callback([options, &exit_status] { exit_status = run_pairs(*options); });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rockcontact: robust contact of polygonal rock blocks"};
  app.set_version_flag("--version", std::string("rockcontact ") + ROCKCONTACT_VERSION);
  app.require_subcommand(1);
  int exit_status = exit_ok;
  add_pairs(app, exit_status);
  try {
    app.parse(argc, argv);
    return exit_status;
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? exit_ok : exit_bad_input;
  } catch (const dyn::InputError& e) {
    std::cerr << "rockcontact: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const UsageError& e) {
    std::cerr << "rockcontact: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::exception& e) {
    std::cerr << "rockcontact: internal error: " << e.what() << '\n';
    return exit_internal_error;
  }
}
