// Stages 2 and 3 of the 2D predicates (predicates.hpp): the same formulas in CGAL's interval
// and exact number types, through the engine of kernel/core/detail/staged_sign.hpp. Every
// double is an exact dyadic number and the formulas use + - * only, so Mpzf's sign is exact.

#include <array>

#include "rockcontact/kernel/2d/predicates.hpp"
#include "rockcontact/kernel/core/detail/staged_sign.hpp"

namespace rockcontact::kernel::detail {
namespace {

auto cross_formula_of(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  return [&](auto as) {
    using T = typename decltype(as)::type;
    return cross_formula<T>(p0, p1, q0, q1, difference<T>);
  };
}

auto crossing_side_formula_of(const Line& a, const Line& b, const Line& c) {
  return [&](auto as) {
    using T = typename decltype(as)::type;
    return crossing_side_formula<T>(a, b, c, difference<T>);
  };
}

}  // namespace

Sign cross_sign_interval_exact(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  return interval_then_exact_sign(PredicateKind::cross, cross_formula_of(p0, p1, q0, q1));
}

Sign crossing_side_value_sign_interval_exact(const Line& a, const Line& b, const Line& c) {
  return interval_then_exact_sign(PredicateKind::crossing_side, crossing_side_formula_of(a, b, c));
}

Sign cross_sign_exact(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1) {
  return exact_sign(cross_formula_of(p0, p1, q0, q1));
}

Sign crossing_side_value_sign_exact(const Line& a, const Line& b, const Line& c) {
  return exact_sign(crossing_side_formula_of(a, b, c));
}

void cross_sign_disagrees(const Point2& p0, const Point2& p1, const Point2& q0, const Point2& q1,
                          Sign staged, Sign exact) {
  const std::array<double, 8> input{p0.x, p0.y, p1.x, p1.y, q0.x, q0.y, q1.x, q1.y};
  throw_disagreement(PredicateKind::cross, input, staged, exact);
}

void crossing_side_disagrees(const Line& a, const Line& b, const Line& c, Sign staged, Sign exact) {
  const std::array<double, 12> input{a.p.x, a.p.y, a.q.x, a.q.y, b.p.x, b.p.y,
                                     b.q.x, b.q.y, c.p.x, c.p.y, c.q.x, c.q.y};
  throw_disagreement(PredicateKind::crossing_side, input, staged, exact);
}

}  // namespace rockcontact::kernel::detail
