#include "rockcontact/kernel/3d/penetration.hpp"

#include <optional>
#include <vector>

#include "local_vector.hpp"
#include "rockcontact/kernel/3d/detail/separating_plane.hpp"
#include "rockcontact/kernel/3d/overlap.hpp"
#include "rockcontact/kernel/core/detail/exact_number.hpp"

namespace rockcontact::kernel {
namespace {

using detail::Vector3;

template <class FT>
struct MinimumAxis {
  const std::vector<Vector3<FT>>& cp;
  const std::vector<Vector3<FT>>& tp;
  bool found = false;
  FT value{};  // h |h| / |n|^2 of the best candidate
  FT extent{};
  Vector3<FT> normal{};

  // The support extent h(n) of cp - tp.
  FT support_extent(const Vector3<FT>& n) const {
    FT high = detail::dot(cp[0], n), low = detail::dot(tp[0], n);
    for (const auto& a : cp) {
      const FT s = detail::dot(a, n);
      if (s > high) high = s;
    }
    for (const auto& b : tp) {
      const FT s = detail::dot(b, n);
      if (s < low) low = s;
    }
    return high - low;
  }

  void offer(const Vector3<FT>& n) {
    const FT nn = detail::dot(n, n);
    if (!(nn > 0)) return;  // only in double, if |n|^2 underflows: no bound from n
    const FT h = support_extent(n);
    const FT square = h * h;
    const FT v = (h < 0 ? FT(-square) : square) / nn;
    if (!found || v < value) {
      found = true;
      value = v;
      extent = h;
      normal = n;
    }
  }
};

template <class FT>
Vector3<FT> face_normal(const std::vector<Vector3<FT>>& v, const ConvexPolyhedron::Face& face) {
  return detail::cross(v[face[1]] - v[face[0]], v[face[2]] - v[face[0]]);
}

// `pairs` rules out the edge pairs that give no facet of cp - tp: the minimum over the
// remaining candidates is still the minimum over all facet normals.
template <class FT, class EdgePairs>
Penetration minimum_translation(const ConvexPolyhedron& cp, const ConvexPolyhedron& tp, const EdgePairs& pairs) {
  const Point3 origin = cp[0];
  const auto cv = detail::local_vertices<FT>(cp, origin);
  const auto tv = detail::local_vertices<FT>(tp, origin);
  MinimumAxis<FT> best{cv, tv};
  for (const auto& face : cp.faces()) best.offer(face_normal(cv, face));
  for (const auto& face : tp.faces()) best.offer(-face_normal(tv, face));
  for (std::size_t e = 0; e < cp.edges().size(); ++e) {
    const auto [i, j] = cp.edges()[e];
    for (std::size_t f = 0; f < tp.edges().size(); ++f) {
      if (!pairs.may_be_facet(e, f)) continue;
      const auto [k, l] = tp.edges()[f];
      const Vector3<FT> n = detail::cross(cv[j] - cv[i], tv[l] - tv[k]);
      if (detail::is_zero(n)) continue;  // parallel edges: no facet of cp - tp
      best.offer(n);
      best.offer(-n);
    }
  }
  using Ops = detail::NumberOps<FT>;
  const FT length = Ops::sqrt(detail::dot(best.normal, best.normal));
  const FT depth = best.extent > 0 ? Ops::sqrt(best.value) : FT(0);
  return {Ops::to_double(depth),
          {Ops::to_double(best.normal.x / length), Ops::to_double(best.normal.y / length),
           Ops::to_double(best.normal.z / length)}};
}

}  // namespace

template <NumberPolicy Policy>
std::optional<Penetration> penetration(const ConvexPolyhedron& cp, const ConvexPolyhedron& tp) {
  if (classify_overlap<Policy>(cp, tp) != Overlap::overlap) return std::nullopt;
  const detail::MinkowskiEdgePairs<Policy> pairs(cp, tp);
  return minimum_translation<detail::ConstructionType<Policy>>(cp, tp, pairs);
}

#define ROCKCONTACT_INSTANTIATE(P) \
  template std::optional<Penetration> penetration<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
