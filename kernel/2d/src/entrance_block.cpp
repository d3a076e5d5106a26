#include "rockcontact/kernel/2d/entrance_block.hpp"

#include <algorithm>

#include "rockcontact/kernel/2d/detail/constructions.hpp"
#include "rockcontact/kernel/core/detail/exact_number.hpp"
#include "rockcontact/kernel/2d/predicates.hpp"

namespace rockcontact::kernel {
namespace {

// Lowest vertex, leftmost among the lowest: its outgoing edge has angle in [0, pi).
std::size_t lowest_leftmost(const ConvexPolygon& p) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < p.size(); ++k) {
    if (p[k].y < p[best].y || (p[k].y == p[best].y && p[k].x < p[best].x)) best = k;
  }
  return best;
}

// The same for -A: A's highest vertex, rightmost among the highest.
std::size_t highest_rightmost(const ConvexPolygon& p) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < p.size(); ++k) {
    if (p[k].y > p[best].y || (p[k].y == p[best].y && p[k].x > p[best].x)) best = k;
  }
  return best;
}

// One edge of E(A, B): it starts at the vertex b_j - a_i (+ a0) and runs along B's edge j,
// along -A's edge (a_{i+1} -> a_i), or along both when they are parallel.
struct MergedEdge {
  std::size_t i;  // vertex of A
  std::size_t j;  // vertex of B
  bool along_b;
  bool along_a;
};

// Calls visit(MergedEdge) for every edge of E in CCW order; stops early when visit returns
// false. Equal directions are merged, so E is strictly convex.
template <NumberPolicy Policy, class Visit>
void merge_edges(const ConvexPolygon& a, const ConvexPolygon& b, Visit&& visit) {
  std::size_t i = highest_rightmost(a), j = lowest_leftmost(b);
  std::size_t used_a = 0, used_b = 0;
  while (used_a < a.size() || used_b < b.size()) {
    bool take_b = used_b < b.size();
    bool take_a = used_a < a.size();
    if (take_a && take_b) {
      const Point2 &b0 = b[j], &b1 = b[b.next(j)];
      const Point2 &a0 = a[a.next(i)], &a1 = a[i];  // -A's edge direction is a_i - a_{i+1}
      const bool b_upper = upper_half(b0, b1), a_upper = upper_half(a0, a1);
      if (b_upper != a_upper) {
        take_a = a_upper;
        take_b = b_upper;
      } else {
        const Sign turn = cross_sign<Policy>(b0, b1, a0, a1);
        take_b = turn != Sign::negative;
        take_a = turn != Sign::positive;
      }
    }
    if (!visit(MergedEdge{i, j, take_b, take_a})) return;
    if (take_b) j = b.next(j), ++used_b;
    if (take_a) i = a.next(i), ++used_a;
  }
}

// Side of a0 with respect to the merged edge (positive = inside), from input points only:
// a0 - (b_j - a_i + a0) = a_i - b_j (see the header).
template <NumberPolicy Policy>
Sign side_of_reference(const ConvexPolygon& a, const ConvexPolygon& b, const MergedEdge& e) {
  if (e.along_b) return cross_sign<Policy>(b[e.j], b[b.next(e.j)], b[e.j], a[e.i]);
  return cross_sign<Policy>(a[a.next(e.i)], a[e.i], b[e.j], a[e.i]);
}

// Distance from the origin to the boundary of the convex polygon w (the origin is inside when
// `inside`), in FT; the only square root is taken once, at the end.
template <class FT>
double boundary_distance(const std::vector<detail::PointT<FT>>& w, bool inside) {
  using Ops = detail::NumberOps<FT>;
  FT best2(-1);
  for (std::size_t k = 0; k < w.size(); ++k) {
    const auto& p = w[k];
    const auto& q = w[(k + 1) % w.size()];
    const FT ex = q.x - p.x, ey = q.y - p.y;
    const FT len2 = ex * ex + ey * ey;
    FT d2;
    if (inside) {
      const FT c = detail::cross(ex, ey, FT(-p.x), FT(-p.y));
      d2 = c * c / len2;
    } else {
      FT t = -(p.x * ex + p.y * ey) / len2;
      if (t < FT(0)) t = FT(0);
      if (t > FT(1)) t = FT(1);
      const FT dx = p.x + t * ex, dy = p.y + t * ey;
      d2 = dx * dx + dy * dy;
    }
    if (best2 < FT(0) || d2 < best2) best2 = d2;
  }
  return Ops::to_double(Ops::sqrt(best2));
}

}  // namespace

template <NumberPolicy Policy>
Overlap classify_overlap(const ConvexPolygon& a, const ConvexPolygon& b) {
  Overlap verdict = Overlap::overlap;
  merge_edges<Policy>(a, b, [&](const MergedEdge& e) {
    const Sign s = side_of_reference<Policy>(a, b, e);
    if (s == Sign::negative) verdict = Overlap::separate;
    if (s == Sign::zero) verdict = Overlap::touch;
    return s != Sign::negative;
  });
  return verdict;
}

template <NumberPolicy Policy>
EntranceBlock compute_entrance_block(const ConvexPolygon& a, const ConvexPolygon& b) {
  using FT = detail::ConstructionType<Policy>;
  using Ops = detail::NumberOps<FT>;
  // a0: the mean of A's vertices, an interior point of A (eq. 9 needs any interior point).
  FT ax(0), ay(0);
  for (const Point2& p : a.vertices()) ax += Ops::from(p.x), ay += Ops::from(p.y);
  const FT count(static_cast<double>(a.size()));
  ax /= count;
  ay /= count;

  EntranceBlock out;
  out.reference = {Ops::to_double(ax), Ops::to_double(ay)};
  out.status = Overlap::overlap;
  std::vector<detail::PointT<FT>> w;  // E - a0 = B - A
  merge_edges<Policy>(a, b, [&](const MergedEdge& e) {
    w.push_back({Ops::from(b[e.j].x) - Ops::from(a[e.i].x), Ops::from(b[e.j].y) - Ops::from(a[e.i].y)});
    const Sign s = side_of_reference<Policy>(a, b, e);
    if (s == Sign::negative) out.status = Overlap::separate;
    if (s == Sign::zero && out.status == Overlap::overlap) out.status = Overlap::touch;
    return true;
  });
  out.vertices.reserve(w.size());
  for (const auto& p : w) out.vertices.push_back({Ops::to_double(p.x + ax), Ops::to_double(p.y + ay)});
  out.distance = out.status == Overlap::touch ? 0.0 : boundary_distance(w, out.status == Overlap::overlap);
  return out;
}

template <NumberPolicy Policy>
double compute_penetration_depth(const ConvexPolygon& a, const ConvexPolygon& b) {
  using FT = detail::ConstructionType<Policy>;
  using Ops = detail::NumberOps<FT>;
  const auto from = [](const Point2& p, const Point2& q) {  // p - q in FT
    return detail::PointT<FT>{Ops::from(p.x) - Ops::from(q.x), Ops::from(p.y) - Ops::from(q.y)};
  };
  bool overlap = true;
  FT best2(-1);
  merge_edges<Policy>(a, b, [&](const MergedEdge& e) {
    if (side_of_reference<Policy>(a, b, e) != Sign::positive) {  // touch or separate
      overlap = false;
      return false;
    }
    // The edge of E - a0 starts at w = b_j - a_i and runs along v: B's edge j, -A's edge i, or
    // both when they are parallel. The origin (a0) is inside; its squared distance to the
    // edge's line is (v x w)^2 / |v|^2.
    const auto w = from(b[e.j], a[e.i]);
    detail::PointT<FT> v{FT(0), FT(0)};
    if (e.along_b) v = from(b[b.next(e.j)], b[e.j]);
    if (e.along_a) {
      const auto va = from(a[e.i], a[a.next(e.i)]);
      v = {v.x + va.x, v.y + va.y};
    }
    const FT c = detail::cross(v.x, v.y, w.x, w.y);
    const FT d2 = c * c / (v.x * v.x + v.y * v.y);
    if (best2 < FT(0) || d2 < best2) best2 = d2;
    return true;
  });
  return overlap ? Ops::to_double(Ops::sqrt(best2)) : 0.0;
}

#define ROCKCONTACT_INSTANTIATE(P)                                                      \
  template Overlap classify_overlap<P>(const ConvexPolygon&, const ConvexPolygon&); \
  template EntranceBlock compute_entrance_block<P>(const ConvexPolygon&, const ConvexPolygon&); \
  template double compute_penetration_depth<P>(const ConvexPolygon&, const ConvexPolygon&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
