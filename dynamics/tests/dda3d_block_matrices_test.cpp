#define BOOST_TEST_MODULE dynamics_dda3d_block_matrices
#include <boost/test/unit_test.hpp>

// Per-block terms of the implicit 3D DDA (dynamics/dda3d/src/block_matrices3d.hpp) against closed
// forms and an independent quadrature, and the configuration update against the exact rotation.

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "../dda3d/src/block_matrices3d.hpp"
#include "rockcontact/generators/pair3d_generators.hpp"
#include "rockcontact/kernel/3d/moments.hpp"
#include "rockcontact/testing/polyhedra3d.hpp"

namespace {

namespace d = rockcontact::dynamics::detail;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using rockcontact::kernel::ConvexPolyhedron;
using rockcontact::kernel::Point3;

using LD = long double;
using V3L = Eigen::Matrix<LD, 3, 1>;
using M12L = Eigen::Matrix<LD, 12, 12>;

constexpr double rho = 2700.0;  // kg/m³
constexpr double u = 0x1p-53;   // unit roundoff of double

// A random multiple of 2^-30 in [lo, hi]: coordinates of at most 31 significant bits below 2 m,
// so a block of them shifted by 2^20 m is the same block exactly.
double dyadic(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> dist(lo, hi);
  return std::ldexp(std::round(std::ldexp(dist(rng), 30)), -30);
}

// The hull of `n` dyadic points in the ellipsoid of semi-axes (0.9, 0.6, 0.45) m about the origin.
ConvexPolyhedron random_hull(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::vector<Point3> points;
  while (static_cast<int>(points.size()) < n) {
    const Point3 p{dyadic(rng, -0.9, 0.9), dyadic(rng, -0.6, 0.6), dyadic(rng, -0.45, 0.45)};
    const double r2 = p.x * p.x / 0.81 + p.y * p.y / 0.36 + p.z * p.z / 0.2025;
    if (r2 <= 1.0) points.push_back(p);
  }
  return *rockcontact::robustness::convex_hull3("random", points);
}

// Two convex parts glued along the square [0, 1]² x {0}: the hull of that square and `n` dyadic
// points below it, and of the square and `n` points above it (a non-convex union in general).
std::vector<ConvexPolyhedron> two_part_block(std::uint64_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::vector<ConvexPolyhedron> parts;
  for (const double side : {-1.0, 1.0}) {
    std::vector<Point3> points{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int k = 0; k < n; ++k) {
      points.push_back(
          {dyadic(rng, 0.0, 1.0), dyadic(rng, 0.0, 1.0), side * dyadic(rng, 0.05, 0.9)});
    }
    parts.push_back(*rockcontact::robustness::convex_hull3(side < 0 ? "below" : "above", points));
  }
  return parts;
}

std::vector<ConvexPolyhedron> translated(const std::vector<ConvexPolyhedron>& parts, Vector3d t) {
  d::StepMap map;
  map.translation = t;
  return d::moved_parts(parts, map);
}

// Independent quadrature, in long double: every part is split into tetrahedra from the mean of
// its vertices (not the code's fan from one vertex), each integrated by the 4-point rule with
// points α v_i + β Σ_{j≠i} v_j, α = (5 + 3√5)/20, β = (5 - √5)/20, weights V/4, exact for
// polynomials of degree 2; T^T T (degree 2) and T (degree 1) are taken from displacement_matrix
// at the offsets from the quadrature's own centroid.
struct Quadrature {
  LD volume = 0;
  V3L centroid = V3L::Zero();
  M12L ttt = M12L::Zero();                                        // ∫ T^T T dV
  Eigen::Matrix<LD, 3, 12> t = Eigen::Matrix<LD, 3, 12>::Zero();  // ∫ T dV
};

Quadrature quadrature(const std::vector<ConvexPolyhedron>& parts) {
  auto point = [](const Point3& p) { return V3L(p.x, p.y, p.z); };
  std::vector<std::array<V3L, 4>> tets;
  for (const ConvexPolyhedron& part : parts) {
    V3L mean = V3L::Zero();
    for (const Point3& p : part.vertices()) mean += point(p);
    mean /= static_cast<LD>(part.size());
    for (const ConvexPolyhedron::Face& f : part.faces()) {
      for (std::size_t k = 1; k + 1 < f.size(); ++k) {
        tets.push_back({mean, point(part[f[0]]), point(part[f[k]]), point(part[f[k + 1]])});
      }
    }
  }
  const LD sqrt5 = std::sqrt(static_cast<LD>(5));
  const LD alpha = (5 + 3 * sqrt5) / 20, beta = (5 - sqrt5) / 20;
  Quadrature q;
  std::vector<std::pair<V3L, LD>> points;
  for (const auto& t : tets) {
    const LD vol = (t[1] - t[0]).dot((t[2] - t[0]).cross(t[3] - t[0])) / 6;
    BOOST_REQUIRE(vol > 0);
    const V3L sum = t[0] + t[1] + t[2] + t[3];
    q.volume += vol;
    q.centroid += vol * sum / 4;
    for (const V3L& v : t) points.emplace_back(alpha * v + beta * (sum - v), vol / 4);
  }
  q.centroid /= q.volume;
  for (const auto& [p, w] : points) {
    const V3L off = p - q.centroid;
    const Point3 offset{static_cast<double>(off.x()), static_cast<double>(off.y()),
                        static_cast<double>(off.z())};
    const Eigen::Matrix<LD, 3, 12> T = d::displacement_matrix(offset).cast<LD>();
    q.ttt += w * T.transpose() * T;
    q.t += w * T;
  }
  return q;
}

double max_abs_difference(const d::Matrix12& a, const d::Matrix12& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

// The largest |M_ij - rho Q_ij| relative to the largest |rho Q_ij|.
double relative_error(const d::Matrix12& M, const Quadrature& q) {
  const d::Matrix12 expected = (static_cast<LD>(rho) * q.ttt).cast<double>();
  return max_abs_difference(M, expected) / expected.cwiseAbs().maxCoeff();
}

Matrix3d skew(const Vector3d& r) {
  Matrix3d k;
  k << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return k;
}

Vector3d random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Vector3d(n(rng), n(rng), n(rng)).normalized();
}

}  // namespace

// An a x b x c box: S = V diag(a², b², c²) / 12, so with m = rho V, by hand from the columns of
// T: rotations m (b²+c², c²+a², a²+b²) / 12, normal strains m (a², b², c²) / 12, shear strains
// m (b²+c², c²+a², a²+b²) / 48, and the only couplings (rx, gyz) = m (b² - c²) / 24,
// (ry, gzx) = m (c² - a²) / 24, (rz, gxy) = m (a² - b²) / 24. The corners are dyadic, so the
// local frame is exact: tolerance a handful of roundings (1e-14 of the largest entry).
BOOST_AUTO_TEST_CASE(box_mass_matrix_in_closed_form) {
  const double a = 2.0, b = 0.5, c = 1.25;
  const std::vector<ConvexPolyhedron> parts{
      rockcontact::testing::box("box", {3, -1, 2}, {5, -0.5, 3.25})};
  const d::CentralMoments3d mom = d::central_moments3d(parts);
  const double V = a * b * c, m = rho * V;
  BOOST_TEST(std::fabs(mom.volume - V) <= 4 * u * V);
  // The centroid o + first / V is rounded a few times at |c| ~ 5 m.
  BOOST_TEST((mom.centroid - Vector3d(4, -0.75, 2.625)).norm() <= 16 * u * 5);
  d::Matrix12 expected = d::Matrix12::Zero();
  expected.diagonal() << m, m, m, m * (b * b + c * c) / 12, m * (c * c + a * a) / 12,
      m * (a * a + b * b) / 12, m * a * a / 12, m * b * b / 12, m * c * c / 12,
      m * (b * b + c * c) / 48, m * (c * c + a * a) / 48, m * (a * a + b * b) / 48;
  expected(3, 9) = expected(9, 3) = m * (b * b - c * c) / 24;
  expected(4, 10) = expected(10, 4) = m * (c * c - a * a) / 24;
  expected(5, 11) = expected(11, 5) = m * (a * a - b * b) / 24;
  const d::Matrix12 M = d::mass_matrix(mom, m);
  BOOST_TEST(max_abs_difference(M, expected) <= 1e-14 * expected.cwiseAbs().maxCoeff());
}

// The same box turned by Q = R(0.3, -0.5, 0.7) about its centre: the rotation block is the
// inertia tensor Q J Qᵀ, now full. The turned corners are rounded (a few u of the 2 m box), so
// the moments move by a few u: tolerance 1e-14 of the largest entry.
BOOST_AUTO_TEST_CASE(turned_box_inertia_tensor) {
  const double a = 2.0, b = 0.5, c = 1.25;
  const ConvexPolyhedron box =
      rockcontact::testing::box("box", {-1, -0.25, -0.625}, {1, 0.25, 0.625});
  const Matrix3d Q = d::rotation_matrix(Vector3d(0.3, -0.5, 0.7));
  std::vector<Point3> turned;
  for (const Point3& p : box.vertices()) {
    const Vector3d x = Vector3d(7, -3, 2) + Q * Vector3d(p.x, p.y, p.z);
    turned.push_back({x.x(), x.y(), x.z()});
  }
  const std::vector<ConvexPolyhedron> parts{box.moved(turned)};
  const double m = rho * a * b * c;
  const Matrix3d J =
      m / 12 * Eigen::Vector3d(b * b + c * c, c * c + a * a, a * a + b * b).asDiagonal();
  const Matrix3d expected = Q * J * Q.transpose();
  const d::Matrix12 M = d::mass_matrix(d::central_moments3d(parts), m);
  const Matrix3d inertia = M.block<3, 3>(3, 3);
  BOOST_TEST_MESSAGE("turned box inertia tensor:\n" << inertia);
  BOOST_TEST((inertia - expected).cwiseAbs().maxCoeff() <= 1e-14 * expected.norm());
  BOOST_TEST((M.topLeftCorner<3, 3>() - m * Matrix3d::Identity()).cwiseAbs().maxCoeff() <=
             1e-14 * m);
  const double coupling = M.topRightCorner<3, 9>().cwiseAbs().maxCoeff();
  BOOST_TEST(coupling == 0.0);
}

// A random hull and a two-part block against the quadrature, every entry. The quadrature's T^T T
// comes from displacement_matrix, so this is also M / rho = ∫ T^T T dV for the T the contact
// terms use. Tolerance: the code's local sums carry a few u per tetrahedron of V diam² (header
// of kernel/3d/moments.hpp), and the parallel-axis shift from a vertex to the centroid loses up
// to m_ij / S_ij ~ a factor 10; the quadrature offsets are rounded to double (2 u). 1e-14 of the
// largest entry is ~90 u (measured: ~2 u).
BOOST_AUTO_TEST_CASE(mass_matrix_matches_tetrahedral_quadrature) {
  for (const std::uint64_t seed : {11u, 12u, 13u}) {
    const std::vector<std::vector<ConvexPolyhedron>> blocks{{random_hull(seed, 30)},
                                                            two_part_block(seed, 12)};
    for (const auto& parts : blocks) {
      BOOST_TEST_CONTEXT("seed " << seed << ", " << parts.size() << " part(s)") {
        const Quadrature q = quadrature(parts);
        const d::CentralMoments3d mom = d::central_moments3d(parts);
        const double V = static_cast<double>(q.volume);
        BOOST_TEST(std::fabs(mom.volume - V) <= 1e-14 * V);
        BOOST_TEST((mom.centroid - q.centroid.cast<double>()).norm() <= 1e-14);
        const double err = relative_error(d::mass_matrix(mom, rho * mom.volume), q);
        BOOST_TEST_MESSAGE("seed " << seed << ", " << parts.size() << " part(s): max error of M "
                                   << err << " of its largest entry");
        BOOST_TEST(err <= 1e-14);
        // Gravity: the work rho g . ∫ T dV D of a uniform load is gravity_load . D; the first
        // moments about the centroid vanish, so only the translation rows carry it. Tolerance as
        // for M.
        const Vector3d g(0.0, 0.0, -9.81);
        const d::Vector12 expected =
            (static_cast<LD>(rho) * q.t.transpose() * g.cast<LD>()).cast<double>();
        const d::Vector12 f = d::gravity_load(rho * mom.volume, g);
        BOOST_TEST((f - expected).cwiseAbs().maxCoeff() <= 1e-14 * expected.norm());
      }
    }
  }
}

// The same block at 2^20 m (~1e6 m) from the origin. Shifted by a power of two its dyadic
// corners stay exact and its local frame is the same to the bit, so M is equal exactly: no digit
// lost to the global frame (central moments from kernel::moments there keep about 3 digits, as
// printed). Then the block turned once (corners no longer on a dyadic grid) and shifted by a
// rounded 1.3e6 m: every corner moves by up to ulp(2e6) / 2 ~ 1.2e-10 m, a relative change of the
// ~1 m block's moments of a few times that: tolerance 1e-9 of the largest entry.
BOOST_AUTO_TEST_CASE(mass_matrix_far_from_the_origin) {
  const std::vector<ConvexPolyhedron> near = two_part_block(21, 12);
  const d::CentralMoments3d mom = d::central_moments3d(near);
  const d::Matrix12 M = d::mass_matrix(mom, rho * mom.volume);

  const Vector3d dyadic_shift(0x1p20, -0x1p20, 0x1p19);
  const d::CentralMoments3d far = d::central_moments3d(translated(near, dyadic_shift));
  BOOST_TEST(far.volume == mom.volume);
  BOOST_TEST(max_abs_difference(d::mass_matrix(far, rho * far.volume), M) == 0.0);
  // The centroid is rounded once at ~1e6 m: ulp(2^20) = 2^-32.
  BOOST_TEST((far.centroid - dyadic_shift - mom.centroid).cwiseAbs().maxCoeff() <= 0x1p-32);
  // What the global frame would give: the parts' global moments summed, then shifted.
  double V = 0, xx = 0, x = 0;
  for (const ConvexPolyhedron& part : translated(near, dyadic_shift)) {
    const rockcontact::kernel::Moments3 g = rockcontact::kernel::moments(part);
    V += g.volume, xx += g.xx, x += g.first.x;
  }
  BOOST_TEST_MESSAGE("2^20 m out, S_xx from global moments: relative error "
                     << std::fabs((xx - x * x / V) - mom.second(0, 0)) / mom.second(0, 0)
                     << " (from the local frame: 0)");

  d::Vector12 turn = d::Vector12::Zero();
  turn.segment<3>(3) = Vector3d(0.3, -0.2, 0.5);
  const std::vector<ConvexPolyhedron> turned =
      d::moved_parts(near, d::step_map(mom.centroid, turn));
  const d::CentralMoments3d turned_mom = d::central_moments3d(turned);
  const d::Matrix12 turned_M = d::mass_matrix(turned_mom, rho * turned_mom.volume);
  const Vector3d shift(1.0e6 + 0.123456789, -1.3e6 - 0.987654321, 0.7e6 + 0.314159265);
  const d::CentralMoments3d rounded = d::central_moments3d(translated(turned, shift));
  const double err = max_abs_difference(d::mass_matrix(rounded, rho * rounded.volume), turned_M) /
                     turned_M.cwiseAbs().maxCoeff();
  BOOST_TEST_MESSAGE("mass matrix 1.3e6 m out, corners rounded there: relative change " << err);
  BOOST_TEST(err > 0.0);  // the corners did move: the shift was not exact
  BOOST_TEST(err <= 1e-9);
}

// E = 3 GPa, nu = 1/4: λ = E ν / ((1+ν)(1-2ν)) = 0.4 E = 1.2 GPa, μ = E / 2.5 = 1.2 GPa, so the
// diagonal is 3.6 GPa for normal strains and 1.2 GPa for shears. The strain energy ½ Dᵀ K D:
// uniaxial strain ε ex stores ½ E' ε² V with the constrained modulus E' = E (1-ν)/((1+ν)(1-2ν));
// uniaxial stress (strain ε (1, -ν, -ν)) stores ½ E ε² V and carries stress (E ε, 0, 0); a shear
// γ stores ½ μ γ² V. Rigid motions store nothing. Tolerance: a few roundings of E.
BOOST_AUTO_TEST_CASE(elasticity_and_strain_energy) {
  const double E = 3.0e9, nu = 0.25, V = 2.5, eps = 1.0e-3;
  const d::Matrix6 C = d::elasticity_matrix3d(E, nu);
  d::Matrix6 hand = d::Matrix6::Zero();
  hand.topLeftCorner<3, 3>().setConstant(1.2e9);
  hand.diagonal() << 3.6e9, 3.6e9, 3.6e9, 1.2e9, 1.2e9, 1.2e9;
  BOOST_TEST((C - hand).cwiseAbs().maxCoeff() <= 4 * u * 3.6e9);

  const d::Matrix12 K = d::elastic_stiffness(C, V);
  auto energy = [&](const d::Vector12& D) { return 0.5 * D.dot(K * D); };
  d::Vector12 D = d::Vector12::Zero();
  D(6) = eps;
  const double constrained = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  BOOST_TEST(std::fabs(energy(D) - 0.5 * constrained * eps * eps * V) <=
             1e-15 * constrained * eps * eps * V);
  D(7) = D(8) = -nu * eps;
  BOOST_TEST(std::fabs(energy(D) - 0.5 * E * eps * eps * V) <= 1e-15 * E * eps * eps * V);
  const Eigen::Matrix<double, 6, 1> stress = C * D.tail<6>();
  BOOST_TEST(std::fabs(stress(0) - E * eps) <= 1e-15 * E * eps);
  BOOST_TEST(stress.tail<5>().cwiseAbs().maxCoeff() <= 1e-15 * E * eps);
  D.setZero();
  D(9) = eps;
  const double mu = E / (2 * (1 + nu));
  BOOST_TEST(std::fabs(energy(D) - 0.5 * mu * eps * eps * V) <= 1e-15 * mu * eps * eps * V);
  BOOST_TEST(K.topRows<6>().cwiseAbs().maxCoeff() == 0.0);
  BOOST_TEST(K.leftCols<6>().cwiseAbs().maxCoeff() == 0.0);
}

// A pure translation moves every vertex by exactly fl(x + t) (the gradient is exactly zero), for
// a deformable (12) and a rigid (6) increment vector alike.
BOOST_AUTO_TEST_CASE(translation_moves_every_vertex_exactly) {
  const std::vector<ConvexPolyhedron> parts = two_part_block(31, 10);
  const d::CentralMoments3d mom = d::central_moments3d(parts);
  const Vector3d t(0.1, -0.37, 2.9e-3);
  d::Vector12 D12 = d::Vector12::Zero();
  D12.head<3>() = t;
  const Eigen::Matrix<double, 6, 1> D6 = D12.head<6>();
  for (const d::StepMap& map : {d::step_map(mom.centroid, D12), d::step_map(mom.centroid, D6)}) {
    const std::vector<ConvexPolyhedron> moved = d::moved_parts(parts, map);
    for (std::size_t i = 0; i < parts.size(); ++i) {
      for (std::size_t k = 0; k < parts[i].size(); ++k) {
        const Point3 p = parts[i][k], q = moved[i][k];
        BOOST_TEST((q == Point3{p.x + t.x(), p.y + t.y(), p.z + t.z()}));
      }
    }
  }
}

// A general step, rotation and strain: every vertex goes to c + t + R(r) (I + ε) (x - c),
// checked in long double with R from Rodrigues' formula written out. Tolerance: the code's
// gradient and product carry a few u of |x - c| <= 2 m, and the result is rounded at |x| ~ 3 m.
BOOST_AUTO_TEST_CASE(step_map_is_rotation_after_strain) {
  const std::vector<ConvexPolyhedron> parts{random_hull(41, 20)};
  const d::CentralMoments3d mom = d::central_moments3d(parts);
  d::Vector12 D;
  D << 0.01, -0.02, 0.03, 0.2, -0.1, 0.4, 1e-3, -2e-3, 5e-4, 3e-3, -1e-3, 2e-3;
  const d::StepMap map = d::step_map(mom.centroid, D);
  const Eigen::Matrix<LD, 3, 1> r = D.segment<3>(3).cast<LD>();
  const LD theta = r.norm();
  Eigen::Matrix<LD, 3, 3> K;
  K << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  const Eigen::Matrix<LD, 3, 3> R = Eigen::Matrix<LD, 3, 3>::Identity() +
                                    std::sin(theta) / theta * K +
                                    (1 - std::cos(theta)) / (theta * theta) * K * K;
  Eigen::Matrix<LD, 3, 3> strain;
  strain << D(6), D(11) / 2, D(10) / 2, D(11) / 2, D(7), D(9) / 2, D(10) / 2, D(9) / 2, D(8);
  const V3L c = mom.centroid.cast<LD>();
  for (const Point3& p : parts[0].vertices()) {
    const V3L x(p.x, p.y, p.z);
    const V3L expected =
        c + D.head<3>().cast<LD>() + R * (Eigen::Matrix<LD, 3, 3>::Identity() + strain) * (x - c);
    const Point3 q = d::apply(map, p);
    BOOST_TEST(static_cast<double>((V3L(q.x, q.y, q.z) - expected).norm()) <= 32 * u);
  }
}

// 10^4 steps of r = 0.01 rad about a fresh random axis each, turning about the current centroid
// as the engine does. The exact rotation keeps the volume: each step rounds the turned corners
// (a few u of the ~1 m block), a relative volume change of a few u of either sign, a random walk
// of ~100 such after 10^4 steps, ~1e-13 (measured: 2e-15); 1e-12 bounds it. The centroid likewise
// stays within 1e-12 m (measured: 7e-16 m). The first-order map I + [r]x, applied to a copy,
// multiplies the volume by det(I + [r]x) = 1 + |r|² each step, (1 + 1e-4)^(10^4) ≈ e in all:
// asserted against that product to 1e-10 (n = 10^4 steps of a few u each).
BOOST_AUTO_TEST_CASE(spinning_block_keeps_its_volume) {
  const std::uint64_t seed = 51;
  BOOST_TEST_MESSAGE("spin: seed " << seed);
  std::mt19937_64 rng(seed);
  std::vector<ConvexPolyhedron> exact{random_hull(seed, 25)};
  std::vector<ConvexPolyhedron> first_order = exact;
  const d::CentralMoments3d start = d::central_moments3d(exact);
  LD growth = 1;
  for (int step = 0; step < 10000; ++step) {
    const Vector3d r = 0.01 * random_unit(rng);
    d::Vector12 D = d::Vector12::Zero();
    D.segment<3>(3) = r;
    exact = d::moved_parts(exact, d::step_map(d::central_moments3d(exact).centroid, D));
    d::StepMap linear;
    linear.centroid = d::central_moments3d(first_order).centroid;
    linear.gradient = skew(r);
    first_order = d::moved_parts(first_order, linear);
    growth *= 1 + static_cast<LD>(r.squaredNorm());
  }
  const d::CentralMoments3d end = d::central_moments3d(exact);
  const double volume_change = end.volume / start.volume - 1;
  const double drift = (end.centroid - start.centroid).norm();
  const double first_order_ratio = d::central_moments3d(first_order).volume / start.volume;
  BOOST_TEST_MESSAGE("10^4 steps of 0.01 rad: exact rotation, volume changed by "
                     << volume_change << " (relative), centroid moved " << drift
                     << " m; first-order map I + [r]x, volume x" << first_order_ratio);
  BOOST_TEST(std::fabs(volume_change) <= 1e-12);
  BOOST_TEST(drift <= 1e-12);
  BOOST_TEST(std::fabs(first_order_ratio / static_cast<double>(growth) - 1) <= 1e-10);
}

// rotation_vector inverts rotation_matrix at angles where a naive log map loses digits: 0,
// underflowing, tiny, moderate, just below π and at π (where r and -r are the same rotation).
// Tolerance: R carries a few u per entry, and the log map is well conditioned on both branches
// (θ / sin θ <= π/2 · √2 where the skew part is used, 1 - cos θ >= 1 where the symmetric part
// is): 8 u of max(|r|, 1) absolute, and 8 u relative for |r| < 1e-3.
BOOST_AUTO_TEST_CASE(rotation_vector_inverts_rodrigues) {
  std::mt19937_64 rng(61);
  const double pi = std::numbers::pi;
  for (const double angle :
       {0.0, 1e-300, 1e-12, 1e-6, 0.3, 1.0, 2.0, 3.0, pi - 1e-6, pi - 1e-12, pi}) {
    for (int k = 0; k < 20; ++k) {
      const Vector3d r = angle * random_unit(rng);
      const Vector3d back = d::rotation_vector(d::rotation_matrix(r));
      const double err =
          angle == pi ? std::min((back - r).norm(), (back + r).norm()) : (back - r).norm();
      const double scale = angle < 1e-3 ? angle : std::max(angle, 1.0);
      BOOST_TEST_CONTEXT("angle " << angle << " axis " << r.transpose()) {
        BOOST_TEST(err <= 8 * u * scale);
      }
    }
  }
  // By hand: R_y(π/2) R_x(π/2) maps x -> -z, y -> x, z -> -y, a turn of 2π/3 about (1, 1, -1)/√3.
  const Matrix3d P =
      d::rotation_matrix(Vector3d(0, pi / 2, 0)) * d::rotation_matrix(Vector3d(pi / 2, 0, 0));
  Matrix3d hand;
  hand << 0, 1, 0, 0, 0, -1, -1, 0, 0;
  BOOST_TEST((P - hand).cwiseAbs().maxCoeff() <= 4 * u);
  const Vector3d expected = 2 * pi / 3 / std::sqrt(3.0) * Vector3d(1, 1, -1);
  BOOST_TEST((d::rotation_vector(P) - expected).norm() <= 8 * u * 2.1);
}

// n steps of r = 0.01 a about one axis a: the accumulated rotation vector is n·0.01 a reduced
// into [-π, π] along a (it never comes within 3e-3 rad of ±π, where the sign would be a coin
// flip, since n·0.01 steps in 0.01 past the odd multiples of π). Tolerance: each composition
// rounds the total's entries (of size <= 1) by about u, turning it by at most ~u, and |r| =
// 0.01 (1 + δ) adds 0.01 u per step: after n steps the angle is off by at most ~n u (1e-12 at
// n = 10^4; measured: under 0.1 n u). The total stays orthogonal to rounding (the Newton–Schulz
// step): |QᵀQ - I| <= 8 u, where the plain product would drift by ~u per step.
BOOST_AUTO_TEST_CASE(accumulated_rotation_about_a_fixed_axis) {
  std::mt19937_64 rng(71);
  const Vector3d a = random_unit(rng);
  const Vector3d r = 0.01 * a;
  Matrix3d total = Matrix3d::Identity();
  double worst = 0.0;
  for (int n = 1; n <= 10000; ++n) {
    total = d::accumulate_rotation(total, r);
    const double phi = static_cast<double>(0.01L * n);
    const double wrapped = phi - 2 * std::numbers::pi * std::round(phi / (2 * std::numbers::pi));
    const double err = (d::rotation_vector(total) - wrapped * a).norm();
    worst = std::max(worst, err / (n * u));
  }
  BOOST_TEST_MESSAGE("fixed axis, 10^4 steps of 0.01 rad: worst error of the rotation vector "
                     << worst << " n u after n steps");
  BOOST_TEST(worst <= 1.0);
  const double orthogonality =
      (total.transpose() * total - Matrix3d::Identity()).cwiseAbs().maxCoeff();
  BOOST_TEST_MESSAGE("|Q^T Q - I| after 10^4 compositions: " << orthogonality / u << " u");
  BOOST_TEST(orthogonality <= 8 * u);
}

// Composition about different axes: 200 random turns of up to 1 rad, accumulated, against the
// plain product of their Rodrigues matrices in long double. Tolerance: each factor carries a few
// u, the product of n of them n times that: 8 n u.
BOOST_AUTO_TEST_CASE(composition_matches_product_of_rodrigues_matrices) {
  std::mt19937_64 rng(81);
  std::uniform_real_distribution<double> angle(0.0, 1.0);
  Matrix3d total = Matrix3d::Identity();
  Eigen::Matrix<LD, 3, 3> product = Eigen::Matrix<LD, 3, 3>::Identity();
  const int n = 200;
  for (int k = 0; k < n; ++k) {
    const Vector3d r = angle(rng) * random_unit(rng);
    total = d::accumulate_rotation(total, r);
    product = d::rotation_matrix(r).cast<LD>() * product;
  }
  const Matrix3d back = d::rotation_matrix(d::rotation_vector(total));
  BOOST_TEST((back.cast<LD>() - product).cwiseAbs().maxCoeff() <= 8 * n * u);
}
