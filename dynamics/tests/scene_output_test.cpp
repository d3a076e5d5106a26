#define BOOST_TEST_MODULE scene_output
#include "rockcontact/dynamics/io/scene_output.hpp"

#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <boost/test/unit_test.hpp>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/testing/output_files.hpp"

namespace dyn = rockcontact::dynamics;
namespace fs = std::filesystem;
namespace pt = boost::property_tree;
using nlohmann::json;

namespace {

// Shortest round-trip text of a double, as the outputs write it.
std::string shortest(double x) {
  std::array<char, 32> text{};
  return {text.data(), std::to_chars(text.data(), text.data() + text.size(), x).ptr};
}

const std::string scene_dir = ROCKCONTACT_DYNAMICS_TESTDATA_DIR "/scenes";

fs::path fresh_dir(const std::string& name) {
  return rockcontact::testing::fresh_dir("scene_output_test", name);
}

using rockcontact::testing::data_array;
using rockcontact::testing::numbers;
using rockcontact::testing::pvd_entries;
using rockcontact::testing::read_text;
using rockcontact::testing::read_xml;
using rockcontact::testing::split;

struct TrackRow {
  double t, x, y, rotation, vx, vy, omega;
  std::string block;
};

// tracks.csv: checks the header, returns the rows.
std::vector<TrackRow> read_tracks(const fs::path& file) {
  const std::vector<std::string> lines = split(read_text(file), '\n');
  BOOST_TEST_REQUIRE(!lines.empty());
  BOOST_TEST(lines[0] == "t,block,x,y,rotation,vx,vy,omega");
  std::vector<TrackRow> rows;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> f = split(lines[i], ',');
    BOOST_TEST_REQUIRE(f.size() == 8u);
    rows.push_back({std::stod(f[0]), std::stod(f[2]), std::stod(f[3]), std::stod(f[4]),
                    std::stod(f[5]), std::stod(f[6]), std::stod(f[7]), f[1]});
  }
  return rows;
}

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// Checks one frame: well-formed XML, one polygon per block with the right number of points,
// connectivity and offsets consistent, cell data per block.
void check_frame(const fs::path& file, const std::vector<std::size_t>& vertex_counts) {
  const pt::ptree tree = read_xml(file);
  BOOST_TEST(tree.get<std::string>("VTKFile.<xmlattr>.type") == "PolyData");
  const pt::ptree& piece = tree.get_child("VTKFile.PolyData.Piece");
  std::size_t points = 0;
  for (const std::size_t n : vertex_counts) points += n;
  BOOST_TEST(piece.get<std::size_t>("<xmlattr>.NumberOfPolys") == vertex_counts.size());
  BOOST_TEST(piece.get<std::size_t>("<xmlattr>.NumberOfPoints") == points);
  BOOST_TEST(numbers(data_array(piece.get_child("Points"), "Points").data()).size() == 3 * points);
  const auto connectivity = numbers(data_array(piece.get_child("Polys"), "connectivity").data());
  const auto offsets = numbers(data_array(piece.get_child("Polys"), "offsets").data());
  BOOST_TEST(connectivity.size() == points);
  BOOST_TEST_REQUIRE(offsets.size() == vertex_counts.size());
  std::size_t end = 0;
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    end += vertex_counts[i];
    BOOST_TEST(offsets[i] == static_cast<double>(end));
  }
  const pt::ptree& cells = piece.get_child("CellData");
  BOOST_TEST(numbers(data_array(cells, "block").data()).size() == vertex_counts.size());
  BOOST_TEST(numbers(data_array(cells, "velocity").data()).size() == 3 * vertex_counts.size());
}


dyn::BlockState square_state(const std::string& id, double x, double y, bool fixed) {
  dyn::BlockState b;
  b.id = id;
  b.vertices = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
  b.centroid = {x + 0.5, y + 0.5};
  b.velocity = {0.25, -0.5, 0.125, 0, 0, 0};
  b.fixed = fixed;
  b.area = 1.0;
  b.mass = 2000.0;
  return b;
}

// A single rigid 1 m square in free fall (gravity only, no other block, so no contact; rigid,
// so no strain mode limits the 1 ms step).
json free_fall_scene(int every) {
  json scene = json::parse(R"({"dimension": 2,
   "time": {"dt": 1e-3, "duration": 0.0505},
   "gravity": [0, -9.81],
   "materials": {"rock": {"density": 2000, "youngs_modulus": 1e9, "poisson_ratio": 0.25}},
   "contact": {"law": "potential", "kn": 1e7, "H": 1.0},
   "blocks": [{"id": "stone", "material": "rock", "vertices": [[2,10],[3,10],[3,11],[2,11]],
               "velocity": [0.5, 0.0, 0.0], "rigid": true}]})");
  scene["output"] = {{"every", every}};
  return scene;
}

}  // namespace

// The recorder alone, on block states built by hand: file layout and formats.
BOOST_AUTO_TEST_CASE(recorder_writes_every_file_in_its_format) {
  const fs::path dir = fresh_dir("recorder");
  dyn::Scene scene =
      dyn::parse_scene(json::parse(R"({"dimension": 2, "time": {"dt": 0.1, "duration": 0.2},
        "materials": {"rock": {"density": 2000, "youngs_modulus": 1e9, "poisson_ratio": 0.25}},
        "contact": {"law": "potential", "kn": 1e7, "H": 1.0},
        "blocks": [{"id": "base", "material": "rock", "vertices": [[0,0],[4,0],[4,1],[0,1]],
                    "fixed": true},
                   {"id": "a, \"quoted\"", "material": "rock",
                    "vertices": [[1,1],[2,1],[2,2],[1,2]]},
                   {"id": "b<c>", "material": "rock", "vertices": [[3,1],[4,1],[3.5,2]]}],
        "output": {"every": 1}})"),
                       "recorder.json");
  std::vector<dyn::BlockState> blocks{square_state("base", 0, 0, true),
                                      square_state("a, \"quoted\"", 1, 1, false),
                                      square_state("b<c>", 3, 1, false)};
  blocks[0].vertices = {{0, 0}, {4, 0}, {4, 1}, {0, 1}};
  blocks[2].vertices = {{3, 1}, {4, 1}, {3.5, 2}};
  {
    dyn::SceneRecorder recorder(scene, dir);
    dyn::Energies energies;
    recorder.record(0.0, blocks, {}, energies);
    energies.kinetic = 0.5;
    energies.gravitational = -2.0;
    energies.contact = 1.25;
    energies.friction_dissipated = 0.125;
    energies.damping_dissipated = 0.0625;
    recorder.record(0.1, blocks, {}, energies);
    energies.strain = 0.03125;
    recorder.record(0.2, blocks, {}, energies);
    BOOST_TEST(recorder.frames() == 3u);
    recorder.finish(blocks, json::object({{"status", "completed"}}));
  }
  const std::string csv = read_text(dir / "tracks.csv");
  BOOST_TEST(csv.substr(0, csv.find('\n')) == "t,block,x,y,rotation,vx,vy,omega");
  // Two tracked blocks (the ones not fixed) at three instants; the id with a comma is quoted.
  BOOST_TEST(count(csv, "\n") == 7u);
  BOOST_TEST(count(csv, "0.1,\"a, \"\"quoted\"\"\",1.5,1.5,0,0.25,-0.5,0.125\n") == 1u);
  BOOST_TEST(count(csv, "0.2,b<c>,3.5,1.5,0,0.25,-0.5,0.125\n") == 1u);

  // One energies row per recorded instant, the terms in summary.json's order, total their sum
  // (every value exact in binary).
  const std::string energies = read_text(dir / "energies.csv");
  BOOST_TEST(energies ==
             "t,kinetic,gravitational,strain,contact,friction_dissipated,damping_dissipated,total\n"
             "0,0,0,0,0,0,0,0\n"
             "0.1,0.5,-2,0,1.25,0.125,0.0625,-0.0625\n"
             "0.2,0.5,-2,0.03125,1.25,0.125,0.0625,-0.03125\n");

  const auto frames = pvd_entries(dir / "frames.pvd");
  BOOST_TEST_REQUIRE(frames.size() == 3u);
  BOOST_TEST(frames[0].second == "frame_0000.vtp");
  BOOST_TEST(frames[2].second == "frame_0002.vtp");
  BOOST_TEST(frames[1].first == 0.1);
  for (const auto& [t, file] : frames) check_frame(dir / file, {4, 4, 3});

  const std::string svg = read_text(dir / "final.svg");
  BOOST_TEST(count(svg, "<polygon") == 5u);  // three blocks, two movable ones' start outlines
  BOOST_TEST(count(svg, "stroke-dasharray") == 2u);
  BOOST_TEST(count(svg, "t = 0.2 s; dashed: t = 0 s") == 1u);
  BOOST_TEST(count(svg, "fill=\"#bdbdbd\"") == 1u);  // the fixed base, grey
  BOOST_TEST(count(svg, "fill=\"#f28e2b\"") == 2u);  // the tracked blocks, highlighted
  BOOST_TEST(count(svg, "<title>b&lt;c&gt;</title>") == 1u);
  BOOST_CHECK_NO_THROW(read_xml(dir / "final.svg"));

  BOOST_TEST(json::parse(read_text(dir / "summary.json")).at("status") == "completed");
}

BOOST_AUTO_TEST_CASE(unwritable_directory_is_an_output_error) {
  const fs::path file = fresh_dir("blocker");
  fs::create_directories(file.parent_path());
  std::ofstream(file) << "a file where the directory should be";
  const dyn::Scene scene = dyn::read_scene_file(scene_dir + "/two_blocks.json");
  BOOST_CHECK_THROW(dyn::SceneRecorder(scene, file / "out"), dyn::OutputError);
}

// An AtomicFile's target appears only at commit(); until then a previous version stays whole,
// and an abandoned write leaves neither the target changed nor the ".partial" file behind.
BOOST_AUTO_TEST_CASE(atomic_file_appears_only_when_committed) {
  const fs::path dir = fresh_dir("atomic");
  fs::create_directories(dir);
  const fs::path target = dir / "result.json";
  const fs::path partial = dir / "result.json.partial";
  {
    dyn::AtomicFile file(target);
    file.stream() << "first";
    BOOST_TEST(!fs::exists(target));
    BOOST_TEST(fs::exists(partial));
    file.commit();
  }
  BOOST_TEST(read_text(target) == "first");
  BOOST_TEST(!fs::exists(partial));
  {
    dyn::AtomicFile file(target);
    file.stream() << "second, abandoned half-way";
  }
  BOOST_TEST(read_text(target) == "first");
  BOOST_TEST(!fs::exists(partial));
}

// A rename that fails (the target is a non-empty directory) is an OutputError naming the
// target; the directory is untouched and the partial file removed.
BOOST_AUTO_TEST_CASE(atomic_file_commit_failure_names_the_target) {
  const fs::path dir = fresh_dir("atomic_blocked");
  const fs::path target = dir / "summary.json";
  fs::create_directories(target / "occupied");
  dyn::AtomicFile file(target);
  file.stream() << "{}";
  try {
    file.commit();
    BOOST_ERROR("commit over a non-empty directory must throw");
  } catch (const dyn::OutputError& e) {
    BOOST_TEST(std::string(e.what()).find("cannot write " + target.string()) == 0u, e.what());
  }
  BOOST_TEST(fs::is_directory(target / "occupied"));
  BOOST_TEST(!fs::exists(dir / "summary.json.partial"));
}

// A run whose third frame cannot be written stops with an OutputError, and leaves no
// truncated file: the frames written before it are whole, tracks.csv and summary.json (written
// in full only at the end) do not exist, and no ".partial" file is left over.
BOOST_AUTO_TEST_CASE(failed_run_leaves_no_half_written_file) {
  const fs::path dir = fresh_dir("failed_run");
  fs::create_directories(dir / "frame_0002.vtp" / "occupied");
  const dyn::Scene scene = dyn::parse_scene(free_fall_scene(10), "free_fall.json");
  dyn::RunOptions options;
  options.out_dir = dir;
  BOOST_CHECK_THROW(dyn::run_scene(scene, options), dyn::OutputError);
  BOOST_TEST(!fs::exists(dir / "tracks.csv"));
  BOOST_TEST(!fs::exists(dir / "summary.json"));
  BOOST_TEST(!fs::exists(dir / "frames.pvd"));
  for (const auto& entry : fs::directory_iterator(dir)) {
    BOOST_TEST(entry.path().extension() != ".partial", entry.path());
  }
  for (const char* frame : {"frame_0000.vtp", "frame_0001.vtp"}) check_frame(dir / frame, {4});
}

// Velocity Verlet integrates a constant force exactly: y(t) = y0 - g t² / 2, x(t) = x0 + vx t,
// vy = -g t, for every recorded row (every 10 steps of 1 ms, plus the final time 0.051 s:
// 0.0505 s rounds up to 51 steps). What is left is rounding: the centroid is recomputed from
// vertices near 10 m (ulp 1.8e-15) after each of 51 steps, so 1e-12 m is generous.
BOOST_AUTO_TEST_CASE(free_fall_rows_follow_the_analytic_parabola) {
  const fs::path dir = fresh_dir("free_fall");
  const dyn::Scene scene = dyn::parse_scene(free_fall_scene(10), "free_fall.json");
  dyn::RunOptions options;
  options.out_dir = dir;
  const dyn::RunReport report = dyn::run_scene(scene, options);
  BOOST_TEST(report.steps == 51u);
  BOOST_TEST(report.status == "completed");
  const std::vector<TrackRow> rows = read_tracks(dir / "tracks.csv");
  const std::vector<double> times{0.0, 0.01, 0.02, 0.03, 0.04, 0.05, 0.051};
  BOOST_TEST_REQUIRE(rows.size() == times.size());
  const double g = 9.81, x0 = 2.5, y0 = 10.5, vx = 0.5;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const TrackRow& r = rows[i];
    BOOST_TEST_CONTEXT("row " << i << " t = " << r.t) {
      BOOST_TEST(r.block == "stone");
      BOOST_TEST(std::abs(r.t - times[i]) < 1e-15);
      BOOST_TEST(std::abs(r.y - (y0 - 0.5 * g * r.t * r.t)) < 1e-12);
      BOOST_TEST(std::abs(r.x - (x0 + vx * r.t)) < 1e-12);
      BOOST_TEST(std::abs(r.vy - (-g * r.t)) < 1e-12);
      BOOST_TEST(std::abs(r.vx - vx) < 1e-12);
      BOOST_TEST(r.rotation == 0.0);
      BOOST_TEST(r.omega == 0.0);
    }
  }
  const auto frames = pvd_entries(dir / "frames.pvd");
  BOOST_TEST_REQUIRE(frames.size() == times.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    BOOST_TEST(std::abs(frames[i].first - times[i]) < 1e-15);
    check_frame(dir / frames[i].second, {4});
  }
  BOOST_TEST(count(read_text(dir / "final.svg"), "<polygon") == 2u);  // the block, and its start outline
}

// The contract scene for a few steps: every file, and a summary that matches the report.
BOOST_AUTO_TEST_CASE(two_block_run_writes_the_contract_outputs) {
  const fs::path dir = fresh_dir("two_blocks");
  dyn::Scene scene = dyn::read_scene_file(scene_dir + "/two_blocks.json");
  dyn::RunOptions options;
  options.out_dir = dir;
  std::size_t progress_calls = 0, observed = 0;
  options.progress = [&](std::size_t done, std::size_t total) {
    ++progress_calls;
    BOOST_TEST(done <= total);
  };
  options.observer = [&](const dyn::Dda2d&) { ++observed; };
  const dyn::RunReport report = dyn::run_scene(scene, options);
  BOOST_TEST(report.steps == 100u);
  BOOST_TEST(progress_calls == 100u);
  BOOST_TEST(observed == 101u);  // t = 0 and after every step

  const std::vector<TrackRow> rows = read_tracks(dir / "tracks.csv");
  BOOST_TEST_REQUIRE(rows.size() == 5u);  // every 25 steps of 100, t = 0 included
  BOOST_TEST(rows.front().t == 0.0);
  BOOST_TEST(std::abs(rows.back().t - 0.01) < 1e-15);
  BOOST_TEST(rows.front().x == 1.5);
  BOOST_TEST(rows.front().y == 1.5);
  for (const TrackRow& r : rows) BOOST_TEST(r.block == "slider");

  const auto frames = pvd_entries(dir / "frames.pvd");
  BOOST_TEST(frames.size() == 5u);
  for (const auto& [t, file] : frames) check_frame(dir / file, {4, 4});
  BOOST_TEST(count(read_text(dir / "final.svg"), "<polygon") == 3u);  // base, slider, the slider at the start

  const json summary = json::parse(read_text(dir / "summary.json"));
  BOOST_TEST(summary.at("status") == "completed");
  BOOST_TEST(summary.at("steps") == 100);
  BOOST_TEST(summary.at("frames") == 5);
  BOOST_TEST(summary.at("time").get<double>() == report.time);
  BOOST_TEST(summary.at("energy").at("start").at("total").get<double>() == report.initial.total());
  BOOST_TEST(summary.at("energy").at("end").at("total").get<double>() == report.final.total());
  BOOST_TEST(summary.at("max_penetration").get<double>() == report.max_penetration);
  BOOST_TEST(summary.at("predicates").at("calls").get<std::uint64_t>() ==
             report.predicates.total_calls());
  BOOST_TEST(summary.at("blocks") == json::array({"base", "slider"}));
  BOOST_TEST(summary.at("tracked") == json::array({"slider"}));
  BOOST_TEST(summary.at("wall_seconds").get<double>() >= 0.0);

  // energies.csv: a row at each recorded instant; the first and the last are summary.json's
  // start and end energies, to the bit.
  std::istringstream energies(read_text(dir / "energies.csv"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(energies, line);) lines.push_back(line);
  BOOST_TEST_REQUIRE(lines.size() == 6u);  // the header and 5 instants
  const auto terms = [](const json& e, double t) {
    std::string row = shortest(t);
    for (const char* name : {"kinetic", "gravitational", "strain", "contact",
                             "friction_dissipated", "damping_dissipated", "total"}) {
      row += "," + shortest(e.at(name).get<double>());
    }
    return row;
  };
  BOOST_TEST(lines[1] == terms(summary.at("energy").at("start"), 0.0));
  BOOST_TEST(lines[5] == terms(summary.at("energy").at("end"), report.time));
}

// The engine refuses a time step above its stability limit before anything is written.
BOOST_AUTO_TEST_CASE(unstable_time_step_is_refused) {
  const dyn::Scene scene = dyn::read_scene_file(scene_dir + "/unstable.json");
  BOOST_CHECK_THROW(dyn::run_scene(scene), dyn::StabilityError);
}

namespace {

// contacts.csv: checks the header, returns the rows split into fields.
std::vector<std::vector<std::string>> read_contacts(const fs::path& file) {
  const std::vector<std::string> lines = split(read_text(file), '\n');
  BOOST_TEST_REQUIRE(!lines.empty());
  BOOST_TEST(lines[0] == "t,block_a,block_b,x,y,nx,ny,fn,ft,state");
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    rows.push_back(split(lines[i], ','));
    BOOST_TEST_REQUIRE(rows.back().size() == 10u);
  }
  return rows;
}

}  // namespace

// A column of four rigid 1 m squares on a fixed floor, relaxed by the static analysis to an
// out-of-balance ratio of 1e-10: at the last instant the interface under the k-th block from
// the top carries the weight of the k blocks down to it, k m g (statics), pointing down on the
// lower block (CP, the lower index) and up on the upper, with no shear. The ratio bounds each
// block's unbalanced force by 1e-10 of the largest force, 4 m g, so the sums from the top are
// within 4e-10 of it: bound 1e-9 relative. Every contact sticks (phi = 30°, no shear load).
BOOST_AUTO_TEST_CASE(contacts_csv_carries_a_static_column_s_weights) {
  const fs::path dir = fresh_dir("column");
  json document = json::parse(R"({"dimension": 2, "analysis": "static", "static_tolerance": 1e-10,
   "initial_equilibrium": false, "time": {"dt": 1e-4, "duration": 10},
   "materials": {"rock": {"density": 2500, "youngs_modulus": 1e10, "poisson_ratio": 0.25}},
   "contact": {"law": "potential", "kn": 1e9, "H": 1.0, "kt": 1e9, "friction_angle_deg": 30},
   "blocks": [{"id": "floor", "material": "rock", "vertices": [[-2,-1],[2,-1],[2,0],[-2,0]],
               "fixed": true}],
   "output": {"every": 1000}})");
  for (int k = 0; k < 4; ++k) {
    const double y = k;
    document["blocks"].push_back({{"id", "b" + std::to_string(k)}, {"material", "rock"}, {"rigid", true},
                                  {"vertices", {{-0.5, y}, {0.5, y}, {0.5, y + 1}, {-0.5, y + 1}}}});
  }
  dyn::RunOptions options;
  options.out_dir = dir;
  const dyn::RunReport report = dyn::run_scene(dyn::parse_scene(document, "column.json"), options);
  BOOST_TEST_REQUIRE(report.converged);
  const double weight = 2500.0 * 9.81;
  std::vector<std::vector<std::string>> last;
  for (const auto& row : read_contacts(dir / "contacts.csv")) {
    if (std::stod(row[0]) == report.time) last.push_back(row);
  }
  BOOST_TEST_REQUIRE(last.size() == 4u);
  const std::vector<std::string> lower{"floor", "b0", "b1", "b2"}, upper{"b0", "b1", "b2", "b3"};
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& row = last[k];
    BOOST_TEST_CONTEXT("contact " << row[1] << " / " << row[2]) {
      BOOST_TEST(row[1] == lower[k]);
      BOOST_TEST(row[2] == upper[k]);
      BOOST_TEST(std::stod(row[5]) == 0.0, boost::test_tools::tolerance(1e-9));   // nx
      BOOST_TEST(std::stod(row[6]) == -1.0, boost::test_tools::tolerance(1e-9));  // ny: down on a
      BOOST_TEST(std::stod(row[7]) / ((4.0 - static_cast<double>(k)) * weight) == 1.0, boost::test_tools::tolerance(1e-9));
      BOOST_TEST(std::fabs(std::stod(row[8])) < 1e-9 * weight);
      BOOST_TEST(row[9] == "stick");
    }
  }
  const auto rows = read_contacts(dir / "contacts.csv");
  const auto at_start = std::count_if(rows.begin(), rows.end(),
                                      [](const auto& row) { return row[0] == "0"; });
  const pt::ptree vtp = read_xml(dir / "contacts_0000.vtp");
  BOOST_TEST(vtp.get<std::size_t>("VTKFile.PolyData.Piece.<xmlattr>.NumberOfPoints") ==
             static_cast<std::size_t>(at_start));
  BOOST_TEST(pvd_entries(dir / "contacts.pvd").size() == report.frames);
}

// A square pressed 0.1 mm into a frictionless floor and thrown upwards at 1 m/s: at t = 0 the
// contact is there (slide: frictionless), by the next recorded instant (5 steps, 0.5 mm of
// flight) it has opened, which is written once, with the last point and normal and no force.
BOOST_AUTO_TEST_CASE(contacts_csv_writes_an_opening_once) {
  const fs::path dir = fresh_dir("opening");
  const json document = json::parse(R"({"dimension": 2, "initial_equilibrium": false,
   "time": {"dt": 1e-4, "duration": 0.002}, "gravity": [0, 0],
   "materials": {"rock": {"density": 2500, "youngs_modulus": 1e10, "poisson_ratio": 0.25}},
   "contact": {"law": "potential", "kn": 1e8, "H": 1.0},
   "blocks": [{"id": "floor", "material": "rock", "vertices": [[-2,-1],[2,-1],[2,0],[-2,0]],
               "fixed": true},
              {"id": "box", "material": "rock", "rigid": true, "velocity": [0, 1, 0],
               "vertices": [[-0.5,-0.0001],[0.5,-0.0001],[0.5,0.9999],[-0.5,0.9999]]}],
   "output": {"every": 5}})");
  dyn::RunOptions options;
  options.out_dir = dir;
  dyn::run_scene(dyn::parse_scene(document, "opening.json"), options);
  const auto rows = read_contacts(dir / "contacts.csv");
  BOOST_TEST_REQUIRE(rows.size() == 2u);
  BOOST_TEST(rows[0][0] == "0");
  BOOST_TEST(rows[0][9] == "slide");
  BOOST_TEST(std::stod(rows[0][7]) > 0.0);
  BOOST_TEST(rows[1][0] == shortest(5e-4));
  BOOST_TEST(rows[1][9] == "open");
  BOOST_TEST((rows[1][1] == "floor" && rows[1][2] == "box"));
  BOOST_TEST((rows[1][3] == rows[0][3] && rows[1][4] == rows[0][4]));  // the last point
  BOOST_TEST((rows[1][7] == "0" && rows[1][8] == "0"));
}
