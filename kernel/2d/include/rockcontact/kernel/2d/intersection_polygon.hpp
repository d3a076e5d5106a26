#pragma once
// The intersection polygon IP of a contact polygon CP and a target polygon TP (seed 000 §3.1.3,
// Table 3): TP clipped successively by the half-planes of CP's edges.
//
// Every IP vertex is kept *symbolic*: a CP vertex, a TP vertex, or the crossing of CP edge i
// with TP edge j. The side of a vertex with respect to the next clipping line is decided by an
// exact predicate on input coordinates (orientation for input vertices, crossing_side for
// crossings), never on a rounded point. Coordinates are constructed only at the end.
//
// Clipping rule (Sutherland-Hodgman with three-valued sides): a vertex on the line is kept, a
// crossing is created only where an edge passes strictly from one side to the other. By
// induction every intermediate polygon is strictly convex with distinct vertices, so:
//   * the result is strictly convex and CCW, with no repeated or collinear vertex;
//   * it has at least 3 vertices exactly when the interiors of CP and TP intersect, i.e. when
//     classify_overlap answers `overlap`; touching polygons give an empty IP.
// Under Filtered these statements hold for the symbolic polygon; each constructed crossing is
// within ~2^-40 of its TP edge's extent of the true crossing (crossing_point.hpp), which can
// fold a sliver thinner than that. The Exact policy constructs exactly and rounds each
// coordinate once.

#include <cstdint>
#include <vector>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
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

// Reusable scratch space: no allocation once its vectors have grown to the largest polygon.
struct ClipWorkspace {
  struct Node {
    std::int32_t line_a = -1;  // input vertex: a = -1 - vertex id; crossing: two line ids
    std::int32_t line_b = -1;
    std::int32_t edge_line = -1;  // line supporting the edge leaving this node
  };
  std::vector<Node> current, next;
  std::vector<signed char> side;
  std::vector<unsigned char> on_clip_line;
};

template <NumberPolicy Policy>
void compute_intersection_polygon(const ConvexPolygon& cp, const ConvexPolygon& tp,
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
