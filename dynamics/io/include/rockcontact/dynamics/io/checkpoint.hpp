#pragma once
// Checkpoints of a scene run: what `rockcontact run SCENE --checkpoint-every N` writes to
// DIR/checkpoint.json (replaced every N steps, atomically) and `rockcontact run SCENE
// --restart FILE` resumes from. A resumed run goes on bit-identically: its tracks, energies and
// summary from the checkpoint's instant on are those the uninterrupted run writes.
//
//   {"format": "rockcontact-checkpoint", "format_version": 1,
//    "rockcontact": the version that wrote it,
//    "scene": the scene file's name (informative), "scene_digest": 16 hex digits (scene.hpp),
//    "steps": steps taken, "time": s,
//    "initial_energy": the run's energies at t = 0 (summary.json's "start"),
//    "engine": the simulation's Snapshot (dda2d.hpp), member by member}
//
// Every double is written in shortest round-trip form, so it reads back to the bit. A
// checkpoint resumes only the scene it was written for (the digest covers every field but
// "description", "output" and "time.duration": a run can be lengthened, or recorded at another
// interval, from a checkpoint) and only under the rockcontact version that wrote it (another
// version may step differently). Anything else is an InputError naming the file, the field and
// what was expected.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "rockcontact/dynamics/dda2d.hpp"
#include "rockcontact/dynamics/io/scene.hpp"

namespace rockcontact::dynamics {

struct Checkpoint {
  std::uint64_t scene_digest = 0;
  Energies initial;  // J/m, the run's energies at t = 0
  Snapshot engine;
};

nlohmann::ordered_json checkpoint_json(const Scene& scene, const Checkpoint& checkpoint);

// Writes checkpoint_json to `file` atomically; throws OutputError when it cannot.
void write_checkpoint(const std::filesystem::path& file, const Scene& scene,
                      const Checkpoint& checkpoint);

// Reads a checkpoint of `scene`; throws InputError for an unreadable or malformed file, one of
// another scene or another version.
Checkpoint read_checkpoint(const std::filesystem::path& file, const Scene& scene);

}  // namespace rockcontact::dynamics
