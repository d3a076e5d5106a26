#pragma once
// `rockcontact report [--quick] -o DIR`: error against run time for every scene that has a
// reference (seed 000 §4; examples/scenes/*.json). Each scene is run over a sweep of
//   time step   dt x {32, 16, 8, 4, 2, 1, 1/2} of the scene's dt   (--quick: {32, 16, 4, 1})
//   stiffness   kn and kt x {0.1, 1, 10}                       (--quick: {1, 10})
//   policy      float | filtered | exact
//   demarcation paper | exact
// and every run records its error against the scene's reference and its wall time. Simulated
// durations: 0.5 s of each scene (--quick: 0.25 s of the squares, 0.03 s of the inclines). The
// scenes and their references (a table in report.cpp; a scene joins by adding an entry):
//   4.1 two squares          velocity exchange vA' = 0, vB' = vA (equal masses, elastic)
//   4.3 incline phi=0/10/20° sliding distance vs eq. 30, l = ½ g (sin θ - cos θ tan φ) t²
// Every reference is analytic; none is a converged run.
//
// A run ends in one of four states:
//   completed  the error is measured;
//   refused    dt is above the engine's critical estimate 2 / omega_max (the stability limit);
//   stopped    the engine's stability monitor stopped it midway;
//   skipped    an exact-policy run longer than the scene's step limit for that policy (GMP
//              arithmetic costs ~1.5 ms per step for one block on an incline, a thousand times
//              the filtered policy; the limit keeps the full report within minutes).
//
// DIR receives:
//   runs.csv         one row per run, header exactly
//                    "scene,policy,demarcation,dt_factor,dt,kn_factor,kn,kt,status,error,
//                    wall_seconds,predicate_calls,fallbacks,critical_dt,pareto" (one line);
//                    error and critical_dt empty unless completed, doubles round-trip;
//   index.md         per scene: the reference, the headline (the cheapest run within 1 %),
//                    the work-precision plot, the stability limit per kn, the exact-fallback
//                    rate per policy and demarcation, the Pareto-best runs; the total run time;
//   <slug>.gp        the gnuplot script of a scene's plot, and its output
//   <slug>.png/.svg  log error against log wall time, one curve per policy/demarcation at the
//                    scene's kn (points labelled by their dt), plus filtered/exact at the other
//                    kn. Without gnuplot the plots are missing and index.md says so.
//
// Runs use one thread, so that wall times compare across scenes and runs.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "rockcontact/kernel/demarcation.hpp"
#include "rockcontact/kernel/number_policy.hpp"

namespace rockcontact::dynamics {

struct ReportOptions {
  std::filesystem::path scenes_dir;  // where the paper scenes' JSON files are
  std::filesystem::path out_dir;     // created if missing
  bool quick = false;                // the shorter sweep and durations (the test suite's)
  std::string gnuplot = "gnuplot";   // the plotting program, looked up in PATH; empty: no plots
  // Called with each scene's name before its runs start (progress on a terminal).
  std::function<void(const std::string&)> on_scene;
  // Called once before the first run with the number of runs and of scenes.
  std::function<void(std::size_t, std::size_t)> on_start;
};

struct ReportRun {
  std::string scene;  // the scene's name, "4.3 incline phi=10°"
  kernel::PolicyKind policy = kernel::PolicyKind::filtered;
  kernel::Demarcation demarcation = kernel::Demarcation::exact;
  double dt_factor = 1.0;  // of the scene's dt
  double dt = 0.0;         // s
  double kn_factor = 1.0;  // of the scene's kn and kt
  double kn = 0.0;         // Pa
  double kt = 0.0;         // N/m; 0 when frictionless
  std::string status;      // completed | refused | stopped | skipped
  double error = std::numeric_limits<double>::quiet_NaN();  // relative; NaN unless completed
  double seconds = 0.0;                                     // wall, engine and observer
  std::uint64_t calls = 0;                                  // filtered predicate calls
  std::uint64_t fallbacks = 0;  // of which fell back to exact arithmetic
  double critical_dt = std::numeric_limits<double>::quiet_NaN();  // engine's estimate, s
  bool pareto = false;  // completed and not dominated in (error, seconds) within its scene
};

struct ReportSummary {
  std::vector<ReportRun> runs;
  double seconds = 0.0;  // wall time of the whole report
  bool plots = false;    // every PNG and SVG was written
  // One sentence per scene: the cheapest run within 1 % error, or the best error reached.
  std::vector<std::string> headlines;
};

// Runs the sweep of every scene and writes DIR. Throws InputError when a scene file is missing
// or malformed, OutputError when DIR cannot be written.
ReportSummary run_report(const ReportOptions& options);

// Sets `pareto` on every run: completed, and no completed run of the same scene has an error
// and a wall time both at most its own with one of them smaller.
void mark_pareto(std::span<ReportRun> runs);

}  // namespace rockcontact::dynamics
