#define BOOST_TEST_MODULE scene_cdem_output
#include "rockcontact/dynamics/io/scene_cdem_output.hpp"

#include <algorithm>
#include <boost/property_tree/ptree.hpp>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/scene_cdem.hpp"
#include "rockcontact/testing/output_files.hpp"

namespace dyn = rockcontact::dynamics;
namespace fs = std::filesystem;
namespace pt = boost::property_tree;
using nlohmann::json;
using rockcontact::testing::data_array;
using rockcontact::testing::numbers;
using rockcontact::testing::pvd_entries;
using rockcontact::testing::read_csv;
using rockcontact::testing::read_text;
using rockcontact::testing::read_xml;

namespace {

const std::string tracks_header = "t,block,x,y,rotation,vx,vy,omega";
const std::string events_header = "t,event,block_a,block_b";

fs::path fresh_dir(const std::string& name) {
  return rockcontact::testing::fresh_dir("scene_cdem_output_test", name);
}

// A square block `id` of side 0.1 m with its lower left corner at (x, 0), meshed at 0.05 m.
json square(const std::string& id, double x) {
  return {{"id", id},
          {"material", "rock"},
          {"vertices", {{x, 0.0}, {x + 0.1, 0.0}, {x + 0.1, 0.1}, {x, 0.1}}},
          {"mesh", {{"max_edge", 0.05}}}};
}

// Seed 003's example: rock (E = 40 GPa), dt 2 µs (below the meshes' critical step, 3.3 µs),
// two-scale contact with friction, no gravity; `blocks` as given.
json scene_with(json blocks, double duration, std::size_t every) {
  json scene = json::parse(R"({"solver": "cdem", "gravity": [0, 0],
   "materials": {"rock": {"density": 2700, "youngs_modulus": 4e10, "poisson_ratio": 0.25}},
   "contact": {"law": "two-scale", "friction_angle_deg": 30, "search_tolerance": 5e-3}})");
  scene["time"] = {{"dt", 2e-6}, {"duration", duration}};
  scene["output"] = {{"every", every}};
  scene["blocks"] = std::move(blocks);
  return scene;
}

// The VTK frame's grid: its point and cell counts, after checking that every array has its
// count of values, every cell is a triangle (type 5) of existing points, and the offsets are
// those of triangles.
std::pair<std::size_t, std::size_t> check_frame(const fs::path& file) {
  const pt::ptree tree = read_xml(file);
  BOOST_TEST(tree.get<std::string>("VTKFile.<xmlattr>.type") == "UnstructuredGrid");
  const pt::ptree& piece = tree.get_child("VTKFile.UnstructuredGrid.Piece");
  const auto points = piece.get<std::size_t>("<xmlattr>.NumberOfPoints");
  const auto cells = piece.get<std::size_t>("<xmlattr>.NumberOfCells");
  BOOST_TEST(numbers(data_array(piece.get_child("Points"), "Points").data()).size() == 3 * points);
  const pt::ptree& grid = piece.get_child("Cells");
  const auto connectivity = numbers(data_array(grid, "connectivity").data());
  const auto offsets = numbers(data_array(grid, "offsets").data());
  const auto types = numbers(data_array(grid, "types").data());
  BOOST_TEST_REQUIRE(connectivity.size() == 3 * cells);
  BOOST_TEST_REQUIRE(offsets.size() == cells);
  BOOST_TEST(std::all_of(types.begin(), types.end(), [](double t) { return t == 5.0; }));
  BOOST_TEST(types.size() == cells);
  for (std::size_t c = 0; c < cells; ++c)
    BOOST_TEST(offsets[c] == 3.0 * static_cast<double>(c + 1));
  BOOST_TEST(*std::max_element(connectivity.begin(), connectivity.end()) <
             static_cast<double>(points));
  BOOST_TEST(numbers(data_array(piece.get_child("PointData"), "velocity").data()).size() ==
             3 * points);
  const pt::ptree& cell_data = piece.get_child("CellData");
  BOOST_TEST(numbers(data_array(cell_data, "block").data()).size() == cells);
  BOOST_TEST(numbers(data_array(cell_data, "stress").data()).size() == 3 * cells);
  BOOST_TEST(numbers(data_array(cell_data, "von_mises").data()).size() == cells);
  return {points, cells};
}

}  // namespace

// A block flying free (no gravity, no contact) keeps its velocity, and its mass centre (the
// polygon's centroid, for lumped masses) moves with it: x = 0.05 + 2 t, y = 0.05 - t. The last
// instant (step 525) is recorded although it is not a multiple of `every`.
BOOST_AUTO_TEST_CASE(a_free_block_keeps_its_velocity) {
  const fs::path dir = fresh_dir("free");
  json document = scene_with({square("i", 0.0)}, 525 * 2e-6, 100);
  document["blocks"][0]["velocity"] = {2.0, -1.0, 0.0};
  const dyn::SceneCdem scene = dyn::parse_scene_cdem(document, "free.json");
  dyn::RunCdemOptions options;
  options.out_dir = dir;
  std::size_t calls = 0;
  options.progress = [&](std::size_t done, std::size_t total) {
    ++calls;
    BOOST_TEST(done == calls);
    BOOST_TEST(total == 525u);
  };
  const dyn::RunCdemReport report = dyn::run_scene_cdem(scene, options);
  BOOST_TEST(report.status == "completed");
  BOOST_TEST(report.steps == 525u);
  BOOST_TEST(calls == 525u);
  BOOST_TEST(report.frames == 7u);  // steps 0, 100, ..., 500 and 525
  const auto rows = read_csv(dir / "tracks.csv", tracks_header);
  BOOST_TEST_REQUIRE(rows.size() == 7u);
  for (const auto& row : rows) {
    const double t = std::stod(row[0]);
    BOOST_TEST_CONTEXT("t = " << row[0]) {
      BOOST_TEST(row[1] == "i");
      // 1e-12 m: the roundoff of 525 additions of 4e-6 m to 0.05 m.
      BOOST_TEST(std::abs(std::stod(row[2]) - (0.05 + 2.0 * t)) < 1e-12);
      BOOST_TEST(std::abs(std::stod(row[3]) - (0.05 - t)) < 1e-12);
      BOOST_TEST(std::abs(std::stod(row[4])) < 1e-12);
      BOOST_TEST(std::abs(std::stod(row[5]) - 2.0) < 1e-12);
      BOOST_TEST(std::abs(std::stod(row[6]) + 1.0) < 1e-12);
      BOOST_TEST(std::abs(std::stod(row[7])) < 1e-9);
    }
  }
  BOOST_TEST(std::stod(rows.back()[0]) == report.time);
  BOOST_TEST(std::abs(report.time - 525 * 2e-6) < 1e-15);
  BOOST_TEST(read_csv(dir / "events.csv", events_header).empty());
}

// Two squares 1 mm apart, the left one at 3 m/s: the files of a run with contact. The first
// event is the touch at t = 1 mm / (3 m/s); the frames are those of tracks.csv; summary.json
// has its keys in the documented order.
BOOST_AUTO_TEST_CASE(the_files_of_an_impact) {
  const fs::path dir = fresh_dir("impact");
  json document = scene_with({square("i", 0.0), square("j", 0.101)}, 0.0005, 50);
  document["blocks"][0]["velocity"] = {3.0, 0.0, 0.0};
  document["output"]["track"] = {"j", "i"};
  const dyn::SceneCdem scene = dyn::parse_scene_cdem(document, "impact.json");
  dyn::RunCdemOptions options;
  options.out_dir = dir;
  const dyn::RunCdemReport report = dyn::run_scene_cdem(scene, options);
  BOOST_TEST(report.status == "completed");
  BOOST_TEST(report.steps == 250u);

  const auto events = read_csv(dir / "events.csv", events_header);
  BOOST_TEST(events.size() == report.events);
  BOOST_TEST_REQUIRE(!events.empty());
  BOOST_TEST(events[0][1] == "touch");
  BOOST_TEST(events[0][2] == "i");  // the block whose node touches
  BOOST_TEST(events[0][3] == "j");
  // The touch time is the engine's exact one; 1e-9 relative covers its roundoff.
  BOOST_TEST(std::abs(std::stod(events[0][0]) - 0.001 / 3.0) < 1e-9 * (0.001 / 3.0));
  for (const auto& e : events) BOOST_TEST((e[1] == "touch" || e[1] == "separate"));

  const auto tracks = read_csv(dir / "tracks.csv", tracks_header);
  const auto frames = pvd_entries(dir / "frames.pvd");
  BOOST_TEST_REQUIRE(frames.size() == 6u);  // steps 0, 50, ..., 250
  BOOST_TEST(report.frames == frames.size());
  BOOST_TEST_REQUIRE(tracks.size() == 2 * frames.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    BOOST_TEST(frames[f].second == "frame_000" + std::to_string(f) + ".vtu");
    BOOST_TEST(tracks[2 * f][1] == "j");  // the order of output.track
    BOOST_TEST(tracks[2 * f + 1][1] == "i");
    BOOST_TEST(std::stod(tracks[2 * f][0]) == frames[f].first);
    const auto [points, cells] = check_frame(dir / frames[f].second);
    if (f == 0) {
      BOOST_TEST(points == report.nodes);
      BOOST_TEST(cells == report.elements);
    }
  }

  const nlohmann::ordered_json summary =
      nlohmann::ordered_json::parse(read_text(dir / "summary.json"));
  std::vector<std::string> keys;
  for (const auto& [key, value] : summary.items()) keys.push_back(key);
  const std::vector<std::string> expected = {
      "scene", "description", "dimension", "solver", "law", "status", "steps", "time", "dt",
      "critical_dt", "wall_seconds", "simulation_seconds", "output_seconds", "elements", "nodes",
      "energy", "momentum", "clone_nodes", "touches", "subdivided_elements", "events", "blocks",
      "tracked", "frames"};
  BOOST_TEST(keys == expected, boost::test_tools::per_element());
  BOOST_TEST(summary["solver"] == "cdem");
  BOOST_TEST(summary["law"] == "two-scale");
  BOOST_TEST(summary["dimension"] == 2);
  BOOST_TEST(summary["events"] == events.size());
  BOOST_TEST(summary["touches"] == report.counters.touches);
  BOOST_TEST(summary["critical_dt"].get<double>() > 2e-6);
  // The moving block's mass, 0.01 m² x 2700 kg/m³ x 1 m = 27 kg, at 3 m/s: 81 kg m/s and
  // 121.5 J, up to the roundoff of summing its node masses (1e-12 relative).
  BOOST_TEST(std::abs(summary["momentum"]["start"][0].get<double>() - 81.0) < 1e-12 * 81.0);
  BOOST_TEST(summary["momentum"]["start"][1].get<double>() == 0.0);
  BOOST_TEST(std::abs(summary["energy"]["start"]["kinetic"].get<double>() - 121.5) <
             1e-12 * 121.5);
  for (const char* term : {"kinetic", "strain", "gravitational", "contact", "onset_loss",
                           "friction", "damping", "tie_work", "total"}) {
    BOOST_TEST(summary["energy"]["end"].contains(term), term);
  }
  BOOST_TEST(summary["blocks"].get<std::vector<std::string>>() ==
             (std::vector<std::string>{"i", "j"}));
  BOOST_TEST(summary["tracked"].get<std::vector<std::string>>() ==
             (std::vector<std::string>{"j", "i"}));

  // final.svg: one group per block, titled with its id, its elements and its outline.
  const pt::ptree svg = read_xml(dir / "final.svg");
  std::vector<std::string> titles;
  for (const auto& [tag, group] : svg.get_child("svg")) {
    if (tag != "g") continue;
    titles.push_back(group.get<std::string>("title"));
    std::size_t polygons = 0;
    for (const auto& [child, node] : group) polygons += child == "polygon";
    BOOST_TEST(polygons > 0u);
    BOOST_TEST(group.count("path") == 1u);
  }
  BOOST_TEST(titles == (std::vector<std::string>{"i", "j"}), boost::test_tools::per_element());
}

// A run the engine stops (a block at 3 km/s driven deep into another, the energy growing)
// returns "stopped" with the engine's message, and its files are complete up to the stop.
BOOST_AUTO_TEST_CASE(a_stopped_run_still_writes_its_files) {
  const fs::path dir = fresh_dir("stopped");
  json document = scene_with({square("i", 0.0), square("j", 0.101)}, 0.002, 100);
  document["blocks"][0]["velocity"] = {3000.0, 0.0, 0.0};
  const dyn::SceneCdem scene = dyn::parse_scene_cdem(document, "stopped.json");
  dyn::RunCdemOptions options;
  options.out_dir = dir;
  const dyn::RunCdemReport report = dyn::run_scene_cdem(scene, options);
  BOOST_TEST_REQUIRE(report.status == "stopped");
  BOOST_TEST(!report.error.empty());
  BOOST_TEST(report.steps < 1000u);
  const json summary = json::parse(read_text(dir / "summary.json"));
  BOOST_TEST(summary["status"] == "stopped");
  BOOST_TEST(summary["error"] == report.error);
  BOOST_TEST(summary["steps"] == report.steps);
  const auto frames = pvd_entries(dir / "frames.pvd");
  BOOST_TEST(frames.size() == report.frames);
  BOOST_TEST(frames.back().first == report.time);  // the state at the stop
  BOOST_TEST(read_csv(dir / "tracks.csv", tracks_header).size() == 2 * frames.size());
  BOOST_TEST(fs::exists(dir / "events.csv"));
  BOOST_TEST(fs::exists(dir / "final.svg"));
}

// Without an output directory the run writes nothing and reports no frames.
BOOST_AUTO_TEST_CASE(a_run_without_outputs) {
  json document = scene_with({square("i", 0.0)}, 10 * 2e-6, 5);
  const dyn::RunCdemReport report =
      dyn::run_scene_cdem(dyn::parse_scene_cdem(document, "quiet.json"));
  BOOST_TEST(report.status == "completed");
  BOOST_TEST(report.steps == 10u);
  BOOST_TEST(report.frames == 0u);
  BOOST_TEST(report.output_seconds == 0.0);
}
