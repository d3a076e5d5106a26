// dda3d_stack: how the implicit 3D DDA scales with the number of blocks.
//
// A 10 x 10 x N stack of 1 m cubes (rigid, 6 unknowns each; --deformable for 12) stands in a fixed
// box (a floor and four walls touching it), every face in exact touch with a neighbour's, under
// gravity: rho 2600, E 10 GPa, kn 1e10 N/m, kt 1e9 N/m, phi 30 degrees, dt 1 ms. The engine's
// initial equilibrium settles it first (one static solve), then it is stepped. For each N:
//   blocks, setup s     the blocks and the construction's wall time (detection and pre-solve);
//   steps/s             steps per wall second over `steps` steps after `warmup`;
//   OCI/step            mean open-close iterations per step;
//   constraints         in the contact list at the end (closed ones in brackets);
//   detect %, solve %   shares of the stepping time in contact detection and in the linear
//                       solves (the rest: assembly, the open-close decisions, the block update);
// then the exponent b of time per step ~ blocks^b (least squares over the N measured).
//
// Usage: dda3d_stack [--layers "1 10 100"] [--steps S] [--warmup W] [--solver ldlt|cg]
//                    [--deformable] [--threads T]
// Measured figures are quoted in docs/performance.md with the command that made them.

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/dynamics/dda3d.hpp"
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"

namespace {

using namespace rockcontact;
using clock_type = std::chrono::steady_clock;

kernel::ConvexPolyhedron box(const std::string& name, kernel::Point3 lo, kernel::Point3 hi) {
  std::vector<kernel::Point3> v{{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                                {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  std::vector<kernel::ConvexPolyhedron::Face> f{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  return kernel::ConvexPolyhedron::make(name, std::move(v), std::move(f));
}

dynamics::Block3dSpec block(const std::string& id, kernel::Point3 lo, kernel::Point3 hi, bool fixed, bool rigid) {
  dynamics::Block3dSpec b;
  b.id = id;
  b.parts = {box(id, lo, hi)};
  b.material = {2600.0, 1.0e10, 0.25};
  b.fixed = fixed;
  b.rigid = rigid;
  return b;
}

std::vector<dynamics::Block3dSpec> stack(int layers, bool rigid) {
  const double top = layers + 1.0;
  std::vector<dynamics::Block3dSpec> out{block("floor", {-1, -1, -1}, {11, 11, 0}, true, true),
                                         block("west", {-1, -1, 0}, {0, 11, top}, true, true),
                                         block("east", {10, -1, 0}, {11, 11, top}, true, true),
                                         block("south", {0, -1, 0}, {10, 0, top}, true, true),
                                         block("north", {0, 10, 0}, {10, 11, top}, true, true)};
  for (int k = 0; k < layers; ++k) {
    for (int j = 0; j < 10; ++j) {
      for (int i = 0; i < 10; ++i) {
        out.push_back(block("c" + std::to_string(i) + "_" + std::to_string(j) + "_" + std::to_string(k),
                            {double(i), double(j), double(k)}, {i + 1.0, j + 1.0, k + 1.0}, false, rigid));
      }
    }
  }
  return out;
}

double seconds(clock_type::time_point since) { return std::chrono::duration<double>(clock_type::now() - since).count(); }

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> layers{1, 10, 100};
  int steps = 20, warmup = 2, threads = 0;
  bool rigid = true;
  dynamics::Solver3d solver = dynamics::Solver3d::ldlt;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "dda3d_stack: %s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--layers") {
      layers.clear();
      std::istringstream in(next());
      for (int n; in >> n;) layers.push_back(n);
    } else if (arg == "--steps") {
      steps = std::atoi(next().c_str());
    } else if (arg == "--warmup") {
      warmup = std::atoi(next().c_str());
    } else if (arg == "--threads") {
      threads = std::atoi(next().c_str());
    } else if (arg == "--deformable") {
      rigid = false;
    } else if (arg == "--solver") {
      const std::string name = next();
      if (name != "ldlt" && name != "cg") {
        std::fprintf(stderr, "dda3d_stack: --solver expects ldlt or cg, got %s\n", name.c_str());
        return 2;
      }
      solver = name == "cg" ? dynamics::Solver3d::cg : dynamics::Solver3d::ldlt;
    } else {
      std::fprintf(stderr, "dda3d_stack: unknown argument %s\n", arg.c_str());
      return 2;
    }
  }
  if (threads > 0) omp_set_num_threads(threads);
  std::printf("solver %s, %s blocks, %d threads\n", solver == dynamics::Solver3d::cg ? "cg" : "ldlt",
              rigid ? "rigid" : "deformable", omp_get_max_threads());
  std::printf("%8s %8s %9s %8s %13s %9s %8s\n", "blocks", "setup s", "steps/s", "OCI/step", "constraints", "detect %",
              "solve %");
  std::vector<double> log_n, log_t;
  for (const int n : layers) {
    dynamics::ContactLaw3d law;
    law.kn = 1.0e10;
    law.kt = 1.0e9;
    law.friction_angle_deg = 30.0;
    dynamics::Dda3dParams params;
    params.dt = 1.0e-3;
    params.solver = solver;
    auto start = clock_type::now();
    dynamics::Dda3d sim(stack(n, rigid), law, params);
    const double setup = seconds(start);
    for (int s = 0; s < warmup; ++s) sim.step();
    const dynamics::Step3dStats before = sim.last_step();
    std::size_t iterations = 0;
    start = clock_type::now();
    for (int s = 0; s < steps; ++s) {
      sim.step();
      iterations += sim.last_step().open_close_iterations;
    }
    const double wall = seconds(start);
    const dynamics::Step3dStats& after = sim.last_step();
    const double blocks = 100.0 * n;
    std::printf("%8.0f %8.2f %9.3g %8.2f %7zu (%zu) %8.1f%% %7.1f%%\n", blocks, setup, steps / wall,
                double(iterations) / steps, after.constraints, after.closed,
                100.0 * (after.detection_seconds - before.detection_seconds) / wall,
                100.0 * (after.solve_seconds - before.solve_seconds) / wall);
    std::fflush(stdout);
    log_n.push_back(std::log(blocks));
    log_t.push_back(std::log(wall / steps));
  }
  if (log_n.size() >= 2) {
    double mn = 0, mt = 0;
    for (std::size_t i = 0; i < log_n.size(); ++i) mn += log_n[i], mt += log_t[i];
    mn /= double(log_n.size());
    mt /= double(log_n.size());
    double num = 0, den = 0;
    for (std::size_t i = 0; i < log_n.size(); ++i) num += (log_n[i] - mn) * (log_t[i] - mt), den += (log_n[i] - mn) * (log_n[i] - mn);
    std::printf("time per step ~ blocks^%.2f\n", num / den);
  }
  return 0;
}
