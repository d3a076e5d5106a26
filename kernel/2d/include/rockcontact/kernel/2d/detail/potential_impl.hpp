#pragma once
// FT-generic pieces of the potential and its demarcation points (see potential.hpp and
// demarcation.hpp for the method). Used by kernel/2d/src/potential.cpp in double and by the
// contact layer in double or GMP rationals.
//
// Along the segment p(t) = a + t (b - a), the distance from p(t) to the line of edge k,
// e_k = v_{k+1} - v_k, is linear in t:
//   d_k(t) = alpha_k + t beta_k,  alpha_k = e_k x (a - v_k) / |e_k|,  beta_k = e_k x (b - a) / |e_k|
// (positive inside a CCW polygon), and d_exit(t) = min_k d_k(t), their lower envelope.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/detail/constructions.hpp"
#include "rockcontact/kernel/2d/predicates.hpp"

namespace rockcontact::kernel::detail {

template <class FT>
struct LinearPieces {
  std::vector<FT> alpha;  // m
  std::vector<FT> beta;   // m per unit of t
  // Written by envelope_breakpoints: the lines sorted by slope, and those on the lower envelope
  // (kept here so that the double path allocates nothing in steady state).
  std::vector<std::uint32_t> order;
  std::vector<std::uint32_t> envelope;

  FT at(const FT& t) const {
    FT best = alpha[0] + t * beta[0];
    for (std::size_t k = 1; k < alpha.size(); ++k) {
      const FT d = alpha[k] + t * beta[k];
      if (d < best) best = d;
    }
    return best;
  }
};

// The vertices of a convex polygon seen from `origin`: the polygon translated by -origin, each
// coordinate difference rounded once (exact when the two are within a factor 2 of each other,
// Sterbenz; else off by u times the difference, a rounding of the polygon's own size). The
// double constructions of a pair run in such a frame, so that a pair 10^6 m from the origin
// gets the force of the same pair at the origin. Edge vectors are still taken from the
// polygon's own coordinates (edge_of): the translated vertices of a very short edge far from
// the origin may round onto each other, its true vector never vanishes.
struct TranslatedPolygon {
  const ConvexPolygon& polygon;
  Point2 origin;

  Point2 operator[](std::size_t k) const {
    return {polygon[k].x - origin.x, polygon[k].y - origin.y};
  }
  std::size_t size() const { return polygon.size(); }
  std::size_t next(std::size_t k) const { return polygon.next(k); }
  std::size_t prev(std::size_t k) const { return polygon.prev(k); }
};

// The functions below take a ConvexPolygon (global frame; the exact path) or a
// TranslatedPolygon (`Poly`).
inline const ConvexPolygon& global_polygon(const ConvexPolygon& poly) { return poly; }
inline const ConvexPolygon& global_polygon(const TranslatedPolygon& poly) { return poly.polygon; }
inline Point2 frame_origin(const ConvexPolygon&) { return {0.0, 0.0}; }
inline Point2 frame_origin(const TranslatedPolygon& poly) { return poly.origin; }

// Edge k's vector v_{k+1} - v_k, from the polygon's own coordinates.
template <class FT, class Poly>
PointT<FT> edge_of(const Poly& poly, std::size_t k) {
  using Ops = NumberOps<FT>;
  const ConvexPolygon& g = global_polygon(poly);
  const Point2 &p = g[k], &q = g[g.next(k)];
  return {FT(Ops::from(q.x) - Ops::from(p.x)), FT(Ops::from(q.y) - Ops::from(p.y))};
}

template <class FT, class Poly>
FT edge_length(const Poly& poly, std::size_t k) {
  const PointT<FT> e = edge_of<FT>(poly, k);
  return NumberOps<FT>::sqrt(e.x * e.x + e.y * e.y);
}

// A polygon's edge vectors and lengths, computed once per pair and read by the distance
// functions of every IP edge (a square root per polygon edge, not per IP edge and polygon edge).
template <class FT>
struct EdgeTable {
  std::vector<PointT<FT>> edge;
  std::vector<FT> length;
};

template <class FT, class Poly>
void tabulate_edges(const Poly& poly, EdgeTable<FT>& out) {
  out.edge.resize(poly.size());
  out.length.resize(poly.size());
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const PointT<FT> e = edge_of<FT>(poly, k);
    out.length[k] = NumberOps<FT>::sqrt(e.x * e.x + e.y * e.y);
    out.edge[k] = e;
  }
}

// The signed distances alpha_k + t beta_k of the point a + t (b - a) from the lines of
// `poly`'s edges (positive inside), from its edge table.
template <class FT, class Poly>
void edge_distance_functions(const Poly& poly, const EdgeTable<FT>& edges, const PointT<FT>& a,
                             const PointT<FT>& b, LinearPieces<FT>& out) {
  using Ops = NumberOps<FT>;
  out.alpha.resize(poly.size());
  out.beta.resize(poly.size());
  const FT dx = b.x - a.x, dy = b.y - a.y;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point2 p = poly[k];
    const FT &ex = edges.edge[k].x, &ey = edges.edge[k].y;
    const FT& len = edges.length[k];
    out.alpha[k] = cross(ex, ey, FT(a.x - Ops::from(p.x)), FT(a.y - Ops::from(p.y))) / len;
    out.beta[k] = cross(ex, ey, dx, dy) / len;
  }
}

// Breakpoints of min_k (alpha_k + t beta_k) for 0 < t < 1, ascending, appended to `out`.
//
// Which lines form the envelope is decided in the dual: line k is the point P_k = (beta_k,
// alpha_k), its value at t is <(t, 1), P_k>, so the lines that are lowest for some t are the
// vertices of the lower convex hull of the P_k, in order of decreasing slope as t grows, and
// the breakpoint between hull neighbours i, j is t = (alpha_j - alpha_i) / (beta_i - beta_j).
// Every decision is a comparison of two coefficients or the orientation of three dual points,
// evaluated exactly on the coefficients as computed (FT = double: the Policy's orientation, so
// Filtered decides exactly on those doubles; FT = ExactRational: exact rationals).
//
// Why not decide on the breakpoints themselves: at a point where three or more edge-distance
// lines meet (exactly concurrent lines: a lattice polygon's medial axis has such vertices) the
// crossing parameters are equal in exact arithmetic but round differently in double; a walk
// that chooses the next line by the smallest rounded crossing can take a line of the wrong
// slope there and then skip the true next line, whose crossing now seems to lie behind it,
// following a line above the envelope and missing a kink: an O(1) error of the integral
// (4 % of the force of lattice_touch pair 394832 of campaign seed 20261124). Here the rounded
// lines form a consistent envelope, and the integral of the envelope of lines each within
// rounding of the true ones is within that rounding of the true integral: a near-concurrent
// triple adds or drops a piece of width ~u.
// Lines of equal slope: only the lowest matters. Collinear dual points: the middle line
// touches the envelope at one point and is dropped.
//
// Only the lines that can be lowest somewhere in [0, 1] enter the hull (most of a polygon's
// edges are far from a given IP edge): with A the lowest line at t = 0, a steeper line is
// above A for every t > 0; with B a line that is (to rounding) lowest at t = 1, a line of
// smaller slope that is certainly above B at t = 1 is above it on all of [0, 1]. Both tests
// only ever drop lines that cannot matter, so the hull of the rest is exact on [0, 1].
//
// Coefficients beyond double's range (a cross product of coordinate differences overflows past
// ~1e150 m, or an edge length does) have no value to decide on exactly: the lines are then
// ordered by Float's orientation, and the pair is far outside the range where a double force
// means anything (robustness_tests/fuzz/fuzz_pair_kernel.cpp: its sane range).
template <NumberPolicy Policy, class FT>
void envelope_breakpoints(LinearPieces<FT>& f, std::vector<FT>& out) {
  const std::size_t n = f.alpha.size();
  bool representable = true;
  if constexpr (std::is_same_v<FT, double>) {
    for (std::size_t k = 0; k < n; ++k) {
      representable &= std::isfinite(f.alpha[k]) && std::isfinite(f.beta[k]);
    }
  }
  const auto turn = [&](std::uint32_t i, std::uint32_t j, std::uint32_t k) {
    if constexpr (std::is_same_v<FT, double>) {
      const Point2 pi{f.beta[i], f.alpha[i]}, pj{f.beta[j], f.alpha[j]}, pk{f.beta[k], f.alpha[k]};
      return representable ? orientation<Policy>(pi, pj, pk) : orientation<Float>(pi, pj, pk);
    } else {
      return sign_of(FT(cross(FT(f.beta[j] - f.beta[i]), FT(f.alpha[j] - f.alpha[i]),
                              FT(f.beta[k] - f.beta[i]), FT(f.alpha[k] - f.alpha[i]))));
    }
  };
  // Is line k above line b at t = 1 for certain? Exact for rationals; in double the two sums
  // and their difference carry at most u (|s_k| + |s_b| + |d|) of error, bounded by 4u (...).
  const auto above_at_one = [&](std::size_t k, std::size_t b) {
    const FT sk = f.alpha[k] + f.beta[k], sb = f.alpha[b] + f.beta[b];
    if constexpr (std::is_same_v<FT, double>) {
      return sk - sb > 0x1p-51 * (std::fabs(sk) + std::fabs(sb));
    } else {
      return sk > sb;
    }
  };
  std::size_t a = 0, b = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (f.alpha[k] < f.alpha[a] || (f.alpha[k] == f.alpha[a] && f.beta[k] < f.beta[a])) a = k;
    if (f.alpha[k] + f.beta[k] < f.alpha[b] + f.beta[b]) b = k;
  }
  std::vector<std::uint32_t>& order = f.order;
  order.clear();
  for (std::size_t k = 0; k < n; ++k) {
    if (f.beta[k] > f.beta[a] || (f.beta[k] < f.beta[b] && above_at_one(k, b))) continue;
    order.push_back(static_cast<std::uint32_t>(k));
  }
  std::sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
    return f.beta[i] < f.beta[j] || (f.beta[i] == f.beta[j] && f.alpha[i] < f.alpha[j]);
  });
  std::vector<std::uint32_t>& hull = f.envelope;
  hull.clear();
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::uint32_t line = order[k];
    if (k > 0 && f.beta[order[k - 1]] == f.beta[line]) continue;  // a higher parallel line
    while (hull.size() >= 2 && turn(hull[hull.size() - 2], hull.back(), line) != Sign::positive) {
      hull.pop_back();
    }
    hull.push_back(line);
  }
  // The envelope meets the hull's lines in decreasing slope as t grows.
  for (std::size_t k = hull.size(); k-- > 1;) {
    const std::uint32_t left = hull[k], right = hull[k - 1];  // beta[left] > beta[right]
    const FT t = (f.alpha[right] - f.alpha[left]) / (f.beta[left] - f.beta[right]);
    if (t > FT(0) && t < FT(1)) out.push_back(t);
  }
}

// Inward unit normal of edge k (v_k -> v_{k+1}) of a CCW polygon.
template <class FT, class Poly>
PointT<FT> inward_normal(const Poly& poly, std::size_t k) {
  const PointT<FT> e = edge_of<FT>(poly, k);
  const FT len = NumberOps<FT>::sqrt(e.x * e.x + e.y * e.y);
  return {FT(-e.y / len), FT(e.x / len)};
}

// A ray o + s r, 0 <= s <= s_max (s_max < 0: unbounded).
template <class FT>
struct Ray {
  PointT<FT> origin;
  PointT<FT> direction;
  FT s_max;
};

// Parameter t in (0, 1) where segment a + t d crosses the ray, if it does (transversally).
template <class FT>
void add_crossing(const PointT<FT>& a, const PointT<FT>& d, const Ray<FT>& ray, std::vector<FT>& out) {
  const FT denom = cross(d.x, d.y, ray.direction.x, ray.direction.y);
  if (denom == FT(0)) return;
  const FT wx = ray.origin.x - a.x, wy = ray.origin.y - a.y;
  const FT t = cross(wx, wy, ray.direction.x, ray.direction.y) / denom;
  const FT s = cross(wx, wy, d.x, d.y) / denom;
  if (t > FT(0) && t < FT(1) && s >= FT(0) && (ray.s_max < FT(0) || s <= ray.s_max)) out.push_back(t);
}

// The paper's demarcation points (seed 000 §3.2.3): the centre of the segment and its
// crossings with the bisector ray of every node; an edge shorter than small_edge gets a
// virtual node where the bisector rays of its two end nodes meet: those two rays stop there
// and one ray continues, bisecting the lines of the two neighbouring edges.
template <class FT, class Poly>
void paper_breakpoints(const Poly& poly, const PointT<FT>& a, const PointT<FT>& b,
                       double small_edge, std::vector<FT>& out) {
  const std::size_t n = poly.size();
  const PointT<FT> d{FT(b.x - a.x), FT(b.y - a.y)};
  out.push_back(FT(1) / FT(2));
  std::vector<PointT<FT>> normal(n);
  std::vector<bool> short_edge(n);
  for (std::size_t k = 0; k < n; ++k) {
    normal[k] = inward_normal<FT>(poly, k);
    short_edge[k] = edge_length<FT>(poly, k) < NumberOps<FT>::from(small_edge);
  }
  const auto bisector = [&](std::size_t k) {  // at node k, between edges k-1 and k
    const PointT<FT>& m = normal[poly.prev(k)];
    return PointT<FT>{FT(m.x + normal[k].x), FT(m.y + normal[k].y)};
  };
  // Parameter along node k's bisector where it meets node (k+1)'s: the virtual node of edge k.
  const auto virtual_node_s = [&](std::size_t k) {
    const PointT<FT> r0 = bisector(k), r1 = bisector(poly.next(k));
    const PointT<FT> e = edge_of<FT>(poly, k);
    return FT(cross(e.x, e.y, r1.x, r1.y) / cross(r0.x, r0.y, r1.x, r1.y));
  };
  for (std::size_t k = 0; k < n; ++k) {
    Ray<FT> ray{lift<FT>(poly[k]), bisector(k), FT(-1)};
    if (short_edge[k]) {
      ray.s_max = virtual_node_s(k);
    } else if (short_edge[poly.prev(k)]) {
      // The virtual node of edge k-1 lies on this ray where node k-1's bisector meets it.
      const std::size_t j = poly.prev(k);
      const PointT<FT> r0 = bisector(j);
      const FT s0 = virtual_node_s(j);
      const PointT<FT> w{FT(lift<FT>(poly[j]).x + s0 * r0.x), FT(lift<FT>(poly[j]).y + s0 * r0.y)};
      const PointT<FT>& r = ray.direction;
      ray.s_max = r.x * r.x >= r.y * r.y ? FT((w.x - ray.origin.x) / r.x) : FT((w.y - ray.origin.y) / r.y);
    }
    add_crossing(a, d, ray, out);
    if (short_edge[k]) {
      const PointT<FT> r0 = bisector(k);
      const FT s = virtual_node_s(k);
      const PointT<FT>& before = normal[poly.prev(k)];
      const PointT<FT>& after = normal[poly.next(k)];
      const Ray<FT> from_virtual{{FT(ray.origin.x + s * r0.x), FT(ray.origin.y + s * r0.y)},
                                 {FT(before.x + after.x), FT(before.y + after.y)},
                                 FT(-1)};
      add_crossing(a, d, from_virtual, out);
    }
  }
}

// Scratch space of the force integration (contact layer), reused across pairs so that the
// double path allocates nothing in steady state.
template <class FT>
struct ForceScratch {
  std::vector<PointT<FT>> vertices;
  EdgeTable<FT> cp_edges, tp_edges;
  LinearPieces<FT> cp_distance, tp_distance;
  std::vector<FT> t;
};

// Sorts and removes duplicates and anything outside (0, 1).
template <class FT>
void normalise_parameters(std::vector<FT>& t) {
  std::erase_if(t, [](const FT& x) { return !(x > FT(0) && x < FT(1)); });
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
}

}  // namespace rockcontact::kernel::detail
