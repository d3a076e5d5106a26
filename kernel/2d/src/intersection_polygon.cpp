#include "rockcontact/kernel/2d/intersection_polygon.hpp"

#include <algorithm>
#include <cassert>

#include "rockcontact/kernel/2d/crossing_point.hpp"
#include "rockcontact/kernel/2d/predicates.hpp"

namespace rockcontact::kernel {
namespace {

using Node = ClipWorkspace::Node;

// Line ids: 0..n-1 are CP's edge lines (vertex k to k+1), n..n+m-1 TP's. Vertex ids: 0..n-1
// CP's vertices, n..n+m-1 TP's; a node for an input vertex stores line_a = -1 - vertex id.
// Raw pointers and sizes: the clip reads them in its innermost loop.
struct Lines {
  const Point2* cp;
  const Point2* tp;
  std::int32_t n;
  std::int32_t m;

  Lines(const ConvexPolygon& a, const ConvexPolygon& b)
      : cp(a.vertices().data()), tp(b.vertices().data()),
        n(static_cast<std::int32_t>(a.size())), m(static_cast<std::int32_t>(b.size())) {}

  std::int32_t next_cp(std::int32_t k) const { return k + 1 == n ? 0 : k + 1; }
  std::int32_t next_tp(std::int32_t j) const { return j + 1 == m ? 0 : j + 1; }
  Line line(std::int32_t id) const {
    if (id < n) return {cp[id], cp[next_cp(id)]};
    const std::int32_t j = id - n;
    return {tp[j], tp[next_tp(j)]};
  }
};

bool is_vertex(const Node& node) { return node.line_a < 0; }
std::int32_t vertex_id(const Node& node) { return -1 - node.line_a; }

// The node where clip line k meets the line of an edge crossing it. Two adjacent CP lines
// meet at a CP vertex, which is then kept as an input vertex (cheaper, exact predicates).
Node make_crossing(const Lines& lines, std::int32_t k, std::int32_t edge_line) {
  if (edge_line < lines.n) {
    if (edge_line == (k == 0 ? lines.n - 1 : k - 1)) return {-1 - k, -1, -1};
    if (edge_line == lines.next_cp(k)) return {-1 - lines.next_cp(k), -1, -1};
  }
  return {k, edge_line, -1};
}

using MemoSide = ClipWorkspace::MemoSide;

// Sides of nodes with respect to one CP line k, each the answer `orientation` or
// `crossing_side` would give under exact signs, each orientation evaluated at most once per
// pair. Only TP's vertices are asked more than once (by their own node and by the crossings on
// their two edges), and only by the line clipping at the time, so their memo is one entry per
// TP vertex holding the line it was computed for; a stale line means unknown, so moving on
// to the next line clears nothing.
//
// A crossing X of CP line i with TP edge j lies strictly inside the segment [t_j, t_{j+1}]:
// it was made by clip i on an edge of S_{i-1} labelled with TP line j whose end nodes lie
// strictly on either side of line i (see the header for S_k). That edge lies on TP's line j
// and in S_{i-1}, a subset of TP, hence in TP ∩ line j, which is the edge [t_j, t_{j+1}]
// itself because TP is strictly convex; X lies strictly between the edge's end nodes, as their
// sides are strictly opposite, so X = t_j + s (t_{j+1} - t_j) with 0 < s < 1 (an edge keeps a
// TP label only while it is part of TP's edge: one found along a clip line is relabelled with
// that line). The side of a point with respect to line k is the sign of an affine function f
// (the cross product in `orientation`), so f(X) = (1 - s) f(t_j) + s f(t_{j+1}), a combination
// with both weights strictly positive: both endpoint values >= 0 and not both 0 give a
// positive f(X); both <= 0 and not both 0 a negative one; both 0 give 0. Only when they have
// strictly opposite signs does the position s matter, and crossing_side decides. The same
// argument does not apply to a crossing's CP line i: X need not lie within CP's edge i (later
// clips may cut it), so the crossing of two CP lines keeps crossing_side.
template <NumberPolicy Policy>
struct LineSides {
  const Lines& lines;
  std::int32_t k;
  Line clip;
  MemoSide* memo;  // m entries

  LineSides(const Lines& l, std::int32_t line, MemoSide* tp_memo)
      : lines(l), k(line), clip(l.line(line)), memo(tp_memo) {}

  Sign tp_vertex(std::int32_t j) const {
    MemoSide& entry = memo[j];
    if (entry.line != k) entry = {k, orientation<Policy>(clip.p, clip.q, lines.tp[j])};
    return entry.side;
  }

  Sign operator()(const Node& node) const {
    const std::int32_t n = lines.n;
    if (node.line_a < -n) return tp_vertex(vertex_id(node) - n);  // the common case
    if (is_vertex(node)) {
      // CP vertex: ConvexPolygon::make certified, with exact predicates, that every turn of CP
      // is strictly left and that its edges wind once; then each vertex lies strictly left of
      // every edge line not through it. Vertex id is on lines id - 1 and id.
      const std::int32_t id = vertex_id(node);
      return id == k || id == lines.next_cp(k) ? Sign::zero : Sign::positive;
    }
    if (node.line_b >= n) {
      const std::int32_t j = node.line_b - n;
      const Sign a = tp_vertex(j), b = tp_vertex(lines.next_tp(j));
      if (a * b != Sign::negative) return sign_of(static_cast<int>(a) + static_cast<int>(b));
    } else if (node.line_a == k || node.line_b == k) {
      return Sign::zero;
    }
    return crossing_side_of(node);
  }

  // The degree-4 predicate is rarely needed: it stays out of the flattened clip loop.
  [[gnu::noinline]] Sign crossing_side_of(const Node& node) const {
    return crossing_side<Policy>(lines.line(node.line_a), lines.line(node.line_b), clip);
  }
};

// A node set S_k of the header.
struct NodeSet {
  Node* nodes;
  std::int32_t size;
};

// One Sutherland-Hodgman step with exact three-valued sides: writes the part of `in` on the
// left of (or on) clip line k to `out`, the kept nodes and the crossings in order, and returns
// their number. `out` has room for 2 in.size nodes: each node gives at most itself and one
// crossing. A set of >= 3 nodes is a closed polygon; one of 2 is a segment, whose edge from
// the last node back to the first is not an edge. An edge whose two end nodes both lie on
// line k lies along it and is labelled k. Flattened, so that the filtered orientation, the
// common predicate, is inlined into the loop.
template <NumberPolicy Policy>
[[gnu::flatten]] std::int32_t clip_by_line(const LineSides<Policy>& side_of, NodeSet in, Node* out) {
  const std::int32_t k = side_of.k;
  const std::int32_t edges = in.size >= 3 ? in.size : in.size - 1;
  std::int32_t count = 0;
  bool last_on_k = false;
  const auto push = [&](const Node& node, bool on_k) {
    if (on_k && last_on_k) out[count - 1].edge_line = k;
    out[count++] = node;
    last_on_k = on_k;
  };
  const Sign first = side_of(in.nodes[0]);
  // The first node written lies on line k unless it is node 0 strictly inside: before any
  // node is written all are outside, and the first inside one is on the line or preceded by
  // the crossing entering.
  const bool first_on_k = first != Sign::positive;
  Sign side = first;  // of node v
  for (std::int32_t v = 0; v < in.size; ++v) {
    const std::int32_t w = v + 1 == in.size ? 0 : v + 1;
    const Sign next_side = w == 0 ? first : side_of(in.nodes[w]);
    if (side != Sign::negative) push(in.nodes[v], side == Sign::zero);
    if (v < edges && side * next_side == Sign::negative) {
      Node crossing = make_crossing(side_of.lines, k, in.nodes[v].edge_line);
      crossing.edge_line = in.nodes[v].edge_line;
      push(crossing, true);
    }
    side = next_side;
  }
  if (first_on_k && last_on_k) out[count - 1].edge_line = k;
  return count;
}

// The labels of a clip's >= 3 final nodes.
void write_labels(const Lines& lines, const Node* nodes, std::int32_t size, IntersectionPolygon& out) {
  const std::int32_t n = lines.n;
  for (std::int32_t v = 0; v < size; ++v) {
    const Node& node = nodes[v];
    IpVertex label;
    if (is_vertex(node)) {
      const std::int32_t id = vertex_id(node);
      label = id < n ? IpVertex{IpVertex::Kind::cp_vertex, id, -1}
                     : IpVertex{IpVertex::Kind::tp_vertex, -1, id - n};
    } else if (node.line_b >= n) {
      // Lines of a surviving crossing: one CP line (the clip line) and one TP line.
      label = IpVertex{IpVertex::Kind::crossing, node.line_a, node.line_b - n};
    } else {
      // Two CP lines. A crossing of non-adjacent CP lines can be made by an intermediate clip
      // (they meet outside CP), but consistent signs always clip it away later; it survives
      // only when Float's rounded signs contradicted each other (found by the pair-kernel
      // fuzzer on a 1e45 m sliver). It has no CP x TP label, so it is left out: Float's IP is
      // then as wrong as its signs, but every label names an existing edge.
      continue;
    }
    out.vertices.push_back(label);
    out.edges.push_back(node.edge_line < n ? IpEdge{IpEdge::On::cp_edge, node.edge_line}
                                           : IpEdge{IpEdge::On::tp_edge, node.edge_line - n});
  }
  if (out.vertices.size() < 3) {  // only after such a contradiction
    out.vertices.clear();
    out.edges.clear();
  }
}

}  // namespace

template <NumberPolicy Policy>
Overlap compute_intersection_polygon(const ConvexPolygon& cp, const ConvexPolygon& tp,
                                     IntersectionPolygon& out, ClipWorkspace& ws) {
  const Lines lines(cp, tp);
  const std::int32_t n = lines.n, m = lines.m;
  out.vertices.clear();
  out.edges.clear();
  MemoSide* const memo = ws.tp_sides.storage(static_cast<std::size_t>(m));
  std::fill(memo, memo + m, MemoSide{});
  int buffer = 0;
  NodeSet set{ws.nodes[buffer].storage(static_cast<std::size_t>(m)), m};
  for (std::int32_t j = 0; j < m; ++j) set.nodes[j] = {-1 - (n + j), -1, n + j};
  for (std::int32_t k = 0; k < n && set.size > 0; ++k) {
    buffer = 1 - buffer;
    Node* const next = ws.nodes[buffer].storage(2 * static_cast<std::size_t>(set.size));
    set = {next, clip_by_line(LineSides<Policy>(lines, k, memo), set, next)};
  }
  if (set.size == 0) return Overlap::separate;
  if (set.size < 3) return Overlap::touch;
  write_labels(lines, set.nodes, set.size, out);
  assert((Policy::kind == PolicyKind::float_ || out.vertices.size() == static_cast<std::size_t>(set.size)));
  return Overlap::overlap;
}

template <NumberPolicy Policy>
IntersectionPolygon compute_intersection_polygon(const ConvexPolygon& cp, const ConvexPolygon& tp) {
  IntersectionPolygon ip;
  ClipWorkspace ws;
  compute_intersection_polygon<Policy>(cp, tp, ip, ws);
  return ip;
}

template <NumberPolicy Policy>
void construct_points(const ConvexPolygon& cp, const ConvexPolygon& tp,
                      const IntersectionPolygon& ip, std::vector<Point2>& out) {
  out.clear();
  for (const IpVertex& v : ip.vertices) {
    switch (v.kind) {
      case IpVertex::Kind::cp_vertex: out.push_back(cp[v.cp]); break;
      case IpVertex::Kind::tp_vertex: out.push_back(tp[v.tp]); break;
      case IpVertex::Kind::crossing:
        out.push_back(construct_crossing_point<Policy>(cp[v.cp], cp[cp.next(v.cp)], tp[v.tp],
                                                       tp[tp.next(v.tp)]));
        break;
    }
  }
}

#define ROCKCONTACT_INSTANTIATE(P)                                                          \
  template Overlap compute_intersection_polygon<P>(const ConvexPolygon&, const ConvexPolygon&, \
                                                   IntersectionPolygon&, ClipWorkspace&);      \
  template IntersectionPolygon compute_intersection_polygon<P>(const ConvexPolygon&,        \
                                                               const ConvexPolygon&);       \
  template void construct_points<P>(const ConvexPolygon&, const ConvexPolygon&,             \
                                    const IntersectionPolygon&, std::vector<Point2>&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
