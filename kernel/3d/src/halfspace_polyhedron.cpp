// HalfspacePolyhedron (halfspace_polyhedron.hpp): the constructions, generic over the number
// type (double, or CGAL::Exact_rational under Exact) on the plane formulas of
// detail/plane_formulas.hpp.

#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"

#include <cassert>
#include <string>
#include <type_traits>
#include <utility>

#include "rockcontact/kernel/3d/detail/halfspace_exact.hpp"
#include "rockcontact/kernel/3d/detail/plane_formulas.hpp"
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

// Every vertex in the frame of o: an input point's difference (rounded once in double, exact in
// rationals), an implicit point by Cramer's rule (detail::three_plane_point) on the planes'
// coefficients, computed once per plane.
template <class T>
std::vector<Vector3T<T>> frame_coordinates(const HalfspacePolyhedron& h, const Point3& o) {
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
    out.push_back({T(x.scaled.x / x.det), T(x.scaled.y / x.det), T(x.scaled.z / x.det)});
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
  return six_volume(h, frame_coordinates<ExactRational>(h, h.frame_origin())) / 6;
}

}  // namespace

template <NumberPolicy Policy>
std::vector<Point3> HalfspacePolyhedron::vertex_coordinates() const {
  const Point3 o = frame_origin();
  std::vector<Point3> out;
  out.reserve(vertices_.size());
  if constexpr (Policy::kind == PolicyKind::exact) {
    const auto x = frame_coordinates<ExactRational>(*this, o);
    const auto round = [](const ExactRational& q) { return detail::NumberOps<ExactRational>::to_double(q); };
    for (const auto& p : x) {
      out.push_back({round(p.x + ExactRational(o.x)), round(p.y + ExactRational(o.y)), round(p.z + ExactRational(o.z))});
    }
  } else {
    const auto x = frame_coordinates<double>(*this, o);
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
    return six_volume(*this, frame_coordinates<double>(*this, frame_origin())) / 6.0;
  }
}

#define ROCKCONTACT_INSTANTIATE(P)                                                 \
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
