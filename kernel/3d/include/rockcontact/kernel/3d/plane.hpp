#pragma once
// Plane3, a plane of the 3D kernel, and the two predicates on it.
//
// A plane is kept in the form that defines it exactly, never as rounded coefficients:
//   * through three input points p0, p1, p2 (a face plane of a ConvexPolyhedron: its first three
//     vertices, counter-clockwise from outside), outward normal (p1 - p0) x (p2 - p0);
//   * by double coefficients a x + b y + c z = d (a cutting or joint plane; the doubles are the
//     plane), normal (a, b, c).
// "Below" is the closed side opposite the normal (inside, for a face plane), "above" the side
// the normal points to. The coefficients of either form are a polynomial of the input doubles
// (detail/plane_formulas.hpp, generic over the number type).
//
// An implicit point is the meeting point of three planes with independent normals; it is never
// rounded to decide anything. The predicates:
//   side_of_plane(s, x)        the side of s at an input point x: orient3d(p0, p1, p2, x) for a
//                              plane through points (predicates.hpp), the sign of
//                              a x + b y + c z - d for a plane by coefficients;
//   side_of_plane(s, p, q, r)  the side of s at the meeting point of p, q, r: the sign of the
//                              4x4 determinant of the rows (n, -d) of s, p, q, r times the sign
//                              of the 3x3 determinant of the normals of p, q, r (Cramer's rule),
//                              a polynomial of degree up to 15 in the input doubles.
// Both are staged like every predicate (kernel/core/detail/staged_sign.hpp) under Filtered,
// Exact and Checked. side_of_plane(s, x) on coefficients has a static double filter (bound
// below); the three-plane side a semi-static one: the formula evaluated in double with a
// running error bound (detail/running_error.hpp), about three times the cost of the plain
// double evaluation, certain when the value exceeds its bound. Checked
// evaluates each sign exactly on its own too and throws PolicyDisagreement on a difference;
// Float evaluates the formulas in double.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel {

struct Plane3 {
  enum class Kind : std::uint8_t { through_points, coefficients };

  Kind kind = Kind::coefficients;
  std::array<Point3, 3> points{};        // Kind::through_points: p0, p1, p2
  std::array<double, 4> coefficients{};  // Kind::coefficients: a, b, c, d

  // Throws std::invalid_argument when the points are collinear (decided exactly) or not finite.
  static Plane3 through(const Point3& p0, const Point3& p1, const Point3& p2);
  // Throws std::invalid_argument when (a, b, c) = 0 or a coefficient is not finite.
  static Plane3 from_coefficients(double a, double b, double c, double d);
  // The plane of face `face` of p (valid by ConvexPolyhedron's validation), normal outward.
  static Plane3 of_face(const ConvexPolyhedron& p, std::size_t face);

  // The same plane with the opposite normal (below and above exchanged), exactly.
  Plane3 opposite() const;

  // The point the frame of the formulas is placed at: p0, or the origin for coefficients.
  Point3 reference() const { return kind == Kind::through_points ? points[0] : Point3{}; }

  friend bool operator==(const Plane3&, const Plane3&) = default;
};

namespace detail {

// Stages 2 and 3 and the Checked comparisons (3d/src/plane.cpp).
Sign coefficient_side_interval_exact(const Plane3& s, const Point3& x);
Sign coefficient_side_exact(const Plane3& s, const Point3& x);
double coefficient_side_naive(const Plane3& s, const Point3& x);
Sign three_plane_side_staged(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r);
Sign three_plane_side_interval_exact(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r);
Sign three_plane_side_exact(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r);
Sign three_plane_side_naive(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r);
[[noreturn]] void plane_side_disagrees(const Plane3* const* planes, int count, const Point3* x, Sign staged,
                                       Sign exact);

// Static filter of a x + b y + c z - d, for any IEEE rounding mode (eps = 2^-52 per
// operation). The computed value ((a x + b y) + c z) - d rounds each of its four terms at most
// four times (a product and three additions), so as long as no product underflows
//   |value - exact| <= ((1 + eps)^4 - 1) M <= (4 eps + 7 eps²) M,
// M = |a x| + |b y| + |c z| + |d| exact. The filter's magnitude M' sums the rounded products,
// M <= M' (1 + eps)^4, so 5 eps M' bounds the error with room for every second-order term; 6 eps
// is used. A non-zero product below 2^-960 (or rounded to zero from non-zero factors) makes the
// filter uncertain, as does an infinite bound.
inline constexpr double coefficient_side_error_factor = 6.0 * 0x1p-52;

inline std::optional<Sign> coefficient_side_static_filter(const Plane3& s, const Point3& x) {
  const auto& [a, b, c, d] = s.coefficients;
  const double ax = a * x.x, by = b * x.y, cz = c * x.z;
  const bool relative =
      product_is_relative(a, x.x, ax) && product_is_relative(b, x.y, by) && product_is_relative(c, x.z, cz);
  const double value = ((ax + by) + cz) - d;
  const double magnitude = ((std::fabs(ax) + std::fabs(by)) + std::fabs(cz)) + std::fabs(d);
  const double bound = coefficient_side_error_factor * magnitude;
  if (!relative || !std::isfinite(bound)) return std::nullopt;
  if (value > bound) return Sign::positive;
  if (-value > bound) return Sign::negative;
  if (magnitude == 0.0) return Sign::zero;
  return std::nullopt;
}

inline Sign coefficient_side_staged(const Plane3& s, const Point3& x) {
  count_call(PredicateKind::plane_side);
  if (const auto sign = coefficient_side_static_filter(s, x)) return *sign;
  return coefficient_side_interval_exact(s, x);
}

}  // namespace detail

// The side of plane s at input point x: positive above (the normal's side), zero on it.
template <NumberPolicy Policy>
Sign side_of_plane(const Plane3& s, const Point3& x) {
  if (s.kind == Plane3::Kind::through_points) return orient3d<Policy>(s.points[0], s.points[1], s.points[2], x);
  if constexpr (Policy::kind == PolicyKind::float_) {
    detail::count_call(PredicateKind::plane_side);
    return sign_of(detail::coefficient_side_naive(s, x));
  } else if constexpr (Policy::kind == PolicyKind::checked) {
    const Sign staged = detail::coefficient_side_staged(s, x);
    const Sign exact = detail::coefficient_side_exact(s, x);
    if (staged != exact) {
      const Plane3* planes[] = {&s};
      detail::plane_side_disagrees(planes, 1, &x, staged, exact);
    }
    return staged;
  } else {
    return detail::coefficient_side_staged(s, x);
  }
}

// The side of plane s at the meeting point of planes p, q, r, whose normals must be linearly
// independent (a precondition: the sign is then exact; with dependent normals it is zero).
template <NumberPolicy Policy>
Sign side_of_plane(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r) {
  if constexpr (Policy::kind == PolicyKind::float_) {
    detail::count_call(PredicateKind::plane_side);
    return detail::three_plane_side_naive(s, p, q, r);
  } else if constexpr (Policy::kind == PolicyKind::checked) {
    const Sign staged = detail::three_plane_side_staged(s, p, q, r);
    const Sign exact = detail::three_plane_side_exact(s, p, q, r);
    if (staged != exact) {
      const Plane3* planes[] = {&s, &p, &q, &r};
      detail::plane_side_disagrees(planes, 4, nullptr, staged, exact);
    }
    return staged;
  } else {
    return detail::three_plane_side_staged(s, p, q, r);
  }
}

}  // namespace rockcontact::kernel
