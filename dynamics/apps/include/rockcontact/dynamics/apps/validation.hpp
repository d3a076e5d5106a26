#pragma once
// `rockcontact validate`: runs the paper's scenes (seed 000 §4-§5, examples/scenes/*.json) and
// compares each with its reference. Every check is one row: what is compared, the reference,
// the measured value, the error, the bound it must respect and the wall time of the run(s)
// behind it. The references and the derivation of each tolerance are in validation.cpp.
//
//   §4.1 two equal squares, vA = 1 m/s       momentum, velocity exchange, kinetic energy after
//   §4.2 block dropped on a symmetric system worst mirror asymmetry of the centroids
//   §4.3 block on a 30° incline, phi 0/10/20 sliding distance vs l = ½ g (sin θ − cos θ tan φ) t²
//   §5.1 bouncing block, 0.1 m and 1 m bases  unified H: same history; inscribed H: different
//   §5.2 5° triangles meeting head-on         point-symmetric response, bounded energy
//   §5.3 vertex on a 0.01 m edge / neighbour  bounded energy, the block rebounds
//   seed 001 §6.1 wedge (examples/scenes3d)   factor of safety vs limit equilibrium; the
//                                              frictionless slide vs ½ g sin ψ t²
//   seed 003 §6 prisms (examples/scenes_cdem)  first touch at 1/3 s, momentum, velocity exchange
//   two equal bars, two-scale and penalty      contact time vs 2 L / c, the striker at rest
//
// A run the engine stops (StabilityError) fails its rows with the engine's message.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::dynamics {

// How a measured error is judged against the tolerance.
enum class Bound {
  at_most,   // pass when error <= tolerance (agreement with a reference)
  at_least,  // pass when error >= tolerance (a difference the paper shows must be there)
};

struct ValidationRow {
  std::string scene;      // "4.3 incline phi=10°"
  std::string check;      // what is compared ("slide at t end")
  std::string reference;  // the reference value or property, with units
  std::string measured;   // the measured value, with units, or why the run stopped
  double error = 0.0;     // the compared quantity (units in `check`/`reference`)
  Bound bound = Bound::at_most;
  double tolerance = 0.0;
  double seconds = 0.0;  // wall time of the run(s) behind the row
  bool pass = false;
};

struct ValidationOptions {
  std::filesystem::path scenes_dir;  // where the paper scenes' JSON files are
  bool quick = false;                // shortened durations (the test suite's setting)
  // Also the generated wedge family's four rows (validation.cpp, wedge_family; not with quick).
  bool wedge_family = false;
  std::filesystem::path out_dir;     // empty: no files; else DIR/<scene file stem>/ per run
  // Called with each scene's name before its runs start (progress on a terminal).
  std::function<void(const std::string&)> on_scene;
};

// The §4.3 reference, also used by `rockcontact report`: seed 000 eq. 30, the distance a rigid
// block slides from rest in time t (s) down a slope θ with friction angle φ (rad) under gravity
// g (m/s²), l = ½ g (sin θ − cos θ tan φ) t² (m).
double incline_slide_eq30(double g, double theta, double phi, double t);

// The displacement from `start` to `end` (m) measured down a slope that rises to the right at
// angle θ (rad), i.e. along -(cos θ, sin θ).
double slide_down_slope(kernel::Point2 start, kernel::Point2 end, double theta);

// Runs every scene and returns its rows, scene by scene. Throws InputError when a scene file
// is missing or malformed, OutputError when out_dir cannot be written.
std::vector<ValidationRow> run_validation(const ValidationOptions& options);

// The table: one row per check, columns scene, check, reference, measured, error, tolerance,
// wall time, PASS/FAIL (aligned for a terminal); then a line "N checks, M failed".
void write_validation_table(std::ostream& out, std::span<const ValidationRow> rows);

}  // namespace rockcontact::dynamics
