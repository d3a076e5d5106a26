// The first touch of a moving node and a moving edge (touch_time.hpp; seed 003 §3): the
// polynomials of the touch written once over the number type, the exact signs of quadratic
// surds, the staged decisions, the rounding of s and λ, and the four policies.

#include "rockcontact/kernel/2d/touch_time.hpp"

#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "rockcontact/kernel/core/detail/staged_sign.hpp"
#include "rockcontact/kernel/core/policy_disagreement.hpp"

namespace rockcontact::kernel {
namespace detail {
namespace {

using Interval = CGAL::Interval_nt_advanced;
using CGAL::Mpzf;

// ---------------------------------------------------------------------------------------------
// The formulas, generic over T: double (Float), Interval (stage 1), Mpzf (stage 2). Ring
// operations only, so Mpzf evaluates them exactly.

template <class T>
struct Vec {
  T x, y;
};

template <class T>
T cross_of(const Vec<T>& u, const Vec<T>& v) {
  return u.x * v.y - u.y * v.x;
}

template <class T>
T dot_of(const Vec<T>& u, const Vec<T>& v) {
  return u.x * v.x + u.y * v.y;
}

// c2 s² + c1 s + c0.
template <class T>
struct Quadratic {
  T c2, c1, c0;

  T at(const T& s) const { return (c2 * s + c1) * s + c0; }
  friend Quadratic operator-(const Quadratic& p, const Quadratic& q) {
    return {p.c2 - q.c2, p.c1 - q.c1, p.c0 - q.c0};
  }
  // p - x q, for a constant x.
  Quadratic minus_times(const T& x, const Quadratic& q) const {
    return {c2 - x * q.c2, c1 - x * q.c1, c0 - x * q.c0};
  }
};

template <class T>
struct TouchPolynomials {
  Quadratic<T> f;        // (b - a) x (p - a): negative while the node is outside
  Quadratic<T> along;    // G = (p - a)·(b - a): >= 0 past the end a
  Quadratic<T> to_end;   // E - G = (b - p)·(b - a): >= 0 before the end b
  Quadratic<T> length2;  // E = |b - a|²
  T discriminant;        // D = B² - 4AC of f
};

// The header's formulas. The displacements are differences of input doubles, and the
// relative motion dr = (p1 - p0) - (a1 - a0) is formed from them rather than from
// (p1 - a1) - (p0 - a0): in double a displacement is usually exact (Sterbenz), so Float
// loses nothing where a node and an edge move together.
template <class T>
TouchPolynomials<T> touch_polynomials(const NodeEdgeMotion& m) {
  const auto diff = [](const Point2& to, const Point2& from) {
    return Vec<T>{T(to.x) - T(from.x), T(to.y) - T(from.y)};
  };
  const auto minus = [](const Vec<T>& u, const Vec<T>& v) { return Vec<T>{u.x - v.x, u.y - v.y}; };
  const Vec<T> e0 = diff(m.b.start, m.a.start);     // b0 - a0
  const Vec<T> r0 = diff(m.node.start, m.a.start);  // p0 - a0
  const Vec<T> da = diff(m.a.end, m.a.start);
  const Vec<T> de = minus(diff(m.b.end, m.b.start), da);        // (b1 - b0) - (a1 - a0)
  const Vec<T> dr = minus(diff(m.node.end, m.node.start), da);  // (p1 - p0) - (a1 - a0)
  TouchPolynomials<T> P;
  P.f = {cross_of(de, dr), cross_of(e0, dr) + cross_of(de, r0), cross_of(e0, r0)};
  P.along = {dot_of(dr, de), dot_of(r0, de) + dot_of(dr, e0), dot_of(r0, e0)};
  P.length2 = {dot_of(de, de), T(2) * dot_of(e0, de), dot_of(e0, e0)};
  P.to_end = P.length2 - P.along;
  P.discriminant = P.f.c1 * P.f.c1 - T(4) * P.f.c2 * P.f.c0;
  return P;
}

// A root of f as the quadratic surd s = (u + w √radicand) / d, d != 0:
//   index 0, 1   (-B + σ √D) / (2A), σ = ∓ sign(A) so that index 0 is the smaller root;
//   index 2      -C / B (u = -C, w = 0, d = B), f linear.
template <class T>
struct Root {
  T u, w, d, radicand;
};

template <class T>
Root<T> root_of(const TouchPolynomials<T>& P, int index, Sign sign_a) {
  if (index == touch_root_linear) return {-P.f.c0, T(0), P.f.c1, T(0)};
  const int sigma = static_cast<int>(sign_a) * (index == touch_root_smaller ? -1 : 1);
  return {-P.f.c1, T(sigma), T(2) * P.f.c2, P.discriminant};
}

// rational + coefficient √radicand, radicand >= 0.
template <class T>
struct Surd {
  T rational, coefficient, radicand;
};

// d (s - x): sign(s - x) = sign(d) sign(d (s - x)).
template <class T>
Surd<T> scaled_offset(const Root<T>& r, const T& x) {
  return {r.u - r.d * x, r.w, r.radicand};
}

// d² q(s) = q2 (u + w√D)² + q1 d (u + w√D) + q0 d²: since d² > 0, its sign is q(s)'s.
template <class T>
Surd<T> scaled_value(const Quadratic<T>& q, const Root<T>& r) {
  return {q.c2 * (r.u * r.u + r.w * r.w * r.radicand) + q.c1 * r.d * r.u + q.c0 * r.d * r.d,
          r.w * (T(2) * q.c2 * r.u + q.c1 * r.d), r.radicand};
}

// A plain polynomial as a surd (coefficient 0), so that every decision goes through one path.
template <class T>
Surd<T> rational(const T& value) {
  return {value, T(0), T(0)};
}

// ---------------------------------------------------------------------------------------------
// Exact signs of surds, in Mpzf. No square root is taken: a sum of two terms of opposite signs
// has the sign of the one with the larger square.

Sign sign_of_mpzf(const Mpzf& x) { return to_sign(x.sign()); }

// sign(y √p + z √q), p, q >= 0.
Sign sum_of_roots_sign(const Mpzf& y, const Mpzf& p, const Mpzf& z, const Mpzf& q) {
  const Sign sy = p.sign() == CGAL::ZERO ? Sign::zero : sign_of_mpzf(y);
  const Sign sz = q.sign() == CGAL::ZERO ? Sign::zero : sign_of_mpzf(z);
  if (sy == Sign::zero) return sz;
  if (sz == Sign::zero || sy == sz) return sy;
  return sy * sign_of_mpzf(y * y * p - z * z * q);  // |y|√p > |z|√q iff y²p > z²q
}

// sign(x + y √p): the two-term case, x = x √1.
Sign surd_sign_exact(const Surd<Mpzf>& v) {
  return sum_of_roots_sign(v.rational, Mpzf(1), v.coefficient, v.radicand);
}

// sign(x + y √p + z √q), p, q >= 0: with t = y √p + z √q (sign by the two-term rule), when x
// and t have opposite signs the larger of x² and t² = y²p + z²q + 2yz √(pq) wins, and
// x² - t² is again a two-term surd, in √(pq).
Sign three_term_sign_exact(const Mpzf& x, const Mpzf& y, const Mpzf& p, const Mpzf& z, const Mpzf& q) {
  const Sign st = sum_of_roots_sign(y, p, z, q);
  const Sign sx = sign_of_mpzf(x);
  if (st == Sign::zero) return sx;
  if (sx == Sign::zero || sx == st) return st;
  const Surd<Mpzf> x2_minus_t2{x * x - y * y * p - z * z * q, Mpzf(-2) * y * z, p * q};
  return sx * surd_sign_exact(x2_minus_t2);
}

// The interval stage's sign of a surd: certain when the enclosure excludes zero or is the
// point zero. The exact radicand is >= 0 (the discriminant of a root that exists); its
// enclosure may reach below zero, where CGAL's sqrt starts the root's enclosure at 0.
CGAL::Uncertain<CGAL::Sign> surd_sign_interval(const Surd<Interval>& v) {
  if (v.coefficient.is_point() && v.coefficient.inf() == 0.0) return CGAL::sign(v.rational);
  return CGAL::sign(v.rational + v.coefficient * CGAL::sqrt(v.radicand));
}

// ---------------------------------------------------------------------------------------------
// The decisions of one motion: each a formula F, a callable F(const TouchPolynomials<T>&) ->
// Surd<T>, decided in intervals first (when filtering) and exactly only if uncertain. The
// decider holds the upward rounding the interval stage needs for its whole lifetime: one
// switch for all of a call's decisions, restored when the decider ends.
// Mpzf arithmetic is integer arithmetic and does not depend on the rounding mode.
class TouchDecider {
 public:
  TouchDecider(const NodeEdgeMotion& m, bool filter)
      : motion_(m), filter_(filter), enclosure_(touch_polynomials<Interval>(m)) {}
  TouchDecider(const TouchDecider&) = delete;
  TouchDecider& operator=(const TouchDecider&) = delete;

  template <class F>
  Sign sign(const F& formula) {
    if (filter_) {
      const CGAL::Uncertain<CGAL::Sign> s = surd_sign_interval(formula(enclosure_));
      if (CGAL::is_certain(s)) return to_sign(CGAL::get_certain(s));
    }
    return surd_sign_exact(formula(exact()));
  }

  const TouchPolynomials<Interval>& enclosure() const { return enclosure_; }
  const TouchPolynomials<Mpzf>& exact() {
    if (!exact_) exact_ = touch_polynomials<Mpzf>(motion_);
    return *exact_;
  }

 private:
  CGAL::Protect_FPU_rounding<true> upward_{CGAL_FE_UPWARD};  // first member: constructed before enclosure_ is evaluated
  const NodeEdgeMotion& motion_;
  bool filter_;
  TouchPolynomials<Interval> enclosure_;
  std::optional<TouchPolynomials<Mpzf>> exact_;
};

struct Decision {
  int root;     // touch_root_*
  Sign sign_a;  // sign of A (zero for the linear root)
};

// The sign of the root's denominator d: 2A, or B for the linear root (positive: first_touch
// takes the linear root only when B > 0).
Sign denominator_sign(const Decision& k) { return k.root == touch_root_linear ? Sign::positive : k.sign_a; }

// Is root k in (0, 1] and the node within the edge's span there?
bool accepts(TouchDecider& decider, const Decision& k) {
  const auto root = [&](const auto& P) { return root_of(P, k.root, k.sign_a); };
  const Sign d = denominator_sign(k);
  const auto offset = [&](double x) {
    return [&, x](const auto& P) {
      using T = std::decay_t<decltype(P.discriminant)>;
      return scaled_offset(root(P), T(x));
    };
  };
  if (d * decider.sign(offset(0.0)) != Sign::positive) return false;  // s > 0
  if (d * decider.sign(offset(1.0)) == Sign::positive) return false;  // s <= 1
  if (decider.sign([&](const auto& P) { return scaled_value(P.along, root(P)); }) == Sign::negative) {
    return false;  // before the end a
  }
  return decider.sign([&](const auto& P) { return scaled_value(P.to_end, root(P)); }) != Sign::negative;
}

// The decisions of first_touch (the header's cases), smallest root first.
std::optional<Decision> decide_first_touch(TouchDecider& decider) {
  if (decider.sign([](const auto& P) { return rational(P.f.c0); }) != Sign::negative) {
    return std::nullopt;  // C = f(0) >= 0: on or inside the line at the start of the step
  }
  const Sign sign_a = decider.sign([](const auto& P) { return rational(P.f.c2); });
  if (sign_a == Sign::zero) {
    // f = B s + C: with C < 0 the root -C/B is positive iff B > 0; B = 0 leaves f = C < 0.
    if (decider.sign([](const auto& P) { return rational(P.f.c1); }) != Sign::positive) return std::nullopt;
    const Decision linear{touch_root_linear, Sign::zero};
    if (accepts(decider, linear)) return linear;
    return std::nullopt;
  }
  const Sign sign_d = decider.sign([](const auto& P) { return rational(P.discriminant); });
  if (sign_d == Sign::negative) return std::nullopt;
  const Decision smaller{touch_root_smaller, sign_a};
  if (accepts(decider, smaller)) return smaller;
  if (sign_d == Sign::zero) return std::nullopt;  // a double root: there is no second one
  const Decision larger{touch_root_larger, sign_a};
  if (accepts(decider, larger)) return larger;
  return std::nullopt;
}

// The decision behind a touch found by first_touch: the sign of A, decided again.
Decision decision_of(TouchDecider& decider, const TouchTime& t) {
  assert(t.root >= touch_root_smaller && t.root <= touch_root_linear);
  if (t.root == touch_root_linear) return {touch_root_linear, Sign::zero};
  return {t.root, decider.sign([](const auto& P) { return rational(P.f.c2); })};
}

// ---------------------------------------------------------------------------------------------
// Rounding s and λ.

// An enclosure of root k, evaluated in the form without cancellation: when -B and σ√D have
// opposite signs (B's sign certain) the root is taken as 2C / (-B - σ√D) (the product of the
// roots is C/A) rather than (-B + σ√D) / (2A), whose numerator would lose the digits the two
// terms share. A division by an enclosure of zero gives the whole line: still an enclosure.
Interval root_enclosure(const TouchPolynomials<Interval>& P, const Decision& k) {
  const Quadratic<Interval>& f = P.f;
  if (k.root == touch_root_linear) return -f.c0 / f.c1;
  const Root<Interval> r = root_of(P, k.root, k.sign_a);  // u = -B, w = σ, d = 2A
  const Interval sigma_root_d = r.w * CGAL::sqrt(P.discriminant);
  const bool cancels = r.w.inf() > 0.0 ? f.c1.inf() > 0.0 : f.c1.sup() < 0.0;
  if (cancels) return Interval(2) * f.c0 / (r.u - sigma_root_d);
  return (r.u + sigma_root_d) / r.d;
}

// A point of the enclosure [lo, hi]: lo + (hi - lo)/2 rounded upward stays at most hi.
double midpoint(const Interval& x) {
  const double mid = x.inf() + 0.5 * (x.sup() - x.inf());
  return mid < x.inf() ? x.inf() : (mid > x.sup() ? x.sup() : mid);
}

// Is the enclosure's width at most touch_time_tolerance · scale? The width is rounded upward
// (the decider's mode), the scaling by 2^44 is exact: the test never accepts a wider one.
bool narrow(const Interval& x, double scale) {
  static_assert(touch_time_tolerance == 0x1p-44, "narrow() scales by 1 / touch_time_tolerance");
  return (x.sup() - x.inf()) * 0x1p44 <= scale;
}

// The double nearest to a value v in [0, 1], ties to even, given an enclosure lo <= v <= hi
// and the exact sign of v - x for any dyadic x. Non-negative doubles are ordered as their bit
// patterns, so a bisection on the patterns of [lo, hi] brackets v between two neighbouring
// doubles, and one comparison with their midpoint picks the nearest: at most ~62 comparisons
// on [0, 1], a handful on a narrow enclosure. The rounding mode plays no part.
template <class SignMinus>
double round_to_nearest(double lo, double hi, const SignMinus& sign_minus) {
  lo = lo > 0.0 ? lo : 0.0;  // also maps NaN and -0 to +0
  hi = hi < 1.0 ? hi : 1.0;
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;
  if (sign_minus(Mpzf(lo)) == Sign::zero) return lo;
  if (sign_minus(Mpzf(hi)) == Sign::zero) return hi;
  std::uint64_t below = std::bit_cast<std::uint64_t>(lo), above = std::bit_cast<std::uint64_t>(hi);
  while (above - below > 1) {  // invariant: double(below) < v < double(above)
    const std::uint64_t middle = below + (above - below) / 2;
    const double x = std::bit_cast<double>(middle);
    const Sign s = sign_minus(Mpzf(x));
    if (s == Sign::zero) return x;
    (s == Sign::positive ? below : above) = middle;
  }
  const double x0 = std::bit_cast<double>(below), x1 = std::bit_cast<double>(above);
  const Sign half = sign_minus((Mpzf(x0) + Mpzf(x1)) * Mpzf(0.5));
  if (half == Sign::negative) return x0;
  if (half == Sign::positive) return x1;
  return (below & 1u) == 0 ? x0 : x1;
}

// s and λ of root k (the header's bounds). `filter`: accept a narrow enclosure's midpoint.
TouchTime rounded_touch(TouchDecider& decider, const Decision& k, bool filter) {
  const TouchPolynomials<Interval>& I = decider.enclosure();
  TouchTime t;
  t.root = k.root;
  const Interval s = root_enclosure(I, k);
  if (filter && s.inf() > 0.0 && narrow(s, s.inf())) {
    t.s = std::fmin(midpoint(s), 1.0);  // the exact s <= 1: clamping cannot move away from it
  } else {
    const Sign d = denominator_sign(k);
    t.s = round_to_nearest(s.inf(), s.sup(), [&](const Mpzf& x) {
      return d * surd_sign_exact(scaled_offset(root_of(decider.exact(), k.root, k.sign_a), x));
    });
  }
  // λ = G(s) / E(s), with E(s) > 0 unless the edge has collapsed at s (then λ = 0).
  const auto root = [&](const auto& P) { return root_of(P, k.root, k.sign_a); };
  if (decider.sign([&](const auto& P) { return scaled_value(P.length2, root(P)); }) == Sign::zero) return t;
  const Interval lambda = I.along.at(s) / I.length2.at(s);
  if (filter && narrow(lambda, 1.0)) {
    t.lambda = std::fmin(std::fmax(midpoint(lambda), 0.0), 1.0);  // the exact λ is in [0, 1]
  } else {
    // sign(λ - x) = sign(G(s) - x E(s)), a quadratic at the root.
    t.lambda = round_to_nearest(lambda.inf(), lambda.sup(), [&](const Mpzf& x) {
      const TouchPolynomials<Mpzf>& P = decider.exact();
      return surd_sign_exact(scaled_value(P.along.minus_times(x, P.length2), root(P)));
    });
  }
  return t;
}

// ---------------------------------------------------------------------------------------------
// The policies.

std::optional<TouchTime> first_touch_float(const NodeEdgeMotion& m) {
  const TouchPolynomials<double> P = touch_polynomials<double>(m);
  const double a = P.f.c2, b = P.f.c1, c = P.f.c0;
  if (!(c < 0.0)) return std::nullopt;
  const auto touch_at = [&](double s, int root) -> std::optional<TouchTime> {
    if (!(s > 0.0 && s <= 1.0)) return std::nullopt;
    const double g = P.along.at(s), e = P.length2.at(s);
    if (!(g >= 0.0 && g <= e)) return std::nullopt;
    return TouchTime{s, e > 0.0 ? std::fmin(g / e, 1.0) : 0.0, root};
  };
  if (a == 0.0) return b > 0.0 ? touch_at(-c / b, touch_root_linear) : std::nullopt;
  const double d = P.discriminant;
  if (d < 0.0) return std::nullopt;
  // The cancellation-free quadratic formula: q = -(B + sign(B) √D) / 2, roots q/A and C/q.
  const double q = -0.5 * (b + std::copysign(std::sqrt(d), b));
  double s0 = q / a;
  double s1 = q != 0.0 ? c / q : s0;
  if (s1 < s0) std::swap(s0, s1);
  if (auto t = touch_at(s0, touch_root_smaller)) return t;
  if (d == 0.0) return std::nullopt;
  return touch_at(s1, touch_root_larger);
}

// Filtered (filter = true) and Exact (false).
std::optional<TouchTime> first_touch_staged(const NodeEdgeMotion& m, bool filter) {
  TouchDecider decider(m, filter);
  const std::optional<Decision> k = decide_first_touch(decider);
  if (!k) return std::nullopt;
  return rounded_touch(decider, *k, filter);
}

std::optional<int> first_root_exact(const NodeEdgeMotion& m) {
  TouchDecider decider(m, false);
  const std::optional<Decision> k = decide_first_touch(decider);
  if (!k) return std::nullopt;
  return k->root;
}

Sign compare_touch_staged(const NodeEdgeMotion& x, const TouchTime& tx, const NodeEdgeMotion& y,
                          const TouchTime& ty, bool filter) {
  TouchDecider dx(x, filter);
  TouchDecider dy(y, filter);
  const Decision kx = decision_of(dx, tx), ky = decision_of(dy, ty);
  if (filter) {  // filtered root isolation: disjoint enclosures are ordered
    const Interval sx = root_enclosure(dx.enclosure(), kx), sy = root_enclosure(dy.enclosure(), ky);
    if (sx.sup() < sy.inf()) return Sign::negative;
    if (sx.inf() > sy.sup()) return Sign::positive;
  }
  // s_x - s_y = (d_y (u_x + w_x √D_x) - d_x (u_y + w_y √D_y)) / (d_x d_y).
  const Root<Mpzf> rx = root_of(dx.exact(), kx.root, kx.sign_a);
  const Root<Mpzf> ry = root_of(dy.exact(), ky.root, ky.sign_a);
  return denominator_sign(kx) * denominator_sign(ky) *
         three_term_sign_exact(rx.u * ry.d - ry.u * rx.d, rx.w * ry.d, rx.radicand, -(ry.w * rx.d),
                               ry.radicand);
}

// ---------------------------------------------------------------------------------------------
// Checked: PolicyDisagreement with the full input as hexadecimal floats (bit for bit), as
// throw_disagreement (core/src/staged_sign.cpp) writes it for the predicates. Built here
// rather than through throw_disagreement, which names a PredicateKind: the touch time has none.

std::string hex_input(std::initializer_list<const NodeEdgeMotion*> motions) {
  std::string text = "[";
  char buffer[32];
  bool first = true;
  for (const NodeEdgeMotion* m : motions) {
    for (const MovingPoint2* q : {&m->node, &m->a, &m->b}) {
      for (const double v : {q->start.x, q->start.y, q->end.x, q->end.y}) {
        std::snprintf(buffer, sizeof buffer, "%s%a", first ? "" : ", ", v);
        text += buffer;
        first = false;
      }
    }
  }
  return text + "] (node, a, b; start x, y, end x, y each)";
}

std::string root_name(const std::optional<int>& root) {
  return root ? "root " + std::to_string(*root) : std::string("no touch");
}

[[noreturn]] void first_touch_disagrees(const NodeEdgeMotion& m, const std::optional<int>& staged,
                                        const std::optional<int>& exact) {
  throw PolicyDisagreement("Checked policy: first_touch staged " + root_name(staged) + " but exact " +
                           root_name(exact) + " on input " + hex_input({&m}));
}

[[noreturn]] void compare_touch_disagrees(const NodeEdgeMotion& x, const TouchTime& tx,
                                          const NodeEdgeMotion& y, const TouchTime& ty, Sign staged,
                                          Sign exact) {
  throw PolicyDisagreement("Checked policy: compare_touch staged sign " +
                           std::to_string(static_cast<int>(staged)) + " but exact sign " +
                           std::to_string(static_cast<int>(exact)) + " for roots " + std::to_string(tx.root) +
                           ", " + std::to_string(ty.root) + " on input " + hex_input({&x, &y}));
}

}  // namespace
}  // namespace detail

template <NumberPolicy P>
std::optional<TouchTime> first_touch(const NodeEdgeMotion& m) {
  if constexpr (P::kind == PolicyKind::float_) {
    return detail::first_touch_float(m);
  } else if constexpr (P::kind == PolicyKind::exact) {
    return detail::first_touch_staged(m, false);
  } else {
    const std::optional<TouchTime> staged = detail::first_touch_staged(m, true);
    if constexpr (P::kind == PolicyKind::checked) {
      const std::optional<int> exact = detail::first_root_exact(m);
      const std::optional<int> root = staged ? std::optional<int>(staged->root) : std::nullopt;
      if (root != exact) detail::first_touch_disagrees(m, root, exact);
    }
    return staged;
  }
}

template <NumberPolicy P>
Sign compare_touch(const NodeEdgeMotion& x, const TouchTime& tx, const NodeEdgeMotion& y,
                   const TouchTime& ty) {
  if constexpr (P::kind == PolicyKind::float_) {
    return sign_of(tx.s - ty.s);
  } else if constexpr (P::kind == PolicyKind::exact) {
    return detail::compare_touch_staged(x, tx, y, ty, false);
  } else {
    const Sign staged = detail::compare_touch_staged(x, tx, y, ty, true);
    if constexpr (P::kind == PolicyKind::checked) {
      const Sign exact = detail::compare_touch_staged(x, tx, y, ty, false);
      if (staged != exact) detail::compare_touch_disagrees(x, tx, y, ty, staged, exact);
    }
    return staged;
  }
}

#define ROCKCONTACT_INSTANTIATE(P)                                                               \
  template std::optional<TouchTime> first_touch<P>(const NodeEdgeMotion&);                       \
  template Sign compare_touch<P>(const NodeEdgeMotion&, const TouchTime&, const NodeEdgeMotion&, \
                                 const TouchTime&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
