#define BOOST_TEST_MODULE report
#include "rockcontact/dynamics/apps/report.hpp"

#include <unistd.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace dyn = rockcontact::dynamics;
namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  for (std::string field; std::getline(stream, field, separator);) fields.push_back(field);
  if (!line.empty() && line.back() == separator) fields.emplace_back();
  return fields;
}

// One row of runs.csv, parsed back from the text (not taken from the summary in memory).
struct Row {
  std::string scene, policy, demarcation, status;
  double dt_factor, dt, kn_factor, error, seconds;
  bool pareto;
};

double number(const std::string& field) { return field.empty() ? std::nan("") : std::stod(field); }

std::vector<Row> read_csv(const fs::path& file) {
  std::istringstream in(read_text(file));
  std::string line;
  std::getline(in, line);
  BOOST_TEST_REQUIRE(line ==
                     "scene,policy,demarcation,dt_factor,dt,kn_factor,kn,kt,status,error,"
                     "wall_seconds,predicate_calls,fallbacks,critical_dt,pareto");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line, ',');
    BOOST_TEST_REQUIRE(f.size() == 15u, line);
    rows.push_back({f[0], f[1], f[2], f[8], number(f[3]), number(f[4]), number(f[5]), number(f[9]),
                    number(f[10]), f[14] == "1"});
  }
  return rows;
}

const Row& find(const std::vector<Row>& rows, const std::string& scene, const std::string& policy,
                const std::string& demarcation, double dt_factor, double kn_factor) {
  for (const Row& r : rows) {
    if (r.scene == scene && r.policy == policy && r.demarcation == demarcation &&
        r.dt_factor == dt_factor && r.kn_factor == kn_factor)
      return r;
  }
  BOOST_FAIL("no row " + scene + " " + policy + "/" + demarcation);
  return rows.front();
}

bool gnuplot_on_path() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  for (const std::string& dir : split(path, ':')) {
    std::error_code ec;
    if (!dir.empty() && fs::exists(fs::path(dir) / "gnuplot", ec)) return true;
  }
  return false;
}

// The quick report, run once for every test case below, into a directory of this process
// (the build trees' test suites may run at the same time) removed at exit.
struct QuickReport {
  fs::path dir;
  dyn::ReportSummary summary;
  std::vector<Row> rows;

  QuickReport()
      : dir(fs::temp_directory_path() / ("rockcontact_report_test_" + std::to_string(getpid()))) {
    fs::remove_all(dir);
    dyn::ReportOptions options;
    options.scenes_dir = fs::path(ROCKCONTACT_EXAMPLES_DIR) / "scenes";
    options.out_dir = dir;
    options.quick = true;
    summary = dyn::run_report(options);
    rows = read_csv(dir / "runs.csv");
  }
  ~QuickReport() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  QuickReport(const QuickReport&) = delete;
  QuickReport& operator=(const QuickReport&) = delete;
};

QuickReport& quick() {
  static QuickReport report;
  return report;
}

// The quick sweeps of report.hpp, scene by scene.
struct QuickSweep {
  std::string scene;
  std::vector<double> dt_factors, kn_factors;
  std::vector<std::string> policies;
  std::string reference_policy;  // empty: the reference is analytic
};

const std::vector<std::string> all_policies{"float", "filtered", "exact"};
const std::vector<std::string> large_policies{"float", "filtered"};

const std::vector<QuickSweep> sweeps{
    {"4.1 two squares", {32, 16, 4, 1}, {1, 10}, all_policies, ""},
    {"4.3 incline phi=0°", {32, 16, 4, 1}, {1, 10}, all_policies, ""},
    {"4.3 incline phi=10°", {32, 16, 4, 1}, {1, 10}, all_policies, ""},
    {"4.3 incline phi=20°", {32, 16, 4, 1}, {1, 10}, all_policies, ""},
    {"4.2 symmetric system", {2, 1}, {1}, all_policies, "exact"},
    {"5.1 bounce thin base", {2, 1}, {1}, all_policies, "exact"},
    {"5.1 bounce thick base", {2, 1}, {1}, all_policies, "exact"},
    {"5.2 5° triangles", {2, 1}, {1}, all_policies, "exact"},
    {"5.3 vertex on 0.01 m edge", {2, 1}, {1}, all_policies, "exact"},
    {"5.3 vertex on neighbour edge", {2, 1}, {1}, all_policies, "exact"},
    {"6.1 collapse phi=15°", {1, 0.5}, {1}, large_policies, "filtered"},
    {"6.1 collapse phi=30°", {1, 0.5}, {1}, large_policies, "filtered"},
    {"6.2 valley", {1, 0.5}, {1}, large_policies, "filtered"},
};

bool analytic(const std::string& scene) {
  return scene.rfind("4.1", 0) == 0 || scene.rfind("4.3", 0) == 0;
}

}  // namespace

// The quick sweeps of report.hpp: every scene x its policies x 2 demarcations x its dt x its kn,
// each combination exactly once; a scene without a closed form has one more row first, its
// converged reference (exact demarcation, dt a quarter of the finest, the largest kn).
BOOST_AUTO_TEST_CASE(csv_has_one_row_per_run_of_the_quick_sweep) {
  const std::vector<Row>& rows = quick().rows;
  std::size_t expected = 0;
  for (const QuickSweep& q : sweeps) {
    expected += (q.reference_policy.empty() ? 0 : 1) +
                q.policies.size() * 2 * q.dt_factors.size() * q.kn_factors.size();
  }
  BOOST_TEST(rows.size() == expected);
  std::set<std::tuple<std::string, std::string, std::string, double, double>> seen;
  for (const Row& r : rows) {
    seen.emplace(r.scene, r.policy, r.demarcation, r.dt_factor, r.kn_factor);
    BOOST_TEST((r.status == "completed" || r.status == "refused" || r.status == "stopped" ||
                r.status == "skipped" || r.status == "reference"),
               r.status);
    BOOST_TEST(std::isnan(r.error) == (r.status != "completed"));
  }
  BOOST_TEST(seen.size() == rows.size());
  for (const QuickSweep& q : sweeps) {
    for (const std::string& policy : q.policies) {
      for (const char* mode : {"paper", "exact"}) {
        for (const double f : q.dt_factors) {
          for (const double k : q.kn_factors) {
            BOOST_TEST(seen.count({q.scene, policy, mode, f, k}) == 1u, q.scene);
          }
        }
      }
    }
    if (q.reference_policy.empty()) continue;
    const auto first = std::find_if(rows.begin(), rows.end(),
                                    [&](const Row& r) { return r.scene == q.scene; });
    BOOST_TEST_REQUIRE((first != rows.end()), q.scene);
    BOOST_TEST(first->status == "reference", q.scene);
    BOOST_TEST(first->policy == q.reference_policy, q.scene);
    BOOST_TEST(first->demarcation == "exact", q.scene);
    BOOST_TEST(first->dt_factor == q.dt_factors.back() / 4.0, q.scene);
    BOOST_TEST(first->kn_factor == q.kn_factors.back(), q.scene);
  }
}

// The stability limit: dda2d.hpp's estimate is 0.7 ms for a deformable 1 m square with
// E = 1 GPa (the squares' dt x 32 is 3.2 ms), and the strain modes' limit scales with the
// block's size, so the 0.5 m x 0.25 m incline block's is at most about a quarter of it,
// 0.18 ms, below its dt x 32 = 0.32 ms: every run at dt x 32 is refused. The scenes' own dt
// is far below the limit, so every float and filtered run at dt x 1 completes.
//
// Every scene's own dt runs with the filtered policy (the float policy may be stopped: on the
// collapse its penetration estimate is too rough, and that is part of what the report shows).
BOOST_AUTO_TEST_CASE(dt_above_the_limit_is_refused_and_the_scene_dt_runs) {
  for (const Row& r : quick().rows) {
    if (r.dt_factor == 32.0) BOOST_TEST(r.status == "refused", r.scene);
    if (r.dt_factor == 1.0 && r.policy == "filtered") BOOST_TEST(r.status == "completed", r.scene);
    if (r.dt_factor == 1.0 && r.policy == "float" && analytic(r.scene))
      BOOST_TEST(r.status == "completed", r.scene);
  }
  const std::string index = read_text(quick().dir / "index.md");
  BOOST_TEST(index.find("largest stable dt") != std::string::npos);
}

// φ = 0°: no friction, hence no stick start-up transient; the block slides under the constant
// force m g sin θ, which velocity Verlet integrates exactly, so eq. 30 holds to rounding. The
// finest exact-policy run must meet the validation tolerance, 1 % (validation.cpp).
BOOST_AUTO_TEST_CASE(finest_exact_incline_run_meets_eq_30) {
  const Row* finest = nullptr;
  for (const Row& r : quick().rows) {
    if (r.scene == "4.3 incline phi=0°" && r.policy == "exact" && r.status == "completed" &&
        (!finest || r.dt < finest->dt))
      finest = &r;
  }
  BOOST_TEST_REQUIRE(finest != nullptr);
  BOOST_TEST(finest->error < 0.01);
}

// φ = 10°: the error against eq. 30 converges, as dt shrinks, to the floor of the stick
// start-up (validation.cpp), which does not depend on dt. Velocity Verlet is second order, so
// refining dt by 4 should shrink the distance to that floor by ~16; asserted: by at least 4
// (first order), |e(dt) - e(dt/4)| <= |e(4 dt) - e(dt)| / 4.
BOOST_AUTO_TEST_CASE(incline_error_converges_as_dt_shrinks) {
  for (const char* mode : {"paper", "exact"}) {
    const std::string scene = "4.3 incline phi=10°";
    const double e16 = find(quick().rows, scene, "filtered", mode, 16.0, 1.0).error;
    const double e4 = find(quick().rows, scene, "filtered", mode, 4.0, 1.0).error;
    const double e1 = find(quick().rows, scene, "filtered", mode, 1.0, 1.0).error;
    BOOST_TEST(std::abs(e1 - e4) <= std::abs(e4 - e16) / 4.0, mode);
  }
}

// kn and kt x 10 with the block re-seated at its static penetration: the stick start-up leaves
// the block faster than eq. 30 by Δv ∝ 1 / w, w = sqrt(kt / m) (validation.cpp), which
// dominates the error, so the error falls by sqrt(10). The next term of the transient (the
// stick displacement, ∝ 1 / w²) is 1 / (w t) relative to it: w = 200 rad/s, t = 0.03 s gives
// 0.17 at kn x 1, so the ratio is asserted within 20 % of 1 / sqrt(10).
BOOST_AUTO_TEST_CASE(incline_error_scales_with_the_tangential_stiffness) {
  const std::string scene = "4.3 incline phi=10°";
  const double e1 = find(quick().rows, scene, "filtered", "exact", 1.0, 1.0).error;
  const double e10 = find(quick().rows, scene, "filtered", "exact", 1.0, 10.0).error;
  BOOST_TEST(e10 / e1 == 1.0 / std::sqrt(10.0), boost::test_tools::tolerance(0.2));
}

// The observed order is the slope of ln error against ln dt: exact on a power law, the
// least-squares slope on scattered points, undefined on a single dt.
BOOST_AUTO_TEST_CASE(convergence_order_is_the_log_log_slope) {
  const auto runs = [](std::initializer_list<std::pair<double, double>> points) {
    std::vector<dyn::ReportRun> out;
    for (const auto& [dt, error] : points) {
      dyn::ReportRun r;
      r.dt = dt;
      r.error = error;
      out.push_back(r);
    }
    return out;
  };
  BOOST_TEST(dyn::convergence_order(runs({{1e-3, 3e-6}, {5e-4, 7.5e-7}, {2.5e-4, 1.875e-7}})) ==
                 2.0,
             boost::test_tools::tolerance(1e-12));
  // ln e = {0, ln 2, 0} at ln dt = {0, ln 2, 2 ln 2}: slope 0 by symmetry.
  BOOST_TEST(std::abs(dyn::convergence_order(runs({{1.0, 1.0}, {2.0, 2.0}, {4.0, 1.0}}))) < 1e-12);
  BOOST_TEST(std::isnan(dyn::convergence_order(runs({{1e-3, 1e-2}, {1e-3, 2e-2}}))));
  BOOST_TEST(std::isnan(dyn::convergence_order(runs({{1e-3, 1e-2}, {5e-4, 0.0}}))));
}

// The filtered and the exact policy make the same decisions (exact predicates) and differ in
// their constructions by rounding only (~1e-16 relative), so their runs of a scene at the same
// dt, kn and demarcation leave the same error against the converged reference up to that
// rounding amplified over the run. 1e-12 of the scene's motion leaves four orders of magnitude
// for the amplification and is still far below the smallest error of these runs (4e-9, the 5°
// triangles at dt x 1): a decision that differed between the policies would show at the scale
// of the errors.
BOOST_AUTO_TEST_CASE(filtered_and_exact_runs_leave_the_same_error) {
  std::size_t compared = 0;
  for (const Row& exact : quick().rows) {
    if (analytic(exact.scene) || exact.policy != "exact" || exact.status != "completed") continue;
    const Row& filtered = find(quick().rows, exact.scene, "filtered", exact.demarcation,
                               exact.dt_factor, exact.kn_factor);
    BOOST_TEST_REQUIRE(filtered.status == "completed", exact.scene);
    BOOST_TEST(std::abs(exact.error - filtered.error) <= 1e-12, exact.scene);
    ++compared;
  }
  BOOST_TEST(compared >= 20u);  // 6 scenes x 2 demarcations x 2 dt, less the refused ones
}

// Against its converged run (dt / 4 of the finest), a method of order p leaves
// e(h) ≈ C (h^p - (h/4)^p), so e(2h) / e(h) = (2^p - 4^-p) / (1 - 4^-p): 2.33 for p = 1, 4.2
// for p = 2. The contact scenes whose motion is smooth between impacts converge at least at
// first order: the 5° triangles and the vertex impacts on the small edge and its neighbour.
BOOST_AUTO_TEST_CASE(smooth_contact_scenes_converge_at_least_at_first_order) {
  for (const char* scene :
       {"5.2 5° triangles", "5.3 vertex on 0.01 m edge", "5.3 vertex on neighbour edge"}) {
    for (const char* mode : {"paper", "exact"}) {
      const double coarse = find(quick().rows, scene, "filtered", mode, 2.0, 1.0).error;
      const double fine = find(quick().rows, scene, "filtered", mode, 1.0, 1.0).error;
      BOOST_TEST(coarse / fine >= 0.9 * 7.0 / 3.0, std::string(scene) + " " + mode);
    }
  }
}

// Pareto marks recomputed from the CSV: a run is marked exactly when it completed and no
// completed run of its scene is at least as good in both error and time and better in one.
BOOST_AUTO_TEST_CASE(pareto_marks_are_the_non_dominated_runs) {
  const std::vector<Row>& rows = quick().rows;
  std::map<std::string, int> marked;
  for (const Row& r : rows) {
    bool dominated = false;
    for (const Row& o : rows) {
      if (&o == &r || o.scene != r.scene || o.status != "completed") continue;
      dominated = dominated || (o.error <= r.error && o.seconds <= r.seconds &&
                                (o.error < r.error || o.seconds < r.seconds));
    }
    BOOST_TEST(r.pareto == (r.status == "completed" && !dominated), r.scene);
    marked[r.scene] += r.pareto ? 1 : 0;
  }
  for (const QuickSweep& q : sweeps) BOOST_TEST(marked[q.scene] >= 1, q.scene);
}

BOOST_AUTO_TEST_CASE(index_has_a_section_per_scene) {
  const std::string index = read_text(quick().dir / "index.md");
  for (const QuickSweep& q : sweeps) {
    BOOST_TEST(index.find("## " + q.scene + "\n") != std::string::npos, q.scene);
  }
  BOOST_TEST(index.find("Pareto-best") != std::string::npos);
  BOOST_TEST(index.find("Exact fallbacks") != std::string::npos);
  BOOST_TEST(index.find("Observed order") != std::string::npos);
  BOOST_TEST(index.find("converged run (exact/exact, dt ×1/4, kn ×1)") != std::string::npos);
  BOOST_TEST(quick().summary.headlines.size() == sweeps.size());
}

// With gnuplot installed every scene has a PNG (its 8-byte signature) and an SVG (an <svg> root
// element, closed); without it index.md says the plots are missing.
BOOST_AUTO_TEST_CASE(plots_are_png_and_svg) {
  const fs::path& dir = quick().dir;
  if (!gnuplot_on_path()) {
    BOOST_TEST_MESSAGE("gnuplot not found: checking that index.md says so");
    BOOST_TEST(read_text(dir / "index.md").find("Plot missing") != std::string::npos);
    return;
  }
  BOOST_TEST(quick().summary.plots);
  for (const char* slug :
       {"collision_squares", "incline_phi00", "incline_phi10", "incline_phi20", "symmetric_system",
        "small_angle_triangles", "collapse_phi15", "toppling_slumping"}) {
    const std::string png = read_text(dir / (std::string(slug) + ".png"));
    BOOST_TEST(png.size() > 8u, slug);
    BOOST_TEST(png.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8), slug);
    const std::string svg = read_text(dir / (std::string(slug) + ".svg"));
    BOOST_TEST(svg.find("<svg") != std::string::npos, slug);
    BOOST_TEST(svg.find("</svg>") != std::string::npos, slug);
  }
}
