#pragma once
// `rockcontact report [--quick] -o DIR`: error against run time for every scene `validate`
// runs (seed 000 §4-§6; examples/scenes/*.json). Each scene is run over a sweep of its own:
//   time step   dt x factors of the scene's dt, from well above its stability limit to below
//               the scene's own dt (§4.1, §4.3: {32, 16, 8, 4, 2, 1, 1/2}; --quick {32, 16, 4, 1})
//   stiffness   kn and kt x {0.1, 1, 10} (§4.1, §4.3), {1, 10} otherwise (--quick: {1, 10} and {1})
//   policy      float | filtered | exact (§6: float | filtered, see below)
//   demarcation paper | exact
// and every run records its error against the scene's reference and its wall time. The
// references (a table in report.cpp; a scene joins by adding an entry):
//   4.1 two squares          analytic: velocity exchange vA' = 0, vB' = vA (equal masses, elastic)
//   4.3 incline phi=0/10/20° analytic: sliding distance vs eq. 30, ½ g (sin θ - cos θ tan φ) t²
//   4.2, 5.1, 5.2, 5.3, 6.2  a converged run of the scene: dt a quarter of the sweep's finest,
//                            kn at its largest factor, exact demarcation, exact policy (§6.2:
//                            filtered, whose predicates decide as the exact ones; the exact
//                            constructions cost 30 ms-0.18 s a step on hundreds of blocks). The
//                            error is the largest departure of any moving block's centroid x, y
//                            or rotation x sqrt(A) from the reference's at 101 equally spaced
//                            instants (linearly interpolated between steps), relative to the
//                            largest motion of any of them in the reference.
//   6.1 collapse phi=15/30°  the same against a converged filtered run, on the rock mass's
//                            centre of mass: a collapse branches at every block collision, so
//                            single blocks' paths part between runs that differ only by rounding.
// Simulated windows: 0.5 s (§4.1, §4.3, §6), 1 s (§4.2), 0.8 s (§5.1), 0.2 s (§5.2), 0.4 s (§5.3);
// shorter under --quick. Each curve's observed order of convergence (convergence_order) is in
// its plot legend and in index.md.
//
// A run ends in one of five states:
//   completed  the error is measured;
//   reference  the converged run of a scene without a closed form (its first row);
//   refused    dt is above the engine's critical estimate 2 / omega_max (the stability limit);
//   stopped    the engine's stability monitor stopped it midway;
//   skipped    an exact-policy run longer than the scene's step limit for that policy (exact
//              constructions cost 0.6-1.4 ms per step for one block on an incline, hundreds of
//              times the filtered policy; the limit keeps the full report within minutes).
//
// DIR receives:
//   runs.csv         one row per run, header exactly
//                    "scene,policy,demarcation,dt_factor,dt,kn_factor,kn,kt,status,error,
//                    wall_seconds,predicate_calls,fallbacks,critical_dt,pareto" (one line);
//                    error empty unless completed, critical_dt empty when refused or
//                    skipped; doubles round-trip;
//   index.md         per scene: the reference, the headline (the cheapest run within 1 %),
//                    the work-precision plot, the observed order of each curve, the
//                    stability limit per kn, the exact-fallback
//                    rate per policy and demarcation, the Pareto-best runs; the total run time;
//   <slug>.gp        the gnuplot script of a scene's plot, and its output
//   <slug>.png/.svg  log error against log wall time, one curve per policy/demarcation at the
//                    scene's kn (points labelled by their dt), plus filtered/exact at the other
//                    kn. Without gnuplot the plots are missing and index.md says so.
//
// When a scene's reference run does not complete, its sweep is not run and index.md says so.
// Runs use one thread, so that wall times compare across scenes and runs.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

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

// The observed order of convergence p in error ≈ C dt^p of one curve (one scene, setting and
// kn): the least-squares slope of ln(error) against ln(dt) over its runs with a positive error.
// NaN when fewer than two distinct dt remain.
double convergence_order(std::span<const ReportRun> runs);

}  // namespace rockcontact::dynamics
