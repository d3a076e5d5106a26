#include "rockcontact/dynamics/apps/validation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <string_view>
#include <utility>

#include "rockcontact/dynamics/apps/safety_factor.hpp"
#include "rockcontact/dynamics/apps/wedge_family.hpp"
#include "rockcontact/dynamics/apps/wedge_limit_equilibrium.hpp"
#include "rockcontact/dynamics/io/json_read.hpp"
#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"
#include "rockcontact/dynamics/io/scene_cdem.hpp"
#include "rockcontact/dynamics/io/scene_output.hpp"

namespace rockcontact::dynamics {

namespace {

using clock = std::chrono::steady_clock;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::string format(double value, int digits = 4) {
  std::ostringstream out;
  out << std::setprecision(digits) << value;
  return out.str();
}

// Columns on a terminal: UTF-8 code points (the table has "°", "θ", "φ"), not bytes.
std::size_t display_width(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

const BlockState& state(const Dda2d& simulation, std::string_view id) {
  const auto& blocks = simulation.blocks();
  return *std::find_if(blocks.begin(), blocks.end(),
                       [&](const BlockState& b) { return b.id == id; });
}

// One run of a scene, measured through an observer.
struct SceneRun {
  bool completed = false;
  std::string error;  // the engine's message when it stopped the run
  double seconds = 0.0;
  RunReport report;
};

ValidationRow judged(std::string scene, std::string check, std::string reference,
                     std::string measured, double error, Bound bound, double tolerance,
                     double seconds) {
  ValidationRow row{std::move(scene),
                    std::move(check),
                    std::move(reference),
                    std::move(measured),
                    error,
                    bound,
                    tolerance,
                    seconds,
                    false};
  row.pass = bound == Bound::at_most ? error <= tolerance : error >= tolerance;
  return row;
}

// The row of a check whose run did not complete.
ValidationRow stopped(std::string scene, std::string check, std::string reference, Bound bound,
                      double tolerance, const SceneRun& run) {
  return {std::move(scene),
          std::move(check),
          std::move(reference),
          "stopped: " + run.error,
          nan,
          bound,
          tolerance,
          run.seconds,
          false};
}

class Validator {
 public:
  explicit Validator(const ValidationOptions& options) : options_(options) {}

  Scene load(std::string_view file) const { return read_scene_file(options_.scenes_dir / file); }
  // The 3D scenes of seed 001 sit beside the 2D ones: examples/scenes3d (installed as
  // share/rockcontact/scenes3d).
  std::filesystem::path scenes3d(std::string_view file) const {
    return options_.scenes_dir.parent_path() / "scenes3d" / file;
  }
  // The CDEM scenes of seed 003: examples/scenes_cdem (installed as share/rockcontact/scenes_cdem).
  std::filesystem::path scenes_cdem(std::string_view file) const {
    return options_.scenes_dir.parent_path() / "scenes_cdem" / file;
  }

  // The full duration, or the quick one under --quick.
  double duration(double full, double quick_run) const { return options_.quick ? quick_run : full; }
  bool quick() const { return options_.quick; }
  bool wedge_family() const { return options_.wedge_family; }

  SceneRun run(const Scene& scene, const std::string& name,
               std::function<void(const Dda2d&)> observer) const {
    SceneRun result;
    RunOptions run_options;
    if (!options_.out_dir.empty()) run_options.out_dir = options_.out_dir / name;
    run_options.observer = std::move(observer);
    const auto start = clock::now();
    try {
      result.report = run_scene(scene, run_options);
      result.completed = result.report.status == "completed";
      result.error = result.report.error;
    } catch (const StabilityError& e) {  // refused at construction
      result.error = e.what();
    }
    result.seconds = std::chrono::duration<double>(clock::now() - start).count();
    return result;
  }

  void announce(const std::string& scene) const {
    if (options_.on_scene) options_.on_scene(scene);
  }

 private:
  const ValidationOptions& options_;
};

// The mechanical energy (kinetic + gravitational + strain, plus what friction and damping have
// dissipated) over a run, against its start, in units of the largest kinetic energy (the
// energy the contacts have to handle). Energies::total() also counts `contact`, the work done
// on the penalty springs, which makes it constant by construction; without that term the sum
// can only rise above its start if a contact gives back more work than it took, i.e. creates
// energy, which is how a bad contact force blows a run up.
struct EnergyWatch {
  double initial = nan;
  double max_mechanical = -std::numeric_limits<double>::infinity();
  double max_kinetic = 0.0;

  void observe(const Energies& e) {
    const double mechanical = e.total() - e.contact;
    if (std::isnan(initial)) initial = mechanical;
    max_mechanical = std::max(max_mechanical, mechanical);
    max_kinetic = std::max(max_kinetic, e.kinetic);
  }
  double growth() const { return (max_mechanical - initial) / max_kinetic; }
};

// §4.1, Table 4 row 4.1 (rho 2000, E 1 GPa, nu 0.25, kn 10 MPa, frictionless, dt 1e-4 s, no
// gravity): A (1 m square, vA = 1 m/s) hits B (same square, at rest) head-on across a 0.1 m
// gap, contact from t = 0.1 s. Equal masses, central impact, elastic contact: the velocities
// are exchanged (vA' = 0, vB' = 1 m/s) and momentum is conserved.
//
// Momentum: the engine applies f to one block and exactly -f to the other, so the sum of m v
// changes only by the rounding of the velocity updates: ~1e-16 relative per step, 5e3 steps,
// hence 1e-12 relative.
// Exchange and kinetic energy: the blocks are deformable (constant strain, E = 1 GPa). At the
// peak of the impact the contact force F = 2 kn δ L / H (face on face, δ = v / ω the largest
// overlap, ω = sqrt(2 (2 kn L / H) / m)) = 1.4e5 N strains each block with energy
// F² / (2 E) ≈ 10 J, 1 % of the impact energy (1000 J). The contact lasts π / ω = 22 ms, ten
// times the period of the blocks' strain modes (≈ 2 ms: the engine's critical step for them is
// 0.7 ms = 2 / ω_strain), so the loading is quasi-static and the unloading returns almost all
// of it; what stays as vibration is well below that 1 %.
// Tolerance 1e-3: of KE0 on the centroid kinetic energy after separation, of vA on each
// velocity (a 1e-3 energy defect moves the velocities by about as much).
void collision_squares(const Validator& v, std::vector<ValidationRow>& rows) {
  const std::string name = "4.1 two squares";
  v.announce(name);
  Scene scene = v.load("collision_squares.json");
  scene.duration = v.duration(0.5, 0.25);
  double p0 = nan, p_end = nan, va = nan, vb = nan, ke0 = nan, ke_end = nan;
  const auto observe = [&](const Dda2d& sim) {
    const BlockState& a = state(sim, "A");
    const BlockState& b = state(sim, "B");
    const double p = a.mass * a.velocity[0] + b.mass * b.velocity[0];
    const double ke =
        0.5 * a.mass * (a.velocity[0] * a.velocity[0] + a.velocity[1] * a.velocity[1]) +
        0.5 * b.mass * (b.velocity[0] * b.velocity[0] + b.velocity[1] * b.velocity[1]);
    if (std::isnan(p0)) p0 = p, ke0 = ke;
    p_end = p, ke_end = ke, va = a.velocity[0], vb = b.velocity[0];
  };
  const SceneRun run = v.run(scene, "collision_squares", observe);
  const std::string momentum = "momentum sum m vx", exchange = "vx after separation",
                    energy = "centroid KE after";
  if (!run.completed) {
    rows.push_back(stopped(name, momentum, "conserved", Bound::at_most, 1e-12, run));
    rows.push_back(stopped(name, exchange, "vA = 0, vB = 1 m/s", Bound::at_most, 1e-3, run));
    rows.push_back(stopped(name, energy, "KE0 (relative loss)", Bound::at_most, 1e-3, run));
    return;
  }
  const double momentum_error = std::abs(p_end - p0) / std::abs(p0);
  rows.push_back(judged(name, momentum, "conserved (relative change)",
                        "P/P0 - 1 = " + format(p_end / p0 - 1.0), momentum_error, Bound::at_most,
                        1e-12, run.seconds));
  rows.push_back(judged(
      name, exchange, "vA = 0, vB = 1 m/s", "vA = " + format(va) + ", vB = " + format(vb) + " m/s",
      std::max(std::abs(va), std::abs(vb - 1.0)), Bound::at_most, 1e-3, run.seconds));
  rows.push_back(judged(name, energy, "KE0 (relative loss)", "KE/KE0 = " + format(ke_end / ke0, 7),
                        std::abs(1.0 - ke_end / ke0), Bound::at_most, 1e-3, run.seconds));
}

// §4.2, Table 4 row 4.2 (rho 2000, E 0.1 GPa, kn 10 MPa, frictionless, dt 1e-3 s): a wedge
// dropped 0.6 m into the gap between two squares standing on a fixed base, everything mirror
// symmetric about x = 0 (the paper's Fig. 9 is symmetric about the top block's axis). The
// response must stay symmetric: left and right centroids mirror images (x_L = -x_R, y_L = y_R,
// r_L = -r_R), the wedge on the axis (x_W = 0, r_W = 0).
//
// Reference 0. In exact arithmetic the run is exactly symmetric; in double the mirrored
// blocks' computations differ only in rounding (vertex order and sums run differently), about
// 1e-16 m per operation. 1e-9 m (1e-9 of the block size) leaves room for that rounding to
// accumulate over 1000 steps and be amplified by the contacts, while any genuine asymmetry of
// the contact law (a CP/TP role dependence, a wrong contact point) shows at the scale of the
// penetration, 1e-3 m.
void symmetric_system(const Validator& v, std::vector<ValidationRow>& rows) {
  const std::string name = "4.2 symmetric system";
  v.announce(name);
  Scene scene = v.load("symmetric_system.json");
  scene.duration = v.duration(1.0, 0.6);
  double asymmetry = 0.0;
  const auto observe = [&](const Dda2d& sim) {
    const BlockState& l = state(sim, "left");
    const BlockState& r = state(sim, "right");
    const BlockState& w = state(sim, "wedge");
    const double size = 1.0;  // m, rotations weighted by the block size
    asymmetry =
        std::max({asymmetry, std::abs(l.centroid.x + r.centroid.x),
                  std::abs(l.centroid.y - r.centroid.y), size * std::abs(l.rotation + r.rotation),
                  std::abs(w.centroid.x), size * std::abs(w.rotation)});
  };
  const SceneRun run = v.run(scene, "symmetric_system", observe);
  const std::string check = "max mirror asymmetry";
  const std::string reference = "0 m (symmetric)";
  if (!run.completed) {
    rows.push_back(stopped(name, check, reference, Bound::at_most, 1e-9, run));
    return;
  }
  rows.push_back(judged(name, check, reference, format(asymmetry) + " m", asymmetry, Bound::at_most,
                        1e-9, run.seconds));
}

// §4.3, Table 4 row 4.3 (rho 2000, E 1 GPa, kn 10 MPa, kt 10 MN/m, dt 1e-5 s): a block
// released on a fixed 30° incline slides l = ½ g (sin θ - cos θ tan φ) t² (eq. 30), the
// rigid Coulomb contact's answer. Two rows per friction angle:
//
// (1) eq. 30, tolerance 1 % at t = 2 s. The penalty contact departs from a rigid Coulomb one by
// a start-up transient that does not decay: a new contact starts in stick with d = 0 (§3.2.5),
// so the block first moves on the tangential spring, m x'' = m g sin θ - kt x, and only slides
// once kt x reaches tan φ m g cos θ, leaving it faster than eq. 30 by Δv = v_s - a t_s, which is
// proportional to 1 / w, w = sqrt(kt / m) (terms of the closed form (2) below): a relative error
// ≈ 2 Δv / (a t) that falls as 1 / (w t). For the
// paper's kt = 10 MN/m and a 1 m square (m = 2000 kg/m, w = 71 rad/s) it is 3.9 % at 1 s for
// φ = 20°, so the scene files use a 0.5 m x 0.25 m block (m = 250 kg/m, w = 200 rad/s, 0.66 %
// at 2 s for φ = 20°, 0.12 % for φ = 10°, none for φ = 0°). The block starts sunk by its static
// overlap m g cos θ H / (2 kn L) (first order in δ / L: the law's force is kn (2 L δ - δ²) / H),
// so the normal spring starts in equilibrium to 1e-4 and does not bounce the stick phase back.
//
// (2) the elastic-plastic closed form of the same penalty contact: stick on kt from rest under
// the full normal force, then Coulomb sliding at a = g (sin θ - cos θ tan φ):
//   x(t) = (g sin θ / w²) (1 - cos w t)  until 1 - cos(w t_s) = r = tan φ / tan θ,
//   l(t) = x_s + v_s (t - t_s) + a (t - t_s)² / 2,  x_s = r g sin θ / w²,  v_s = (g sin θ / w) sin(w t_s).
// (r >= 1: the block never slides; φ < θ in every scene.) It leaves out only the block's rocking
// under the friction torque tan φ m g cos θ h / 2 on the rotational stiffness of the face contact,
// (2 kn / H) L³ / 12: a tilt of 5e-4 rad for this block at φ = 20°, which moves the base by
// tilt h / 2 ~ 6e-5 m and perturbs the slip speed by tilt (h / 2) w_rock ~ 1e-2 m/s during the
// first few ms: together ~1e-4 m, 3e-5 of l. Tolerance 1e-3 of l leaves a factor 30 for them.
struct InclineReferences {
  double rigid = 0.0;             // eq. 30, m
  double elastic_plastic = 0.0;   // (2) above, m
};

InclineReferences incline_references(double g, double theta, double phi, double kt, double mass,
                                     double t) {
  const double a = g * (std::sin(theta) - std::cos(theta) * std::tan(phi));
  InclineReferences refs;
  refs.rigid = incline_slide_eq30(g, theta, phi, t);
  const double r = std::tan(phi) / std::tan(theta);
  if (r == 0.0) {
    refs.elastic_plastic = refs.rigid;
    return refs;
  }
  const double w = std::sqrt(kt / mass);
  const double ts = std::acos(1.0 - r) / w;
  const double xs = r * g * std::sin(theta) / (w * w);
  const double vs = g * std::sin(theta) / w * std::sin(w * ts);
  refs.elastic_plastic = xs + vs * (t - ts) + 0.5 * a * (t - ts) * (t - ts);
  return refs;
}

void incline(const Validator& v, std::vector<ValidationRow>& rows, int phi_deg) {
  const std::string tag = phi_deg < 10 ? "0" + std::to_string(phi_deg) : std::to_string(phi_deg);
  const std::string name = "4.3 incline phi=" + std::to_string(phi_deg) + "°";
  v.announce(name);
  Scene scene = v.load("incline_phi" + tag + ".json");
  scene.duration = v.duration(2.0, 2.0);
  const double theta = std::numbers::pi / 6.0;
  const double phi = phi_deg * std::numbers::pi / 180.0;
  const double g = std::hypot(scene.params.gravity.x, scene.params.gravity.y);
  const double kt = scene.law.friction ? scene.law.friction->kt : 0.0;
  kernel::Point2 start{nan, nan}, end{nan, nan};
  double mass = nan;
  const auto observe = [&](const Dda2d& sim) {
    const BlockState& b = state(sim, "block");
    if (std::isnan(start.x)) start = b.centroid, mass = b.mass;
    end = b.centroid;
  };
  const SceneRun run = v.run(scene, "incline_phi" + tag, observe);
  const std::string rigid = "slide l vs eq. 30", elastic = "slide l vs stick+slide";
  if (!run.completed) {
    rows.push_back(stopped(name, rigid, "½ g (sin θ - cos θ tan φ) t²", Bound::at_most, 0.01, run));
    rows.push_back(stopped(name, elastic, "closed form", Bound::at_most, 1e-3, run));
    return;
  }
  const double t = run.report.time;
  const InclineReferences refs = incline_references(g, theta, phi, kt, mass, t);
  const double measured = slide_down_slope(start, end, theta);
  const std::string at = " m at t = " + format(t) + " s";
  rows.push_back(judged(name, rigid, format(refs.rigid) + at, format(measured, 6) + " m",
                        std::abs(measured - refs.rigid) / refs.rigid, Bound::at_most, 0.01,
                        run.seconds));
  rows.push_back(judged(name, elastic, format(refs.elastic_plastic, 6) + at,
                        format(measured, 6) + " m",
                        std::abs(measured - refs.elastic_plastic) / refs.elastic_plastic,
                        Bound::at_most, 1e-3, run.seconds));
}

// §5.1, Table 5 row 5.1 (rho 2000, E 1 GPa, kn 50 MPa, kt 10 MN/m, dt 1e-4 s): a 1 m square
// dropped 1 m onto a fixed base 0.1 m high (thin) or 1 m high (thick). The bases have equal
// perimeters (3.9 x 0.1 and 3 x 1), so the scenes' mean edge length, the unified H, is the
// same (1.5 m) in both (so is the paper's own unified value, the average of the longest and
// shortest edge: 2 m); the paper's "previous approach" takes the inscribed radius, here the
// smallest one: 0.05 m (thin) against 0.5 m (thick).
//
// Unified H: while the penetration stays below the thin base's half height (0.05 m; the run
// reports it), the base's potential in the intersection is the depth below its top face in both
// cases, so the two histories are the same function of time; they differ only by the rounding
// of different coordinates (1e-16 m), amplified over a few bounces. Tolerance 1e-6 m.
// Inscribed H: the thin base's potential is 10 times steeper, the contact stiffer and shorter;
// the histories must differ visibly, as in Fig. 14: by at least 1 mm over the run.
void bounce(const Validator& v, std::vector<ValidationRow>& rows) {
  const std::string name = "5.1 bounce";
  v.announce(name);
  const double duration = v.duration(2.0, 0.8);
  const auto history = [&](Scene scene, const std::string& run_name, std::vector<double>& y) {
    scene.duration = duration;
    double y0 = nan;
    return v.run(scene, run_name, [&](const Dda2d& sim) {
      const double yc = state(sim, "A").centroid.y;
      if (std::isnan(y0)) y0 = yc;
      y.push_back(yc - y0);
    });
  };
  const auto difference = [](const std::vector<double>& a, const std::vector<double>& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
      worst = std::max(worst, std::abs(a[i] - b[i]));
    }
    return worst;
  };
  const auto inscribed = [](Scene scene) {
    scene.h_rule = HRule::inscribed;
    scene.law.normal.H = smallest_inscribed_radius(scene.blocks);
    return scene;
  };
  const Scene thin = v.load("bounce_thin_base.json");
  const Scene thick = v.load("bounce_thick_base.json");
  std::vector<double> y_thin, y_thick, y_thin_inscribed, y_thick_inscribed;
  const SceneRun a = history(thin, "bounce_thin_base", y_thin);
  const SceneRun b = history(thick, "bounce_thick_base", y_thick);
  const SceneRun c = history(inscribed(thin), "bounce_thin_base_inscribed", y_thin_inscribed);
  const SceneRun d = history(inscribed(thick), "bounce_thick_base_inscribed", y_thick_inscribed);

  const std::string check = "max |y_thin - y_thick|";
  if (!a.completed || !b.completed) {
    rows.push_back(stopped(name + " H=mean_edge", check, "same history", Bound::at_most, 1e-6,
                           a.completed ? b : a));
  } else {
    const double diff = difference(y_thin, y_thick);
    rows.push_back(judged(name + " H=mean_edge", check, "0 m (same history)", format(diff) + " m",
                          diff, Bound::at_most, 1e-6, a.seconds + b.seconds));
  }
  if (!c.completed || !d.completed) {
    rows.push_back(stopped(name + " H=inscribed", check, "different (Fig. 14)", Bound::at_least,
                           1e-3, c.completed ? d : c));
  } else {
    const double diff = difference(y_thin_inscribed, y_thick_inscribed);
    rows.push_back(judged(name + " H=inscribed", check, ">= 1 mm (differs, Fig. 14)",
                          format(diff) + " m", diff, Bound::at_least, 1e-3, c.seconds + d.seconds));
  }
}

// §5.2, Table 5 row 5.2 (rho 2000, E 1 GPa, kn 50 MPa, kt 10 MN/m, dt 2e-5 s): two identical
// triangles with a 5° apex angle, apex to apex on the y axis 0.1 m apart, moving towards each
// other at 1 m/s; no gravity, so the configuration is point symmetric about the origin for
// all time (the paper: "symmetric regarding the collision centroid").
//
// Point symmetry: c_top = -c_bottom and r_top = r_bottom. Reference 0, tolerance 1e-9 m as in
// §4.2 (rounding only). Energy (EnergyWatch): the mechanical energy must not rise above its
// start by more than 1 % of the impact energy; a rise would be energy created by the contact,
// the paper's concern with small angles, where a potential that misplaces the force pumps
// energy in. Losing energy is allowed: the potential force is not the gradient of a single
// energy, so loading and unloading of the wedge-tip overlap differ, and the triangles separate
// with about 6 % less kinetic energy (the run's summary shows it as `contact` work).
void small_angle_triangles(const Validator& v, std::vector<ValidationRow>& rows) {
  const std::string name = "5.2 5° triangles";
  v.announce(name);
  Scene scene = v.load("small_angle_triangles.json");
  scene.duration = v.duration(0.2, 0.2);
  double asymmetry = 0.0;
  EnergyWatch energy;
  const auto observe = [&](const Dda2d& sim) {
    const BlockState& top = state(sim, "top");
    const BlockState& bottom = state(sim, "bottom");
    const double size = 1.0;  // m, the triangles' height
    asymmetry = std::max(
        {asymmetry,
         std::hypot(top.centroid.x + bottom.centroid.x, top.centroid.y + bottom.centroid.y),
         size * std::abs(top.rotation - bottom.rotation)});
    energy.observe(sim.energies());
  };
  const SceneRun run = v.run(scene, "small_angle_triangles", observe);
  const std::string symmetry = "max point asymmetry", growth = "energy growth / KE";
  if (!run.completed) {
    rows.push_back(stopped(name, symmetry, "0 m (symmetric)", Bound::at_most, 1e-9, run));
    rows.push_back(stopped(name, growth, "<= 0 (bounded)", Bound::at_most, 0.01, run));
    return;
  }
  rows.push_back(judged(name, symmetry, "0 m (symmetric)", format(asymmetry) + " m", asymmetry,
                        Bound::at_most, 1e-9, run.seconds));
  rows.push_back(judged(name, growth, "0 (bounded)", format(energy.growth()), energy.growth(),
                        Bound::at_most, 0.01, run.seconds));
}

// §5.3, Table 5 row 5.3 (rho 2000, E 1 GPa, kn 50 MPa, kt 10 MN/m, dt 1e-4 s): a square
// standing on a vertex (a diamond, 1 m diagonal) falls 0.05 m onto a fixed block whose top
// has an edge of 0.01 m: (a) the vertex hits that small edge, (b) it hits the neighbouring
// edge 0.3 m to the right. No blow-up (the run completes), energy bounded (as §5.2: no growth
// above 1 % of the impact energy), and the block rebounds: the largest upward centroid speed
// after the first contact is at least half the impact speed (the largest downward speed
// before it moves up). The penalty contact stores and returns energy without damping, so a
// vertical vertex impact (a) comes back with a ratio near 1; the oblique impact (b) turns part
// of it into rotation and friction work. A contact that loses the vertex (the failure the paper
// describes: part of the intersection where no potential is defined) would leave the block
// sinking or stuck, ratio ~0.
void small_edge(const Validator& v, std::vector<ValidationRow>& rows, const std::string& file,
                const std::string& label) {
  const std::string name = "5.3 " + label;
  v.announce(name);
  Scene scene = v.load(file + ".json");
  scene.duration = v.duration(0.4, 0.3);
  EnergyWatch energy;
  bool touched = false, rising = false;
  double impact_speed = 0.0, rebound_speed = 0.0;
  const auto observe = [&](const Dda2d& sim) {
    energy.observe(sim.energies());
    const double vy = state(sim, "falling").velocity[1];
    touched = touched || !sim.contacts().empty();
    rising = rising || (touched && vy > 0.0);
    if (!rising) impact_speed = std::max(impact_speed, -vy);
    if (rising) rebound_speed = std::max(rebound_speed, vy);
  };
  const SceneRun run = v.run(scene, file, observe);
  const std::string growth = "energy growth / KE", rebound = "rebound vy / impact";
  if (!run.completed) {
    rows.push_back(stopped(name, growth, "0 (bounded)", Bound::at_most, 0.01, run));
    rows.push_back(stopped(name, rebound, "rebounds", Bound::at_least, 0.5, run));
    return;
  }
  rows.push_back(judged(name, growth, "0 (bounded)", format(energy.growth()), energy.growth(),
                        Bound::at_most, 0.01, run.seconds));
  const double ratio = impact_speed > 0.0 ? rebound_speed / impact_speed : 0.0;
  rows.push_back(judged(name, rebound, "rebounds",
                        format(rebound_speed) + " / " + format(impact_speed) + " m/s", ratio,
                        Bound::at_least, 0.5, run.seconds));
}

// §6.1 (rho 2700, E 2 GPa, nu 0.3, kn 2 GPa, kt 1 GN/m, dt 1e-4 s, 7.5 s): the 50 m x 20 m
// rock mass cut by joints at 80° and 40° (spacings 1.5 m and 2.5 m) collapses to the left onto
// the floor; joint friction 15° (case 1) or 30° (case 2), rock-boundary friction 35°. The paper
// compares pictures at 2.5, 5.0 and 7.5 s (Fig. 20): a faster collapse and a longer runout with
// the lower friction. Measured at each of those times in both cases:
//   runout          the largest leftward travel of a rock block's centroid, m;
//   runout mass     the fraction of the rock mass whose centroid has run out past the toe
//                   (x < 0, the region's left face), the paper's "runout mass";
// and over the whole run: every block is still on the floor and inside the domain (x in
// [-80, 52] m, y >= -2 m: none fell through or flew off), and the total rock area changed by
// at most 1e-3 (strains are ~sigma / E <= rho g h / E = 2.6e-4 from the 20 m of overburden;
// a rotation map that inflates blocks would show percent-level growth within seconds).
// --quick runs 0.2 s of both cases and keeps only the last two checks (the collapse has not
// developed yet). Verdicts: case 1 runs out farther and puts more mass past the toe than case 2
// at every time, by at least 0.5 m and 0.02 of the mass (differences well clear of the effect of
// rounding, which perturbs a collapse that branches at every block collision, but cannot
// reverse a trend set by a friction twice as large).
struct Collapse {
  std::vector<double> runout, collapsed;  // at 2.5, 5.0, 7.5 s (or the quick times)
  double area_change = 0.0;               // max |A / A0 - 1| of the rock blocks
  // Rock blocks whose centroid was ever inside the floor (below its surface y = 0 over its length
  // -80 <= x <= 52) or behind the wall (x > 50, up to its top): through a boundary. A block that
  // runs off the floor's far end (x < -80) and falls is a long runout, not a failure: without
  // contact damping the paper's law bounces a block shot out of the collapse along the floor,
  // and rounding decides whether one gets that far in 7.5 s.
  std::size_t through = 0;
  SceneRun run;
};

Collapse collapse_run(const Validator& v, const std::string& file, const std::vector<double>& times) {
  Scene scene = v.load(file + ".json");
  scene.duration = times.back();
  Collapse c;
  std::vector<kernel::Point2> start;
  std::vector<char> escaped;
  double area0 = 0.0;
  std::size_t next = 0;
  const auto is_rock = [&](std::size_t i) { return i >= scene.generated_first && i < scene.generated_first + scene.generated_count; };
  const auto observe = [&](const Dda2d& sim) {
    const auto& blocks = sim.blocks();
    double area = 0.0;
    for (std::size_t i = 0; i < blocks.size(); ++i) area += is_rock(i) ? blocks[i].area : 0.0;
    if (start.empty()) {
      for (const BlockState& b : blocks) start.push_back(b.centroid);
      area0 = area;
    }
    c.area_change = std::max(c.area_change, std::abs(area / area0 - 1.0));
    escaped.resize(blocks.size(), 0);
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const kernel::Point2 p = blocks[i].centroid;
      const bool in_floor = p.x >= -80.0 && p.x <= 52.0 && p.y < 0.0;
      const bool behind_wall = p.x > 50.0 && p.y <= 25.0;
      if (is_rock(i) && !escaped[i] && (in_floor || behind_wall)) {
        escaped[i] = 1;
        ++c.through;
      }
    }
    if (next >= times.size() || sim.time() < times[next] - 0.5 * scene.params.dt) return;
    double runout = 0.0, moved = 0.0, total = 0.0;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      if (!is_rock(i)) continue;
      const kernel::Point2 p = blocks[i].centroid, p0 = start[i];
      runout = std::max(runout, p0.x - p.x);
      total += blocks[i].mass;
      if (p.x < 0.0) moved += blocks[i].mass;
    }
    c.runout.push_back(runout);
    c.collapsed.push_back(moved / total);
    ++next;
  };
  c.run = v.run(scene, file, observe);
  return c;
}

void collapse(const Validator& v, std::vector<ValidationRow>& rows) {
  const std::string name = "6.1 collapse";
  v.announce(name);
  const std::vector<double> times =
      v.quick() ? std::vector<double>{0.2} : std::vector<double>{2.5, 5.0, 7.5};
  const Collapse a = collapse_run(v, "collapse_phi15", times);
  const Collapse b = collapse_run(v, "collapse_phi30", times);
  const double seconds = a.run.seconds + b.run.seconds;
  if (!a.run.completed || !b.run.completed) {
    rows.push_back(stopped(name, "runout phi 15° - 30°", "> 0", Bound::at_least, 0.5, a.run.completed ? b.run : a.run));
    return;
  }
  for (std::size_t k = 0; k < times.size() && !v.quick(); ++k) {
    const std::string at = " at " + format(times[k]) + " s";
    rows.push_back(judged(name, "runout 15° - 30°" + at, "case 1 farther (Fig. 20)",
                          format(a.runout[k]) + " vs " + format(b.runout[k]) + " m",
                          a.runout[k] - b.runout[k], Bound::at_least, 0.5, seconds));
    rows.push_back(judged(name, "runout mass 15° - 30°" + at, "case 1 more (Fig. 20)",
                          format(a.collapsed[k]) + " vs " + format(b.collapsed[k]),
                          a.collapsed[k] - b.collapsed[k], Bound::at_least, 0.02, seconds));
  }
  rows.push_back(judged(name, "blocks through floor or wall", "none",
                        std::to_string(a.through) + " + " + std::to_string(b.through),
                        static_cast<double>(a.through + b.through), Bound::at_most, 0.0, seconds));
  const double area = std::max(a.area_change, b.area_change);
  const double fallbacks = static_cast<double>(a.run.report.predicates.total_fallbacks() + b.run.report.predicates.total_fallbacks());
  const double calls = static_cast<double>(a.run.report.predicates.total_calls() + b.run.report.predicates.total_calls());
  rows.push_back(judged(name, "rock area change", "conserved (|A/A0 - 1|)",
                        format(area) + "; exact fallbacks " + format(fallbacks / calls) + " of predicates",
                        area, Bound::at_most, 1e-3, seconds));
}

// §6.2 after Fig. 21 (rho 2700, E 2 GPa, nu 0.3, kn 0.5 GPa, kt 1e8 N/m, dt 1e-4 s, 3.5 s): a
// valley cut by one joint set (traces at 75° from horizontal, dipping out of the left slope and
// into the right one), the left slope on a 30° sliding base (friction 32°), joints 22°. The
// paper's verdict (Fig. 22) is a pattern: the left slope slumps, the right slope topples. Made
// numerical at the end of the run, against the scale of what elastic contact alone does (the
// blocks' penalty displacements are ~1e-2 m and their rocking ~0.1°):
//   toppling  a right-slope block has turned towards the valley (counter-clockwise) by at
//             least 1°;
//   slumping  the left-slope blocks have moved down the base by at least 0.1 m on average
//             (mass weighted), and turned on average by less than half the toppling rotation
//             (they slide rather than topple).
// --quick runs 0.3 s and keeps only the stability of the run (the failure has not developed).
void toppling_slumping(const Validator& v, std::vector<ValidationRow>& rows) {
  const std::string name = "6.2 valley";
  v.announce(name);
  Scene scene = v.load("toppling_slumping.json");
  scene.duration = v.duration(3.5, 0.3);
  std::vector<kernel::Point2> start;
  double topple = 0.0, slide = 0.0, turn = 0.0;
  const double c = std::cos(std::numbers::pi / 6.0), s = std::sin(std::numbers::pi / 6.0);
  const auto observe = [&](const Dda2d& sim) {
    const auto& blocks = sim.blocks();
    if (start.empty()) {
      for (const BlockState& b : blocks) start.push_back(b.centroid);
    }
    topple = 0.0;
    double mass = 0.0, along = 0.0, rotation = 0.0;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const BlockState& b = blocks[i];
      if (b.id.rfind("right_", 0) == 0) topple = std::max(topple, b.rotation);
      if (b.id.rfind("left_", 0) != 0) continue;
      mass += b.mass;
      along += b.mass * ((b.centroid.x - start[i].x) * c - (b.centroid.y - start[i].y) * s);
      rotation += b.mass * std::abs(b.rotation);
    }
    slide = along / mass;
    turn = rotation / mass;
  };
  const SceneRun run = v.run(scene, "toppling_slumping", observe);
  const double degree = std::numbers::pi / 180.0;
  if (!run.completed) {
    rows.push_back(stopped(name, "right: max rotation", "topples (>= 1°)", Bound::at_least, 1.0, run));
    return;
  }
  if (v.quick()) {
    rows.push_back(judged(name, "run completes", "no blow-up", "t = " + format(run.report.time) + " s",
                          0.0, Bound::at_most, 0.0, run.seconds));
    return;
  }
  rows.push_back(judged(name, "right: max rotation", "topples (>= 1°)", format(topple / degree) + "°",
                        topple / degree, Bound::at_least, 1.0, run.seconds));
  rows.push_back(judged(name, "left: slide down base", "slumps (>= 0.1 m)", format(slide) + " m",
                        slide, Bound::at_least, 0.1, run.seconds));
  rows.push_back(judged(name, "left: |rotation| / right", "slides (< 0.5)",
                        format(turn / degree) + "° / " + format(topple / degree) + "°",
                        turn / topple, Bound::at_most, 0.5, run.seconds));

}

// The first event of a kind in a CDEM run, or NaN.
double first_event(const Cdem& cdem, CdemEvent::Kind kind) {
  for (const CdemEvent& e : cdem.events())
    if (e.kind == kind) return e.t;
  return nan;
}

// Seed 003 §6 (examples/scenes_cdem/prisms.json): block i's vertex meets block j's edge 1 m away
// at 3 m/s, so the first touch is at 1/3 s; the run measures it to 1e-9 (the exact touch time of
// the step that holds it; free flight's rounding moves it by < 4e-12 s). Momentum is conserved by
// construction (equal and opposite impulses and forces) to 1e-9. After the impact block j leaves
// with about block i's initial velocity (velocities exchanged, the seed's Fig. 16): within 5 %,
// the onset loss and the vibration left in the blocks taking the rest.
void prisms_cdem(const Validator& v, std::vector<ValidationRow>& rows) {
  const std::string name = "003 6 prisms";
  v.announce(name);
  const SceneCdem scene = read_scene_cdem_file(v.scenes_cdem("prisms.json"));
  const auto start = clock::now();
  Cdem cdem(scene.blocks, scene.params);
  const auto p0 = cdem.momentum();
  const std::size_t steps = step_count(scene.duration, scene.params.dt);
  while (cdem.steps() < steps) cdem.step();
  const double seconds = std::chrono::duration<double>(clock::now() - start).count();
  const double touch = first_event(cdem, CdemEvent::Kind::touch);
  rows.push_back(judged(name, "first touch vs 1/3 s", "0.333333333 s", format(touch, 12) + " s",
                        std::abs(touch * 3.0 - 1.0), Bound::at_most, 1e-9, seconds));
  const auto p = cdem.momentum();
  rows.push_back(judged(name, "momentum kept (relative)", format(p0[0], 6) + " kg m/s",
                        format(p[0], 12) + " kg m/s", std::hypot(p[0] - p0[0], p[1] - p0[1]) / std::abs(p0[0]),
                        Bound::at_most, 1e-9, 0.0));
  const double vj = cdem.block_state(1).velocity[0];
  rows.push_back(judged(name, "j leaves with i's velocity", "3 m/s", format(vj, 4) + " m/s (i " +
                            format(cdem.block_state(0).velocity[0], 3) + " m/s)",
                        std::abs(vj / 3.0 - 1.0), Bound::at_most, 0.05, 0.0));
}

// Saint-Venant's impact of two equal bars (examples/scenes_cdem/bars.json; nu = 0, plane stress:
// 1D waves): the contact lasts 2 L / c, c = sqrt(E / rho), and the striker stops. Within 5 % of
// 2 L / c (the mesh's dispersion of the wave front; docs/validation.md has the error against the
// mesh and dt) under the two-scale law, and under penalty springs of kn = 1e10 N/m beside it.
void bars_cdem(const Validator& v, std::vector<ValidationRow>& rows) {
  const SceneCdem scene = read_scene_cdem_file(v.scenes_cdem("bars.json"));
  const double length = 1.0;
  const CdemMaterial& m = scene.blocks[0].material;
  const double duration = 2.0 * length / std::sqrt(m.youngs_modulus / m.density);
  for (const CdemLaw law : {CdemLaw::two_scale, CdemLaw::penalty}) {
    const std::string name = law == CdemLaw::two_scale ? "bars two-scale" : "bars penalty";
    v.announce(name);
    CdemParams params = scene.params;
    params.contact.law = law;
    params.contact.kn = law == CdemLaw::penalty ? 1.0e10 : 0.0;
    const auto start = clock::now();
    Cdem cdem(scene.blocks, params);
    const std::size_t steps = step_count(scene.duration, scene.params.dt);
    while (cdem.steps() < steps) cdem.step();
    const double seconds = std::chrono::duration<double>(clock::now() - start).count();
    const double contact = first_event(cdem, CdemEvent::Kind::separate) - first_event(cdem, CdemEvent::Kind::touch);
    rows.push_back(judged(name, "contact time vs 2L/c", format(duration * 1e3, 5) + " ms",
                          format(contact * 1e3, 5) + " ms", std::abs(contact / duration - 1.0), Bound::at_most, 0.05,
                          seconds));
    rows.push_back(judged(name, "striker at rest after", "0 m/s (v0 = 1 m/s)",
                          format(cdem.block_state(0).velocity[0], 3) + " m/s",
                          std::abs(cdem.block_state(0).velocity[0]), Bound::at_most, 0.05, 0.0));
  }
}

}  // namespace

double incline_slide_eq30(double g, double theta, double phi, double t) {
  return 0.5 * g * (std::sin(theta) - std::cos(theta) * std::tan(phi)) * t * t;
}

double slide_down_slope(kernel::Point2 start, kernel::Point2 end, double theta) {
  return -((end.x - start.x) * std::cos(theta) + (end.y - start.y) * std::sin(theta));
}

// Seed 001 §6.1 (examples/scenes3d/wedge.json, cut by joints 50°/110° and 55°/240°, φ = 40° on
// both): the factor of safety by strength reduction (safety_factor.hpp: 1 s trials, bisection to
// 1e-3) against Hoek & Bray's limit equilibrium on the joints of wedge_cut.json
// (wedge_limit_equilibrium.hpp, 2.198), within 0.5 % (the paper's DDA: 2.158, 1.8 % low); and
// the frictionless wedge's slide along the line of intersection in 0.4 s against ½ g sin ψ t²
// (ψ its plunge), within 2 %.
void wedge3d(const Validator& v, std::vector<ValidationRow>& rows) {
  const std::string name = "001 6.1 wedge";
  v.announce(name);
  const Scene3d scene = read_scene3d_file(v.scenes3d("wedge.json"));
  const nlohmann::json cut = read_json_file(v.scenes3d("wedge_cut.json"));
  std::array<WedgeJoint, 2> joints;
  for (std::size_t k = 0; k < 2; ++k) {
    const nlohmann::json& set = cut.at("joint_sets").at(k);
    joints[k] = {set.at("dip_deg"), set.at("dip_direction_deg"), scene.law.interfaces.at(0).friction_angle_deg, 0.0, 0.0};
  }
  const WedgeLimitEquilibrium reference = wedge_factor_of_safety(joints[0], joints[1], 1.0);
  auto start = clock::now();
  const SafetyFactorResult fs = safety_factor(scene.blocks, scene.law, scene.params, "wedge");
  const double fs_seconds = std::chrono::duration<double>(clock::now() - start).count();
  rows.push_back(judged(name, "factor of safety vs limit equilibrium", format(reference.factor_of_safety) + " (Hoek & Bray)",
                        format(fs.factor_of_safety) + " (" + std::to_string(fs.iterations) + " trials)",
                        std::abs(fs.factor_of_safety - reference.factor_of_safety) / reference.factor_of_safety,
                        Bound::at_most, 5e-3, fs_seconds));

  Scene3d frictionless = scene;
  frictionless.law.friction_angle_deg = 0.0;
  for (Interface3d& f : frictionless.law.interfaces) f.friction_angle_deg = 0.0;
  start = clock::now();
  Dda3d sim(frictionless.blocks, frictionless.law, frictionless.params);
  const auto wedge = [&] {
    return std::find_if(sim.blocks().begin(), sim.blocks().end(), [](const Block3dState& b) { return b.id == "wedge"; });
  };
  const kernel::Point3 c0 = wedge()->centroid;
  while (sim.time() < 0.4 - 1e-9) sim.step();
  const kernel::Point3 c = wedge()->centroid, line = reference.intersection;
  const double along = (c.x - c0.x) * line.x + (c.y - c0.y) * line.y + (c.z - c0.z) * line.z;
  const double g = std::hypot(scene.params.gravity[0], scene.params.gravity[1], scene.params.gravity[2]);
  const double t = sim.time();
  const double expected = 0.5 * g * std::sin(reference.plunge_deg * std::numbers::pi / 180.0) * t * t;
  rows.push_back(judged(name + " phi=0", "slide along the line vs ½ g sin ψ t²",
                        format(expected, 6) + " m at t = " + format(t) + " s", format(along, 6) + " m",
                        std::abs(along - expected) / expected, Bound::at_most, 0.02,
                        std::chrono::duration<double>(clock::now() - start).count()));
}

// Issue 29's reference family (wedge_family.hpp): wedges never seen here, generated from seed 1
// on the user's path (cut, then the scene), against Hoek & Bray's closed form, at the default
// penalty (kn = auto_normal_penalty3d, 10 E L of the wedge) and at ten times it, kt = kn / 10,
// dt = 10⁻⁴ s (the family's scenes), four rows:
//   factor of safety  the worst relative error over the first 10 wedges at φ = 40° (safety_factor,
//                     as `rockcontact safety-factor`), within 0.5 %;
//   slide             the worst relative error over the first 5 of the family that cannot stand
//                     at φ = 20° (FS < 1) and can slide without turning (wedge_sliding_support): the wedge's displacement along the line of
//                     intersection from rest against ½ g sin ψ_i (1 − FS) t², within 1 %, at
//                     t = wedge_slide_time (1 s, or less where the wedge would reach the free
//                     face and tip over its edge).
// The cases run side by side on the threads (each engine then runs on one). Only with
// ValidationOptions::wedge_family (`validate --wedge-family`), not under --quick: about 16
// minutes on 2 cores.
struct FamilyCase {
  double reference = nan, measured = nan;
  std::string error;  // the run's, when it stopped
};

// Runs `job` for every case on the threads, each case's exception kept as its error.
template <typename Job>
std::vector<FamilyCase> run_cases(std::size_t count, const Job& job) {
  std::vector<FamilyCase> out(count);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(count); ++k) {
    FamilyCase& c = out[static_cast<std::size_t>(k)];
    try {
      job(static_cast<std::size_t>(k), c);
    } catch (const std::exception& e) {
      c.error = e.what();
    }
  }
  return out;
}

// The row of the worst case of a family run.
ValidationRow worst_case(const std::string& name, const std::string& check, const std::string& reference,
                         const std::vector<FamilyCase>& cases, double tolerance, double seconds) {
  std::size_t worst = 0;
  double error = -1.0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (!cases[k].error.empty()) {
      SceneRun run;
      run.error = "case " + std::to_string(k) + ": " + cases[k].error;
      run.seconds = seconds;
      return stopped(name, check, reference, Bound::at_most, tolerance, run);
    }
    const double e = std::abs(cases[k].measured / cases[k].reference - 1.0);
    if (e > error) error = e, worst = k;
  }
  return judged(name, check, reference,
                "case " + std::to_string(worst) + ": " + format(cases[worst].measured, 5) + " vs " +
                    format(cases[worst].reference, 5),
                error, Bound::at_most, tolerance, seconds);
}

void wedge_family(const Validator& v, std::vector<ValidationRow>& rows) {
  if (v.quick() || !v.wedge_family()) return;
  constexpr std::uint64_t seed = 1;
  constexpr std::size_t fs_cases = 10, slide_cases = 5;
  const std::vector<WedgeCase> standing = generate_wedges(seed, fs_cases, 40.0);
  // The first wedges of the family at φ = 20° that cannot stand (about one in three can).
  std::vector<WedgeCase> sliding;
  for (std::size_t n = slide_cases; sliding.size() < slide_cases; n += slide_cases) {
    sliding.clear();
    for (const WedgeCase& c : generate_wedges(seed, n, 20.0)) {
      // A wedge that would have to turn from the start has no slide reference (wedge_slide_time 0).
      if (sliding.size() < slide_cases && wedge_factor_of_safety(c.a, c.b, 1.0).factor_of_safety < 1.0 &&
          wedge_sliding_support(c, 0.0).margin > 0.0) {
        sliding.push_back(c);
      }
    }
  }
  const auto scene_of = [](const WedgeCase& c, double factor) {
    Scene3d scene = wedge_scene(c);
    scene.law.kn = factor * auto_normal_penalty3d(scene.blocks);
    scene.law.kt = scene.law.kn / 10.0;
    return scene;
  };
  for (const double factor : {1.0, 10.0}) {
    const std::string name = factor == 1.0 ? "wedge family kn=auto" : "wedge family kn=10 auto";
    v.announce(name);
    auto start = clock::now();
    const std::vector<FamilyCase> fs = run_cases(standing.size(), [&](std::size_t k, FamilyCase& out) {
      const WedgeCase& c = standing[k];
      out.reference = wedge_factor_of_safety(c.a, c.b, 1.0).factor_of_safety;
      const Scene3d scene = scene_of(c, factor);
      out.measured = safety_factor(scene.blocks, scene.law, scene.params, "wedge").factor_of_safety;
    });
    rows.push_back(worst_case(name, "worst FS error, 10 wedges φ=40°", "Hoek & Bray", fs, 5e-3,
                              std::chrono::duration<double>(clock::now() - start).count()));
    start = clock::now();
    const std::vector<FamilyCase> slides = run_cases(sliding.size(), [&](std::size_t k, FamilyCase& out) {
      const WedgeCase& c = sliding[k];
      const WedgeLimitEquilibrium reference = wedge_factor_of_safety(c.a, c.b, 1.0);
      const Scene3d scene = scene_of(c, factor);
      Dda3d sim(scene.blocks, scene.law, scene.params);
      const auto wedge = [&] {
        return std::find_if(sim.blocks().begin(), sim.blocks().end(), [](const Block3dState& b) { return b.id == "wedge"; });
      };
      const kernel::Point3 c0 = wedge()->centroid;
      const double until = wedge_slide_time(c, reference, wedge_family_gravity);
      while (sim.time() < until - 1e-9) sim.step();
      const kernel::Point3 c1 = wedge()->centroid, line = reference.intersection;
      const double t = sim.time();
      out.reference = 0.5 * wedge_slide_acceleration(reference, wedge_family_gravity) * t * t;
      out.measured = (c1.x - c0.x) * line.x + (c1.y - c0.y) * line.y + (c1.z - c0.z) * line.z;
    });
    rows.push_back(worst_case(name, "worst slide error, 5 wedges φ=20°", "½ g sin ψ (1 - FS) t²", slides, 1e-2,
                              std::chrono::duration<double>(clock::now() - start).count()));
  }
}

std::vector<ValidationRow> run_validation(const ValidationOptions& options) {
  const Validator v(options);
  std::vector<ValidationRow> rows;
  collision_squares(v, rows);
  symmetric_system(v, rows);
  for (const int phi : {0, 10, 20}) incline(v, rows, phi);
  bounce(v, rows);
  small_angle_triangles(v, rows);
  small_edge(v, rows, "small_edge_vertex", "vertex on 0.01 m edge");
  small_edge(v, rows, "small_edge_neighbour", "vertex on neighbour edge");
  collapse(v, rows);
  toppling_slumping(v, rows);
  wedge3d(v, rows);
  wedge_family(v, rows);
  prisms_cdem(v, rows);
  bars_cdem(v, rows);
  return rows;
}

void write_validation_table(std::ostream& out, std::span<const ValidationRow> rows) {
  const std::vector<std::string> header{"scene", "check",     "reference", "measured",
                                        "error", "tolerance", "wall s",    "result"};
  std::vector<std::vector<std::string>> table{header};
  std::size_t failed = 0;
  for (const ValidationRow& r : rows) {
    table.push_back({r.scene, r.check, r.reference, r.measured, format(r.error, 3),
                     (r.bound == Bound::at_most ? "<= " : ">= ") + format(r.tolerance, 3),
                     format(r.seconds, 3), r.pass ? "PASS" : "FAIL"});
    failed += r.pass ? 0 : 1;
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& line : table) {
    for (std::size_t c = 0; c < line.size(); ++c) {
      width[c] = std::max(width[c], display_width(line[c]));
    }
  }
  for (const auto& line : table) {
    for (std::size_t c = 0; c < line.size(); ++c) {
      out << (c == 0 ? "" : "  ") << line[c];
      if (c + 1 < line.size()) out << std::string(width[c] - display_width(line[c]), ' ');
    }
    out << '\n';
  }
  out << rows.size() << " checks, " << failed << " failed\n";
}

}  // namespace rockcontact::dynamics
