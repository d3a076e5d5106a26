#pragma once
// DoubleDouble: an unevaluated sum hi + lo of two doubles, |lo| <= ulp(hi) / 2, about 106 bits
// of precision at double's speed. The lazy stage of an Exact construction evaluates the exact
// formula in it with a running error bound (3d/detail/running_error.hpp) and rounds when the
// bound settles the nearest double; exact rationals only when it cannot.
//
// Building blocks (Dekker 1971; Knuth, TAOCP vol. 2, 4.2.2), exact in round to nearest barring
// overflow and underflow:
//   two_sum(a, b)       s + e = a + b exactly, s = fl(a + b)           (Knuth, 6 flops)
//   fast_two_sum(a, b)  the same when |a| >= |b| or a = 0              (Dekker, 3 flops)
//   two_product(a, b)   p + e = a b exactly, p = fl(a b)               (Dekker's split, 17 flops;
//                       no FMA: the kernel builds without -mfma, where std::fma is a library call)
// Dekker's split multiplies by 2^27 + 1: exact for |a| < 2^996.
// The operations and their relative error bounds, u = 2^-53 (Joldes, Muller, Popescu, "Tight and
// rigorous error bounds for basic building blocks of double-word arithmetic", ACM TOMS 44(2),
// 2017: AccurateDWPlusDW, Algorithm 6, 3u^2 + 13u^3; DWTimesDW1, Algorithm 10, 7u^2):
//   a + b, a - b   <= 4 u^2 |result|
//   a * b          <= 8 u^2 |result|
// Users take 2^-100 = 64 u^2 per operation (running_error.hpp), a factor 8 of margin.
// Requires round to nearest, the mode of all the library's double code (an interval stage
// switches to upward rounding for its own evaluation only).
// An overflow shows as a non-finite hi or lo; below 2^-969 the low word loses bits to underflow,
// which users bound as an absolute error (running_error.hpp).

#include <cmath>

namespace rockcontact::kernel::detail {

struct DoubleDouble {
  double hi = 0.0;
  double lo = 0.0;

  DoubleDouble() = default;
  explicit DoubleDouble(double x) : hi(x) {}
  DoubleDouble(double h, double l) : hi(h), lo(l) {}

  static DoubleDouble two_sum(double a, double b) {
    const double s = a + b;
    const double bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
  }
  static DoubleDouble fast_two_sum(double a, double b) {
    const double s = a + b;
    return {s, b - (s - a)};
  }
  static DoubleDouble two_product(double a, double b) {
    const auto split = [](double x) {
      const double c = 134217729.0 * x;  // 2^27 + 1
      const double high = c - (c - x);
      return DoubleDouble{high, x - high};
    };
    const double p = a * b;
    const DoubleDouble x = split(a), y = split(b);
    return {p, ((x.hi * y.hi - p) + x.hi * y.lo + x.lo * y.hi) + x.lo * y.lo};
  }

  friend DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
    const DoubleDouble s = two_sum(a.hi, b.hi);
    const DoubleDouble t = two_sum(a.lo, b.lo);
    const DoubleDouble v = fast_two_sum(s.hi, s.lo + t.hi);
    return fast_two_sum(v.hi, t.lo + v.lo);
  }
  friend DoubleDouble operator-(const DoubleDouble& a) { return {-a.hi, -a.lo}; }
  friend DoubleDouble operator-(const DoubleDouble& a, const DoubleDouble& b) { return a + (-b); }
  friend DoubleDouble operator*(const DoubleDouble& a, const DoubleDouble& b) {
    const DoubleDouble c = two_product(a.hi, b.hi);
    return fast_two_sum(c.hi, c.lo + (a.hi * b.lo + a.lo * b.hi));
  }

  // An upper bound on |hi + lo| within a factor 1 + 2^-52.
  double magnitude() const { return std::fabs(hi) + std::fabs(lo); }
  bool finite() const { return std::isfinite(hi) && std::isfinite(lo); }
};

}  // namespace rockcontact::kernel::detail
