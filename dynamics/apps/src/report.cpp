#include "rockcontact/dynamics/apps/report.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "rockcontact/dynamics/io/atomic_file.hpp"
#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/dynamics/io/scene_output.hpp"
#include "rockcontact/dynamics/apps/validation.hpp"

extern char** environ;

namespace rockcontact::dynamics {

namespace {

using clock = std::chrono::steady_clock;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// Shortest round-trip form, for the CSV.
std::string exact_text(double value) {
  if (std::isnan(value)) return "";
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

std::string format(double value, int digits = 3) {
  std::ostringstream out;
  out << std::setprecision(digits) << value;
  return out.str();
}

// An observed order with one decimal ("1.9", "0.0"; "–" when undefined).
std::string order_text(double p) {
  if (std::isnan(p)) return "–";
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << (std::abs(p) < 0.05 ? 0.0 : p);
  return out.str();
}

// "16", "1", "1/2": a sweep factor as written in the tables and labels.
std::string factor_text(double factor) {
  return factor < 1.0 ? "1/" + format(1.0 / factor) : format(factor);
}

const BlockState& state(const Dda2d& simulation, std::string_view id) {
  const auto& blocks = simulation.blocks();
  return *std::find_if(blocks.begin(), blocks.end(),
                       [&](const BlockState& b) { return b.id == id; });
}

// The trajectory of a run: its measured quantities at equally spaced instants,
// samples[k][i] = quantity i at t_k.
using Samples = std::vector<std::vector<double>>;

// What one run is measured with: an observer of the simulation, the relative error it leaves
// at the end and, for the scenes whose reference is a converged run, its trajectory.
struct Probe {
  std::function<void(const Dda2d&)> observe;
  std::function<double()> error;
  std::function<Samples()> samples;  // empty for the analytic references
};

// The quantities a converged-run reference is compared on, in metres.
using Measure = std::function<std::vector<double>(const Dda2d&)>;

// Records measure(sim) at t_k = k T / n for k < n, interpolating linearly between the two
// observations around t_k (the observer sees t = 0 and the end of every step), and at the end
// of the run for k = n: runs with different dt are compared at the same instants. The
// interpolation error is O(dt²) on a smooth stretch of motion, below the integrator's.
class Sampler {
 public:
  Sampler(Measure measure, double duration, std::size_t intervals)
      : measure_(std::move(measure)), duration_(duration), intervals_(intervals) {}

  void observe(const Dda2d& sim) {
    const double t = sim.time();
    std::vector<double> q = measure_(sim);
    for (double tk = sample_time(); next_ < intervals_ && t >= tk; tk = sample_time()) {
      std::vector<double> s = q;
      if (tk < t && !last_.empty()) {
        const double w = (tk - last_time_) / (t - last_time_);
        for (std::size_t i = 0; i < s.size(); ++i) s[i] = last_[i] + w * (q[i] - last_[i]);
      }
      samples_.push_back(std::move(s));
      ++next_;
    }
    last_time_ = t;
    last_ = std::move(q);
  }

  Samples samples() const {
    Samples all = samples_;
    all.push_back(last_);
    return all;
  }

 private:
  double sample_time() const {
    return duration_ * static_cast<double>(next_) / static_cast<double>(intervals_);
  }

  Measure measure_;
  double duration_;
  std::size_t intervals_;
  std::size_t next_ = 0;
  Samples samples_;
  std::vector<double> last_;
  double last_time_ = 0.0;
};

// Instants a trajectory is sampled at: 100 intervals resolve a bounce or an impact of the
// scenes' durations, and keep each interval longer than the coarsest dt of the sweeps.
constexpr std::size_t sample_intervals = 100;

// max_k,i |q_ki - r_ki| / max_i (max_k r_ki - min_k r_ki): the largest departure from the
// reference trajectory, relative to the largest motion of any quantity in the reference.
double trajectory_error(const Samples& run, const Samples& reference) {
  if (run.size() != reference.size()) {
    throw std::logic_error("report: a run and its reference have different sample counts");
  }
  double scale = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < reference.front().size(); ++i) {
    double low = reference.front()[i], high = low;
    for (const auto& r : reference) low = std::min(low, r[i]), high = std::max(high, r[i]);
    scale = std::max(scale, high - low);
  }
  for (std::size_t k = 0; k < run.size(); ++k) {
    for (std::size_t i = 0; i < run[k].size(); ++i) {
      worst = std::max(worst, std::abs(run[k][i] - reference[k][i]));
    }
  }
  return worst / scale;
}

// A probe that samples `measure` over the run and compares with the reference trajectory
// (none when this run is the reference itself: its error is 0).
Probe trajectory_probe(Measure measure, double duration, const Samples* reference) {
  auto sampler = std::make_shared<Sampler>(std::move(measure), duration, sample_intervals);
  return {[sampler](const Dda2d& sim) { sampler->observe(sim); },
          [sampler, reference] {
            return reference ? trajectory_error(sampler->samples(), *reference) : 0.0;
          },
          [sampler] { return sampler->samples(); }};
}

// Every block that moves: centroid x and y, and the rotation as the arc it sweeps at the
// block's size sqrt(A), so that all quantities are lengths.
std::vector<double> movable_blocks(const Dda2d& sim) {
  std::vector<double> q;
  for (const BlockState& b : sim.blocks()) {
    if (b.fixed) continue;
    q.insert(q.end(), {b.centroid.x, b.centroid.y, std::sqrt(b.area) * b.rotation});
  }
  return q;
}

// §4.1: equal masses, central elastic impact: the velocities are exchanged. Error:
// max(|vA'|, |vB' - vA|) / vA at the end. It does not vanish as dt -> 0: the deformable blocks
// keep part of the impact as strain vibration (validation.cpp: well below 1e-3 of vA).
Probe velocity_exchange(const Scene&, const Samples*) {
  auto v0 = std::make_shared<double>(nan);
  auto va = std::make_shared<double>(nan);
  auto vb = std::make_shared<double>(nan);
  return {[=](const Dda2d& sim) {
            *va = state(sim, "A").velocity[0];
            *vb = state(sim, "B").velocity[0];
            if (std::isnan(*v0)) *v0 = *va;
          },
          [=] { return std::max(std::abs(*va), std::abs(*vb - *v0)) / std::abs(*v0); },
          nullptr};
}

constexpr double incline_theta = std::numbers::pi / 6.0;  // the 30° slope of the scene files

// §4.3: the slide down the slope against eq. 30, l = ½ g (sin θ - cos θ tan φ) t², at the end
// of the run. The penalty contact's stick start-up leaves a floor that falls as 1 / t
// (validation.cpp: 0.12 % at 2 s for φ = 10°, 0.66 % for φ = 20°, none for φ = 0°).
Probe incline_slide(const Scene& scene, const Samples*) {
  const double g = std::hypot(scene.params.gravity.x, scene.params.gravity.y);
  const double phi =
      scene.law.friction ? scene.law.friction->friction_angle_deg * std::numbers::pi / 180.0 : 0.0;
  struct Track {
    Point2 start{nan, nan}, end{nan, nan};
    double time = 0.0;
  };
  auto track = std::make_shared<Track>();
  return {[=](const Dda2d& sim) {
            const Point2 c = state(sim, "block").centroid;
            if (std::isnan(track->start.x)) track->start = c;
            track->end = c;
            track->time = sim.time();
          },
          [=] {
            const double l = incline_slide_eq30(g, incline_theta, phi, track->time);
            const double slide = slide_down_slope(track->start, track->end, incline_theta);
            return std::abs(slide - l) / l;
          },
          nullptr};
}

// The incline block starts at its static penetration δ = m g cos θ H / (2 kn L) (to first order
// in δ / L), so that the normal spring starts in equilibrium (examples/scenes/README.md). δ goes
// as 1 / kn: with kn scaled, the block is moved along the slope's normal to δ / factor, or a
// stiffer spring would throw it off the slope and a softer one drop it, both transients
// unrelated to the contact's accuracy.
void reseat_incline_block(Scene& scene, double kn_factor) {
  const Vector2 normal{-std::sin(incline_theta), std::cos(incline_theta)};  // out of the slope
  for (BlockSpec& block : scene.blocks) {
    if (block.id != "block") continue;
    double depth = 0.0;  // of the deepest vertex below the slope line through the origin
    for (const Point2& v : block.vertices) {
      depth = std::max(depth, -(normal.x * v.x + normal.y * v.y));
    }
    const double lift = depth - depth / kn_factor;
    for (Point2& v : block.vertices) v = {v.x + lift * normal.x, v.y + lift * normal.y};
  }
}

// The settings a scene is swept over; the demarcation always takes both modes.
struct Sweep {
  std::vector<double> dt_factors, kn_factors;
  std::vector<kernel::PolicyKind> policies{kernel::PolicyKind::float_, kernel::PolicyKind::filtered,
                                           kernel::PolicyKind::exact};
};

// A scene without a closed form is measured against a converged run of itself: dt a quarter
// of the sweep's finest, kn and kt at the sweep's largest factor, exact demarcation, and
// `policy` (exact, unless its cost rules it out: then `why`).
struct ConvergedReference {
  kernel::PolicyKind policy = kernel::PolicyKind::exact;
  std::string why;
};
constexpr double reference_refinement = 4.0;

struct ReferenceFactors {
  double dt, kn;  // of the scene's dt and kn
};

// A scene of the report: its file, its reference and how a run of it is measured.
struct ReportScene {
  std::string name;       // as in `validate`
  std::string slug;       // file stem of its plot
  std::string file;       // in scenes_dir
  std::string reference;  // what the error is measured against (analytic) or on (converged)
  double duration = 0.0, quick_duration = 0.0;  // s
  Sweep full, quick;
  // Exact-policy runs with more steps are skipped (see report.hpp); 0: no limit.
  std::size_t exact_steps = 0, quick_exact_steps = 0;
  std::optional<ConvergedReference> converged{};  // empty: the reference is analytic
  // Called after kn and kt were scaled by the factor (may be empty).
  std::function<void(Scene&, double)> restiffen{};
  // The probe of a run of `scene` (its duration set); `reference` is the converged run's
  // trajectory, null for the analytic scenes and for the converged run itself.
  std::function<Probe(const Scene&, const Samples* reference)> probe;

  const Sweep& sweep(bool quick_run) const { return quick_run ? quick : full; }
  double window(bool quick_run) const { return quick_run ? quick_duration : duration; }
  // The converged run's dt and kn factors (ConvergedReference).
  ReferenceFactors reference_factors(bool quick_run) const {
    const Sweep& s = sweep(quick_run);
    return {*std::min_element(s.dt_factors.begin(), s.dt_factors.end()) / reference_refinement,
            *std::max_element(s.kn_factors.begin(), s.kn_factors.end())};
  }
};

// The centre of mass of the blocks cut from the scene's region (the §6.1 rock mass). A
// collapse branches at every block collision: single blocks' paths part between runs that
// differ only by rounding, and no refinement makes them converge. The centre of mass averages
// the branchings out, and it carries the collapse's runout.
Measure rock_mass_centre(const Scene& scene) {
  const std::size_t first = scene.generated_first, count = scene.generated_count;
  return [first, count](const Dda2d& sim) {
    double mass = 0.0, x = 0.0, y = 0.0;
    for (std::size_t i = first; i < first + count; ++i) {
      const BlockState& b = sim.blocks()[i];
      mass += b.mass;
      x += b.mass * b.centroid.x;
      y += b.mass * b.centroid.y;
    }
    return std::vector<double>{x / mass, y / mass};
  };
}

Probe blocks_probe(const Scene& scene, const Samples* reference) {
  return trajectory_probe(movable_blocks, scene.duration, reference);
}

Probe rock_mass_probe(const Scene& scene, const Samples* reference) {
  return trajectory_probe(rock_mass_centre(scene), scene.duration, reference);
}

// A scene measured against its converged run, on every moving block's path.
ReportScene converged_scene(std::string name, const std::string& stem, double duration,
                            double quick_duration, Sweep full, Sweep quick,
                            std::size_t exact_steps = 0, std::size_t quick_exact_steps = 0) {
  return {.name = std::move(name),
          .slug = stem,
          .file = stem + ".json",
          .reference = "every moving block's centroid x, y and rotation × √A",
          .duration = duration,
          .quick_duration = quick_duration,
          .full = std::move(full),
          .quick = std::move(quick),
          .exact_steps = exact_steps,
          .quick_exact_steps = quick_exact_steps,
          .converged = ConvergedReference{},
          .probe = blocks_probe};
}

std::vector<ReportScene> report_scenes() {
  using enum kernel::PolicyKind;
  std::vector<ReportScene> scenes;
  const Sweep analytic_full{{32.0, 16.0, 8.0, 4.0, 2.0, 1.0, 0.5}, {0.1, 1.0, 10.0}};
  const Sweep analytic_quick{{32.0, 16.0, 4.0, 1.0}, {1.0, 10.0}};
  scenes.push_back({.name = "4.1 two squares",
                    .slug = "collision_squares",
                    .file = "collision_squares.json",
                    .reference = "velocity exchange vA' = 0, vB' = vA (equal masses, elastic impact)",
                    .duration = 0.5,
                    .quick_duration = 0.25,
                    .full = analytic_full,
                    .quick = analytic_quick,
                    .probe = velocity_exchange});
  for (const char* phi : {"00", "10", "20"}) {
    const std::string deg = phi[0] == '0' ? std::string(phi + 1) : std::string(phi);
    // The incline's exact runs: 4000 steps are ~8 s each, 200 steps under --quick.
    scenes.push_back({.name = "4.3 incline phi=" + deg + "°",
                      .slug = std::string("incline_phi") + phi,
                      .file = std::string("incline_phi") + phi + ".json",
                      .reference = "eq. 30: l = ½ g (sin θ - cos θ tan φ) t²",
                      .duration = 0.5,
                      .quick_duration = 0.03,
                      .full = analytic_full,
                      .quick = analytic_quick,
                      .exact_steps = 4000,
                      .quick_exact_steps = 200,
                      .restiffen = reseat_incline_block,
                      .probe = incline_slide});
  }
  // No closed form: the windows hold each scene's event (§4.2: the wedge lands and settles;
  // §5.1: the drop, the impact and the first rebound; §5.2: the head-on impact and the
  // separation; §5.3: the impact and the rebound; §6: the start of the collapse, the slump
  // and the toppling).
  const Sweep small_quick{{2.0, 1.0}, {1.0}};
  const Sweep small_full{{8.0, 4.0, 2.0, 1.0, 0.5}, {1.0, 10.0}};
  scenes.push_back(converged_scene("4.2 symmetric system", "symmetric_system", 1.0, 0.5,
                                   {{4.0, 2.0, 1.0, 0.5, 0.25}, {1.0, 10.0}}, small_quick));
  scenes.push_back(converged_scene("5.1 bounce thin base", "bounce_thin_base", 0.8, 0.6,
                                   small_full, small_quick));
  scenes.push_back(converged_scene("5.1 bounce thick base", "bounce_thick_base", 0.8, 0.6,
                                   small_full, small_quick));
  // The triangles' dt is 2e-5 s: exact runs above 20 000 steps (~5 s each) are skipped.
  scenes.push_back(converged_scene("5.2 5° triangles", "small_angle_triangles", 0.2, 0.1,
                                   small_full, small_quick, 20000, 5000));
  scenes.push_back(converged_scene("5.3 vertex on 0.01 m edge", "small_edge_vertex", 0.4, 0.3,
                                   small_full, small_quick));
  scenes.push_back(converged_scene("5.3 vertex on neighbour edge", "small_edge_neighbour", 0.4,
                                   0.3, small_full, small_quick));
  // §6: hundreds of blocks. The exact policy's constructions cost 0.18 s a step on the collapse
  // (30 ms on the valley) against ~1 ms filtered, so the sweeps run float and filtered and the
  // reference is filtered: its predicates decide as the exact policy's, and its constructions
  // differ from the exact ones by rounding, far below the errors of dt and kn.
  const ConvergedReference filtered_reference{
      filtered,
      "exact constructions cost 30 ms (valley) to 0.18 s (collapse) a step; filtered predicates "
      "decide as the exact ones"};
  // Their dt is within a factor 2 of the stability limit at kn x 1 (1.7e-4 s on the collapse).
  const Sweep large_full{{1.0, 0.5, 0.25}, {1.0, 10.0}, {float_, filtered}};
  const Sweep large_quick{{1.0, 0.5}, {1.0}, {float_, filtered}};
  for (const char* phi : {"15", "30"}) {
    ReportScene s = converged_scene(std::string("6.1 collapse phi=") + phi + "°",
                                    std::string("collapse_phi") + phi, 0.5, 0.05, large_full,
                                    large_quick);
    s.reference = "the rock mass's centre of mass x, y (single blocks' paths branch)";
    s.converged = filtered_reference;
    s.probe = rock_mass_probe;
    scenes.push_back(std::move(s));
  }
  ReportScene valley =
      converged_scene("6.2 valley", "toppling_slumping", 0.5, 0.05, large_full, large_quick);
  valley.converged = filtered_reference;
  scenes.push_back(std::move(valley));
  return scenes;
}

// The scene with kn and kt (of the law and of every interface) scaled.
Scene stiffened(Scene scene, double factor) {
  scene.law.normal.kn *= factor;
  if (scene.law.friction) scene.law.friction->kt *= factor;
  for (Interface& i : scene.law.interfaces) {
    i.kn *= factor;
    if (i.friction) i.friction->kt *= factor;
  }
  return scene;
}

// One run of the sweep. `reference` is the converged run's trajectory for the scenes that have
// one. With `trajectory` set, this run is the converged reference itself: its status is
// "reference" once completed, and its trajectory is stored there.
ReportRun run_one(const ReportScene& entry, const Scene& base, bool quick,
                  kernel::PolicyKind policy, kernel::Demarcation demarcation, double dt_factor,
                  double kn_factor, const Samples* reference, Samples* trajectory = nullptr) {
  Scene scene = stiffened(base, kn_factor);
  if (entry.restiffen) entry.restiffen(scene, kn_factor);
  scene.law.policy = policy;
  scene.law.normal.demarcation = demarcation;
  scene.params.dt *= dt_factor;
  scene.params.threads = 1;
  scene.duration = entry.window(quick);
  ReportRun run;
  run.scene = entry.name;
  run.policy = policy;
  run.demarcation = demarcation;
  run.dt_factor = dt_factor;
  run.dt = scene.params.dt;
  run.kn_factor = kn_factor;
  run.kn = scene.law.normal.kn;
  run.kt = scene.law.friction ? scene.law.friction->kt : 0.0;
  const std::size_t limit = quick ? entry.quick_exact_steps : entry.exact_steps;
  if (!trajectory && policy == kernel::PolicyKind::exact && limit > 0 &&
      step_count(scene) > limit) {
    run.status = "skipped";
    return run;
  }
  const Probe probe = entry.probe(scene, reference);
  RunOptions options;
  options.observer = probe.observe;
  const auto start = clock::now();
  try {
    const RunReport report = run_scene(scene, options);
    run.status = report.status;
    run.calls = report.predicates.total_calls();
    run.fallbacks = report.predicates.total_fallbacks();
    run.critical_dt = report.critical_time_step;
    if (report.status == "completed" && trajectory) {
      *trajectory = probe.samples();
      run.status = "reference";
    } else if (report.status == "completed") {
      run.error = probe.error();
    }
  } catch (const StabilityError&) {  // dt above the critical estimate: refused at construction
    run.status = "refused";
  }
  run.seconds = std::chrono::duration<double>(clock::now() - start).count();
  return run;
}

// The converged run of a scene that has no closed form (ConvergedReference).
ReportRun reference_run(const ReportScene& entry, const Scene& base, bool quick,
                        Samples& trajectory) {
  const ReferenceFactors f = entry.reference_factors(quick);
  return run_one(entry, base, quick, entry.converged->policy, kernel::Demarcation::exact, f.dt,
                 f.kn, nullptr, &trajectory);
}

// What a scene's errors are measured against, in one line: the formula, or the converged run
// with its settings and what is compared.
std::string reference_text(const ReportScene& entry, bool quick) {
  if (!entry.converged) return "analytic: " + entry.reference;
  const ReferenceFactors f = entry.reference_factors(quick);
  return "converged run (" + std::string(kernel::to_string(entry.converged->policy)) +
         "/exact, dt ×" + factor_text(f.dt) + ", kn ×" + factor_text(f.kn) +
         ") on " + entry.reference;
}

void write_csv(const std::filesystem::path& file, std::span<const ReportRun> runs) {
  AtomicFile out(file);
  out.stream() << "scene,policy,demarcation,dt_factor,dt,kn_factor,kn,kt,status,error,"
                  "wall_seconds,predicate_calls,fallbacks,critical_dt,pareto\n";
  for (const ReportRun& r : runs) {
    out.stream() << r.scene << ',' << kernel::to_string(r.policy) << ','
                 << kernel::to_string(r.demarcation) << ',' << exact_text(r.dt_factor) << ','
                 << exact_text(r.dt) << ',' << exact_text(r.kn_factor) << ',' << exact_text(r.kn)
                 << ',' << exact_text(r.kt) << ',' << r.status << ',' << exact_text(r.error) << ','
                 << exact_text(r.seconds) << ',' << r.calls << ',' << r.fallbacks << ','
                 << exact_text(r.critical_dt) << ',' << (r.pareto ? 1 : 0) << '\n';
  }
  out.commit();
}

std::string setting(const ReportRun& r) {
  return std::string(kernel::to_string(r.policy)) + "/" +
         std::string(kernel::to_string(r.demarcation));
}

// The cheapest completed run within 1 % error, in one sentence; else the best error reached.
std::string headline(const std::string& name, std::span<const ReportRun> runs) {
  const ReportRun* cheapest = nullptr;
  const ReportRun* best = nullptr;
  for (const ReportRun& r : runs) {
    if (r.scene != name || r.status != "completed") continue;
    if (!best || r.error < best->error) best = &r;
    if (r.error <= 0.01 && (!cheapest || r.seconds < cheapest->seconds)) cheapest = &r;
  }
  if (cheapest) {
    return "To get 1 % error on " + name + " you need dt ≤ " + format(cheapest->dt) + " s (kn ×" +
           factor_text(cheapest->kn_factor) + ", " + setting(*cheapest) + ") and it costs " +
           format(cheapest->seconds, 2) + " s (error " + format(100.0 * cheapest->error, 2) +
           " %).";
  }
  if (best) {
    return "No run of " + name + " reaches 1 % error; the best is " +
           format(100.0 * best->error, 3) + " % at dt = " + format(best->dt) + " s (kn ×" +
           factor_text(best->kn_factor) + ", " + setting(*best) + "), " + format(best->seconds, 2) +
           " s.";
  }
  return "No run of " + name + " completed.";
}

// A string in a gnuplot single-quoted literal ('' stands for ').
std::string gnuplot_quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// The line style of a setting, the same in every plot: a colour per policy, a point type per
// demarcation, dashes for a kn other than the scene's.
std::string line_style(kernel::PolicyKind policy, kernel::Demarcation mode, double kn_factor) {
  const char* colour = policy == kernel::PolicyKind::float_     ? "#d62728"
                       : policy == kernel::PolicyKind::filtered ? "#1f77b4"
                                                                : "#2ca02c";
  const int point = mode == kernel::Demarcation::paper ? 6 : 7;  // open / filled circle
  const int dash = kn_factor == 1.0 ? 1 : kn_factor < 1.0 ? 2 : 3;
  return std::string("lc rgb '") + colour + "' pt " + std::to_string(point) + " dt " +
         std::to_string(dash);
}

// Below this largest error a scene's runs differ by rounding only: a plot would show noise.
constexpr double round_off_error = 1e-12;

// The gnuplot script of a scene's work-precision diagram, writing base.png and base.svg.
std::string plot_script(const ReportScene& entry, const std::filesystem::path& base,
                        std::span<const ReportRun> runs, bool quick) {
  struct Curve {
    std::string title;
    std::string style;
    std::vector<ReportRun> points;
    bool labelled;
  };
  std::vector<Curve> curves;
  const auto completed = [](const ReportRun& r) {
    return r.status == "completed" && r.error > 0.0;
  };
  for (const auto policy :
       {kernel::PolicyKind::float_, kernel::PolicyKind::filtered, kernel::PolicyKind::exact}) {
    for (const auto mode : {kernel::Demarcation::paper, kernel::Demarcation::exact}) {
      std::map<double, Curve> by_kn;
      for (const ReportRun& r : runs) {
        if (r.scene != entry.name || r.policy != policy || r.demarcation != mode || !completed(r))
          continue;
        // The other kn only for filtered/exact, the default setting: 18 curves would be unreadable.
        const bool base_kn = r.kn_factor == 1.0;
        if (!base_kn &&
            (policy != kernel::PolicyKind::filtered || mode != kernel::Demarcation::exact))
          continue;
        Curve& c = by_kn[r.kn_factor];
        c.title = setting(r) + (base_kn ? "" : " kn ×" + factor_text(r.kn_factor));
        c.style = line_style(policy, mode, r.kn_factor);
        c.labelled = policy == kernel::PolicyKind::filtered && mode == kernel::Demarcation::exact;
        c.points.push_back(r);
      }
      for (auto& [kn, c] : by_kn) {
        const double p = convergence_order(c.points);
        if (!std::isnan(p)) c.title += ", order " + order_text(p);
        curves.push_back(std::move(c));
      }
    }
  }
  std::ostringstream gp;
  gp << "# Work-precision diagram of " << entry.name << ", written by `rockcontact report`.\n"
     << "set logscale xy\nset grid\nset key outside below horizontal maxcols 3 font ',9'\n"
     << "set format xy '%g'\n"
     << "set title " << gnuplot_quoted(entry.name + (quick ? " (--quick: short runs)" : "")) << '\n'
     << "set label 1 " << gnuplot_quoted("error against the " + reference_text(entry, quick))
     << " at graph 0.5, graph 1.02 center font ',9'\n"
     << "set xlabel 'wall time of the run (s)'\nset ylabel 'relative error'\n";
  for (std::size_t i = 0; i < curves.size(); ++i) {
    gp << "$c" << i << " << EOD\n";
    for (const ReportRun& r : curves[i].points) {
      gp << exact_text(r.seconds) << ' ' << exact_text(r.error) << " \"dt×"
         << factor_text(r.dt_factor) << "\"\n";
    }
    gp << "EOD\n";
  }
  std::ostringstream plot;
  plot << "plot ";
  for (std::size_t i = 0; i < curves.size(); ++i) {
    plot << (i ? ", \\\n     " : "") << "$c" << i << " using 1:2 with linespoints "
         << curves[i].style << " title " << gnuplot_quoted(curves[i].title);
    if (curves[i].labelled) {
      plot << ", $c" << i << " using 1:2:3 with labels offset 1,0.6 font ',8' notitle";
    }
  }
  if (curves.empty()) plot << "1/0 title 'no completed run'";
  const std::string png = base.string() + ".png", svg = base.string() + ".svg";
  gp << "set terminal pngcairo size 900,640\nset output " << gnuplot_quoted(png) << '\n'
     << plot.str() << "\nset output\n"
     << "set terminal svg size 900,640 dynamic\nset output " << gnuplot_quoted(svg) << '\n'
     << plot.str() << "\nset output\n";
  return gp.str();
}

// Runs `program script`; true when it exits with status 0.
bool run_program(const std::string& program, const std::filesystem::path& script) {
  const std::string script_text = script.string();
  std::vector<char*> argv{const_cast<char*>(program.c_str()),
                          const_cast<char*>(script_text.c_str()), nullptr};
  pid_t pid = 0;
  if (posix_spawnp(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
    return false;
  }
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return false;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// The largest error of a scene's completed runs (0 when none completed).
double largest_error(const std::string& scene, std::span<const ReportRun> runs) {
  double largest = 0.0;
  for (const ReportRun& r : runs) {
    if (r.scene == scene && r.status == "completed") largest = std::max(largest, r.error);
  }
  return largest;
}

bool write_plot(const ReportOptions& options, const ReportScene& entry,
                std::span<const ReportRun> runs) {
  const std::filesystem::path base = options.out_dir / entry.slug;
  std::filesystem::path script = base;
  script += ".gp";
  AtomicFile file(script);
  file.stream() << plot_script(entry, base, runs, options.quick);
  file.commit();
  if (options.gnuplot.empty() || !run_program(options.gnuplot, script)) return false;
  for (const char* ext : {".png", ".svg"}) {
    std::filesystem::path out = base;
    out += ext;
    std::error_code ec;
    if (std::filesystem::file_size(out, ec) == 0 || ec) return false;
  }
  return true;
}

void write_stability(std::ostream& md, const std::string& name, std::span<const ReportRun> runs,
                     std::span<const double> kn_factors) {
  md << "\n**Stability limit** (over every policy and demarcation; `refused`: dt above the "
        "engine's critical estimate, `stopped`: the stability monitor stopped the run):\n\n"
     << "| kn × | largest stable dt (s) | smallest unstable dt (s) | engine estimate 2/ω_max (s) "
        "|\n"
     << "|---|---|---|---|\n";
  for (const double k : kn_factors) {
    double stable = nan, unstable = nan, estimate = nan;
    for (const ReportRun& r : runs) {
      if (r.scene != name || r.kn_factor != k) continue;
      if (r.status == "completed") {
        stable = std::isnan(stable) ? r.dt : std::max(stable, r.dt);
        estimate = r.critical_dt;
      }
      if (r.status == "refused" || r.status == "stopped") {
        unstable = std::isnan(unstable) ? r.dt : std::min(unstable, r.dt);
      }
    }
    const auto cell = [](double v, const char* none) {
      return std::isnan(v) ? std::string(none) : format(v);
    };
    md << "| " << factor_text(k) << " | " << cell(stable, "none") << " | "
       << cell(unstable, "none in the sweep") << " | " << cell(estimate, "–") << " |\n";
  }
}

void write_fallbacks(std::ostream& md, const std::string& name, std::span<const ReportRun> runs) {
  md << "\n**Exact fallbacks** (summed over the scene's runs that were not refused or skipped; "
        "every policy counts some, because the engine's penetration monitor always runs the "
        "filtered predicates):\n\n"
     << "| policy/demarcation | predicate calls | fallbacks | rate |\n|---|---|---|---|\n";
  std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> totals;
  for (const ReportRun& r : runs) {
    if (r.scene != name || r.status == "refused" || r.status == "skipped") continue;
    auto& [calls, fallbacks] = totals[setting(r)];
    calls += r.calls;
    fallbacks += r.fallbacks;
  }
  for (const auto& [key, counts] : totals) {
    md << "| " << key << " | " << counts.first << " | " << counts.second << " | "
       << (counts.first
               ? format(static_cast<double>(counts.second) / static_cast<double>(counts.first))
               : "–")
       << " |\n";
  }
}

void write_pareto(std::ostream& md, const std::string& name, std::span<const ReportRun> runs) {
  std::vector<const ReportRun*> front;
  for (const ReportRun& r : runs) {
    if (r.scene == name && r.pareto) front.push_back(&r);
  }
  std::sort(front.begin(), front.end(),
            [](const ReportRun* a, const ReportRun* b) { return a->seconds < b->seconds; });
  md << "\n**Pareto-best settings** (no other run is both faster and more accurate):\n\n"
     << "| dt (s) | dt × | kn × | policy/demarcation | error | wall s "
        "|\n|---|---|---|---|---|---|\n";
  for (const ReportRun* r : front) {
    md << "| " << format(r->dt) << " | " << factor_text(r->dt_factor) << " | "
       << factor_text(r->kn_factor) << " | " << setting(*r) << " | " << format(r->error) << " | "
       << format(r->seconds) << " |\n";
  }
}

// "{32, 16, 1/2}": a list of sweep factors.
std::string factor_list(std::span<const double> factors) {
  std::string text = "{";
  for (std::size_t i = 0; i < factors.size(); ++i) text += (i ? ", " : "") + factor_text(factors[i]);
  return text + "}";
}

// The observed order of every curve of a scene, one table row per policy/demarcation and kn.
void write_orders(std::ostream& md, const std::string& name, std::span<const ReportRun> runs) {
  std::map<std::string, std::vector<ReportRun>> curves;
  for (const ReportRun& r : runs) {
    if (r.scene == name && r.status == "completed" && r.error > 0.0) {
      curves[setting(r) + " | " + factor_text(r.kn_factor)].push_back(r);
    }
  }
  md << "\n**Observed order** p in error ≈ C dt^p (least-squares slope of ln error against ln "
        "dt over the completed runs of a curve; a curve that has reached the error floor of its "
        "kn or of the reference's shows p near 0):\n\n"
     << "| policy/demarcation | kn × | runs | p |\n|---|---|---|---|\n";
  for (const auto& [key, points] : curves) {
    const double p = convergence_order(points);
    md << "| " << key << " | " << points.size() << " | " << order_text(p) << " |\n";
  }
}

void write_index(const ReportOptions& options, const std::vector<ReportScene>& scenes,
                 const ReportSummary& summary, const std::vector<bool>& plotted) {
  AtomicFile file(options.out_dir / "index.md");
  std::ostream& md = file.stream();
  md << "# Error against run time (`rockcontact report" << (options.quick ? " --quick" : "")
     << "`)\n\n"
     << summary.runs.size() << " runs, one thread each, in " << format(summary.seconds)
     << " s of wall time; every run is in [runs.csv](runs.csv). Each scene is swept over dt "
        "and kn (kn and kt scaled together), the policies listed and both demarcations "
        "(paper | exact). Errors are relative: against a closed form where the paper gives one "
        "(§4.1, §4.3), else against a converged run of the scene, the finest dt and stiffest "
        "kn of the sweep refined once more (dt / 4), on the quantities named.\n";
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const ReportScene& e = scenes[i];
    const Sweep& s = e.sweep(options.quick);
    md << "\n## " << e.name << "\n\n"
       << "Scene `" << e.file << "`, " << format(e.window(options.quick))
       << " s simulated; dt × " << factor_list(s.dt_factors) << " of its dt, kn × "
       << factor_list(s.kn_factors) << ", policies";
    for (const kernel::PolicyKind p : s.policies) md << ' ' << kernel::to_string(p);
    md << ". Reference, " << reference_text(e, options.quick) << '.';
    if (e.converged && !e.converged->why.empty()) md << " Not exact: " << e.converged->why << '.';
    if (e.converged) {
      // The reference run is the scene's first row; the sweep runs only when it completed.
      const auto first = std::find_if(summary.runs.begin(), summary.runs.end(),
                                      [&](const ReportRun& r) { return r.scene == e.name; });
      if (first->status == "reference") {
        md << " The reference run took " << format(first->seconds) << " s.";
      } else {
        md << " The reference run did not complete (" << first->status << "): no sweep.";
      }
    }
    md << "\n\n" << summary.headlines[i] << "\n\n";
    const double largest = largest_error(e.name, summary.runs);
    if (largest < round_off_error) {
      md << "No plot: every run's error is rounding (the largest " << format(largest)
         << "), so the curves would show noise only.\n";
    } else if (plotted[i]) {
      md << "![" << e.name << "](" << e.slug << ".png) ([SVG](" << e.slug << ".svg))\n";
    } else {
      md << "Plot missing: gnuplot did not run (script in `" << e.slug << ".gp`).\n";
    }
    write_orders(md, e.name, summary.runs);
    write_stability(md, e.name, summary.runs, s.kn_factors);
    write_fallbacks(md, e.name, summary.runs);
    write_pareto(md, e.name, summary.runs);
  }
  file.commit();
}

}  // namespace

void mark_pareto(std::span<ReportRun> runs) {
  for (ReportRun& r : runs) {
    r.pareto = r.status == "completed";
    for (const ReportRun& o : runs) {
      if (!r.pareto) break;
      if (&o == &r || o.scene != r.scene || o.status != "completed") continue;
      const bool no_worse = o.error <= r.error && o.seconds <= r.seconds;
      const bool better = o.error < r.error || o.seconds < r.seconds;
      if (no_worse && better) r.pareto = false;
    }
  }
}

double convergence_order(std::span<const ReportRun> runs) {
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (const ReportRun& r : runs) {
    if (!(r.error > 0.0) || !(r.dt > 0.0)) continue;
    const double x = std::log(r.dt), y = std::log(r.error);
    n += 1.0, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double spread = n * sxx - sx * sx;
  if (n < 2.0 || !(spread > 1e-12 * n * sxx + 1e-300)) return nan;
  return (n * sxy - sx * sy) / spread;
}

ReportSummary run_report(const ReportOptions& options) {
  const auto start = clock::now();
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) throw OutputError(options.out_dir.string() + ": cannot create: " + ec.message());
  const std::vector<ReportScene> scenes = report_scenes();
  ReportSummary summary;
  if (options.on_start) {
    std::size_t count = 0;
    for (const ReportScene& e : scenes) {
      const Sweep& s = e.sweep(options.quick);
      count += (e.converged ? 1 : 0) +
               s.policies.size() * 2 * s.kn_factors.size() * s.dt_factors.size();
    }
    options.on_start(count, scenes.size());
  }
  for (const ReportScene& entry : scenes) {
    if (options.on_scene) options.on_scene(entry.name);
    const Scene base = read_scene_file(options.scenes_dir / entry.file);
    Samples trajectory;
    if (entry.converged) {
      summary.runs.push_back(reference_run(entry, base, options.quick, trajectory));
      if (summary.runs.back().status != "reference") continue;
    }
    const Samples* reference = entry.converged ? &trajectory : nullptr;
    const Sweep& s = entry.sweep(options.quick);
    for (const auto policy : s.policies) {
      for (const auto mode : {kernel::Demarcation::paper, kernel::Demarcation::exact}) {
        for (const double k : s.kn_factors) {
          for (const double f : s.dt_factors) {
            summary.runs.push_back(
                run_one(entry, base, options.quick, policy, mode, f, k, reference));
          }
        }
      }
    }
  }
  mark_pareto(summary.runs);
  for (const ReportScene& entry : scenes)
    summary.headlines.push_back(headline(entry.name, summary.runs));
  std::vector<bool> plotted;
  for (const ReportScene& entry : scenes) {
    // A scene whose errors are all rounding gets a sentence instead (write_index).
    plotted.push_back(largest_error(entry.name, summary.runs) < round_off_error ||
                      write_plot(options, entry, summary.runs));
  }
  summary.plots = std::all_of(plotted.begin(), plotted.end(), [](bool p) { return p; });
  write_csv(options.out_dir / "runs.csv", summary.runs);
  summary.seconds = std::chrono::duration<double>(clock::now() - start).count();
  write_index(options, scenes, summary, plotted);
  return summary;
}

}  // namespace rockcontact::dynamics
