#include "block_matrices3d.hpp"

#include <cassert>
#include <cmath>
#include <cstddef>

#include <Eigen/Geometry>

#include "rockcontact/kernel/3d/moments.hpp"

namespace rockcontact::dynamics::detail {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d skew(const Vector3d& r) {
  Matrix3d k;
  k << 0.0, -r.z(), r.y(),  //
      r.z(), 0.0, -r.x(),   //
      -r.y(), r.x(), 0.0;
  return k;
}

// R(r) - I = (sin θ / θ) K + ((1 - cos θ) / θ²) K², K = [r]x, without forming I: the second
// coefficient as ½ (sin(θ/2) / (θ/2))², free of the cancellation in 1 - cos θ; both
// coefficients tend to their limits 1 and ½ as θ -> 0 (also when |r|² underflows to θ = 0).
Matrix3d rotation_minus_identity(const Vector3d& r) {
  const double theta = r.norm();
  const double half = theta / 2;
  const double sinc = theta == 0.0 ? 1.0 : std::sin(theta) / theta;
  const double sinc_half = half == 0.0 ? 1.0 : std::sin(half) / half;
  const Matrix3d k = skew(r);
  return sinc * k + (0.5 * sinc_half * sinc_half) * (k * k);
}

}  // namespace

CentralMoments3d central_moments3d(std::span<const kernel::ConvexPolyhedron> parts) {
  assert(!parts.empty());
  const kernel::Point3 o = parts.front()[0];
  double volume = 0.0;
  Vector3d first = Vector3d::Zero();
  Matrix3d second = Matrix3d::Zero();
  for (const kernel::ConvexPolyhedron& part : parts) {
    const kernel::Moments3 m = kernel::moments_about(part, o);
    volume += m.volume;
    first += Vector3d(m.first.x, m.first.y, m.first.z);
    Matrix3d s;
    s << m.xx, m.xy, m.zx,  //
        m.xy, m.yy, m.yz,   //
        m.zx, m.yz, m.zz;
    second += s;
  }
  CentralMoments3d out;
  out.volume = volume;
  out.centroid = Vector3d(o.x, o.y, o.z) + first / volume;
  out.second = second - first * first.transpose() / volume;
  return out;
}

Matrix12 mass_matrix(const CentralMoments3d& m, double mass) {
  assert(m.volume > 0.0 && mass > 0.0);
  const Matrix3d& S = m.second;
  const double xx = S(0, 0), yy = S(1, 1), zz = S(2, 2);
  const double xy = S(0, 1), yz = S(1, 2), zx = S(2, 0);
  Matrix12 M = Matrix12::Zero();
  M.topLeftCorner<3, 3>() = m.volume * Matrix3d::Identity();
  Eigen::Matrix<double, 9, 9> r;
  // rx, ry, rz, ex, ey, ez, gyz, gzx, gxy (header table; upper triangle, mirrored below).
  r << yy + zz, -xy, -zx, 0, -yz, yz, (yy - zz) / 2, xy / 2, -zx / 2,  //
      0, zz + xx, -yz, zx, 0, -zx, -xy / 2, (zz - xx) / 2, yz / 2,     //
      0, 0, xx + yy, -xy, xy, 0, zx / 2, -yz / 2, (xx - yy) / 2,       //
      0, 0, 0, xx, 0, 0, 0, zx / 2, xy / 2,                            //
      0, 0, 0, 0, yy, 0, yz / 2, 0, xy / 2,                            //
      0, 0, 0, 0, 0, zz, yz / 2, zx / 2, 0,                            //
      0, 0, 0, 0, 0, 0, (yy + zz) / 4, xy / 4, zx / 4,                 //
      0, 0, 0, 0, 0, 0, 0, (zz + xx) / 4, yz / 4,                      //
      0, 0, 0, 0, 0, 0, 0, 0, (xx + yy) / 4;
  M.bottomRightCorner<9, 9>() = r.selfadjointView<Eigen::Upper>();
  return mass / m.volume * M;
}

Matrix6 elasticity_matrix3d(double youngs_modulus, double poisson_ratio) {
  const double E = youngs_modulus, nu = poisson_ratio;
  assert(E > 0.0 && nu > -1.0 && nu < 0.5);
  const double lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = E / (2.0 * (1.0 + nu));
  Matrix6 C = Matrix6::Zero();
  C.topLeftCorner<3, 3>().setConstant(lambda);
  C.topLeftCorner<3, 3>().diagonal().array() += 2.0 * mu;
  C.bottomRightCorner<3, 3>().diagonal().setConstant(mu);
  return C;
}

Matrix12 elastic_stiffness(const Matrix6& elasticity, double volume) {
  Matrix12 K = Matrix12::Zero();
  K.bottomRightCorner<6, 6>() = volume * elasticity;
  return K;
}

Vector12 gravity_load(double mass, const Eigen::Vector3d& g) {
  Vector12 f = Vector12::Zero();
  f.head<3>() = mass * g;
  return f;
}

Eigen::Matrix3d rotation_matrix(const Eigen::Vector3d& r) {
  return Matrix3d::Identity() + rotation_minus_identity(r);
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& rotation) {
  const Matrix3d& R = rotation;
  const Vector3d v = 0.5 * Vector3d(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const double cos_theta = 0.5 * (R.trace() - 1.0);
  const double sin_theta = v.norm();
  const double theta = std::atan2(sin_theta, cos_theta);
  if (cos_theta >= 0.0) {
    // θ / sin θ -> 1 as θ -> 0; sin θ = 0 here only for R = I to rounding.
    return sin_theta == 0.0 ? Vector3d::Zero() : Vector3d((theta / sin_theta) * v);
  }
  const Matrix3d B = 0.5 * (R + R.transpose()) - cos_theta * Matrix3d::Identity();
  Eigen::Index k = 0;
  B.diagonal().maxCoeff(&k);
  Vector3d axis = B.col(k).normalized();
  if (axis.dot(v) < 0.0) axis = -axis;
  return theta * axis;
}

Eigen::Matrix3d accumulate_rotation(const Eigen::Matrix3d& total, const Eigen::Vector3d& r) {
  const Matrix3d q = rotation_matrix(r) * total;
  return 0.5 * q * (3.0 * Matrix3d::Identity() - q.transpose() * q);
}

StepMap step_map(const Eigen::Vector3d& centroid, const Eigen::Ref<const Eigen::VectorXd>& d) {
  assert(d.size() == rigid_dof3d || d.size() == dof3d);
  StepMap map;
  map.centroid = centroid;
  map.translation = d.head<3>();
  const Matrix3d rotation_increment = rotation_minus_identity(d.segment<3>(3));
  map.gradient = rotation_increment;
  if (d.size() == dof3d) {
    const double ex = d(6), ey = d(7), ez = d(8), gyz = d(9), gzx = d(10), gxy = d(11);
    Matrix3d strain;
    strain << ex, gxy / 2, gzx / 2,  //
        gxy / 2, ey, gyz / 2,        //
        gzx / 2, gyz / 2, ez;
    // R (I + ε) - I = (R - I) + R ε.
    map.gradient += (Matrix3d::Identity() + rotation_increment) * strain;
  }
  return map;
}

kernel::Point3 apply(const StepMap& map, const kernel::Point3& x) {
  const Vector3d u =
      map.translation + map.gradient * Vector3d(x.x - map.centroid.x(), x.y - map.centroid.y(),
                                                x.z - map.centroid.z());
  return {x.x + u.x(), x.y + u.y(), x.z + u.z()};
}

std::vector<kernel::ConvexPolyhedron> moved_parts(std::span<const kernel::ConvexPolyhedron> parts,
                                                  const StepMap& map) {
  std::vector<kernel::ConvexPolyhedron> out;
  out.reserve(parts.size());
  std::vector<kernel::Point3> vertices;
  for (const kernel::ConvexPolyhedron& part : parts) {
    vertices.assign(part.vertices().begin(), part.vertices().end());
    for (kernel::Point3& p : vertices) p = apply(map, p);
    out.push_back(part.moved(vertices));
  }
  return out;
}

}  // namespace rockcontact::dynamics::detail
