#pragma once
// Running a scene and writing what `rockcontact run SCENE --out DIR` promises in DIR:
//
//   tracks.csv     header exactly "t,block,x,y,rotation,vx,vy,omega": for each tracked block
//                  (scene order), every `every` steps, at t = 0 and at the final time: centroid
//                  (m), rotation since the start (rad, CCW), centroid velocity (m/s) and angular
//                  velocity (rad/s). Doubles in shortest round-trip form.
//   energies.csv   header exactly "t,kinetic,gravitational,strain,contact,friction_dissipated,
//                  damping_dissipated,total": the energy terms of dda2d.hpp's Energies (J per m
//                  of thickness, named as in summary.json) at the same instants as the track
//                  rows. total stays at its start value up to the integrator's O(dt²) error,
//                  so its drift is the balance's error. A static analysis writes them too,
//                  though its fictitious motion gives them no physical meaning.
//   contacts.csv   header exactly "t,block_a,block_b,x,y,nx,ny,fn,ft,state": a row per contact
//                  (per pair of convex parts in contact) at the same instants: the ids of CP (a,
//                  the lower index) and TP (b), the contact point (m), the unit normal n of the
//                  normal force on a, and the total contact force on a (N/m; on b the opposite)
//                  split into fn along n and ft along t = (-ny, nx) (dashpots included; the
//                  friction force is along t). state is "stick", "slide" (the friction force at
//                  the Coulomb limit; always on a frictionless interface) or "open": written once
//                  for a pair in contact at the previous instant and no longer, with its last
//                  point and normal and fn = ft = 0.
//   contacts_NNNN.vtp, contacts.pvd  the same as VTK points, with point data "normal" (nx, ny,
//                  0), "fn", "ft" and "state" (0 stick, 1 slide, 2 open).
//   frame_NNNN.vtp VTK XML PolyData, one polygon per block (scene order), written at the same
//                  instants as the track rows; cell data: "block" (index in the scene),
//                  "fixed" (0/1), "velocity" (vx, vy, 0) m/s, "omega" rad/s, "stress"
//                  (sigma_x, sigma_y, tau_xy) Pa. Points carry z = 0. NNNN is zero-padded to
//                  the width of the last frame number (at least 4 digits).
//   frames.pvd     the ParaView collection of the frames with their times (open this one).
//   final.svg      the final state, y up: blocks filled, fixed ones grey, tracked ones orange,
//                  each polygon titled with its block id; over it the movable blocks at the
//                  first frame as dashed outlines, and both times in the corner.
//   summary.json   status, steps, times, energy terms at the start and the end, wall seconds,
//                  predicate calls and exact fallbacks, largest penetration (see run_summary).
//
// If the engine stops the run (StabilityError after some steps), the outputs are still
// completed with the last state and summary.json says "status": "stopped" and why.
// Every file is written through an AtomicFile: a run that fails part-way (an exception, a full
// disk) leaves no truncated file under any of these names.

#include <cstddef>
#include <filesystem>
#include <array>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/atomic_file.hpp"
#include "rockcontact/dynamics/dda2d.hpp"
#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::dynamics {

// Writes the files listed above into one directory (created if missing).
class SceneRecorder {
 public:
  // Throws OutputError when the directory or tracks.csv cannot be created.
  SceneRecorder(const Scene& scene, std::filesystem::path dir);

  // Track rows, an energies row, contact rows and one frame of the state at `time` (s).
  void record(double time, std::span<const BlockState> blocks,
              std::span<const ContactState> contacts, const Energies& energies);

  // frames.pvd, final.svg of `blocks`, summary.json; throws OutputError if one cannot be written.
  void finish(std::span<const BlockState> blocks, const nlohmann::ordered_json& summary);

  std::size_t frames() const noexcept { return frames_.size(); }

 private:
  struct Frame {
    double time;
    std::string index;  // NNNN of frame_NNNN.vtp and contacts_NNNN.vtp
  };

  std::filesystem::path dir_;
  std::vector<std::string> track_;
  std::size_t frame_digits_;
  std::optional<AtomicFile> tracks_;    // set in the constructor, once the directory exists
  std::optional<AtomicFile> energies_;  // likewise
  std::optional<AtomicFile> contacts_;  // likewise
  std::vector<Frame> frames_;
  std::vector<std::vector<kernel::Point2>> start_;  // the blocks' vertices at the first frame
  // The contacts of the last recorded instant, by (cp, tp, cp_part, tp_part): ids, point and
  // normal, for the "open" row of a pair that has separated since.
  struct Open {
    std::string a, b;
    double x, y, nx, ny;
  };
  std::map<std::array<std::size_t, 4>, Open> last_contacts_;
};

struct RunReport {
  std::string status = "completed";       // or "stopped" (the engine's StabilityError)
  std::string error;                      // the engine's message when stopped
  std::size_t steps = 0;                  // steps taken
  double time = 0.0;                      // s, simulated time reached
  Energies initial;                       // J/m, at t = 0
  Energies final;                         // J/m, at `time`
  double max_penetration = 0.0;           // m, largest minimum-translation distance seen
  double critical_time_step = 0.0;        // s, the engine's estimate 2 / omega_max (may be +inf)
  std::string critical_time_step_source;  // what set it (the engine's words)
  double simulation_seconds = 0.0;        // wall, engine construction and steps (observer included)
  double output_seconds = 0.0;            // wall, writing files
  kernel::PredicateCounters predicates;   // spent by this simulation
  std::size_t frames = 0;                 // VTK frames written
  Equilibrium equilibrium;                // what the initial-equilibrium pre-solve did
  // Static analysis: the out-of-balance force ratio at every recorded step (step, ratio), and
  // whether it fell below the scene's static_tolerance.
  std::vector<std::pair<std::size_t, double>> balance;
  bool converged = false;
  // A run resumed from a checkpoint: the file and the step it resumed at.
  std::filesystem::path restarted_from;
  std::size_t restart_steps = 0;
};

// The summary.json document of a run (keys in this order): scene, description, status,
// [error], steps, time, dt, critical_time_step (null when unlimited),
// critical_time_step_source, H, H_rule, [restart {file, steps, time} for a resumed run], wall_seconds, simulation_seconds,
// output_seconds, energy {start, end} each {kinetic, gravitational, strain, contact,
// friction_dissipated, damping_dissipated, total}, predicates {calls, fallbacks},
// max_penetration, initial_equilibrium {blocks, iterations, ratio, converged, seconds, unsettled
// [ids]} (null when no block started
// in contact with a support or the scene turned it off), [static {tolerance, converged,
// iterations, ratio, history [[step, ratio], ...] at every recorded step} for a static
// analysis], blocks [ids in frame order], tracked [ids], frames. A static analysis stops at the
// first step whose ratio is below the tolerance, or at the duration's step count (status
// "completed" either way; "converged" says which).
nlohmann::ordered_json run_summary(const Scene& scene, const RunReport& report);

struct RunOptions {
  std::filesystem::path out_dir;  // empty: no files (validation measures through `observer`)
  // Called with the simulation at t = 0 and after every step.
  std::function<void(const Dda2d&)> observer;
  // Called after every step with (steps done, steps in the run).
  std::function<void(std::size_t, std::size_t)> progress;
  // Every this many steps (counted from the run's start), out_dir/checkpoint.json is replaced
  // by the state after the step (checkpoint.hpp); 0: never. Needs out_dir.
  std::size_t checkpoint_every = 0;
  // Resume from this checkpoint of the scene instead of starting: the run goes on from its
  // step to the scene's step count, and its files cover that stretch (the tracks and energies
  // from the checkpoint's instant on, the frames numbered from 0); summary.json's "start"
  // energies are those of the original run's t = 0.
  std::filesystem::path restart;
};

// Builds the engine from the scene (or resumes options.restart), takes the steps up to
// step_count(scene) and records. A run the engine stops midway returns with status "stopped"
// and the engine's message in `error`. Throws what the engine's constructor throws
// (StabilityError for a dt above its limit, std::invalid_argument for a parameter it refuses),
// InputError for a checkpoint that cannot be resumed, std::invalid_argument for checkpoints
// without an output directory, and OutputError.
RunReport run_scene(const Scene& scene, const RunOptions& options = {});

}  // namespace rockcontact::dynamics
