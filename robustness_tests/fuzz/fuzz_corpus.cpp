// Writes the seed corpora of the fuzz targets, so that no binary blob is kept in the repository:
//
//   fuzz_corpus OUT_DIR [PAIRS_PER_FAMILY]      (default 16)
//
//   OUT_DIR/pair_kernel/  PAIRS_PER_FAMILY pairs of every generator family
//                         (robustness::all_families, raw encoding of pair_input.hpp), half of
//                         them flagged to go through convex_hull or paper demarcation, plus a
//                         few hand-made degenerate pairs in the small-integer, dyadic and tagged
//                         encodings;
//   OUT_DIR/pair_kernel3d/  PAIRS_PER_FAMILY generated-mode inputs of every 3D family
//                         (fuzz_pair_kernel3d.cpp's format), half with a one-ulp
//                         perturbation, and two cubes in the points mode;
//   OUT_DIR/pairs_json/   the `pairs` examples (examples/pairs/*.json);
//   OUT_DIR/scene_json/   the scenes (examples/scenes/*.json), plus a region whose joint spacing
//                         (1e-9 m in a 1 km square) the reader must reject quickly;
//   OUT_DIR/scene3d_json/ the 3D scenes and cut documents (examples/scenes3d/*.json);
//   OUT_DIR/scene_cdem_json/ the CDEM scenes (examples/scenes_cdem/*.json) and the CLI tests'
//                         (dynamics/tests/data/scenes/cdem_*.json: one valid, one without a
//                         mesh, one clockwise, one with a block inside another), plus a block
//                         resting under gravity on a fixed base by the penalty law, and two
//                         blocks meeting with subdivided elements and exact touch predicates,
//                         so that both laws have seeds.
//
// The seed of the generators is fixed, so the corpus is the same on every run.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "rockcontact/generators/pair3d_generators.hpp"
#include "rockcontact/generators/pair_generators.hpp"
#include "pair_input.hpp"

namespace {

namespace fs = std::filesystem;
namespace rb = rockcontact::robustness;
namespace rf = rockcontact::fuzz;

constexpr std::uint64_t seed = 0xf022'5eedull;

void write(const fs::path& file, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::fprintf(stderr, "fuzz_corpus: cannot write %s\n", file.c_str());
    std::exit(1);
  }
}

std::size_t write_generated(const fs::path& dir, std::size_t per_family) {
  std::size_t written = 0;
  for (const rb::Family family : rb::all_families) {
    for (std::size_t i = 0; i < per_family; ++i) {
      const rb::PolygonPair pair = rb::generate_pair(family, seed, i);
      if (pair.cp.size() > rf::max_vertices || pair.tp.size() > rf::max_vertices) continue;
      // Odd indices vary the flags so that the hull and paper-demarcation paths have seeds too.
      const std::uint8_t flags = i % 2 == 0 ? 0 : (i % 4 == 1 ? rf::flag_hull : rf::flag_paper);
      write(dir / (std::string(rb::to_string(family)) + "_" + std::to_string(i) + ".bin"),
            rf::encode_raw_pair(pair.cp, pair.tp, flags));
      ++written;
    }
  }
  return written;
}

// fuzz_pair_kernel3d's generated mode: flags 1, family, seed (8 bytes), index (2 bytes), then
// for odd indices one perturbation (vertex 0 of b, coordinate z, +1 ulp); and its points mode
// in the small encoding: a unit cube of side 4 and the same cube on top of it (face touch).
std::size_t write_generated3d(const fs::path& dir, std::size_t per_family) {
  std::size_t written = 0;
  for (std::size_t f = 0; f < rb::all_families3d.size(); ++f) {
    for (std::size_t i = 0; i < per_family; ++i) {
      std::vector<std::uint8_t> bytes{1, static_cast<std::uint8_t>(f)};
      for (int k = 0; k < 8; ++k) bytes.push_back(static_cast<std::uint8_t>(seed >> (8 * k)));
      bytes.push_back(static_cast<std::uint8_t>(i));
      bytes.push_back(static_cast<std::uint8_t>(i >> 8));
      if (i % 2 == 1) bytes.insert(bytes.end(), {0x80, 2, 1, 0});
      write(dir / (std::string(rb::to_string(rb::all_families3d[f])) + "_" + std::to_string(i) + ".bin"), bytes);
      ++written;
    }
  }
  const auto small = static_cast<std::uint8_t>(static_cast<std::uint8_t>(rf::Encoding::small) << 1);
  std::vector<std::uint8_t> cubes{small, 8, 8};
  for (const int z0 : {0, 4}) {
    for (const int x : {0, 4}) {
      for (const int y : {0, 4}) {
        for (const int z : {0, 4}) {
          cubes.insert(cubes.end(), {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y),
                                     static_cast<std::uint8_t>(z0 + z)});
        }
      }
    }
  }
  write(dir / "small_cubes_face_touch.bin", cubes);
  return written + 1;
}

// Hand-made pairs in the other encodings (byte layout in pair_input.hpp).
std::size_t write_handmade(const fs::path& dir) {
  const auto small = static_cast<std::uint8_t>(rf::Encoding::small);
  const auto dyadic = static_cast<std::uint8_t>(rf::Encoding::dyadic);
  const auto tagged = static_cast<std::uint8_t>(rf::Encoding::tagged);
  const auto t = [](int v) { return static_cast<std::uint8_t>(v + rf::tag_zero); };
  const std::vector<std::pair<std::string, std::vector<std::uint8_t>>> seeds{
      // Unit squares sharing an edge (touch), and a square on another's corner.
      {"small_edge_touch", {small, 4, 4, 0, 0, 4, 0, 4, 4, 0, 4, 4, 0, 8, 0, 8, 4, 4, 4}},
      {"small_corner", {small, 4, 3, 0, 0, 4, 0, 4, 4, 0, 4, 4, 4, 8, 8, 2, 6}},
      // A triangle with a collinear vertex (must be rejected) against a square.
      {"small_collinear", {small, 4, 4, 0, 0, 2, 0, 4, 0, 2, 3, 1, 1, 3, 1, 3, 3, 1, 3}},
      // Squares of side 2^-40 m at (1e6, 1e6) m, overlapping by half.
      {"dyadic_far",
       {dyadic, 4, 4, 128 - 40,
        // offset 1e6 as a little-endian double: 0x412E848000000000
        0, 0, 0, 0, 0x80, 0x84, 0x2e, 0x41,
        0, 0, 0, 0, 2, 0, 0, 0, 2, 0, 2, 0, 0, 0, 2, 0,
        1, 0, 1, 0, 3, 0, 1, 0, 3, 0, 3, 0, 1, 0, 3, 0}},
      // A lattice square against a triangle with a NaN vertex.
      {"tagged_nan",
       {tagged, 4, 3, t(0), t(0), t(2), t(0), t(2), t(2), t(0), t(2), t(1), t(1), t(3), t(1), rf::tag_raw,
        0, 0, 0, 0, 0, 0, 0xf8, 0x7f, t(2)}},
  };
  for (const auto& [name, bytes] : seeds) write(dir / (name + ".bin"), bytes);
  return seeds.size();
}

// The .json files of `from` whose names start with `prefix`.
std::size_t copy_json(const fs::path& from, const fs::path& to, std::string_view prefix = "") {
  std::size_t copied = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(from)) {
    if (entry.path().extension() != ".json" || !entry.path().filename().string().starts_with(prefix)) continue;
    fs::copy_file(entry.path(), to / entry.path().filename(), fs::copy_options::overwrite_existing);
    ++copied;
  }
  return copied;
}

void write_text(const fs::path& file, std::string_view text) {
  write(file, std::vector<std::uint8_t>(text.begin(), text.end()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: fuzz_corpus OUT_DIR [PAIRS_PER_FAMILY]\n");
    return 2;
  }
  const fs::path out = argv[1];
  const std::size_t per_family = argc == 3 ? std::strtoull(argv[2], nullptr, 10) : 16;
  const fs::path examples = ROCKCONTACT_EXAMPLES_DIR;
  for (const char* dir : {"pair_kernel", "pair_kernel3d", "pairs_json", "scene_json", "scene3d_json", "scene_cdem_json"}) {
    fs::create_directories(out / dir);
  }

  const std::size_t pairs = write_generated(out / "pair_kernel", per_family) + write_handmade(out / "pair_kernel");
  const std::size_t pairs3d = write_generated3d(out / "pair_kernel3d", per_family);
  const std::size_t pair_files = copy_json(examples / "pairs", out / "pairs_json");
  std::size_t scenes = copy_json(examples / "scenes", out / "scene_json");
  write_text(out / "scene_json" / "spacing_1e-9.json",
             R"({"dimension": 2, "time": {"dt": 1e-4, "duration": 1},
 "materials": {"rock": {"density": 2700, "youngs_modulus": 1e9, "poisson_ratio": 0.25}},
 "contact": {"law": "potential", "kn": 1e9, "H": "mean_edge"},
 "region": {"vertices": [[0, 0], [1000, 0], [1000, 1000], [0, 1000]], "material": "rock"},
 "joint_sets": [{"dip_deg": 30, "spacing": 1e-9}]}
)");
  ++scenes;
  const std::size_t scenes3d = copy_json(examples / "scenes3d", out / "scene3d_json");
  const std::size_t scenes_cdem = copy_json(examples / "scenes_cdem", out / "scene_cdem_json") +
                                  copy_json(ROCKCONTACT_TEST_SCENES_DIR, out / "scene_cdem_json", "cdem_") + 2;
  write_text(out / "scene_cdem_json" / "penalty_on_base.json",
             R"({"solver": "cdem", "time": {"dt": 1e-6, "duration": 1e-3}, "gravity": [0, -9.81],
 "plane": "stress", "thickness": 0.5, "damping": 10,
 "materials": {"rock": {"density": 2700, "youngs_modulus": 1e9, "poisson_ratio": 0.25}},
 "contact": {"law": "penalty", "kn": 1e7, "kt": 5e6, "friction_angle_deg": 30, "cohesion": 1e3, "policy": "checked",
             "tensile_strength": 1e3, "search_tolerance": 1e-3},
 "blocks": [{"id": "base", "material": "rock", "vertices": [[0, -0.1], [0.4, -0.1], [0.4, 0], [0, 0]],
             "fixed": true, "mesh": {"max_edge": 0.1}},
            {"id": "block", "material": "rock", "vertices": [[0.1, 0], [0.2, 0], [0.2, 0.1], [0.1, 0.1]],
             "velocity": [0.1, -0.01, 0], "mesh": {"max_edge": 0.05}}],
 "output": {"every": 5}}
)");
  write_text(out / "scene_cdem_json" / "subdivide_exact.json",
             R"({"format": "rockcontact-scene/1", "dimension": 2, "solver": "cdem",
 "time": {"dt": 2e-6, "duration": 4e-5}, "gravity": [0, 0],
 "materials": {"rock": {"density": 2700, "youngs_modulus": 4e10, "poisson_ratio": 0.25}},
 "contact": {"law": "two-scale", "subdivide": true, "policy": "exact", "search_tolerance": 5e-3},
 "blocks": [{"id": "i", "material": "rock", "vertices": [[0, 0], [0.1, 0.04], [0, 0.1]],
             "velocity": [5, 0, 1], "mesh": {"max_edge": 0.05}},
            {"id": "j", "material": "rock", "vertices": [[0.1001, 0], [0.2, 0], [0.2, 0.1], [0.1001, 0.1]],
             "mesh": {"max_edge": 0.05}}],
 "output": {"track": ["i"], "every": 1}}
)");
  std::printf("fuzz_corpus: %zu pair inputs, %zu 3D pair inputs, %zu pairs documents, %zu scenes, %zu 3D scenes, "
              "%zu CDEM scenes in %s\n",
              pairs, pairs3d, pair_files, scenes, scenes3d, scenes_cdem, out.c_str());
  return 0;
}
