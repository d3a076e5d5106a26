#include "stiff_extreme.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/dynamics/dda2d.hpp"
#include "rockcontact/dynamics/io/scene.hpp"

namespace rockcontact::stiff {
namespace {

using dynamics::BlockSpec;
using dynamics::BlockState;
using dynamics::ContactLaw;
using dynamics::Dda2d;
using dynamics::DdaParams;
using dynamics::Material;
using dynamics::StabilityError;
using kernel::Point2;

constexpr double g = 9.81;          // m/s²
constexpr double rho = 2000.0;      // kg/m³, seed 000 Tables 4-5
constexpr double youngs = 1.0e9;    // Pa
constexpr double poisson = 0.25;
constexpr double side = 1.0;        // m, every square
constexpr double H = 1.0;           // m
// A dt far below anything the scenes need, used only to read the engine's estimate (the
// constructor refuses a dt above it, so the estimate cannot be read from a rejected one).
constexpr double probe_dt = 1.0e-12;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<Point2> rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

BlockSpec make_block(std::string id, std::vector<Point2> vertices, bool fixed, bool rigid,
                     double density = rho) {
  BlockSpec b;
  b.id = std::move(id);
  b.vertices = std::move(vertices);
  b.fixed = fixed;
  b.rigid = rigid;
  b.material = Material{density, youngs, poisson};
  return b;
}

ContactLaw frictionless(double kn) {
  ContactLaw law;
  law.normal.kn = kn;
  law.normal.H = H;
  return law;
}

// Every scenario starts from a prescribed state (a depth, a squeeze, an impact) and compares the
// integrator's motion from it with a closed form or a linear model, so the initial-equilibrium
// pre-solve, which would replace that state by the static one, stays off.
DdaParams step_params(double dt, bool gravity) {
  DdaParams p;
  p.dt = dt;
  p.gravity = {0.0, gravity ? -g : 0.0};
  p.initial_equilibrium = rockcontact::dynamics::InitialEquilibrium::off;
  return p;
}

double estimate_of(const std::vector<BlockSpec>& blocks, const ContactLaw& law, bool gravity) {
  return Dda2d(blocks, law, step_params(probe_dt, gravity)).critical_time_step();
}

// --- the linear model ----------------------------------------------------------------------
// M x'' + K x = f with M diagonal, started at rest from x = 0. With mass-normalised modes phi_k
// (phi^T M phi = 1) the static state is x_s = sum_k phi_k (phi_k . f) / omega_k² and
// x(t) = x_s + sum_k c_k phi_k cos(omega_k t), c_k = -(phi_k . f) / omega_k² (times 1 - a for
// a release from a x_s). Velocity Verlet
// reproduces each mode exactly as c_k cos(theta_k n) with cos theta_k = 1 - (omega_k h)² / 2,
// and its full-step energy is E_k (1 - q_k sin²(theta_k n)), q_k = (omega_k h / 2)²,
// E_k = ½ omega_k² c_k²: the energy never rises above its start and dips by at most q_k E_k.
struct LinearModel {
  std::size_t n = 0;
  std::vector<double> omega2;             // rad²/s²
  std::vector<std::vector<double>> phi;   // mass-normalised mode shapes
  std::vector<double> c;                  // modal amplitudes of the release from rest at 0
};

// Eigen-decomposition of a symmetric matrix (row-major, n x n) by cyclic Jacobi rotations.
void jacobi(std::vector<double>& a, std::vector<double>& v, std::size_t n) {
  v.assign(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) v[i * n + i] = 1.0;
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0, diag = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      diag += a[i * n + i] * a[i * n + i];
      for (std::size_t j = i + 1; j < n; ++j) off += a[i * n + j] * a[i * n + j];
    }
    if (off <= 1e-32 * diag) return;
    for (std::size_t p = 0; p < n; ++p) {
      for (std::size_t q = p + 1; q < n; ++q) {
        if (a[p * n + q] == 0.0) continue;
        const double theta = (a[q * n + q] - a[p * n + p]) / (2.0 * a[p * n + q]);
        const double t = std::copysign(1.0, theta) / (std::fabs(theta) + std::hypot(theta, 1.0));
        const double cs = 1.0 / std::hypot(t, 1.0), sn = t * cs;
        for (std::size_t k = 0; k < n; ++k) {  // A <- A J
          const double akp = a[k * n + p], akq = a[k * n + q];
          a[k * n + p] = cs * akp - sn * akq;
          a[k * n + q] = sn * akp + cs * akq;
        }
        for (std::size_t k = 0; k < n; ++k) {  // A <- J^T A
          const double apk = a[p * n + k], aqk = a[q * n + k];
          a[p * n + k] = cs * apk - sn * aqk;
          a[q * n + k] = sn * apk + cs * aqk;
        }
        for (std::size_t k = 0; k < n; ++k) {
          const double vkp = v[k * n + p], vkq = v[k * n + q];
          v[k * n + p] = cs * vkp - sn * vkq;
          v[k * n + q] = sn * vkp + cs * vkq;
        }
      }
    }
  }
}

// `start` is where the release happens, as a fraction of the static state (0: from x = 0).
LinearModel solve_model(const std::vector<double>& mass, const std::vector<double>& K,
                        const std::vector<double>& f, double start = 0.0) {
  const std::size_t n = mass.size();
  std::vector<double> a(n * n), v;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) a[i * n + j] = K[i * n + j] / std::sqrt(mass[i] * mass[j]);
  jacobi(a, v, n);
  LinearModel m;
  m.n = n;
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<double> shape(n);
    double load = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      shape[i] = v[i * n + k] / std::sqrt(mass[i]);
      load += shape[i] * f[i];
    }
    m.omega2.push_back(a[k * n + k]);
    m.c.push_back(-(1.0 - start) * load / a[k * n + k]);
    m.phi.push_back(std::move(shape));
  }
  return m;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// theta of the Verlet recurrence for a mode: cos theta = 1 - (omega h)² / 2.
double verlet_theta(double omega2, double h) { return std::acos(1.0 - 0.5 * omega2 * h * h); }

double omega_max(const LinearModel& m) { return std::sqrt(*std::ranges::max_element(m.omega2)); }

// Period of the slowest mode under Verlet, s.
double slow_period(const LinearModel& m, double h) {
  return 2.0 * std::numbers::pi * h / verlet_theta(*std::ranges::min_element(m.omega2), h);
}

double energy_scale(const LinearModel& m) {
  double e = 0.0;
  for (std::size_t k = 0; k < m.n; ++k) e += 0.5 * m.omega2[k] * m.c[k] * m.c[k];
  return e;
}

double verlet_energy_bound(const LinearModel& m, double h) {
  double e = 0.0;
  for (std::size_t k = 0; k < m.n; ++k) {
    const double q = 0.25 * m.omega2[k] * h * h;
    e += q * 0.5 * m.omega2[k] * m.c[k] * m.c[k];
  }
  return e;
}

// Largest excursion of the depth D = -b.x above its static value: sum_k |c_k b.phi_k|.
double depth_excursion(const LinearModel& m, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t k = 0; k < m.n; ++k) s += std::fabs(m.c[k] * dot(b, m.phi[k]));
  return s;
}

// Bound of |mean of D over steps 1..N - static D|: the mean of cos(theta n) over N steps is
// sin(N theta / 2) cos((N + 1) theta / 2) / (N sin(theta / 2)).
double mean_error_bound(const LinearModel& m, const std::vector<double>& b, std::size_t N, double h) {
  double s = 0.0;
  for (std::size_t k = 0; k < m.n; ++k) {
    const double theta = verlet_theta(m.omega2[k], h);
    const double ratio = std::fabs(std::sin(0.5 * static_cast<double>(N) * theta) /
                                   (static_cast<double>(N) * std::sin(0.5 * theta)));
    s += std::fabs(m.c[k] * dot(b, m.phi[k])) * std::min(1.0, ratio);
  }
  return s;
}

// The law's -d² term (header) softens the spring by 2 d / L of itself over an oscillation of
// amplitude up to D_s, which moves the mean of the depth off D_s by about D_s² / L.
double nonlinear_shift(double Ds, double L) { return Ds * Ds / L; }

double penetration_of(const Dda2d& sim, std::size_t a, std::size_t b) {
  for (const auto& c : sim.contacts())
    if ((c.cp == a && c.tp == b) || (c.cp == b && c.tp == a)) return c.penetration;
  return 0.0;
}

// Upward crossings of the mean with a hysteresis of half the amplitude, so that a faster mode
// riding on the slow one cannot add crossings while its amplitude stays below that.
double crossing_period(const std::vector<double>& y, double dt) {
  const auto [lo, hi] = std::ranges::minmax_element(y);
  double mean = 0.0;
  for (double v : y) mean += v;
  mean /= static_cast<double>(y.size());
  const double band = 0.25 * (*hi - *lo);
  std::vector<double> times;
  bool below = false;
  std::size_t last_below_mean = 0;
  for (std::size_t n = 0; n < y.size(); ++n) {
    if (y[n] < mean) last_below_mean = n;
    if (y[n] < mean - band) below = true;
    if (below && y[n] > mean + band) {
      below = false;
      const std::size_t k = last_below_mean;  // y[k] < mean <= y[k + 1]
      const double frac = (mean - y[k]) / (y[k + 1] - y[k]);
      times.push_back((static_cast<double>(k) + frac) * dt);
    }
  }
  if (times.size() < 2) return nan;
  return (times.back() - times.front()) / static_cast<double>(times.size() - 1);
}

std::vector<BlockSpec> resting_scene() {
  return {make_block("base", rectangle(-1.0, -1.0, 2.0, 0.0), true, false),
          make_block("block", rectangle(0.0, 0.0, side, side), false, false)};
}

// The 3-DOF model of the resting block: x = (v0, ex, ey), M = m diag(1, l²/12, l²/12) (eq. 5a
// about the centroid), K = S E-matrix on (ex, ey) plus the contact spring k b b^T on the face
// displacement b.x = v0 - (l/2) ey, linearised at the static depth: k = kn / H (2 L - 2 D_s).
LinearModel resting_model(double kn) {
  const double m = rho * side * side;
  const double Ds = static_depth(m * g, side, kn, H, false);
  const double k = kn / H * (2.0 * side - 2.0 * Ds);
  const double e = side * side * youngs / (1.0 - poisson * poisson);
  const std::vector<double> b{1.0, 0.0, -0.5 * side};
  std::vector<double> K{0, 0, 0, 0, e, e * poisson, 0, e * poisson, e};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) K[i * 3 + j] += k * b[i] * b[j];
  const double mr = m * side * side / 12.0;
  return solve_model({m, mr, mr}, K, {-m * g, 0.0, 0.0});
}

}  // namespace

double static_depth(double W, double L, double kn, double H_, bool equal_faces) {
  const double a = W * H_ / kn;
  // kn/H (2 L d - d²) = W  ->  d = L - sqrt(L² - a);   2 kn/H (L d - d²) = W  ->  d = (L -
  // sqrt(L² - 2a)) / 2, written as a / (L + sqrt(...)) forms to avoid cancellation.
  return equal_faces ? a / (L + std::sqrt(L * L - 2.0 * a)) : a / (L + std::sqrt(L * L - a));
}

RestingRun resting_block(double kn_over_e, double dt_fraction, double periods) {
  const auto start = Clock::now();
  RestingRun r;
  r.kn_over_e = kn_over_e;
  const double kn = kn_over_e * youngs;
  const auto blocks = resting_scene();
  const ContactLaw law = frictionless(kn);
  r.dt_estimate = estimate_of(blocks, law, true);
  r.dt = dt_fraction * r.dt_estimate;
  const LinearModel model = resting_model(kn);
  const double m = rho * side * side;
  const std::vector<double> b{-1.0, 0.0, 0.5 * side};  // D = b.x (depth, positive in)
  r.dt_model = 2.0 / omega_max(model);
  r.static_depth = static_depth(m * g, side, kn, H, false);
  r.period_rigid = 2.0 * std::numbers::pi * std::sqrt(m / (kn / H * (2.0 * side - 2.0 * r.static_depth)));
  r.period_model = slow_period(model, r.dt);
  r.energy_scale = energy_scale(model);
  r.energy_bound = verlet_energy_bound(model, r.dt);
  r.max_depth_bound = r.static_depth + depth_excursion(model, b);

  Dda2d sim(blocks, law, step_params(r.dt, true));
  const double e0 = sim.energies().total();
  const auto N = static_cast<std::size_t>(std::llround(periods * r.period_model / r.dt));
  std::vector<double> y;
  y.reserve(N);
  double depth_sum = 0.0;
  while (sim.steps() < N) {
    sim.step();
    const double d = penetration_of(sim, 0, 1);
    depth_sum += d;
    r.max_depth = std::max(r.max_depth, d);
    y.push_back(sim.blocks()[1].centroid.y);
    const double e = sim.energies().total() - e0;
    r.energy_rise = std::max(r.energy_rise, e);
    r.energy_drop = std::max(r.energy_drop, -e);
  }
  r.steps = N;
  r.mean_depth = depth_sum / static_cast<double>(N);
  r.mean_depth_tolerance = mean_error_bound(model, b, N, r.dt) + nonlinear_shift(r.static_depth, side);
  r.period_measured = crossing_period(y, r.dt);
  r.seconds = seconds_since(start);
  return r;
}

std::string resting_block_refusal(double kn_over_e, double dt_fraction) {
  const auto blocks = resting_scene();
  const ContactLaw law = frictionless(kn_over_e * youngs);
  const double dt = dt_fraction * estimate_of(blocks, law, true);
  try {
    Dda2d sim(blocks, law, step_params(dt, true));
  } catch (const StabilityError& e) {
    return e.what();
  }
  return {};
}

SqueezedRun squeezed_block(double dt_over_estimate, std::size_t steps) {
  const auto start = Clock::now();
  SqueezedRun r;
  constexpr double depth = 1.0e-4;  // m, initial overlap on every face
  r.kn_over_e = 12.0 * H / (28.0 * side * (1.0 - poisson));
  const double kn = r.kn_over_e * youngs;
  // Left and right blocks stop short of the top and bottom ones (fixed pairs never meet).
  const std::vector<BlockSpec> blocks{
      make_block("squeezed", rectangle(0.0, 0.0, side, side), false, false),
      make_block("bottom", rectangle(-1.0, -1.0, 2.0, depth), true, false),
      make_block("top", rectangle(-1.0, side - depth, 2.0, 2.0), true, false),
      make_block("left", rectangle(-1.0, depth, depth, side - depth), true, false),
      make_block("right", rectangle(side - depth, depth, 2.0, side - depth), true, false)};
  const ContactLaw law = frictionless(kn);
  // Dilatation ex = ey = e: M_e = m l² / 6, elastic 2 S E / (1 - nu), contact: four faces of
  // stiffness k_f = 2 kn l / H whose depth grows by e l / 2, k_f l² (O(depth / l) ignored).
  const double m = rho * side * side;
  const double kf = 2.0 * kn * side / H;
  const double Ke = 2.0 * side * side * youngs / (1.0 - poisson) + kf * side * side;
  const double Me = m * side * side / 6.0;
  r.dt_model = 2.0 / std::sqrt(Ke / Me);
  const double es = -2.0 * kf * depth * side / Ke;
  r.energy_scale = 0.5 * Ke * es * es;
  r.dt_estimate = estimate_of(blocks, law, false);
  r.dt = dt_over_estimate * r.dt_estimate;
  try {
    Dda2d sim(blocks, law, step_params(r.dt, false));
    const double e0 = sim.energies().total();
    try {
      while (sim.steps() < steps) {
        sim.step();
        const double e = sim.energies().total() - e0;
        r.energy_rise = std::max(r.energy_rise, e);
        r.energy_drop = std::max(r.energy_drop, -e);
      }
    } catch (const StabilityError& e) {
      r.stopped = true;
      r.message = e.what();
    }
    r.steps = sim.steps();
  } catch (const StabilityError& e) {
    r.refused = true;
    r.message = e.what();
  }
  r.seconds = seconds_since(start);
  return r;
}

MassRatioRun mass_ratio(double ratio, bool heavy_on_top, double slow_periods) {
  const auto start = Clock::now();
  MassRatioRun r;
  r.ratio = ratio;
  r.heavy_on_top = heavy_on_top;
  constexpr double kn = 1.0e7;  // Pa, seed 000 Table 4
  // The light block is a 0.5 m square, so every face in contact lies inside a wider one: two
  // equal aligned faces would push an offset further out (the corner terms of the potential,
  // see resting_stack) and squeeze a frictionless light block out sideways.
  const double small = 0.5 * side;
  const double mh = rho * side * side, ml = mh / ratio;
  const double st = heavy_on_top ? side : small, sl = heavy_on_top ? small : side;  // sizes
  const double mt = heavy_on_top ? mh : ml, mlow = heavy_on_top ? ml : mh;
  r.top_static = static_depth(mt * g, std::min(st, sl), kn, H, false);
  r.bottom_static = static_depth((mt + mlow) * g, sl, kn, H, false);
  // Started at rest with half the static overlaps, so that the contacts stay closed (checked
  // by the model's excursions) and the motion is the linear model's.
  const double y_low = -0.5 * r.bottom_static, y_top = y_low + sl - 0.5 * r.top_static;
  const double x_low = 0.5 * (side - sl), x_top = 0.5 * (side - st);
  const std::vector<BlockSpec> blocks{
      make_block("base", rectangle(-1.0, -1.0, 2.0, 0.0), true, true),
      make_block(heavy_on_top ? "light" : "heavy", rectangle(x_low, y_low, x_low + sl, y_low + sl),
                 false, true, mlow / (sl * sl)),
      make_block(heavy_on_top ? "heavy" : "light", rectangle(x_top, y_top, x_top + st, y_top + st),
                 false, true, mt / (st * st))};
  const ContactLaw law = frictionless(kn);
  r.dt_estimate = estimate_of(blocks, law, true);
  r.dt = default_dt_fraction * r.dt_estimate;
  // x = (v_top, v_low) from the static state; springs linearised at the static depths.
  const double k1 = kn / H * (2.0 * std::min(st, sl) - 2.0 * r.top_static);
  const double k0 = kn / H * (2.0 * sl - 2.0 * r.bottom_static);
  const LinearModel model =
      solve_model({mt, mlow}, {k1, -k1, -k1, k1 + k0}, {-mt * g, -mlow * g}, 0.5);
  const std::vector<double> b_top{-1.0, 1.0}, b_low{0.0, -1.0};
  r.energy_scale = energy_scale(model);
  r.energy_bound = verlet_energy_bound(model, r.dt);
  r.top_excursion = depth_excursion(model, b_top);
  r.bottom_excursion = depth_excursion(model, b_low);

  Dda2d sim(blocks, law, step_params(r.dt, true));
  const double e0 = sim.energies().total();
  const auto N = static_cast<std::size_t>(std::llround(slow_periods * slow_period(model, r.dt) / r.dt));
  double top_sum = 0.0, low_sum = 0.0;
  while (sim.steps() < N) {
    sim.step();
    top_sum += penetration_of(sim, 1, 2);
    low_sum += penetration_of(sim, 0, 1);
    const double e = sim.energies().total() - e0;
    r.energy_rise = std::max(r.energy_rise, e);
    r.energy_drop = std::max(r.energy_drop, -e);
  }
  r.steps = N;
  r.top_mean = top_sum / static_cast<double>(N);
  r.bottom_mean = low_sum / static_cast<double>(N);
  r.top_tolerance = mean_error_bound(model, b_top, N, r.dt) +
                    nonlinear_shift(r.top_static, std::min(st, sl));
  r.bottom_tolerance = mean_error_bound(model, b_low, N, r.dt) + nonlinear_shift(r.bottom_static, sl);
  r.max_depth = sim.max_penetration();
  r.seconds = seconds_since(start);
  return r;
}

StackRun resting_stack(std::size_t steps) {
  const auto start = Clock::now();
  StackRun r;
  constexpr std::size_t count = 10;
  constexpr double kn = 5.0e7;  // Pa, seed 000 Table 5
  const double m = rho * side * side;
  std::vector<BlockSpec> blocks{make_block("base", rectangle(-1.0, -1.0, 2.0, 0.0), true, true)};
  double bottom = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double load = static_cast<double>(count - i) * m * g;
    const double d = static_depth(load, side, kn, H, i > 0);
    r.energy_stored += i > 0 ? 2.0 * kn / H * (side * d * d / 2.0 - d * d * d / 3.0)
                             : kn / H * (side * d * d - d * d * d / 3.0);
    bottom -= d;
    blocks.push_back(make_block("s" + std::to_string(i), rectangle(0.0, bottom, side, bottom + side),
                                false, true));
    bottom += side;
  }
  // Friction (seed 000 Table 5: kt 1e7 N/m, the §5 scenes' 30°) holds the stack laterally: two
  // equal aligned faces offset by s push each other further out with 2 kn / H (s d - s²/2) (the
  // corner terms of the shortest-exit potential, as in the header's force law), a negative
  // lateral stiffness of about W / L that kt = 1e7 N/m outweighs by 50 times; without friction
  // rounding alone grows into a collapse of the stack within 10^4 steps.
  ContactLaw law = frictionless(kn);
  law.friction = dynamics::FrictionLaw{1.0e7, 30.0};
  r.blocks = count;
  r.dt_estimate = estimate_of(blocks, law, true);
  r.dt = default_dt_fraction * r.dt_estimate;
  Dda2d sim(blocks, law, step_params(r.dt, true));
  std::vector<Point2> c0;
  for (const BlockState& s : sim.blocks()) c0.push_back(s.centroid);
  const double e0 = sim.energies().total();
  while (sim.steps() < steps) {
    sim.step();
    const auto& states = sim.blocks();
    for (std::size_t i = 1; i < states.size(); ++i) {
      r.position_drift = std::max(r.position_drift, std::hypot(states[i].centroid.x - c0[i].x,
                                                               states[i].centroid.y - c0[i].y));
      r.rotation_drift = std::max(r.rotation_drift, std::fabs(states[i].rotation));
    }
    r.energy_drift = std::max(r.energy_drift, std::fabs(sim.energies().total() - e0));
  }
  r.steps = steps;
  r.seconds = seconds_since(start);
  return r;
}

PaperSceneRun paper_scene(const std::filesystem::path& file, double kn_factor, double duration) {
  const auto start = Clock::now();
  PaperSceneRun r;
  r.scene = file.stem().string();
  r.kn_factor = kn_factor;
  dynamics::Scene scene = dynamics::read_scene_file(file);
  scene.law.normal.kn *= kn_factor;
  for (auto& i : scene.law.interfaces) i.kn *= kn_factor;
  r.kn = scene.law.normal.kn;
  DdaParams params = scene.params;
  params.dt = probe_dt;
  r.dt_estimate = Dda2d(scene.blocks, scene.law, params).critical_time_step();
  params.dt = r.dt = default_dt_fraction * r.dt_estimate;
  const double T = duration > 0.0 ? duration : scene.duration;
  r.steps = static_cast<std::size_t>(std::ceil(T / r.dt));
  Dda2d sim(scene.blocks, scene.law, params);
  const auto index = [&](const std::string& id) {
    const auto& s = sim.blocks();
    const auto it = std::ranges::find_if(s, [&](const BlockState& b) { return b.id == id; });
    return it == s.end() ? s.size() : static_cast<std::size_t>(it - s.begin());
  };
  const std::size_t top = index("top"), bottom = index("bottom"), falling = index("falling");
  const std::size_t none = sim.blocks().size();
  const double e0 = sim.energies().total();
  double rise = 0.0, impact = 0.0, rebound = 0.0;
  bool touched = false, rising = false;
  const auto observe = [&] {
    const dynamics::Energies e = sim.energies();
    r.impact_energy = std::max(r.impact_energy, e.kinetic);
    rise = std::max(rise, e.total() - e0);
    const auto& s = sim.blocks();
    if (top != none && bottom != none) {
      const double a = std::max(std::hypot(s[top].centroid.x + s[bottom].centroid.x,
                                           s[top].centroid.y + s[bottom].centroid.y),
                                std::fabs(s[top].rotation - s[bottom].rotation));
      r.asymmetry = std::isnan(r.asymmetry) ? a : std::max(r.asymmetry, a);
    }
    if (falling != none) {
      const double vy = s[falling].velocity[1];
      touched = touched || !sim.contacts().empty();
      rising = rising || (touched && vy > 0.0);
      if (!rising) impact = std::max(impact, -vy);
      if (rising) rebound = std::max(rebound, vy);
    }
  };
  observe();
  try {
    while (sim.steps() < r.steps) {
      sim.step();
      observe();
    }
    r.completed = true;
  } catch (const StabilityError& e) {
    r.message = e.what();
  }
  r.max_penetration = sim.max_penetration();
  r.energy_growth = rise / r.impact_energy;
  if (falling != none && impact > 0.0) r.rebound_ratio = rebound / impact;
  r.seconds = seconds_since(start);
  return r;
}

}  // namespace rockcontact::stiff
