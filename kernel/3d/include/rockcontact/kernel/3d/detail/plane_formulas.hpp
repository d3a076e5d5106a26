#pragma once
// The plane formulas, written once and generic over the number type T (double for the Float
// face and the double constructions, CGAL::Interval_nt_advanced and CGAL::Mpzf for the staged
// predicates, CGAL::Exact_rational for the Exact constructions). They use + - * only, so Mpzf
// evaluates them exactly.
//
// A plane in a local frame with origin o: n . (x - o) = d, with
//   through p0, p1, p2:   n = (p1 - p0) x (p2 - p0)          degree 2 in the input doubles
//                         d = n . (p0 - o)                   degree 3
//   a x + b y + c z = e:  n = (a, b, c)                      degree 1
//                         d = e - n . o                      degree 2
// The frame changes no sign (every formula below is the same polynomial of the point's
// coordinates in any frame); it keeps the interval enclosures tight for a pair far from the
// origin (the contact3d pairs sit at +-2^20 m).

#include "rockcontact/kernel/3d/plane.hpp"
#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::kernel::detail {

template <class T>
struct Vector3T {
  T x, y, z;
};

template <class T>
Vector3T<T> cross(const Vector3T<T>& u, const Vector3T<T>& v) {
  return {T(u.y * v.z) - T(u.z * v.y), T(u.z * v.x) - T(u.x * v.z), T(u.x * v.y) - T(u.y * v.x)};
}

template <class T>
T dot(const Vector3T<T>& u, const Vector3T<T>& v) {
  return T(T(u.x * v.x) + T(u.y * v.y)) + T(u.z * v.z);
}

template <class T>
Vector3T<T> difference3(const Point3& p, const Point3& q) {  // p - q
  return {T(p.x) - T(q.x), T(p.y) - T(q.y), T(p.z) - T(q.z)};
}

// n . (x - o) = d, the plane in the frame of o.
template <class T>
struct PlaneCoefficients {
  Vector3T<T> n;
  T d;
};

template <class T>
PlaneCoefficients<T> plane_coefficients(const Plane3& plane, const Point3& o) {
  if (plane.kind == Plane3::Kind::through_points) {
    const auto& [p0, p1, p2] = plane.points;
    const Vector3T<T> n = cross(difference3<T>(p1, p0), difference3<T>(p2, p0));
    return {n, dot(n, difference3<T>(p0, o))};
  }
  const auto& [a, b, c, e] = plane.coefficients;
  const Vector3T<T> n{T(a), T(b), T(c)};
  return {n, T(e) - dot(n, Vector3T<T>{T(o.x), T(o.y), T(o.z)})};
}

// The meeting point X of planes p, q, r in the frame of o, by Cramer's rule:
//   det * X = d_p (n_q x n_r) + d_q (n_r x n_p) + d_r (n_p x n_q),  det = n_p . (n_q x n_r),
// the two returned separately (det != 0 exactly when the three normals are independent).
template <class T>
struct HomogeneousPoint {
  Vector3T<T> scaled;  // det * X
  T det;
};

template <class T>
HomogeneousPoint<T> three_plane_point(const PlaneCoefficients<T>& p, const PlaneCoefficients<T>& q,
                                      const PlaneCoefficients<T>& r) {
  const Vector3T<T> qr = cross(q.n, r.n), rp = cross(r.n, p.n), pq = cross(p.n, q.n);
  const Vector3T<T> scaled{T(T(p.d * qr.x) + T(q.d * rp.x)) + T(r.d * pq.x),
                           T(T(p.d * qr.y) + T(q.d * rp.y)) + T(r.d * pq.y),
                           T(T(p.d * qr.z) + T(q.d * rp.z)) + T(r.d * pq.z)};
  return {scaled, dot(p.n, qr)};
}

// The side of plane s at the meeting point of p, q, r: n_s . X - d_s has the sign of
//   (n_s . (det X) - d_s det) * det,
// the 4x4 determinant of the four planes' rows (n, -d) times the 3x3 determinant of the three
// normals. For planes through input points its degree is 15 in the input doubles (3 + 6 + 6).
template <class T>
T three_plane_side_of_coefficients(const PlaneCoefficients<T>& s, const PlaneCoefficients<T>& p,
                                   const PlaneCoefficients<T>& q, const PlaneCoefficients<T>& r) {
  const HomogeneousPoint<T> x = three_plane_point(p, q, r);
  const T value = dot(s.n, x.scaled) - T(s.d * x.det);
  return T(value * x.det);
}

template <class T>
T three_plane_side_formula(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r,
                           const Point3& o) {
  return three_plane_side_of_coefficients(plane_coefficients<T>(s, o), plane_coefficients<T>(p, o),
                                          plane_coefficients<T>(q, o), plane_coefficients<T>(r, o));
}

// The side of the plane a x + b y + c z = e at an input point x: a x + b y + c z - e, degree 2.
template <class T>
T coefficient_side_formula(const Plane3& plane, const Point3& x) {
  const auto& [a, b, c, e] = plane.coefficients;
  return T(T(T(T(a) * T(x.x)) + T(T(b) * T(x.y))) + T(T(c) * T(x.z))) - T(e);
}

}  // namespace rockcontact::kernel::detail
