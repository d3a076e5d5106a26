#include "rockcontact/kernel/3d/overlap.hpp"

#include "rockcontact/kernel/3d/detail/separating_plane.hpp"

namespace rockcontact::kernel {

template <NumberPolicy Policy>
Overlap classify_overlap(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  using detail::Gap;
  bool touching = false;
  const auto weigh = [&](Gap gap) {
    touching |= gap == Gap::zero;
    return gap == Gap::positive;
  };
  for (const auto& face : a.faces()) {
    if (weigh(detail::face_gap<Policy>(a, face, b))) return Overlap::separate;
  }
  for (const auto& face : b.faces()) {
    if (weigh(detail::face_gap<Policy>(b, face, a))) return Overlap::separate;
  }
  for (const auto& ea : a.edges()) {
    for (const auto& eb : b.edges()) {
      if (weigh(detail::edge_gap<Policy>(a, ea, b, eb))) return Overlap::separate;
    }
  }
  return touching ? Overlap::touch : Overlap::overlap;
}

#define ROCKCONTACT_INSTANTIATE(P) \
  template Overlap classify_overlap<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
