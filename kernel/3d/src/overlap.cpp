#include "rockcontact/kernel/3d/overlap.hpp"

#include "rockcontact/kernel/3d/detail/separating_plane.hpp"

namespace rockcontact::kernel {

// Only the edge pairs that may give a facet of the Minkowski difference are tested
// (detail::MinkowskiEdgePairs): the verdict is the one over all candidates, while an overlapping
// pair costs F E predicates for the pruning signs instead of E_A E_B (V_A + V_B).
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
  const detail::MinkowskiEdgePairs<Policy> pairs(a, b);
  for (std::size_t i = 0; i < a.edges().size(); ++i) {
    for (std::size_t j = 0; j < b.edges().size(); ++j) {
      if (pairs.may_be_facet(i, j) && weigh(detail::edge_gap<Policy>(a, a.edges()[i], b, b.edges()[j]))) {
        return Overlap::separate;
      }
    }
  }
  return touching ? Overlap::touch : Overlap::overlap;
}

#define ROCKCONTACT_INSTANTIATE(P) \
  template Overlap classify_overlap<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
