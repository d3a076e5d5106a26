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
struct Lines {
  const ConvexPolygon& cp;
  const ConvexPolygon& tp;

  std::int32_t n() const { return static_cast<std::int32_t>(cp.size()); }
  Line line(std::int32_t id) const {
    if (id < n()) return {cp[id], cp[cp.next(id)]};
    const std::size_t j = id - n();
    return {tp[j], tp[tp.next(j)]};
  }
};

bool is_vertex(const Node& node) { return node.line_a < 0; }
std::int32_t vertex_id(const Node& node) { return -1 - node.line_a; }

// The node where clip line k meets the line of an edge crossing it. Two adjacent CP lines
// meet at a CP vertex, which is then kept as an input vertex (cheaper, exact predicates).
Node make_crossing(const Lines& lines, std::int32_t k, std::int32_t edge_line) {
  const std::int32_t n = lines.n();
  if (edge_line < n) {
    if (edge_line == (k + n - 1) % n) return {-1 - k, -1, -1};
    if (edge_line == (k + 1) % n) return {-1 - (k + 1) % n, -1, -1};
  }
  return {k, edge_line, -1};
}

constexpr signed char unknown_side = 2;

Sign to_sign(signed char side) { return static_cast<Sign>(side); }

// Sides of nodes with respect to CP lines, each answer the one `orientation` or
// `crossing_side` would give under exact signs, and each orientation evaluated at most once.
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
class Sides {
 public:
  // `table` has room for n m entries.
  Sides(const Lines& lines, signed char* table) : lines_(lines), table_(table) {
    const std::size_t entries = lines.cp.size() * lines.tp.size();
    std::fill(table_, table_ + entries, unknown_side);
  }

  Sign operator()(const Node& node, std::int32_t k) {
    const std::int32_t n = lines_.n();
    if (is_vertex(node)) {
      const std::int32_t id = vertex_id(node);
      if (id >= n) return tp_vertex(id - n, k);
      // CP vertex: ConvexPolygon::make certified, with exact predicates, that every turn of CP
      // is strictly left and that its edges wind once; then each vertex lies strictly left of
      // every edge line not through it. Vertex id is on lines id - 1 and id.
      return id == k || id == static_cast<std::int32_t>(lines_.cp.next(k)) ? Sign::zero : Sign::positive;
    }
    if (node.line_b >= n) {
      const auto j = static_cast<std::size_t>(node.line_b - n);
      const Sign a = tp_vertex(static_cast<std::int32_t>(j), k);
      const Sign b = tp_vertex(static_cast<std::int32_t>(lines_.tp.next(j)), k);
      if (a * b != Sign::negative) return sign_of(static_cast<int>(a) + static_cast<int>(b));
    } else if (node.line_a == k || node.line_b == k) {
      return Sign::zero;
    }
    return crossing_side<Policy>(lines_.line(node.line_a), lines_.line(node.line_b), lines_.line(k));
  }

 private:
  Sign tp_vertex(std::int32_t j, std::int32_t k) {
    signed char& side = table_[static_cast<std::size_t>(k) * lines_.tp.size() + j];
    if (side == unknown_side) {
      const Line clip = lines_.line(k);
      side = static_cast<signed char>(orientation<Policy>(clip.p, clip.q, lines_.tp[j]));
    }
    return to_sign(side);
  }

  const Lines& lines_;
  signed char* table_;
};

// The node set S_k of the header, in the workspace's two node buffers.
template <NumberPolicy Policy>
class Clip {
 public:
  Clip(const Lines& lines, ClipWorkspace& ws)
      : lines_(lines), ws_(ws), sides_(lines, ws.tp_sides.storage(lines.cp.size() * lines.tp.size())) {
    const std::size_t m = lines.tp.size();
    nodes_ = ws_.nodes[0].storage(m);
    const std::int32_t n = lines.n();
    for (std::size_t j = 0; j < m; ++j) {
      const auto id = static_cast<std::int32_t>(j);
      nodes_[j] = {-1 - (n + id), -1, n + id};
    }
    size_ = static_cast<std::int32_t>(m);
  }

  std::int32_t size() const { return size_; }
  const Node* nodes() const { return nodes_; }

  // One Sutherland-Hodgman step with exact three-valued sides: keeps the part of the set on
  // the left of (or on) clip line k. A set of >= 3 nodes is a closed polygon; one of 2 is a
  // segment, whose edge from the last node back to the first is not an edge.
  void by_line(std::int32_t k) {
    signed char* sides = ws_.node_sides.storage(static_cast<std::size_t>(size_));
    bool any_negative = false;
    std::int32_t out_size = 0;
    for (std::int32_t v = 0; v < size_; ++v) {
      const Sign s = sides_(nodes_[v], k);
      sides[v] = static_cast<signed char>(s);
      any_negative |= s == Sign::negative;
      out_size += s != Sign::negative;
    }
    if (!any_negative) {
      // Nothing is cut: only edges found along line k change their label.
      for (std::int32_t v = 0; v < size_; ++v) {
        if (sides[v] == 0 && sides[next(v)] == 0) nodes_[v].edge_line = k;
      }
      return;
    }
    const std::int32_t edges = size_ >= 3 ? size_ : size_ - 1;
    for (std::int32_t v = 0; v < edges; ++v) out_size += sides[v] * sides[next(v)] < 0;
    if (out_size == 0) {
      size_ = 0;
      return;
    }
    which_ ^= 1;
    Node* out = ws_.nodes[which_].storage(static_cast<std::size_t>(out_size));
    emit(k, sides, edges, out);
    nodes_ = out;
  }

 private:
  std::int32_t next(std::int32_t v) const { return v + 1 == size_ ? 0 : v + 1; }

  // Writes the kept nodes and the crossings, in order, to `out`. An edge whose two end nodes
  // both lie on line k lies along it and is labelled k.
  void emit(std::int32_t k, const signed char* sides, std::int32_t edges, Node* out) {
    std::int32_t count = 0;
    bool first_on_k = false, last_on_k = false;
    const auto push = [&](const Node& node, bool on_k) {
      if (count == 0) first_on_k = on_k;
      if (on_k && last_on_k) out[count - 1].edge_line = k;
      out[count++] = node;
      last_on_k = on_k;
    };
    for (std::int32_t v = 0; v < size_; ++v) {
      if (sides[v] >= 0) push(nodes_[v], sides[v] == 0);
      if (v < edges && sides[v] * sides[next(v)] < 0) {
        Node crossing = make_crossing(lines_, k, nodes_[v].edge_line);
        crossing.edge_line = nodes_[v].edge_line;
        push(crossing, true);
      }
    }
    if (first_on_k && last_on_k) out[count - 1].edge_line = k;
    size_ = count;
  }

  const Lines& lines_;
  ClipWorkspace& ws_;
  Sides<Policy> sides_;
  Node* nodes_ = nullptr;
  std::int32_t size_ = 0;
  int which_ = 0;  // the buffer nodes_ points into
};

// The labels of a clip's >= 3 final nodes.
void write_labels(const Lines& lines, const Node* nodes, std::int32_t size, IntersectionPolygon& out) {
  const std::int32_t n = lines.n();
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
  const Lines lines{cp, tp};
  out.vertices.clear();
  out.edges.clear();
  Clip<Policy> clip(lines, ws);
  for (std::int32_t k = 0; k < lines.n() && clip.size() > 0; ++k) clip.by_line(k);
  if (clip.size() == 0) return Overlap::separate;
  if (clip.size() < 3) return Overlap::touch;
  write_labels(lines, clip.nodes(), clip.size(), out);
  assert((Policy::kind == PolicyKind::float_ || out.vertices.size() == static_cast<std::size_t>(clip.size())));
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
ROCKCONTACT_INSTANTIATE(Float)
ROCKCONTACT_INSTANTIATE(Filtered)
ROCKCONTACT_INSTANTIATE(Exact)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
