#include "rockcontact/kernel/2d/crossing_point.hpp"

#include <cmath>

#include "rockcontact/kernel/2d/detail/constructions.hpp"
#include "rockcontact/kernel/core/detail/exact_number.hpp"
#include "rockcontact/kernel/core/detail/rounded_quotient.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::kernel {
namespace detail {

// A construction, evaluated in round to nearest (the library's mode outside an interval stage): unit roundoff
// u = 2^-53 and the smallest subnormal.
inline constexpr double unit_roundoff = 0x1p-53;
inline constexpr double smallest_subnormal = 0x1p-1074;

std::optional<CertifiedCrossing> crossing_in_double(const Point2& p, const Point2& q, const Point2& t0,
                                                    const Point2& t1, double tolerance,
                                                    const Point2& origin) {
  constexpr double e = (4.0 + 32.0 * unit_roundoff) * unit_roundoff;  // ccwerrboundA + u: see the header
  const double lx = q.x - p.x, ly = q.y - p.y;
  const double dx = t1.x - t0.x, dy = t1.y - t0.y;
  const double wx = p.x - t0.x, wy = p.y - t0.y;
  const double n = cross(lx, ly, wx, wy);
  const double d = cross(lx, ly, dx, dy);
  const double n_bar = std::fabs(lx * wy) + std::fabs(ly * wx);
  const double d_bar = std::fabs(lx * dy) + std::fabs(ly * dx);
  double s = n / d;
  const double ds = ((e * (n_bar + d_bar) + 0x1p-1073) / std::fabs(d) + unit_roundoff * std::fabs(s) +
                     smallest_subnormal) *
                    (1.0 + 0x1p-40);
  if (!std::isfinite(s) || !std::isfinite(ds) || !(ds <= tolerance)) return std::nullopt;
  // The exact s lies in [0, 1]; clamping s' there cannot move it further from s.
  s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
  return CertifiedCrossing{{(t0.x - origin.x) + s * dx, (t0.y - origin.y) + s * dy}, ds};
}

}  // namespace detail

namespace {

// X - origin rounded to nearest, each coordinate once. With l = q - p, d = t1 - t0, w = p - t0,
// N = l x w and D = l x d, X = t0 + (N / D) d, so X_c - o_c = ((t0_c - o_c) D + N d_c) / D: a
// quotient of polynomials of the input doubles, evaluated in Mpzf and rounded by
// rounded_quotient without an exact division. Only where that cannot round (overflow) are the
// coordinates constructed in exact rationals.
Point2 crossing_rounded_exactly(const Point2& p, const Point2& q, const Point2& t0, const Point2& t1,
                                const Point2& origin) {
  using CGAL::Mpzf;
  const auto diff = [](double a, double b) { return Mpzf(a) - Mpzf(b); };
  const Mpzf lx = diff(q.x, p.x), ly = diff(q.y, p.y);
  const Mpzf dx = diff(t1.x, t0.x), dy = diff(t1.y, t0.y);
  const Mpzf wx = diff(p.x, t0.x), wy = diff(p.y, t0.y);
  const Mpzf n = lx * wy - ly * wx;
  const Mpzf d = lx * dy - ly * dx;
  const auto x = detail::rounded_quotient(diff(t0.x, origin.x) * d + n * dx, d);
  const auto y = detail::rounded_quotient(diff(t0.y, origin.y) * d + n * dy, d);
  if (x && y) return {*x, *y};
  using detail::ExactRational;
  detail::PointT<ExactRational> exact = detail::construct_crossing<ExactRational>(p, q, t0, t1);
  exact.x -= ExactRational(origin.x);
  exact.y -= ExactRational(origin.y);
  return detail::round(exact);
}

}  // namespace

template <NumberPolicy Policy>
Point2 construct_crossing_point(const Point2& p, const Point2& q, const Point2& t0, const Point2& t1,
                                const Point2& origin) {
  detail::count_call(PredicateKind::crossing_point);
  if constexpr (Policy::kind == PolicyKind::float_) {
    const Point2 x = detail::round(detail::construct_crossing<double>(p, q, t0, t1));
    return {x.x - origin.x, x.y - origin.y};
  } else if constexpr (Policy::kind != PolicyKind::exact) {  // Filtered, Checked
    if (const auto c = detail::crossing_in_double(p, q, t0, t1, crossing_parameter_tolerance, origin)) {
      return c->point;
    }
    detail::count_fallback(PredicateKind::crossing_point);
    return crossing_rounded_exactly(p, q, t0, t1, origin);
  } else {
    return crossing_rounded_exactly(p, q, t0, t1, origin);
  }
}

#define ROCKCONTACT_INSTANTIATE(P)                                                         \
  template Point2 construct_crossing_point<P>(const Point2&, const Point2&, const Point2&, \
                                              const Point2&, const Point2&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
