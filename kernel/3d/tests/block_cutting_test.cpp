#define BOOST_TEST_MODULE kernel3d_block_cutting
#include "rockcontact/kernel/3d/block_cutting.hpp"

#include <boost/test/unit_test.hpp>

#include <gmpxx.h>

#include <cmath>
#include <string>
#include <vector>

#include "rockcontact/kernel/3d/detail/halfspace_exact.hpp"
#include "rockcontact/testing/polyhedra3d.hpp"

// Joint-set cutting in 3D against what the geometry forces: axis-aligned sets cut a cube into
// known cubes; oblique sets conserve the region's volume exactly (the pieces' exact rational
// volumes sum to the region's); planes through a vertex, along an edge or on a face leave the
// region whole; a non-convex region's pieces of one cell that meet face to face form one block;
// bad sets are refused naming the field.

namespace rk = rockcontact::kernel;
using rk::ConvexPolyhedron;
using rockcontact::testing::box;
using rk::JointSet3;
using rk::Point3;

namespace {

mpq_class exact_volume(const rk::HalfspacePolyhedron& p) {
  mpq_class v(rk::detail::exact_volume_string(p));
  v.canonicalize();
  return v;
}

// The exact total volume of the pieces.
mpq_class total_volume(const std::vector<rk::CutPiece3>& pieces) {
  mpq_class sum = 0;
  for (const auto& piece : pieces) sum += exact_volume(piece.piece);
  return sum;
}

double rounded_volume(const ConvexPolyhedron& p) { return rk::HalfspacePolyhedron(p).volume<rk::Filtered>(); }

void expect_refused(const std::vector<JointSet3>& sets, const std::string& subject, const std::string& words) {
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {10, 10, 10});
  try {
    static_cast<void>(rk::cut_by_joint_sets<rk::Filtered>(std::span(&cube, 1), sets));
    BOOST_FAIL("accepted bad joint sets (expected " << subject << ")");
  } catch (const rk::InvalidCut& e) {
    BOOST_TEST(e.subject() == subject);
    BOOST_TEST_INFO(e.what());
    BOOST_TEST(std::string(e.what()).find(words) != std::string::npos);
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(joint_normals_follow_dip_and_dip_direction) {
  // Dip direction clockwise from North (+y): 90 is East. A plane dipping 30 degrees towards the
  // East has its upward normal tilted towards the East: (sin 30, 0, cos 30).
  const Point3 east = rk::joint_normal({30, 90, 1, 0});
  BOOST_TEST(east.x == 0.5, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(east.y == 0.0);
  BOOST_TEST(east.z == std::sqrt(3.0) / 2, boost::test_tools::tolerance(1e-15));
  // Multiples of 90 degrees are exact: horizontal and vertical joints are axis-aligned.
  BOOST_TEST((rk::joint_normal({0, 0, 1, 0}) == Point3{0, 0, 1}));
  BOOST_TEST((rk::joint_normal({90, 0, 1, 0}) == Point3{0, 1, 0}));
  BOOST_TEST((rk::joint_normal({90, 270, 1, 0}) == Point3{-1, 0, 0}));
}

BOOST_AUTO_TEST_CASE(axis_aligned_sets_cut_a_cube_into_cubes) {
  // Planes z = 5k, y = 5k, x = 5k through a 10 m cube: the planes at 0 and 10 only touch it, the
  // ones at 5 cut it into eight 5 m cubes of 125 m³.
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {10, 10, 10});
  const std::vector<JointSet3> sets{{0, 0, 5, 0}, {90, 0, 5, 0}, {90, 90, 5, 0}};
  const auto pieces = rk::cut_by_joint_sets<rk::Exact>(std::span(&cube, 1), sets);
  BOOST_TEST(pieces.size() == 8u);
  for (const auto& piece : pieces) BOOST_TEST(exact_volume(piece.piece) == mpq_class(125));
  const auto blocks = rk::cut_region<rk::Filtered>(std::span(&cube, 1), sets, "rock");
  BOOST_TEST(blocks.size() == 8u);
  for (const auto& block : blocks) {
    BOOST_TEST(block.parts.size() == 1u);
    BOOST_TEST(block.parts[0].size() == 8u);
    BOOST_TEST(block.parts[0].faces().size() == 6u);
    BOOST_TEST(rounded_volume(block.parts[0]) == 125.0);
  }
  BOOST_TEST(blocks.front().parts[0].name() == "rock_1");
}

BOOST_AUTO_TEST_CASE(oblique_sets_conserve_the_volume_exactly) {
  // Three oblique sets through a 10 m cube (seed 001 §6.1's two joints and a gentle third):
  // the pieces are bounded by exactly the same planes, so their exact volumes sum to 1000 m³
  // exactly, under Filtered and Exact alike (the cut's decisions are the same exact signs).
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {10, 10, 10});
  const std::vector<JointSet3> sets{{50, 110, 3, 0.3}, {55, 240, 4, -1.1}, {20, 10, 2.5, 0.7}};
  for (const bool exact : {false, true}) {
    const auto pieces = exact ? rk::cut_by_joint_sets<rk::Exact>(std::span(&cube, 1), sets)
                              : rk::cut_by_joint_sets<rk::Filtered>(std::span(&cube, 1), sets);
    BOOST_TEST_INFO((exact ? "Exact" : "Filtered"));
    BOOST_TEST(total_volume(pieces) == mpq_class(1000));
    BOOST_TEST(pieces.size() > 20u);
  }
  // The rounded blocks keep it to rounding: each vertex moves by at most half an ulp of 10 m
  // (8.9e-16 m), changing a block's volume by at most its area times that; the blocks' total
  // area is below 6 * 100 m² plus twice each set's planes' sections (< 20 * 150 m²): a
  // relative 1e-14 bounds the total with a wide margin.
  const auto blocks = rk::cut_region<rk::Filtered>(std::span(&cube, 1), sets, "rock");
  double sum = 0;
  for (const auto& block : blocks) sum += rounded_volume(block.parts[0]);
  BOOST_TEST(sum == 1000.0, boost::test_tools::tolerance(1e-14));
}

// The cut rounds each vertex once, to the nearest double of its exact point, so the pieces that
// share a vertex give it the same coordinates: blocks meet exactly where they touch. Checked on
// three oblique sets: any two vertices of different blocks within 1e-9 m of each other (the
// same exact point, as the cut's vertices are otherwise at least centimetres apart) are equal,
// under Filtered as under Exact.
BOOST_AUTO_TEST_CASE(blocks_share_their_vertices_exactly) {
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {10, 10, 10});
  const std::vector<JointSet3> sets{{50, 110, 3, 0.3}, {55, 240, 4, -1.1}, {20, 10, 2.5, 0.7}};
  for (const bool exact : {false, true}) {
    const auto blocks = exact ? rk::cut_region<rk::Exact>(std::span(&cube, 1), sets, "rock")
                              : rk::cut_region<rk::Filtered>(std::span(&cube, 1), sets, "rock");
    BOOST_TEST_INFO((exact ? "Exact" : "Filtered"));
    std::size_t shared = 0, differ = 0;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      for (std::size_t j = i + 1; j < blocks.size(); ++j) {
        for (const Point3& p : blocks[i].parts[0].vertices()) {
          for (const Point3& q : blocks[j].parts[0].vertices()) {
            if (std::hypot(p.x - q.x, p.y - q.y, p.z - q.z) > 1e-9) continue;
            ++shared;
            if (!(p.x == q.x && p.y == q.y && p.z == q.z)) ++differ;
          }
        }
      }
    }
    BOOST_TEST(shared > 100u);
    BOOST_TEST(differ == 0u);
  }
}

BOOST_AUTO_TEST_CASE(planes_through_a_vertex_an_edge_or_a_face_leave_the_region_whole) {
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {10, 10, 10});
  // z = 0 and z = 10 (faces), x + z = 0 (the edge x = z = 0: dip 45 towards the East, n =
  // (sin 45, 0, cos 45), offset 0), and x + y + z = 0 through the vertex (0, 0, 0) (spacing
  // larger than the cube so no other plane of the set meets it).
  for (const JointSet3& set : {JointSet3{0, 0, 10, 0}, JointSet3{45, 90, 100, 0}, JointSet3{54.735610317245346, 45, 100, 0}}) {
    const auto pieces = rk::cut_by_joint_sets<rk::Exact>(std::span(&cube, 1), std::vector{set});
    BOOST_TEST_INFO("dip " << set.dip_deg << " towards " << set.dip_direction_deg);
    BOOST_TEST(pieces.size() == 1u);
    BOOST_TEST(total_volume(pieces) == mpq_class(1000));
  }
}

BOOST_AUTO_TEST_CASE(pieces_of_one_cell_across_parts_form_one_block) {
  // An L-shaped region as two boxes sharing the face y = 1 over x in [0, 1]; the horizontal
  // plane z = 0.5 halves both. Below it, the two lower halves meet face to face across the seam:
  // one block of two parts; likewise above: 2 blocks.
  const std::vector<ConvexPolyhedron> region{box("a", {0, 0, 0}, {2, 1, 1}), box("b", {0, 1, 0}, {1, 2, 1})};
  const auto blocks = rk::cut_region<rk::Filtered>(region, std::vector<JointSet3>{{0, 0, 0.5, 0}}, "l");
  BOOST_TEST(blocks.size() == 2u);
  for (const auto& block : blocks) {
    BOOST_TEST(block.parts.size() == 2u);
    BOOST_TEST(rounded_volume(block.parts[0]) + rounded_volume(block.parts[1]) == 1.5);
  }
  BOOST_TEST(blocks[0].parts[1].name() == "l_1.2");
}

BOOST_AUTO_TEST_CASE(bad_joint_sets_are_named) {
  expect_refused({{95, 0, 1, 0}}, "joint_sets[0].dip_deg", "[0, 90]");
  expect_refused({{10, 0, 1, 0}, {10, 0, 0, 0}}, "joint_sets[1].spacing", "> 0");
  expect_refused({{10, 360, 1, 0}}, "joint_sets[0].dip_direction_deg", "[0, 360)");
  expect_refused({{10, 0, 1, NAN}}, "joint_sets[0].offset", "finite");
  expect_refused({{10, 0, 1e-6, 0}}, "joint_sets[0]", "too small");
}
