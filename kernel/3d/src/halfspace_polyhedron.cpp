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
// frame coordinate of its vertices, bounded from below): a volume then moves by at most about
// area * 2^-42 * extent, below the 1e-12 scale^3 the contact3d README allows near zero and far
// below its 1e-9 relative tolerance.
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

// Every vertex in the frame of o in double: an input point's difference rounded once, an
// implicit point certified in double, else from its exact homogeneous coordinates.
std::vector<Vector3T<double>> frame_coordinates(const HalfspacePolyhedron& h, const Point3& o) {
  std::vector<detail::PlaneCoefficients<Bounded>> planes;
  planes.reserve(h.planes().size());
  for (const Plane3& plane : h.planes()) planes.push_back(detail::plane_coefficients<Bounded>(plane, o));
  // First pass: input points and candidate implicit points. The extent is a lower bound on the
  // largest frame coordinate of the exact vertices, |x| - error over the candidates, so a
  // badly conditioned candidate cannot widen the tolerance of the others.
  std::vector<std::optional<CertifiedPoint>> candidates(h.vertices().size());
  double extent = 0.0;
  const auto widen = [&](const CertifiedPoint& c) {
    extent = std::max({extent, std::fabs(c.x.x) - c.error, std::fabs(c.x.y) - c.error, std::fabs(c.x.z) - c.error});
  };
  for (std::size_t i = 0; i < h.vertices().size(); ++i) {
    const HalfspacePolyhedron::Vertex& v = h.vertices()[i];
    if (v.input) {
      candidates[i] = CertifiedPoint{detail::difference3<double>(v.point, o), 0.0};
    } else {
      candidates[i] = certified_point(planes[v.planes[0]], planes[v.planes[1]], planes[v.planes[2]]);
    }
    if (candidates[i]) widen(*candidates[i]);
  }
  std::vector<Vector3T<double>> out;
  out.reserve(h.vertices().size());
  for (std::size_t i = 0; i < h.vertices().size(); ++i) {
    const auto& c = candidates[i];
    const bool certified = c && c->error <= vertex_tolerance * extent;
    out.push_back(certified ? c->x : exact_quotient_point(h, h.vertices()[i], o));
  }
  return out;
}

// Six times the volume: the divergence theorem with the faces fanned into triangles
// (x0, x_i, x_{i+1}), each counter-clockwise from outside, against the apex c = the first
// vertex: sum of det(x0 - c, x_i - c, x_{i+1} - c).
template <class T>
T six_volume(const HalfspacePolyhedron& h, const std::vector<Vector3T<T>>& x) {
  T sum(0);
  if (x.empty()) return sum;
  const Vector3T<T>& c = x.front();
  const auto from_c = [&](std::uint32_t v) {
    return Vector3T<T>{T(x[v].x - c.x), T(x[v].y - c.y), T(x[v].z - c.z)};
  };
  for (const HalfspacePolyhedron::Face& face : h.faces()) {
    const Vector3T<T> a = from_c(face.loop[0]);
    for (std::size_t i = 1; i + 1 < face.loop.size(); ++i) {
      sum = sum + detail::dot(a, detail::cross(from_c(face.loop[i]), from_c(face.loop[i + 1])));
    }
  }
  return sum;
}

ExactRational exact_volume(const HalfspacePolyhedron& h) {
  return six_volume(h, exact_frame_coordinates(h, h.frame_origin())) / 6;
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
    const auto x = frame_coordinates(*this, o);
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
    return detail::NumberOps<ExactRational>::to_double(exact_volume(*this));
  } else {
    return six_volume(*this, frame_coordinates(*this, frame_origin())) / 6.0;
  }
}

#define ROCKCONTACT_INSTANTIATE(P)                                                 \
  template std::vector<Sign> HalfspacePolyhedron::sides<P>(const Plane3&) const;   \
  template std::vector<Point3> HalfspacePolyhedron::vertex_coordinates<P>() const; \
  template double HalfspacePolyhedron::volume<P>() const;
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

namespace detail {

std::string exact_volume_string(const HalfspacePolyhedron& p) {
  if (p.empty()) return "0";
  ExactRational v = exact_volume(p);
  v.canonicalize();
  return v.get_str();
}

}  // namespace detail
}  // namespace rockcontact::kernel
