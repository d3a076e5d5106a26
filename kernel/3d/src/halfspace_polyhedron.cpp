// HalfspacePolyhedron (halfspace_polyhedron.hpp): the constructions, generic over the number
// type (double, or CGAL::Exact_rational under Exact) on the plane formulas of
// detail/plane_formulas.hpp.

#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"

#include <CGAL/Mpzf.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "rockcontact/kernel/3d/detail/halfspace_exact.hpp"
#include "rockcontact/kernel/3d/detail/plane_formulas.hpp"
#include "rockcontact/kernel/3d/detail/running_error.hpp"
#include "rockcontact/kernel/core/detail/exact_number.hpp"

namespace rockcontact::kernel {

HalfspacePolyhedron::HalfspacePolyhedron(const ConvexPolyhedron& p) {
  planes_.reserve(p.faces().size());
  faces_.reserve(p.faces().size());
  for (std::size_t f = 0; f < p.faces().size(); ++f) {
    planes_.push_back(Plane3::of_face(p, f));
    faces_.push_back({static_cast<std::uint32_t>(f), p.faces()[f]});
  }
  vertices_.reserve(p.size());
  for (const Point3& x : p.vertices()) vertices_.push_back({true, x, {}});
}

HalfspacePolyhedron::HalfspacePolyhedron(std::vector<Plane3> planes, std::vector<Face> faces,
                                         std::vector<Vertex> vertices)
    : planes_(std::move(planes)), faces_(std::move(faces)), vertices_(std::move(vertices)) {
#ifndef NDEBUG
  for (const Face& face : faces_) {
    assert(face.plane < planes_.size() && face.loop.size() >= 3);
    for (std::uint32_t v : face.loop) assert(v < vertices_.size());
  }
  for (const Vertex& v : vertices_) {
    if (!v.input) {
      for (std::uint32_t i : v.planes) assert(i < planes_.size());
    }
  }
#endif
}

Point3 HalfspacePolyhedron::frame_origin() const {
  for (const Vertex& v : vertices_) {
    if (v.input) return v.point;
  }
  return planes_.empty() ? Point3{} : planes_.front().reference();
}

namespace {

using detail::ExactRational;
using detail::Vector3T;

// Every vertex in the frame of o, exactly: an input point's difference, an implicit point by
// Cramer's rule (detail::three_plane_point) on the planes' exact coefficients.
std::vector<Vector3T<ExactRational>> exact_frame_coordinates(const HalfspacePolyhedron& h, const Point3& o) {
  using T = ExactRational;
  std::vector<detail::PlaneCoefficients<T>> planes;
  planes.reserve(h.planes().size());
  for (const Plane3& plane : h.planes()) planes.push_back(detail::plane_coefficients<T>(plane, o));
  std::vector<Vector3T<T>> out;
  out.reserve(h.vertices().size());
  for (const HalfspacePolyhedron::Vertex& v : h.vertices()) {
    if (v.input) {
      out.push_back(detail::difference3<T>(v.point, o));
      continue;
    }
    const auto x = detail::three_plane_point(planes[v.planes[0]], planes[v.planes[1]], planes[v.planes[2]]);
    out.push_back({x.scaled.x / x.det, x.scaled.y / x.det, x.scaled.z / x.det});
  }
  return out;
}

using Bounded = detail::RunningError;
using detail::bound_rounding_margin;

// A double vertex is kept when certified within 2^-42 of the polyhedron's extent (the largest
// frame coordinate of its vertices, bounded from below). The volume then moves by up to sqrt 3
// times that per unit of surface area, more than volume_tolerance extent^3 on a large thin
// polyhedron: certified_volume takes its own bound, and where it must those vertices are
// divided from their exact homogeneous coordinates instead (sharpen).
constexpr double vertex_tolerance = 0x1p-42;

// An implicit vertex in double with a bound on its error: with S and D the computed det X and
// det, and ES, ED their running bounds,
//   |S/D - X| <= (|S/D| ED + ES) / (|D| - ED)   (when |D| > ED),
// plus one rounding of the quotient (RunningError::rounding: eps relative, and 2^-1069 should
// it underflow). No point when |D| <= ED (the sign of det is not certain).
// The bound itself is computed in double, to within a few eps relative: negligible against the
// 2^-42 it is compared with.
struct CertifiedPoint {
  Vector3T<double> x;
  double error;
};

std::optional<CertifiedPoint> certified_point(const detail::PlaneCoefficients<Bounded>& p,
                                              const detail::PlaneCoefficients<Bounded>& q,
                                              const detail::PlaneCoefficients<Bounded>& r) {
  const auto x = detail::three_plane_point(p, q, r);
  const double ed = bound_rounding_margin * x.det.error;
  const double d = std::fabs(x.det.value);
  if (!(d > ed)) return std::nullopt;
  const Vector3T<double> out{x.scaled.x.value / x.det.value, x.scaled.y.value / x.det.value,
                             x.scaled.z.value / x.det.value};
  const auto error = [&](double xi, const Bounded& si) {
    return (std::fabs(xi) * ed + bound_rounding_margin * si.error) / (d - ed) + Bounded::rounding(xi);
  };
  return CertifiedPoint{out, std::max({error(out.x, x.scaled.x), error(out.y, x.scaled.y), error(out.z, x.scaled.z)})};
}

// An implicit vertex from its exact homogeneous coordinates, det X and det evaluated exactly in
// CGAL::Mpzf (no gcd, unlike rationals). CGAL's Mpzf::to_double is within 2 eps relative only
// where its result is a normal double: below 2^-1022 it rounds to a multiple of 2^-1074, so a
// det of a few 2^-1074 (two face planes at a dihedral angle of that order, from a subnormal
// coordinate) keeps one or two significant bits and the quotient of the two roundings is off by
// any factor (0 for -0.3 and -1 for -0.7 in intersection_test.cpp's
// subnormal_coordinate_beside_a_gap), or 0/0. So the rounded det X and det are divided only
// when each is a normal double (or an exact zero), within 5 eps of |X| then; otherwise the
// exact rational quotient is rounded once (NumberOps: to nearest).
Vector3T<double> exact_quotient_point(const HalfspacePolyhedron& h, const HalfspacePolyhedron::Vertex& v,
                                      const Point3& o) {
  using T = CGAL::Mpzf;
  const auto x = detail::three_plane_point(detail::plane_coefficients<T>(h.planes()[v.planes[0]], o),
                                           detail::plane_coefficients<T>(h.planes()[v.planes[1]], o),
                                           detail::plane_coefficients<T>(h.planes()[v.planes[2]], o));
  if (CGAL::is_zero(x.det)) {  // dependent planes: only after a wrong Float decision
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }
  const double det = CGAL::to_double(x.det);
  const Vector3T<double> scaled{CGAL::to_double(x.scaled.x), CGAL::to_double(x.scaled.y), CGAL::to_double(x.scaled.z)};
  const auto relative = [](double rounded, const T& exact) { return std::isnormal(rounded) || CGAL::is_zero(exact); };
  if (std::isnormal(det) && relative(scaled.x, x.scaled.x) && relative(scaled.y, x.scaled.y) &&
      relative(scaled.z, x.scaled.z)) {
    return {scaled.x / det, scaled.y / det, scaled.z / det};
  }
  const ExactRational d(x.det);
  const auto round = [&](const T& s) { return detail::NumberOps<ExactRational>::to_double(ExactRational(s) / d); };
  return {round(x.scaled.x), round(x.scaled.y), round(x.scaled.z)};
}

// Every vertex in the frame of o in double, with a bound on the error of each of its coordinates,
// and a lower bound on the extent (the largest frame coordinate of the exact vertices).
struct FrameCoordinates {
  std::vector<Vector3T<double>> x;
  std::vector<double> error;  // of each coordinate of x[v], m
  double extent = 0.0;        // m
};

double max_abs(const Vector3T<double>& x) { return std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)}); }

// The error bound of a vertex from exact_quotient_point: 5 eps < 2^-49 of |X|, or half an ulp
// of a subnormal.
double quotient_error(const Vector3T<double>& x) { return 0x1p-49 * max_abs(x) + 0x1p-1074; }

// An input point's difference rounded once (within eps of it, exact when subnormal), an
// implicit point certified in double, else from its exact homogeneous coordinates (within
// 5 eps < 2^-49 of |X| plus 2^-1074, exact_quotient_point).
FrameCoordinates frame_coordinates(const HalfspacePolyhedron& h, const Point3& o) {
  std::vector<detail::PlaneCoefficients<Bounded>> planes;
  planes.reserve(h.planes().size());
  for (const Plane3& plane : h.planes()) planes.push_back(detail::plane_coefficients<Bounded>(plane, o));
  // First pass: input points and candidate implicit points. The extent is a lower bound on the
  // largest frame coordinate of the exact vertices, |x| - error over the candidates, so a
  // badly conditioned candidate cannot widen the tolerance of the others.
  std::vector<std::optional<CertifiedPoint>> candidates(h.vertices().size());
  FrameCoordinates out;
  const auto widen = [&](const CertifiedPoint& c) { out.extent = std::max(out.extent, max_abs(c.x) - c.error); };
  for (std::size_t i = 0; i < h.vertices().size(); ++i) {
    const HalfspacePolyhedron::Vertex& v = h.vertices()[i];
    if (v.input) {
      const Vector3T<double> x = detail::difference3<double>(v.point, o);
      candidates[i] = CertifiedPoint{x, 0x1p-52 * max_abs(x)};
    } else {
      candidates[i] = certified_point(planes[v.planes[0]], planes[v.planes[1]], planes[v.planes[2]]);
    }
    if (candidates[i]) widen(*candidates[i]);
  }
  out.x.reserve(h.vertices().size());
  out.error.reserve(h.vertices().size());
  for (std::size_t i = 0; i < h.vertices().size(); ++i) {
    const auto& c = candidates[i];
    if (c && c->error <= vertex_tolerance * out.extent) {
      out.x.push_back(c->x);
      out.error.push_back(c->error);
    } else {
      out.x.push_back(exact_quotient_point(h, h.vertices()[i], o));
      out.error.push_back(quotient_error(out.x.back()));
    }
  }
  return out;
}

// Every implicit vertex certified to worse than 2^-48 of the extent taken from its exact
// homogeneous coordinates instead: the second stage of the volume (certified_volume).
void sharpen(const HalfspacePolyhedron& h, const Point3& o, FrameCoordinates& frame) {
  for (std::size_t i = 0; i < h.vertices().size(); ++i) {
    if (h.vertices()[i].input || frame.error[i] <= 0x1p-48 * frame.extent) continue;
    frame.x[i] = exact_quotient_point(h, h.vertices()[i], o);
    frame.error[i] = quotient_error(frame.x[i]);
  }
}

// Six times the volume by the divergence theorem: the faces fanned into triangles
// (x0, x_i, x_{i+1}), each counter-clockwise from outside, against the apex c = the first
// vertex, S = sum of det(x0 - c, x_i - c, x_{i+1} - c). The differences y_v = x_v - c are taken
// once per vertex; term(a, b, d) is called with the vertex ids of each fan triangle.
template <class T>
std::vector<Vector3T<T>> from_apex(const std::vector<Vector3T<T>>& x) {
  std::vector<Vector3T<T>> y;
  y.reserve(x.size());
  for (const Vector3T<T>& v : x) y.push_back({T(v.x - x.front().x), T(v.y - x.front().y), T(v.z - x.front().z)});
  return y;
}

template <class Term>
void for_each_fan_triangle(const HalfspacePolyhedron& h, Term term) {
  for (const HalfspacePolyhedron::Face& face : h.faces()) {
    for (std::size_t i = 1; i + 1 < face.loop.size(); ++i) term(face.loop[0], face.loop[i], face.loop[i + 1]);
  }
}

template <class T>
T fan_term(const std::vector<Vector3T<T>>& y, std::uint32_t a, std::uint32_t b, std::uint32_t d) {
  return detail::dot(y[a], detail::cross(y[b], y[d]));
}

template <class T>
T six_volume(const HalfspacePolyhedron& h, const std::vector<Vector3T<T>>& x) {
  T sum(0);
  if (x.empty()) return sum;
  const std::vector<Vector3T<T>> y = from_apex(x);
  for_each_fan_triangle(h, [&](std::uint32_t a, std::uint32_t b, std::uint32_t d) { sum = sum + fan_term(y, a, b, d); });
  return sum;
}

// The double volume V~ is kept when certified within volume_relative_tolerance of |V|, or within
// volume_tolerance R^3, R the largest frame coordinate of the polyhedron's vertices and of the
// points its planes are through: for an intersection, input points of the pair, so R is at most
// the largest extent s of the pair's bounding box. 2^-31 and 2^-41 are below half the robustness
// harness's 1e-9 relative and 1e-12 s^3 (robustness_tests/pair3d_queries.hpp), so two volumes of
// one pair, Filtered's and Exact's or (a, b)'s and (b, a)'s, agree within those.
constexpr double volume_relative_tolerance = 0x1p-31;
constexpr double volume_tolerance = 0x1p-41;

// A lower bound on the largest frame coordinate of the points h's planes are through (planes
// given by coefficients have none): each difference rounded once, within eps of it.
double plane_point_extent(const HalfspacePolyhedron& h, const Point3& o) {
  double out = 0.0;
  for (const Plane3& plane : h.planes()) {
    if (plane.kind != Plane3::Kind::through_points) continue;
    for (const Point3& p : plane.points) out = std::max(out, max_abs(detail::difference3<double>(p, o)));
  }
  return (1.0 - 0x1p-52) * out;
}

// The volume from the double vertices x (every coordinate within tau of the exact vertex's,
// FrameCoordinates::error), or nullopt when its bound exceeds both tolerances. With u =
// 2^-52 (any rounding mode), T fan triangles, y~ the rounded differences, L the sides of their
// bounding box, S the exact six times the volume and S~ the computed sum:
//   * the vertices: S is a cubic in the vertices, the same for any apex (the fan triangles of
//     the faces close a surface), and its gradient in vertex v is twice the sum of the area
//     vectors of the triangles around v, so the linear part of S(x~) - S(x) is at most
//     2 sqrt 3 tau sum_t 3 A_t = 6 sqrt 3 tau A, A the surface area of the exact polyhedron, at
//     most its bounding box's, 2 (Lx Ly + Ly Lz + Lz Lx) with each L widened by 2 tau. The
//     quadratic and cubic parts of each term, det(a + alpha, ...) with |alpha| <= 2 tau per
//     coordinate, are at most 3 * 6 (2 tau)^2 L + 6 (2 tau)^3 = 72 tau^2 L + 48 tau^3;
//   * the rounding of a term: three differences, the cross product (a product, a difference)
//     and the dot product (a product, two sums) make at most 8 roundings on each of the six
//     products of det, so the term is within 9u m_a m_b m_d of det(y_a, y_b, y_d) with m = |y~|_1
//     (covering the rounding of m itself); where a product underflows it loses at most
//     2^-1074, multiplied by at most L in the dot product: (6 L + 3) 2^-1074 per term, taken
//     twice to cover the underflow of the bound's own products;
//   * the sum of the terms: within T u sum |term| (recursive summation);
//   * V = S~ / 6: one more rounding, u |V|.
// The bound is itself computed in double from non-negative terms, on the rounded y~; the factor
// 1 + 2^-40 covers those roundings.
std::optional<double> certified_volume(const HalfspacePolyhedron& h, const Point3& o, const FrameCoordinates& frame) {
  const std::vector<Vector3T<double>> y = from_apex(frame.x);
  std::vector<double> m;
  m.reserve(y.size());
  Vector3T<double> lo{0, 0, 0}, hi{0, 0, 0};
  for (const Vector3T<double>& v : y) {
    m.push_back(std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z));
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  double sum = 0.0, magnitude = 0.0, abs_sum = 0.0, terms = 0.0;
  for_each_fan_triangle(h, [&](std::uint32_t a, std::uint32_t b, std::uint32_t d) {
    const double t = fan_term(y, a, b, d);
    sum += t;
    abs_sum += std::fabs(t);
    magnitude += m[a] * m[b] * m[d];
    terms += 1.0;
  });
  const double tau = *std::max_element(frame.error.begin(), frame.error.end());
  const double lx = hi.x - lo.x + 2 * tau, ly = hi.y - lo.y + 2 * tau, lz = hi.z - lo.z + 2 * tau;
  const double l = std::max({lx, ly, lz});
  const double area = 2 * (lx * ly + ly * lz + lz * lx);
  const double vertices = 6 * std::sqrt(3.0) * tau * area + terms * (72 * tau * tau * l + 48 * tau * tau * tau);
  const double rounding = 9 * 0x1p-52 * magnitude + terms * (6 * l + 3) * 0x1p-1073 + terms * 0x1p-52 * abs_sum;
  const double volume = sum / 6.0;
  const double bound = bound_rounding_margin * ((vertices + rounding) / 6.0 + 0x1p-52 * std::fabs(volume));
  if (bound <= volume_relative_tolerance * (std::fabs(volume) - bound)) return volume;
  const double r = std::max(frame.extent, plane_point_extent(h, o));
  if (bound <= volume_tolerance * r * r * r) return volume;
  return std::nullopt;
}

ExactRational exact_volume(const HalfspacePolyhedron& h) {
  return six_volume(h, exact_frame_coordinates(h, h.frame_origin())) / 6;
}

// The lazy stage of the Exact volume: the exact volume's formula evaluated in DoubleDouble
// with a running error bound (BoundedDD), rounded when the bound settles the nearest double.
using detail::DoubleDouble;
using BoundedDD = detail::RunningErrorOf<DoubleDouble>;

// A lower bound on |v|: |lo| <= 2^-53 |hi| for a normalized DoubleDouble, and the product below
// rounds up by at most 2^-53 relative.
double magnitude_lower_bound(const DoubleDouble& v) { return std::fabs(v.hi) * (1.0 - 0x1p-50); }

// An implicit vertex's coordinate X = S / D from the bounded S and D of Cramer's rule: the
// quotient q = q0 + q1 refined once by its residual, with the bound
//   |q - X| <= (|S - q D| + ES + |q| ED) / (|D| - ED)
// (X - q = (S* - q D*) / D* for the exact S*, D*, which are within ES, ED of S, D), where
// |S - q D| is bounded by evaluating it in BoundedDD. Nullopt when |D| <= ED.
std::optional<BoundedDD> bounded_quotient(const BoundedDD& s, const BoundedDD& d) {
  const double ed = bound_rounding_margin * d.error;
  const double d_low = magnitude_lower_bound(d.value);
  if (!(d_low > ed) || !s.finite() || !d.finite()) return std::nullopt;
  const double q0 = s.value.hi / d.value.hi;
  const DoubleDouble r0 = s.value - DoubleDouble(q0) * d.value;
  const DoubleDouble q = DoubleDouble::fast_two_sum(q0, r0.hi / d.value.hi);
  const BoundedDD residual = BoundedDD(s.value, 0.0) - BoundedDD(q, 0.0) * BoundedDD(d.value, 0.0);
  const double numerator =
      residual.magnitude() + residual.error + s.error + q.magnitude() * d.error;
  return BoundedDD(q, bound_rounding_margin * bound_rounding_margin * numerator / (d_low - ed));
}

// An exact Mpzf number as a BoundedDD: hi its rounding, lo the midpoint of an enclosure of the
// exact remainder x - hi, the error that enclosure's width.
BoundedDD bounded_of(const CGAL::Mpzf& x) {
  const double hi = CGAL::to_double(x);
  if (!std::isfinite(hi)) return BoundedDD(hi);
  const auto [low, high] = CGAL::to_interval(x - CGAL::Mpzf(hi));
  return BoundedDD(DoubleDouble::fast_two_sum(hi, 0.5 * low + 0.5 * high), high - low);
}

// An implicit vertex accurate to `accuracy` times its largest coordinate. Cramer's rule in
// BoundedDD first (about 2^-100 on ordinary planes); where three nearly dependent planes leave
// it less accurate (or undecided), det X and det are evaluated exactly in CGAL::Mpzf and
// divided in BoundedDD (about 2^-104). Nullopt when even then the quotient is not certified.
std::optional<Vector3T<BoundedDD>> bounded_implicit_vertex(
    const HalfspacePolyhedron& h, const HalfspacePolyhedron::Vertex& v,
    const std::vector<detail::PlaneCoefficients<BoundedDD>>& planes, const Point3& o, double accuracy) {
  const auto divide = [](const auto& x) -> std::optional<Vector3T<BoundedDD>> {
    const auto px = bounded_quotient(x.scaled.x, x.det);
    const auto py = bounded_quotient(x.scaled.y, x.det);
    const auto pz = bounded_quotient(x.scaled.z, x.det);
    if (!px || !py || !pz) return std::nullopt;
    return Vector3T<BoundedDD>{*px, *py, *pz};
  };
  const auto accurate = [accuracy](const Vector3T<BoundedDD>& p) {
    const double size = std::max({p.x.magnitude(), p.y.magnitude(), p.z.magnitude()});
    return std::max({p.x.error, p.y.error, p.z.error}) <= accuracy * size;
  };
  const auto x = detail::three_plane_point(planes[v.planes[0]], planes[v.planes[1]], planes[v.planes[2]]);
  if (const auto p = divide(x); p && accurate(*p)) return p;
  using T = CGAL::Mpzf;
  const auto e = detail::three_plane_point(detail::plane_coefficients<T>(h.planes()[v.planes[0]], o),
                                           detail::plane_coefficients<T>(h.planes()[v.planes[1]], o),
                                           detail::plane_coefficients<T>(h.planes()[v.planes[2]], o));
  return divide(detail::HomogeneousPoint<BoundedDD>{
      {bounded_of(e.scaled.x), bounded_of(e.scaled.y), bounded_of(e.scaled.z)}, bounded_of(e.det)});
}

// Every vertex in the frame of o in BoundedDD: an input point's difference, an implicit point
// by bounded_implicit_vertex to `accuracy`. Nullopt when a vertex is not certified.
std::optional<std::vector<Vector3T<BoundedDD>>> bounded_frame_coordinates(const HalfspacePolyhedron& h,
                                                                          const Point3& o, double accuracy) {
  std::vector<detail::PlaneCoefficients<BoundedDD>> planes;
  planes.reserve(h.planes().size());
  for (const Plane3& plane : h.planes()) planes.push_back(detail::plane_coefficients<BoundedDD>(plane, o));
  std::vector<Vector3T<BoundedDD>> out;
  out.reserve(h.vertices().size());
  for (const HalfspacePolyhedron::Vertex& v : h.vertices()) {
    if (v.input) {
      out.push_back(detail::difference3<BoundedDD>(v.point, o));
      continue;
    }
    const auto x = bounded_implicit_vertex(h, v, planes, o, accuracy);
    if (!x) return std::nullopt;
    out.push_back(*x);
  }
  return out;
}

// w > 0 for certain: its value exceeds its bound plus `extra`.
bool certainly_positive(const BoundedDD& w, double extra) {
  return w.finite() && w.value.hi > 0.0 &&
         magnitude_lower_bound(w.value) > bound_rounding_margin * (w.error + extra);
}

// The double nearest to V = V6 / 6 when the bounded V6 settles it. The candidate r is V6's
// value divided by 6 with one correction by its remainder (within an ulp or so of V); r is the
// answer when V lies strictly between the midpoints of r and its two neighbours, i.e.
// 6 m- < V6 < 6 m+, each side decided by certainly_positive; the walk steps to the neighbour
// while V6 is certainly beyond a midpoint. A tie or a near-tie (neither side certain), a
// subnormal or non-finite candidate: nullopt.
std::optional<double> nearest_double_of_sixth(const BoundedDD& v6) {
  if (!v6.finite()) return std::nullopt;
  const double q0 = v6.value.hi / 6.0;
  const DoubleDouble remainder = v6.value - DoubleDouble::two_product(q0, 6.0);
  double r = q0 + remainder.hi / 6.0;
  const auto six_midpoint = [](double a, double b) {  // 3 (a + b), a + b exact in two_sum
    return BoundedDD(DoubleDouble::two_sum(a, b), 0.0) * BoundedDD(3.0);
  };
  for (int steps = 0; steps < 4; ++steps) {
    const double up = std::nextafter(r, HUGE_VAL), down = std::nextafter(r, -HUGE_VAL);
    if (!std::isnormal(r) || !std::isfinite(up) || !std::isfinite(down)) return std::nullopt;
    const BoundedDD above = six_midpoint(r, up) - v6;
    const BoundedDD below = v6 - six_midpoint(r, down);
    const bool under_up = certainly_positive(above, 0.0), over_down = certainly_positive(below, 0.0);
    if (under_up && over_down) return r;
    if (under_up && certainly_positive(BoundedDD(-below.value, below.error), 0.0)) {
      r = down;
    } else if (over_down && certainly_positive(BoundedDD(-above.value, above.error), 0.0)) {
      r = up;
    } else {
      return std::nullopt;
    }
  }
  return std::nullopt;
}

// The Exact volume: the lazy stage, else the exact rational volume rounded once.
double rounded_exact_volume(const HalfspacePolyhedron& h) {
  if (const std::optional<double> lazy = detail::lazily_rounded_volume(h)) return *lazy;
  return detail::NumberOps<ExactRational>::to_double(exact_volume(h));
}

}  // namespace

template <NumberPolicy Policy>
std::vector<Sign> HalfspacePolyhedron::sides(const Plane3& s) const {
  std::vector<Sign> out(vertices_.size());
  if constexpr (Policy::kind == PolicyKind::float_) {
    for (std::uint32_t v = 0; v < out.size(); ++v) out[v] = side<Policy>(v, s);
  } else {
    // The stages of side_of_plane(s, p, q, r) (plane.hpp), the double filter on coefficients in
    // the frame of the polyhedron (any frame gives the same exact sign).
    const Point3 o = frame_origin();
    const detail::PlaneCoefficients<Bounded> cs = detail::plane_coefficients<Bounded>(s, o);
    std::vector<std::optional<detail::PlaneCoefficients<Bounded>>> cache(planes_.size());
    const auto coefficients = [&](std::uint32_t i) -> const detail::PlaneCoefficients<Bounded>& {
      if (!cache[i]) cache[i] = detail::plane_coefficients<Bounded>(planes_[i], o);
      return *cache[i];
    };
    for (std::uint32_t v = 0; v < out.size(); ++v) {
      const Vertex& vertex = vertices_[v];
      if (vertex.input) {
        out[v] = side_of_plane<Policy>(s, vertex.point);
        continue;
      }
      const auto [i, j, k] = vertex.planes;
      const Plane3 &p = planes_[i], &q = planes_[j], &r = planes_[k];
      if (s == p || s == q || s == r) {
        out[v] = Sign::zero;
        continue;
      }
      detail::count_call(PredicateKind::plane_side);
      const Bounded value = detail::three_plane_side_of_coefficients(cs, coefficients(i), coefficients(j), coefficients(k));
      const double bound = bound_rounding_margin * value.error;
      Sign staged;
      if (std::isfinite(value.value) && std::isfinite(bound) && std::fabs(value.value) > bound) {
        staged = sign_of(value.value);
      } else {
        staged = detail::three_plane_side_interval_exact(s, p, q, r);
      }
      if constexpr (Policy::kind == PolicyKind::checked) {
        const Sign exact = detail::three_plane_side_exact(s, p, q, r);
        if (staged != exact) {
          const Plane3* planes[] = {&s, &p, &q, &r};
          detail::plane_side_disagrees(planes, 4, nullptr, staged, exact);
        }
      }
      out[v] = staged;
    }
  }
  return out;
}

template <NumberPolicy Policy>
std::vector<Point3> HalfspacePolyhedron::vertex_coordinates() const {
  const Point3 o = frame_origin();
  std::vector<Point3> out;
  out.reserve(vertices_.size());
  if constexpr (Policy::kind == PolicyKind::exact) {
    const auto x = exact_frame_coordinates(*this, o);
    const auto round = [](const ExactRational& q) { return detail::NumberOps<ExactRational>::to_double(q); };
    for (const auto& p : x) {
      out.push_back({round(p.x + ExactRational(o.x)), round(p.y + ExactRational(o.y)), round(p.z + ExactRational(o.z))});
    }
  } else {
    const auto x = frame_coordinates(*this, o).x;
    for (std::size_t v = 0; v < vertices_.size(); ++v) {
      out.push_back(vertices_[v].input ? vertices_[v].point : Point3{o.x + x[v].x, o.y + x[v].y, o.z + x[v].z});
    }
  }
  return out;
}

template <NumberPolicy Policy>
double HalfspacePolyhedron::volume() const {
  if (empty()) return 0.0;
  if constexpr (Policy::kind == PolicyKind::exact) {
    return rounded_exact_volume(*this);
  } else if constexpr (Policy::kind == PolicyKind::float_) {
    return six_volume(*this, frame_coordinates(*this, frame_origin()).x) / 6.0;
  } else {
    // Three stages: the certified double vertices; where the volume's bound is too wide, the
    // loosely certified ones from their exact homogeneous coordinates; the exact volume.
    const Point3 o = frame_origin();
    FrameCoordinates frame = frame_coordinates(*this, o);
    if (const auto volume = certified_volume(*this, o, frame)) return *volume;
    sharpen(*this, o, frame);
    if (const auto volume = certified_volume(*this, o, frame)) return *volume;
    return rounded_exact_volume(*this);
  }
}

#define ROCKCONTACT_INSTANTIATE(P)                                                 \
  template std::vector<Sign> HalfspacePolyhedron::sides<P>(const Plane3&) const;   \
  template std::vector<Point3> HalfspacePolyhedron::vertex_coordinates<P>() const; \
  template double HalfspacePolyhedron::volume<P>() const;
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

namespace detail {

// Two tries: vertices to 2^-80 (Mpzf only for nearly dependent planes), enough unless the
// volume is small against the polyhedron's extent cubed; then every implicit vertex from Mpzf,
// whose 2^-104 leaves the fan sum's own rounding as the limit.
std::optional<double> lazily_rounded_volume(const HalfspacePolyhedron& h) {
  if (h.empty()) return 0.0;
  for (const double accuracy : {0x1p-80, 0.0}) {
    const auto x = bounded_frame_coordinates(h, h.frame_origin(), accuracy);
    if (!x) continue;
    if (const std::optional<double> v = nearest_double_of_sixth(six_volume(h, *x))) return v;
  }
  return std::nullopt;
}

std::string exact_volume_string(const HalfspacePolyhedron& p) {
  if (p.empty()) return "0";
  ExactRational v = exact_volume(p);
  v.canonicalize();
  return v.get_str();
}

}  // namespace detail
}  // namespace rockcontact::kernel
