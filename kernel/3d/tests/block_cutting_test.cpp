#define BOOST_TEST_MODULE kernel3d_block_cutting
#include "rockcontact/kernel/3d/block_cutting.hpp"

#include <boost/test/unit_test.hpp>

#include <gmpxx.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "rockcontact/kernel/3d/detail/halfspace_exact.hpp"
#include "rockcontact/kernel/3d/moments.hpp"
#include "rockcontact/testing/polyhedra3d.hpp"

// Joint-set cutting in 3D against what the geometry forces: axis-aligned sets cut a cube into
// known cubes; oblique sets conserve the region's volume exactly (the pieces' exact rational
// volumes sum to the region's); planes through a vertex, along an edge or on a face leave the
// region whole; a non-convex region's pieces of one cell that meet face to face form one block;
// bad sets are refused naming the field. Merging small blocks (min_block_volume): hand-built
// cases whose volumes and shared faces are computed by hand (a slab into the neighbour it
// shares the larger face with, on either side of the order; equal faces to the lower index; a
// merged fragment merging again; blocks without a neighbour kept; 0 changing nothing), the
// oblique sets merged under a bound with their volume kept, and the bad bound refused.

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

namespace {

// Dyadic slab thickness, so every coordinate and volume below is exact in double.
constexpr double thin = 1.0 / 128;

// Horizontal joints z = offset + 10 k (n = (0, 0, 1), exact), and vertical ones x = offset + 10 k
// (dip 90 towards the East: n = (1, 0, 0), exact).
JointSet3 horizontal_at(double offset) { return {0, 0, 10, offset}; }
JointSet3 vertical_at(double offset) { return {90, 90, 10, offset}; }

rk::CutOptions3 merge_below(double min_block_volume) { return rk::CutOptions3{min_block_volume}; }

std::vector<std::size_t> parts_per_block(const std::vector<rk::CutBlock3>& blocks) {
  std::vector<std::size_t> counts;
  for (const auto& block : blocks) counts.push_back(block.parts.size());
  return counts;
}

// The smallest x of a part's vertices.
double min_x(const ConvexPolyhedron& p) {
  double x = INFINITY;
  for (const Point3& v : p.vertices()) x = std::min(x, v.x);
  return x;
}

}  // namespace

// A slab 1/128 m thick (4 x 1 m, 1/32 m³) between a 1 m cube and a 4 x 1 x (1 - 1/128) m block,
// in a region given as two boxes: the cube under one end of a long box, the joints z = 1 (on
// their seam) and z = 1 + 1/128 making the slab the long box's bottom. The slab shares its whole
// bottom with the cube's top only over the cube's 1 m² (the two face polygons overlap in part,
// so the clipping decides), and its 4 m² top with the block above. With min_block_volume 0.1 it
// merges into the block above, the third, although the cube comes first: the merged block (the
// block above's part first, then the slab) is the second, of 4 m³; the cube keeps the first
// place. Mirrored (the long box below, the cube on top, joints at 1 - 1/128 and 1), the larger
// face is the first block's, and the slab merges into it. The volumes are exact in double; their
// computation (a sum of tetrahedra, divided by 6) rounds them by a few ulps: 1e-14.
BOOST_AUTO_TEST_CASE(a_thin_slab_merges_into_the_neighbour_it_shares_more_face_with) {
  const auto tolerance = boost::test_tools::tolerance(1e-14);
  const std::vector<ConvexPolyhedron> cube_below{box("q", {0, 0, 0}, {1, 1, 1}), box("p", {0, 0, 1}, {4, 1, 2})};
  const std::vector<JointSet3> above_seam{horizontal_at(1), horizontal_at(1 + thin)};
  const auto unmerged = rk::cut_region<rk::Filtered>(cube_below, above_seam, "r");
  BOOST_TEST_REQUIRE(unmerged.size() == 3u);
  BOOST_TEST(rounded_volume(unmerged[0].parts[0]) == 1.0, tolerance);
  BOOST_TEST(rounded_volume(unmerged[1].parts[0]) == 4 * thin, tolerance);
  BOOST_TEST(rounded_volume(unmerged[2].parts[0]) == 4 * (1 - thin), tolerance);

  const auto merged = rk::cut_region<rk::Filtered>(cube_below, above_seam, "r", merge_below(0.1));
  BOOST_TEST((parts_per_block(merged) == std::vector<std::size_t>{1, 2}));
  BOOST_TEST(rounded_volume(merged[0].parts[0]) == 1.0, tolerance);
  BOOST_TEST(rounded_volume(merged[1].parts[0]) == 4 * (1 - thin), tolerance);
  BOOST_TEST(rounded_volume(merged[1].parts[1]) == 4 * thin, tolerance);
  BOOST_TEST(merged[0].parts[0].name() == "r_1");
  BOOST_TEST(merged[1].parts[0].name() == "r_2.1");
  BOOST_TEST(merged[1].parts[1].name() == "r_2.2");

  const std::vector<ConvexPolyhedron> cube_above{box("p", {0, 0, 0}, {4, 1, 1}), box("q", {0, 0, 1}, {1, 1, 2})};
  const std::vector<JointSet3> below_seam{horizontal_at(1 - thin), horizontal_at(1)};
  const auto mirrored = rk::cut_region<rk::Filtered>(cube_above, below_seam, "r", merge_below(0.1));
  BOOST_TEST((parts_per_block(mirrored) == std::vector<std::size_t>{2, 1}));
  BOOST_TEST(rounded_volume(mirrored[0].parts[0]) == 4 * (1 - thin), tolerance);
  BOOST_TEST(rounded_volume(mirrored[0].parts[1]) == 4 * thin, tolerance);
  BOOST_TEST(rounded_volume(mirrored[1].parts[0]) == 1.0, tolerance);
}

// Equal faces, and a merged fragment merging again, in the box [0, 4] x [0, 1] x [0, 1] cut by
// vertical joints; every shared face is a 1 m² square, computed exactly.
//   - x = 2 and 2 + 1/128: the slab (1/128 m³) shares 1 m² with [0, 2] (2 m³, first) and with
//     [2 + 1/128, 4] (third): the tie goes to the first, which becomes [0, 2 + 1/128] in two
//     parts; the third block is the second now.
//   - x = 1/128 and 2/128: two slabs of 1/128 m³ before [2/128, 4]. With min_block_volume 0.02,
//     the first slab goes first (equal volumes: the lower index) into its only neighbour, the
//     second slab; their union (2/128 = 0.015625 m³) is still below 0.02 and merges into the big
//     block. One block of three parts: the big block's, then the second slab (the first merge's
//     receiver), then the first slab; had the second slab gone first, it would have merged into
//     the first (equal faces, lower index) and the last two parts would be swapped.
BOOST_AUTO_TEST_CASE(equal_faces_go_to_the_lower_index_and_merged_fragments_merge_again) {
  const auto tolerance = boost::test_tools::tolerance(1e-14);
  const ConvexPolyhedron bar = box("bar", {0, 0, 0}, {4, 1, 1});
  const std::vector<JointSet3> slab_in_the_middle{vertical_at(2), vertical_at(2 + thin)};
  const auto tie = rk::cut_region<rk::Filtered>(std::span(&bar, 1), slab_in_the_middle, "t", merge_below(0.1));
  BOOST_TEST((parts_per_block(tie) == std::vector<std::size_t>{2, 1}));
  BOOST_TEST(rounded_volume(tie[0].parts[0]) == 2.0, tolerance);
  BOOST_TEST(rounded_volume(tie[0].parts[1]) == thin, tolerance);
  BOOST_TEST(min_x(tie[0].parts[1]) == 2.0);
  BOOST_TEST(rounded_volume(tie[1].parts[0]) == 2 - thin, tolerance);

  const std::vector<JointSet3> two_slabs{vertical_at(thin), vertical_at(2 * thin)};
  const auto unmerged = rk::cut_region<rk::Filtered>(std::span(&bar, 1), two_slabs, "t");
  BOOST_TEST_REQUIRE(unmerged.size() == 3u);
  // The tie of volumes is exact: the two slabs are translates by a dyadic step.
  BOOST_TEST_REQUIRE(rk::moments(unmerged[0].parts[0]).volume == rk::moments(unmerged[1].parts[0]).volume);
  const auto chain = rk::cut_region<rk::Filtered>(std::span(&bar, 1), two_slabs, "t", merge_below(0.02));
  BOOST_TEST((parts_per_block(chain) == std::vector<std::size_t>{3}));
  BOOST_TEST(min_x(chain[0].parts[0]) == 2 * thin);
  BOOST_TEST(min_x(chain[0].parts[1]) == thin);
  BOOST_TEST(min_x(chain[0].parts[2]) == 0.0);
  double sum = 0;
  for (const auto& part : chain[0].parts) sum += rounded_volume(part);
  BOOST_TEST(sum == 4.0, tolerance);
  BOOST_TEST(chain[0].parts[2].name() == "t_1.3");
}

// Blocks without a face-sharing neighbour stay, however small: a region cut by nothing (one
// block), and two unit cubes meeting only along an edge (x = y = 1): their faces on x = 1 and on
// y = 1 are coplanar and opposite but meet in a segment, of area 0. A bound of 0 merges nothing:
// the blocks are those of the default options, part for part.
BOOST_AUTO_TEST_CASE(blocks_without_a_neighbour_stay_and_zero_merges_nothing) {
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {1, 1, 1});
  const auto lone = rk::cut_region<rk::Filtered>(std::span(&cube, 1), {}, "c", merge_below(100));
  BOOST_TEST((parts_per_block(lone) == std::vector<std::size_t>{1}));
  const std::vector<ConvexPolyhedron> edge_to_edge{cube, box("other", {1, 1, 0}, {2, 2, 1})};
  const auto apart = rk::cut_region<rk::Filtered>(edge_to_edge, {}, "c", merge_below(100));
  BOOST_TEST((parts_per_block(apart) == std::vector<std::size_t>{1, 1}));

  const ConvexPolyhedron bar = box("bar", {0, 0, 0}, {4, 1, 1});
  const std::vector<JointSet3> two_slabs{vertical_at(thin), vertical_at(2 * thin)};
  const auto plain = rk::cut_region<rk::Filtered>(std::span(&bar, 1), two_slabs, "t");
  const auto zero = rk::cut_region<rk::Filtered>(std::span(&bar, 1), two_slabs, "t", merge_below(0));
  BOOST_TEST_REQUIRE(zero.size() == plain.size());
  for (std::size_t b = 0; b < plain.size(); ++b) {
    BOOST_TEST_REQUIRE(zero[b].parts.size() == 1u);
    BOOST_TEST(zero[b].parts[0].name() == plain[b].parts[0].name());
    BOOST_TEST((std::vector<Point3>(zero[b].parts[0].vertices().begin(), zero[b].parts[0].vertices().end()) ==
                std::vector<Point3>(plain[b].parts[0].vertices().begin(), plain[b].parts[0].vertices().end())));
  }
}

// The oblique sets of oblique_sets_conserve_the_volume_exactly: their faces are planar only to
// rounding, and a neighbour's shared face is found only within shared_face_tolerance. Of their 88
// blocks (a mean of 11.4 m³; the smallest a sliver of 4e-8 m³), 41 are below 2 m³. Merged below
// 2 m³, every block reaches it (all have neighbours), no part is lost or made (the parts are the
// unmerged blocks), and the volume is the unmerged blocks' to rounding (1e-14, as there).
BOOST_AUTO_TEST_CASE(oblique_blocks_merge_with_their_volume_kept) {
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {10, 10, 10});
  const std::vector<JointSet3> sets{{50, 110, 3, 0.3}, {55, 240, 4, -1.1}, {20, 10, 2.5, 0.7}};
  const auto unmerged = rk::cut_region<rk::Filtered>(std::span(&cube, 1), sets, "rock");
  std::size_t fragments = 0;
  for (const auto& block : unmerged) fragments += rounded_volume(block.parts[0]) < 2.0 ? 1 : 0;
  BOOST_TEST(unmerged.size() == 88u);
  BOOST_TEST(fragments == 41u);
  const auto merged = rk::cut_region<rk::Filtered>(std::span(&cube, 1), sets, "rock", merge_below(2.0));
  BOOST_TEST(merged.size() < unmerged.size());
  std::size_t parts = 0;
  double sum = 0;
  for (const auto& block : merged) {
    double volume = 0;
    for (const auto& part : block.parts) volume += rounded_volume(part);
    BOOST_TEST(volume >= 2.0);
    parts += block.parts.size();
    sum += volume;
  }
  BOOST_TEST(parts == unmerged.size());
  BOOST_TEST(sum == 1000.0, boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(a_bad_min_block_volume_is_named) {
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {1, 1, 1});
  for (const double bound : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    BOOST_TEST_INFO("min_block_volume " << bound);
    try {
      static_cast<void>(rk::cut_region<rk::Filtered>(std::span(&cube, 1), {}, "c", merge_below(bound)));
      BOOST_ERROR("accepted a bad min_block_volume");
    } catch (const rk::InvalidCut& e) {
      BOOST_TEST(e.subject() == "min_block_volume");
      BOOST_TEST(std::string(e.what()).find("a finite number of m³ >= 0, got") != std::string::npos);
    }
    BOOST_CHECK_THROW(rk::merge_small_blocks({}, merge_below(bound), "c"), rk::InvalidCut);
  }
}
