// Pair-level micro-benchmarks: the cost of one pair of blocks under each number policy.
//
//   classify/<policy>/<pool>      kernel::classify_overlap (the verdict alone)
//   intersection/<policy>/<pool>  kernel::compute_intersection_polygon (the verdict and the
//                                 symbolic IP in one clip) + construct_points
//   evaluate/<policy>/<pool>      contact::evaluate_pair (verdict, IP, force, contact point)
//   pair_api/<policy>/<pool>      PairEvaluator::evaluate, the host-facing call: evaluate plus
//                                 validating both polygons from plain arrays and the
//                                 penetration depth (identity poses)
//
// Pools of 512 pairs (fixed seed, built before timing): `random` is the random family of
// robustness_tests/generators/include/rockcontact/generators/pair_generators.hpp (overlap, touch, separate); `general` its pairs in general
// position (touching pairs left out); `adversarial` cycles through the 17 other families
// (short and tiny edges, wedges down to 0.1°, near-parallel edges down to one ulp, exact
// vertex and edge incidences, slivers, nested and identical polygons, offsets to 1e9 m,
// rotations).
//
// One benchmark iteration is one pass over the whole pool, so every policy is timed on the same
// pairs (the Exact force costs milliseconds per pair; timing a prefix of the pool would bias
// it). Counters:
//   per_pair        seconds per pair (wall clock of the passes / pairs; 53.2n = 53.2 ns)
//   interval_rate   calls whose double filter was unsure (the interval stage ran) / predicate
//                   calls (predicate_counters()); zero under Float, which has no stages
//   fallback_rate   calls whose interval was unsure too (the exact stage ran) / predicate calls;
//                   Exact shares Filtered's staged signs, so both show the same rates
//   predicates      predicate calls per pair
// Workspaces are reused and warmed on the pool before timing, so the Float and Filtered paths
// allocate nothing in the timed loop; the Exact path allocates its GMP numbers.

#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rockcontact/generators/pair_generators.hpp"
#include "rockcontact/contact/embed/pair_contact.hpp"
#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/2d/intersection_polygon.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "run_passes.hpp"

namespace {

using rockcontact::bench::run_passes;

namespace rb = rockcontact::robustness;
namespace rk = rockcontact::kernel;
namespace rc = rockcontact::contact;

constexpr std::uint64_t seed = 0x5eed'2024'0611ull;
constexpr std::size_t pool_size = 512;

struct Pool {
  std::string name;
  std::vector<rk::ConvexPolygon> cp;
  std::vector<rk::ConvexPolygon> tp;
  std::vector<std::vector<double>> cp_xy, tp_xy;  // the same polygons, interleaved x, y
};

std::vector<double> interleaved(const rk::ConvexPolygon& polygon) {
  std::vector<double> xy;
  for (const rk::Point2& p : polygon.vertices()) xy.insert(xy.end(), {p.x, p.y});
  return xy;
}

enum class PoolKind { random, general, adversarial };

// `general` keeps the random pairs in general position (exact verdict separate or overlap), so
// the filter should certify every sign; `random` includes the touching pairs, each of which
// needs one exact evaluation to confirm its zero.
Pool make_pool(std::string name, PoolKind kind) {
  Pool pool{std::move(name), {}, {}, {}, {}};
  for (std::uint64_t index = 0; pool.cp.size() < pool_size; ++index) {
    // The adversarial pool skips all_families[0], the random family.
    const rb::Family family = kind == PoolKind::adversarial
                                  ? rb::all_families[1 + index % (rb::all_families.size() - 1)]
                                  : rb::Family::random;
    const rb::PolygonPair pair = rb::generate_pair(family, seed, index);
    rk::ConvexPolygon cp = rk::ConvexPolygon::make("cp", pair.cp);
    rk::ConvexPolygon tp = rk::ConvexPolygon::make("tp", pair.tp);
    if (kind == PoolKind::general && rk::classify_overlap<rk::Exact>(cp, tp) == rk::Overlap::touch) continue;
    pool.cp_xy.push_back(interleaved(cp));
    pool.tp_xy.push_back(interleaved(tp));
    pool.cp.push_back(std::move(cp));
    pool.tp.push_back(std::move(tp));
  }
  return pool;
}

template <rk::NumberPolicy Policy>
void classify(benchmark::State& state, const Pool& pool) {
  run_passes(state, pool_size, [&](std::size_t i) {
    benchmark::DoNotOptimize(rk::classify_overlap<Policy>(pool.cp[i], pool.tp[i]));
  });
}

template <rk::NumberPolicy Policy>
void intersection(benchmark::State& state, const Pool& pool) {
  rk::IntersectionPolygon ip;
  rk::ClipWorkspace workspace;
  std::vector<rk::Point2> points;
  run_passes(state, pool_size, [&](std::size_t i) {
    rk::compute_intersection_polygon<Policy>(pool.cp[i], pool.tp[i], ip, workspace);
    rk::construct_points<Policy>(pool.cp[i], pool.tp[i], ip, points);
    benchmark::DoNotOptimize(points.data());
  });
}

template <rk::NumberPolicy Policy>
void evaluate(benchmark::State& state, const Pool& pool) {
  const rc::PotentialContactParams params = rc::default_potential_contact_params();
  rc::PairWorkspace workspace;
  rc::PairResult result;
  run_passes(state, pool_size, [&](std::size_t i) {
    rc::evaluate_pair<Policy>(pool.cp[i], pool.tp[i], params, workspace, result);
    benchmark::DoNotOptimize(result.force);
  });
}

template <rk::NumberPolicy Policy>
void pair_api(benchmark::State& state, const Pool& pool) {
  rockcontact::PairContactParams params = rockcontact::default_pair_contact_params();
  params.policy = Policy::kind;
  rockcontact::PairEvaluator contact(params);
  run_passes(state, pool_size, [&](std::size_t i) {
    benchmark::DoNotOptimize(contact.evaluate(pool.cp_xy[i], {}, pool.tp_xy[i], {}));
  });
}

template <rk::NumberPolicy Policy>
void register_policy(const Pool& pool) {
  const std::string suffix = std::string("/") + std::string(Policy::name) + "/" + pool.name;
  const Pool* p = &pool;  // outlives the run (main's locals)
  benchmark::RegisterBenchmark(("classify" + suffix).c_str(),
                               [p](benchmark::State& state) { classify<Policy>(state, *p); });
  benchmark::RegisterBenchmark(("intersection" + suffix).c_str(),
                               [p](benchmark::State& state) { intersection<Policy>(state, *p); });
  benchmark::RegisterBenchmark(("evaluate" + suffix).c_str(),
                               [p](benchmark::State& state) { evaluate<Policy>(state, *p); });
  benchmark::RegisterBenchmark(("pair_api" + suffix).c_str(),
                               [p](benchmark::State& state) { pair_api<Policy>(state, *p); });
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const Pool random = make_pool("random", PoolKind::random);
  const Pool general = make_pool("general", PoolKind::general);
  const Pool adversarial = make_pool("adversarial", PoolKind::adversarial);
  for (const Pool* pool : {&random, &general, &adversarial}) {
    register_policy<rk::Float>(*pool);
    register_policy<rk::Filtered>(*pool);
    register_policy<rk::Exact>(*pool);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
