// dda_scale: how the explicit 2D DDA scales with the number of blocks.
//
// A square region of side sqrt(N) m is cut by two joint sets (0° and 90°, spacing 1 m, so N unit
// blocks; kernel::cut_region) and left to settle under gravity on a fixed floor: rho 2700,
// E 2 GPa, kn 2 GPa, kt 1 GN/m, friction 30°, H 1 m, dt 1e-4 s (seed 000 §6.1's parameters).
// The blocks start in exact touch, so every neighbour pair is a contact candidate and the
// loaded ones overlap from the first steps. For each N and thread count the program reports:
//   cut s        wall time of cut_region (the exact arrangement of the joint traces);
//   setup s      wall time of the engine's construction (validation, moments, estimates);
//   steps/s      steps per wall second, over `steps` steps after `warmup` steps;
//   contacts     contacts at the last step, and contact pairs evaluated per second;
//   B/block      resident memory added by the engine (after the warm-up) per block;
// then the exponent b of time per step ~ N^b, a least-squares fit over the N measured.
//
// With --settled N it measures instead a settled pile of N unit squares (settled_blocks): the
// contacts per second per core of a scene whose contacts are all loaded, the figure a DEM user
// compares with their own code.
//
// Usage: dda_scale [--max N] [--steps S] [--warmup W] [--threads "1 2"] [--settled N]
// Measured figures are quoted in docs/performance.md with the command that made them.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "rockcontact/dynamics/dda2d.hpp"
#include "rockcontact/kernel/2d/block_cutting.hpp"

namespace {

using namespace rockcontact;
using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point start) {
  return std::chrono::duration<double>(clock_type::now() - start).count();
}

// Resident set size, bytes (Linux /proc/self/statm: pages).
double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0, resident = 0.0;
  statm >> pages >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

struct Options {
  std::size_t max_blocks = 100000;
  std::size_t steps = 20;
  std::size_t warmup = 20;
  std::vector<std::size_t> threads{1, 2};
  std::size_t settled = 0;  // blocks of the settled pile; 0: the scaling table
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--max") {
      o.max_blocks = std::stoul(value);
    } else if (flag == "--steps") {
      o.steps = std::stoul(value);
    } else if (flag == "--warmup") {
      o.warmup = std::stoul(value);
    } else if (flag == "--settled") {
      o.settled = std::stoul(value);
    } else if (flag == "--threads") {
      o.threads.clear();
      std::istringstream list(value);
      for (std::size_t t; list >> t;) o.threads.push_back(t);
    } else {
      std::fprintf(stderr, "dda_scale: unknown flag %s\n", flag.c_str());
      std::exit(2);
    }
  }
  return o;
}

struct Measure {
  std::size_t blocks = 0, threads = 0, contacts = 0;
  double cut = 0.0, setup = 0.0, per_step = 0.0, contact_rate = 0.0, bytes_per_block = 0.0;
};

std::vector<dynamics::BlockSpec> settling_blocks(std::size_t n, const dynamics::Material& rock,
                                                 double& cut_seconds) {
  const double side = std::round(std::sqrt(static_cast<double>(n)));
  const std::vector<kernel::Point2> region{{0, 0}, {side, 0}, {side, side}, {0, side}};
  const std::vector<kernel::JointSet> sets{{0.0, 1.0}, {90.0, 1.0}};
  const auto start = clock_type::now();
  const std::vector<std::vector<kernel::Point2>> pieces = kernel::cut_region(region, sets);
  cut_seconds = seconds_since(start);
  std::vector<dynamics::BlockSpec> blocks;
  dynamics::BlockSpec floor;
  floor.id = "floor";
  floor.fixed = true;
  floor.material = rock;
  floor.vertices = {{-1, -1}, {side + 1, -1}, {side + 1, 0}, {-1, 0}};
  blocks.push_back(floor);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    dynamics::BlockSpec b;
    b.id = "b" + std::to_string(k);
    b.material = rock;
    b.vertices = pieces[k];
    blocks.push_back(std::move(b));
  }
  return blocks;
}

// Rigid unit squares stacked in sqrt(N) columns on the fixed floor, each already at its static
// overlap with what is below it, so that every vertical pair is a loaded contact from the first
// step and every side pair an exact touch: a settled pile without the cost of settling one. A block
// carrying the weight W of its column above it (itself included) overlaps by d where the
// face-on-face force of the potential law (seed 000 eq. 12-14, the shortest exit) balances W:
// against an equal face 2 kn/H (L d - d²) = W, against the wider floor kn/H (2 L d - d²) = W.
std::vector<dynamics::BlockSpec> settled_blocks(std::size_t n, const dynamics::Material& rock,
                                                double kn, double H, double g) {
  const auto side = static_cast<std::size_t>(std::round(std::sqrt(static_cast<double>(n))));
  const double L = 1.0, weight = rock.density * L * L * g;
  std::vector<dynamics::BlockSpec> blocks;
  dynamics::BlockSpec floor;
  floor.id = "floor";
  floor.fixed = true;
  floor.material = rock;
  const double width = static_cast<double>(side);
  floor.vertices = {{-1, -1}, {width + 1, -1}, {width + 1, 0}, {-1, 0}};
  blocks.push_back(floor);
  for (std::size_t j = 0; j < side; ++j) {
    double top = 0.0;  // of the block below (the floor's top at first)
    for (std::size_t i = 0; i < side; ++i) {
      const double w = static_cast<double>(side - i) * weight;
      const double d = i == 0 ? L - std::sqrt(L * L - w * H / kn)
                              : 0.5 * (L - std::sqrt(L * L - 2.0 * w * H / kn));
      const double x = static_cast<double>(j), y = top - d;
      dynamics::BlockSpec b;
      b.id = "b" + std::to_string(j) + "_" + std::to_string(i);
      b.material = rock;
      b.vertices = {{x, y}, {x + L, y}, {x + L, y + L}, {x, y + L}};
      b.rigid = true;  // deformable blocks would first sink by their elastic strain and bounce
      blocks.push_back(std::move(b));
      top = y + L;
    }
  }
  return blocks;
}

Measure run(std::size_t n, std::size_t threads, const Options& o, bool settled) {
  Measure m;
  m.threads = threads;
  const dynamics::Material rock{2700.0, 2.0e9, 0.3};
  const std::vector<dynamics::BlockSpec> blocks =
      settled ? settled_blocks(n, rock, 2.0e9, 1.0, 9.81) : settling_blocks(n, rock, m.cut);
  m.blocks = blocks.size() - 1;
  dynamics::ContactLaw law;
  law.normal.kn = 2.0e9;
  law.normal.H = 1.0;
  law.friction = dynamics::FrictionLaw{1.0e9, 30.0};
  dynamics::DdaParams params;
  params.dt = 1.0e-4;
  params.threads = threads;
  params.initial_equilibrium = rockcontact::dynamics::InitialEquilibrium::off;  // the step's cost is measured, from the states placed
  const double before = resident_bytes();
  auto start = clock_type::now();
  dynamics::Dda2d sim(blocks, law, params);
  m.setup = seconds_since(start);
  for (std::size_t s = 0; s < o.warmup; ++s) sim.step();
  m.bytes_per_block = (resident_bytes() - before) / static_cast<double>(m.blocks);
  std::size_t evaluated = 0;
  start = clock_type::now();
  for (std::size_t s = 0; s < o.steps; ++s) {
    sim.step();
    evaluated += sim.contacts().size();
  }
  const double elapsed = seconds_since(start);
  m.per_step = elapsed / static_cast<double>(o.steps);
  m.contacts = sim.contacts().size();
  m.contact_rate = static_cast<double>(evaluated) / elapsed;
  return m;
}

// Least-squares slope of log(y) against log(x).
double exponent(const std::vector<Measure>& rows, std::size_t threads) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, count = 0;
  for (const Measure& r : rows) {
    if (r.threads != threads) continue;
    const double x = std::log(static_cast<double>(r.blocks)), y = std::log(r.per_step);
    sx += x, sy += y, sxx += x * x, sxy += x * y, count += 1;
  }
  return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  if (o.settled > 0) {
    std::printf("%8s %7s %9s %9s %13s %16s\n", "blocks", "threads", "steps/s", "contacts",
                "contacts/s", "contacts/s/core");
    for (const std::size_t t : o.threads) {
      const Measure m = run(o.settled, t, o, true);
      std::printf("%8zu %7zu %9.1f %9zu %13.3g %16.3g\n", m.blocks, m.threads, 1.0 / m.per_step,
                  m.contacts, m.contact_rate, m.contact_rate / static_cast<double>(t));
      std::fflush(stdout);
    }
    return 0;
  }
  std::vector<Measure> rows;
  std::printf("%8s %7s %7s %8s %9s %9s %9s %13s %9s\n", "blocks", "threads", "cut s", "setup s",
              "steps/s", "ms/step", "contacts", "contacts/s", "B/block");
  for (std::size_t n = 100; n <= o.max_blocks; n *= 10) {
    for (const std::size_t t : o.threads) {
      const Measure m = run(n, t, o, false);
      rows.push_back(m);
      std::printf("%8zu %7zu %7.3f %8.3f %9.1f %9.3f %9zu %13.3g %9.0f\n", m.blocks, m.threads, m.cut,
                  m.setup, 1.0 / m.per_step, 1e3 * m.per_step, m.contacts, m.contact_rate,
                  m.bytes_per_block);
      std::fflush(stdout);
    }
  }
  for (const std::size_t t : o.threads) {
    std::printf("time per step ~ N^%.3f on %zu thread(s)\n", exponent(rows, t), t);
  }
  return 0;
}
