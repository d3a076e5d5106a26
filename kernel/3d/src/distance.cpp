#include "rockcontact/kernel/3d/distance.hpp"

#include <vector>

#include "local_vector.hpp"
#include "rockcontact/kernel/3d/overlap.hpp"
#include "rockcontact/kernel/core/detail/exact_number.hpp"

namespace rockcontact::kernel {
namespace {

using detail::Vector3;

// The best candidate so far: a point of A, a point of B and their squared distance.
template <class FT>
struct Closest {
  bool found = false;
  FT distance2{};
  Vector3<FT> on_a{}, on_b{};

  void offer(const Vector3<FT>& p, const Vector3<FT>& q) {
    const Vector3<FT> d = q - p;
    const FT d2 = detail::dot(d, d);
    if (!found || d2 < distance2) *this = {true, d2, p, q};
  }
};

// Vertices of `q` against the faces of `p` whose plane's foot of the vertex lies in the face
// (on the inner side of, or on, each edge's plane perpendicular to the face).
template <class FT, class Offer>
void vertex_face(const ConvexPolyhedron& p, const std::vector<Vector3<FT>>& pv,
                 const std::vector<Vector3<FT>>& qv, Offer offer) {
  for (const auto& face : p.faces()) {
    const Vector3<FT>& f0 = pv[face[0]];
    const Vector3<FT> n = detail::cross(pv[face[1]] - f0, pv[face[2]] - f0);
    const FT nn = detail::dot(n, n);
    if (!(nn > 0)) continue;  // only in double, if |n|^2 underflows (faces below ~1e-80 m)
    for (const Vector3<FT>& x : qv) {
      bool inside = true;
      for (std::size_t i = 0; i < face.size() && inside; ++i) {
        const Vector3<FT>& e0 = pv[face[i]];
        const Vector3<FT>& e1 = pv[face[(i + 1) % face.size()]];
        inside = detail::dot(n, detail::cross(e1 - e0, x - e0)) >= 0;
      }
      if (inside) offer(x - FT(detail::dot(x - f0, n) / nn) * n, x);
    }
  }
}

// Vertices of `q` against the edges of `p`, the foot clamped to the edge.
template <class FT, class Offer>
void vertex_edge(const ConvexPolyhedron& p, const std::vector<Vector3<FT>>& pv,
                 const std::vector<Vector3<FT>>& qv, Offer offer) {
  for (const auto& [i, j] : p.edges()) {
    const Vector3<FT> e = pv[j] - pv[i];
    const FT ee = detail::dot(e, e);
    if (!(ee > 0)) continue;  // only in double, if |e|^2 underflows (edges below ~1e-150 m)
    for (const Vector3<FT>& x : qv) {
      FT t = detail::dot(x - pv[i], e) / ee;
      if (t < 0) t = 0;
      if (t > 1) t = 1;
      offer(pv[i] + t * e, x);
    }
  }
}

// Edge pairs whose lines' closest points lie inside both edges: with e, f the edge vectors and
// w = p0 - q0, the parameters minimising |w + s e - t f|^2 solve
//   [e.e  -e.f] [s]   [-e.w]
//   [e.f  -f.f] [t] = [-f.w],   det = (e.f)^2 - (e.e)(f.f) < 0 unless parallel.
template <class FT>
void edge_edge(const ConvexPolyhedron& a, const std::vector<Vector3<FT>>& av, const ConvexPolyhedron& b,
               const std::vector<Vector3<FT>>& bv, Closest<FT>& best) {
  for (const auto& [i, j] : a.edges()) {
    const Vector3<FT> e = av[j] - av[i];
    const FT ee = detail::dot(e, e);
    for (const auto& [k, l] : b.edges()) {
      const Vector3<FT> f = bv[l] - bv[k];
      const Vector3<FT> w = av[i] - bv[k];
      const FT ef = detail::dot(e, f), ff = detail::dot(f, f), ew = detail::dot(e, w), fw = detail::dot(f, w);
      const FT det = ee * ff - ef * ef;
      if (!(det > 0)) continue;
      const FT s = (ef * fw - ff * ew) / det;
      const FT t = (ee * fw - ef * ew) / det;
      if (s < 0 || s > 1 || t < 0 || t > 1) continue;
      best.offer(av[i] + s * e, bv[k] + t * f);
    }
  }
}

template <class FT>
Separation closest_points(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  const Point3 origin = a[0];
  const auto av = detail::local_vertices<FT>(a, origin);
  const auto bv = detail::local_vertices<FT>(b, origin);
  Closest<FT> best;
  const auto a_to_b = [&](const Vector3<FT>& on_a, const Vector3<FT>& on_b) { best.offer(on_a, on_b); };
  const auto b_to_a = [&](const Vector3<FT>& on_b, const Vector3<FT>& on_a) { best.offer(on_a, on_b); };
  vertex_face(a, av, bv, a_to_b);
  vertex_face(b, bv, av, b_to_a);
  vertex_edge(a, av, bv, a_to_b);
  vertex_edge(b, bv, av, b_to_a);
  edge_edge(a, av, b, bv, best);
  using Ops = detail::NumberOps<FT>;
  return {Ops::to_double(Ops::sqrt(best.distance2)), detail::global(best.on_a, origin),
          detail::global(best.on_b, origin)};
}

}  // namespace

template <NumberPolicy Policy>
std::optional<Separation> separation(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  if (classify_overlap<Policy>(a, b) != Overlap::separate) return std::nullopt;
  return closest_points<detail::ConstructionType<Policy>>(a, b);
}

#define ROCKCONTACT_INSTANTIATE(P) \
  template std::optional<Separation> separation<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
