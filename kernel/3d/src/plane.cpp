// Plane3's constructors and the staged stages of its predicates (plane.hpp): the formulas of
// detail/plane_formulas.hpp in CGAL's interval and exact number types, through the engine of
// kernel/core/detail/staged_sign.hpp.

#include "rockcontact/kernel/3d/plane.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "rockcontact/kernel/3d/detail/plane_formulas.hpp"
#include "rockcontact/kernel/3d/detail/running_error.hpp"
#include "rockcontact/kernel/core/detail/staged_sign.hpp"

namespace rockcontact::kernel {

namespace {

bool finite(const Point3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

}  // namespace

Plane3 Plane3::through(const Point3& p0, const Point3& p1, const Point3& p2) {
  if (!finite(p0) || !finite(p1) || !finite(p2)) throw std::invalid_argument("Plane3::through: a point is not finite");
  if (parallel<Filtered>(p0, p1, p0, p2)) throw std::invalid_argument("Plane3::through: the points are collinear");
  Plane3 plane;
  plane.kind = Kind::through_points;
  plane.points = {p0, p1, p2};
  return plane;
}

Plane3 Plane3::from_coefficients(double a, double b, double c, double d) {
  if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d)) {
    throw std::invalid_argument("Plane3::from_coefficients: a coefficient is not finite");
  }
  if (a == 0.0 && b == 0.0 && c == 0.0) throw std::invalid_argument("Plane3::from_coefficients: zero normal");
  Plane3 plane;
  plane.kind = Kind::coefficients;
  plane.coefficients = {a, b, c, d};
  return plane;
}

Plane3 Plane3::of_face(const ConvexPolyhedron& p, std::size_t face) {
  const ConvexPolyhedron::Face& f = p.faces()[face];
  Plane3 plane;
  plane.kind = Kind::through_points;
  plane.points = {p[f[0]], p[f[1]], p[f[2]]};
  return plane;
}

Plane3 Plane3::opposite() const {
  Plane3 plane = *this;
  if (kind == Kind::through_points) {
    std::swap(plane.points[1], plane.points[2]);  // (p2 - p0) x (p1 - p0) = -n
  } else {
    for (double& c : plane.coefficients) c = -c;  // exact
  }
  return plane;
}

namespace detail {
namespace {

auto coefficient_side_of(const Plane3& s, const Point3& x) {
  return [&](auto as) {
    using T = typename decltype(as)::type;
    return coefficient_side_formula<T>(s, x);
  };
}

auto three_plane_side_of(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r) {
  return [&, o = p.reference()](auto as) {
    using T = typename decltype(as)::type;
    return three_plane_side_formula<T>(s, p, q, r, o);
  };
}

void append(std::vector<double>& out, const Plane3& plane) {
  if (plane.kind == Plane3::Kind::through_points) {
    for (const Point3& p : plane.points) out.insert(out.end(), {p.x, p.y, p.z});
  } else {
    out.insert(out.end(), plane.coefficients.begin(), plane.coefficients.end());
  }
}

}  // namespace

Sign coefficient_side_interval_exact(const Plane3& s, const Point3& x) {
  return interval_then_exact_sign(PredicateKind::plane_side, coefficient_side_of(s, x));
}

Sign coefficient_side_exact(const Plane3& s, const Point3& x) { return exact_sign(coefficient_side_of(s, x)); }

double coefficient_side_naive(const Plane3& s, const Point3& x) { return coefficient_side_formula<double>(s, x); }

// The double filter of the three-plane side: the formula evaluated once more with a running
// error bound (detail/running_error.hpp), certain when the value exceeds the bound. It never
// certifies zero: an exact incidence is left to the interval stage (exact when every operation
// was) and then to Mpzf.
namespace {
std::optional<Sign> three_plane_side_filter(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r) {
  const RunningError v = three_plane_side_formula<RunningError>(s, p, q, r, p.reference());
  const double bound = bound_rounding_margin * v.error;
  if (!std::isfinite(v.value) || !std::isfinite(bound)) return std::nullopt;
  if (v.value > bound) return Sign::positive;
  if (-v.value > bound) return Sign::negative;
  return std::nullopt;
}
}  // namespace

Sign three_plane_side_staged(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r) {
  count_call(PredicateKind::plane_side);
  if (const auto sign = three_plane_side_filter(s, p, q, r)) return *sign;
  return three_plane_side_interval_exact(s, p, q, r);
}

Sign three_plane_side_interval_exact(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r) {
  return interval_then_exact_sign(PredicateKind::plane_side, three_plane_side_of(s, p, q, r));
}

Sign three_plane_side_exact(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r) {
  return exact_sign(three_plane_side_of(s, p, q, r));
}

Sign three_plane_side_naive(const Plane3& s, const Plane3& p, const Plane3& q, const Plane3& r) {
  return sign_of(three_plane_side_formula<double>(s, p, q, r, p.reference()));
}

void plane_side_disagrees(const Plane3* const* planes, int count, const Point3* x, Sign staged, Sign exact) {
  std::vector<double> input;
  for (int i = 0; i < count; ++i) append(input, *planes[i]);
  if (x != nullptr) input.insert(input.end(), {x->x, x->y, x->z});
  throw_disagreement(PredicateKind::plane_side, input, staged, exact);
}

}  // namespace detail
}  // namespace rockcontact::kernel
