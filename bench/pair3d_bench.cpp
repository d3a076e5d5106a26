// 3D pair cost by family: the library's queries beside a naive double kernel and CGAL's exact
// corefinement, all on the same pairs.
//
//   classify/<policy>/<family>   kernel::classify_overlap (the verdict) under Float, Filtered,
//                                Exact
//   volume/<policy>/<family>     kernel::intersection_volume under Filtered, Exact
//   overlap_volume/<policy>/<family>  the verdict, then the volume when overlapping (what the
//                                naive row below computes), under Float, Filtered, Exact
//   overlap_volume_constraints/<policy>/<family>  a contact pass's work on the pair: the
//                                verdict, the volume when overlapping, the generalized contact
//                                constraints (contact_constraints.hpp) when touching or
//                                overlapping; under Float, Filtered, Exact
//   naive_sat_clip_volume/<family>  the naive counterpart: naive SAT, then the naive clip's
//                                volume when it says overlap
//   naive_sat/<family>           naive_clip3d.hpp: the separating axis test in plain double
//   naive_clip_volume/<family>   naive_clip3d.hpp: a clipped by b's face planes (Sutherland-
//                                Hodgman on the face polygons, a cap face per plane), volume by
//                                the divergence theorem, plain double
//   cgal_corefine_volume/<family>  PMP::corefine_and_compute_intersection of the two blocks as
//                                Surface_mesh<Epeck::Point_3> (faces fanned into triangles),
//                                then PMP::volume of the result, converted to double. Corefining
//                                modifies its inputs, so each pair copies its two prepared
//                                meshes first; the copy (a few µs) is inside the time, which is
//                                in milliseconds.
//
// Pools: 64 pairs of each 3D generator family (pair3d_generators.hpp; `random` is the 8-20-point
// random hulls), seed below. One iteration is a pass over the pool; per_pair (CPU seconds per
// pair) is the figure to compare. The context records, per pool, the Exact verdict counts, the
// naive SAT's wrong verdicts and the largest |naive volume - CGAL volume| over the smaller
// block's volume (relative to the intersection itself the error is unbounded: a touching or
// barely pushed pair has a volume near zero).
//
// Adding a library query: one entry in `contenders` (a name and a function of the pool and the
// pair index); every pool gets the row.

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "naive_clip3d.hpp"
#include "rockcontact/generators/pair3d_generators.hpp"
#include "rockcontact/kernel/3d/contact_constraints.hpp"
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/intersection.hpp"
#include "rockcontact/kernel/3d/moments.hpp"
#include "rockcontact/kernel/3d/overlap.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "run_passes.hpp"

namespace {

namespace rb = rockcontact::robustness;
namespace rk = rockcontact::kernel;
namespace PMP = CGAL::Polygon_mesh_processing;
using rockcontact::bench::run_passes;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Epeck::Point_3>;

constexpr std::uint64_t seed = 0x3d'be7c'2026ull;
constexpr std::size_t pool_size = 64;

naive3d::Block to_naive(const rk::ConvexPolyhedron& p) {
  naive3d::Block b;
  for (const rk::Point3& v : p.vertices()) b.vertices.push_back({v.x, v.y, v.z});
  for (const auto& f : p.faces()) b.faces.emplace_back(f.begin(), f.end());
  for (const auto& e : p.edges()) b.edges.push_back({e.first, e.second});
  return b;
}

Mesh to_mesh(const rk::ConvexPolyhedron& p) {
  Mesh m;
  std::vector<Mesh::Vertex_index> index;
  for (const rk::Point3& v : p.vertices()) index.push_back(m.add_vertex(Epeck::Point_3(v.x, v.y, v.z)));
  for (const auto& f : p.faces()) {
    for (std::size_t k = 1; k + 1 < f.size(); ++k) m.add_face(index[f[0]], index[f[k]], index[f[k + 1]]);
  }
  return m;
}

struct Pool {
  std::string name;
  std::vector<rb::PolyhedronPair> pairs;
  std::vector<naive3d::Block> naive_a, naive_b;
  std::vector<Mesh> mesh_a, mesh_b;
};

Pool make_pool(rb::Family3d family) {
  Pool pool;
  pool.name = std::string(rb::to_string(family));
  for (std::size_t i = 0; i < pool_size; ++i) {
    rb::PolyhedronPair pair = rb::generate_pair3d(family, seed, i);
    pool.naive_a.push_back(to_naive(pair.a));
    pool.naive_b.push_back(to_naive(pair.b));
    pool.mesh_a.push_back(to_mesh(pair.a));
    pool.mesh_b.push_back(to_mesh(pair.b));
    pool.pairs.push_back(std::move(pair));
  }
  return pool;
}

double cgal_volume(const Pool& pool, std::size_t i) {
  Mesh a = pool.mesh_a[i], b = pool.mesh_b[i], out;
  if (!PMP::corefine_and_compute_intersection(a, b, out)) return -1.0;
  return CGAL::to_double(PMP::volume(out));
}

struct Contender {
  std::string name;
  std::function<void(const Pool&, std::size_t)> one_pair;
};

template <rk::NumberPolicy Policy>
Contender classify() {
  return {"classify/" + std::string(Policy::name), [](const Pool& pool, std::size_t i) {
            benchmark::DoNotOptimize(rk::classify_overlap<Policy>(pool.pairs[i].a, pool.pairs[i].b));
          }};
}

// The work of a contact pass on one pair: the verdict, the intersection volume when overlapping,
// the generalized contact constraints when touching or overlapping.
template <rk::NumberPolicy Policy>
Contender overlap_volume_constraints() {
  return {"overlap_volume_constraints/" + std::string(Policy::name), [](const Pool& pool, std::size_t i) {
            const rk::ConvexPolyhedron &a = pool.pairs[i].a, &b = pool.pairs[i].b;
            const rk::Overlap verdict = rk::classify_overlap<Policy>(a, b);
            if (verdict == rk::Overlap::overlap) benchmark::DoNotOptimize(rk::intersection_volume<Policy>(a, b));
            if (verdict != rk::Overlap::separate) benchmark::DoNotOptimize(rk::contact_constraints<Policy>(a, b));
          }};
}

// The naive kernel's work, like for like: the verdict, and the volume when overlapping.
template <rk::NumberPolicy Policy>
Contender overlap_volume() {
  return {"overlap_volume/" + std::string(Policy::name), [](const Pool& pool, std::size_t i) {
            const rk::ConvexPolyhedron &a = pool.pairs[i].a, &b = pool.pairs[i].b;
            if (rk::classify_overlap<Policy>(a, b) == rk::Overlap::overlap) {
              benchmark::DoNotOptimize(rk::intersection_volume<Policy>(a, b));
            }
          }};
}

template <rk::NumberPolicy Policy>
Contender volume() {
  return {"volume/" + std::string(Policy::name), [](const Pool& pool, std::size_t i) {
            benchmark::DoNotOptimize(rk::intersection_volume<Policy>(pool.pairs[i].a, pool.pairs[i].b));
          }};
}

const std::vector<Contender> contenders{
    classify<rk::Float>(),
    classify<rk::Filtered>(),
    classify<rk::Exact>(),
    volume<rk::Filtered>(),
    volume<rk::Exact>(),
    overlap_volume<rk::Float>(),
    overlap_volume<rk::Filtered>(),
    overlap_volume<rk::Exact>(),
    overlap_volume_constraints<rk::Float>(),
    overlap_volume_constraints<rk::Filtered>(),
    overlap_volume_constraints<rk::Exact>(),
    {"naive_sat_clip_volume",
     [](const Pool& pool, std::size_t i) {
       if (naive3d::sat_verdict(pool.naive_a[i], pool.naive_b[i]) == naive3d::Verdict::overlap) {
         benchmark::DoNotOptimize(naive3d::clip_volume(pool.naive_a[i], pool.naive_b[i]));
       }
     }},
    {"naive_sat",
     [](const Pool& pool, std::size_t i) {
       benchmark::DoNotOptimize(naive3d::sat_verdict(pool.naive_a[i], pool.naive_b[i]));
     }},
    {"naive_clip_volume",
     [](const Pool& pool, std::size_t i) {
       benchmark::DoNotOptimize(naive3d::clip_volume(pool.naive_a[i], pool.naive_b[i]));
     }},
    {"cgal_corefine_volume", [](const Pool& pool, std::size_t i) { benchmark::DoNotOptimize(cgal_volume(pool, i)); }},
};

// Untimed: what the pool holds and how the naive kernel fares on it.
void describe(const Pool& pool) {
  std::size_t counts[3] = {0, 0, 0};
  std::size_t naive_wrong = 0;
  double worst_volume = 0.0;
  for (std::size_t i = 0; i < pool_size; ++i) {
    const rk::Overlap exact = rk::classify_overlap<rk::Exact>(pool.pairs[i].a, pool.pairs[i].b);
    ++counts[static_cast<int>(exact)];
    if (static_cast<int>(naive3d::sat_verdict(pool.naive_a[i], pool.naive_b[i])) != static_cast<int>(exact)) {
      ++naive_wrong;
    }
    const double reference = cgal_volume(pool, i);
    const double naive = naive3d::clip_volume(pool.naive_a[i], pool.naive_b[i]);
    const double smaller = std::min(rk::moments(pool.pairs[i].a).volume, rk::moments(pool.pairs[i].b).volume);
    if (reference >= 0.0) worst_volume = std::max(worst_volume, std::fabs(naive - reference) / smaller);
  }
  benchmark::AddCustomContext("pool " + pool.name + " separate/touch/overlap",
                              std::to_string(counts[0]) + "/" + std::to_string(counts[1]) + "/" +
                                  std::to_string(counts[2]));
  benchmark::AddCustomContext("pool " + pool.name + " naive_sat wrong verdicts", std::to_string(naive_wrong));
  char worst[32];
  std::snprintf(worst, sizeof worst, "%.2e", worst_volume);
  benchmark::AddCustomContext("pool " + pool.name + " naive volume max |error vs CGAL| / smaller block volume",
                              worst);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  std::vector<Pool> pools;
  for (rb::Family3d family : rb::all_families3d) pools.push_back(make_pool(family));
  benchmark::AddCustomContext("pool seed", std::to_string(seed));
  benchmark::AddCustomContext("pool pairs", std::to_string(pool_size));
  for (const Pool& pool : pools) {
    describe(pool);
    for (const Contender& c : contenders) {
      benchmark::RegisterBenchmark((c.name + "/" + pool.name).c_str(), [&pool, &c](benchmark::State& state) {
        run_passes(state, pool_size, [&](std::size_t i) { c.one_pair(pool, i); });
      });
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
