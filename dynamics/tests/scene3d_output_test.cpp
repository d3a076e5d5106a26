#define BOOST_TEST_MODULE scene3d_output
#include "rockcontact/dynamics/io/scene3d_output.hpp"

#include <array>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/scene3d.hpp"
#include "rockcontact/testing/box_json.hpp"
#include "rockcontact/testing/output_files.hpp"

namespace dyn = rockcontact::dynamics;
namespace fs = std::filesystem;
namespace pt = boost::property_tree;
using nlohmann::json;

namespace {

constexpr double g = 9.81;
constexpr double density = 2500.0;

fs::path fresh_dir(const std::string& name) {
  return rockcontact::testing::fresh_dir("scene3d_output_test", name);
}

using rockcontact::testing::pvd_entries;
using rockcontact::testing::read_csv;
using rockcontact::testing::read_text;
using rockcontact::testing::read_xml;

using rockcontact::testing::box_json;

json block(const std::string& id, std::array<double, 3> lo, std::array<double, 3> hi, bool fixed) {
  json b = box_json(lo, hi);
  b["id"] = id;
  b["material"] = "rock";
  b["rigid"] = true;
  if (fixed) b["fixed"] = true;
  return b;
}

// dt 1 ms, kn = kt = 1e9 N/m, friction 30°, `blocks` as given.
json scene_with(json blocks, double duration, std::size_t every) {
  json scene = {
      {"dimension", 3},
      {"time", {{"dt", 1e-3}, {"duration", duration}}},
      {"materials",
       {{"rock", {{"density", density}, {"youngs_modulus", 1e10}, {"poisson_ratio", 0.25}}}}},
      {"contact", {{"law", "penalty"}, {"kn", 1e9}, {"kt", 1e9}, {"friction_angle_deg", 30}}},
      {"output", {{"every", every}}}};
  scene["blocks"] = std::move(blocks);
  return scene;
}

}  // namespace

// A unit cube falling freely from rest: the constant-acceleration step integrates a constant
// force exactly, so every row of tracks.csv has z = z0 - g t² / 2 and vz = -g t up to the
// rounding of the sums over 100 steps (each of about 1e-16 relative of metres and m/s: 1e-12 is
// ten times what 100 steps of 10 m can accumulate). x, y and the rotation do not move at all.
BOOST_AUTO_TEST_CASE(free_fall_tracks_follow_the_parabola) {
  const fs::path dir = fresh_dir("free_fall");
  const dyn::Scene3d scene = dyn::parse_scene3d(
      scene_with({block("cube", {0, 0, 10}, {1, 1, 11}, false)}, 0.1, 10), "fall.json");
  dyn::Run3dOptions options;
  options.out_dir = dir;
  const dyn::Run3dReport report = dyn::run_scene3d(scene, options);
  BOOST_TEST(report.status == "completed");
  BOOST_TEST(report.steps == 100u);
  // At most 1 mm a step (0.98 m/s x 1 ms), below 0.001 x the cube's diagonal (1.73 mm): no cut.
  BOOST_TEST(report.step_cuts == 0u);
  const auto rows = read_csv(dir / "tracks.csv", "t,block,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz");
  BOOST_TEST_REQUIRE(rows.size() == 11u);  // t = 0, every 10 steps, the last at 0.1 s
  BOOST_TEST(std::stod(rows.front()[0]) == 0.0);
  BOOST_TEST(std::fabs(std::stod(rows.back()[0]) - 0.1) <= 1e-15);
  for (const auto& r : rows) {
    const double t = std::stod(r[0]);
    BOOST_TEST(r[1] == "cube");
    BOOST_TEST(std::stod(r[2]) == 0.5);
    BOOST_TEST(std::stod(r[3]) == 0.5);
    BOOST_TEST(std::fabs(std::stod(r[4]) - (10.5 - 0.5 * g * t * t)) <= 1e-12);
    for (std::size_t k : {5, 6, 7, 8, 9, 11, 12, 13}) BOOST_TEST(std::stod(r[k]) == 0.0);
    BOOST_TEST(std::fabs(std::stod(r[10]) + g * t) <= 1e-12);
  }
  // Kinetic plus gravitational energy stays zero: 1e-9 J of the 1.2 kJ exchanged is rounding
  // (1e-16 relative a step over 100 steps is 1e-11 J).
  const json summary = json::parse(read_text(dir / "summary.json"));
  BOOST_TEST(summary["status"] == "completed");
  BOOST_TEST(summary["steps"] == 100);
  BOOST_TEST(summary["frames"] == 11);
  BOOST_TEST(summary["energy"]["end"]["kinetic"].get<double>() > 1200.0);  // ½ m (g t)² = 1203 J
  BOOST_TEST(std::fabs(summary["energy"]["end"]["total"].get<double>()) <= 1e-9);
  BOOST_TEST(summary["open_close_iterations"]["max"] == 1);
  BOOST_TEST(summary["max_penetration"] == 0.0);
  BOOST_TEST(summary["tracked"] == json::array({"cube"}));
  // No contact at all: contacts.csv is its header alone.
  BOOST_TEST(
      read_csv(dir / "contacts.csv", "t,block_a,block_b,x,y,z,nx,ny,nz,fn,ft,state").empty());
}

// A unit cube resting on a fixed slab: four vertex-face constraints, one per bottom corner, at
// every output instant. At t = 0 no step has loaded them (fn = 0); once the bounce of the first
// steps has died out (dda3d_test: within 1 % of the static penetration after 0.2 s) they carry
// the weight: the forces sum to m g within 1 %.
BOOST_AUTO_TEST_CASE(a_resting_cube_has_four_contacts_carrying_its_weight) {
  const fs::path dir = fresh_dir("resting");
  const dyn::Scene3d scene =
      dyn::parse_scene3d(scene_with({block("slab", {-2, -2, -1}, {6, 2, 0}, true),
                                     block("cube", {-0.5, -0.5, 0}, {0.5, 0.5, 1}, false)},
                                    0.2, 50),
                         "resting.json");
  dyn::Run3dOptions options;
  options.out_dir = dir;
  const dyn::Run3dReport report = dyn::run_scene3d(scene, options);
  BOOST_TEST(report.status == "completed");
  const auto rows = read_csv(dir / "contacts.csv", "t,block_a,block_b,x,y,z,nx,ny,nz,fn,ft,state");
  std::map<std::string, std::vector<std::vector<std::string>>> by_time;
  for (const auto& r : rows) by_time[r[0]].push_back(r);
  const auto track_rows = read_csv(dir / "tracks.csv", "t,block,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz");
  BOOST_TEST(by_time.size() == track_rows.size());  // the same instants: t = 0, 0.05, ..., 0.2
  BOOST_TEST(track_rows.size() == 5u);
  for (const auto& track : track_rows) {
    BOOST_TEST_CONTEXT("t = " << track[0]) {
      const auto& instant = by_time[track[0]];
      BOOST_TEST(instant.size() == 4u);
      for (const auto& r : instant) {
        BOOST_TEST(r[1] == "slab");
        BOOST_TEST(r[2] == "cube");
        BOOST_TEST(std::stod(r[8]) == 1.0);  // nz: from the slab up towards the cube
        BOOST_TEST(std::fabs(std::fabs(std::stod(r[3])) - 0.5) <= 1e-9);  // a bottom corner
      }
    }
  }
  for (const auto& r : by_time["0"]) BOOST_TEST(std::stod(r[9]) == 0.0);
  const auto& last = by_time[track_rows.back()[0]];
  double fn = 0.0;
  for (const auto& r : last) {
    fn += std::stod(r[9]);
    BOOST_TEST(r[11] == "stick");
  }
  const double weight = density * 1.0 * g;
  BOOST_TEST_MESSAGE("fn sums to " << fn << " N, m g = " << weight << " N");
  BOOST_TEST(std::fabs(fn - weight) <= 0.01 * weight);
  // The largest penetration: at least the static one, m g / (4 kn).
  BOOST_TEST(report.max_penetration >= 0.99 * weight / 4e9);
}

// frames.pvd lists every frame, in order, at the instants of tracks.csv; each frame is VTK XML
// with one polygon per face (2 boxes, 12 faces); final.svg draws the faces turned towards the
// viewer, three of each box.
BOOST_AUTO_TEST_CASE(the_pvd_lists_every_frame) {
  const fs::path dir = fresh_dir("frames");
  const dyn::Scene3d scene =
      dyn::parse_scene3d(scene_with({block("slab", {-2, -2, -1}, {6, 2, 0}, true),
                                     block("cube", {-0.5, -0.5, 0}, {0.5, 0.5, 1}, false)},
                                    0.012, 5),
                         "frames.json");
  dyn::Run3dOptions options;
  options.out_dir = dir;
  const dyn::Run3dReport report = dyn::run_scene3d(scene, options);
  const auto entries = pvd_entries(dir / "frames.pvd");
  const auto tracks = read_csv(dir / "tracks.csv", "t,block,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz");
  BOOST_TEST_REQUIRE(entries.size() == 4u);  // steps 0, 5, 10 and the last, 12
  BOOST_TEST(report.frames == entries.size());
  BOOST_TEST_REQUIRE(tracks.size() == entries.size());
  std::size_t vtp_files = 0;
  for (const auto& entry : fs::directory_iterator(dir))
    vtp_files += entry.path().extension() == ".vtp";
  BOOST_TEST(vtp_files == entries.size());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    BOOST_TEST(entries[i].second == "frame_000" + std::to_string(i) + ".vtp");
    BOOST_TEST(entries[i].first == std::stod(tracks[i][0]));
    const pt::ptree frame = read_xml(dir / entries[i].second);
    BOOST_TEST(frame.get<std::size_t>("VTKFile.PolyData.Piece.<xmlattr>.NumberOfPolys") == 12u);
    BOOST_TEST(frame.get<std::size_t>("VTKFile.PolyData.Piece.<xmlattr>.NumberOfPoints") == 16u);
  }
  std::size_t polygons = 0;
  const pt::ptree svg = read_xml(dir / "final.svg");
  for (const auto& [name, node] : svg.get_child("svg")) polygons += name == "polygon";
  BOOST_TEST(polygons == 6u);
}

// A step that would have to shrink below min_dt_ratio * dt (a cube at 1000 m/s with
// max_displacement_ratio 1e-9) stops the run: status "stopped", the engine's message, and the
// files completed with the state at the stop.
BOOST_AUTO_TEST_CASE(a_stopped_run_still_writes_its_files) {
  const fs::path dir = fresh_dir("stopped");
  json document = scene_with({block("cube", {0, 0, 0}, {1, 1, 1}, false)}, 0.01, 5);
  document["blocks"][0]["velocity"] = {1000, 0, 0, 0, 0, 0};
  document["time"]["max_displacement_ratio"] = 1e-9;
  const dyn::Scene3d scene = dyn::parse_scene3d(document, "stopped.json");
  dyn::Run3dOptions options;
  options.out_dir = dir;
  const dyn::Run3dReport report = dyn::run_scene3d(scene, options);
  BOOST_TEST(report.status == "stopped");
  BOOST_TEST(report.steps == 0u);
  BOOST_TEST(report.error.find("max_displacement_ratio") != std::string::npos);
  const json summary = json::parse(read_text(dir / "summary.json"));
  BOOST_TEST(summary["status"] == "stopped");
  BOOST_TEST(summary["error"] == report.error);
  BOOST_TEST(summary["step_cuts"].get<std::size_t>() > 0u);
  BOOST_TEST(read_csv(dir / "tracks.csv", "t,block,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz").size() == 1u);
  BOOST_TEST(pvd_entries(dir / "frames.pvd").size() == 1u);
}
