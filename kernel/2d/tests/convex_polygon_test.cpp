#define BOOST_TEST_MODULE kernel_convex_polygon
#include <boost/test/unit_test.hpp>

#include "rockcontact/testing/seed.hpp"

// ConvexPolygon::make: one named degenerate case per InvalidPolygon::Reason, each checking the
// reason, the reported vertex and that the message names the polygon and the vertex; the
// clockwise normalisation; and nearly collinear vertices whose acceptance must follow their
// exact orientation (decided here in GMP rationals), not a rounded one.

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rk = rockcontact::kernel;
using rk::ConvexPolygon;
using rk::InvalidPolygon;
using rk::Point2;
using Reason = InvalidPolygon::Reason;

namespace {

using rockcontact::testing::seed_for;

const char* reason_name(Reason r) {
  switch (r) {
    case Reason::too_few_vertices: return "too_few_vertices";
    case Reason::non_finite: return "non_finite";
    case Reason::repeated_vertex: return "repeated_vertex";
    case Reason::collinear: return "collinear";
    case Reason::clockwise: return "clockwise";
    case Reason::not_convex: return "not_convex";
  }
  return "?";
}

// The error make() throws, or nullopt when it accepts the polygon. Every case also checks
// assign() (its one-pass check for valid CCW input, make() for the rest) on a polygon of the
// same name: the same error, with the polygon left as it was, or the same accepted vertices.
std::optional<InvalidPolygon> error_of(const std::string& name, std::vector<Point2> v,
                                       rk::VertexOrder order = rk::VertexOrder::require_ccw) {
  const std::vector<Point2> triangle{{0, 0}, {1, 0}, {0, 1}};
  ConvexPolygon assigned = ConvexPolygon::make(name, triangle);
  std::optional<InvalidPolygon> from_assign;
  try {
    assigned.assign(v, order);
  } catch (const InvalidPolygon& e) {
    from_assign = e;
  }
  std::optional<InvalidPolygon> from_make;
  try {
    const ConvexPolygon made = ConvexPolygon::make(name, std::move(v), order);
    BOOST_TEST_INFO("case " << name << ": assign accepts what make accepts, as make leaves it");
    BOOST_TEST((!from_assign && made.reversed() == assigned.reversed() &&
                std::equal(made.vertices().begin(), made.vertices().end(),
                           assigned.vertices().begin(), assigned.vertices().end())));
  } catch (const InvalidPolygon& e) {
    from_make = e;
    BOOST_TEST_INFO("case " << name << ": assign refuses what make refuses, for the same reason");
    BOOST_TEST((from_assign && from_assign->reason() == e.reason() &&
                from_assign->vertex() == e.vertex() &&
                std::string(from_assign->what()) == e.what()));
    BOOST_TEST_INFO("case " << name << ": a refused assign leaves the polygon as it was");
    BOOST_TEST((std::equal(triangle.begin(), triangle.end(), assigned.vertices().begin(),
                           assigned.vertices().end())));
  }
  return from_make;
}

// Asserts the reason, the vertex (when `vertex` >= 0; -1 means "the polygon as a whole") and
// that the message names the polygon and, for a vertex error, "vertex <index>".
void expect_error(const std::string& name, std::vector<Point2> v, Reason reason, std::ptrdiff_t vertex,
                  rk::VertexOrder order = rk::VertexOrder::require_ccw) {
  const auto e = error_of(name, std::move(v), order);
  BOOST_TEST_INFO("case " << name);
  BOOST_TEST_REQUIRE(e.has_value());
  BOOST_TEST_INFO("case " << name << ": got " << reason_name(e->reason()) << ", message: " << e->what());
  BOOST_TEST((e->reason() == reason));
  BOOST_TEST(e->polygon() == name);
  BOOST_TEST(e->vertex() == vertex);
  const std::string message = e->what();
  BOOST_TEST_INFO("message: " << message);
  BOOST_TEST(message.find(name) != std::string::npos);
  if (vertex >= 0) {
    BOOST_TEST_INFO("message: " << message);
    BOOST_TEST(message.find("vertex " + std::to_string(vertex)) != std::string::npos);
  }
}

rk::Sign exact_orientation(const Point2& p, const Point2& q, const Point2& r) {
  const mpq_class det = (mpq_class(q.x) - p.x) * (mpq_class(r.y) - p.y) - (mpq_class(q.y) - p.y) * (mpq_class(r.x) - p.x);
  return static_cast<rk::Sign>(sgn(det));
}

}  // namespace

BOOST_AUTO_TEST_CASE(valid_polygons_are_kept_as_given) {
  const std::vector<Point2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const ConvexPolygon p = ConvexPolygon::make("square", square);
  BOOST_TEST(p.name() == "square");
  BOOST_TEST(p.size() == 4u);
  BOOST_TEST(!p.reversed());
  for (std::size_t i = 0; i < 4; ++i) BOOST_TEST((p[i] == square[i]));
  BOOST_TEST(p.next(3) == 0u);
  BOOST_TEST(p.prev(0) == 3u);
  // A CCW polygon passes normalise untouched.
  const ConvexPolygon q = ConvexPolygon::make("square", square, rk::VertexOrder::normalise);
  BOOST_TEST(!q.reversed());
  for (std::size_t i = 0; i < 4; ++i) BOOST_TEST((q[i] == square[i]));
  // A 0.5 degree wedge and a polygon far from the origin are valid.
  BOOST_TEST(!error_of("wedge", {{0, 0}, {1, -0.0043633}, {1, 0.0043633}}));
  BOOST_TEST(!error_of("far", {{1e6, 1e6}, {1e6 + 0.01, 1e6}, {1e6, 1e6 + 0.01}}));
}

// Every reason, by name. The expected vertex follows from the definition: the first vertex
// (in input order) at which the property fails.
BOOST_AUTO_TEST_CASE(each_reason_names_polygon_and_vertex) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  // too few vertices: the polygon as a whole.
  expect_error("two_points", {{0, 0}, {1, 0}}, Reason::too_few_vertices, -1);
  expect_error("empty", {}, Reason::too_few_vertices, -1);
  // non-finite coordinates, at the first offending vertex.
  expect_error("nan_at_2", {{0, 0}, {1, 0}, {nan, 1}, {0, 1}}, Reason::non_finite, 2);
  expect_error("inf_at_1", {{0, 0}, {1, inf}, {1, 1}, {0, 1}}, Reason::non_finite, 1);
  expect_error("minus_inf_at_0", {{-inf, 0}, {1, 0}, {1, 1}}, Reason::non_finite, 0);
  // repeated vertex: consecutive (zero-length edge) and non-consecutive; the later index.
  expect_error("zero_length_edge_2", {{0, 0}, {1, 0}, {1, 0}, {0, 1}}, Reason::repeated_vertex, 2);
  expect_error("closing_vertex_repeated_3", {{0, 0}, {1, 0}, {0, 1}, {0, 0}}, Reason::repeated_vertex, 3);
  expect_error("figure_eight_repeat_3", {{0, 0}, {2, 0}, {1, 1}, {2, 0}, {2, 2}}, Reason::repeated_vertex, 3);
  // collinear vertex: on the segment between its neighbours, and all three collinear.
  expect_error("collinear_1", {{0, 0}, {1, 0}, {2, 0}, {1, 1}}, Reason::collinear, 1);
  expect_error("collinear_far_3", {{1e6, 1e6}, {1e6 + 2, 1e6}, {1e6 + 2, 1e6 + 2}, {1e6 + 1, 1e6 + 2}, {1e6, 1e6 + 2}},
               Reason::collinear, 3);
  expect_error("degenerate_triangle", {{0, 0}, {1, 1}, {3, 3}}, Reason::collinear, 0);
  // clockwise: the polygon as a whole.
  expect_error("clockwise_square", {{0, 0}, {0, 1}, {1, 1}, {1, 0}}, Reason::clockwise, -1);
  expect_error("clockwise_triangle", {{0, 0}, {0, 1}, {1, 0}}, Reason::clockwise, -1);
  // non-convex: the reflex vertex (the turn in the minority direction).
  expect_error("reflex_2", {{0, 0}, {2, 0}, {1, 0.5}, {2, 2}, {0, 2}}, Reason::not_convex, 2);
  expect_error("reflex_in_clockwise_4", {{0, 0}, {0, 2}, {2, 2}, {2, 0}, {1, 0.5}}, Reason::not_convex, 4);
  expect_error("reflex_normalised_2", {{0, 0}, {2, 0}, {1, 0.5}, {2, 2}, {0, 2}}, Reason::not_convex, 2,
               rk::VertexOrder::normalise);
}

// A pentagram turns left at every vertex but its boundary winds twice: not convex. Which vertex
// is blamed is a choice of the implementation; it must be one of the five and be named. Same
// for a bow-tie and a doubly wound hexagon.
BOOST_AUTO_TEST_CASE(self_intersecting_polygons_are_not_convex) {
  std::vector<Point2> pentagon;
  for (int k = 0; k < 5; ++k) {
    const double angle = 1.5707963267948966 + k * 1.2566370614359172;
    pentagon.push_back({std::cos(angle), std::sin(angle)});
  }
  std::vector<Point2> star;
  for (int k = 0; k < 5; ++k) star.push_back(pentagon[(2 * k) % 5]);
  for (const auto order : {rk::VertexOrder::require_ccw, rk::VertexOrder::normalise}) {
    const auto e = error_of("pentagram", star, order);
    BOOST_TEST_REQUIRE(e.has_value());
    BOOST_TEST((e->reason() == Reason::not_convex));
    BOOST_TEST(e->vertex() >= 0);
    BOOST_TEST(e->vertex() < 5);
    const std::string message = e->what();
    BOOST_TEST(message.find("pentagram") != std::string::npos);
    BOOST_TEST(message.find("vertex " + std::to_string(e->vertex())) != std::string::npos);
  }
  // A bow-tie turns right twice and left twice: not convex, whichever vertex is blamed.
  const auto bowtie = error_of("bowtie", {{0, 0}, {1, 1}, {1, 0}, {0, 1}});
  BOOST_TEST_REQUIRE(bowtie.has_value());
  BOOST_TEST((bowtie->reason() == Reason::not_convex));
  BOOST_TEST(bowtie->vertex() >= 0);
  BOOST_TEST(bowtie->vertex() < 4);
  // The reversed pentagram (all right turns) is reported as not convex as well when normalised.
  const std::vector<Point2> reversed_star(star.rbegin(), star.rend());
  const auto e = error_of("pentagram_cw", reversed_star, rk::VertexOrder::normalise);
  BOOST_TEST_REQUIRE(e.has_value());
  BOOST_TEST((e->reason() == Reason::not_convex));
  BOOST_TEST(e->vertex() >= 0);
  BOOST_TEST(e->vertex() < 5);
  // Six distinct points on a circle visited twice around in increasing angle (steps of 120 and
  // about 149 degrees): every turn is left, the boundary winds twice.
  std::vector<Point2> hexagram;
  for (int k = 0; k < 6; ++k) {
    const double angle = k * 2.0943951023931953 + (k >= 3 ? 0.5 : 0.0);
    hexagram.push_back({std::cos(angle), std::sin(angle)});
  }
  const auto h = error_of("double_wound_hexagon", hexagram);
  BOOST_TEST_REQUIRE(h.has_value());
  BOOST_TEST((h->reason() == Reason::not_convex));
}

BOOST_AUTO_TEST_CASE(normalise_reverses_clockwise) {
  const std::vector<Point2> cw{{0, 0}, {0, 1}, {1, 1.5}, {1, 0}};
  const ConvexPolygon p = ConvexPolygon::make("cw", cw, rk::VertexOrder::normalise);
  BOOST_TEST(p.reversed());
  BOOST_TEST(!error_of("cw", cw, rk::VertexOrder::normalise));  // assign reverses it alike
  BOOST_TEST_REQUIRE(p.size() == cw.size());
  // Same vertices, opposite order, and every turn now left (checked exactly).
  for (std::size_t i = 0; i < cw.size(); ++i) BOOST_TEST((p[i] == cw[cw.size() - 1 - i]));
  for (std::size_t i = 0; i < p.size(); ++i) {
    BOOST_TEST((exact_orientation(p[p.prev(i)], p[i], p[p.next(i)]) == rk::Sign::positive));
  }
}

// A vertex near the line of its neighbours: 1e-12 off it either way, or rounded onto it, or
// exactly on it (dyadic coordinates); near the origin and at 1000 m, where 1e-12 m is a few
// ulps and rounding the vertex can move it across the line. Acceptance (left turn), rejection
// as not convex (right turn) or as collinear (exactly on the line) must follow the exact
// orientation of the three doubles.
BOOST_AUTO_TEST_CASE(nearly_collinear_vertex_follows_exact_orientation) {
  std::mt19937_64 rng(seed_for("nearly_collinear_vertex_follows_exact_orientation", 20240611));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> sixteenths(3, 13);
  int accepted = 0, reflex = 0, collinear = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int kind = trial % 4;  // 0: rounded onto the line; 1: 1e-12 outward; 2: 1e-12 inward;
                                 // 3: exactly on the line
    const double shift = (trial / 4) % 2 == 0 ? 0.0 : 1000.0;
    // Quadrilateral a, m, b, c (CCW) with m near segment ab.
    Point2 a{0.1 + 0.3 * unit(rng), 0.2 * unit(rng)};
    Point2 b{1.3 + 0.3 * unit(rng), 0.7 + 0.2 * unit(rng)};
    const Point2 c{shift + 0.2 * unit(rng), shift + 1.1 + 0.3 * unit(rng)};
    double t = 0.2 + 0.6 * unit(rng);
    if (kind == 3) {  // multiples of 2^-8 and t = k/16: m = a + t (b - a) is exact
      a = {std::round(a.x * 256) / 256, std::round(a.y * 256) / 256};
      b = {std::round(b.x * 256) / 256, std::round(b.y * 256) / 256};
      t = sixteenths(rng) / 16.0;
    }
    a = {a.x + shift, a.y + shift};
    b = {b.x + shift, b.y + shift};
    const double offset = kind == 1 ? 1e-12 : (kind == 2 ? -1e-12 : 0.0);
    // The outward normal of ab in a CCW polygon a -> b -> c is (dy, -dx) / |d|.
    const double dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
    const Point2 m{a.x + t * dx + offset * dy / len, a.y + t * dy - offset * dx / len};
    const rk::Sign turn = exact_orientation(a, m, b);
    const auto e = error_of("near_collinear", {a, m, b, c});
    BOOST_TEST_INFO("trial " << trial << " turn " << static_cast<int>(turn));
    if (turn == rk::Sign::positive) {
      BOOST_TEST(!e.has_value());
      ++accepted;
    } else {
      BOOST_TEST_REQUIRE(e.has_value());
      BOOST_TEST((e->reason() == (turn == rk::Sign::zero ? Reason::collinear : Reason::not_convex)));
      BOOST_TEST(e->vertex() == 1);
      ++(turn == rk::Sign::zero ? collinear : reflex);
    }
  }
  BOOST_TEST_MESSAGE("nearly collinear vertex: " << accepted << " accepted, " << reflex << " reflex, "
                                                 << collinear << " exactly collinear");
  // Each outcome must actually occur, or the test does not exercise the exact decision.
  BOOST_TEST(accepted > 0);
  BOOST_TEST(reflex > 0);
  BOOST_TEST(collinear > 0);
}

// Closed forms: a 3-4-5 right triangle has r = (3 + 4 - 5) / 2 = 1; a w x h rectangle
// min(w, h) / 2 (the optimum is not unique: any centre on the mid-line); a regular hexagon of
// side s has s sqrt(3) / 2. The same shapes 1e6 m from the origin give the same radii to the
// rounding of their coordinates (1e6 has ulp 1.2e-10, hence 1e-9 relative).
BOOST_AUTO_TEST_CASE(inscribed_radius_matches_closed_forms) {
  const auto shifted = [](std::vector<Point2> polygon, double dx, double dy) {
    for (auto& p : polygon) p = {p.x + dx, p.y + dy};
    return polygon;
  };
  const std::vector<Point2> triangle{{0, 0}, {4, 0}, {0, 3}};
  const std::vector<Point2> rectangle{{0, 0}, {5, 0}, {5, 0.1}, {0, 0.1}};
  std::vector<Point2> hexagon;
  for (int k = 0; k < 6; ++k) {
    const double angle = std::numbers::pi / 3.0 * k;
    hexagon.push_back({2.0 * std::cos(angle), 2.0 * std::sin(angle)});
  }
  BOOST_TEST(rk::inscribed_radius(triangle) == 1.0, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(rk::inscribed_radius(rectangle) == 0.05, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(rk::inscribed_radius(hexagon) == std::sqrt(3.0), boost::test_tools::tolerance(1e-14));
  BOOST_TEST(rk::inscribed_radius(shifted(triangle, 1e6, -1e6)) == 1.0,
             boost::test_tools::tolerance(1e-9));
  BOOST_TEST(rk::inscribed_radius(shifted(rectangle, -1e6, 1e6)) == 0.05,
             boost::test_tools::tolerance(1e-9));
  // A 1 x 0.01 sliver turned by 30°: half its short side.
  const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
  std::vector<Point2> sliver;
  for (const Point2& p : std::vector<Point2>{{0, 0}, {1, 0}, {1, 0.01}, {0, 0.01}}) {
    sliver.push_back({c * p.x - s * p.y, s * p.x + c * p.y});
  }
  BOOST_TEST(rk::inscribed_radius(sliver) == 0.005,
             boost::test_tools::tolerance(1e-12));
}
