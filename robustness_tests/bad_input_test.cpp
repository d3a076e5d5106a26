#define BOOST_TEST_MODULE robustness_bad_input
#include <boost/test/unit_test.hpp>

// Bad input is rejected at the API boundary with a typed error whose message names the culprit
// (house style 7):
//   * ConvexPolygon::make throws InvalidPolygon for NaN/inf coordinates, repeated vertices,
//     collinear vertices (including zero-area polygons), clockwise order under require_ccw and
//     reflex vertices; the message names the polygon and the vertex (convex_polygon.hpp);
//   * contact::evaluate_pair throws std::invalid_argument when kn or H is not finite and
//     positive (potential_contact.hpp), under every policy and through both overloads, and
//     the workspace stays usable afterwards.
// Numbered edge cases first, then the same corruptions planted in generated adversarial
// polygons (slivers, 1e6 m offsets, 0.01 m edges), where the expected answer is decided by an
// independent exact orientation in GMP rationals written here.

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/generators/pair_generators.hpp"
#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace {

namespace rc = rockcontact;
namespace rb = rockcontact::robustness;
namespace rk = rockcontact::kernel;
using rk::ConvexPolygon;
using rk::InvalidPolygon;
using rk::Point2;
using rk::VertexOrder;
using Reason = InvalidPolygon::Reason;

constexpr std::uint64_t seed = 0x5eed'2024'0611ull;
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();
constexpr double infinity = std::numeric_limits<double>::infinity();

std::optional<InvalidPolygon> rejection(const std::string& name, const std::vector<Point2>& vertices,
                                        VertexOrder order = VertexOrder::require_ccw) {
  try {
    ConvexPolygon::make(name, vertices, order);
  } catch (const InvalidPolygon& e) {
    return e;
  }
  return std::nullopt;
}

// The error names the polygon, and the vertex when there is one ("polygon NAME, vertex I").
void expect_rejection(const std::string& name, const std::vector<Point2>& vertices, Reason reason,
                      std::ptrdiff_t vertex, VertexOrder order = VertexOrder::require_ccw) {
  BOOST_TEST_CONTEXT(name) {
    const std::optional<InvalidPolygon> e = rejection(name, vertices, order);
    BOOST_TEST_REQUIRE(e.has_value());
    BOOST_TEST(static_cast<int>(e->reason()) == static_cast<int>(reason));
    BOOST_TEST(e->vertex() == vertex);
    BOOST_TEST(e->polygon() == name);
    const std::string message = e->what();
    BOOST_TEST(message.find("polygon " + name) != std::string::npos, message);
    if (vertex >= 0) {
      BOOST_TEST(message.find("vertex " + std::to_string(vertex)) != std::string::npos, message);
    }
  }
}

int exact_orientation(const Point2& p, const Point2& q, const Point2& r) {
  const mpq_class ux = mpq_class(q.x) - mpq_class(p.x), uy = mpq_class(q.y) - mpq_class(p.y);
  const mpq_class vx = mpq_class(r.x) - mpq_class(p.x), vy = mpq_class(r.y) - mpq_class(p.y);
  return sgn(mpq_class(ux * vy - uy * vx));
}

// Exact turn at every vertex of a closed polygon.
std::vector<int> turns(const std::vector<Point2>& v) {
  std::vector<int> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    out.push_back(exact_orientation(v[(i + v.size() - 1) % v.size()], v[i], v[(i + 1) % v.size()]));
  }
  return out;
}

}  // namespace

// Numbered edge cases: what a user typing a polygon gets wrong, near the origin and 1e6 m away.
BOOST_AUTO_TEST_CASE(polygon_edge_cases) {
  const double f = 1e6;
  // 1-3: non-finite coordinates, at the first offending vertex.
  expect_rejection("case1_nan", {{0, 0}, {1, 0}, {1, not_a_number}, {0, 1}}, Reason::non_finite, 2);
  expect_rejection("case2_inf", {{infinity, 0}, {1, 0}, {1, 1}}, Reason::non_finite, 0);
  expect_rejection("case3_minus_inf_far", {{f, f}, {f + 1, f}, {f + 1, -infinity}, {f, f + 1}}, Reason::non_finite, 2);
  // 4-6: duplicates: a zero-length edge, a closed ring (first vertex repeated at the end), a
  // non-adjacent repeat; the later index is named.
  expect_rejection("case4_zero_length_edge", {{0, 0}, {1, 0}, {1, 0}, {1, 1}}, Reason::repeated_vertex, 2);
  expect_rejection("case5_closed_ring", {{f, f}, {f + 1, f}, {f + 1, f + 1}, {f, f}}, Reason::repeated_vertex, 3);
  expect_rejection("case6_repeat_apart", {{0, 0}, {2, 0}, {0, 0.5}, {2, 2}, {0, 0.5}}, Reason::repeated_vertex, 4);
  // 7-9: zero area and collinear vertices (dyadic, so exactly collinear).
  expect_rejection("case7_zero_area", {{0.5, 0.25}, {1.5, 0.75}, {3.5, 1.75}}, Reason::collinear, 0);
  expect_rejection("case8_zero_area_far", {{f, f}, {f + 0.125, f + 0.25}, {f + 0.5, f + 1}}, Reason::collinear, 0);
  expect_rejection("case9_midpoint", {{0, 0}, {1, 0}, {1, 1}, {0.5, 1}, {0, 1}}, Reason::collinear, 3);
  // 10-11: clockwise under require_ccw names the polygon as a whole; normalise accepts it.
  expect_rejection("case10_clockwise", {{0, 0}, {0, 1}, {1, 1}, {1, 0}}, Reason::clockwise, -1);
  expect_rejection("case11_clockwise_sliver", {{0, 0}, {1, 1e-9}, {2, 0}}, Reason::clockwise, -1);
  BOOST_TEST(ConvexPolygon::make("case11_normalised", {{0, 0}, {1, 1e-9}, {2, 0}}, VertexOrder::normalise).reversed());
  // 12-13: a reflex vertex (the one turning against the others), also when normalising.
  expect_rejection("case12_reflex", {{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}}, Reason::not_convex, 3);
  expect_rejection("case13_reflex_cw", {{0, 2}, {1, 1}, {2, 2}, {2, 0}, {0, 0}}, Reason::not_convex, 1,
                   VertexOrder::normalise);
  // 14: fewer than three vertices.
  expect_rejection("case14_segment", {{0, 0}, {1, 1}}, Reason::too_few_vertices, -1);
}

// The same corruptions planted in generated polygons of every family. Each corruption is
// checked with the exact orientation above to produce exactly the intended defect (else the
// case is skipped and not counted); a minimum count per kind keeps the test honest.
BOOST_AUTO_TEST_CASE(corrupted_generated_polygons) {
  constexpr std::size_t per_family = 300;
  std::size_t non_finite = 0, repeated = 0, clockwise = 0, collinear = 0, reflex = 0;
  for (rb::Family family : rb::all_families) {
    for (std::size_t index = 0; index < per_family; ++index) {
      const std::vector<Point2> good = rb::generate_pair(family, seed, index).cp;
      const std::size_t n = good.size();
      const std::size_t i = index % n;
      const std::string name = std::string(rb::to_string(family)) + "[" + std::to_string(index) + "].cp";

      std::vector<Point2> bad = good;
      bad[i].y = index % 3 == 0 ? not_a_number : (index % 3 == 1 ? infinity : -infinity);
      expect_rejection(name, bad, Reason::non_finite, static_cast<std::ptrdiff_t>(i));
      ++non_finite;

      bad = good;
      bad.insert(bad.begin() + static_cast<std::ptrdiff_t>(i) + 1, good[i]);
      expect_rejection(name, bad, Reason::repeated_vertex, static_cast<std::ptrdiff_t>(i) + 1);
      ++repeated;

      expect_rejection(name, std::vector<Point2>(good.rbegin(), good.rend()), Reason::clockwise, -1);
      ++clockwise;

      // The midpoint of edge i inserted after vertex i, when it is exactly representable.
      const Point2& a = good[i];
      const Point2& b = good[(i + 1) % n];
      const Point2 mid{(a.x + b.x) / 2, (a.y + b.y) / 2};
      const bool between = std::min(a.x, b.x) <= mid.x && mid.x <= std::max(a.x, b.x) &&
                           std::min(a.y, b.y) <= mid.y && mid.y <= std::max(a.y, b.y);
      if (exact_orientation(a, mid, b) == 0 && between && !(mid == a) && !(mid == b)) {
        bad = good;
        bad.insert(bad.begin() + static_cast<std::ptrdiff_t>(i) + 1, mid);
        expect_rejection(name, bad, Reason::collinear, static_cast<std::ptrdiff_t>(i) + 1);
        ++collinear;
      }

      // Vertex i pushed half its depth past the chord of its neighbours, when that makes it the
      // only right turn of a polygon with at least 4 vertices.
      if (n >= 4) {
        const Point2& prev = good[(i + n - 1) % n];
        const Point2& next = good[(i + 1) % n];
        const Point2 chord_mid{prev.x + (next.x - prev.x) / 2, prev.y + (next.y - prev.y) / 2};
        bad = good;
        bad[i] = {a.x + 1.5 * (chord_mid.x - a.x), a.y + 1.5 * (chord_mid.y - a.y)};
        const std::vector<int> t = turns(bad);
        bool only_i = t[i] < 0;
        for (std::size_t k = 0; k < n; ++k) only_i = only_i && (k == i || t[k] > 0);
        if (only_i) {
          expect_rejection(name, bad, Reason::not_convex, static_cast<std::ptrdiff_t>(i));
          ++reflex;
        }
      }
    }
  }
  BOOST_TEST_MESSAGE("corrupted generated polygons: " << non_finite << " non-finite, " << repeated
                                                      << " repeated, " << clockwise << " clockwise, "
                                                      << collinear << " collinear, " << reflex << " reflex");
  BOOST_TEST(collinear >= 500u);
  BOOST_TEST(reflex >= 1000u);
}

BOOST_AUTO_TEST_CASE(contact_parameters_must_be_finite_and_positive) {
  const ConvexPolygon cp = ConvexPolygon::make("cp", {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  const ConvexPolygon tp = ConvexPolygon::make("tp", {{0.5, 0.5}, {2, 0.5}, {2, 2}, {0.5, 2}});
  const auto with = [](double kn, double H) {
    rc::contact::PotentialContactParams p = rc::contact::default_potential_contact_params();
    p.kn = kn;
    p.H = H;
    return p;
  };
  const std::vector<double> bad_values{0.0, -0.0, -1.0, -1e7, not_a_number, infinity, -infinity};
  rc::contact::PairWorkspace workspace;
  rc::contact::PairResult result;
  for (const char* field : {"kn", "H"}) {
    for (double value : bad_values) {
      const bool kn = std::string(field) == "kn";
      const rc::contact::PotentialContactParams params = with(kn ? value : 1e7, kn ? 1.0 : value);
      BOOST_TEST_CONTEXT(field << " = " << value) {
        const auto check_message = [&](const std::invalid_argument& e) {
          return std::string(e.what()).find(field) != std::string::npos;
        };
        BOOST_CHECK_EXCEPTION(rc::contact::evaluate_pair(rk::PolicyKind::filtered, cp, tp, params),
                              std::invalid_argument, check_message);
        BOOST_CHECK_EXCEPTION(rc::contact::evaluate_pair<rk::Float>(cp, tp, params, workspace, result),
                              std::invalid_argument, check_message);
        BOOST_CHECK_EXCEPTION(rc::contact::evaluate_pair<rk::Filtered>(cp, tp, params, workspace, result),
                              std::invalid_argument, check_message);
        BOOST_CHECK_EXCEPTION(rc::contact::evaluate_pair<rk::Exact>(cp, tp, params, workspace, result),
                              std::invalid_argument, check_message);
      }
    }
  }
  // The workspace is still usable, and the smallest positive (subnormal) values are valid input.
  rc::contact::evaluate_pair<rk::Filtered>(cp, tp, with(1e7, 1.0), workspace, result);
  BOOST_TEST(static_cast<int>(result.status) == static_cast<int>(rk::Overlap::overlap));
  BOOST_TEST(result.force.x < 0.0);
  BOOST_CHECK_NO_THROW(rc::contact::evaluate_pair<rk::Filtered>(
      cp, tp, with(std::numeric_limits<double>::denorm_min(), 1.0), workspace, result));
}
