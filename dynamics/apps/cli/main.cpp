// rockcontact: the command-line driver. One pair of functions per subcommand: `add_<name>`
// declares its options and registers `run_<name>` as its callback, which CLI11 calls once the
// command line is parsed; the callback's return value is the exit status.
//
// Exit status: 0 success (pairs with an invalid polygon are results, not failures), 2 malformed
// input, bad flags, an output file that cannot be written or a scene the engine refuses or
// stops (StabilityError, Stability3dError, CdemStabilityError), 3 a check that failed (a
// `validate` scene off its reference, a `pairs --compare` that found a disagreement), 1 an
// unexpected internal error.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <exception>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_cases.hpp"
#include "rockcontact/dynamics/io/atomic_file.hpp"
#include "rockcontact/dynamics/dda2d.hpp"
#include "rockcontact/dynamics/apps/pairs_compare.hpp"
#include "rockcontact/dynamics/apps/safety_factor.hpp"
#include "rockcontact/dynamics/io/cut3d.hpp"
#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/dynamics/io/pairs_io.hpp"
#include "rockcontact/dynamics/apps/pairs_summary.hpp"
#include "rockcontact/dynamics/apps/report.hpp"
#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"
#include "rockcontact/dynamics/io/scene3d_output.hpp"
#include "rockcontact/dynamics/io/scene_cdem.hpp"
#include "rockcontact/dynamics/io/scene_cdem_output.hpp"
#include "rockcontact/dynamics/io/scene_output.hpp"
#include "rockcontact/dynamics/apps/validation.hpp"
#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace {

namespace dyn = rockcontact::dynamics;
namespace kernel = rockcontact::kernel;

constexpr int exit_ok = 0;
constexpr int exit_internal_error = 1;
constexpr int exit_bad_input = 2;
constexpr int exit_check_failed = 3;

struct PairsOptions {
  std::string input;
  std::string output;  // empty: no JSON; "-": JSON on stdout, summary on stderr
  std::string policy;
  std::string demarcation;
  std::string compare;  // THEIRS.json: compare mode
  dyn::CompareOptions compare_options;
};

void write_json(const std::string& target, const nlohmann::ordered_json& document) {
  if (target == "-") {
    std::cout << document.dump(2) << '\n';
    return;
  }
  dyn::AtomicFile file(target);
  file.stream() << document.dump(2) << '\n';
  file.commit();
}

dyn::PairsOverrides pairs_overrides(const PairsOptions& options) {
  dyn::PairsOverrides overrides;
  if (!options.policy.empty()) overrides.policy = kernel::parse_policy(options.policy);
  if (!options.demarcation.empty())
    overrides.demarcation = kernel::parse_demarcation(options.demarcation);
  return overrides;
}

// `pairs --compare THEIRS IN`: the report on stdout (stderr when the JSON goes to stdout).
int run_compare(const PairsOptions& options) {
  const dyn::PairsInput input = dyn::read_pairs_file(options.input);
  const dyn::ResultsDocument theirs = dyn::read_results_file(options.compare, input.dimension);
  const dyn::Comparison comparison =
      dyn::compare_pairs(input, theirs, pairs_overrides(options), options.compare_options);
  if (!options.output.empty()) write_json(options.output, dyn::comparison_json(comparison));
  std::ostream& report = options.output == "-" ? std::cerr : std::cout;
  dyn::write_comparison(report, comparison);
  if (!options.output.empty() && options.output != "-")
    report << "JSON written to " << options.output << '\n';
  return comparison.agrees() ? exit_ok : exit_check_failed;
}

int run_pairs(const PairsOptions& options) {
  if (!options.compare.empty()) return run_compare(options);
  const dyn::PairsInput input = dyn::read_pairs_file(options.input);
  const nlohmann::ordered_json document = dyn::run_pairs(input, pairs_overrides(options));
  if (!options.output.empty()) write_json(options.output, document);
  std::ostream& summary = options.output == "-" ? std::cerr : std::cout;
  dyn::write_pairs_summary(summary, document);
  if (!options.output.empty() && options.output != "-")
    summary << "JSON written to " << options.output << '\n';
  return exit_ok;
}

void add_compare_options(CLI::App* sub, PairsOptions& options) {
  CLI::Option* compare =
      sub->add_option("--compare", options.compare,
                      "THEIRS.json: another kernel's results for INPUT (output schema of its "
                      "dimension, only results[].id required); compare them with ours field by "
                      "field and exit 3 on a disagreement (dynamics/.../pairs_compare.hpp)");
  sub->add_option("--rtol", options.compare_options.rtol,
                  "With --compare: relative tolerance (error > atol + rtol * scale disagrees)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str()
      ->needs(compare);
  sub->add_option("--atol", options.compare_options.atol,
                  "With --compare: absolute tolerance, in each field's unit (m, m^2, m^3, N/m, "
                  "rad)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str()
      ->needs(compare);
  sub->add_option("--worst", options.compare_options.worst,
                  "With --compare: worst cases shown per field")
      ->capture_default_str()
      ->needs(compare);
}

void add_pairs(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<PairsOptions>();
  CLI::App* sub = app.add_subcommand(
      "pairs",
      "Evaluate the contact of polygon pairs (2D) or polyhedron pairs (\"dimension\": 3) read "
      "from JSON under a number policy, or check another kernel's results for them against "
      "ours (--compare)");
  sub->add_option("input", options->input,
                  "Input JSON: kn, H, pairs [{id, cp, tp}]; in 3D dimension 3, kn, tolerance?, "
                  "pairs [{id, cp: {vertices, faces}, tp}] (docs/user-guide.md)")
      ->required();
  sub->add_option("-o,--output", options->output,
                  "Write the result document (with --compare: the comparison report) as JSON "
                  "('-' for stdout)");
  sub->add_option("--policy", options->policy,
                  "Number policy, overrides the file's (default filtered; with --compare "
                  "default exact, and the file's policy is ignored)")
      ->check(CLI::IsMember({"float", "filtered", "exact", "checked"}));
  sub->add_option("--demarcation", options->demarcation,
                  "Demarcation points, overrides the file's (default exact)")
      ->check(CLI::IsMember({"paper", "exact"}));
  add_compare_options(sub, *options);
  sub->callback([options, &exit_status] { exit_status = run_pairs(*options); });
}

struct RunArgs {
  std::string scene;
  std::string out;
  std::size_t checkpoint_every = 0;
  std::string restart;
  std::size_t threads = 0;  // the engine's params' threads: 0 is one per core
  std::optional<double> dt;        // overrides time.dt, s
  std::optional<double> duration;  // overrides time.duration, s
};

bool stderr_is_terminal() { return isatty(fileno(stderr)) != 0; }

// A one-line progress bar on stderr, drawn only when stderr is a terminal; redrawn when the
// shown per mille changes.
class ProgressBar {
 public:
  ProgressBar() : enabled_(stderr_is_terminal()), start_(std::chrono::steady_clock::now()) {}

  // `done` of `total` steps.
  void update(std::size_t done, std::size_t total) {
    if (!enabled_ || total == 0) return;
    draw(done * 1000 / total, "step " + std::to_string(done) + '/' + std::to_string(total));
  }

  // A 3D run, whose step count is not known ahead (step cuts): `steps` taken, `time` of
  // `duration` simulated.
  void update_time(std::size_t steps, double time, double duration) {
    if (!enabled_) return;
    const double fraction = std::clamp(time / duration, 0.0, 1.0);
    std::ostringstream what;
    what << "step " << steps << ", t = " << std::setprecision(4) << time << " s";
    draw(static_cast<std::size_t>(fraction * 1000.0), what.str());
  }

  // The pre-solve (dynamics/common/equilibrium.hpp): `iterations` done, the out-of-balance
  // ratio reached, towards `tolerance` (the bar: how many of the decades from 1 down to it).
  void update_presolve(std::size_t iterations, double ratio, double tolerance) {
    if (!enabled_) return;
    const double fraction = std::clamp(std::log10(ratio) / std::log10(tolerance), 0.0, 1.0);
    std::ostringstream what;
    what << "initial equilibrium: iteration " << iterations << ", ratio " << std::setprecision(3) << ratio;
    draw(static_cast<std::size_t>(fraction * 1000.0), what.str());
  }

  // Ends the bar's line, if one was drawn.
  void finish() {
    if (drawn_) std::cerr << '\n';
    drawn_ = false;
  }

 private:
  void draw(std::size_t permille, const std::string& what) {
    if (permille == shown_) return;
    shown_ = permille;
    constexpr std::size_t width = 40;
    const std::size_t filled = permille * width / 1000;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double remaining = permille == 0 ? 0.0
                                           : elapsed * static_cast<double>(1000 - permille) /
                                                 static_cast<double>(permille);
    std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, '.') << "] "
              << std::fixed << std::setprecision(1) << std::setw(5)
              << static_cast<double>(permille) / 10.0 << "%  " << what << "  " << elapsed << " s, "
              << remaining << " s to go   " << std::defaultfloat << std::flush;
    drawn_ = true;
  }

  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::size_t shown_ = static_cast<std::size_t>(-1);
  bool drawn_ = false;
};

// A run the engine stopped: says when and why, and where its outputs are.
int report_stop(const RunArgs& options, double time, const std::string& error) {
  std::cerr << "rockcontact: " << options.scene << ": stopped at t = " << time << " s: " << error
            << "\nrockcontact: the outputs up to the stop are in " << options.out << '\n';
  return exit_bad_input;
}

// What a user must know of the pre-solve that started the run: the blocks it started from their
// given state, and a state reached above the tolerance.
void warn_equilibrium(const RunArgs& options, const dyn::Equilibrium& e) {
  if (!e.unsettled.empty()) {
    std::cerr << "rockcontact: " << options.scene << ": warning: the initial equilibrium left "
              << e.unsettled.size() << " block(s) without a static state where they rest, started from "
              << "their given state:";
    for (std::size_t k = 0; k < e.unsettled.size() && k < 10; ++k) std::cerr << " '" << e.unsettled[k] << "'";
    if (e.unsettled.size() > 10) std::cerr << " ... (all in summary.json)";
    std::cerr << '\n';
  }
  if (e.ran && !e.converged) {
    std::cerr << "rockcontact: " << options.scene << ": warning: the initial equilibrium stopped at "
              << "an out-of-balance force ratio of " << e.ratio << " after " << e.iterations
              << " iterations, above its tolerance; the run starts from there\n";
  }
}

// The flags only the 2D DDA has: false, after saying that `flag` `applies` (the rest of the
// message), when one of them is given.
bool without_2d_flags(const RunArgs& options, std::string_view applies) {
  for (const auto& [given, flag] : {std::pair{options.checkpoint_every > 0, "--checkpoint-every"},
                                    std::pair{!options.restart.empty(), "--restart"}}) {
    if (given) {
      std::cerr << "rockcontact: " << options.scene << ": " << flag << ' ' << applies << '\n';
      return false;
    }
  }
  return true;
}

// Says that a 3D region's cut merged fragments into their neighbours (region.min_block_volume),
// which changes the blocks a user counts on; nothing when it merged none.
void note_merged(std::ostream& out, std::size_t merged, double min_block_volume) {
  if (merged == 0) return;
  std::ostringstream bound;
  bound << std::setprecision(3) << min_block_volume;
  out << "region: " << merged << (merged == 1 ? " fragment" : " fragments") << " below " << bound.str()
      << " m³ merged into neighbours\n";
}

// A 3D scene ("dimension": 3) on the implicit 3D DDA (dynamics/io/scene3d_output.hpp).
int run_run3d(const RunArgs& options, const nlohmann::json& document) {
  if (!without_2d_flags(options, "applies to 2D scenes only; the 3D engine has no checkpoints")) {
    return exit_bad_input;
  }
  dyn::Scene3d scene = dyn::parse_scene3d(document, options.scene);
  note_merged(std::cout, scene.merged_fragments, scene.min_block_volume);
  scene.params.threads = options.threads;
  ProgressBar bar;
  scene.params.equilibrium_progress = [&bar](std::size_t iterations, double ratio) {
    bar.update_presolve(iterations, ratio, 1e-12);
  };
  dyn::Run3dOptions run_options;
  run_options.out_dir = options.out;
  run_options.progress = [&bar, &scene](std::size_t steps, double time) {
    bar.update_time(steps, time, scene.duration);
  };
  dyn::Run3dReport report;
  try {
    report = dyn::run_scene3d(scene, run_options);
  } catch (const std::invalid_argument& e) {  // a parameter or block the engine refuses
    std::cerr << "rockcontact: " << options.scene << ": " << e.what() << '\n';
    return exit_bad_input;
  } catch (const dyn::Stability3dError& e) {  // an initial equilibrium the blocks do not have
    std::cerr << "rockcontact: " << options.scene << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  bar.finish();
  warn_equilibrium(options, report.equilibrium);
  if (report.status != "completed") return report_stop(options, report.time, report.error);
  const double mean = report.steps == 0 ? 0.0
                                        : static_cast<double>(report.open_close_total) /
                                              static_cast<double>(report.steps);
  std::cout << "scene: " << scene.source << " (3D, " << scene.blocks.size() << " blocks)\n"
            << "steps: " << report.steps << " (t = " << report.time << " s, " << report.step_cuts
            << " step cuts), wall " << report.simulation_seconds + report.output_seconds
            << " s (simulation " << report.simulation_seconds << " s)\n"
            << "open-close iterations per step: mean " << mean << ", max "
            << report.open_close_max << '\n'
            << "energy: total " << report.initial.total() << " J at the start, "
            << report.final.total() << " J at the end\n"
            << "predicates: " << report.predicates.total_calls() << " calls, "
            << report.predicates.total_fallbacks() << " exact fallbacks; largest penetration "
            << report.max_penetration << " m\n"
            << "outputs: " << options.out << " (tracks.csv, contacts.csv, " << report.frames
            << " frames in frames.pvd, final.svg, summary.json)\n";
  return exit_ok;
}

// A CDEM scene ("solver": "cdem") on the CDEM engine (dynamics/io/scene_cdem_output.hpp).
int run_run_cdem(const RunArgs& options, const nlohmann::json& document) {
  if (!without_2d_flags(options, "applies to 2D DDA scenes only; the CDEM engine has no checkpoints")) {
    return exit_bad_input;
  }
  dyn::SceneCdem scene = dyn::parse_scene_cdem(document, options.scene);
  scene.params.threads = options.threads;
  ProgressBar bar;
  dyn::RunCdemOptions run_options;
  run_options.out_dir = options.out;
  run_options.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
  dyn::RunCdemReport report;
  try {
    report = dyn::run_scene_cdem(scene, run_options);
  } catch (const std::invalid_argument& e) {  // a polygon, mesh size, dt or law the engine refuses
    std::cerr << "rockcontact: " << options.scene << ": " << e.what() << '\n';
    return exit_bad_input;
  } catch (const dyn::CdemStabilityError& e) {  // a start the engine cannot take a step from
    std::cerr << "rockcontact: " << options.scene << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  bar.finish();
  if (report.status != "completed") return report_stop(options, report.time, report.error);
  const dyn::CdemCounters& c = report.counters;
  std::cout << "scene: " << scene.source << " (CDEM, " << scene.blocks.size() << " blocks, "
            << report.elements << " elements, " << report.nodes << " nodes)\n"
            << "steps: " << report.steps << " (t = " << report.time << " s, critical dt "
            << report.critical_dt << " s), wall "
            << report.simulation_seconds + report.output_seconds << " s (simulation "
            << report.simulation_seconds << " s)\n"
            << "energy: total " << report.initial.total() << " J at the start, "
            << report.final.total() << " J at the end\n"
            << "contact: " << c.touches << " touches, " << c.clone_nodes_formed
            << " clone nodes formed, " << c.clone_nodes_separated << " separated, "
            << c.subdivided_elements << " subdivided elements; " << report.events << " events\n"
            << "outputs: " << options.out << " (tracks.csv, events.csv, " << report.frames
            << " frames in frames.pvd, final.svg, summary.json)\n";
  return exit_ok;
}

int run_run(const RunArgs& options) {
  // --dt and --duration replace the document's values before it is parsed, so the scene's checks
  // and its digest (checkpoints) see them.
  nlohmann::json document = dyn::read_json_file(options.scene);
  if (document.is_object() && document.contains("time") && document["time"].is_object()) {
    if (options.dt) document["time"]["dt"] = *options.dt;
    if (options.duration) document["time"]["duration"] = *options.duration;
  }
  if (dyn::is_scene_cdem_document(document)) return run_run_cdem(options, document);
  if (dyn::is_scene3d_document(document)) return run_run3d(options, document);
  dyn::Scene scene = dyn::parse_scene(document, options.scene);
  for (const std::string& warning : dyn::stiffness_warnings(scene)) {
    std::cerr << "rockcontact: " << options.scene << ": warning: " << warning << '\n';
  }
  scene.params.threads = options.threads;
  ProgressBar bar;
  const double tolerance = scene.params.equilibrium_tolerance;
  scene.params.equilibrium_progress = [&bar, tolerance](std::size_t iterations, double ratio) {
    bar.update_presolve(iterations, ratio, tolerance);
  };
  dyn::RunOptions run_options;
  run_options.out_dir = options.out;
  run_options.checkpoint_every = options.checkpoint_every;
  run_options.restart = options.restart;
  run_options.progress = [&bar](std::size_t done, std::size_t total) { bar.update(done, total); };
  dyn::RunReport report;
  try {
    report = dyn::run_scene(scene, run_options);
  } catch (const std::invalid_argument& e) {  // a parameter or polygon the engine refuses
    std::cerr << "rockcontact: " << options.scene << ": " << e.what() << '\n';
    return exit_bad_input;
  } catch (const dyn::StabilityError& e) {  // a time step above the engine's limit
    std::cerr << "rockcontact: " << options.scene << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  bar.finish();
  warn_equilibrium(options, report.equilibrium);
  if (report.status != "completed") return report_stop(options, report.time, report.error);
  std::cout << "scene: " << scene.source << '\n';
  if (!report.restarted_from.empty()) {
    std::cout << "restarted: from " << report.restarted_from.string() << " at step "
              << report.restart_steps << '\n';
  }
  std::cout
            << "steps: " << report.steps << " (t = " << report.time << " s), wall "
            << report.simulation_seconds + report.output_seconds << " s (simulation "
            << report.simulation_seconds << " s)\n";
  if (scene.params.analysis == dyn::Analysis::static_equilibrium) {
    std::cout << "static: " << (report.converged ? "converged" : "not converged") << ", out-of-balance ratio "
              << (report.balance.empty() ? 0.0 : report.balance.back().second) << " (tolerance "
              << scene.static_tolerance << ")\n";
  } else {
    std::cout << "energy: total " << report.initial.total() << " J/m at the start, "
              << report.final.total() << " J/m at the end\n";
  }
  std::cout
            << "predicates: " << report.predicates.total_calls() << " calls, "
            << report.predicates.total_fallbacks() << " exact fallbacks; largest penetration "
            << report.max_penetration << " m\n"
            << "outputs: " << options.out << " (tracks.csv, " << report.frames
            << " frames in frames.pvd, energies.csv, final.svg, summary.json"
            << (options.checkpoint_every > 0 ? ", checkpoint.json" : "") << ")\n";
  return exit_ok;
}

void add_run(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<RunArgs>();
  CLI::App* sub = app.add_subcommand(
      "run",
      "Run a scene and write its tracks, contacts, frames and summary: 2D (explicit DDA with "
      "potential contact; SI units, forces per metre of thickness, contact kn in Pa, kt in N/m); "
      "with \"dimension\": 3, 3D (implicit DDA with penalty contact, kn and kt in N/m per "
      "constraint); or, with \"solver\": \"cdem\", 2D CDEM (deformable blocks meshed into "
      "triangles, two-scale clone-node or penalty contact; tracks, events, meshes). Every field: "
      "docs/user-guide.md");
  sub->add_option("scene", options->scene, "Scene JSON (fields: docs/user-guide.md)")
      ->required();
  sub->add_option("-o,--out", options->out, "Output directory (created if missing)")->required();
  sub->add_option("--checkpoint-every", options->checkpoint_every,
                  "Replace OUT/checkpoint.json with the full state every N steps (0: never)");
  sub->add_option("--restart", options->restart,
                  "Resume from a checkpoint.json of this scene (bit-identical continuation)");
  const auto positive_seconds = [](const std::string& text) -> std::string {
    double value = 0.0;
    try {
      std::size_t used = 0;
      value = std::stod(text, &used);
      if (used != text.size()) return "expected a time in s, a finite number > 0, got " + text;
    } catch (const std::exception&) {
      return "expected a time in s, a finite number > 0, got " + text;
    }
    return std::isfinite(value) && value > 0.0
               ? std::string()
               : "expected a time in s, a finite number > 0, got " + text;
  };
  sub->add_option("--dt", options->dt, "Time step in s, overrides the scene's time.dt")
      ->check(CLI::Validator(positive_seconds, "SECONDS"));
  sub->add_option("--duration", options->duration,
                  "Simulated time in s, overrides the scene's time.duration")
      ->check(CLI::Validator(positive_seconds, "SECONDS"));
  sub->add_option("--threads", options->threads,
                  "Threads of the engine's parallel passes, in every engine (0: one per core the "
                  "process may use); the results do not depend on it")
      ->check(CLI::Range(std::size_t{0}, std::size_t{1024}))
      ->capture_default_str();
  sub->callback([options, &exit_status] { exit_status = run_run(*options); });
}

struct CutArgs {
  std::string scene;
  std::string output;
};

// 3D: the region of a {"dimension": 3, "region", "joint_sets"} document (dynamics/io/cut3d.hpp).
int run_cut3(const CutArgs& options, const nlohmann::json& document) {
  const dyn::Cut3Input input = dyn::parse_cut3(document, options.scene);
  const dyn::Cut3Result cut = dyn::cut3d(input);
  write_json(options.output, dyn::cut3d_blocks(input, cut));
  std::ostream& summary = options.output == "-" ? std::cerr : std::cout;
  summary << cut.blocks.size() << " blocks cut from the 3D region of " << options.scene;
  if (options.output != "-") summary << ", written to " << options.output;
  summary << '\n';
  note_merged(summary, cut.merged, cut.min_block_volume);
  return exit_ok;
}

int run_cut(const CutArgs& options) {
  const nlohmann::json document = dyn::read_json_file(options.scene);
  if (dyn::is_cut3_document(document)) return run_cut3(options, document);
  const dyn::Scene scene = dyn::parse_scene(document, options.scene);
  if (scene.generated_count == 0) {  // a region always yields at least one block
    std::cerr << "rockcontact: " << options.scene << ": region: the scene has no region to cut\n";
    return exit_bad_input;
  }
  write_json(options.output, dyn::generated_blocks_json(scene));
  std::ostream& summary = options.output == "-" ? std::cerr : std::cout;
  summary << scene.generated_count << " blocks cut from the region of " << options.scene;
  if (options.output != "-") summary << ", written to " << options.output;
  summary << '\n';
  return exit_ok;
}

void add_cut(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<CutArgs>();
  CLI::App* sub = app.add_subcommand(
      "cut", "Cut a scene's region by its joint sets and write the blocks as JSON (2D, or 3D with "
             "\"dimension\": 3)");
  sub->add_option("scene", options->scene, "Scene JSON with \"region\" and \"joint_sets\"")
      ->required();
  sub->add_option("-o,--output", options->output, "Blocks JSON ('-' for stdout)")->required();
  sub->callback([options, &exit_status] { exit_status = run_cut(*options); });
}

struct SafetyFactorArgs {
  std::string scene;
  std::string block;
  std::string output = "-";
  dyn::SafetyFactorParams params;
};

std::string_view status_name(dyn::SafetyStatus status) {
  switch (status) {
    case dyn::SafetyStatus::converged: return "converged";
    case dyn::SafetyStatus::stable_at_max: return "stable_at_max";
    case dyn::SafetyStatus::slides_at_min: return "slides_at_min";
  }
  return "converged";
}

// The factor of safety of one block of a 3D scene by strength reduction
// (dynamics/apps/safety_factor.hpp), written as {"factor_of_safety",
// "critical_friction_angle_deg", "iterations", "status", "trials": [{"factor", "slid",
// "displacement"}]} in that order, then the block, the slip threshold (m) and the trials' time
// (s), and each trial's wall seconds after its three fields.
int run_safety_factor(const SafetyFactorArgs& options) {
  const nlohmann::json document = dyn::read_json_file(options.scene);
  if (!document.is_object() || !document.contains("dimension") || document.at("dimension") != 3) {
    std::cerr << "rockcontact: " << options.scene
              << ": dimension: safety-factor needs a 3D scene (\"dimension\": 3)\n";
    return exit_bad_input;
  }
  const dyn::Scene3d scene = dyn::parse_scene3d(document, options.scene);
  dyn::SafetyFactorResult result;
  try {
    result = dyn::safety_factor(scene.blocks, scene.law, scene.params, options.block, options.params);
  } catch (const std::invalid_argument& e) {
    std::cerr << "rockcontact: " << options.scene << ": " << e.what() << '\n';
    return exit_bad_input;
  } catch (const dyn::Stability3dError& e) {
    std::cerr << "rockcontact: " << options.scene << ": a trial stopped: " << e.what() << '\n';
    return exit_bad_input;
  }
  nlohmann::ordered_json trials = nlohmann::ordered_json::array();
  for (const dyn::SafetyTrial& t : result.trials) {
    trials.push_back({{"factor", t.factor}, {"slid", t.slid}, {"displacement", t.displacement},
                      {"wall_seconds", t.run_seconds}});
  }
  write_json(options.output, {{"factor_of_safety", result.factor_of_safety},
                              {"critical_friction_angle_deg", result.critical_friction_angle_deg},
                              {"iterations", result.iterations},
                              {"status", status_name(result.status)},
                              {"trials", trials},
                              {"block", options.block},
                              {"slip", result.slip},
                              {"time", options.params.time},
                              {"settling", result.settling},
                              {"warnings", result.warnings}});
  for (const std::string& warning : result.warnings) std::cerr << "rockcontact: warning: " << warning << '\n';
  std::ostream& summary = options.output == "-" ? std::cerr : std::cout;
  summary << "block " << options.block << ": factor of safety " << result.factor_of_safety << " ("
          << status_name(result.status) << ", " << result.iterations << " trials of " << options.params.time
          << " s, slip threshold " << result.slip << " m)\n";
  // A bracket end is a bound, not a factor of safety: say so, and what to change.
  switch (result.status) {
    case dyn::SafetyStatus::converged: return exit_ok;
    case dyn::SafetyStatus::slides_at_min:
      std::cerr << "rockcontact: " << options.scene << ": block '" << options.block << "' slides even at factor "
                << result.factor_of_safety << " (its friction and cohesion times " << 1.0 / result.factor_of_safety
                << "): the factor of safety is below that, or the block is not held at all. Check that it rests "
                   "on its supports in the scene, and that the contacts' settling under kn does not pass the slip "
                   "threshold (--slip, times the block's size: "
                << result.slip << " m here); a stiffer kn settles less\n";
      return exit_check_failed;
    case dyn::SafetyStatus::stable_at_max:
      std::cerr << "rockcontact: " << options.scene << ": block '" << options.block << "' stands even at factor "
                << result.factor_of_safety << ": the factor of safety is at least that (a block with cohesion, or "
                   "resting on a gentle slope)\n";
      return exit_check_failed;
  }
  return exit_ok;
}

void add_safety_factor(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<SafetyFactorArgs>();
  CLI::App* sub = app.add_subcommand(
      "safety-factor",
      "Factor of safety of a block of a 3D scene by strength reduction (tan phi / F, c / F on every "
      "interface it touches, bisection on F over [0.1, 10] to 1e-3 relative)");
  sub->add_option("scene", options->scene, "3D scene JSON")->required();
  sub->add_option("--block", options->block, "The id of the block (movable)")->required();
  sub->add_option("-o,--output", options->output, "Result JSON ('-' for stdout)")->capture_default_str();
  sub->add_option("--slip", options->params.slip_ratio,
                  "A trial slides when the block's centroid moves farther than this fraction of its "
                  "size (the cube root of its volume)")
      ->check(CLI::Range(0.0, 1.0).description("in (0, 1)"))
      ->capture_default_str();
  sub->add_option("--damping", options->params.damping_ratio,
                  "Damping ratio of the trials' contact dashpots (the scene's, if larger), against the "
                  "rocking of the block on its penalty springs")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sub->add_option("--time", options->params.time, "Simulated seconds of each trial")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->callback([options, &exit_status] { exit_status = run_safety_factor(*options); });
}

// The paper scenes: beside an installed executable (PREFIX/bin/rockcontact reads
// PREFIX/share/rockcontact/scenes), else in the source tree this executable was built from.
std::string default_scenes_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed = exe.parent_path() / ROCKCONTACT_SCENES_FROM_BINDIR;
    if (std::filesystem::is_directory(installed, ec)) return installed.lexically_normal().string();
  }
  return ROCKCONTACT_SCENES_DIR;
}

// Options of the commands that go over the directory of paper scenes (validate, report).
struct SceneSetArgs {
  bool quick = false;
  bool wedge_family = false;  // validate only
  std::string out;
  std::string scenes = default_scenes_dir();
};

void add_scene_set_options(CLI::App* sub, SceneSetArgs& options) {
  sub->add_flag("--quick", options.quick, "Shortened durations (what the test suite runs)");
  sub->add_option("--scenes", options.scenes, "Directory of the scene files")
      ->capture_default_str();
}

int run_validate(const SceneSetArgs& options) {
  dyn::ValidationOptions validation;
  validation.scenes_dir = options.scenes;
  validation.quick = options.quick;
  validation.wedge_family = options.wedge_family;
  validation.out_dir = options.out;
  if (stderr_is_terminal()) {
    validation.on_scene = [](const std::string& scene) {
      std::cerr << "running " << scene << '\n';
    };
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<dyn::ValidationRow> rows = dyn::run_validation(validation);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << (options.quick ? "quick" : "full") << " validation, scenes from " << options.scenes
            << '\n';
  dyn::write_validation_table(std::cout, rows);
  std::cout << "total wall time " << std::setprecision(3) << seconds << " s\n";
  for (const dyn::ValidationRow& row : rows) {
    if (!row.pass) return exit_check_failed;
  }
  return exit_ok;
}

void add_validate(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<SceneSetArgs>();
  CLI::App* sub = app.add_subcommand(
      "validate", "Run the paper's scenes and compare each with its reference (exit 3 on a FAIL)");
  add_scene_set_options(sub, *options);
  sub->add_option("-o,--out", options->out, "Write each run's outputs into DIR/<scene>/");
  sub->add_flag("--wedge-family", options->wedge_family,
                "Also the generated wedges against Hoek & Bray at kn auto and 10x it (about 15 minutes on 2 "
                "cores; not with --quick)");
  sub->callback([options, &exit_status] { exit_status = run_validate(*options); });
}

struct FuzzCasesArgs {
  std::string family;
  rockcontact::cli::FuzzCases cases;
  std::string output;
};

int run_fuzz_cases(FuzzCasesArgs options) {
  // CLI11 has checked --family with parse_families.
  options.cases.families = rockcontact::cli::parse_families(options.family).value();
  std::uint64_t written = 0;
  if (options.output == "-") {
    written = rockcontact::cli::write_fuzz_cases(std::cout, options.cases);
  } else {
    dyn::AtomicFile file(options.output);
    written = rockcontact::cli::write_fuzz_cases(file.stream(), options.cases);
    file.commit();
  }
  std::ostream& summary = options.output == "-" ? std::cerr : std::cout;
  summary << written << " cases (" << options.family << ", seed " << options.cases.seed << ')';
  if (options.output != "-") summary << " written to " << options.output;
  summary << '\n';
  return exit_ok;
}

void add_fuzz_cases(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<FuzzCasesArgs>();
  CLI::App* sub = app.add_subcommand("fuzz-cases",
                                     "Write pairs from the robustness generators as a `pairs` "
                                     "input file (ids FAMILY-sSEED-iINDEX)");
  sub->add_option("--family", options->family,
                  "Generator families, comma-separated, or all (COUNT of each)")
      ->required()
      ->check(CLI::Validator(
          [](const std::string& names) -> std::string {
            if (rockcontact::cli::parse_families(names)) return "";
            return "unknown family in \"" + names + "\"; expected " +
                   rockcontact::cli::family_choices() + ", or names separated by commas";
          },
          "FAMILY[,FAMILY...]"));
  sub->add_option("--count", options->cases.count, "Pairs per family")->required();
  sub->add_option("--seed", options->cases.seed, "Seed of the generators' streams")
      ->capture_default_str();
  sub->add_option("--kn", options->cases.kn, "Normal penalty kn, Pa")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("--H", options->cases.H, "Potential length scale H, m")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  sub->add_option("-o,--output", options->output, "Cases JSON ('-' for stdout)")->required();
  sub->callback([options, &exit_status] { exit_status = run_fuzz_cases(*options); });
}

int run_report(const SceneSetArgs& options) {
  dyn::ReportOptions report;
  report.scenes_dir = options.scenes;
  report.out_dir = options.out;
  report.quick = options.quick;
  if (stderr_is_terminal()) {
    report.on_scene = [](const std::string& scene) { std::cerr << "sweeping " << scene << '\n'; };
  }
  // Said before a long wait: the full sweep took 916 s (945 runs) on the 2-core machine, the
  // quick one 31 s.
  report.on_start = [quick = options.quick](std::size_t runs, std::size_t scenes) {
    std::cerr << "report: " << runs << " runs over " << scenes << " scenes, one after another; "
              << (quick ? "about half a minute" : "about 15 minutes, 10 of them the §6 collapses")
              << '\n';
  };
  const dyn::ReportSummary summary = dyn::run_report(report);
  for (const std::string& line : summary.headlines) std::cout << line << '\n';
  std::cout << summary.runs.size() << " runs in " << std::setprecision(3) << summary.seconds
            << " s; " << options.out << "/index.md, runs.csv"
            << (summary.plots ? " and the plots (PNG, SVG)" : "; plots missing (no gnuplot)")
            << '\n';
  return exit_ok;
}

void add_report(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<SceneSetArgs>();
  CLI::App* sub = app.add_subcommand(
      "report", "Sweep dt, kn, policy and demarcation over the validated scenes: error vs run time");
  add_scene_set_options(sub, *options);
  sub->add_option("-o,--out", options->out, "Output directory: index.md, runs.csv, plots")
      ->required();
  sub->callback([options, &exit_status] { exit_status = run_report(*options); });
}

// libgomp's idle threads spin for about 300 000 iterations, waiting for the next parallel region,
// before they sleep: on a core that another job holds, the spinning thread takes the time slices
// the working one needs (a 3D run took 1.3 s instead of 0.54 s beside one busy process, 30 s
// instead of 0.9 s on a machine loaded by other jobs as well: docs/performance.md). libgomp reads OMP_WAIT_POLICY and GOMP_SPINCOUNT once, when it is loaded,
// before main(); so unless the user set either, the program sets OMP_WAIT_POLICY=passive (idle
// threads sleep at once) and runs itself again with the same arguments. The variable is the guard:
// the new process finds it set and goes on. If the exec fails, this one goes on as it is.
void choose_wait_policy(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("OMP_WAIT_POLICY");  // not in force here, so not handed to child processes either
}

}  // namespace

int main(int argc, char** argv) {
  choose_wait_policy(argv);
  CLI::App app{"rockcontact: robust contact of polygonal rock blocks"};
  app.set_version_flag("--version", std::string("rockcontact ") + ROCKCONTACT_VERSION);
  app.require_subcommand(1);
  int exit_status = exit_ok;
  add_pairs(app, exit_status);
  add_run(app, exit_status);
  add_cut(app, exit_status);
  add_safety_factor(app, exit_status);
  add_validate(app, exit_status);
  add_report(app, exit_status);
  add_fuzz_cases(app, exit_status);
  try {
    app.parse(argc, argv);
    return exit_status;
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? exit_ok : exit_bad_input;
  } catch (const dyn::InputError& e) {
    std::cerr << "rockcontact: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const dyn::OutputError& e) {
    std::cerr << "rockcontact: " << e.what() << '\n';
    return exit_bad_input;
  } catch (const std::exception& e) {
    std::cerr << "rockcontact: internal error: " << e.what() << '\n';
    return exit_internal_error;
  }
}
