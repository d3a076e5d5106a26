#pragma once
// Running a 3D scene (scene3d.hpp) on the implicit 3D DDA (dda3d.hpp) and writing what
// `rockcontact run SCENE --out DIR` promises in DIR for "dimension": 3:
//
//   tracks.csv     header exactly "t,block,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz": for each tracked
//                  block (in the order of output.track), at t = 0, every `every` accepted steps
//                  and at the final time: centroid (m), rotation since the start as a rotation
//                  vector (the angle in rad times the unit axis), centroid velocity (m/s) and
//                  angular velocity (rad/s). Doubles in shortest round-trip form.
//   contacts.csv   header exactly "t,block_a,block_b,x,y,z,nx,ny,nz,fn,ft,state": a row per
//                  constraint in the engine's contact list at the same instants (open ones
//                  included): the ids of block_a (the lower block index) and block_b, the
//                  contact point on block_b (m), the unit normal from a towards b, the normal
//                  force on b along it (N, compression > 0), the magnitude of the tangential
//                  force (N), and the mode "open", "stick" or "slide".
//   frame_NNNN.vtp VTK XML PolyData, one polygon per face of every block's convex parts
//                  (faces as given, counter-clockwise seen from outside), at the same
//                  instants; cell data per face: "block" (index in the scene), "part", "fixed"
//                  (0/1), "velocity" (vx, vy, vz) m/s, "angular_velocity" (wx, wy, wz) rad/s,
//                  "stress" Pa (six components in ParaView's order xx, yy, zz, xy, yz, xz).
//                  NNNN is zero-padded to at least 4 digits (the width of the frame count the
//                  scene's dt and every predict; step cuts may add frames).
//   frames.pvd     the ParaView collection of the frames with their times (open this one).
//   final.svg      the final state in an orthographic view from the South-East, above
//                  (looking along (-0.4, 1, -0.5)): the faces turned towards the viewer, far
//                  ones first, shaded by their slope; fixed blocks grey, tracked ones orange,
//                  the others blue; each face titled with its block id.
//   summary.json   see run3d_summary.
//
// Times: the engine cuts a step (h / 2) when it must and grows it back to dt, so the instants
// are those of the accepted steps; the run ends at the first step whose end reaches the
// duration (it may pass it by less than dt). If the engine stops the run (Stability3dError),
// the outputs are completed with the last state and summary.json says "status": "stopped" and
// why. Every file is written through an AtomicFile (no truncated file under these names).

#include <cstddef>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "rockcontact/dynamics/dda3d.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::dynamics {

struct Run3dReport {
  std::string status = "completed";  // or "stopped" (the engine's Stability3dError)
  std::string error;                 // the engine's message when stopped
  std::size_t steps = 0;             // accepted steps taken
  double time = 0.0;                 // s, simulated time reached
  Energies3d initial;                // J, at t = 0
  Energies3d final;                  // J, at `time`
  double max_penetration = 0.0;      // m, the most negative gap seen after any step, as a depth
  std::size_t open_close_total = 0;  // open-close iterations over all accepted steps
  std::size_t open_close_max = 0;    // the most of one accepted step
  std::size_t step_cuts = 0;         // steps halved and redone
  double simulation_seconds = 0.0;   // wall, engine construction and steps
  double output_seconds = 0.0;       // wall, writing files
  kernel::PredicateCounters predicates;  // spent by this simulation
  std::size_t frames = 0;                // VTK frames written
  Equilibrium equilibrium;               // what the pre-solve did
};

// The summary.json document of a 3D run (keys in this order): scene, description, dimension
// (3), status, [error], steps, time, dt, max_displacement_ratio, max_rotation_deg, wall_seconds,
// simulation_seconds, output_seconds, energy {start, end} each {kinetic, gravitational, strain,
// contact, friction_dissipated, numerical_dissipated, total} (Energies3d, J),
// open_close_iterations {mean, max} per accepted step, step_cuts, predicates {calls,
// interval_fallbacks, fallbacks, by_kind {cross, crossing_side, crossing_point, triple,
// plane_side} each {calls, interval_fallbacks, fallbacks}}, max_penetration (m),
// initial_equilibrium (null, or {blocks, iterations, ratio, converged, seconds, unsettled}: the
// open-close iterations of the pre-solve and its last solve's relative residual), blocks [ids],
// tracked [ids], frames.
nlohmann::ordered_json run3d_summary(const Scene3d& scene, const Run3dReport& report);

struct Run3dOptions {
  std::filesystem::path out_dir;  // empty: no files
  // Called after every accepted step with the steps done and the simulated time (s).
  std::function<void(std::size_t, double)> progress;
};

// Builds the engine from the scene, steps until the duration is reached and records. A run the
// engine stops midway returns with status "stopped" and its message in `error`. Throws what the
// engine's constructor throws (std::invalid_argument for a parameter or block it refuses) and
// OutputError.
Run3dReport run_scene3d(const Scene3d& scene, const Run3dOptions& options = {});

}  // namespace rockcontact::dynamics
