#pragma once
// rounded_quotient(P, Q): the double nearest to the exact quotient P / Q of two CGAL::Mpzf
// numbers, ties to even, the way the Exact policy rounds a constructed coordinate. Included by
// kernel .cpp files only (it includes CGAL).
//
// A lazy exact construction: a coordinate that is a quotient of two polynomials of the input
// doubles (a crossing of two lines, later a point on three planes) is evaluated exactly as two
// Mpzf numbers, which stay in Mpzf's inline limbs, instead of as a GMP rational, and is never
// divided exactly. The double r = fl(P~ / Q~) of their enclosures is within a few ulps of the
// quotient; r is the answer exactly when the quotient lies between the midpoints of r and its
// two neighbours, and each comparison with a midpoint m is the sign of P - m Q (times the sign
// of Q), a product of Mpzf numbers: exact. The walk steps to the neighbour while a comparison
// fails. Where r is not finite or a neighbour is (overflow, or Q~ rounding to zero) the caller
// falls back to exact rationals: the function answers nullopt.

#include <CGAL/Mpzf.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>

namespace rockcontact::kernel::detail {

inline std::optional<double> rounded_quotient(const CGAL::Mpzf& p, const CGAL::Mpzf& q) {
  using CGAL::Mpzf;
  const int sign_q = static_cast<int>(q.sign());
  if (sign_q == 0) return std::nullopt;
  const auto [p_lo, p_hi] = CGAL::to_interval(p);
  const auto [q_lo, q_hi] = CGAL::to_interval(q);
  double r = (0.5 * p_lo + 0.5 * p_hi) / (0.5 * q_lo + 0.5 * q_hi);
  // The sign of P/Q - m for the midpoint m of r and its neighbour toward `toward`.
  const auto side_of_midpoint = [&](double r0, double toward) {
    const double neighbour = std::nextafter(r0, toward);
    const Mpzf m = (Mpzf(r0) + Mpzf(neighbour)) * Mpzf(0.5);
    return static_cast<int>((p - m * q).sign()) * sign_q;
  };
  const auto even = [](double a, double b) {
    return (std::bit_cast<std::uint64_t>(a) & 1u) == 0 ? a : b;
  };
  for (int steps = 0; steps < 64; ++steps) {
    if (!std::isfinite(r) || !std::isfinite(std::nextafter(r, HUGE_VAL)) ||
        !std::isfinite(std::nextafter(r, -HUGE_VAL))) {
      return std::nullopt;
    }
    const int above = side_of_midpoint(r, HUGE_VAL);
    if (above > 0) {
      r = std::nextafter(r, HUGE_VAL);
      continue;
    }
    if (above == 0) return even(r, std::nextafter(r, HUGE_VAL));
    const int below = side_of_midpoint(r, -HUGE_VAL);
    if (below < 0) {
      r = std::nextafter(r, -HUGE_VAL);
      continue;
    }
    if (below == 0) return even(r, std::nextafter(r, -HUGE_VAL));
    return r;
  }
  return std::nullopt;  // the enclosures were far off (cannot happen for finite r); be safe
}

}  // namespace rockcontact::kernel::detail
