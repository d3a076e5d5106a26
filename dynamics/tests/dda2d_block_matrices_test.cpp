#define BOOST_TEST_MODULE dynamics_dda2d_block_matrices
#include <boost/test/unit_test.hpp>

// Per-block matrices of the 2D DDA engine (dynamics/dda2d/src/block_matrices.hpp) against closed
// forms and independent quadrature.

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "../dda2d/src/block_matrices.hpp"

namespace {

using namespace rockcontact::dynamics;
namespace d = rockcontact::dynamics::detail;

std::vector<Point2> rectangle(double x0, double y0, double a, double b) {
  return {{x0, y0}, {x0 + a, y0}, {x0 + a, y0 + b}, {x0, y0 + b}};
}

double max_abs(const Eigen::Matrix4d& m) { return m.cwiseAbs().maxCoeff(); }

// The six columns of T (eq. 3) at offset (x, y) from the centroid.
std::array<Eigen::Vector2d, 6> columns(double x, double y) {
  return {Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1), Eigen::Vector2d(-y, x),
          Eigen::Vector2d(x, 0), Eigen::Vector2d(0, y), Eigen::Vector2d(y / 2, x / 2)};
}

}  // namespace

// An a x b rectangle: I_xx = a³ b / 12, I_yy = a b³ / 12, I_xy = 0, so with m = rho a b the
// (r0, ex, ey, gxy) block is m [[(a²+b²)/12, 0, 0, (a²-b²)/24], [0, a²/12, 0, 0],
// [0, 0, b²/12, 0], [(a²-b²)/24, 0, 0, (a²+b²)/48]]. Tolerance: a handful of roundings.
BOOST_AUTO_TEST_CASE(rectangle_mass_matrix_in_closed_form) {
  const double a = 2.0, b = 0.5, m = 2000.0 * a * b;
  std::vector<Point2> scratch;
  const d::CentralMoments mom = d::central_moments(rectangle(3.0, -1.0, a, b), scratch);
  BOOST_TEST(std::fabs(mom.area - a * b) <= 1e-15);
  BOOST_TEST(std::fabs(mom.centroid.x - 4.0) <= 1e-15);
  BOOST_TEST(std::fabs(mom.centroid.y + 0.75) <= 1e-15);
  Eigen::Matrix4d expected;
  expected << (a * a + b * b) / 12, 0, 0, (a * a - b * b) / 24,  //
      0, a * a / 12, 0, 0,                                        //
      0, 0, b * b / 12, 0,                                        //
      (a * a - b * b) / 24, 0, 0, (a * a + b * b) / 48;
  expected *= m;
  const Eigen::Matrix4d M = d::rotation_strain_mass(mom, m);
  BOOST_TEST(max_abs(M - expected) <= 1e-12 * max_abs(expected));
  BOOST_TEST(std::fabs(d::rotational_inertia(mom, m) - m * (a * a + b * b) / 12) <= 1e-12 * m);
}

// A scalene triangle against quadrature: the edge-midpoint rule ∫ f dA = S/3 Σ f(midpoints)
// is exact for quadratics, and every entry c_i . c_j of T^T T is quadratic. Also far from the
// origin (1e6 m): coordinates there carry 1e6 * 2^-53 ~ 1e-10 m of rounding, i.e. ~1e-10 of a
// 1 m block, so 1e-8 bounds the change.
BOOST_AUTO_TEST_CASE(triangle_mass_matrix_matches_quadrature) {
  for (const double far : {0.0, 1.0e6}) {
    const std::vector<Point2> tri{{far + 0.1, 0.2}, {far + 1.7, -0.3}, {far + 0.6, 1.3}};
    std::vector<Point2> scratch;
    const d::CentralMoments mom = d::central_moments(tri, scratch);
    const double m = 2000.0 * mom.area;
    Eigen::Matrix<double, 6, 6> quadrature = Eigen::Matrix<double, 6, 6>::Zero();
    for (std::size_t k = 0; k < 3; ++k) {
      const Point2& p = tri[k];
      const Point2& q = tri[(k + 1) % 3];
      const auto c = columns(0.5 * (p.x + q.x) - mom.centroid.x, 0.5 * (p.y + q.y) - mom.centroid.y);
      for (int i = 0; i < 6; ++i) {
        for (int j = 0; j < 6; ++j) quadrature(i, j) += 2000.0 * mom.area / 3.0 * c[i].dot(c[j]);
      }
    }
    BOOST_TEST_CONTEXT("offset " << far) {
      // Translation block m I, decoupled from the rest (first moments vanish about the centroid).
      BOOST_TEST(std::fabs(quadrature(0, 0) - m) <= 1e-8 * m);
      const double coupling = quadrature.block<2, 4>(0, 2).cwiseAbs().maxCoeff();
      BOOST_TEST(coupling <= 1e-8 * m);
      const Eigen::Matrix4d M = d::rotation_strain_mass(mom, m);
      const Eigen::Matrix4d Q = quadrature.block<4, 4>(2, 2);
      BOOST_TEST(max_abs(M - Q) <= 1e-8 * max_abs(Q));
    }
  }
}

// Plane stress, uniaxial: strain (1, -nu, 0) carries stress (E, 0, 0). Plane strain: strain
// (1, 0, 0) gives sigma_y / sigma_x = nu / (1 - nu) and sigma_x = E (1-nu) / ((1+nu)(1-2nu)).
// Shear modulus E / (2 (1 + nu)) in both.
BOOST_AUTO_TEST_CASE(elasticity_matrices) {
  Material mat;
  mat.youngs_modulus = 3.0e9;
  mat.poisson_ratio = 0.3;
  const double E = mat.youngs_modulus, nu = mat.poisson_ratio, G = E / (2 * (1 + nu));
  const Eigen::Matrix3d Ds = d::elasticity_matrix(mat, PlaneMode::stress);
  const Eigen::Vector3d uniaxial = Ds * Eigen::Vector3d(1.0, -nu, 0.0);
  BOOST_TEST(std::fabs(uniaxial(0) - E) <= 1e-12 * E);
  BOOST_TEST(std::fabs(uniaxial(1)) <= 1e-12 * E);
  BOOST_TEST(std::fabs(Ds(2, 2) - G) <= 1e-12 * E);
  const Eigen::Matrix3d De = d::elasticity_matrix(mat, PlaneMode::strain);
  const Eigen::Vector3d confined = De * Eigen::Vector3d(1.0, 0.0, 0.0);
  BOOST_TEST(std::fabs(confined(0) - E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))) <= 1e-12 * E);
  BOOST_TEST(std::fabs(confined(1) / confined(0) - nu / (1 - nu)) <= 1e-12);
  BOOST_TEST(std::fabs(De(2, 2) - G) <= 1e-12 * E);
}

// (T^T f) . d = f . (T d) for the rows of eq. 3, on random offsets, forces and DOFs.
BOOST_AUTO_TEST_CASE(transform_transpose_is_the_adjoint_of_T) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    const Vector2 r{u(rng), u(rng)}, f{u(rng), u(rng)};
    const std::array<double, 6> dof{u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)};
    const d::Vector6 g = d::transform_transpose(r, f);
    double lhs = 0.0;
    for (std::size_t i = 0; i < 6; ++i) lhs += g[i] * dof[i];
    const double tx = dof[0] - r.y * dof[2] + r.x * dof[3] + r.y / 2 * dof[5];
    const double ty = dof[1] + r.x * dof[2] + r.y * dof[4] + r.x / 2 * dof[5];
    BOOST_TEST(std::fabs(lhs - (f.x * tx + f.y * ty)) <= 1e-14);
  }
}

// Unit square, m = 2000: at a corner (x = y = 1/2) a force along x accelerates the point by
// (1 + 6y² + 12x² + 6y²)/m = 7/m with the strain DOFs (the (r0, ex, ey, gxy) block is
// m diag(1/6, 1/12, 1/12, 1/24)), by (1 + r²/(1/6))/m = 4/m for a rigid block; by symmetry the
// diagonal direction gives the same largest eigenvalue.
BOOST_AUTO_TEST_CASE(corner_compliance_of_a_square) {
  const auto sq = rectangle(-0.5, -0.5, 1.0, 1.0);
  std::vector<Point2> scratch;
  const d::CentralMoments mom = d::central_moments(sq, scratch);
  BOOST_TEST(std::fabs(d::max_vertex_compliance(sq, mom, 2000.0, false) * 2000.0 - 7.0) <= 1e-12);
  BOOST_TEST(std::fabs(d::max_vertex_compliance(sq, mom, 2000.0, true) * 2000.0 - 4.0) <= 1e-12);
}

BOOST_AUTO_TEST_CASE(perimeter_of_a_rectangle) {
  BOOST_TEST(std::fabs(d::perimeter(rectangle(5, 5, 2, 1)) - 6.0) <= 1e-15);
}
