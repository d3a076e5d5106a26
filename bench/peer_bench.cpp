// Pair-level cost against peers: our kernel and contact force beside Box2D's polygon manifold,
// CGAL's exact Boolean intersection and Minkowski sum, and a plain double Sutherland-Hodgman
// clip, all on the same pairs.
//
//   classify/<policy>/<pool>     kernel::classify_overlap (the verdict alone)
//   overlap_ip/<policy>/<pool>   compute_intersection_polygon (the verdict and the symbolic
//                                IP in one clip), then construct_points for overlapping
//                                pairs (what evaluate_pair does before its force)
//   force_exact/<policy>/<pool>  contact::evaluate_pair, exact demarcation
//   force_paper/<policy>/<pool>  contact::evaluate_pair, paper demarcation
//   naive_clip/<pool>            examples/naive_clipper/naive_clip.hpp: TP clipped by CP's edge half-planes;
//                                no filter, no symbolic vertices (the naive reference)
//   box2d_manifold/3-8           b2CollidePolygons (Box2D 2.4, float): the contact manifold
//   cgal_intersection/<pool>     CGAL::intersection of two Polygon_2, Epeck kernel
//   cgal_minkowski/<pool>        CGAL::minkowski_sum_2(CP, -TP) and the side of the origin, Epeck
//                                (the overlap verdict the way a Minkowski-sum code asks it)
//
// Pools of 512 pairs from an mt19937_64 seeded with `seed` + the pool's vertex cap (`seed` is
// printed in the context): `3-8` has 3 to 8 vertices per polygon, `3-12` 3 to 12. Box2D caps at
// b2_maxPolygonVertices vertices (8 in the Debian build), so it runs on `3-8` only. Each is
// inscribed in a random ellipse (so it is strictly convex) with angles stratified so that no
// two vertices are closer than a fifth of the mean angular gap; TP's centre is placed at a
// random fraction of the sum of the two circumradii, tuned so that about half of the pairs
// overlap. The exact overlap fraction of each pool (and the fraction of pairs on which
// Filtered fell back to exact arithmetic) is printed in the context and stored in the JSON.
//
// One iteration is a pass over the whole pool, so every contender is timed on the same pairs;
// per_pair (CPU seconds per pair; 53.2n = 53.2 ns) is the figure to compare. interval_rate and
// fallback_rate are the calls that reached the interval and the exact stage, per predicate call
// (kernel/core/predicate_stats.hpp); Exact shares Filtered's staged signs.
// Every input is converted to each contender's own types before timing (Box2D's Set computes a
// hull and normals; CGAL's polygons hold lazy exact points), so only the query is timed.
// Box2D's polygon skin (m_radius, 0.01 m) is set to zero so that it answers the same geometric
// question as the others: do the polygons themselves overlap.

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/minkowski_sum_2.h>
#include <benchmark/benchmark.h>
#include <box2d/box2d.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/demarcation.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/2d/intersection_polygon.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "naive_clip.hpp"
#include "run_passes.hpp"

namespace {

using rockcontact::bench::run_passes;

namespace rk = rockcontact::kernel;
namespace rc = rockcontact::contact;

using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalPolygon = CGAL::Polygon_2<Epeck>;
using CgalPolygonWithHoles = CGAL::Polygon_with_holes_2<Epeck>;

constexpr std::uint64_t seed = 0x0006'9ee7'2026ull;
constexpr std::size_t pool_size = 512;
// TP's centre lies at distance u * reach * (r_cp + r_tp) from CP's, u uniform in [0, 1). The
// polygons are inscribed in ellipses with aspect in [0.5, 1], so they overlap for most of the
// lower part of that range and never near the top; 1.45 gives about one half.
constexpr double reach = 1.45;

struct Pool {
  std::string name;
  std::vector<rk::ConvexPolygon> cp, tp;
  std::vector<CgalPolygon> cgal_cp, cgal_tp, cgal_minus_tp;
  std::vector<b2PolygonShape> box_cp, box_tp;  // empty when a polygon exceeds Box2D's cap
  double overlap_fraction = 0.0;                 // exact verdict `overlap`
  double fallback_pair_fraction = 0.0;           // pairs where Filtered evaluate_pair fell back
};

struct Circle {
  rk::Point2 centre;
  double radius = 0.0;  // m
};

// A strictly convex CCW polygon with `n` vertices on an ellipse around `circle.centre`.
std::vector<rk::Point2> random_convex(std::mt19937_64& rng, int n, const Circle& circle) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double two_pi = 2.0 * std::numbers::pi;
  const double aspect = 0.5 + 0.5 * unit(rng);
  const double tilt = two_pi * unit(rng);
  const double phase = two_pi * unit(rng);
  std::vector<rk::Point2> vertices;
  for (int k = 0; k < n; ++k) {
    // Stratified angles: the k-th vertex in the k-th sector, jittered over 80% of it.
    const double t = phase + two_pi * (k + 0.8 * unit(rng)) / n;
    const double ex = circle.radius * std::cos(t);
    const double ey = aspect * circle.radius * std::sin(t);
    vertices.push_back({circle.centre.x + ex * std::cos(tilt) - ey * std::sin(tilt),
                        circle.centre.y + ex * std::sin(tilt) + ey * std::cos(tilt)});
  }
  return vertices;
}

CgalPolygon to_cgal(const rk::ConvexPolygon& polygon, double sign) {
  CgalPolygon out;
  for (const rk::Point2& v : polygon.vertices()) out.push_back(Epeck::Point_2(sign * v.x, sign * v.y));
  return out;
}

b2PolygonShape to_box2d(const rk::ConvexPolygon& polygon) {
  std::vector<b2Vec2> points;
  for (const rk::Point2& v : polygon.vertices())
    points.emplace_back(static_cast<float>(v.x), static_cast<float>(v.y));
  b2PolygonShape shape;
  shape.Set(points.data(), static_cast<int32>(points.size()));
  shape.m_radius = 0.0f;
  return shape;
}

Pool make_pool(std::string name, int max_vertices) {
  Pool pool;
  pool.name = std::move(name);
  std::mt19937_64 rng(seed + static_cast<std::uint64_t>(max_vertices));
  std::uniform_int_distribution<int> vertex_count(3, max_vertices);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t i = 0; i < pool_size; ++i) {
    const Circle cp_circle{{0.0, 0.0}, 0.5 + unit(rng)};
    const double tp_radius = 0.5 + unit(rng);
    const double distance = reach * unit(rng) * (cp_circle.radius + tp_radius);
    const double direction = 2.0 * std::numbers::pi * unit(rng);
    const Circle tp_circle{{distance * std::cos(direction), distance * std::sin(direction)}, tp_radius};
    pool.cp.push_back(rk::ConvexPolygon::make("cp", random_convex(rng, vertex_count(rng), cp_circle)));
    pool.tp.push_back(rk::ConvexPolygon::make("tp", random_convex(rng, vertex_count(rng), tp_circle)));
  }
  const bool box2d_fits = max_vertices <= b2_maxPolygonVertices;
  const rc::PotentialContactParams params = rc::default_potential_contact_params();
  rc::PairWorkspace workspace;
  rc::PairResult result;
  std::size_t overlapping = 0, fell_back = 0;
  for (std::size_t i = 0; i < pool_size; ++i) {
    pool.cgal_cp.push_back(to_cgal(pool.cp[i], 1.0));
    pool.cgal_tp.push_back(to_cgal(pool.tp[i], 1.0));
    pool.cgal_minus_tp.push_back(to_cgal(pool.tp[i], -1.0));
    if (box2d_fits) {
      pool.box_cp.push_back(to_box2d(pool.cp[i]));
      pool.box_tp.push_back(to_box2d(pool.tp[i]));
    }
    if (rk::classify_overlap<rk::Exact>(pool.cp[i], pool.tp[i]) == rk::Overlap::overlap) ++overlapping;
    rc::evaluate_pair<rk::Filtered>(pool.cp[i], pool.tp[i], params, workspace, result);
    if (result.fallbacks > 0) ++fell_back;
  }
  pool.overlap_fraction = static_cast<double>(overlapping) / pool_size;
  pool.fallback_pair_fraction = static_cast<double>(fell_back) / pool_size;
  return pool;
}

template <rk::NumberPolicy Policy>
void classify(benchmark::State& state, const Pool& pool) {
  run_passes(state, pool_size, [&](std::size_t i) {
    benchmark::DoNotOptimize(rk::classify_overlap<Policy>(pool.cp[i], pool.tp[i]));
  });
}

template <rk::NumberPolicy Policy>
void overlap_ip(benchmark::State& state, const Pool& pool) {
  rk::IntersectionPolygon ip;
  rk::ClipWorkspace workspace;
  std::vector<rk::Point2> points;
  run_passes(state, pool_size, [&](std::size_t i) {
    points.clear();
    if (rk::compute_intersection_polygon<Policy>(pool.cp[i], pool.tp[i], ip, workspace) ==
        rk::Overlap::overlap) {
      rk::construct_points<Policy>(pool.cp[i], pool.tp[i], ip, points);
    }
    benchmark::DoNotOptimize(points.data());
  });
}

template <rk::NumberPolicy Policy>
void force(benchmark::State& state, const Pool& pool, rk::Demarcation demarcation) {
  rc::PotentialContactParams params = rc::default_potential_contact_params();
  params.demarcation = demarcation;
  rc::PairWorkspace workspace;
  rc::PairResult result;
  run_passes(state, pool_size, [&](std::size_t i) {
    rc::evaluate_pair<Policy>(pool.cp[i], pool.tp[i], params, workspace, result);
    benchmark::DoNotOptimize(result.force);
  });
}

void naive(benchmark::State& state, const Pool& pool) {
  std::vector<rk::Point2> out, scratch;
  run_passes(state, pool_size, [&](std::size_t i) {
    naive::clip_polygon(pool.cp[i].vertices(), pool.tp[i].vertices(), out, scratch);
    benchmark::DoNotOptimize(out.data());
  });
}

void box2d_manifold(benchmark::State& state, const Pool& pool) {
  b2Transform identity;
  identity.SetIdentity();
  b2Manifold manifold;
  run_passes(state, pool.box_cp.size(), [&](std::size_t i) {
    b2CollidePolygons(&manifold, &pool.box_cp[i], identity, &pool.box_tp[i], identity);
    benchmark::DoNotOptimize(manifold.pointCount);
  });
}

void cgal_intersection(benchmark::State& state, const Pool& pool) {
  std::vector<CgalPolygonWithHoles> pieces;
  run_passes(state, pool_size, [&](std::size_t i) {
    pieces.clear();
    CGAL::intersection(pool.cgal_cp[i], pool.cgal_tp[i], std::back_inserter(pieces));
    benchmark::DoNotOptimize(pieces.data());
  });
}

void cgal_minkowski(benchmark::State& state, const Pool& pool) {
  const Epeck::Point_2 origin(0, 0);
  run_passes(state, pool_size, [&](std::size_t i) {
    const CgalPolygonWithHoles sum = CGAL::minkowski_sum_2(pool.cgal_cp[i], pool.cgal_minus_tp[i]);
    benchmark::DoNotOptimize(sum.outer_boundary().bounded_side(origin));
  });
}

template <rk::NumberPolicy Policy>
void register_ours(const Pool* pool) {
  const std::string suffix = "/" + std::string(Policy::name) + "/" + pool->name;
  benchmark::RegisterBenchmark(("classify" + suffix).c_str(),
                               [pool](benchmark::State& state) { classify<Policy>(state, *pool); });
  benchmark::RegisterBenchmark(("overlap_ip" + suffix).c_str(),
                               [pool](benchmark::State& state) { overlap_ip<Policy>(state, *pool); });
  benchmark::RegisterBenchmark(("force_exact" + suffix).c_str(), [pool](benchmark::State& state) {
    force<Policy>(state, *pool, rk::Demarcation::exact);
  });
  benchmark::RegisterBenchmark(("force_paper" + suffix).c_str(), [pool](benchmark::State& state) {
    force<Policy>(state, *pool, rk::Demarcation::paper);
  });
}

void register_pool(const Pool* pool) {
  register_ours<rk::Float>(pool);
  register_ours<rk::Filtered>(pool);
  register_ours<rk::Exact>(pool);
  const std::string suffix = "/" + pool->name;
  benchmark::RegisterBenchmark(("naive_clip" + suffix).c_str(),
                               [pool](benchmark::State& state) { naive(state, *pool); });
  if (!pool->box_cp.empty())
    benchmark::RegisterBenchmark(("box2d_manifold" + suffix).c_str(),
                                 [pool](benchmark::State& state) { box2d_manifold(state, *pool); });
  benchmark::RegisterBenchmark(("cgal_intersection" + suffix).c_str(),
                               [pool](benchmark::State& state) { cgal_intersection(state, *pool); });
  benchmark::RegisterBenchmark(("cgal_minkowski" + suffix).c_str(),
                               [pool](benchmark::State& state) { cgal_minkowski(state, *pool); });
  benchmark::AddCustomContext("pool " + pool->name + " overlap_fraction",
                              std::to_string(pool->overlap_fraction));
  benchmark::AddCustomContext("pool " + pool->name + " fallback_pair_fraction",
                              std::to_string(pool->fallback_pair_fraction));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const Pool small = make_pool("3-8", 8);
  const Pool large = make_pool("3-12", 12);
  benchmark::AddCustomContext("pool seed", std::to_string(seed));
  benchmark::AddCustomContext("pool pairs", std::to_string(pool_size));
  register_pool(&small);
  register_pool(&large);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
