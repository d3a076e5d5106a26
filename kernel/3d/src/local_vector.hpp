#pragma once
// Vectors of the FT-generic 3D constructions (distance, penetration, contact set), in a local
// frame: a pair is translated by one of its input points before anything is constructed, so
// that pairs far from the origin (the test data sit at +-2^20 m) keep the precision of their
// size rather than of their position. Under double the translation rounds each coordinate once
// (relative error 2^-53 of the local coordinate); under Exact (FT = ExactRational) it is exact.
// Private to kernel/3d/src.

#include <vector>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/detail/number_ops.hpp"

namespace rockcontact::kernel::detail {

template <class FT>
struct Vector3 {
  FT x, y, z;
};

template <class FT>
Vector3<FT> operator+(const Vector3<FT>& u, const Vector3<FT>& v) {
  return {u.x + v.x, u.y + v.y, u.z + v.z};
}
template <class FT>
Vector3<FT> operator-(const Vector3<FT>& u, const Vector3<FT>& v) {
  return {u.x - v.x, u.y - v.y, u.z - v.z};
}
template <class FT>
Vector3<FT> operator-(const Vector3<FT>& u) {
  return {-u.x, -u.y, -u.z};
}
template <class FT>
Vector3<FT> operator*(const FT& s, const Vector3<FT>& u) {
  return {s * u.x, s * u.y, s * u.z};
}
template <class FT>
FT dot(const Vector3<FT>& u, const Vector3<FT>& v) {
  return u.x * v.x + u.y * v.y + u.z * v.z;
}
template <class FT>
Vector3<FT> cross(const Vector3<FT>& u, const Vector3<FT>& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}
template <class FT>
bool is_zero(const Vector3<FT>& u) {
  return u.x == 0 && u.y == 0 && u.z == 0;
}

// p - origin in FT.
template <class FT>
Vector3<FT> local(const Point3& p, const Point3& origin) {
  using Ops = NumberOps<FT>;
  return {Ops::from(p.x) - Ops::from(origin.x), Ops::from(p.y) - Ops::from(origin.y),
          Ops::from(p.z) - Ops::from(origin.z)};
}

// origin + u, rounded once per coordinate.
template <class FT>
Point3 global(const Vector3<FT>& u, const Point3& origin) {
  using Ops = NumberOps<FT>;
  return {Ops::to_double(u.x + Ops::from(origin.x)), Ops::to_double(u.y + Ops::from(origin.y)),
          Ops::to_double(u.z + Ops::from(origin.z))};
}

// The vertices of p in the frame at `origin`.
template <class FT>
std::vector<Vector3<FT>> local_vertices(const ConvexPolyhedron& p, const Point3& origin) {
  std::vector<Vector3<FT>> out;
  out.reserve(p.size());
  for (const Point3& v : p.vertices()) out.push_back(local<FT>(v, origin));
  return out;
}

}  // namespace rockcontact::kernel::detail
