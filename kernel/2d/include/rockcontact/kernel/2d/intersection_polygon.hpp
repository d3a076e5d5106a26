#pragma once
// The intersection polygon IP of a contact polygon CP and a target polygon TP (seed 000 §3.1.3,
// Table 3): TP clipped successively by the half-planes of CP's edges; and, from the same clip,
// the pair's overlap verdict.
//
// Every IP vertex is kept *symbolic*: a CP vertex, a TP vertex, or the crossing of CP edge i
// with TP edge j. The side of a vertex with respect to the next clipping line is decided by an
// exact predicate on input coordinates (orientation for input vertices, crossing_side for
// crossings), never on a rounded point. Coordinates are constructed only at the end.
//
// Clipping rule (Sutherland-Hodgman with three-valued sides): a vertex on the line is kept, a
// crossing is created only where an edge passes strictly from one side to the other. With
// H_k the closed half-plane left of CP's edge line k, the nodes after clip k are, when the
// signs are exact, the vertices of S_k = TP ∩ H_0 ∩ ... ∩ H_k, by induction on k:
//   * S_k a polygon with interior (>= 3 nodes, strictly convex, CCW, distinct): if some node is
//     strictly inside H_k, S_k ∩ H_k has interior and the rule lists its vertices; if all are
//     on or outside the line, S_k ∩ H_k is the edge on the line (two adjacent nodes on it, the
//     edge between them labelled with the line) or the vertex on it (one node), and no
//     crossing is made (a crossing needs a node strictly inside); if all are outside, empty;
//   * S_k a segment (2 nodes): clipped as a segment, not as a cycle, so that its one crossing
//     with the line is not made twice; the result is a segment, a point or empty;
//   * S_k a point (1 node): kept when it is on or inside the line;
//   * S_k empty: the clip stops.
// Hence:
//   * the IP is strictly convex and CCW, with no repeated or collinear vertex;
//   * the verdict. S_{n-1} = CP ∩ TP. It has >= 3 nodes exactly when it has interior, i.e.
//     (CP and TP being convex with interior) when the interiors of CP and TP intersect:
//     `overlap`. It has 1 or 2 nodes when CP ∩ TP is a point or a segment: the polygons meet
//     but their interiors do not, `touch`. It has none when they are disjoint: `separate`.
//     These are the three cases classify_overlap decides from the entrance block
//     (entrance_block.hpp); both decide them exactly under Filtered and Exact, so there the
//     two verdicts are equal (tests/intersection_polygon_test.cpp checks it on every
//     generator family and on the contact2d reference data). Under Float each follows its
//     own rounded signs, and they may differ.
// Under Filtered these statements hold for the symbolic polygon; each constructed crossing is
// within ~2^-40 of its TP edge's extent of the true crossing (crossing_point.hpp), which can
// fold a sliver thinner than that. The Exact policy constructs exactly and rounds each
// coordinate once.
//
// Cost: each side is decided at most once per pair, and a crossing's side mostly without a
// predicate (intersection_polygon.cpp derives each rule):
//   * TP vertex j against CP line k: orientation, memoised in a table filled on demand;
//   * CP vertex against CP line k: zero on the vertex's own two lines, else positive, by CP's
//     strict convexity (ConvexPolygon::make certifies it with exact predicates);
//   * crossing of CP line i with TP edge j against CP line k: it lies strictly inside TP edge
//     j, so its side follows from the memoised sides of the edge's endpoints unless they are
//     strictly opposite; only then the degree-4 crossing_side;
//   * crossing of two CP lines (made on the way, never an IP vertex under exact signs):
//     crossing_side.
// S_k has at most n + m vertices (each edge lies on a different one of the n + m lines), so a
// ClipWorkspace with inline room for both polygons clips without allocating.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/detail/inline_buffer.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/sign.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::kernel {

struct IpVertex {
  enum class Kind : std::uint8_t { cp_vertex, tp_vertex, crossing };
  Kind kind = Kind::tp_vertex;
  // cp_vertex: cp = vertex index; tp_vertex: tp = vertex index; crossing: cp = CP edge index
  // (from vertex cp to cp+1), tp = TP edge index. Unused fields are -1.
  std::int32_t cp = -1;
  std::int32_t tp = -1;
  friend bool operator==(const IpVertex&, const IpVertex&) = default;
};

// The polygon boundary an IP edge lies on. Along a CP edge the CP potential is zero, along a
// TP edge the TP potential is zero (seed 000 §3.2.3 steps 2-3).
struct IpEdge {
  enum class On : std::uint8_t { cp_edge, tp_edge };
  On on = On::tp_edge;
  std::int32_t index = -1;
  friend bool operator==(const IpEdge&, const IpEdge&) = default;
};

struct IntersectionPolygon {
  std::vector<IpVertex> vertices;  // CCW; empty unless the interiors overlap
  std::vector<IpEdge> edges;       // edges[k] joins vertices[k] and vertices[k + 1 mod size]
  bool empty() const noexcept { return vertices.empty(); }
};

// Reusable scratch space of the clip; what it holds between calls means nothing. Pairs whose
// polygons have at most `inline_vertices` vertices each are clipped in arrays inside it, with
// no allocation; larger ones in heap vectors, grown to the largest pair and reused.
struct ClipWorkspace {
  static constexpr std::size_t inline_vertices = 16;
  struct Node {
    std::int32_t line_a = -1;  // input vertex: a = -1 - vertex id; crossing: two line ids
    std::int32_t line_b = -1;
    std::int32_t edge_line = -1;  // line supporting the edge leaving this node
  };
  // The node set before and after one clip, the two swapping roles: at most n + m nodes, but
  // room for twice the set being clipped, the most a clip can emit whatever the signs.
  detail::InlineBuffer<Node, 4 * inline_vertices> nodes[2];
  // The memo of the sides of TP's vertices: entry j holds the side of TP vertex j with
  // respect to CP line `line` (unknown for any other line).
  struct MemoSide {
    std::int32_t line = -1;
    Sign side = Sign::zero;
  };
  detail::InlineBuffer<MemoSide, inline_vertices> tp_sides;
};

// The IP of cp and tp into `out` (empty unless the pair overlaps) and the overlap verdict,
// decided by the clip itself (see above; under Float an `overlap` may come with an empty IP
// when Float's signs contradict each other). Allocates nothing when both polygons fit the
// workspace's inline arrays and `out` has grown to the largest IP.
template <NumberPolicy Policy>
Overlap compute_intersection_polygon(const ConvexPolygon& cp, const ConvexPolygon& tp,
                                     IntersectionPolygon& out, ClipWorkspace& workspace);

template <NumberPolicy Policy>
IntersectionPolygon compute_intersection_polygon(const ConvexPolygon& cp, const ConvexPolygon& tp);

// Coordinates of the IP vertices (m): input vertices copied, crossings constructed by
// construct_crossing_point<Policy> (crossing_point.hpp: under Filtered within
// (2^-40 + 3u) |t_{j+1} - t_j| + 2u |X| per coordinate, near-parallel ones rounded exactly;
// under Exact the exact crossing rounded once).
template <NumberPolicy Policy>
void construct_points(const ConvexPolygon& cp, const ConvexPolygon& tp,
                      const IntersectionPolygon& ip, std::vector<Point2>& out);

}  // namespace rockcontact::kernel
