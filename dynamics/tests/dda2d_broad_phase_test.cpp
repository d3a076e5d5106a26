#define BOOST_TEST_MODULE dynamics_dda2d_broad_phase
#include <boost/test/unit_test.hpp>

// The uniform-grid broad phase of the 2D DDA engine (dynamics/dda2d/src/broad_phase.hpp) against
// brute force, and the engine on a scene large enough to use it (a Newton's cradle).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "../dda2d/src/broad_phase.hpp"
#include "dda2d_fixtures.hpp"
#include "rockcontact/dynamics/dda2d.hpp"

namespace {

using namespace rockcontact::dynamics;
using detail::BlockPair;
using detail::BroadPhaseBox;

// Every pair with overlapping closed boxes and at least one movable block, sorted.
std::vector<BlockPair> brute_force(const std::vector<BroadPhaseBox>& boxes) {
  std::vector<BlockPair> out;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      const BroadPhaseBox& a = boxes[i];
      const BroadPhaseBox& b = boxes[j];
      if (a.fixed && b.fixed) continue;
      if (a.xmax < b.xmin || b.xmax < a.xmin || a.ymax < b.ymin || b.ymax < a.ymin) continue;
      out.emplace_back(i, j);
    }
  }
  return out;
}

// `count` boxes on a 0.25 m lattice in [0, 10] m², 0.25-1 m wide and high, one in five fixed,
// then a fixed floor across the whole scene.
std::vector<BroadPhaseBox> random_boxes(std::mt19937& rng, std::size_t count) {
  std::uniform_int_distribution<int> cell(0, 40), size(1, 4), coin(0, 4);
  std::vector<BroadPhaseBox> boxes(count);
  for (BroadPhaseBox& b : boxes) {
    b.xmin = 0.25 * cell(rng);
    b.ymin = 0.25 * cell(rng);
    b.xmax = b.xmin + 0.25 * size(rng);
    b.ymax = b.ymin + 0.25 * size(rng);
    b.fixed = coin(rng) == 0;
  }
  boxes.push_back({-1.0, 12.0, 2.0, 2.5, true});
  return boxes;
}

}  // namespace

// Random boxes on a coarse grid (so that touching boxes, shared edges and equal left ends are
// common, and boxes often end exactly on cell boundaries), some fixed, plus one long fixed box
// covering many cells; the boxes then drift and the same UniformGrid object is reused.
BOOST_AUTO_TEST_CASE(uniform_grid_equals_brute_force) {
  const std::uint32_t seed = 20240603;
  BOOST_TEST_MESSAGE("seed " << seed);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coin(0, 4);
  for (int scene = 0; scene < 50; ++scene) {
    std::vector<BroadPhaseBox> boxes = random_boxes(rng, 1 + static_cast<std::size_t>(scene) * 4);
    detail::UniformGrid grid;
    std::vector<BlockPair> pairs;
    for (int frame = 0; frame < 5; ++frame) {
      grid.find_pairs(boxes, pairs);
      std::sort(pairs.begin(), pairs.end());  // the grid reports them in cell order
      BOOST_TEST_CONTEXT("scene " << scene << ", frame " << frame) {
        BOOST_TEST((pairs == brute_force(boxes)));
      }
      for (BroadPhaseBox& b : boxes) {
        if (b.fixed) continue;
        const double dx = 0.25 * (coin(rng) - 2);
        b.xmin += dx;
        b.xmax += dx;
      }
    }
  }
}

// The Verlet list on the same kind of boxes, drifting by 1/64 m per frame (the margin is 1/20
// of the largest extent, 1 m: a box leaves its inflated box after 4 frames or more), over 40
// frames: after every update the list is sorted, has no duplicate and holds every pair of
// overlapping closed boxes; it stands on some frames and rebuilds on others.
BOOST_AUTO_TEST_CASE(verlet_list_holds_every_overlapping_pair) {
  const std::uint32_t seed = 20261125;
  BOOST_TEST_MESSAGE("seed " << seed);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> step(-1, 1);
  std::size_t rebuilds = 0, frames = 0;
  for (int scene = 0; scene < 20; ++scene) {
    std::vector<BroadPhaseBox> boxes = random_boxes(rng, 1 + static_cast<std::size_t>(scene) * 8);
    detail::VerletList list;
    for (int frame = 0; frame < 40; ++frame, ++frames) {
      rebuilds += list.update(boxes);
      const std::vector<BlockPair>& pairs = list.pairs();
      BOOST_TEST_CONTEXT("scene " << scene << ", frame " << frame) {
        BOOST_TEST((std::adjacent_find(pairs.begin(), pairs.end(), std::greater_equal<>()) == pairs.end()));
        for (const BlockPair& p : brute_force(boxes)) {
          BOOST_TEST(std::binary_search(pairs.begin(), pairs.end(), p), p.first << "-" << p.second);
        }
      }
      for (BroadPhaseBox& b : boxes) {
        if (b.fixed) continue;
        const double dx = step(rng) / 64.0, dy = step(rng) / 64.0;
        b.xmin += dx;
        b.xmax += dx;
        b.ymin += dy;
        b.ymax += dy;
      }
    }
  }
  BOOST_TEST_MESSAGE(rebuilds << " rebuilds in " << frames << " frames");
  BOOST_TEST(rebuilds > 20u);  // more than the first build of each scene
  BOOST_TEST(rebuilds < frames / 2);
}

BOOST_AUTO_TEST_CASE(all_pairs_skips_only_fixed_pairs) {
  std::vector<BroadPhaseBox> boxes(4);
  boxes[0].fixed = boxes[2].fixed = true;
  std::vector<BlockPair> pairs;
  detail::all_pairs(boxes, pairs);
  const std::vector<BlockPair> expected{{0, 1}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  BOOST_TEST((pairs == expected));
}

// A Newton's cradle of 10 rigid 1 m squares in a row, 0.1 m apart (Table 4 row 4.1 contact:
// kn 1e7 Pa, H 1 m, dt 1e-4 s, no gravity): the first moves at 1 m/s. With gaps the
// collisions are one at a time (each lasts pi sqrt(m / (4 kn L / H)) = 22 ms while the next
// gap takes 100 ms to close), and each exchanges the velocities of an equal pair, so at the
// end block 9 carries 1 m/s and the others rest. With more than 8 blocks the candidate pairs
// come from the uniform grid. Tolerances: each exchange leaves O((omega h)²) = 2e-4 behind (see
// dda2d_collision_test), nine of them 2e-3; momentum is exact to round-off (1e-12).
BOOST_AUTO_TEST_CASE(newtons_cradle_passes_the_velocity_down_the_row) {
  std::vector<BlockSpec> blocks;
  for (int k = 0; k < 10; ++k) {
    BlockSpec b;
    b.id = "b" + std::to_string(k);
    const double x0 = 1.1 * k;
    b.vertices = {{x0, 0.0}, {x0 + 1.0, 0.0}, {x0 + 1.0, 1.0}, {x0, 1.0}};
    b.rigid = true;
    blocks.push_back(b);
  }
  blocks[0].velocity = {1.0, 0.0};
  Dda2d sim(blocks, testing::frictionless(), testing::params(1.0e-4));
  const double m = sim.blocks()[0].mass;
  double worst_momentum = 0.0;
  while (sim.steps() < 12000) {  // the last collision ends near 0.9 + 0.2 = 1.1 s
    sim.step();
    double momentum = 0.0;
    for (const BlockState& s : sim.blocks()) momentum += s.mass * s.velocity[0];
    worst_momentum = std::max(worst_momentum, std::fabs(momentum - m));
  }
  const auto& s = sim.blocks();
  BOOST_TEST_MESSAGE("cradle: v9 = " << s[9].velocity[0] << " m/s, v8 = " << s[8].velocity[0]
                     << ", v0 = " << s[0].velocity[0] << "; momentum error " << worst_momentum / m
                     << "; energy " << sim.energies().total() << " J/m of 1000");
  BOOST_TEST(sim.contacts().empty());
  BOOST_TEST(std::fabs(s[9].velocity[0] - 1.0) <= 2e-3);
  for (std::size_t k = 0; k < 9; ++k) BOOST_TEST(std::fabs(s[k].velocity[0]) <= 2e-3);
  BOOST_TEST(worst_momentum <= 1e-12 * m);
}

// Determinism across thread counts: 120 rigid and deformable 0.5 m squares, in a staggered
// stack with 5 mm gaps, fall onto a fixed floor and into each other with friction (enough blocks and
// candidate pairs for every parallel pass to use its threads). Every candidate pair is measured
// independently and the contacts are assembled in pair order, and every per-block update touches
// its own block, so 1, 2 and 3 threads must give the same state to the last bit, and the same
// count of predicate calls.
BOOST_AUTO_TEST_CASE(results_do_not_depend_on_the_thread_count) {
  std::vector<BlockSpec> blocks;
  BlockSpec floor;
  floor.id = "floor";
  floor.fixed = true;
  floor.vertices = {{-1, -1}, {8, -1}, {8, 0}, {-1, 0}};
  blocks.push_back(floor);
  for (int k = 0; k < 120; ++k) {
    const double x = 0.6 * (k % 12) + 0.15 * ((k / 12) % 2), y = 0.005 + 0.505 * (k / 12);
    BlockSpec b;
    b.id = "b" + std::to_string(k);
    b.vertices = {{x, y}, {x + 0.5, y}, {x + 0.5, y + 0.5}, {x, y + 0.5}};
    b.rigid = k % 3 == 0;
    blocks.push_back(b);
  }
  ContactLaw law;
  law.normal.kn = 1.0e8;
  law.normal.H = 0.5;
  law.friction = FrictionLaw{1.0e8, 30.0};
  std::vector<std::vector<BlockState>> finals;
  std::vector<std::uint64_t> predicates;
  for (const std::size_t threads : {1u, 2u, 3u}) {
    DdaParams p;
    p.dt = 1.0e-4;
    p.threads = threads;
    Dda2d sim(blocks, law, p);
    while (sim.steps() < 2000) sim.step();
    BOOST_TEST_MESSAGE(threads << " threads: " << sim.contacts().size() << " contacts at t = " << sim.time());
    BOOST_TEST(sim.contacts().size() > 64u);  // more than the parallel threshold of the passes
    finals.push_back(sim.blocks());
    predicates.push_back(sim.predicate_counters().total_calls());
  }
  BOOST_TEST(predicates[1] == predicates[0]);  // the workers' predicate calls are counted too
  BOOST_TEST(predicates[2] == predicates[0]);
  for (std::size_t run = 1; run < finals.size(); ++run) {
    for (std::size_t i = 0; i < finals[0].size(); ++i) {
      BOOST_TEST_CONTEXT("run " << run << ", block " << finals[0][i].id) {
        for (std::size_t k = 0; k < finals[0][i].vertices.size(); ++k) {
          BOOST_TEST(finals[run][i].vertices[k].x == finals[0][i].vertices[k].x);
          BOOST_TEST(finals[run][i].vertices[k].y == finals[0][i].vertices[k].y);
        }
        for (std::size_t k = 0; k < 6; ++k) BOOST_TEST(finals[run][i].velocity[k] == finals[0][i].velocity[k]);
      }
    }
  }
}
