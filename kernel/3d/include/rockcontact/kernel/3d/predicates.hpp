#pragma once
// 3D geometric predicates under a number policy. Each returns a Sign.
//
//   triple_sign(p0, p1, q0, q1, r0, r1)  sign of ((p1 - p0) x (q1 - q0)) . (r1 - r0)
//   orient3d(a, b, c, d)                 sign of ((b - a) x (c - a)) . (d - a): negative when d
//                                        lies below the plane of a, b, c, i.e. on the side
//                                        opposite to the normal of the counter-clockwise
//                                        triangle a b c (inside, for a face seen from outside)
//
// Both read input coordinates only; a plane or an axis defined by input points (a face's
// normal, the cross product of two edges) stays implicit in the formula, as the 2D kernel keeps
// its derived points symbolic. Evaluated by the staged engine of kernel/core (double filter,
// CGAL::Interval_nt_advanced, CGAL::Mpzf), the same under Filtered, Exact and Checked; Float
// evaluates the formula in double; Checked also evaluates it exactly on its own and throws
// PolicyDisagreement when the two differ.

#include <cmath>
#include <optional>

#include "rockcontact/kernel/3d/detail/predicate_formulas.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel {
namespace detail {

// Stages 2 and 3 (3d/src/predicates_staged.cpp).
Sign triple_sign_interval_exact(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                                const Point3& r0, const Point3& r1);
Sign triple_sign_exact(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                       const Point3& r0, const Point3& r1);
[[noreturn]] void triple_sign_disagrees(const Point3& p0, const Point3& p1, const Point3& q0,
                                        const Point3& q1, const Point3& r0, const Point3& r1,
                                        Sign staged, Sign exact);

// Static filter of the triple product, for any IEEE rounding mode (eps = 2^-52 per operation,
// predicates.hpp of the 2D kernel). With u, v, w the rounded differences, each of the six terms
// of the computed value, such as fl(fl(fl(uy vz) - fl(uz vy)) wx), passes through at most eight
// roundings: three differences, two products, one difference, one product and the sum of three
// (two additions for the first terms). As long as no product underflows, every rounding is
// relative, so
//   |value - exact| <= ((1 + eps)^8 - 1) P_exact <= (8 eps + 29 eps²) P_exact,
// with P_exact = sum over the six terms of |a b c| on the exact differences. The filter computes
// the magnitude P = sum (|uy vz| + |uz vy|) |wx| + ... from the rounded differences, itself within
// a factor (1 - eps)^9 of P_exact, so 9 eps P bounds the error with room for every
// second-order term. Underflow: a product that is non-zero but below 2^-960 (or rounded to zero
// although both factors are non-zero) makes the filter answer `uncertain`; the interval stage
// decides it. tests/predicates_test.cpp re-derives the bound in GMP under round to nearest and
// upward rounding.
inline constexpr double triple_error_factor = 9.0 * 0x1p-52;
inline constexpr double triple_min_product = 0x1p-960;

inline bool product_is_relative(double a, double b, double product) {
  return a == 0.0 || b == 0.0 || std::fabs(product) >= triple_min_product;
}

inline std::optional<Sign> triple_sign_static_filter(const Point3& p0, const Point3& p1,
                                                     const Point3& q0, const Point3& q1,
                                                     const Point3& r0, const Point3& r1) {
  const double ux = p1.x - p0.x, uy = p1.y - p0.y, uz = p1.z - p0.z;
  const double vx = q1.x - q0.x, vy = q1.y - q0.y, vz = q1.z - q0.z;
  const double wx = r1.x - r0.x, wy = r1.y - r0.y, wz = r1.z - r0.z;
  const double a1 = uy * vz, a2 = uz * vy, b1 = uz * vx, b2 = ux * vz, c1 = ux * vy, c2 = uy * vx;
  const double nx = a1 - a2, ny = b1 - b2, nz = c1 - c2;
  const double tx = nx * wx, ty = ny * wy, tz = nz * wz;
  const bool relative = product_is_relative(uy, vz, a1) && product_is_relative(uz, vy, a2) &&
                        product_is_relative(uz, vx, b1) && product_is_relative(ux, vz, b2) &&
                        product_is_relative(ux, vy, c1) && product_is_relative(uy, vx, c2) &&
                        product_is_relative(nx, wx, tx) && product_is_relative(ny, wy, ty) &&
                        product_is_relative(nz, wz, tz);
  const double value = (tx + ty) + tz;
  const double magnitude = (std::fabs(a1) + std::fabs(a2)) * std::fabs(wx) +
                           (std::fabs(b1) + std::fabs(b2)) * std::fabs(wy) +
                           (std::fabs(c1) + std::fabs(c2)) * std::fabs(wz);
  const double bound = triple_error_factor * magnitude;
  if (!relative || !std::isfinite(bound)) return std::nullopt;
  if (value > bound) return Sign::positive;
  if (-value > bound) return Sign::negative;
  if (magnitude == 0.0) return Sign::zero;  // every term is exactly zero
  return std::nullopt;
}

inline Sign triple_sign_staged(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                               const Point3& r0, const Point3& r1) {
  count_call(PredicateKind::triple);
  if (const auto sign = triple_sign_static_filter(p0, p1, q0, q1, r0, r1)) return *sign;
  return triple_sign_interval_exact(p0, p1, q0, q1, r0, r1);
}

}  // namespace detail

template <NumberPolicy Policy>
Sign triple_sign(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                 const Point3& r0, const Point3& r1) {
  if constexpr (Policy::kind == PolicyKind::float_) {
    detail::count_call(PredicateKind::triple);
    return sign_of(detail::triple_formula<double>(p0, p1, q0, q1, r0, r1,
                                                  [](double a, double b) { return a - b; }));
  } else if constexpr (Policy::kind == PolicyKind::checked) {
    const Sign staged = detail::triple_sign_staged(p0, p1, q0, q1, r0, r1);
    const Sign exact = detail::triple_sign_exact(p0, p1, q0, q1, r0, r1);
    if (staged != exact) detail::triple_sign_disagrees(p0, p1, q0, q1, r0, r1, staged, exact);
    return staged;
  } else {
    return detail::triple_sign_staged(p0, p1, q0, q1, r0, r1);
  }
}

template <NumberPolicy Policy>
Sign orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return triple_sign<Policy>(a, b, a, c, a, d);
}

// triple_sign(p0, p1, q0, q1, r0, r1) for many (r0, r1) against one normal (p1 - p0) x (q1 - q0):
// a face plane against a block's vertices (orient3d(a, b, c, x) is TripleSigns(a, b, a, c)(a, x)),
// an edge-edge plane against them, a facet normal against another block's edges. The normal's
// products, its magnitudes and their underflow checks are computed once; each call evaluates
// only the terms in r1 - r0. The value, the filter's bound and so every sign and counter are
// those of triple_sign, bit for bit: the same operations in the same order. The points are
// referred to, not copied: they must outlive the object.
template <NumberPolicy Policy>
class TripleSigns {
 public:
  TripleSigns(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1)
      : p0_(p0), p1_(p1), q0_(q0), q1_(q1) {
    const double ux = p1.x - p0.x, uy = p1.y - p0.y, uz = p1.z - p0.z;
    const double vx = q1.x - q0.x, vy = q1.y - q0.y, vz = q1.z - q0.z;
    const double a1 = uy * vz, a2 = uz * vy, b1 = uz * vx, b2 = ux * vz, c1 = ux * vy, c2 = uy * vx;
    nx_ = a1 - a2;
    ny_ = b1 - b2;
    nz_ = c1 - c2;
    mx_ = std::fabs(a1) + std::fabs(a2);
    my_ = std::fabs(b1) + std::fabs(b2);
    mz_ = std::fabs(c1) + std::fabs(c2);
    using detail::product_is_relative;
    relative_ = product_is_relative(uy, vz, a1) && product_is_relative(uz, vy, a2) &&
                product_is_relative(uz, vx, b1) && product_is_relative(ux, vz, b2) &&
                product_is_relative(ux, vy, c1) && product_is_relative(uy, vx, c2);
  }

  // triple_sign<Policy>(p0, p1, q0, q1, r0, r1).
  Sign operator()(const Point3& r0, const Point3& r1) const {
    if constexpr (Policy::kind == PolicyKind::checked) {
      return triple_sign<Policy>(p0_, p1_, q0_, q1_, r0, r1);
    } else {
      detail::count_call(PredicateKind::triple);
      const double wx = r1.x - r0.x, wy = r1.y - r0.y, wz = r1.z - r0.z;
      const double tx = nx_ * wx, ty = ny_ * wy, tz = nz_ * wz;
      const double value = (tx + ty) + tz;
      if constexpr (Policy::kind == PolicyKind::float_) {
        return sign_of(value);
      } else {
        using detail::product_is_relative;
        const bool relative = relative_ && product_is_relative(nx_, wx, tx) && product_is_relative(ny_, wy, ty) &&
                              product_is_relative(nz_, wz, tz);
        const double magnitude = mx_ * std::fabs(wx) + my_ * std::fabs(wy) + mz_ * std::fabs(wz);
        const double bound = detail::triple_error_factor * magnitude;
        if (relative && std::isfinite(bound)) {
          if (value > bound) return Sign::positive;
          if (-value > bound) return Sign::negative;
          if (magnitude == 0.0) return Sign::zero;
        }
        return detail::triple_sign_interval_exact(p0_, p1_, q0_, q1_, r0, r1);
      }
    }
  }

 private:
  const Point3 &p0_, &p1_, &q0_, &q1_;
  double nx_, ny_, nz_;  // the computed normal
  double mx_, my_, mz_;  // |a1| + |a2| and so on: the magnitude's factors of |wx|, |wy|, |wz|
  bool relative_;        // no product of the normal underflowed
};

// Is (p1 - p0) x (q1 - q0) the zero vector, i.e. are the two directions parallel (or one of
// them zero)? Each component is a triple product with a unit axis, so exact under the staged
// policies.
template <NumberPolicy Policy>
bool parallel(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1) {
  constexpr Point3 origin{0, 0, 0};
  constexpr Point3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const Point3& axis : axes) {
    if (triple_sign<Policy>(p0, p1, q0, q1, origin, axis) != Sign::zero) return false;
  }
  return true;
}

}  // namespace rockcontact::kernel
