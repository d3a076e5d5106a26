#include "rockcontact/kernel/3d/overlap.hpp"

#include "rockcontact/kernel/3d/predicates.hpp"

namespace rockcontact::kernel {
namespace {

// What a candidate plane says about the pair.
enum class Gap { none, zero, positive };  // not a separating plane / weakly / strictly

// The plane of a face of `p` against the vertices of `q`.
template <NumberPolicy Policy>
Gap face_gap(const ConvexPolyhedron& p, const ConvexPolyhedron::Face& face, const ConvexPolyhedron& q) {
  const Point3 &f0 = p[face[0]], &f1 = p[face[1]], &f2 = p[face[2]];
  Gap gap = Gap::positive;
  for (const Point3& x : q.vertices()) {
    const Sign s = orient3d<Policy>(f0, f1, f2, x);
    if (s == Sign::negative) return Gap::none;
    if (s == Sign::zero) gap = Gap::zero;
  }
  return gap;
}

// The common sign of triple(e, f, origin -> x) over the vertices x of `p`, or zero when the
// plane through origin with normal e x f cuts p (both signs occur). Never all zero: p is solid.
template <NumberPolicy Policy>
Sign side(const Point3& e0, const Point3& e1, const Point3& f0, const Point3& f1, const Point3& origin,
          const ConvexPolyhedron& p) {
  Sign side = Sign::zero;
  for (const Point3& x : p.vertices()) {
    const Sign s = triple_sign<Policy>(e0, e1, f0, f1, origin, x);
    if (s == Sign::zero) continue;
    if (side == Sign::zero) {
      side = s;
    } else if (s != side) {
      return Sign::zero;
    }
  }
  return side;
}

template <NumberPolicy Policy>
Gap edge_gap(const ConvexPolyhedron& a, const ConvexPolyhedron::Edge& ea, const ConvexPolyhedron& b,
             const ConvexPolyhedron::Edge& eb) {
  const Point3 &e0 = a[ea.first], &e1 = a[ea.second], &f0 = b[eb.first], &f1 = b[eb.second];
  if (parallel<Policy>(e0, e1, f0, f1)) return Gap::none;
  const Sign side_a = side<Policy>(e0, e1, f0, f1, e0, a);
  if (side_a == Sign::zero) return Gap::none;
  const Sign side_b = side<Policy>(e0, e1, f0, f1, f0, b);
  if (side_b != -side_a) return Gap::none;
  const Sign gap = side_b * triple_sign<Policy>(e0, e1, f0, f1, e0, f0);
  if (gap == Sign::negative) return Gap::none;
  return gap == Sign::zero ? Gap::zero : Gap::positive;
}

}  // namespace

template <NumberPolicy Policy>
Overlap classify_overlap(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  bool touching = false;
  const auto weigh = [&](Gap gap) {
    touching |= gap == Gap::zero;
    return gap == Gap::positive;
  };
  for (const auto& face : a.faces()) {
    if (weigh(face_gap<Policy>(a, face, b))) return Overlap::separate;
  }
  for (const auto& face : b.faces()) {
    if (weigh(face_gap<Policy>(b, face, a))) return Overlap::separate;
  }
  for (const auto& ea : a.edges()) {
    for (const auto& eb : b.edges()) {
      if (weigh(edge_gap<Policy>(a, ea, b, eb))) return Overlap::separate;
    }
  }
  return touching ? Overlap::touch : Overlap::overlap;
}

#define ROCKCONTACT_INSTANTIATE(P) \
  template Overlap classify_overlap<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
