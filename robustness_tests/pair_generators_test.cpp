#define BOOST_TEST_MODULE robustness_pair_generators
#include <boost/test/unit_test.hpp>

// The pair generators (pair_generators.hpp): every pair is valid input for ConvexPolygon::make,
// each family has the property it is named after, and a pair depends on (family, seed, index)
// only, identically on every platform (a fingerprint of the first pairs is pinned below).
//
// The family properties are checked with exact predicates (orientation under the Exact policy)
// or exact comparisons of doubles; the two measured ones (wedge angles, near-parallel angles)
// state their tolerance where they are checked.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "pair_generators.hpp"
#include "rockcontact/kernel/convex_polygon.hpp"
#include "rockcontact/kernel/entrance_block.hpp"
#include "rockcontact/kernel/number_policy.hpp"
#include "rockcontact/kernel/predicates.hpp"

namespace {

namespace rc = rockcontact;
namespace rb = rockcontact::robustness;
using rc::kernel::ConvexPolygon;
using rc::kernel::Exact;
using rc::kernel::Overlap;
using rc::kernel::Point2;
using rc::kernel::Sign;

constexpr std::uint64_t seed = 0x5eed'2024'0611ull;
constexpr std::size_t pairs_per_family = 2000;

using Polygon = std::vector<Point2>;

std::string label(rb::Family family, std::size_t index) {
  return std::string(rb::to_string(family)) + "[" + std::to_string(index) + "]";
}

Sign orient(const Point2& p, const Point2& q, const Point2& r) {
  return rc::kernel::orientation<Exact>(p, q, r);
}

// Is v on the closed segment [a, b]? Exact: collinearity by the exact predicate, then the
// coordinate ranges (exact comparisons of doubles).
bool on_segment(const Point2& a, const Point2& b, const Point2& v) {
  return orient(a, b, v) == Sign::zero && std::min(a.x, b.x) <= v.x && v.x <= std::max(a.x, b.x) &&
         std::min(a.y, b.y) <= v.y && v.y <= std::max(a.y, b.y);
}

template <class Visit>
bool any_edge_pair(const Polygon& cp, const Polygon& tp, Visit visit) {
  for (std::size_t i = 0; i < cp.size(); ++i) {
    for (std::size_t j = 0; j < tp.size(); ++j) {
      if (visit(cp[i], cp[(i + 1) % cp.size()], tp[j], tp[(j + 1) % tp.size()])) return true;
    }
  }
  return false;
}

bool tp_vertex_on_cp_edge(const rb::PolygonPair& p) {
  return any_edge_pair(p.cp, p.tp, [](const Point2& a, const Point2& b, const Point2& v, const Point2&) {
    return on_segment(a, b, v);
  });
}

bool shares_vertex(const rb::PolygonPair& p) {
  return std::any_of(p.tp.begin(), p.tp.end(), [&](const Point2& v) {
    return std::find(p.cp.begin(), p.cp.end(), v) != p.cp.end();
  });
}

bool has_collinear_edges(const rb::PolygonPair& p) {
  return any_edge_pair(p.cp, p.tp, [](const Point2& a, const Point2& b, const Point2& t0, const Point2& t1) {
    return orient(a, b, t0) == Sign::zero && orient(a, b, t1) == Sign::zero;
  });
}

// Smallest interior angle (rad) of a polygon; libm's atan2 is accurate to about 1 ulp.
double smallest_angle(const Polygon& poly) {
  double best = M_PI;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2& p = poly[(i + poly.size() - 1) % poly.size()];
    const Point2& v = poly[i];
    const Point2& q = poly[(i + 1) % poly.size()];
    const double ax = p.x - v.x, ay = p.y - v.y, bx = q.x - v.x, by = q.y - v.y;
    best = std::min(best, std::atan2(std::fabs(ax * by - ay * bx), ax * bx + ay * by));
  }
  return best;
}

double shortest_edge(const Polygon& poly) {
  double best = HUGE_VAL;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2& p = poly[i];
    const Point2& q = poly[(i + 1) % poly.size()];
    best = std::min(best, std::hypot(q.x - p.x, q.y - p.y));
  }
  return best;
}

// Smallest |sin| of the angle between a cp edge and an anti-parallel tp edge. Unit vectors
// in double: the cross product carries an absolute error of a few 1e-16.
double most_antiparallel_sine(const rb::PolygonPair& p) {
  double best = 1.0;
  any_edge_pair(p.cp, p.tp, [&](const Point2& a, const Point2& b, const Point2& t0, const Point2& t1) {
    const double ex = b.x - a.x, ey = b.y - a.y, fx = t1.x - t0.x, fy = t1.y - t0.y;
    const double scale = std::hypot(ex, ey) * std::hypot(fx, fy);
    if (ex * fx + ey * fy < 0.0) best = std::min(best, std::fabs(ex * fy - ey * fx) / scale);
    return false;
  });
  return best;
}

bool on_grid(double x, int exponent) {
  const double scaled = std::ldexp(x, -exponent);
  return scaled == std::trunc(scaled);
}

bool all_coordinates(const rb::PolygonPair& p, auto predicate) {
  for (const Polygon* poly : {&p.cp, &p.tp}) {
    for (const Point2& v : *poly) {
      if (!predicate(v.x) || !predicate(v.y)) return false;
    }
  }
  return true;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_pair_is_valid_and_has_its_family_property) {
  BOOST_TEST_MESSAGE("seed " << seed << ", " << pairs_per_family << " pairs per family");
  for (rb::Family family : rb::all_families) {
    std::array<std::size_t, 3> verdicts{};
    std::size_t on_edge = 0;
    for (std::size_t i = 0; i < pairs_per_family; ++i) {
      const rb::PolygonPair pair = rb::generate_pair(family, seed, i);
      const std::string name = label(family, i);
      ConvexPolygon cp = ConvexPolygon::make(name + ".cp", pair.cp);
      ConvexPolygon tp = ConvexPolygon::make(name + ".tp", pair.tp);
      ++verdicts[static_cast<std::size_t>(rc::kernel::classify_overlap<Exact>(cp, tp))];
      on_edge += tp_vertex_on_cp_edge(pair);
      switch (family) {
        case rb::Family::vertex_on_vertex:
          BOOST_TEST_REQUIRE(shares_vertex(pair), name << ": no shared vertex");
          break;
        case rb::Family::edge_on_edge:
          BOOST_TEST_REQUIRE(has_collinear_edges(pair), name << ": no collinear edges");
          break;
        case rb::Family::offset_1e6:
          BOOST_TEST_REQUIRE(all_coordinates(pair, [](double x) {
            return on_grid(x, -33) && std::fabs(std::fabs(x) - 1e6) < 10.0;
          }), name << ": not on the 2^-33 grid near (1e6, -1e6)");
          break;
        case rb::Family::lattice_touch:
          BOOST_TEST_REQUIRE(all_coordinates(pair, [](double x) { return on_grid(x, -3); }),
                             name << ": off the lattice");
          break;
        case rb::Family::wedge_5deg:
        case rb::Family::wedge_0_5deg: {
          // The apex angle is 2 atan(h) for the rounded constant h, and the corners are
          // rounded to ~1e-16 m on ~1e-2..1e-3 m half-widths: within 1e-9 relative.
          const double apex = (family == rb::Family::wedge_5deg ? 5.0 : 0.5) * M_PI / 180.0;
          for (const Polygon* poly : {&pair.cp, &pair.tp}) {
            BOOST_TEST_REQUIRE(std::fabs(smallest_angle(*poly) - apex) <= 1e-9 * apex,
                               name << ": apex " << smallest_angle(*poly));
          }
          break;
        }
        case rb::Family::near_parallel:
          // Generated at 1.8e-12..9.5e-7 rad; measured with an error of a few 1e-16.
          BOOST_TEST_REQUIRE(most_antiparallel_sine(pair) <= 1e-6, name << ": no near-parallel edges");
          break;
        case rb::Family::short_edges:
          // Chamfers are 0.01 m (rounded), or shorter where capped at 0.3 of a short edge.
          BOOST_TEST_REQUIRE(std::min(shortest_edge(pair.cp), shortest_edge(pair.tp)) <= 0.0100001,
                             name << ": no chamfer edge");
          break;
        case rb::Family::random:
        case rb::Family::vertex_on_edge: break;
      }
    }
    const double n = static_cast<double>(pairs_per_family);
    BOOST_TEST_MESSAGE(rb::to_string(family)
                       << ": separate " << verdicts[0] << ", touch " << verdicts[1] << ", overlap "
                       << verdicts[2] << ", tp vertex exactly on a cp edge " << on_edge);
    if (family == rb::Family::vertex_on_edge) {
      // Two of the four variants keep V on the edge; the shifted ones move it off.
      BOOST_TEST(on_edge / n >= 0.4);
    }
    if (family == rb::Family::random || family == rb::Family::lattice_touch ||
        family == rb::Family::vertex_on_edge) {
      for (std::size_t v = 0; v < verdicts.size(); ++v) {
        BOOST_TEST(verdicts[v] / n >= 0.05, rb::to_string(family)
                                              << ": verdict " << rc::kernel::to_string(static_cast<Overlap>(v))
                                              << " in only " << verdicts[v] << " pairs");
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(a_pair_depends_on_family_seed_and_index_only) {
  for (rb::Family family : rb::all_families) {
    const rb::PolygonPair late = rb::generate_pair(family, seed, 12345);
    rb::generate_pair(family, seed, 0);
    const rb::PolygonPair again = rb::generate_pair(family, seed, 12345);
    BOOST_TEST((late.cp == again.cp && late.tp == again.tp), rb::to_string(family));
    const rb::PolygonPair other = rb::generate_pair(family, seed + 1, 12345);
    BOOST_TEST(!(late.cp == other.cp && late.tp == other.tp), rb::to_string(family));
  }
}

// FNV-1a over the bit patterns of every coordinate of the first 64 pairs of every family. The
// generators use only correctly rounded IEEE operations and the standard's mt19937_64, so this
// number is the same on every platform; a change means the streams changed (update it and say
// why in the commit).
BOOST_AUTO_TEST_CASE(the_streams_are_pinned) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  const auto add = [&](double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    for (int b = 0; b < 64; b += 8) {
      hash ^= (bits >> b) & 0xffu;
      hash *= 0x100000001b3ull;
    }
  };
  for (rb::Family family : rb::all_families) {
    for (std::uint64_t i = 0; i < 64; ++i) {
      const rb::PolygonPair pair = rb::generate_pair(family, 1, i);
      for (const Polygon* poly : {&pair.cp, &pair.tp}) {
        add(static_cast<double>(poly->size()));
        for (const Point2& v : *poly) add(v.x), add(v.y);
      }
    }
  }
  BOOST_TEST_MESSAGE("stream fingerprint " << std::hex << hash);
  BOOST_TEST(hash == 0x0c2f'b59a'79a7'5ef6ull);
}

BOOST_AUTO_TEST_CASE(hull_snap_and_exact_translation) {
  // Collinear and repeated points are dropped; the hull is CCW from the lowest-leftmost point.
  const Polygon hull = rb::convex_hull({{1, 1}, {0, 0}, {2, 0}, {1, 0}, {2, 2}, {0, 2}, {2, 0}, {0, 1}});
  BOOST_TEST((hull == Polygon{{0, 0}, {2, 0}, {2, 2}, {0, 2}}));
  BOOST_TEST(rb::convex_hull({{0, 0}, {1, 1}, {3, 3}}).size() == 2u);

  const rb::PolygonPair pair{{{0.1, 0.1}, {1.1, 0.1}, {0.6, 0.9}}, {{0.3, 0.3}, {1.3, 0.3}, {0.8, 1.3}}, {}};
  // 0.1 is not a multiple of 2^-33: translating it by 1e6 rounds.
  BOOST_TEST(!rb::translate_exactly(pair, {1e6, -1e6}).has_value());
  const auto snapped = rb::snap_to_grid(pair, -33);
  BOOST_TEST_REQUIRE(snapped.has_value());
  const auto far = rb::translate_exactly(*snapped, {1e6, -1e6});
  BOOST_TEST_REQUIRE(far.has_value());
  BOOST_TEST(far->cp[0].x - 1e6 == snapped->cp[0].x);
  // A grid so coarse that the triangle collapses to a segment.
  BOOST_TEST(!rb::snap_to_grid({{{0, 0}, {4, 0}, {2, 0.25}}, pair.tp, {}}, 1).has_value());
}
