// cdem_scale: the CDEM engine's cost per element and per boundary node (issue 21).
//
// 1. Element throughput. One deformable 1 m square block (E 40 GPa, nu 0.25, rho 2700, plane
//    strain, zero gravity, two-scale law) meshed with the max_edge that gives about the number of
//    elements asked for (calibrated on kernel::mesh_polygon), spinning at 10 rad/s about its
//    centre: it starts unstressed, so the spin stretches it (nothing holds the nodes on their
//    circles) and every element carries a changing stress. A single block skips the touch search
//    (Cdem::Impl::move), so a step is the element forces, the gather over nodes and the per-node
//    passes (the kicks, the drift, the rotations, the stability monitor). dt = 0.9 critical_dt().
//    For each size and thread count (omp_set_num_threads), after a warm-up of a tenth of the
//    budget, N steps are timed, N chosen so that the measurement takes about --seconds:
//      element-steps/s   elements x steps / wall seconds;
//      B/element         resident memory added by the engine (after its warm-up, glibc's free
//                        pages returned by malloc_trim, so the mesher's garbage is not counted)
//                        per element;
//      preempted         involuntary context switches during the timing: every parallel region
//                        waits for a thread another job took off its core, so a 2-thread row
//                        with more than a few of them measured the machine's load;
//    then the exponent b of time per step ~ elements^b (least squares) per thread count, and
//    the 2-thread rates against the goal of 2e7 element-steps/s.
//
// 2. Contact detection against boundary nodes. Two strips 1 m long and 8 max_edge thick (so the
//    elements grow like the boundary, about 14 per boundary node, and 10^4 boundary nodes stay
//    near 1.6e5 elements; two squares would need 1e7), max_edge = 2^-k m with k chosen for the
//    --boundary targets (the mesher's boundary splits round them), one at rest and one
//    moving towards it at 1 m/s, long faces facing, two-scale law, search tolerance 1e-3 m, three
//    scenes of about the same elements and boundary nodes:
//      alone  one strip 2 m long: no detection (find_touches is skipped for a single block);
//      far    the two strips 10 m apart: the edge grid is built and every boundary node looks up
//             its cells every step, but no box comes within the tolerance, no candidate pair;
//      near   the two strips 0.5 mm apart (half the tolerance) and closing: every node of the
//             facing sides is boxed against the facing edges within the tolerance and each such
//             pair gets an exact first_touch test (no touch happens: the engine is rebuilt before
//             the gap halves, construction outside the timing).
//    It reports microseconds per step, per step and boundary node, and the differences from
//    `alone` (the grid: far - alone; the whole detection: near - alone), their share of the
//    step, and the exponents of each against the boundary nodes. The engine has no timer hook,
//    so the difference of scenes is the measurement.
//
// Usage: cdem_scale [--elements "1e3 1e4 1e5"] [--boundary "1e2 3e2 1e3 3e3 1e4"]
//                   [--threads "1 2"] [--seconds S] [--repeat R] [--quick]
// An empty list ("") skips its part; --repeat keeps the fastest of R measurements of each row
// (on a shared machine); --quick is a smoke run (small sizes, 0.3 s each).
// Measured figures are in bench/README.md ("cdem_scale") with the command that made them.

#include <malloc.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/dynamics/cdem.hpp"
#include "rockcontact/kernel/2d/triangle_mesh.hpp"

namespace {

using namespace rockcontact;
using clock_type = std::chrono::steady_clock;

constexpr double goal_element_steps = 2.0e7;  // issue 21: on 2 cores
constexpr double spin = 10.0;                 // rad/s, the throughput block
constexpr double approach_speed = 1.0;        // m/s, the moving strip
constexpr double tolerance = 1.0e-3;          // m, contact.search_tolerance
constexpr double near_gap = 0.5 * tolerance;  // m, the near scene's initial gap
constexpr double far_gap = 10.0;              // m, the far scene's gap
constexpr double strip_layers = 8.0;          // strip thickness in max_edge

double seconds_since(clock_type::time_point start) {
  return std::chrono::duration<double>(clock_type::now() - start).count();
}

// Resident set size now, bytes (Linux /proc/self/statm: pages), after glibc returns its free
// pages to the system.
double resident_bytes() {
  malloc_trim(0);
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0, resident = 0.0;
  statm >> pages >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

// Peak resident set size of the process (VmHWM), bytes.
double peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) * 1024.0;
  }
  return 0.0;
}

// Involuntary context switches of the process so far: a thread taken off its core by another
// job. Every parallel region then waits for it at its barrier, so a measurement with many of
// them says more about the machine's load than about the engine.
long preemptions() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_nivcsw;
}

// The 1-minute load average (other jobs on the cores shift every figure here).
double load_average() {
  std::ifstream in("/proc/loadavg");
  double one = 0.0;
  in >> one;
  return one;
}

double fitted_exponent(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += std::log(x[i]), my += std::log(y[i]);
  mx /= double(x.size());
  my /= double(x.size());
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    num += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    den += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return num / den;
}

std::vector<kernel::Point2> rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

dynamics::CdemBlockSpec block(const std::string& id, std::vector<kernel::Point2> outline, double max_edge,
                              std::array<double, 3> velocity) {
  dynamics::CdemBlockSpec b;
  b.id = id;
  b.vertices = std::move(outline);
  b.material = {2700.0, 40.0e9, 0.25};
  b.max_edge = max_edge;
  b.velocity = velocity;
  return b;
}

dynamics::CdemParams params_with(double dt) {
  dynamics::CdemParams p;
  p.dt = dt;
  p.plane = dynamics::CdemPlane::strain;
  p.contact.law = dynamics::CdemLaw::two_scale;
  p.contact.search_tolerance = tolerance;
  return p;
}

// 0.9 times the critical step of the blocks' meshes (an engine built with a tiny dt tells it).
double stable_dt(const std::vector<dynamics::CdemBlockSpec>& blocks) {
  const dynamics::Cdem probe(blocks, params_with(1e-15));
  return 0.9 * probe.critical_dt();
}

// Boundary nodes of every block: the edges used by one triangle (a closed loop per block has as
// many nodes as edges).
std::size_t boundary_nodes(const dynamics::Cdem& sim) {
  std::size_t count = 0;
  for (std::size_t b = 0; b < sim.block_count(); ++b) {
    std::vector<std::uint64_t> edges;
    for (const auto& t : *sim.mesh(b).triangles) {
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t i = t[k], j = t[(k + 1) % 3];
        edges.push_back(std::min(i, j) << 32 | std::max(i, j));
      }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i == 1) ++count;
      i = j;
    }
  }
  return count;
}

struct Timing {
  double wall = 0.0;   // s, of the timed steps
  std::size_t steps = 0;
  std::size_t rounds = 0;  // engines built
  long preempted = 0;      // involuntary context switches while timing
  std::size_t touches = 0;  // contacts formed (the detection scenes expect none)
  double per_step() const { return wall / double(steps); }
};

// Steps engines from `make` until `budget` seconds of timed stepping: each engine takes at most
// `limit` steps (0: no limit), the first `warmup` of them untimed.
Timing time_steps(const std::function<dynamics::Cdem()>& make, std::size_t limit, std::size_t warmup,
                  double budget) {
  Timing t;
  if (limit == 0) limit = std::numeric_limits<std::size_t>::max();
  while (t.wall < budget) {
    dynamics::Cdem sim = make();
    ++t.rounds;
    std::size_t left = limit;
    for (std::size_t w = 0; w < warmup && left > 1; ++w, --left) sim.step();
    while (left > 0 && t.wall < budget) {
      std::size_t chunk = 1;
      if (t.steps > 0) {
        const double wanted = std::ceil((budget - t.wall) / t.per_step());
        chunk = static_cast<std::size_t>(std::clamp(wanted, 1.0, double(left)));
      }
      const long preempted = preemptions();
      const auto start = clock_type::now();
      for (std::size_t s = 0; s < chunk; ++s) sim.step();
      t.wall += seconds_since(start);
      t.preempted += preemptions() - preempted;
      t.steps += chunk;
      left -= chunk;
    }
    t.touches += sim.counters().touches;
  }
  return t;
}

// Steps one engine: a warm-up of a tenth of the budget (at least 3 steps, which also prices a
// step), then timed chunks of the steps the budget still has room for at the rate so far.
Timing time_engine(dynamics::Cdem& sim, double budget) {
  std::size_t warm = 0;
  const auto warm_start = clock_type::now();
  while (warm < 3 || seconds_since(warm_start) < 0.1 * budget) sim.step(), ++warm;
  double estimate = seconds_since(warm_start) / double(warm);
  Timing t;
  t.rounds = 1;
  while (t.wall < budget) {
    const auto chunk = static_cast<std::size_t>(std::max(3.0, std::ceil((budget - t.wall) / estimate)));
    const long preempted = preemptions();
    const auto start = clock_type::now();
    for (std::size_t s = 0; s < chunk; ++s) sim.step();
    t.wall += seconds_since(start);
    t.preempted += preemptions() - preempted;
    t.steps += chunk;
    estimate = t.per_step();
  }
  return t;
}

// The fastest per step of `repeat` measurements (the one least disturbed by other jobs).
Timing best_of(int repeat, const std::function<Timing()>& measure) {
  Timing best = measure();
  for (int r = 1; r < repeat; ++r) {
    const Timing t = measure();
    if (t.per_step() < best.per_step()) best = t;
  }
  return best;
}

// The max_edge that meshes the unit square into about `elements` triangles: Delaunay refinement
// gives about 4.6 / max_edge² (kernel/2d/triangle_mesh.hpp, step 1), corrected once by a mesh.
double square_max_edge(double elements) {
  const auto square = rectangle(0.0, 0.0, 1.0, 1.0);
  double h = std::sqrt(4.6 / elements);
  const double got = double(kernel::mesh_polygon(square, h).triangles.size());
  return h * std::sqrt(got / elements);
}

struct Options {
  std::vector<double> elements{1e3, 1e4, 1e5};
  std::vector<double> boundary{1e2, 3e2, 1e3, 3e3, 1e4};
  std::vector<int> threads{1, 2};
  double seconds = 2.0;
  int repeat = 1;
};

std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  std::istringstream in(text);
  for (std::string word; in >> word;) out.push_back(std::stod(word));
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "cdem_scale: %s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--elements") {
      o.elements = numbers(next());
    } else if (arg == "--boundary") {
      o.boundary = numbers(next());
    } else if (arg == "--threads") {
      o.threads.clear();
      for (double t : numbers(next())) o.threads.push_back(static_cast<int>(t));
    } else if (arg == "--seconds") {
      o.seconds = std::stod(next());
    } else if (arg == "--repeat") {
      o.repeat = std::max(1, std::atoi(next().c_str()));
    } else if (arg == "--quick") {
      o.elements = {1e3, 4e3};
      o.boundary = {1e2, 3e2};
      o.seconds = 0.3;
    } else {
      std::fprintf(stderr, "cdem_scale: unknown argument %s\n", arg.c_str());
      std::exit(2);
    }
  }
  for (int t : o.threads) {
    if (t < 1) {
      std::fprintf(stderr, "cdem_scale: --threads expects counts >= 1\n");
      std::exit(2);
    }
  }
  return o;
}

void throughput(const Options& o) {
  std::printf("## Element throughput: one 1 m square, spin %g rad/s, dt = 0.9 critical\n\n", spin);
  std::printf("| elements | nodes | boundary nodes | max_edge m | dt s | threads | steps | s | element-steps/s "
              "| x 1 thread | B/element | preempted |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::vector<std::vector<double>> per_thread_n(o.threads.size()), per_thread_t(o.threads.size());
  std::vector<std::array<double, 2>> goal_rates;  // elements, element-steps/s on 2 threads
  for (const double target : o.elements) {
    const double h = square_max_edge(target);
    const std::vector<dynamics::CdemBlockSpec> blocks{
        block("square", rectangle(0.0, 0.0, 1.0, 1.0), h, {0.0, 0.0, spin})};
    const double dt = stable_dt(blocks);
    const double before = resident_bytes();
    dynamics::Cdem sim(blocks, params_with(dt));
    for (int s = 0; s < 3; ++s) sim.step();
    const double bytes = resident_bytes() - before;
    const double elements = double(sim.element_count());
    const std::size_t boundary = boundary_nodes(sim);
    double one_thread = 0.0;
    for (std::size_t ti = 0; ti < o.threads.size(); ++ti) {
      const int threads = o.threads[ti];
      omp_set_num_threads(threads);
      const Timing t = best_of(o.repeat, [&] { return time_engine(sim, o.seconds); });
      const double wall = t.wall;
      const std::size_t steps = t.steps;
      const double rate = elements * double(steps) / wall;
      if (ti == 0) one_thread = rate;
      if (threads == 2) goal_rates.push_back({elements, rate});
      std::printf("| %.0f | %zu | %zu | %.4g | %.3g | %d | %zu | %.2f | %.3g | %.2f | %.0f | %ld |\n", elements,
                  sim.node_count(), boundary, h, dt, threads, steps, wall, rate, rate / one_thread,
                  bytes / elements, t.preempted);
      std::fflush(stdout);
      per_thread_n[ti].push_back(elements);
      per_thread_t[ti].push_back(wall / double(steps));
    }
  }
  std::printf("\n");
  for (std::size_t ti = 0; ti < o.threads.size(); ++ti) {
    if (per_thread_n[ti].size() >= 2) {
      std::printf("%d thread(s): time per step ~ elements^%.2f\n", o.threads[ti],
                  fitted_exponent(per_thread_n[ti], per_thread_t[ti]));
    }
  }
  for (const auto& [elements, rate] : goal_rates) {
    std::printf("goal %.0e element-steps/s on 2 threads, %.0f elements: %.3g (%.2f of the goal)\n", goal_element_steps,
                elements, rate, rate / goal_element_steps);
  }
  std::printf("\n");
}

struct SceneRow {
  std::string name;
  double per_step = 0.0;  // s
  std::size_t steps = 0, rounds = 0, boundary = 0, elements = 0;
  long preempted = 0;
};

// The three scenes of part 2 at max_edge 2^-k, each timed at `threads`.
std::vector<SceneRow> detection_scenes(int k, int threads, double budget, int repeat) {
  const double h = std::ldexp(1.0, -k), thick = strip_layers * h;
  const std::array<double, 3> rest{}, approach{0.0, -approach_speed, 0.0};
  const auto two = [&](double gap) {
    return std::vector<dynamics::CdemBlockSpec>{
        block("lower", rectangle(0.0, 0.0, 1.0, thick), h, rest),
        block("upper", rectangle(0.0, thick + gap, 1.0, 2.0 * thick + gap), h, approach)};
  };
  struct Scene {
    std::string name;
    std::vector<dynamics::CdemBlockSpec> blocks;
    bool closing;
  };
  const std::vector<Scene> scenes{{"alone", {block("strip", rectangle(0.0, 0.0, 2.0, thick), h, rest)}, false},
                                  {"far", two(far_gap), false},
                                  {"near", two(near_gap), true}};
  omp_set_num_threads(threads);
  std::vector<SceneRow> rows;
  for (const Scene& scene : scenes) {
    const double dt = stable_dt(scene.blocks);
    // The near strips close by at most half their gap on one engine: no touch inside a round.
    const std::size_t limit =
        scene.closing ? std::max<std::size_t>(3, static_cast<std::size_t>(0.5 * near_gap / (approach_speed * dt))) : 0;
    const auto make = [&] { return dynamics::Cdem(scene.blocks, params_with(dt)); };
    const Timing t = best_of(repeat, [&] { return time_steps(make, limit, 2, budget); });
    if (t.touches > 0) {
      std::fprintf(stderr, "cdem_scale: %zu contacts formed in the '%s' scene: its time includes the tie solve\n",
                   t.touches, scene.name.c_str());
    }
    const dynamics::Cdem sim = make();
    rows.push_back(
        {scene.name, t.per_step(), t.steps, t.rounds, boundary_nodes(sim), sim.element_count(), t.preempted});
  }
  return rows;
}

void detection(const Options& o) {
  std::printf("## Detection against boundary nodes: two strips 1 m x 8 max_edge, tolerance %g m\n\n", tolerance);
  std::printf("| boundary nodes | elements | threads | scene | steps (engines) | us/step | us/step per boundary node "
              "| - alone, us/step | - alone, us per boundary node | share of step | preempted |\n");
  std::printf("|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
  const std::vector<std::string> names{"alone", "far", "near"};
  // [thread][scene]: boundary nodes and time per step; differences from alone for far and near.
  std::vector<std::vector<std::vector<double>>> xs(o.threads.size(), std::vector<std::vector<double>>(5)),
      ys = xs;
  for (const double target : o.boundary) {
    // Two strips: 2 (2^k + 8) boundary nodes each.
    const int k = std::max(2, static_cast<int>(std::lround(std::log2(std::max(1.0, (target - 32.0) / 4.0)))));
    for (std::size_t ti = 0; ti < o.threads.size(); ++ti) {
      const std::vector<SceneRow> rows = detection_scenes(k, o.threads[ti], o.seconds, o.repeat);
      const SceneRow& alone = rows[0];
      for (std::size_t si = 0; si < rows.size(); ++si) {
        const SceneRow& r = rows[si];
        const double us = 1e6 * r.per_step, nodes = double(r.boundary);
        xs[ti][si].push_back(nodes);
        ys[ti][si].push_back(us);
        if (si == 0) {
          std::printf("| %zu | %zu | %d | %s | %zu (%zu) | %.1f | %.4f | | | | %ld |\n", r.boundary, r.elements,
                      o.threads[ti], r.name.c_str(), r.steps, r.rounds, us, us / nodes, r.preempted);
        } else {
          const double extra = us - 1e6 * alone.per_step;
          std::printf("| %zu | %zu | %d | %s | %zu (%zu) | %.1f | %.4f | %.1f | %.4f | %.0f%% | %ld |\n",
                      r.boundary, r.elements, o.threads[ti], r.name.c_str(), r.steps, r.rounds, us, us / nodes,
                      extra, extra / nodes, 100.0 * extra / us, r.preempted);
          if (extra > 0.0) {
            xs[ti][si + 2].push_back(nodes);
            ys[ti][si + 2].push_back(extra);
          }
        }
        std::fflush(stdout);
      }
    }
  }
  std::printf("\n");
  const std::vector<std::string> series{"alone", "far", "near", "far - alone (grid)", "near - alone (detection)"};
  for (std::size_t ti = 0; ti < o.threads.size(); ++ti) {
    for (std::size_t s = 0; s < series.size(); ++s) {
      if (xs[ti][s].size() >= 2) {
        std::printf("%d thread(s), %s: us/step ~ boundary nodes^%.2f\n", o.threads[ti], series[s].c_str(),
                    fitted_exponent(xs[ti][s], ys[ti][s]));
      }
    }
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  std::printf("cdem_scale: %d hardware threads, budget %.2g s per measurement, load average %.2f\n\n",
              omp_get_num_procs(), o.seconds, load_average());
  try {
    if (!o.elements.empty()) throughput(o);
    if (!o.boundary.empty()) detection(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cdem_scale: %s\n", e.what());
    return 1;
  }
  std::printf("peak resident set (VmHWM): %.0f MB; load average at the end %.2f\n", peak_resident_bytes() / 1e6,
              load_average());
  return 0;
}
