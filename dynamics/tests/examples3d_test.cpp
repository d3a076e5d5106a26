#define BOOST_TEST_MODULE examples3d
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rockcontact/dynamics/io/cut3d.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"
#include "rockcontact/kernel/3d/block_cutting.hpp"
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"
#include "rockcontact/testing/json_file.hpp"

// The 3D example scenes of seed 001 (examples/scenes3d): their blocks are valid convex polyhedra,
// are exactly what their cut documents make, and fill their regions (the volumes sum to the
// region's: 1000 m³ for the 10 m cube, 40 x 30 x 25 = 30000 m³ for the slope block, within the
// rounding of the cut blocks' vertices, 1e-12 relative); the block system has the 18 blocks of
// §6.3, and the wedge rests on the two joints of §6.1 (its faces' normals are the joints').

namespace dyn = rockcontact::dynamics;
namespace rk = rockcontact::kernel;
using nlohmann::json;

namespace {

const std::string dir = std::string(ROCKCONTACT_EXAMPLES_DIR) + "/scenes3d/";

rk::ConvexPolyhedron solid(const std::string& name, const json& j) {
  std::vector<rk::Point3> vertices;
  for (const auto& p : j.at("vertices")) vertices.push_back({p[0].get<double>(), p[1].get<double>(), p[2].get<double>()});
  std::vector<rk::ConvexPolyhedron::Face> faces;
  for (const auto& f : j.at("faces")) faces.push_back(f.get<std::vector<std::uint32_t>>());
  return rk::ConvexPolyhedron::make(name, std::move(vertices), std::move(faces));
}

double volume(const rk::ConvexPolyhedron& p) { return rk::HalfspacePolyhedron(p).volume<rk::Filtered>(); }

// The scene's blocks (each part of a non-convex block separately), without the fixed ones when
// `free_only`.
std::vector<rk::ConvexPolyhedron> solids(const json& scene, const std::vector<std::string>& skip) {
  std::vector<rk::ConvexPolyhedron> out;
  for (const auto& b : scene.at("blocks")) {
    const std::string id = b.at("id");
    if (std::find(skip.begin(), skip.end(), id) != skip.end()) continue;
    if (b.contains("parts")) {
      for (const auto& part : b.at("parts")) out.push_back(solid(id, part));
    } else {
      out.push_back(solid(id, b));
    }
  }
  return out;
}

// The scene's blocks other than `skip` are the cut document's, vertex for vertex and face for face.
void expect_cut_blocks(const json& scene, const std::string& cut_file, const std::vector<std::string>& skip) {
  const dyn::Cut3Input input = dyn::parse_cut3(rockcontact::testing::read_json(dir + cut_file), cut_file);
  const json cut = dyn::cut3d_blocks(input, dyn::cut3d(input));
  std::vector<json> ours;
  for (const auto& b : cut.at("blocks")) {
    if (b.contains("parts")) {
      for (const auto& part : b.at("parts")) ours.push_back(part);
    } else {
      ours.push_back({{"vertices", b.at("vertices")}, {"faces", b.at("faces")}});
    }
  }
  std::vector<json> theirs;
  for (const auto& b : scene.at("blocks")) {
    if (std::find(skip.begin(), skip.end(), b.at("id").get<std::string>()) != skip.end()) continue;
    if (b.contains("parts")) {
      for (const auto& part : b.at("parts")) theirs.push_back(part);
    } else {
      theirs.push_back({{"vertices", b.at("vertices")}, {"faces", b.at("faces")}});
    }
  }
  BOOST_TEST_REQUIRE(ours.size() == theirs.size());
  for (std::size_t i = 0; i < ours.size(); ++i) BOOST_TEST((ours[i] == theirs[i]), cut_file << " block " << i);
}

}  // namespace

BOOST_AUTO_TEST_CASE(block_system_has_18_blocks_filling_the_cube) {
  const json scene = rockcontact::testing::read_json(dir + "block_system.json");
  const auto blocks = solids(scene, {"ground"});
  BOOST_TEST(blocks.size() == 18u);
  double sum = 0;
  for (const auto& b : blocks) sum += volume(b);
  BOOST_TEST(sum == 1000.0, boost::test_tools::tolerance(1e-12));
  expect_cut_blocks(scene, "block_system_cut.json", {"ground"});
}

// The jointed mass (docs/validation.md runs it): its region cut into 147 blocks, the two slivers
// among them merged into neighbours by the default region.min_block_volume ("auto";
// dynamics_scene3d_test derives the count), so 145 movable blocks that fill the 6 x 6 x 4 m box
// exactly (the cut's exact pieces rounded once: 1e-12 relative), on the fixed slab, with the
// penalties left to auto (the defaults the run checks).
BOOST_AUTO_TEST_CASE(jointed_mass_cuts_into_145_blocks_filling_its_box) {
  const dyn::Scene3d scene = dyn::read_scene3d_file(dir + "jointed_mass.json");
  BOOST_TEST(scene.generated_count == 145u);
  BOOST_TEST(scene.merged_fragments == 2u);
  BOOST_TEST(scene.blocks.size() == 146u);
  double sum = 0;
  for (std::size_t i = scene.generated_first; i < scene.generated_first + scene.generated_count; ++i) {
    BOOST_TEST(!scene.blocks[i].fixed);
    for (const auto& part : scene.blocks[i].parts) sum += volume(part);
  }
  BOOST_TEST(sum == 144.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(scene.kn_auto);
}

BOOST_AUTO_TEST_CASE(wedge_rests_on_the_two_joints) {
  const json scene = rockcontact::testing::read_json(dir + "wedge.json");
  const auto pieces = solids(scene, {});
  BOOST_TEST(pieces.size() == 4u);  // the base's three parts and the wedge
  double sum = 0;
  for (const auto& b : pieces) sum += volume(b);
  BOOST_TEST(sum == 30000.0, boost::test_tools::tolerance(1e-12));
  expect_cut_blocks(scene, "wedge_cut.json", {});
  // The wedge is a tetrahedron; besides its top (z = 0) and free face (y = 0) its faces lie on
  // the joints, with outward normals opposite to the joints' upward normals (it rests on them).
  const rk::ConvexPolyhedron& wedge = pieces.back();
  BOOST_TEST(wedge.name() == "wedge");
  BOOST_TEST(wedge.size() == 4u);
  const json cut = rockcontact::testing::read_json(dir + "wedge_cut.json");
  for (const auto& set : cut.at("joint_sets")) {
    const rk::Point3 n = rk::joint_normal({set.at("dip_deg"), set.at("dip_direction_deg"), set.at("spacing"), set.at("offset")});
    bool found = false;
    for (const auto& face : wedge.faces()) {
      const rk::Point3 &a = wedge[face[0]], &b = wedge[face[1]], &c = wedge[face[2]];
      const rk::Point3 u{b.x - a.x, b.y - a.y, b.z - a.z}, v{c.x - a.x, c.y - a.y, c.z - a.z};
      rk::Point3 m{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
      const double length = std::hypot(m.x, m.y, m.z);
      // 1e-9: the face's normal from rounded vertices 10 m apart, off by ulps of 10 m.
      found |= std::abs(m.x / length + n.x) < 1e-9 && std::abs(m.y / length + n.y) < 1e-9 &&
               std::abs(m.z / length + n.z) < 1e-9;
    }
    BOOST_TEST(found, "a wedge face on the joint dipping " << set.at("dip_deg") << " towards " << set.at("dip_direction_deg"));
  }
}

BOOST_AUTO_TEST_CASE(cut_documents_refuse_bad_joint_sets) {
  json document = rockcontact::testing::read_json(dir + "wedge_cut.json");
  document["joint_sets"][1]["dip_deg"] = 95;
  BOOST_CHECK_THROW(dyn::parse_cut3(document, "case.json"), dyn::InputError);
  try {
    dyn::parse_cut3(document, "case.json");
  } catch (const dyn::InputError& e) {
    BOOST_TEST(e.path() == "joint_sets[1].dip_deg");
  }
  document = rockcontact::testing::read_json(dir + "wedge_cut.json");
  document["joint_sets"][0]["spacing"] = 0;
  try {
    dyn::parse_cut3(document, "case.json");
    BOOST_ERROR("accepted a zero spacing");
  } catch (const dyn::InputError& e) {
    BOOST_TEST(e.path() == "joint_sets[0].spacing");
  }
  document = rockcontact::testing::read_json(dir + "wedge_cut.json");
  document["region"]["box"]["max"][2] = -30;
  try {
    dyn::parse_cut3(document, "case.json");
    BOOST_ERROR("accepted an empty box");
  } catch (const dyn::InputError& e) {
    BOOST_TEST(e.path() == "region.box.max");
  }
}
