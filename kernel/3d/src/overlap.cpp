#include "rockcontact/kernel/3d/overlap.hpp"

#include "rockcontact/kernel/3d/detail/separating_plane.hpp"

#include <vector>

#include "rockcontact/kernel/3d/predicates.hpp"

namespace rockcontact::kernel {
namespace {

// Signs of (outward normal of facet g of p) . (direction of edge e of q), g-major: the normal of
// g is (g1 - g0) x (g2 - g0), so each is one triple product of input points.
template <NumberPolicy Policy>
std::vector<Sign> normal_dot_edges(const ConvexPolyhedron& p, const ConvexPolyhedron& q) {
  std::vector<Sign> out;
  out.reserve(p.faces().size() * q.edges().size());
  for (const auto& g : p.faces()) {
    for (const auto& [e0, e1] : q.edges()) out.push_back(triple_sign<Policy>(p[g[0]], p[g[1]], p[g[0]], p[g[2]], q[e0], q[e1]));
  }
  return out;
}

}  // namespace

// Edge pairs are pruned on the Gauss map: e x f is a facet normal of the Minkowski difference
// only when the arc of e (between its facets' normals n1, n2) crosses the arc of f negated
// (between -m1 and -m2). With n1 x n2 along e and m1 x m2 along f (ConvexPolyhedron::edge_faces)
// the arcs cross exactly when (m1 . e)(m2 . e) < 0, (n1 . f)(n2 . f) < 0 and (m1 . e)(n2 . f) < 0
// (the great circles cross, and on the arcs rather than at their antipodes). A pair is skipped
// only when one of the three products is strictly positive: a zero keeps it, so every facet of
// the difference stays a candidate and the verdict is the same as over all edge pairs, while an
// overlapping pair costs F E predicates for the signs instead of E_A E_B (V_A + V_B).
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
  const std::vector<Sign> b_normal_a_edge = normal_dot_edges<Policy>(b, a);  // m . e
  const std::vector<Sign> a_normal_b_edge = normal_dot_edges<Policy>(a, b);  // n . f
  const std::size_t edges_a = a.edges().size(), edges_b = b.edges().size();
  for (std::size_t i = 0; i < edges_a; ++i) {
    const auto [n1, n2] = a.edge_faces()[i];
    for (std::size_t j = 0; j < edges_b; ++j) {
      const auto [m1, m2] = b.edge_faces()[j];
      const Sign m1e = b_normal_a_edge[m1 * edges_a + i], m2e = b_normal_a_edge[m2 * edges_a + i];
      const Sign n1f = a_normal_b_edge[n1 * edges_b + j], n2f = a_normal_b_edge[n2 * edges_b + j];
      const bool skip = m1e * m2e == Sign::positive || n1f * n2f == Sign::positive || m1e * n2f == Sign::positive;
      if (!skip && weigh(detail::edge_gap<Policy>(a, a.edges()[i], b, b.edges()[j]))) return Overlap::separate;
    }
  }
  return touching ? Overlap::touch : Overlap::overlap;
}

#define ROCKCONTACT_INSTANTIATE(P) \
  template Overlap classify_overlap<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
