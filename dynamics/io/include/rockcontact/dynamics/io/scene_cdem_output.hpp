#pragma once
// Running a CDEM scene (scene_cdem.hpp) on the CDEM engine (cdem.hpp) and writing what
// `rockcontact run SCENE --out DIR` promises in DIR for "solver": "cdem":
//
//   tracks.csv     header exactly "t,block,x,y,rotation,vx,vy,omega": for each tracked block
//                  (in the order of output.track), at t = 0, every `every` steps and at the
//                  final time: the mass centre (m), the mean rotation since the start (rad,
//                  counter-clockwise), the mass-averaged velocity (m/s) and the mean angular
//                  velocity (rad/s) of CdemBlockState. Doubles in shortest round-trip form.
//   events.csv     header exactly "t,event,block_a,block_b": one row per engine event
//                  (Cdem::events(), in order): its time (s), "touch" or "separate", and the
//                  ids of block_a (the block whose node touches) and block_b. Written at the
//                  end of the run, complete.
//   frame_NNNN.vtu VTK XML UnstructuredGrid at the same instants as the track rows: every
//                  block's mesh (blocks in scene order, nodes at their current positions, z = 0),
//                  one triangle cell (VTK type 5) per element; point data "velocity" (vx, vy, 0)
//                  m/s; cell data "block" (index in the scene), "stress" (xx, yy, xy) Pa and
//                  "von_mises" Pa (with sigma_zz = nu (sigma_xx + sigma_yy) in plane strain, 0 in
//                  plane stress). NNNN is zero-padded to the width of the last frame number (at
//                  least 4 digits).
//   frames.pvd     the ParaView collection of the frames with their times (open this one).
//   final.svg      the final meshes, y up, fitted to their extent: every element a thin outline
//                  over its block's fill (fixed blocks grey, tracked ones orange, the others
//                  blue), each block's boundary drawn thicker and the block titled with its id;
//                  the time in the corner.
//   summary.json   see run_cdem_summary.
//
// Times: the run takes step_count(scene) steps of dt (scene_cdem.hpp: the duration / dt rounded
// up, but not for the decimals' rounding), so it ends at the first step at or past the
// duration. If the engine stops the run (CdemStabilityError), the outputs are completed with the
// last state and summary.json says "status": "stopped" and why. Every file is written through
// an AtomicFile (no truncated file under these names).

#include <array>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "rockcontact/dynamics/cdem.hpp"
#include "rockcontact/dynamics/io/scene_cdem.hpp"

namespace rockcontact::dynamics {

struct RunCdemReport {
  std::string status = "completed";  // or "stopped" (the engine's CdemStabilityError)
  std::string error;                 // the engine's message when stopped
  std::size_t steps = 0;             // steps taken
  double time = 0.0;                 // s, simulated time reached
  CdemEnergies initial;              // J, at t = 0
  CdemEnergies final;                // J, at `time`
  std::array<double, 2> momentum_initial{};  // kg m/s, of every movable node, at t = 0
  std::array<double, 2> momentum_final{};    // kg m/s, at `time`
  CdemCounters counters;                     // the engine's, at the end
  std::size_t events = 0;                    // rows of events.csv
  double critical_dt = 0.0;                  // s, the engine's stability limit
  double simulation_seconds = 0.0;           // wall, engine construction and steps
  double output_seconds = 0.0;               // wall, writing files
  std::size_t frames = 0;                    // VTK frames written
  std::size_t elements = 0;                  // triangles of the meshes as built
  std::size_t nodes = 0;                     // nodes of the meshes as built
};

// The summary.json document of a CDEM run (keys in this order): scene, description, dimension
// (2), solver ("cdem"), law ("two-scale" or "penalty"), status, [error], steps, time, dt,
// critical_dt (null when unlimited), wall_seconds, simulation_seconds, output_seconds, elements,
// nodes, energy {start, end} each {kinetic, strain, gravitational, contact, onset_loss,
// friction, damping, tie_work, total} (CdemEnergies, J), momentum {start: [px, py], end: [px,
// py]} (kg m/s), clone_nodes {formed, separated}, touches, subdivided_elements, events (the
// count), blocks [ids], tracked [ids], frames.
nlohmann::ordered_json run_cdem_summary(const SceneCdem& scene, const RunCdemReport& report);

struct RunCdemOptions {
  std::filesystem::path out_dir;  // empty: no files
  // Called after every step with (steps done, steps in the run).
  std::function<void(std::size_t, std::size_t)> progress;
};

// Builds the engine from the scene, takes step_count(scene) steps and records. A run the
// engine stops midway returns with status "stopped" and its message in `error`. Throws what the
// engine's constructor throws (std::invalid_argument for a polygon, mesh size, dt or contact
// parameter it refuses) and OutputError.
RunCdemReport run_scene_cdem(const SceneCdem& scene, const RunCdemOptions& options = {});

}  // namespace rockcontact::dynamics
