// Stages 2 and 3 of the 3D predicates (predicates.hpp): the triple product in CGAL's interval
// and exact number types, through the engine of kernel/core/detail/staged_sign.hpp.

#include <array>

#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/detail/staged_sign.hpp"

namespace rockcontact::kernel::detail {
namespace {

auto triple_formula_of(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                       const Point3& r0, const Point3& r1) {
  return [&](auto as) {
    using T = typename decltype(as)::type;
    return triple_formula<T>(p0, p1, q0, q1, r0, r1, difference<T>);
  };
}

}  // namespace

Sign triple_sign_interval_exact(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                                const Point3& r0, const Point3& r1) {
  return interval_then_exact_sign(PredicateKind::triple, triple_formula_of(p0, p1, q0, q1, r0, r1));
}

Sign triple_sign_exact(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                       const Point3& r0, const Point3& r1) {
  return exact_sign(triple_formula_of(p0, p1, q0, q1, r0, r1));
}

void triple_sign_disagrees(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1,
                           const Point3& r0, const Point3& r1, Sign staged, Sign exact) {
  const std::array<double, 18> input{p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, q0.x, q0.y, q0.z,
                                     q1.x, q1.y, q1.z, r0.x, r0.y, r0.z, r1.x, r1.y, r1.z};
  throw_disagreement(PredicateKind::triple, input, staged, exact);
}

}  // namespace rockcontact::kernel::detail
