#define BOOST_TEST_MODULE kernel3d_contact_constraints
#include "rockcontact/kernel/3d/contact_constraints.hpp"

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/testing/contact3d.hpp"
#include "rockcontact/testing/polyhedra3d.hpp"

// Contact constraints (seed 001 §2) against closed forms: blocks with dyadic coordinates placed
// so that each contact's type, features, points, normal and gap are known exactly; and against
// the independent contact3d reference data (exact statuses, distances, penetration depths and
// contact-set corners of 132 adversarial pairs). Combinatorial results (how many constraints,
// of which type, which features, zero gaps) are exact under Filtered, Exact and Checked and are
// asserted with ==; constructed numbers carry the tolerances explained where they are used.

namespace rk = rockcontact::kernel;
using rk::ConstraintType;
using rk::ContactConstraint;
using rk::ConvexPolyhedron;
using rockcontact::testing::box;
using rk::Feature;
using rk::Point3;

namespace {

Point3 operator-(const Point3& a, const Point3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Point3 operator+(const Point3& a, const Point3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
double dot(const Point3& a, const Point3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }

constexpr std::uint32_t box_top = 1, box_right = 3, box_back = 4;  // faces z = hi, x = hi, y = hi

// The prism swept by the convex polygon `base` along h; the base loop is reversed if needed so
// that it runs counter-clockwise seen from outside (its normal opposite to h).
ConvexPolyhedron prism(const std::string& name, std::vector<Point3> base, Point3 h) {
  if (dot(cross(base[1] - base[0], base[2] - base[0]), h) > 0) std::reverse(base.begin(), base.end());
  const auto n = static_cast<std::uint32_t>(base.size());
  std::vector<Point3> vertices = base;
  for (const Point3& p : base) vertices.push_back(p + h);
  std::vector<ConvexPolyhedron::Face> faces(2);
  for (std::uint32_t i = 0; i < n; ++i) {
    faces[0].push_back(i);
    faces[1].push_back(2 * n - 1 - i);
    const std::uint32_t j = (i + 1) % n;
    faces.push_back({j, i, i + n, j + n});
  }
  return ConvexPolyhedron::make(name, std::move(vertices), std::move(faces));
}

ConvexPolyhedron tetrahedron(const std::string& name, Point3 a, Point3 b, Point3 c, Point3 d) {
  if (dot(cross(b - a, c - a), d - a) > 0) std::swap(b, c);
  return ConvexPolyhedron::make(name, {a, b, c, d}, {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
}

std::uint32_t vertex_index(const ConvexPolyhedron& p, const Point3& v) {
  const auto it = std::find(p.vertices().begin(), p.vertices().end(), v);
  BOOST_TEST_REQUIRE((it != p.vertices().end()));
  return static_cast<std::uint32_t>(it - p.vertices().begin());
}

std::uint32_t edge_index(const ConvexPolyhedron& p, const Point3& a, const Point3& b) {
  const std::uint32_t i = vertex_index(p, a), j = vertex_index(p, b);
  const ConvexPolyhedron::Edge e{std::min(i, j), std::max(i, j)};
  const auto it = std::find(p.edges().begin(), p.edges().end(), e);
  BOOST_TEST_REQUIRE((it != p.edges().end()));
  return static_cast<std::uint32_t>(it - p.edges().begin());
}

// The normal is unit and (tangent1, tangent2, normal) orthonormal and right-handed: each within
// 4 ulps of 1 (normalising rounds each component by half an ulp, the products add a few more).
void check_frame(const ContactConstraint& c) {
  constexpr double eps = 4 * 0x1p-52;
  BOOST_TEST(std::fabs(norm(c.normal) - 1) <= eps);
  BOOST_TEST(std::fabs(norm(c.tangent1) - 1) <= eps);
  BOOST_TEST(std::fabs(norm(c.tangent2) - 1) <= eps);
  BOOST_TEST(std::fabs(dot(c.tangent1, c.normal)) <= eps);
  BOOST_TEST(std::fabs(dot(c.tangent2, c.normal)) <= eps);
  BOOST_TEST(norm(cross(c.tangent1, c.tangent2) - c.normal) <= eps);
}

bool has_point(const std::vector<ContactConstraint>& cs, const Point3& p, double tolerance) {
  return std::any_of(cs.begin(), cs.end(),
                     [&](const ContactConstraint& c) { return norm(c.point_tp - p) <= tolerance; });
}

template <class Test>
void for_staged(Test test) {
  test(rk::Filtered{});
  test(rk::Exact{});
  test(rk::Checked{});
}

}  // namespace

// A unit cube resting inside the top face of a 4 x 4 x 1 box: the four bottom corners of the
// cube touch the face (vertex-face, the face's normal, gap exactly 0), and nothing else: the
// cube's bottom edges cross no edge of the face. Exchanging the blocks flips the normal. Also
// 2^20 m from the origin, where the contact points must still be the corners exactly (they are
// input vertices, and touching puts point_cp on point_tp).
BOOST_AUTO_TEST_CASE(cube_resting_on_a_face) {
  for (const Point3 o : {Point3{0, 0, 0}, Point3{0x1p20 + 0.25, -0x1p20 + 0.5, 0x1p20}}) {
    const ConvexPolyhedron base = box("base", o + Point3{0, 0, -1}, o + Point3{4, 4, 0});
    const ConvexPolyhedron cube = box("cube", o + Point3{1, 1, 0}, o + Point3{2, 2, 1});
    for_staged([&](auto policy) {
      using P = decltype(policy);
      BOOST_TEST_CONTEXT(P::name << " at " << o.x) {
        const auto cs = rk::contact_constraints<P>(base, cube);
        BOOST_TEST_REQUIRE(cs.size() == 4u);
        for (const ContactConstraint& c : cs) {
          BOOST_TEST((c.type == ConstraintType::vertex_face));
          BOOST_TEST((c.entering == rk::BlockRole::tp));
          BOOST_TEST((c.cp_feature == Feature{Feature::Kind::face, box_top, 0}));
          BOOST_TEST((c.plane == rk::PlaneSource{rk::PlaneSource::Kind::cp_face, box_top, 0}));
          BOOST_TEST((c.tp_feature.kind == Feature::Kind::vertex));
          BOOST_TEST(c.tp_feature.index < 4u);  // the cube's bottom corners are its vertices 0-3
          BOOST_TEST((c.point_tp == cube[c.tp_feature.index]));
          BOOST_TEST((c.point_cp == c.point_tp));
          BOOST_TEST((c.normal == Point3{0, 0, 1}));
          BOOST_TEST(c.gap == 0.0);
          BOOST_TEST(c.candidates.empty());
          check_frame(c);
        }
        const auto swapped = rk::contact_constraints<P>(cube, base);
        BOOST_TEST_REQUIRE(swapped.size() == 4u);
        for (const ContactConstraint& c : swapped) {
          BOOST_TEST((c.entering == rk::BlockRole::cp));
          BOOST_TEST((c.normal == Point3{0, 0, -1}));
          BOOST_TEST(c.gap == 0.0);
        }
      }
    });
  }
}

// The same cube pushed 1e-3 into the face: its bottom corners lie 1e-3 below the top face and
// much deeper below every other face, so each is a vertex-face constraint on the top face
// (shortest exit, eq. 4) with gap -1e-3; the point on cp is the corner's projection, z = 0.
// The gap is the corner's height z0 = -1e-3 (a double): Exact must give it exactly (the exact
// gap is the double z0, rounded once); Filtered constructs in double with coordinates below 4 m
// and about ten operations, so within 16 ulps of 4 m (1.5e-14).
BOOST_AUTO_TEST_CASE(cube_pushed_into_a_face) {
  const double z0 = -1e-3;
  const ConvexPolyhedron base = box("base", {0, 0, -1}, {4, 4, 0});
  const ConvexPolyhedron cube = box("cube", {1, 1, z0}, {2, 2, 1 + z0});
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      const auto cs = rk::contact_constraints<P>(base, cube);
      BOOST_TEST_REQUIRE(cs.size() == 4u);
      for (const ContactConstraint& c : cs) {
        BOOST_TEST((c.type == ConstraintType::vertex_face));
        BOOST_TEST((c.cp_feature == Feature{Feature::Kind::face, box_top, 0}));
        BOOST_TEST((c.point_tp == cube[c.tp_feature.index]));
        BOOST_TEST(c.point_tp.z == z0);
        BOOST_TEST(std::fabs(c.point_cp.z) <= 16 * 4 * 0x1p-52);
        BOOST_TEST(c.point_cp.x == c.point_tp.x);
        BOOST_TEST(c.point_cp.y == c.point_tp.y);
        BOOST_TEST((c.normal == Point3{0, 0, 1}));
        if constexpr (P::kind == rk::PolicyKind::exact) {
          BOOST_TEST(c.gap == z0);
        } else {
          BOOST_TEST(std::fabs(c.gap - z0) <= 16 * 4 * 0x1p-52);
        }
      }
    }
  });
}

// Overlapping pairs (header, step 4): every constraint within the pair's penetration depth, and
// a face pushed into an equal face held at three or more non-collinear points. The depth is
// 2^-10 m (a double, so the exact gaps are too); Filtered constructs in a frame of size ~2 m, so
// its gaps are within 16 ulps of 2 m, Exact's as well (the penetration plane is built in double).
namespace {

constexpr double overlap_depth = 0x1p-10;
constexpr double overlap_slack = 16 * 2 * 0x1p-52;

// The closed constraints' contact points span a plane region: three of them not collinear.
bool holds_a_face(const std::vector<ContactConstraint>& cs) {
  for (std::size_t i = 0; i < cs.size(); ++i) {
    for (std::size_t j = i + 1; j < cs.size(); ++j) {
      for (std::size_t k = j + 1; k < cs.size(); ++k) {
        if (cs[i].gap > 0 || cs[j].gap > 0 || cs[k].gap > 0) continue;
        if (norm(cross(cs[j].point_tp - cs[i].point_tp, cs[k].point_tp - cs[i].point_tp)) > 1e-6) return true;
      }
    }
  }
  return false;
}

// The checks every overlapping pair must pass: something closed, nothing deeper than `depth`.
template <class P>
void check_within_depth(const std::vector<ContactConstraint>& cs, double depth) {
  BOOST_TEST(std::any_of(cs.begin(), cs.end(), [](const ContactConstraint& c) { return c.gap <= 0.0; }));
  for (const ContactConstraint& c : cs) {
    BOOST_TEST(c.gap >= -depth - overlap_slack);
    check_frame(c);
  }
}

}  // namespace

// Two equal unit cubes, the second 2^-10 m into the first along x: every corner of the
// overlap's faces lies on an edge of the other cube, with an edge of its own leaving it into
// the other, so no plane separates the blocks there (the case that gave no constraint). The
// minimum translation is 2^-10 m along +x: four constraints, one per corner of the unit square
// at x = 1 (a corner of cp on a corner of tp is one position), normal (1, 0, 0), gap -2^-10.
// Swapped, the normal flips and the gaps stay.
BOOST_AUTO_TEST_CASE(equal_cubes_overlapping_face_on) {
  const ConvexPolyhedron a = box("a", {0, 0, 0}, {1, 1, 1});
  const ConvexPolyhedron b = box("b", {1 - overlap_depth, 0, 0}, {2 - overlap_depth, 1, 1});
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      for (const bool swapped : {false, true}) {
        const auto cs = swapped ? rk::contact_constraints<P>(b, a) : rk::contact_constraints<P>(a, b);
        BOOST_TEST_REQUIRE(cs.size() == 4u);
        check_within_depth<P>(cs, overlap_depth);
        BOOST_TEST(holds_a_face(cs));
        for (const ContactConstraint& c : cs) {
          BOOST_TEST((c.plane.kind == rk::PlaneSource::Kind::penetration));
          BOOST_TEST((c.normal == Point3{swapped ? -1.0 : 1.0, 0, 0}));
          BOOST_TEST(std::fabs(c.gap + overlap_depth) <= overlap_slack);
          BOOST_TEST(std::fabs(c.point_tp.y * (1 - c.point_tp.y)) == 0.0);  // a corner: y, z in {0, 1}
          BOOST_TEST(std::fabs(c.point_tp.z * (1 - c.point_tp.z)) == 0.0);
        }
      }
    }
  });
}

// The same overlap with b offset by (1/4, 3/8) across the face: b's corner (1 - d, 1/4, 3/8) is
// inside a, a's corner (1, 1, 1) inside b; their edges cross at the overlap's other corners
// along the face planes (gap -d), and across its sides: a's edge y = z = 1 against b's edge
// x = 1 - d, y = 1/4 cross 3/4 m "deep", a's edge along y at x = 1, z = 1 against b's along z
// 5/8 m: such planes are no way for the blocks to come apart (they did push with 500 x the
// penetration force) and are dropped. What is left holds the face, within the depth.
BOOST_AUTO_TEST_CASE(offset_cubes_overlapping_keep_within_the_depth) {
  const ConvexPolyhedron a = box("a", {0, 0, 0}, {1, 1, 1});
  const ConvexPolyhedron b = box("b", {1 - overlap_depth, 0.25, 0.375}, {2 - overlap_depth, 1.25, 1.375});
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      for (const bool swapped : {false, true}) {
        const auto cs = swapped ? rk::contact_constraints<P>(b, a) : rk::contact_constraints<P>(a, b);
        check_within_depth<P>(cs, overlap_depth);
        BOOST_TEST(holds_a_face(cs));
        std::size_t along_x = 0;
        for (const ContactConstraint& c : cs) along_x += std::fabs(std::fabs(c.normal.x) - 1) <= 1e-15;
        BOOST_TEST(along_x == 4u);
      }
    }
  });
}

// Translation invariance of the penetration plane: the offset pair moved by (2^20, -2^20, 2^19)
// m, an exact translation, gives the same constraints: the same types and features, the gaps
// within 16 ulps of the local size (the frame is at cp's first vertex), the points translated.
BOOST_AUTO_TEST_CASE(overlapping_pair_far_from_the_origin) {
  const Point3 shift{0x1p20, -0x1p20, 0x1p19};
  const ConvexPolyhedron a = box("a", {0, 0, 0}, {1, 1, 1});
  const ConvexPolyhedron b = box("b", {1 - overlap_depth, 0.25, 0.375}, {2 - overlap_depth, 1.25, 1.375});
  const auto moved = [&](const ConvexPolyhedron& p) {
    std::vector<Point3> v;
    for (const Point3& x : p.vertices()) v.push_back(x + shift);
    return ConvexPolyhedron::make(p.name(), std::move(v),
                                  std::vector<ConvexPolyhedron::Face>(p.faces().begin(), p.faces().end()));
  };
  const auto near = rk::contact_constraints<rk::Filtered>(a, b);
  const auto far = rk::contact_constraints<rk::Filtered>(moved(a), moved(b));
  BOOST_TEST_REQUIRE(near.size() == far.size());
  for (std::size_t i = 0; i < near.size(); ++i) {
    BOOST_TEST((near[i].type == far[i].type));
    BOOST_TEST((near[i].cp_feature == far[i].cp_feature));
    BOOST_TEST((near[i].tp_feature == far[i].tp_feature));
    BOOST_TEST(std::fabs(near[i].gap - far[i].gap) <= overlap_slack);
    BOOST_TEST(norm(near[i].point_tp + shift - far[i].point_tp) <= 0x1p-52 * 0x1p21);
  }
}

// Two identical blocks have no separating plane anywhere, and every vertex touches: each takes
// the plane of a minimum translation (a unit along an axis, the tie broken by the kernel), and
// the constraints stay within that depth.
BOOST_AUTO_TEST_CASE(identical_cubes_are_held) {
  const ConvexPolyhedron a = box("a", {0, 0, 0}, {1, 1, 1});
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      const auto cs = rk::contact_constraints<P>(a, a);
      check_within_depth<P>(cs, 1.0);
      BOOST_TEST(holds_a_face(cs));
    }
  });
}

// A tetrahedral wedge resting in a V made of two convex parts, meeting along the internal face
// x = 0: part 0 has the slope z = -x (x <= 0), part 1 the slope z = x. The wedge's ridge
// (0, 1..2, 0) lies in the V's concave edge, its two other faces flush on the slopes. Per part:
// the wedge vertex on the slope is vertex-face, the two ridge vertices are vertex-edge (on the
// part's edge along the V bottom), and all three take the part's slope normal, (1, 0, 1)/sqrt 2
// for part 0 and (-1, 0, 1)/sqrt 2 for part 1 (§2.2.2: the concave edge splits into the two
// parts' planes; the internal face x = 0 is never a plane). Six constraints, gap 0.
BOOST_AUTO_TEST_CASE(wedge_in_a_v_of_two_parts) {
  const std::vector<ConvexPolyhedron> v = {
      prism("left", {{0, 0, 0}, {0, 0, -1}, {-2, 0, -1}, {-2, 0, 2}}, {0, 3, 0}),
      prism("right", {{0, 0, 0}, {2, 0, 2}, {2, 0, -1}, {0, 0, -1}}, {0, 3, 0})};
  const std::vector<ConvexPolyhedron> wedge = {
      tetrahedron("wedge", {0, 1, 0}, {0, 2, 0}, {-1, 1.5, 1}, {1, 1.5, 1})};
  const double h = std::sqrt(0.5);
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      const auto cs = rk::contact_constraints<P>(std::span<const ConvexPolyhedron>(v),
                                                 std::span<const ConvexPolyhedron>(wedge));
      BOOST_TEST_REQUIRE(cs.size() == 6u);
      for (std::uint32_t part : {0u, 1u}) {
        const Point3 expected = part == 0 ? Point3{h, 0, h} : Point3{-h, 0, h};
        int faces = 0, edges = 0;
        for (const ContactConstraint& c : cs) {
          if (c.cp_feature.part != part) continue;
          faces += c.type == ConstraintType::vertex_face;
          edges += c.type == ConstraintType::vertex_edge;
          BOOST_TEST(c.gap == 0.0);
          BOOST_TEST((c.point_cp == c.point_tp));
          // The unit of (1, 0, 1) rounded: each component within an ulp of sqrt(1/2).
          BOOST_TEST(norm(c.normal - expected) <= 0x1p-52);
          if (c.type == ConstraintType::vertex_edge) {
            BOOST_TEST(std::fabs(c.point_tp.x) == 0.0);
            BOOST_TEST(c.point_tp.z == 0.0);
          }
        }
        BOOST_TEST(faces == 1);
        BOOST_TEST(edges == 2);
      }
    }
  });
}

// Two triangular prisms whose ridges cross at right angles and touch at (0, 0, 1): the lower
// ridge runs along x, the upper along y. Exactly one edge-edge constraint on the two ridges,
// normal (1, 0, 0) x (0, 1, 0) = (0, 0, 1) pointing from cp (below) to tp, point_cp = point_tp
// = the crossing. Lifted by 1/4 they are apart: the constraint appears with gap 1/4 when the
// tolerance is at least 1/4 (exactly 1/4 included: the comparison is exact) and not below.
// Lowered by 1/8 the ridges cut into each other: the same constraint with gap -1/8, points
// (0, 0, 1) on the lower ridge and (0, 0, 7/8) on the upper (dyadic: constructed exactly).
BOOST_AUTO_TEST_CASE(crossing_ridges) {
  const ConvexPolyhedron lower = prism("lower", {{-2, -1, 0}, {-2, 1, 0}, {-2, 0, 1}}, {4, 0, 0});
  for (const double lift : {0.0, 0.25, -0.125}) {
    const ConvexPolyhedron upper =
        prism("upper", {{-1, -2, 2 + lift}, {1, -2, 2 + lift}, {0, -2, 1 + lift}}, {0, 4, 0});
    const std::uint32_t lower_ridge = edge_index(lower, {-2, 0, 1}, {2, 0, 1});
    const std::uint32_t upper_ridge = edge_index(upper, {0, -2, 1 + lift}, {0, 2, 1 + lift});
    for_staged([&](auto policy) {
      using P = decltype(policy);
      BOOST_TEST_CONTEXT(P::name << ", lift " << lift) {
        if (lift > 0) {
          BOOST_TEST(rk::contact_constraints<P>(lower, upper, 0.0).empty());
          BOOST_TEST(rk::contact_constraints<P>(lower, upper, 0.2).empty());
        }
        for (const double tolerance : {std::max(lift, 0.0), 0.3}) {
          const auto cs = rk::contact_constraints<P>(lower, upper, tolerance);
          BOOST_TEST_REQUIRE(cs.size() == 1u);
          const ContactConstraint& c = cs.front();
          BOOST_TEST((c.type == ConstraintType::edge_edge));
          BOOST_TEST((c.cp_feature == Feature{Feature::Kind::edge, lower_ridge, 0}));
          BOOST_TEST((c.tp_feature == Feature{Feature::Kind::edge, upper_ridge, 0}));
          BOOST_TEST((c.plane == rk::PlaneSource{rk::PlaneSource::Kind::edge_pair, lower_ridge, upper_ridge}));
          BOOST_TEST((c.normal == Point3{0, 0, 1}));
          BOOST_TEST((c.point_cp == Point3{0, 0, 1}));
          BOOST_TEST((c.point_tp == Point3{0, 0, 1 + lift}));
          BOOST_TEST(c.gap == lift);
          check_frame(c);
        }
      }
    });
  }
}

// An octahedron's vertex on the cube's top back edge (y = 1, z = 1), the octahedron behind it
// (y >= 1): one vertex-edge constraint, point (0.5, 1, 1) on both blocks. Two candidate planes
// keep the octahedron's edges at the vertex and the cube's wedge at the edge apart: the cube's
// back face y = 1, and the plane through the cube's edge and the octahedron's edge down to
// (0.5, 1.5, 0.5), normal (0, 1, 1)/sqrt 2 (the octahedron lies in y + z >= 2, the cube in
// y + z <= 2). The top face z = 1 fails (that octahedron edge goes down into it), and so do the
// octahedron's faces (tilted in x against the cube's edge). Both pass at gap 0; the tie goes to
// the face of the block whose edge is touched: normal (0, 1, 0).
BOOST_AUTO_TEST_CASE(vertex_on_an_edge) {
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {1, 1, 1});
  const Point3 c{0.5, 1.5, 1};
  const double r = 0.5;
  const ConvexPolyhedron octa = ConvexPolyhedron::make(
      "octahedron",
      {{c.x + r, c.y, c.z}, {c.x - r, c.y, c.z}, {c.x, c.y + r, c.z}, {c.x, c.y - r, c.z}, {c.x, c.y, c.z + r},
       {c.x, c.y, c.z - r}},
      {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      const auto cs = rk::contact_constraints<P>(cube, octa);
      BOOST_TEST_REQUIRE(cs.size() == 1u);
      const ContactConstraint& k = cs.front();
      BOOST_TEST((k.type == ConstraintType::vertex_edge));
      BOOST_TEST((k.entering == rk::BlockRole::tp));
      BOOST_TEST((k.tp_feature == Feature{Feature::Kind::vertex, 3, 0}));
      BOOST_TEST((k.cp_feature == Feature{Feature::Kind::edge, edge_index(cube, {0, 1, 1}, {1, 1, 1}), 0}));
      BOOST_TEST((k.point_cp == Point3{0.5, 1, 1}));
      BOOST_TEST((k.point_tp == Point3{0.5, 1, 1}));
      BOOST_TEST((k.normal == Point3{0, 1, 0}));
      BOOST_TEST(k.gap == 0.0);
      const std::uint32_t cube_edge = edge_index(cube, {0, 1, 1}, {1, 1, 1});
      BOOST_TEST((k.plane == rk::PlaneSource{rk::PlaneSource::Kind::cp_face, box_back, 0}));
      BOOST_TEST_REQUIRE(k.candidates.size() == 2u);
      BOOST_TEST((k.candidates[0].normal == Point3{0, 1, 0}));
      BOOST_TEST((k.candidates[0].source == k.plane));
      const double h = std::sqrt(0.5);
      BOOST_TEST(norm(k.candidates[1].normal - Point3{0, h, h}) <= 0x1p-52);  // rounded unit
      BOOST_TEST((k.candidates[1].source.kind == rk::PlaneSource::Kind::edge_pair));
      BOOST_TEST(k.candidates[1].source.cp_index == cube_edge);
      BOOST_TEST(k.candidates[1].source.tp_index == edge_index(octa, {0.5, 1, 1}, {0.5, 1.5, 0.5}));
    }
  });
}

// A tetrahedron whose apex sits on the cube's corner (1, 1, 1) and opens away from it along
// (2, 1, 1), (1, 2, 1), (1, 1, 2): one vertex-vertex constraint (found from both blocks, kept
// once). The planes that keep both tangent cones apart are the cube's three faces at the corner
// (the tetrahedron's faces and the edge-edge planes cut the cube's cone), all at gap 0; the tie
// goes to the first by the header's order. With the cube as cp its vertex is located first, so
// the tetrahedron's faces come first (none passes), then the cube's by index: the top face,
// normal (0, 0, 1). With the blocks exchanged the tetrahedron's vertex is located first and the
// cube's faces come first: the top face again, now (0, 0, -1) from cp to tp.
BOOST_AUTO_TEST_CASE(vertex_on_a_vertex) {
  const ConvexPolyhedron cube = box("cube", {0, 0, 0}, {1, 1, 1});
  const ConvexPolyhedron tet = tetrahedron("tet", {1, 1, 1}, {3, 2, 2}, {2, 3, 2}, {2, 2, 3});
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      for (const bool cube_first : {true, false}) {
        const auto cs = cube_first ? rk::contact_constraints<P>(cube, tet) : rk::contact_constraints<P>(tet, cube);
        BOOST_TEST_REQUIRE(cs.size() == 1u);
        const ContactConstraint& k = cs.front();
        BOOST_TEST((k.type == ConstraintType::vertex_vertex));
        BOOST_TEST((k.point_cp == Point3{1, 1, 1}));
        BOOST_TEST((k.point_tp == Point3{1, 1, 1}));
        BOOST_TEST(k.gap == 0.0);
        const double s = cube_first ? 1 : -1;
        BOOST_TEST((k.normal == Point3{0, 0, s}));
        BOOST_TEST_REQUIRE(k.candidates.size() == 3u);
        for (const Point3 axis : {Point3{s, 0, 0}, Point3{0, s, 0}, Point3{0, 0, s}}) {
          BOOST_TEST(std::count_if(k.candidates.begin(), k.candidates.end(),
                                   [&](const rk::CandidatePlane& p) { return p.normal == axis; }) == 1);
        }
        // The cube's top face, as a face of cp or of tp.
        const auto kind = cube_first ? rk::PlaneSource::Kind::cp_face : rk::PlaneSource::Kind::tp_face;
        BOOST_TEST((k.plane == rk::PlaneSource{kind, cube_first ? box_top : 0, cube_first ? 0 : box_top}));
        const Feature corner{Feature::Kind::vertex, 6, 0};  // the box's vertex (hi, hi, hi)
        BOOST_TEST(((cube_first ? k.cp_feature : k.tp_feature) == corner));
      }
    }
  });
}

// Two unit cubes stacked with coincident footprints: the four touching corner pairs are
// vertex-vertex (each found from both blocks, kept once), and every plane that keeps the two
// corner cones apart is horizontal (a side face has the other block's edge going into it), so
// the normal is (0, 0, 1) whichever candidate the tie-break picks.
BOOST_AUTO_TEST_CASE(stacked_cubes_corner_on_corner) {
  const ConvexPolyhedron lower = box("lower", {0, 0, 0}, {1, 1, 1});
  const ConvexPolyhedron upper = box("upper", {0, 0, 1}, {1, 1, 2});
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      const auto cs = rk::contact_constraints<P>(lower, upper);
      BOOST_TEST_REQUIRE(cs.size() == 4u);
      for (const ContactConstraint& c : cs) {
        BOOST_TEST((c.type == ConstraintType::vertex_vertex));
        BOOST_TEST((c.normal == Point3{0, 0, 1}));
        BOOST_TEST(c.point_cp.z == 1.0);
        BOOST_TEST((c.point_cp == c.point_tp));
        BOOST_TEST(c.gap == 0.0);
        BOOST_TEST(!c.candidates.empty());
        for (const rk::CandidatePlane& p : c.candidates) BOOST_TEST((p.normal == Point3{0, 0, 1}));
      }
    }
  });
}

// The four bottom corners of a cube pushed 0.01 into part 0's top face: vertex-face constraints
// on that face, normal (0, 0, 1), and with `depth`, gap -0.01 (within 16 ulps of the 2 m scale
// under Filtered).
void expect_corners_on_top(const std::vector<ContactConstraint>& cs, bool depth) {
  BOOST_TEST_REQUIRE(cs.size() == 4u);
  for (const ContactConstraint& c : cs) {
    BOOST_TEST((c.type == ConstraintType::vertex_face));
    BOOST_TEST((c.cp_feature == Feature{Feature::Kind::face, box_top, 0}));
    BOOST_TEST((c.normal == Point3{0, 0, 1}));
    if (depth) BOOST_TEST(std::fabs(c.gap + 0.01) <= 16 * 2 * 0x1p-52);
  }
}

// Internal faces are no exit: a base of two unit boxes side by side (parts meeting at x = 1) and
// a cube pushed 0.01 into part 0's top, two of its bottom corners 0.005 from the internal face
// x = 1. Were that face an exit, those corners would take it (0.005 < 0.01) with normal (1, 0, 0);
// as it is internal, all four corners exit through the top: vertex-face on part 0's top face,
// normal (0, 0, 1), gap -0.01 (within 16 ulps of the 2 m scale under Filtered, as above). Part 1
// is not reached, and the cube's vertical edges and the part's seam edge are on the same side
// of their common plane, so no edge-edge constraint either.
BOOST_AUTO_TEST_CASE(internal_face_is_no_exit) {
  const std::vector<ConvexPolyhedron> base = {box("part 0", {0, 0, -1}, {1, 1, 0}),
                                              box("part 1", {1, 0, -1}, {2, 1, 0})};
  const std::vector<ConvexPolyhedron> cube = {box("cube", {0.5, 0.25, -0.01}, {0.995, 0.75, 0.99})};
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      const auto cs = rk::contact_constraints<P>(std::span<const ConvexPolyhedron>(base),
                                                 std::span<const ConvexPolyhedron>(cube));
      expect_corners_on_top(cs, true);
    }
  });
}

// Parts that meet only to rounding, as the parts of a cut block do (their implicit vertices
// rounded each on its own): the base of internal_face_is_no_exit with part 1's seam face
// tilted by one ulp (its vertices at y = 0 moved to x = 1 - 2^-53), so the two seam faces are
// not exactly coplanar. They are still internal (within face_planarity_tolerance of the
// block's size, 2e-9 m here): the cube's corners 0.005 from the seam exit through the top, as
// before; an exact coplanarity test would let them exit through the seam, normal (1, 0, 0).
BOOST_AUTO_TEST_CASE(parts_meeting_to_rounding_have_internal_faces) {
  const ConvexPolyhedron exact = box("part 1", {1, 0, -1}, {2, 1, 0});
  std::vector<Point3> vertices(exact.vertices().begin(), exact.vertices().end());
  for (Point3& p : vertices) {
    if (p.x == 1.0 && p.y == 0.0) p.x = std::nextafter(1.0, 0.0);
  }
  const std::vector<ConvexPolyhedron> base = {
      box("part 0", {0, 0, -1}, {1, 1, 0}), ConvexPolyhedron::make(
                                                  "part 1", std::move(vertices),
                                                  std::vector<ConvexPolyhedron::Face>(exact.faces().begin(), exact.faces().end()))};
  const std::vector<ConvexPolyhedron> cube = {box("cube", {0.5, 0.25, -0.01}, {0.995, 0.75, 0.99})};
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      const auto cs = rk::contact_constraints<P>(std::span<const ConvexPolyhedron>(base),
                                                 std::span<const ConvexPolyhedron>(cube));
      expect_corners_on_top(cs, false);
    }
  });
}

// A step: part 0 the low tread [0, 1] x [0, 1] x [-1, 0], part 1 under the riser [1, 2] x [0, 1]
// x [-1, 0] and part 2 the riser [1, 2] x [0, 1] x [0, 1] on it. The tread's top (z = 0, outward
// +z) lies in the plane of the riser's bottom (outward -z) with the riser on its outer side, but
// the two faces only meet along the edge x = 1: the tread is an outer face, and a cube resting
// on it gets its four corners as vertex-face constraints with normal +z. (Part 1's top is the
// riser's bottom exactly: internal, no constraint from part 1 or 2 at z = 0.) This is the face
// a wedge rests on next to the concave edge of its base.
BOOST_AUTO_TEST_CASE(coplanar_faces_meeting_at_an_edge_are_not_internal) {
  const std::vector<ConvexPolyhedron> step = {box("tread", {0, 0, -1}, {1, 1, 0}), box("under", {1, 0, -1}, {2, 1, 0}),
                                              box("riser", {1, 0, 0}, {2, 1, 1})};
  const std::vector<ConvexPolyhedron> cube = {box("cube", {0.25, 0.25, -0.01}, {0.75, 0.75, 0.49})};
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      const auto cs = rk::contact_constraints<P>(std::span<const ConvexPolyhedron>(step),
                                                 std::span<const ConvexPolyhedron>(cube), 0.1);
      expect_corners_on_top(cs, true);
    }
  });
}

// A cube 0.1 above the box's top face: within a tolerance of 0.1 (the same double as the gap,
// included exactly) its four bottom corners give vertex-face constraints with gap 0.1 (Exact: the
// double 0.1 exactly; Filtered: within 16 ulps of 4 m, as above); within 0.0999, none. A
// negative or NaN tolerance is refused.
BOOST_AUTO_TEST_CASE(separated_within_tolerance) {
  const ConvexPolyhedron base = box("base", {0, 0, -1}, {4, 4, 0});
  const ConvexPolyhedron cube = box("cube", {1, 1, 0.1}, {2, 2, 1.1});
  for_staged([&](auto policy) {
    using P = decltype(policy);
    BOOST_TEST_CONTEXT(P::name) {
      BOOST_CHECK_THROW(rk::contact_constraints<P>(base, cube, -0.1), std::invalid_argument);
      BOOST_CHECK_THROW(rk::contact_constraints<P>(base, cube, NAN), std::invalid_argument);
      BOOST_TEST(rk::contact_constraints<P>(base, cube, 0.0999).empty());
      const auto cs = rk::contact_constraints<P>(base, cube, 0.1);
      BOOST_TEST_REQUIRE(cs.size() == 4u);
      for (const ContactConstraint& c : cs) {
        BOOST_TEST((c.type == ConstraintType::vertex_face));
        BOOST_TEST((c.normal == Point3{0, 0, 1}));
        if constexpr (P::kind == rk::PolicyKind::exact) {
          BOOST_TEST(c.gap == 0.1);
        } else {
          BOOST_TEST(std::fabs(c.gap - 0.1) <= 16 * 4 * 0x1p-52);
        }
      }
    }
  });
}

// §2.3, eq. 6-8: the tangential part of the relative motion, normalised.
BOOST_AUTO_TEST_CASE(sliding_direction_on_the_plane) {
  const Point3 n{0, 0, 1};
  const auto t = rk::sliding_direction(n, {3, 4, 5});
  BOOST_TEST_REQUIRE(t.has_value());
  BOOST_TEST(std::fabs(t->x - 0.6) <= 0x1p-52);
  BOOST_TEST(std::fabs(t->y - 0.8) <= 0x1p-52);
  BOOST_TEST(t->z == 0.0);
  BOOST_TEST(!rk::sliding_direction(n, {0, 0, 2}).has_value());       // pure normal motion
  BOOST_TEST(!rk::sliding_direction(n, {3e-7, 4e-7, 1}, 1e-6).has_value());  // |v_t| = 5e-7 <= 1e-6
  BOOST_TEST(rk::sliding_direction(n, {3e-7, 4e-7, 1}, 1e-7).has_value());
}

// The contact3d reference pairs (README there), with justified assertions only:
//  * touch (tolerance 0): every constraint has gap exactly 0 and point_cp == point_tp (a touch
//    is decided exactly), and every corner of the exact contact set is the contact point of some
//    constraint: a corner is a vertex of one block lying on the other or the crossing of an edge
//    of each, which is what steps 1 and 2 find. Within 1e-9 scale (the reference's suggested
//    tolerance; our crossing points are rounded to within an ulp of their coordinates). The
//    chosen plane separates the blocks: each vertex x of cp has (x - point) . normal <= allowance
//    and each of tp >= -allowance, with allowance = 1e-12 scale + 8 ulps of the largest
//    coordinate (the rounded point and unit normal);
//  * separate: no constraint at tolerance 0, none at tolerance distance (1 - 1e-6) (every feature
//    pair is at least the distance apart; the margin covers the reference's rounding, 1e-9
//    relative), some at distance (1 + 1e-6), all with positive gap (these are exact decisions);
//    one has gap <= distance (1 + 1e-6) + slack (the closest pair's constraint), and the
//    vertex-face and edge-edge gaps, which are distances between a feature pair, are
//    >= distance (1 - 1e-6) - slack. The slack is the construction's error: Filtered computes
//    the gap in double from coordinates translated to cp's first vertex, at most `scale` in
//    size, through about ten roundings of 2^-53 relative to values below scale^k, so 32 ulps of
//    the scale bounds it (these gaps are 1e-13 to 1e-11 m: the error is absolute, not relative);
//  * overlap: each vertex-face gap is >= -depth (1 + 1e-9) - 1e-12 scale: a penetrating vertex's
//    gap is minus its distance to the other block's boundary (the shortest exit), and moving
//    the blocks apart by the penetration depth clears the vertex, so that distance is at most
//    the depth; no such bound holds for edge-edge gaps (a sideways move can uncross two edges),
//    so they are not asserted;
//  * every normal is unit and every tangent frame orthonormal (check_frame).
namespace {

// The reference writes its numbers as decimal strings (exact to 50 digits).
double number(const nlohmann::json& j) { return std::stod(j.get<std::string>()); }

double max_coordinate(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  double m = 0;
  for (const auto* p : {&a, &b}) {
    for (const Point3& v : p->vertices()) m = std::max({m, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  }
  return m;
}

template <class P>
void check_reference_pair(const rockcontact::testing::Contact3dPair& pair) {
  const std::string status = pair.expected.at("status").get<std::string>();
  const double scale = number(pair.expected.at("scale"));
  const auto cs = rk::contact_constraints<P>(pair.cp, pair.tp);
  for (const ContactConstraint& c : cs) check_frame(c);
  if (status == "touch") {
    BOOST_TEST(!cs.empty());
    const double allowance = 1e-12 * scale + 8 * 0x1p-52 * max_coordinate(pair.cp, pair.tp);
    for (const ContactConstraint& c : cs) {
      BOOST_TEST(c.gap == 0.0);
      BOOST_TEST((c.point_cp == c.point_tp));
      double cp_side = -INFINITY, tp_side = INFINITY;
      for (const Point3& x : pair.cp.vertices()) cp_side = std::max(cp_side, dot(x - c.point_cp, c.normal));
      for (const Point3& x : pair.tp.vertices()) tp_side = std::min(tp_side, dot(x - c.point_cp, c.normal));
      BOOST_TEST(cp_side <= allowance);
      BOOST_TEST(tp_side >= -allowance);
    }
    for (const auto& corner : pair.expected.at("contact_set").at("vertices")) {
      const Point3 p{number(corner.at(0)), number(corner.at(1)), number(corner.at(2))};
      BOOST_TEST_INFO("corner " << p.x << " " << p.y << " " << p.z);
      BOOST_TEST(has_point(cs, p, 1e-9 * scale));
    }
  } else if (status == "separate") {
    BOOST_TEST(cs.empty());
    const double distance = number(pair.expected.at("distance"));
    const double slack = 32 * 0x1p-52 * scale;
    BOOST_TEST(rk::contact_constraints<P>(pair.cp, pair.tp, distance * (1 - 1e-6)).empty());
    const auto near = rk::contact_constraints<P>(pair.cp, pair.tp, distance * (1 + 1e-6));
    BOOST_TEST_REQUIRE(!near.empty());
    double smallest = INFINITY;
    for (const ContactConstraint& c : near) {
      BOOST_TEST(c.gap > 0.0);
      smallest = std::min(smallest, c.gap);
      if (c.type == ConstraintType::vertex_face || c.type == ConstraintType::edge_edge) {
        BOOST_TEST(c.gap >= distance * (1 - 1e-6) - slack);
      }
    }
    BOOST_TEST(smallest <= distance * (1 + 1e-6) + slack);
  } else {
    const double depth = number(pair.expected.at("penetration").at("depth"));
    for (const ContactConstraint& c : cs) {
      if (c.type == ConstraintType::vertex_face) BOOST_TEST(c.gap >= -depth * (1 + 1e-9) - 1e-12 * scale);
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(contact3d_reference_pairs) {
  const auto& pairs = rockcontact::testing::contact3d_pairs();
  BOOST_TEST_REQUIRE(pairs.size() == 132u);
  std::array<std::size_t, 4> by_type{};
  int overlap_without = 0, float_differs = 0;
  for (const auto& pair : pairs) {
    BOOST_TEST_CONTEXT("pair " << pair.id) {
      check_reference_pair<rk::Filtered>(pair);
      check_reference_pair<rk::Exact>(pair);
      check_reference_pair<rk::Checked>(pair);
    }
    const auto cs = rk::contact_constraints<rk::Filtered>(pair.cp, pair.tp);
    for (const ContactConstraint& c : cs) ++by_type[static_cast<std::size_t>(c.type)];
    overlap_without += cs.empty() && pair.expected.at("status").get<std::string>() == "overlap";
    const auto naive = rk::contact_constraints<rk::Float>(pair.cp, pair.tp);
    float_differs += !std::equal(cs.begin(), cs.end(), naive.begin(), naive.end(), [](const auto& a, const auto& b) {
      return a.type == b.type && a.cp_feature == b.cp_feature && a.tp_feature == b.tp_feature;
    });
  }
  BOOST_TEST_MESSAGE("contact3d at tolerance 0 (Filtered): " << by_type[0] << " vertex-face, " << by_type[1]
                     << " edge-edge, " << by_type[2] << " vertex-edge, " << by_type[3] << " vertex-vertex; "
                     << overlap_without << " overlapping pairs without a constraint; Float's feature list differs on "
                     << float_differs << " of 132 pairs");
}

// Rigid-motion invariance: the cyclic permutation (x, y, z) -> (y, z, x) is an exact rotation
// (it keeps every coordinate and the faces' orientation), so every contact3d pair rotated must
// give the same constraints: the same types, features and order exactly (the decisions are
// exact, and ties are broken by indices, never by coordinates), normals and points rotated,
// gaps equal. The constructed numbers may differ by the different order of the rounded sums:
// 32 ulps of the scale for gaps and points (as in contact3d_reference_pairs) plus 4 ulps of the
// largest coordinate for points (which are rounded back to the input's position), and 8 ulps
// for unit normals.
BOOST_AUTO_TEST_CASE(contact3d_rotation_invariance) {
  const auto rotate = [](const ConvexPolyhedron& p) {
    std::vector<Point3> vertices;
    for (const Point3& v : p.vertices()) vertices.push_back({v.y, v.z, v.x});
    return ConvexPolyhedron::make(p.name() + " rotated", std::move(vertices),
                                  std::vector<ConvexPolyhedron::Face>(p.faces().begin(), p.faces().end()));
  };
  const auto turn = [](const Point3& v) { return Point3{v.y, v.z, v.x}; };
  for (const auto& pair : rockcontact::testing::contact3d_pairs()) {
    BOOST_TEST_CONTEXT("pair " << pair.id) {
      const double scale = number(pair.expected.at("scale"));
      const double slack = 32 * 0x1p-52 * scale, point_slack = slack + 4 * 0x1p-52 * max_coordinate(pair.cp, pair.tp);
      const auto cs = rk::contact_constraints<rk::Filtered>(pair.cp, pair.tp);
      const auto rs = rk::contact_constraints<rk::Filtered>(rotate(pair.cp), rotate(pair.tp));
      BOOST_TEST_REQUIRE(cs.size() == rs.size());
      for (std::size_t i = 0; i < cs.size(); ++i) {
        BOOST_TEST((cs[i].type == rs[i].type));
        BOOST_TEST((cs[i].cp_feature == rs[i].cp_feature));
        BOOST_TEST((cs[i].tp_feature == rs[i].tp_feature));
        BOOST_TEST((cs[i].entering == rs[i].entering));
        if (cs[i].plane.kind == rk::PlaneSource::Kind::penetration) {
          // The penetration plane's normal is the minimum translation's, chosen in double among
          // directions tied within 1e-9 relative (penetration.hpp): rotated, the choice may fall
          // on a neighbour, within 1e-6 rad (penetration_test), which moves a gap and a point by
          // that angle times the scale.
          BOOST_TEST(norm(turn(cs[i].normal) - rs[i].normal) <= 1e-6);
          BOOST_TEST(std::fabs(cs[i].gap - rs[i].gap) <= 1e-6 * scale + slack);
          BOOST_TEST(norm(turn(cs[i].point_tp) - rs[i].point_tp) <= 1e-6 * scale + point_slack);
          continue;
        }
        BOOST_TEST(std::fabs(cs[i].gap - rs[i].gap) <= slack);
        BOOST_TEST(norm(turn(cs[i].normal) - rs[i].normal) <= 8 * 0x1p-52);
        BOOST_TEST(norm(turn(cs[i].point_cp) - rs[i].point_cp) <= point_slack);
        BOOST_TEST(norm(turn(cs[i].point_tp) - rs[i].point_tp) <= point_slack);
        BOOST_TEST((cs[i].plane == rs[i].plane));
        BOOST_TEST(cs[i].candidates.size() == rs[i].candidates.size());
      }
    }
  }
}
