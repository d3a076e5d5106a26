// The intersection polyhedron of two convex polyhedra (intersection.hpp).

#include "rockcontact/kernel/3d/intersection.hpp"

#include "rockcontact/kernel/3d/plane.hpp"
#include "rockcontact/kernel/3d/plane_cut.hpp"
#include "rockcontact/kernel/core/predicate_scope.hpp"

namespace rockcontact::kernel {

template <NumberPolicy Policy>
HalfspacePolyhedron intersection(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  const PredicateScope scope;
  HalfspacePolyhedron result(a);
  for (std::size_t f = 0; f < b.faces().size() && !result.empty(); ++f) {
    result = clip<Policy>(result, Plane3::of_face(b, f));
  }
  return result;
}

template <NumberPolicy Policy>
double intersection_volume(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  return intersection<Policy>(a, b).template volume<Policy>();
}

#define ROCKCONTACT_INSTANTIATE(P)                                                                 \
  template HalfspacePolyhedron intersection<P>(const ConvexPolyhedron&, const ConvexPolyhedron&); \
  template double intersection_volume<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
