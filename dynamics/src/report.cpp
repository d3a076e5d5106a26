#include "rockcontact/dynamics/report.hpp"

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
#include <sstream>
#include <utility>

#include "rockcontact/dynamics/atomic_file.hpp"
#include "rockcontact/dynamics/scene.hpp"
#include "rockcontact/dynamics/scene_output.hpp"
#include "rockcontact/dynamics/validation.hpp"

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

// "16", "1", "1/2": a sweep factor as written in the tables and labels.
std::string factor_text(double factor) {
  return factor < 1.0 ? "1/" + format(1.0 / factor) : format(factor);
}

const BlockState& state(const Dda2d& simulation, std::string_view id) {
  const auto& blocks = simulation.blocks();
  return *std::find_if(blocks.begin(), blocks.end(),
                       [&](const BlockState& b) { return b.id == id; });
}

// What one run is measured with: an observer of the simulation and the relative error it
// leaves at the end.
struct Probe {
  std::function<void(const Dda2d&)> observe;
  std::function<double()> error;
};

// A scene of the report: its file, its reference and how a run of it is measured.
struct ReportScene {
  std::string name;                             // as in `validate`
  std::string slug;                             // file stem of its plot
  std::string file;                             // in scenes_dir
  std::string reference;                        // what the error is measured against
  double duration = 0.0, quick_duration = 0.0;  // s
  // Exact-policy runs with more steps are skipped (see report.hpp).
  std::size_t exact_steps = 0, quick_exact_steps = 0;
  // Called after kn and kt were scaled by the factor (may be empty).
  std::function<void(Scene&, double)> restiffen;
  std::function<Probe(const Scene&)> probe;
};

// §4.1: equal masses, central elastic impact: the velocities are exchanged. Error:
// max(|vA'|, |vB' - vA|) / vA at the end. It does not vanish as dt -> 0: the deformable blocks
// keep part of the impact as strain vibration (validation.cpp: well below 1e-3 of vA).
Probe velocity_exchange(const Scene&) {
  auto v0 = std::make_shared<double>(nan);
  auto va = std::make_shared<double>(nan);
  auto vb = std::make_shared<double>(nan);
  return {[=](const Dda2d& sim) {
            *va = state(sim, "A").velocity[0];
            *vb = state(sim, "B").velocity[0];
            if (std::isnan(*v0)) *v0 = *va;
          },
          [=] { return std::max(std::abs(*va), std::abs(*vb - *v0)) / std::abs(*v0); }};
}

constexpr double incline_theta = std::numbers::pi / 6.0;  // the 30° slope of the scene files

// §4.3: the slide down the slope against eq. 30, l = ½ g (sin θ - cos θ tan φ) t², at the end
// of the run. The penalty contact's stick start-up leaves a floor that falls as 1 / t
// (validation.cpp: 0.12 % at 2 s for φ = 10°, 0.66 % for φ = 20°, none for φ = 0°).
Probe incline_slide(const Scene& scene) {
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
          }};
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

std::vector<ReportScene> report_scenes() {
  std::vector<ReportScene> scenes;
  scenes.push_back({"4.1 two squares", "collision_squares", "collision_squares.json",
                    "velocity exchange vA' = 0, vB' = vA (equal masses, elastic impact)", 0.5, 0.25,
                    0, 0, nullptr, velocity_exchange});
  for (const char* phi : {"00", "10", "20"}) {
    const std::string deg = phi[0] == '0' ? std::string(phi + 1) : std::string(phi);
    // The incline's exact runs: 4000 steps are ~8 s each, 200 steps under --quick.
    scenes.push_back({"4.3 incline phi=" + deg + "°", std::string("incline_phi") + phi,
                      std::string("incline_phi") + phi + ".json",
                      "eq. 30: l = ½ g (sin θ - cos θ tan φ) t²", 0.5, 0.03, 4000, 200,
                      reseat_incline_block, incline_slide});
  }
  return scenes;
}

struct Sweep {
  std::vector<double> dt_factors, kn_factors;
};

Sweep sweep(bool quick) {
  if (quick) return {{32.0, 16.0, 4.0, 1.0}, {1.0, 10.0}};
  return {{32.0, 16.0, 8.0, 4.0, 2.0, 1.0, 0.5}, {0.1, 1.0, 10.0}};
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

ReportRun run_one(const ReportScene& entry, const Scene& base, bool quick,
                  kernel::PolicyKind policy, kernel::Demarcation demarcation, double dt_factor,
                  double kn_factor) {
  Scene scene = stiffened(base, kn_factor);
  if (entry.restiffen) entry.restiffen(scene, kn_factor);
  scene.law.policy = policy;
  scene.law.normal.demarcation = demarcation;
  scene.params.dt *= dt_factor;
  scene.params.threads = 1;
  scene.duration = quick ? entry.quick_duration : entry.duration;
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
  if (policy == kernel::PolicyKind::exact && limit > 0 && step_count(scene) > limit) {
    run.status = "skipped";
    return run;
  }
  const Probe probe = entry.probe(scene);
  RunOptions options;
  options.observer = probe.observe;
  const auto start = clock::now();
  try {
    const RunReport report = run_scene(scene, options);
    run.status = report.status;
    run.calls = report.predicates.total_calls();
    run.fallbacks = report.predicates.total_fallbacks();
    run.critical_dt = report.critical_time_step;
    if (report.status == "completed") run.error = probe.error();
  } catch (const StabilityError&) {  // dt above the critical estimate: refused at construction
    run.status = "refused";
  }
  run.seconds = std::chrono::duration<double>(clock::now() - start).count();
  return run;
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
    std::vector<const ReportRun*> points;
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
        c.points.push_back(&r);
      }
      for (auto& [kn, c] : by_kn) curves.push_back(std::move(c));
    }
  }
  std::ostringstream gp;
  gp << "# Work-precision diagram of " << entry.name << ", written by `rockcontact report`.\n"
     << "set logscale xy\nset grid\nset key outside below horizontal maxcols 3 font ',9'\n"
     << "set format xy '%g'\n"
     << "set title " << gnuplot_quoted(entry.name + (quick ? " (--quick: short runs)" : "")) << '\n'
     << "set label 1 " << gnuplot_quoted("error against " + entry.reference)
     << " at graph 0.5, graph 1.02 center font ',9'\n"
     << "set xlabel 'wall time of the run (s)'\nset ylabel 'relative error'\n";
  for (std::size_t i = 0; i < curves.size(); ++i) {
    gp << "$c" << i << " << EOD\n";
    for (const ReportRun* r : curves[i].points) {
      gp << exact_text(r->seconds) << ' ' << exact_text(r->error) << " \"dt×"
         << factor_text(r->dt_factor) << "\"\n";
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

void write_index(const ReportOptions& options, const std::vector<ReportScene>& scenes,
                 const ReportSummary& summary, const std::vector<bool>& plotted) {
  const Sweep s = sweep(options.quick);
  AtomicFile file(options.out_dir / "index.md");
  std::ostream& md = file.stream();
  md << "# Error against run time (`rockcontact report" << (options.quick ? " --quick" : "")
     << "`)\n\n"
     << "Sweep: dt × {";
  for (std::size_t i = 0; i < s.dt_factors.size(); ++i)
    md << (i ? ", " : "") << factor_text(s.dt_factors[i]);
  md << "} of each scene's dt; kn and kt × {";
  for (std::size_t i = 0; i < s.kn_factors.size(); ++i)
    md << (i ? ", " : "") << factor_text(s.kn_factors[i]);
  md << "}; policy float | filtered | exact; demarcation paper | exact. " << summary.runs.size()
     << " runs, one thread each, in " << format(summary.seconds) << " s of wall time. "
     << "Every run is in [runs.csv](runs.csv). Errors are relative to analytic references.\n";
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const ReportScene& e = scenes[i];
    md << "\n## " << e.name << "\n\n"
       << "Scene `" << e.file << "`, " << format(options.quick ? e.quick_duration : e.duration)
       << " s simulated; reference (analytic): " << e.reference << ".\n\n"
       << summary.headlines[i] << "\n\n";
    const double largest = largest_error(e.name, summary.runs);
    if (largest < round_off_error) {
      md << "No plot: every run's error is rounding (the largest " << format(largest)
         << "), so the curves would show noise only.\n";
    } else if (plotted[i]) {
      md << "![" << e.name << "](" << e.slug << ".png) ([SVG](" << e.slug << ".svg))\n";
    } else {
      md << "Plot missing: gnuplot did not run (script in `" << e.slug << ".gp`).\n";
    }
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

ReportSummary run_report(const ReportOptions& options) {
  const auto start = clock::now();
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) throw OutputError(options.out_dir.string() + ": cannot create: " + ec.message());
  const std::vector<ReportScene> scenes = report_scenes();
  const Sweep s = sweep(options.quick);
  ReportSummary summary;
  if (options.on_start) {
    const std::size_t settings = 3 * 2;  // the policies and demarcations of the loops below
    options.on_start(scenes.size() * settings * s.kn_factors.size() * s.dt_factors.size(),
                     scenes.size());
  }
  for (const ReportScene& entry : scenes) {
    if (options.on_scene) options.on_scene(entry.name);
    const Scene base = read_scene_file(options.scenes_dir / entry.file);
    for (const auto policy :
         {kernel::PolicyKind::float_, kernel::PolicyKind::filtered, kernel::PolicyKind::exact}) {
      for (const auto mode : {kernel::Demarcation::paper, kernel::Demarcation::exact}) {
        for (const double k : s.kn_factors) {
          for (const double f : s.dt_factors) {
            summary.runs.push_back(run_one(entry, base, options.quick, policy, mode, f, k));
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
