#pragma once
// The candidate separating planes of two convex polyhedra (overlap.hpp states the method): a
// face plane of one block against the vertices of the other, or the plane through an edge of A
// parallel to an edge of B. Shared by the overlap verdict and the contact set, which needs the
// zero-gap plane itself. Every decision is an exact sign under the staged policies.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/sign.hpp"

namespace rockcontact::kernel::detail {

// What a candidate plane says about the pair.
enum class Gap { none, zero, positive };  // not a separating plane / weakly / strictly

// The plane of a face of `p` against the vertices of `q`.
template <NumberPolicy Policy>
Gap face_gap(const ConvexPolyhedron& p, const ConvexPolyhedron::Face& face, const ConvexPolyhedron& q) {
  const Point3 &f0 = p[face[0]], &f1 = p[face[1]], &f2 = p[face[2]];
  const TripleSigns<Policy> orient(f0, f1, f0, f2);  // orient(f0, x) = orient3d(f0, f1, f2, x)
  Gap gap = Gap::positive;
  for (const Point3& x : q.vertices()) {
    const Sign s = orient(f0, x);
    if (s == Sign::negative) return Gap::none;
    if (s == Sign::zero) gap = Gap::zero;
  }
  return gap;
}

// The common sign of triple(e, f, origin -> x) over the vertices x of `p`, or zero when the
// plane through origin with normal e x f cuts p (both signs occur). Never all zero: p is solid.
// `edge` is the edge of p the plane goes through (origin is its first end): its two ends are on
// the plane by definition, so they are skipped; evaluated, the far end's zero would be an exact
// zero that rounding hides from the filters, sending every such call to the exact stage.
template <NumberPolicy Policy>
Sign side(const Point3& e0, const Point3& e1, const Point3& f0, const Point3& f1, const Point3& origin,
          const ConvexPolyhedron& p, const ConvexPolyhedron::Edge& edge) {
  const TripleSigns<Policy> triple(e0, e1, f0, f1);
  Sign side = Sign::zero;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    if (i == edge.first || i == edge.second) continue;
    const Sign s = triple(origin, p[i]);
    if (s == Sign::zero) continue;
    if (side == Sign::zero) {
      side = s;
    } else if (s != side) {
      return Sign::zero;
    }
  }
  return side;
}

// The plane through edge ea of `a` parallel to edge eb of `b` (normal e x f), when it and its
// parallel through eb support a and b on opposite sides: the sign of the gap between them.
template <NumberPolicy Policy>
Gap edge_gap(const ConvexPolyhedron& a, const ConvexPolyhedron::Edge& ea, const ConvexPolyhedron& b,
             const ConvexPolyhedron::Edge& eb) {
  const Point3 &e0 = a[ea.first], &e1 = a[ea.second], &f0 = b[eb.first], &f1 = b[eb.second];
  if (parallel<Policy>(e0, e1, f0, f1)) return Gap::none;
  const Sign side_a = side<Policy>(e0, e1, f0, f1, e0, a, ea);
  if (side_a == Sign::zero) return Gap::none;
  const Sign side_b = side<Policy>(e0, e1, f0, f1, f0, b, eb);
  if (side_b != -side_a) return Gap::none;
  const Sign gap = side_b * triple_sign<Policy>(e0, e1, f0, f1, e0, f0);
  if (gap == Sign::negative) return Gap::none;
  return gap == Sign::zero ? Gap::zero : Gap::positive;
}

// Edge pairs pruned on the Gauss map: e x f is a facet normal of the Minkowski difference only
// when the arc of e (between its facets' normals n1, n2) crosses the arc of f negated (between
// -m1 and -m2). With n1 x n2 along e and m1 x m2 along f (ConvexPolyhedron::edge_faces) the
// arcs cross exactly when (m1 . e)(m2 . e) < 0, (n1 . f)(n2 . f) < 0 and (m1 . e)(n2 . f) < 0
// (the great circles cross, and on the arcs rather than at their antipodes). A pair is ruled
// out only when one of the three products is strictly positive: a zero keeps it, so every facet
// of the difference stays a candidate. The signs are triple products of input points, one per
// (facet, edge of the other block), computed once: F_B E_A + F_A E_B predicates instead of the
// E_A E_B (V_A + V_B) of testing every pair.
// The sign of (outward normal of one facet, (g1 - g0) x (g2 - g0)) . (an edge's direction),
// exactly: the facet's side test for MinkowskiEdgePairs (contact_constraints.cpp has one that
// takes directions nearly in the facet's plane for in it).
template <NumberPolicy Policy>
class FacetSides {
 public:
  FacetSides(const Point3& g0, const Point3& g1, const Point3& g2) : normal_(g0, g1, g0, g2) {}
  Sign operator()(const Point3& e0, const Point3& e1) const { return normal_(e0, e1); }

 private:
  TripleSigns<Policy> normal_;
};

template <NumberPolicy Policy, template <NumberPolicy> class Sides = FacetSides>
class MinkowskiEdgePairs {
 public:
  MinkowskiEdgePairs(const ConvexPolyhedron& a, const ConvexPolyhedron& b)
      : a_(a), b_(b), m_dot_e_(normal_dot_edges(b, a)), n_dot_f_(normal_dot_edges(a, b)) {}

  // May edge i of a and edge j of b give a facet of the Minkowski difference?
  bool may_be_facet(std::size_t i, std::size_t j) const {
    const auto [n1, n2] = a_.edge_faces()[i];
    const auto [m1, m2] = b_.edge_faces()[j];
    const std::size_t edges_a = a_.edges().size(), edges_b = b_.edges().size();
    const Sign m1e = m_dot_e_[m1 * edges_a + i], m2e = m_dot_e_[m2 * edges_a + i];
    const Sign n1f = n_dot_f_[n1 * edges_b + j], n2f = n_dot_f_[n2 * edges_b + j];
    return m1e * m2e != Sign::positive && n1f * n2f != Sign::positive && m1e * n2f != Sign::positive;
  }

 private:
  // Signs of (outward normal of facet g of p) . (direction of edge e of q), g-major.
  static std::vector<Sign> normal_dot_edges(const ConvexPolyhedron& p, const ConvexPolyhedron& q) {
    std::vector<Sign> out;
    out.reserve(p.faces().size() * q.edges().size());
    for (const auto& g : p.faces()) {
      const Sides<Policy> normal(p[g[0]], p[g[1]], p[g[2]]);
      for (const auto& [e0, e1] : q.edges()) out.push_back(normal(q[e0], q[e1]));
    }
    return out;
  }

  const ConvexPolyhedron& a_;
  const ConvexPolyhedron& b_;
  std::vector<Sign> m_dot_e_;  // b's facet normals against a's edges
  std::vector<Sign> n_dot_f_;  // a's facet normals against b's edges
};

}  // namespace rockcontact::kernel::detail
