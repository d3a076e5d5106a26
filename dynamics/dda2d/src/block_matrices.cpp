#include "block_matrices.hpp"

#include <algorithm>
#include <cmath>

#include "rockcontact/kernel/2d/moments.hpp"

namespace rockcontact::dynamics::detail {

CentralMoments central_moments(std::span<const Point2> vertices, std::vector<Point2>& scratch) {
  const Point2 o = vertices[0];
  scratch.clear();
  for (const Point2& p : vertices) scratch.push_back({p.x - o.x, p.y - o.y});
  const kernel::PolygonMoments local = kernel::compute_moments(scratch);
  CentralMoments m;
  m.area = local.S;
  const double cx = local.Sx / local.S, cy = local.Sy / local.S;
  m.centroid = {o.x + cx, o.y + cy};
  // Parallel-axis shift from the first vertex to the centroid (distances of block size, so the
  // subtraction loses at most a few digits of a few).
  m.ixx = local.Sxx - cx * local.Sx;
  m.iyy = local.Syy - cy * local.Sy;
  m.ixy = local.Sxy - cx * local.Sy;
  return m;
}

Eigen::Matrix4d rotation_strain_mass(const CentralMoments& m, double mass) {
  const double rho = mass / m.area;
  const double polar = m.ixx + m.iyy;
  const double half_diff = 0.5 * (m.ixx - m.iyy);
  const double half_xy = 0.5 * m.ixy;
  Eigen::Matrix4d M;
  M << polar, -m.ixy, m.ixy, half_diff,  //
      -m.ixy, m.ixx, 0.0, half_xy,       //
      m.ixy, 0.0, m.iyy, half_xy,        //
      half_diff, half_xy, half_xy, 0.25 * polar;
  return rho * M;
}

double rotational_inertia(const CentralMoments& m, double mass) {
  return mass / m.area * (m.ixx + m.iyy);
}

Eigen::Matrix3d elasticity_matrix(const Material& material, PlaneMode plane) {
  const double E = material.youngs_modulus, nu = material.poisson_ratio;
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
  if (plane == PlaneMode::stress) {
    const double c = E / (1.0 - nu * nu);
    D(0, 0) = D(1, 1) = c;
    D(0, 1) = D(1, 0) = c * nu;
    D(2, 2) = c * (1.0 - nu) / 2.0;
  } else {
    const double c = E / ((1.0 + nu) * (1.0 - 2.0 * nu));
    D(0, 0) = D(1, 1) = c * (1.0 - nu);
    D(0, 1) = D(1, 0) = c * nu;
    D(2, 2) = c * (1.0 - 2.0 * nu) / 2.0;
  }
  return D;
}

Vector6 transform_transpose(Vector2 r, Vector2 f) {
  return {f.x, f.y, r.x * f.y - r.y * f.x, r.x * f.x, r.y * f.y, 0.5 * (r.y * f.x + r.x * f.y)};
}

Vector2 transform(Vector2 r, const Vector6& d) {
  return {d[0] - r.y * d[2] + r.x * d[3] + 0.5 * r.y * d[5],
          d[1] + r.x * d[2] + r.y * d[4] + 0.5 * r.x * d[5]};
}

namespace {

// Rows of T restricted to (r0, ex, ey, gxy) at offset r.
Eigen::Matrix<double, 2, 4> rotation_strain_rows(Vector2 r) {
  Eigen::Matrix<double, 2, 4> t;
  t << -r.y, r.x, 0.0, 0.5 * r.y,  //
      r.x, 0.0, r.y, 0.5 * r.x;
  return t;
}

}  // namespace

double max_vertex_compliance(std::span<const Point2> vertices, const CentralMoments& m,
                             double mass, bool rigid) {
  const Eigen::Matrix4d M = rotation_strain_mass(m, mass);
  const Eigen::LLT<Eigen::Matrix4d> llt(M);
  const double inertia = rotational_inertia(m, mass);
  double worst = 0.0;
  for (const Point2& p : vertices) {
    const Vector2 r{p.x - m.centroid.x, p.y - m.centroid.y};
    Eigen::Matrix2d c = Eigen::Matrix2d::Identity() / mass;
    if (rigid) {
      const Eigen::Vector2d arm(-r.y, r.x);
      c += arm * arm.transpose() / inertia;
    } else {
      const Eigen::Matrix<double, 2, 4> t = rotation_strain_rows(r);
      c += t * llt.solve(t.transpose());
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(c, Eigen::EigenvaluesOnly);
    worst = std::max(worst, eig.eigenvalues()(1));
  }
  return worst;
}

double elastic_omega_squared(const CentralMoments& m, double mass, const Eigen::Matrix3d& elasticity) {
  Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
  K.bottomRightCorner<3, 3>() = m.area * elasticity;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix4d> eig(
      K, rotation_strain_mass(m, mass), Eigen::EigenvaluesOnly);
  return eig.eigenvalues().maxCoeff();
}

double perimeter(std::span<const Point2> vertices) {
  double sum = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Point2& p = vertices[i];
    const Point2& q = vertices[i + 1 == vertices.size() ? 0 : i + 1];
    sum += std::hypot(q.x - p.x, q.y - p.y);
  }
  return sum;
}

}  // namespace rockcontact::dynamics::detail
