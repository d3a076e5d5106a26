// Contact constraints of two polyhedral blocks (contact_constraints.hpp has the method). The
// work of a part pair runs in two phases: decide (exact signs only: which features touch, which
// plane wins) into Decision records, then construct the points, normals and gaps from them in
// the policy's construction number type.

#include "rockcontact/kernel/3d/contact_constraints.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "box3.hpp"
#include "convex_clip2.hpp"
#include "rockcontact/kernel/3d/detail/separating_plane.hpp"
#include "rockcontact/kernel/3d/penetration.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/3d/tolerances.hpp"
#include "rockcontact/kernel/core/detail/exact_number.hpp"
#include "rockcontact/kernel/core/detail/staged_sign.hpp"

namespace rockcontact::kernel {
namespace {

using detail::As;
using detail::difference;

// ---- vectors generic over the number type ---------------------------------------------------

template <class T>
struct Vec {
  T x, y, z;
};

// b - a from input doubles, each component T(b) - T(a).
template <class T>
Vec<T> sub(const Point3& a, const Point3& b) {
  return {difference<T>(b.x, a.x), difference<T>(b.y, a.y), difference<T>(b.z, a.z)};
}

template <class T>
Vec<T> cross(const Vec<T>& u, const Vec<T>& v) {
  return {T(u.y * v.z) - T(u.z * v.y), T(u.z * v.x) - T(u.x * v.z), T(u.x * v.y) - T(u.y * v.x)};
}

template <class T>
T dot(const Vec<T>& u, const Vec<T>& v) {
  return T(T(u.x * v.x) + T(u.y * v.y)) + T(u.z * v.z);
}

// ---- exact signs of polynomial formulas ---------------------------------------------------

// The sign of a formula f(As<T>) of input doubles: in double under Float; under the staged
// policies by the interval stage, then CGAL::Mpzf (core/detail/staged_sign.hpp). The formulas
// here (degree 2 to 8 dot and cross products) have no double filter of their own: the interval
// stage is their filter, so each call counts as an interval fallback of PredicateKind::triple
// (the triple products themselves go through predicates.hpp and its static filter, and are
// tested first where they can reject). Checked also evaluates exactly and compares.
template <NumberPolicy Policy, class Formula>
Sign decide(const Formula& f) {
  if constexpr (Policy::kind == PolicyKind::float_) {
    detail::count_call(PredicateKind::triple);
    return sign_of(f(As<double>{}));
  } else {
    detail::count_call(PredicateKind::triple);
    const Sign staged = detail::interval_then_exact_sign(PredicateKind::triple, f);
    if constexpr (Policy::kind == PolicyKind::checked) {
      const Sign exact = detail::exact_sign(f);
      if (exact != staged) detail::throw_disagreement(PredicateKind::triple, {}, staged, exact);
    }
    return staged;
  }
}

// A signed distance N / sqrt(D), D > 0, as two formulas of input doubles (and the tolerance).
// compare_distances gives the exact sign of N1 / sqrt(D1) - N2 / sqrt(D2): by the signs of N1
// and N2 when they differ, else by the sign of N1^2 D2 - N2^2 D1 (flipped when both negative).
template <class N, class D>
struct Distance {
  N numerator;
  D denominator_squared;
};
template <class N, class D>
Distance(N, D) -> Distance<N, D>;

template <NumberPolicy Policy, class N1, class D1, class N2, class D2>
Sign compare_distances(const Distance<N1, D1>& a, const Distance<N2, D2>& b) {
  const Sign sa = decide<Policy>(a.numerator), sb = decide<Policy>(b.numerator);
  if (sa != sb) return static_cast<int>(sa) > static_cast<int>(sb) ? Sign::positive : Sign::negative;
  if (sa == Sign::zero) return Sign::zero;
  const Sign squares = decide<Policy>([&](auto as) {
    using T = typename decltype(as)::type;
    const T na = a.numerator(as), nb = b.numerator(as);
    return T(T(na * na) * b.denominator_squared(as)) - T(T(nb * nb) * a.denominator_squared(as));
  });
  return sa == Sign::positive ? squares : -squares;
}

// Is N / sqrt(D) <= tolerance? Exactly: N <= 0, or N^2 - tolerance^2 D <= 0.
template <NumberPolicy Policy, class N, class D>
bool within(const Distance<N, D>& d, double tolerance) {
  if (decide<Policy>(d.numerator) != Sign::positive) return true;
  return decide<Policy>([&](auto as) {
           using T = typename decltype(as)::type;
           const T n = d.numerator(as);
           return T(n * n) - T(T(T(tolerance) * T(tolerance)) * d.denominator_squared(as));
         }) != Sign::positive;
}

// Is sqrt(Q / D) <= tolerance, for a squared distance Q / D (D > 0)? Exactly: Q - tolerance^2 D <= 0.
template <NumberPolicy Policy, class Q, class D>
bool within_squared(const Q& q, const D& d, double tolerance) {
  return decide<Policy>([&](auto as) {
           using T = typename decltype(as)::type;
           return q(as) - T(T(T(tolerance) * T(tolerance)) * d(as));
         }) != Sign::positive;
}

// ---- topology of a convex part ----------------------------------------------------------------

struct Topology {
  const ConvexPolyhedron* poly;
  std::uint32_t part;
  std::vector<std::vector<std::uint32_t>> neighbours;    // per vertex
  std::vector<std::vector<std::uint32_t>> vertex_edges;  // per vertex, the edges to its neighbours
  std::vector<std::vector<std::uint32_t>> vertex_faces;  // per vertex
  // Per edge (first < second): [0] the face whose loop runs first -> second, [1] the other.
  std::vector<std::array<std::uint32_t, 2>> edge_faces;
  std::vector<bool> internal;  // per face
  // Per face: internal, and in the plane of an outer face of another part with the same outward
  // normal (mark_internal_faces): the face continues that face across a concave edge.
  std::vector<bool> continues_outer;

  const Point3& p(std::uint32_t i) const { return (*poly)[i]; }
  const ConvexPolyhedron::Face& face(std::uint32_t f) const { return poly->faces()[f]; }
  // A vertex of face f off the edge (i, j).
  std::uint32_t off_edge(std::uint32_t f, std::uint32_t i, std::uint32_t j) const {
    for (std::uint32_t k : face(f)) {
      if (k != i && k != j) return k;
    }
    return i;  // unreachable: a face has at least three distinct vertices
  }
};

Topology make_topology(const ConvexPolyhedron& poly, std::uint32_t part) {
  Topology t{&poly, part, {}, {}, {}, {}, std::vector<bool>(poly.faces().size(), false),
             std::vector<bool>(poly.faces().size(), false)};
  t.neighbours.resize(poly.size());
  t.vertex_edges.resize(poly.size());
  t.vertex_faces.resize(poly.size());
  std::map<ConvexPolyhedron::Edge, std::uint32_t> edge_index;
  for (std::uint32_t e = 0; e < poly.edges().size(); ++e) {
    const auto [i, j] = poly.edges()[e];
    edge_index[poly.edges()[e]] = e;
    t.neighbours[i].push_back(j);
    t.neighbours[j].push_back(i);
    t.vertex_edges[i].push_back(e);
    t.vertex_edges[j].push_back(e);
  }
  t.edge_faces.resize(poly.edges().size());
  for (std::uint32_t f = 0; f < poly.faces().size(); ++f) {
    const auto& loop = poly.faces()[f];
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::uint32_t i = loop[k], j = loop[(k + 1) % loop.size()];
      t.vertex_faces[i].push_back(f);
      t.edge_faces[edge_index.at({std::min(i, j), std::max(i, j)})][i < j ? 0 : 1] = f;
    }
  }
  return t;
}

// Height of v over face f, h_f = n_f . (v - f0) / |n_f|.
auto face_height(const Topology& t, std::uint32_t f, Point3 v) {
  const auto& loop = t.face(f);
  const Point3 f0 = t.p(loop[0]), f1 = t.p(loop[1]), f2 = t.p(loop[2]);
  return Distance{[=](auto as) {
                    using T = typename decltype(as)::type;
                    return dot(cross(sub<T>(f0, f1), sub<T>(f0, f2)), sub<T>(f0, v));
                  },
                  [=](auto as) {
                    using T = typename decltype(as)::type;
                    const Vec<T> n = cross(sub<T>(f0, f1), sub<T>(f0, f2));
                    return dot(n, n);
                  }};
}

// Whether `p` lies strictly inside the convex loop `g` of `t`, seen from `w`, a point off the
// loop's plane: on the loop's side of every plane through an edge of the loop and w.
template <NumberPolicy Policy>
bool inside_loop(const Topology& t, const ConvexPolyhedron::Face& g, const Point3& w, const Point3& p) {
  for (std::size_t k = 0; k < g.size(); ++k) {
    const Point3 &a = t.p(g[k]), &b = t.p(g[(k + 1) % g.size()]), &c = t.p(g[(k + 2) % g.size()]);
    const Sign side = orient3d<Policy>(a, b, w, p);
    if (side == Sign::zero || side != orient3d<Policy>(a, b, w, c)) return false;
  }
  return true;
}

Point3 loop_centroid(const Topology& t, const ConvexPolyhedron::Face& loop) {
  Point3 sum{0.0, 0.0, 0.0};
  for (const std::uint32_t k : loop) sum = {sum.x + t.p(k).x, sum.y + t.p(k).y, sum.z + t.p(k).z};
  const double n = static_cast<double>(loop.size());
  return {sum.x / n, sum.y / n, sum.z / n};
}

// Does every vertex of `loop` (a face of `other`) lie within `flush` of face f's plane?
template <NumberPolicy Policy>
bool in_face_plane(const Topology& t, std::uint32_t f, const Topology& other, const ConvexPolyhedron::Face& loop,
                   double flush) {
  return std::all_of(loop.begin(), loop.end(), [&](std::uint32_t k) {
    const auto height = face_height(t, f, other.p(k));
    const Distance depth{[&](auto as) { return -height.numerator(as); }, height.denominator_squared};
    return within<Policy>(height, flush) && within<Policy>(depth, flush);
  });
}

// Marks the faces of each part that lie against a face of another part of the same block: all
// the other face's vertices within `flush` (metres) of the plane, the other part on the plane's
// outer side, and the two faces overlapping (the centroid of one strictly inside the other, seen
// from the other part's vertex farthest above the plane), not only touching along an edge in
// the plane: a wedge's two joint faces meet the base's parts in one plane each, on both sides of
// the base's concave edge, and the face it rests on is no internal face. `flush` is
// face_planarity_tolerance times the block's size: parts cut from one block meet only to the
// rounding of their vertices, and an exact test would leave their shared faces as contact planes
// inside the block.
template <NumberPolicy Policy>
void mark_internal_faces(std::vector<Topology>& parts, double flush) {
  for (Topology& t : parts) {
    for (std::uint32_t f = 0; f < t.internal.size(); ++f) {
      const auto& loop = t.face(f);
      const Point3 &f0 = t.p(loop[0]), &f1 = t.p(loop[1]), &f2 = t.p(loop[2]);
      const Point3 centre = loop_centroid(t, loop);
      for (const Topology& other : parts) {
        if (&other == &t || t.internal[f]) continue;
        std::optional<Point3> above;
        double highest = 0.0;
        for (const Point3& x : other.poly->vertices()) {
          // Above by more than the rounding: a vertex the two parts share lies on the plane but for
          // it, and seen from there every point of the plane looks inside every loop.
          if (orient3d<Policy>(f0, f1, f2, x) != Sign::positive || within<Policy>(face_height(t, f, x), flush)) continue;
          const double h = std::abs(dot(cross(sub<double>(f0, f1), sub<double>(f0, f2)), sub<double>(f0, x)));
          if (!above || h > highest) above = x, highest = h;
        }
        if (!above) continue;
        for (const auto& g : other.poly->faces()) {
          if (in_face_plane<Policy>(t, f, other, g, flush) && (inside_loop<Policy>(other, g, *above, centre) ||
                           inside_loop<Policy>(t, loop, *above, loop_centroid(other, g)))) {
            t.internal[f] = true;
          }
        }
      }
    }
  }
  // An internal face in the plane of another part's outer face, facing the same way: a face of
  // the block's concave edge (the face of the keel part below a wedge's two joints, where the
  // joint faces of the parts beside it meet).
  for (Topology& t : parts) {
    for (std::uint32_t f = 0; f < t.internal.size(); ++f) {
      if (!t.internal[f]) continue;
      const auto& loop = t.face(f);
      const Point3 &f0 = t.p(loop[0]), &f1 = t.p(loop[1]), &f2 = t.p(loop[2]);
      const Vec<double> n = cross(sub<double>(f0, f1), sub<double>(f0, f2));
      for (const Topology& other : parts) {
        if (&other == &t || t.continues_outer[f]) continue;
        for (std::uint32_t g = 0; g < other.internal.size() && !t.continues_outer[f]; ++g) {
          if (other.internal[g]) continue;
          const auto& other_loop = other.face(g);
          const Vec<double> m = cross(sub<double>(other.p(other_loop[0]), other.p(other_loop[1])),
                                      sub<double>(other.p(other_loop[0]), other.p(other_loop[2])));
          t.continues_outer[f] = dot(n, m) > 0.0 && in_face_plane<Policy>(t, f, other, other_loop, flush);
        }
      }
    }
  }
}

// ---- the decisions ----------------------------------------------------------------------------

// A plane by its implicit normal sigma (p1 - p0) x (q1 - q0), oriented from the block X whose
// vertex or edge is located towards the other block Y, and where it comes from: a face of X or
// of Y, or an edge of each (x_index, y_index).
struct Plane {
  enum class Source : std::uint8_t { x_face, y_face, edge_pair };
  Point3 p0, p1, q0, q1;
  int sigma = 1;
  Source source = Source::x_face;
  std::uint32_t x_index = 0, y_index = 0;
};

template <class T>
Vec<T> plane_normal(const Plane& plane) {
  const Vec<T> n = cross(sub<T>(plane.p0, plane.p1), sub<T>(plane.q0, plane.q1));
  if (plane.sigma > 0) return n;
  return {T(0) - n.x, T(0) - n.y, T(0) - n.z};
}

// The plane of face f of X (outward normal, X -> Y) or of Y (inward normal).
Plane face_plane(const Topology& t, std::uint32_t f, Plane::Source source) {
  const auto& loop = t.face(f);
  if (source == Plane::Source::x_face) return {t.p(loop[0]), t.p(loop[1]), t.p(loop[0]), t.p(loop[2]), 1, source, f, 0};
  return {t.p(loop[0]), t.p(loop[1]), t.p(loop[0]), t.p(loop[2]), -1, source, 0, f};
}

// What a located vertex, or an edge pair, touches; enough to construct the constraint.
struct Decision {
  ConstraintType type;
  bool x_is_cp;          // X (the located vertex's block, cp for edge pairs) is cp
  Feature x_feature, y_feature;
  Point3 x0, x1;         // X's vertex (x0), or edge [x0, x1]
  Point3 y0, y1;         // Y's face point (y0 on the plane), edge [y0, y1], or vertex (y0)
  Plane plane;           // the contact plane's normal, X -> Y
  bool line_normal;      // no candidate passed: the normal is the unit of point_y - point_x
  bool touching;         // the two contact points coincide (exactly)
  // A touching vertex with no plane that separates the two blocks' tangent cones there: the
  // blocks overlap around it. It takes the pair's penetration plane (step 4 of the header), or
  // gives no constraint when the pair only touches.
  bool unseparated;
  Sign gap_sign;         // exact sign of the gap, when known (zero forces gap = 0)
  std::vector<Plane> candidates;
};

// Sign of ((q - p) x n_f) . (v - p) for the edge p -> q of face f's loop: positive when v
// projects onto f's plane outside the edge's line (degree 4).
template <NumberPolicy Policy>
Sign edge_side(const Topology& t, std::uint32_t f, const Point3& p, const Point3& q, const Point3& v) {
  const auto& loop = t.face(f);
  const Point3 &f0 = t.p(loop[0]), &f1 = t.p(loop[1]), &f2 = t.p(loop[2]);
  return decide<Policy>([&](auto as) {
    using T = typename decltype(as)::type;
    const Vec<T> n = cross(sub<T>(f0, f1), sub<T>(f0, f2));
    return dot(cross(sub<T>(p, q), n), sub<T>(p, v));
  });
}

// edge_side, but zero when v projects inside the edge's line by no more than `tie` (metres): a
// vertex meant to lie on an edge (a vertex of a block slid along a concave edge it rests in) is
// off it by the rounding of its move, and would otherwise fall into the Voronoi region of a
// face beside the edge, an internal one where two parts of a block meet (degree 8).
template <NumberPolicy Policy>
Sign edge_side_within(const Topology& t, std::uint32_t f, const Point3& p, const Point3& q, const Point3& v, double tie) {
  const Sign s = edge_side<Policy>(t, f, p, q, v);
  if (s != Sign::negative || !(tie > 0.0)) return s;
  const auto& loop = t.face(f);
  const Point3 &f0 = t.p(loop[0]), &f1 = t.p(loop[1]), &f2 = t.p(loop[2]);
  {  // In double first: beyond 2 tie by the estimate is beyond whatever its rounding.
    const Vec<double> m = cross(sub<double>(p, q), cross(sub<double>(f0, f1), sub<double>(f0, f2)));
    const double along = dot(m, sub<double>(p, v)), bound = 4.0 * tie * tie * dot(m, m);
    if (std::isfinite(bound) && along * along > bound) return s;
  }
  const Sign beyond = decide<Policy>([&](auto as) {
    using T = typename decltype(as)::type;
    const Vec<T> m = cross(sub<T>(p, q), cross(sub<T>(f0, f1), sub<T>(f0, f2)));
    const T along = dot(m, sub<T>(p, v));
    return T(T(along * along) - T(T(T(tie) * T(tie)) * dot(m, m)));
  });
  return beyond == Sign::positive ? s : Sign::zero;
}

// Sign of (v - a) . (b - a) (degree 2).
template <NumberPolicy Policy>
Sign dot_sign(const Point3& a, const Point3& v, const Point3& b) {
  return decide<Policy>([&](auto as) {
    using T = typename decltype(as)::type;
    return dot(sub<T>(a, v), sub<T>(a, b));
  });
}

struct Located {
  Feature::Kind kind;
  std::uint32_t index;
  bool inside;    // v strictly inside Y: a penetrating vertex
  bool touching;  // v on Y's boundary
  bool near;      // touching, or off the boundary by no more than the rounding (Ties::rounding)
};

// The slack of decisions about coincidence, metres, from the pair's extent: `tie` =
// same_contact_tolerance of it (the shortest exit's ties and a vertex on an edge's line, which
// choose among contacts but set no gap), `rounding` = coincidence_tolerance of it (a vertex off
// the feature it meets by no more than the rounding of a move: its no-overlap check takes
// cone_flush_angle; its gap stays the exact one).
struct Ties {
  double tie = 0.0;
  double rounding = 0.0;
};

// Can a vertex inside Y leave it through face f? Outer faces, and internal faces that continue
// an outer one: a vertex pushed past a concave edge of the block leaves by the plane of a face
// meeting there (§2.2.2), as the crest of a wedge settling into its base's keel part does.
bool exit_face(const Topology& y, std::uint32_t f) { return !y.internal[f] || y.continues_outer[f]; }

// The shortest exit of a vertex strictly inside Y: the exit face it is least deep below (eq. 4),
// ties to the lowest index.
template <NumberPolicy Policy>
std::optional<Located> shortest_exit_face(const Point3& v, const Topology& y) {
  std::optional<std::uint32_t> best;
  for (std::uint32_t f = 0; f < y.internal.size(); ++f) {
    if (!exit_face(y, f)) continue;
    if (!best || compare_distances<Policy>(face_height(y, f, v), face_height(y, *best, v)) == Sign::positive) {
      best = f;
    }
  }
  if (!best) return std::nullopt;
  return Located{Feature::Kind::face, *best, true, false, false};
}

// Step 1 of the header for a vertex v on or outside Y: the feature whose relative interior holds
// v's closest point, if within the tolerance. The three region tests are exclusive (the closest
// point lies in the relative interior of exactly one feature), so the first match is the answer.
template <NumberPolicy Policy>
std::optional<Located> closest_feature(const Point3& v, const Topology& y, const std::vector<Sign>& heights,
                                       bool touching, double tolerance, const Ties& ties) {
  const double tie = ties.tie;
  const ConvexPolyhedron& poly = *y.poly;
  for (std::uint32_t w = 0; w < poly.size(); ++w) {
    const Point3 pw = y.p(w);
    const bool region = std::all_of(y.neighbours[w].begin(), y.neighbours[w].end(), [&](std::uint32_t u) {
      return dot_sign<Policy>(pw, v, y.p(u)) != Sign::positive;
    });
    if (!region) continue;
    const auto squared = [&](auto as) {
      using T = typename decltype(as)::type;
      const Vec<T> d = sub<T>(pw, v);
      return dot(d, d);
    };
    const auto one = [](auto as) { return typename decltype(as)::type(1); };
    if (!touching && !within_squared<Policy>(squared, one, tolerance)) return std::nullopt;
    return Located{Feature::Kind::vertex, w, false, touching, touching || within_squared<Policy>(squared, one, ties.rounding)};
  }
  for (std::uint32_t e = 0; e < poly.edges().size(); ++e) {
    const Point3 a = y.p(poly.edges()[e].first), b = y.p(poly.edges()[e].second);
    const bool region = dot_sign<Policy>(a, v, b) == Sign::positive && dot_sign<Policy>(b, v, a) == Sign::positive &&
                        edge_side_within<Policy>(y, y.edge_faces[e][0], a, b, v, tie) != Sign::negative &&
                        edge_side_within<Policy>(y, y.edge_faces[e][1], b, a, v, tie) != Sign::negative;
    if (!region) continue;
    const auto squared = [&](auto as) {
      using T = typename decltype(as)::type;
      const Vec<T> c = cross(sub<T>(a, v), sub<T>(a, b));
      return dot(c, c);
    };
    const auto length = [&](auto as) {
      using T = typename decltype(as)::type;
      const Vec<T> d = sub<T>(a, b);
      return dot(d, d);
    };
    if (!touching && !within_squared<Policy>(squared, length, tolerance)) return std::nullopt;
    return Located{Feature::Kind::edge, e, false, touching,
                   touching || within_squared<Policy>(squared, length, ties.rounding)};
  }
  for (std::uint32_t f = 0; f < heights.size(); ++f) {
    if (heights[f] == Sign::negative) continue;
    const auto& loop = y.face(f);
    bool interior = true;
    for (std::size_t k = 0; k < loop.size() && interior; ++k) {
      interior = edge_side<Policy>(y, f, y.p(loop[k]), y.p(loop[(k + 1) % loop.size()]), v) == Sign::negative;
    }
    if (!interior) continue;
    if (y.internal[f] || (!touching && !within<Policy>(face_height(y, f, v), tolerance))) return std::nullopt;
    return Located{Feature::Kind::face, f, false, touching, touching};  // `near` serves step 3 only
  }
  return std::nullopt;  // only under Float, whose rounded signs may contradict each other
}

// Step 1 of the header: where vertex v of X stands against Y, if it is a contact.
template <NumberPolicy Policy>
std::optional<Located> locate_vertex(const Point3& v, const Topology& y, double tolerance, const Ties& ties) {
  const double tie = ties.tie;
  std::vector<Sign> heights(y.internal.size());
  bool inside = true, touching = true;
  for (std::uint32_t f = 0; f < heights.size(); ++f) {
    const auto& loop = y.face(f);
    heights[f] = orient3d<Policy>(y.p(loop[0]), y.p(loop[1]), y.p(loop[2]), v);
    inside &= heights[f] == Sign::negative;
    touching &= heights[f] != Sign::positive;
  }
  if (inside) {
    // Inside by no more than `tie` below some faces: on the boundary but for the rounding (a
    // block's vertex on an edge of the other, moved there along it), located as touching, so
    // the edge's candidate planes decide (step 3) and not the rounding of the depths.
    bool near = false;
    for (std::uint32_t f = 0; f < heights.size(); ++f) {
      const auto height = face_height(y, f, v);
      // In double first: deeper than 2 tie by the estimate is deeper whatever its rounding.
      const double n = height.numerator(As<double>{}), dd = height.denominator_squared(As<double>{});
      if (std::isfinite(dd) && n * n > 4.0 * tie * tie * dd) continue;
      const Distance depth{[&](auto as) { return -height.numerator(as); }, height.denominator_squared};
      if (within<Policy>(depth, tie)) heights[f] = Sign::zero, near = true;
    }
    if (near) {
      if (auto at = closest_feature<Policy>(v, y, heights, true, tolerance, ties)) return at;
    }
    return shortest_exit_face<Policy>(v, y);
  }
  if (!touching) {
    if (!(tolerance > 0.0)) return std::nullopt;
    // v's distance to Y is at least its height over any face: a cheap exact rejection.
    for (std::uint32_t f = 0; f < heights.size(); ++f) {
      if (heights[f] == Sign::positive && !within<Policy>(face_height(y, f, v), tolerance)) return std::nullopt;
    }
  }
  return closest_feature<Policy>(v, y, heights, touching, tolerance, ties);
}

// The tangent cone of a block at a contact point, by generators: rays (from, to) and lines
// (from, to), the directions to - from (lines in both senses).
struct Cone {
  std::vector<std::pair<Point3, Point3>> rays;
  std::vector<std::pair<Point3, Point3>> lines;
};

Cone vertex_cone(const Topology& t, std::uint32_t w) {
  Cone cone;
  for (std::uint32_t u : t.neighbours[w]) cone.rays.emplace_back(t.p(w), t.p(u));
  return cone;
}

Cone edge_cone(const Topology& t, std::uint32_t e) {
  const auto [i, j] = t.poly->edges()[e];
  Cone cone;
  cone.lines.emplace_back(t.p(i), t.p(j));
  for (std::uint32_t f : t.edge_faces[e]) cone.rays.emplace_back(t.p(i), t.p(t.off_edge(f, i, j)));
  return cone;
}

// The side of the plane through an edge pair (normal n = (p1 - p0) x (q1 - q0)) the direction
// r = r1 - r0 points to: the sign of n . r, or zero when r is within cone_flush_angle of the
// plane ((n . r)^2 <= sin^2 |n|^2 |r|^2, exact, degree 6; tolerances.hpp says why).
template <NumberPolicy Policy>
Sign flush_side(const Point3& p0, const Point3& p1, const Point3& q0, const Point3& q1, const Point3& r0,
                const Point3& r1, bool flush = true) {
  const Sign s = triple_sign<Policy>(p0, p1, q0, q1, r0, r1);
  if (s == Sign::zero || !flush) return s;
  {  // In double first: |n . r| above 1.4 sin |n| |r| is beyond whatever the rounding, which is
     // a few ulps of |n| |r|.
    const double ux = p1.x - p0.x, uy = p1.y - p0.y, uz = p1.z - p0.z;
    const double vx = q1.x - q0.x, vy = q1.y - q0.y, vz = q1.z - q0.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double rx = r1.x - r0.x, ry = r1.y - r0.y, rz = r1.z - r0.z;
    const double along = nx * rx + ny * ry + nz * rz;
    const double bound = 2.0 * cone_flush_sine * cone_flush_sine * (nx * nx + ny * ny + nz * nz) * (rx * rx + ry * ry + rz * rz);
    if (std::isfinite(bound) && along * along > bound) return s;
  }
  const Sign beyond = decide<Policy>([&](auto as) {
    using T = typename decltype(as)::type;
    const Vec<T> n = cross(sub<T>(p0, p1), sub<T>(q0, q1));
    const Vec<T> r = sub<T>(r0, r1);
    const T along = dot(n, r);
    return T(T(along * along) - T(T(cone_flush_sine * cone_flush_sine) * T(dot(n, n) * dot(r, r))));
  });
  return beyond == Sign::positive ? s : Sign::zero;
}

// The no-overlap check of §2.2.1 for a candidate plane oriented X -> Y: X's cone on its
// non-positive side, Y's on its non-negative side, each generator up to cone_flush_angle
// (flush_side): faces that are coplanar but for the rounding of moved or cut vertices, or a
// block tilted by its penalty settling, touch along the plane instead of crossing it.
template <NumberPolicy Policy>
bool separates(const Plane& plane, const Cone& x, const Cone& y, bool flush) {
  const auto side = [&](const std::pair<Point3, Point3>& r) {
    const Sign s = flush_side<Policy>(plane.p0, plane.p1, plane.q0, plane.q1, r.first, r.second, flush);
    return plane.sigma > 0 ? s : -s;
  };
  return std::all_of(x.rays.begin(), x.rays.end(), [&](const auto& r) { return side(r) != Sign::positive; }) &&
         std::all_of(y.rays.begin(), y.rays.end(), [&](const auto& r) { return side(r) != Sign::negative; }) &&
         std::all_of(y.lines.begin(), y.lines.end(), [&](const auto& r) { return side(r) == Sign::zero; });
}

// The separation distance of eq. 4 for a candidate plane, (p - v) . n / |n|, with p = y0 (a
// vertex of Y) or p = the projection of v on Y's edge [y0, y1]:
//   vertex: N = n . (y0 - v),                               D = |n|^2;
//   edge:   N = |d|^2 n . (y0 - v) + ((v - y0) . d)(d . n),  D = |d|^4 |n|^2,  d = y1 - y0.
auto candidate_distance(const Plane& plane, Point3 v, Point3 y0, Point3 y1, bool edge) {
  return Distance{[=](auto as) {
                    using T = typename decltype(as)::type;
                    const Vec<T> n = plane_normal<T>(plane);
                    const T base = dot(n, sub<T>(v, y0));
                    if (!edge) return base;
                    const Vec<T> d = sub<T>(y0, y1);
                    return T(T(dot(d, d) * base) + T(dot(sub<T>(y0, v), d) * dot(d, n)));
                  },
                  [=](auto as) {
                    using T = typename decltype(as)::type;
                    const Vec<T> n = plane_normal<T>(plane);
                    const T nn = dot(n, n);
                    if (!edge) return nn;
                    const Vec<T> d = sub<T>(y0, y1);
                    const T dd = dot(d, d);
                    return T(T(dd * dd) * nn);
                  }};
}

// Are [a, b] and [c, d] within cone_flush_angle of parallel (|n|^2 <= sin^2 |b - a|^2 |d - c|^2,
// n = (b - a) x (d - c), exact, degree 4)? Their crossing then runs along them a thousand
// times faster than they move across each other, and its plane is the rounding's: edges meant
// to be collinear (a block's edge slid along the concave edge it rests in) cross at an angle of
// 1e-16, where the construction divides by |n|^2 and gives no number. The vertices at the ends
// of their overlap carry such a contact, as for parallel edges; nor do they span a candidate
// plane of a vertex contact (step 3).
template <NumberPolicy Policy>
bool nearly_parallel(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = d.x - c.x, vy = d.y - c.y, vz = d.z - c.z;
  const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  const double bound = cone_flush_sine * cone_flush_sine * (ux * ux + uy * uy + uz * uz) * (vx * vx + vy * vy + vz * vz);
  if (std::isfinite(bound) && nx * nx + ny * ny + nz * nz > 2.0 * bound) return false;
  return decide<Policy>([&](auto as) {
           using T = typename decltype(as)::type;
           const Vec<T> u = sub<T>(a, b), v = sub<T>(c, d), n = cross(u, v);
           return T(dot(n, n) - T(T(T(cone_flush_sine * cone_flush_sine) * dot(u, u)) * dot(v, v)));
         }) != Sign::positive;
}

// Step 3 of the header: the candidate planes of a vertex-edge or vertex-vertex contact that pass
// the no-overlap check, in tie-break order, and the shortest exit among them.
template <NumberPolicy Policy>
void choose_plane(Decision& d, const Topology& x, std::uint32_t v, const Topology& y, const Located& at, double tie) {
  const bool edge = at.kind == Feature::Kind::edge;
  const Cone x_cone = vertex_cone(x, v);
  const Cone y_cone = edge ? edge_cone(y, at.index) : vertex_cone(y, at.index);
  const std::vector<std::uint32_t> y_faces = edge ? std::vector<std::uint32_t>{y.edge_faces[at.index][0],
                                                                                   y.edge_faces[at.index][1]}
                                                  : y.vertex_faces[at.index];
  const std::vector<std::uint32_t> y_edges = edge ? std::vector<std::uint32_t>{at.index} : y.vertex_edges[at.index];
  std::vector<Plane> planes;
  for (std::uint32_t f : y_faces) {
    if (!y.internal[f]) planes.push_back(face_plane(y, f, Plane::Source::y_face));
  }
  for (std::uint32_t f : x.vertex_faces[v]) {
    if (!x.internal[f]) planes.push_back(face_plane(x, f, Plane::Source::x_face));
  }
  for (std::size_t k = 0; k < x.neighbours[v].size(); ++k) {
    const Point3 u = x.p(x.neighbours[v][k]);
    for (std::uint32_t g : y_edges) {
      const Point3 c = y.p(y.poly->edges()[g].first), e = y.p(y.poly->edges()[g].second);
      if (nearly_parallel<Policy>(x.p(v), u, c, e)) continue;  // a plane of the rounding's, or none
      for (int sigma : {1, -1}) {
        planes.push_back({x.p(v), u, c, e, sigma, Plane::Source::edge_pair, x.vertex_edges[v][k], g});
      }
    }
  }
  for (const Plane& plane : planes) {
    if (separates<Policy>(plane, x_cone, y_cone, at.near)) d.candidates.push_back(plane);
  }
  const auto distance = [&](const Plane& plane) { return candidate_distance(plane, d.x0, d.y0, d.y1, edge); };
  // Distances within `tie` of each other are a tie, which the order above breaks: at a touch
  // between faces coplanar but for rounding (a block slid along the faces it rests on), every
  // candidate through the contact point is within a few ulps of 0, and their rounding, not the
  // geometry, would choose. Beyond `tie` (far above the rounding of the double estimate) the
  // larger distance wins.
  const auto estimate = [&](const Plane& plane) {
    const auto dd = distance(plane);
    return dd.numerator(As<double>{}) / std::sqrt(dd.denominator_squared(As<double>{}));
  };
  const Plane* best = nullptr;
  double best_distance = 0.0;
  for (const Plane& plane : d.candidates) {
    const double here = estimate(plane);
    if (!best || here > best_distance + tie) best = &plane, best_distance = here;
  }
  d.line_normal = best == nullptr;
  if (best) {
    d.plane = *best;
    d.gap_sign = d.touching ? Sign::zero : decide<Policy>(distance(*best).numerator);
  } else {
    d.gap_sign = Sign::positive;
  }
}

// Steps 1 and 3 for vertex v of X against Y.
template <NumberPolicy Policy>
std::optional<Decision> vertex_decision(const Topology& x, std::uint32_t v, bool x_is_cp, const Topology& y,
                                        double tolerance, const Ties& ties) {
  const std::optional<Located> at = locate_vertex<Policy>(x.p(v), y, tolerance, ties);
  if (!at) return std::nullopt;
  Decision d{};
  d.x_is_cp = x_is_cp;
  d.x_feature = {Feature::Kind::vertex, v, x.part};
  d.y_feature = {at->kind, at->index, y.part};
  d.x0 = d.x1 = x.p(v);
  d.touching = at->touching;
  switch (at->kind) {
    case Feature::Kind::face:
      d.type = ConstraintType::vertex_face;
      d.plane = face_plane(y, at->index, Plane::Source::y_face);
      d.y0 = d.y1 = y.p(y.face(at->index)[0]);
      d.gap_sign = at->touching ? Sign::zero : at->inside ? Sign::negative : Sign::positive;
      // A vertex on a face, with an edge of X leaving it into Y: the face's plane does not
      // separate the blocks there.
      d.unseparated = at->touching && !separates<Policy>(d.plane, vertex_cone(x, v), Cone{}, true);
      return d;
    case Feature::Kind::edge:
      d.type = ConstraintType::vertex_edge;
      d.y0 = y.p(y.poly->edges()[at->index].first);
      d.y1 = y.p(y.poly->edges()[at->index].second);
      break;
    case Feature::Kind::vertex:
      d.type = ConstraintType::vertex_vertex;
      d.y0 = d.y1 = y.p(at->index);
      break;
  }
  choose_plane<Policy>(d, x, v, y, *at, ties.tie);
  // A touch with no separating candidate: the blocks overlap around the touching point (a
  // corner of one on a coincident corner or edge of the other, as with identical blocks), or
  // the only separating plane is an internal face.
  d.unseparated = d.line_normal && d.touching;
  return d;
}

// The common non-zero sign of triple(origin -> x) against one normal over the given points, or
// zero when both signs occur or all are zero; a point within cone_flush_angle of the plane
// counts as on it (flush_side: a face of the edge coplanar with the other edge's but for rounding
// or settling, as where a block slides along a face and its edges cross the face's edges).
// The normal is that of `triple`, (b - a) x (d - c).
template <NumberPolicy Policy>
Sign common_side(const TripleSigns<Policy>& triple, const std::array<Point3, 4>& abcd, const Point3& origin,
                 std::initializer_list<Point3> points) {
  Sign side = Sign::zero;
  for (const Point3& p : points) {
    Sign s = triple(origin, p);
    if (s != Sign::zero && flush_side<Policy>(abcd[0], abcd[1], abcd[2], abcd[3], origin, p) == Sign::zero) {
      s = Sign::zero;
    }
    if (s == Sign::zero) continue;
    if (side != Sign::zero && s != side) return Sign::zero;
    side = s;
  }
  return side;
}

// Does the segment [a, b] meet the interior of part `t`? With h_f(a), h_f(b) the (scaled) heights
// of the endpoints over face f, the segment's points a + s (b - a) strictly below f's plane form
// an interval of s: s > h_f(a) / (h_f(a) - h_f(b)) when h_f(a) >= 0 > h_f(b), s < the same ratio
// when h_f(a) < 0 <= h_f(b), empty when neither is negative. The open intervals meet when every
// lower bound (face f) is below every upper bound (face g), i.e. (with the positive
// denominators h_f(a) - h_f(b) and h_g(b) - h_g(a)) when h_f(a) h_g(b) - h_g(a) h_f(b) < 0,
// degree 6.
template <NumberPolicy Policy>
bool segment_meets(const Topology& t, const Point3& a, const Point3& b) {
  const auto height = [&](std::uint32_t f, const Point3& x) {
    const auto& loop = t.face(f);
    const Point3 f0 = t.p(loop[0]), f1 = t.p(loop[1]), f2 = t.p(loop[2]);
    return [=](auto as) {
      using T = typename decltype(as)::type;
      return dot(cross(sub<T>(f0, f1), sub<T>(f0, f2)), sub<T>(f0, x));
    };
  };
  std::vector<std::uint32_t> lower, upper;
  for (std::uint32_t f = 0; f < t.internal.size(); ++f) {
    const auto& loop = t.face(f);
    const Sign ha = orient3d<Policy>(t.p(loop[0]), t.p(loop[1]), t.p(loop[2]), a);
    const Sign hb = orient3d<Policy>(t.p(loop[0]), t.p(loop[1]), t.p(loop[2]), b);
    if (ha != Sign::negative && hb != Sign::negative) return false;
    if (ha != Sign::negative) lower.push_back(f);
    if (hb != Sign::negative) upper.push_back(f);
  }
  for (std::uint32_t f : lower) {
    for (std::uint32_t g : upper) {
      const auto fa = height(f, a), fb = height(f, b), ga = height(g, a), gb = height(g, b);
      const Sign order = decide<Policy>([&](auto as) {
        using T = typename decltype(as)::type;
        return T(fa(as) * gb(as)) - T(ga(as) * fb(as));
      });
      if (order != Sign::negative) return false;
    }
  }
  return true;
}


// Step 2 of the header: edge e = [a, b] of X (cp) against edge g = [c, d] of Y (tp).
template <NumberPolicy Policy>
std::optional<Decision> edge_decision(const Topology& x, std::uint32_t e, const Topology& y, std::uint32_t g,
                                      double tolerance) {
  const auto [ia, ib] = x.poly->edges()[e];
  const auto [ic, id] = y.poly->edges()[g];
  const Point3 a = x.p(ia), b = x.p(ib), c = y.p(ic), d = y.p(id);
  // s = S / N2 on e, t = U / N2 on g (eq. 2-3): S = ((c - a) x (d - c)) . n,
  // U = ((c - a) x (b - a)) . n, N2 = |n|^2, n = (b - a) x (d - c).
  const auto n2 = [&](auto as) {
    using T = typename decltype(as)::type;
    const Vec<T> n = cross(sub<T>(a, b), sub<T>(c, d));
    return dot(n, n);
  };
  const auto along = [&](const Point3& p0, const Point3& p1) {
    return [&, p0, p1](auto as) {
      using T = typename decltype(as)::type;
      return dot(cross(sub<T>(a, c), sub<T>(p0, p1)), cross(sub<T>(a, b), sub<T>(c, d)));
    };
  };
  const auto s = along(c, d), u = along(a, b);
  const auto interior = [&](const auto& q) {
    return decide<Policy>(q) == Sign::positive && decide<Policy>([&](auto as) {
             using T = typename decltype(as)::type;
             return T(n2(as) - q(as));
           }) == Sign::positive;
  };
  // Cheapest first: the supporting sides and the gap's sign are triple products (static filter).
  // Parallel edges (n = 0) make every triple product zero, so side_x == 0 rejects them too.
  const auto [xf0, xf1] = x.edge_faces[e];
  const auto [yf0, yf1] = y.edge_faces[g];
  const TripleSigns<Policy> triple(a, b, c, d);
  const std::array<Point3, 4> abcd{a, b, c, d};
  const Sign side_x = common_side(triple, abcd, a, {x.p(x.off_edge(xf0, ia, ib)), x.p(x.off_edge(xf1, ia, ib))});
  if (side_x == Sign::zero) return std::nullopt;
  const Sign side_y = common_side(triple, abcd, c, {y.p(y.off_edge(yf0, ic, id)), y.p(y.off_edge(yf1, ic, id))});
  if (side_y != -side_x) return std::nullopt;
  if (nearly_parallel<Policy>(a, b, c, d)) return std::nullopt;
  const Plane plane{a, b, c, d, side_x == Sign::positive ? -1 : 1, Plane::Source::edge_pair, e, g};
  const Sign gap_sign = -side_x * triple(a, c);
  const auto gap = [=](auto as) {
    using T = typename decltype(as)::type;
    return dot(plane_normal<T>(plane), sub<T>(a, c));
  };
  if (gap_sign == Sign::positive && !within<Policy>(Distance{gap, n2}, tolerance)) return std::nullopt;
  if (!interior(s) || !interior(u)) return std::nullopt;
  if (gap_sign == Sign::negative && (!segment_meets<Policy>(y, a, b) || !segment_meets<Policy>(x, c, d))) {
    return std::nullopt;
  }
  Decision out{};
  out.type = ConstraintType::edge_edge;
  out.x_is_cp = true;
  out.x_feature = {Feature::Kind::edge, e, x.part};
  out.y_feature = {Feature::Kind::edge, g, y.part};
  out.x0 = a;
  out.x1 = b;
  out.y0 = c;
  out.y1 = d;
  out.plane = plane;
  out.touching = gap_sign == Sign::zero;
  out.gap_sign = gap_sign;
  return out;
}

// The facet side test of detail::MinkowskiEdgePairs's Gauss-map pruning, with an edge within
// cone_flush_angle of the facet's plane counted as in it (flush_side): where two faces are
// coplanar but for rounding or settling (a block sliding along the face it rests on), an edge of
// one crossing an edge of the other at a corner of their contact polygon has its arc end on the
// other's arc, which the exact signs would place just off it.
template <NumberPolicy Policy>
class FlushFacetSides {
 public:
  FlushFacetSides(const Point3& g0, const Point3& g1, const Point3& g2) : g0_(g0), g1_(g1), g2_(g2) {}
  Sign operator()(const Point3& e0, const Point3& e1) const { return flush_side<Policy>(g0_, g1_, g0_, g2_, e0, e1); }

 private:
  const Point3 &g0_, &g1_, &g2_;
};

using detail::Box3;
using detail::box_of;

template <NumberPolicy Policy>
void decide_pair(const Topology& cp, const Topology& tp, double tolerance, std::vector<Decision>& out) {
  Box3 pair = box_of({cp.poly, 1});  // the pair's extent, for its Ties
  pair.add({tp.poly, 1});
  const Ties ties{same_contact_tolerance * pair.size(), coincidence_tolerance * pair.size()};
  std::set<std::pair<std::uint32_t, std::uint32_t>> vertex_pairs;  // (cp vertex, tp vertex)
  for (std::uint32_t v = 0; v < cp.poly->size(); ++v) {
    if (auto d = vertex_decision<Policy>(cp, v, true, tp, tolerance, ties)) {
      if (d->type == ConstraintType::vertex_vertex) vertex_pairs.emplace(v, d->y_feature.index);
      out.push_back(std::move(*d));
    }
  }
  for (std::uint32_t w = 0; w < tp.poly->size(); ++w) {
    if (auto d = vertex_decision<Policy>(tp, w, false, cp, tolerance, ties)) {
      if (d->type == ConstraintType::vertex_vertex && vertex_pairs.count({d->y_feature.index, w})) continue;
      out.push_back(std::move(*d));
    }
  }
  // An edge-edge contact needs planes through e and g supporting cp and tp on opposite sides:
  // e x g is then a facet normal of the Minkowski difference, which the Gauss-map test keeps.
  const detail::MinkowskiEdgePairs<Policy, FlushFacetSides> edge_pairs(*cp.poly, *tp.poly);
  for (std::uint32_t e = 0; e < cp.poly->edges().size(); ++e) {
    for (std::uint32_t g = 0; g < tp.poly->edges().size(); ++g) {
      if (!edge_pairs.may_be_facet(e, g)) continue;
      if (auto d = edge_decision<Policy>(cp, e, tp, g, tolerance)) out.push_back(std::move(*d));
    }
  }
}

// ---- the constructions ------------------------------------------------------------------------

template <class FT>
struct Frame {
  using Ops = detail::NumberOps<FT>;
  Point3 origin;

  Vec<FT> at(const Point3& p) const {
    return {FT(Ops::from(p.x) - Ops::from(origin.x)), FT(Ops::from(p.y) - Ops::from(origin.y)),
            FT(Ops::from(p.z) - Ops::from(origin.z))};
  }
  Point3 back(const Vec<FT>& v) const {
    return {Ops::to_double(FT(v.x + Ops::from(origin.x))), Ops::to_double(FT(v.y + Ops::from(origin.y))),
            Ops::to_double(FT(v.z + Ops::from(origin.z)))};
  }
};

template <class FT>
Vec<FT> minus(const Vec<FT>& a, const Vec<FT>& b) {
  return {FT(a.x - b.x), FT(a.y - b.y), FT(a.z - b.z)};
}

// a + (k / m) d
template <class FT>
Vec<FT> advance_along(const Vec<FT>& a, const FT& k, const FT& m, const Vec<FT>& d) {
  const FT r = k / m;
  return {FT(a.x + FT(r * d.x)), FT(a.y + FT(r * d.y)), FT(a.z + FT(r * d.z))};
}

template <class FT>
Point3 unit(const Vec<FT>& v) {
  const FT length = detail::NumberOps<FT>::sqrt(dot(v, v));
  return {detail::NumberOps<FT>::to_double(FT(v.x / length)), detail::NumberOps<FT>::to_double(FT(v.y / length)),
          detail::NumberOps<FT>::to_double(FT(v.z / length))};
}

template <class FT>
Vec<FT> frame_normal(const Frame<FT>& frame, const Plane& plane) {
  const Vec<FT> n = cross(minus(frame.at(plane.p1), frame.at(plane.p0)), minus(frame.at(plane.q1), frame.at(plane.q0)));
  if (plane.sigma > 0) return n;
  return {FT(-n.x), FT(-n.y), FT(-n.z)};
}

Point3 negate(const Point3& p) { return {-p.x, -p.y, -p.z}; }

PlaneSource source_of(const Plane& plane, bool x_is_cp) {
  using Kind = PlaneSource::Kind;
  const std::uint32_t cp_index = x_is_cp ? plane.x_index : plane.y_index;
  const std::uint32_t tp_index = x_is_cp ? plane.y_index : plane.x_index;
  switch (plane.source) {
    case Plane::Source::x_face: return {x_is_cp ? Kind::cp_face : Kind::tp_face, cp_index, tp_index};
    case Plane::Source::y_face: return {x_is_cp ? Kind::tp_face : Kind::cp_face, cp_index, tp_index};
    case Plane::Source::edge_pair: break;
  }
  return {Kind::edge_pair, cp_index, tp_index};
}

// Tangent basis of §2.3: t1 = the unit projection onto the plane of the axis least aligned with
// the normal, t2 = n x t1.
void set_tangents(ContactConstraint& c) {
  const Point3& n = c.normal;
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  const Point3 axis = ax <= ay && ax <= az ? Point3{1, 0, 0} : ay <= az ? Point3{0, 1, 0} : Point3{0, 0, 1};
  const double k = axis.x * n.x + axis.y * n.y + axis.z * n.z;
  Point3 t{axis.x - k * n.x, axis.y - k * n.y, axis.z - k * n.z};
  const double length = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
  t = {t.x / length, t.y / length, t.z / length};
  c.tangent1 = t;
  c.tangent2 = {n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
}

template <class FT>
ContactConstraint construct(const Decision& d, const Frame<FT>& frame) {
  const Vec<FT> x0 = frame.at(d.x0), x1 = frame.at(d.x1), y0 = frame.at(d.y0), y1 = frame.at(d.y1);
  const Vec<FT> n = frame_normal(frame, d.plane);
  Vec<FT> px = x0, py = y0;
  switch (d.type) {
    case ConstraintType::vertex_face:  // eq. 1: the projection of the vertex on the face's plane
      py = advance_along(x0, dot(minus(y0, x0), n), dot(n, n), n);
      break;
    case ConstraintType::edge_edge: {  // eq. 2-3: the closest points of the two lines
      const Vec<FT> de = minus(x1, x0), dg = minus(y1, y0), m = cross(de, dg);
      const FT mm = dot(m, m);
      px = advance_along(x0, dot(cross(minus(y0, x0), dg), m), mm, de);
      py = advance_along(y0, dot(cross(minus(y0, x0), de), m), mm, dg);
      break;
    }
    case ConstraintType::vertex_edge: {  // §2.1 method (a): the projection on the edge
      const Vec<FT> dg = minus(y1, y0);
      py = advance_along(y0, dot(minus(x0, y0), dg), dot(dg, dg), dg);
      break;
    }
    case ConstraintType::vertex_vertex: break;
  }
  if (d.touching) py = px;
  ContactConstraint c;
  c.type = d.type;
  const Point3 normal = d.line_normal ? unit(minus(py, px)) : unit(n);
  // Contact points that are input vertices are returned as given, not through the frame.
  const bool x_vertex = d.type != ConstraintType::edge_edge;
  const Point3 point_x = x_vertex ? d.x0 : frame.back(px);
  const Point3 point_y = d.touching ? point_x : d.type == ConstraintType::vertex_vertex ? d.y0 : frame.back(py);
  if (d.gap_sign != Sign::zero) {
    const Vec<FT> gap = minus(py, px);
    const FT along = d.line_normal ? detail::NumberOps<FT>::sqrt(dot(gap, gap))
                                   : FT(dot(gap, n) / detail::NumberOps<FT>::sqrt(dot(n, n)));
    c.gap = detail::NumberOps<FT>::to_double(along);
    // A penetrating contact whose rounded gap came out positive (its exact gap a few ulps below
    // zero) is reported touching, as its decision says it holds.
    if (d.gap_sign == Sign::negative) c.gap = std::min(c.gap, 0.0);
  }
  c.entering = d.x_is_cp ? BlockRole::cp : BlockRole::tp;
  c.cp_feature = d.x_is_cp ? d.x_feature : d.y_feature;
  c.tp_feature = d.x_is_cp ? d.y_feature : d.x_feature;
  c.point_cp = d.x_is_cp ? point_x : point_y;
  c.point_tp = d.x_is_cp ? point_y : point_x;
  c.normal = d.x_is_cp ? normal : negate(normal);
  c.plane = d.line_normal ? PlaneSource{PlaneSource::Kind::contact_line, 0, 0} : source_of(d.plane, d.x_is_cp);
  for (const Plane& plane : d.candidates) {
    const Point3 u = unit(frame_normal(frame, plane));
    c.candidates.push_back({d.x_is_cp ? u : negate(u), source_of(plane, d.x_is_cp)});
  }
  set_tangents(c);
  return c;
}

// ---- step 4: the penetration plane of an overlapping part pair ----------------------------------

// The decisions of one convex part of cp against one of tp.
struct PartPair {
  const ConvexPolyhedron* cp;
  const ConvexPolyhedron* tp;
  std::uint32_t cp_part, tp_part;  // their positions in the blocks' lists of parts
  std::vector<Decision> decisions;
};

double dot3(const Point3& a, const Point3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Point3 along3(const Point3& p, double k, const Point3& n) { return {p.x + k * n.x, p.y + k * n.y, p.z + k * n.z}; }

// The support heights of an overlapping part pair along its penetration normal n, in a frame at
// cp's first vertex: cp reaches up to high (max over its vertices of (v - o) . n), tp down to
// low; high - low is the penetration depth (penetration.hpp), and every point of the overlap
// lies between the two planes.
struct Slab {
  Point3 origin, normal;
  double high = 0.0, low = 0.0, slack = 0.0;

  Slab(const ConvexPolyhedron& cp, const ConvexPolyhedron& tp, const Penetration& p)
      : origin(cp[0]), normal(p.normal) {
    high = -HUGE_VAL, low = HUGE_VAL;
    double extent = 0.0;
    for (const Point3& v : cp.vertices()) high = std::max(high, height(v)), extent = std::max(extent, distance(v));
    for (const Point3& w : tp.vertices()) low = std::min(low, height(w)), extent = std::max(extent, distance(w));
    slack = penetration_slack * extent;
  }
  Point3 local(const Point3& v) const { return {v.x - origin.x, v.y - origin.y, v.z - origin.z}; }
  double height(const Point3& v) const { return dot3(local(v), normal); }
  double distance(const Point3& v) const { return std::sqrt(dot3(local(v), local(v))); }
  // Where a point of the overlap projects onto the plane of height h.
  Point3 onto(const Point3& v, double h) const { return along3(v, h - height(v), normal); }
};

// The constraint of an unseparated vertex on the penetration plane: a vertex v of cp is pushed
// by the plane of tp's lowest points, gap = low - h(v); a vertex w of tp by the plane of cp's
// highest, gap = h(w) - high. Both lie in [-(high - low), 0]: v in tp is above tp's lowest
// point, w in cp below cp's highest.
ContactConstraint on_penetration_plane(const Decision& d, const Slab& slab) {
  ContactConstraint c;
  c.type = d.type;
  c.entering = d.x_is_cp ? BlockRole::cp : BlockRole::tp;
  c.cp_feature = d.x_is_cp ? d.x_feature : d.y_feature;
  c.tp_feature = d.x_is_cp ? d.y_feature : d.x_feature;
  c.point_cp = d.x_is_cp ? d.x0 : slab.onto(d.x0, slab.high);
  c.point_tp = d.x_is_cp ? slab.onto(d.x0, slab.low) : d.x0;
  c.normal = slab.normal;
  c.plane = {PlaneSource::Kind::penetration, 0, 0};
  c.gap = d.x_is_cp ? std::min(0.0, slab.low - slab.height(d.x0)) : std::min(0.0, slab.height(d.x0) - slab.high);
  set_tangents(c);
  return c;
}

// The convex hull, counter-clockwise, of 2D points (Andrew's monotone chain); collinear points
// and duplicates within `slack` (metres) dropped.
std::vector<std::array<double, 2>> hull2(std::vector<std::array<double, 2>> p, double slack) {
  std::sort(p.begin(), p.end());
  const auto turn = [](const auto& o, const auto& a, const auto& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  const auto scale = [&](const auto& o, const auto& b) { return std::hypot(b[0] - o[0], b[1] - o[1]); };
  std::vector<std::array<double, 2>> h(2 * p.size() + 1);
  std::size_t k = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = k;
    for (const auto& q : p) {
      while (k >= base + 2 && turn(h[k - 2], h[k - 1], q) <= slack * scale(h[k - 2], q)) --k;
      if (k == base || scale(h[k - 1], q) > slack) h[k++] = q;
    }
    if (k > base) --k;
    std::reverse(p.begin(), p.end());
  }
  h.resize(k);
  return h;
}

// Where two segments of the plane meet: the crossing of their lines, or for (nearly) parallel
// ones the middle of the four endpoints.
std::array<double, 2> crossing2(const std::vector<std::array<double, 2>>& a, const std::vector<std::array<double, 2>>& b) {
  const double ux = a[1][0] - a[0][0], uy = a[1][1] - a[0][1], vx = b[1][0] - b[0][0], vy = b[1][1] - b[0][1];
  const double det = ux * vy - uy * vx;
  if (std::fabs(det) <= 1e-12 * std::hypot(ux, uy) * std::hypot(vx, vy)) {
    return {0.25 * (a[0][0] + a[1][0] + b[0][0] + b[1][0]), 0.25 * (a[0][1] + a[1][1] + b[0][1] + b[1][1])};
  }
  const double t = ((b[0][0] - a[0][0]) * vy - (b[0][1] - a[0][1]) * vx) / det;
  return {a[0][0] + t * ux, a[0][1] + t * uy};
}

// The fallback of step 4 when no penetrating or touching contact holds an overlapping pair: the
// corners of the region where cp's support feature along n (its vertices within the slack of
// `high`) and tp's (within the slack of `low`) overlap in projection on the plane, each a
// constraint with the depth as its gap, between the two support planes.
void add_support_corners(const PartPair& pair, const Slab& slab, std::vector<ContactConstraint>& out) {
  const Point3 n = slab.normal;
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  const Point3 axis = ax <= ay && ax <= az ? Point3{1, 0, 0} : ay <= az ? Point3{0, 1, 0} : Point3{0, 0, 1};
  Point3 u = along3(axis, -dot3(axis, n), n);
  const double length = std::sqrt(dot3(u, u));
  u = {u.x / length, u.y / length, u.z / length};
  const Point3 w{n.y * u.z - n.z * u.y, n.z * u.x - n.x * u.z, n.x * u.y - n.y * u.x};
  const auto support = [&](const ConvexPolyhedron& poly, double level, std::vector<std::uint32_t>& ids) {
    std::vector<std::array<double, 2>> points;
    for (std::uint32_t i = 0; i < poly.size(); ++i) {
      if (std::fabs(slab.height(poly[i]) - level) > slab.slack) continue;
      ids.push_back(i);
      points.push_back({dot3(slab.local(poly[i]), u), dot3(slab.local(poly[i]), w)});
    }
    return points;
  };
  std::vector<std::uint32_t> cp_ids, tp_ids;
  const std::vector<std::array<double, 2>> top = support(*pair.cp, slab.high, cp_ids);
  const std::vector<std::array<double, 2>> bottom = support(*pair.tp, slab.low, tp_ids);
  std::vector<std::array<double, 2>> a = hull2(top, slab.slack), b = hull2(bottom, slab.slack);
  if (a.size() < b.size()) std::swap(a, b);
  std::vector<std::array<double, 2>> corners;
  if (b.size() == 1) {
    corners = b;  // a vertex against a vertex, an edge or a face: the vertex
  } else if (a.size() == 2) {
    corners = {crossing2(a, b)};  // two edges
  } else {
    // A support feature of one or two points (a vertex or an edge) is clipped by the other's
    // polygon: its points inside it, or its segment's part inside.
    corners = hull2(b.size() >= 3 ? detail::clip_convex2(a, b) : detail::clip_convex2(b, a), slab.slack);
    if (corners.empty()) corners = {b.front()};  // rounding lost a touch along an edge
  }
  const auto nearest = [&](const std::vector<std::array<double, 2>>& points, const std::vector<std::uint32_t>& ids,
                           const std::array<double, 2>& q) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < points.size(); ++i) {
      if (std::hypot(points[i][0] - q[0], points[i][1] - q[1]) <
          std::hypot(points[best][0] - q[0], points[best][1] - q[1])) {
        best = i;
      }
    }
    return ids[best];
  };
  for (const auto& q : corners) {
    const Point3 at = along3(along3(slab.origin, q[0], u), q[1], w);
    ContactConstraint c;
    c.type = ConstraintType::vertex_face;
    c.cp_feature = {Feature::Kind::vertex, nearest(top, cp_ids, q), pair.cp_part};
    c.tp_feature = {Feature::Kind::vertex, nearest(bottom, tp_ids, q), pair.tp_part};
    c.point_cp = along3(at, slab.high, n);
    c.point_tp = along3(at, slab.low, n);
    c.normal = n;
    c.plane = {PlaneSource::Kind::penetration, 0, 0};
    c.gap = std::min(0.0, slab.low - slab.high);
    set_tangents(c);
    out.push_back(c);
  }
}

// Step 4 of the header, for an overlapping part pair (its penetration given): drop constraints
// deeper than the pair, give the unseparated vertices the penetration plane, and the support
// corners when nothing else holds the pair.
// `closed[i]` is the exact verdict that found[i] touches or penetrates (its decision's gap sign),
// which decides whether anything holds the pair: a gap rounded to +1e-18 still holds it.
void fit_to_penetration(const PartPair& pair, const Penetration& depth, std::vector<ContactConstraint>& found,
                        std::vector<char>& closed) {
  const Slab slab(*pair.cp, *pair.tp, depth);
  const double deepest = slab.high - slab.low + slab.slack;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (found[i].gap < -deepest) continue;
    found[kept] = std::move(found[i]);
    closed[kept++] = closed[i];
  }
  found.resize(kept);
  closed.resize(kept);
  // A corner of cp on a corner of tp gives one such constraint from each vertex, at one position
  // on the plane: merge_coincident (step 5) keeps one.
  for (const Decision& d : pair.decisions) {
    if (!d.unseparated) continue;
    found.push_back(on_penetration_plane(d, slab));
    closed.push_back(1);
  }
  if (std::none_of(closed.begin(), closed.end(), [](char k) { return k != 0; })) add_support_corners(pair, slab, found);
}


template <NumberPolicy Policy>
std::vector<Topology> topologies(std::span<const ConvexPolyhedron> parts) {
  std::vector<Topology> out;
  for (std::uint32_t i = 0; i < parts.size(); ++i) out.push_back(make_topology(parts[i], i));
  mark_internal_faces<Policy>(out, face_planarity_tolerance * box_of(parts).size());
  return out;
}

}  // namespace

template <NumberPolicy Policy>
std::vector<ContactConstraint> contact_constraints(std::span<const ConvexPolyhedron> cp_parts,
                                                   std::span<const ConvexPolyhedron> tp_parts, double tolerance) {
  if (!std::isfinite(tolerance) || tolerance < 0.0) {
    throw std::invalid_argument("contact_constraints: the tolerance must be finite and >= 0 (metres), got " +
                                std::to_string(tolerance));
  }
  std::vector<PartPair> pairs;
  const std::vector<Topology> cp = topologies<Policy>(cp_parts), tp = topologies<Policy>(tp_parts);
  for (const Topology& a : cp) {
    for (const Topology& b : tp) {
      PartPair pair{a.poly, b.poly, a.part, b.part, {}};
      decide_pair<Policy>(a, b, tolerance, pair.decisions);
      pairs.push_back(std::move(pair));
    }
  }
  std::vector<ContactConstraint> out;
  using FT = detail::ConstructionType<Policy>;
  const Frame<FT> frame{cp_parts.front().vertices().front()};
  for (const PartPair& pair : pairs) {
    // Step 4 of the header, for a pair with a penetrating or an unseparated contact, or with no
    // closed one whose boxes' interiors meet: a needle through a block overlaps it with no
    // vertex inside and no edge pair crossing. A pair that touches at every contact it has does
    // not overlap, nor does one whose boxes at most touch (most pairs the engine asks within
    // its detection range), which spares them the overlap verdict.
    const bool may_overlap = std::any_of(pair.decisions.begin(), pair.decisions.end(), [](const Decision& d) {
      return d.gap_sign == Sign::negative || d.unseparated;
    }) || (std::none_of(pair.decisions.begin(), pair.decisions.end(), [](const Decision& d) {
      return d.gap_sign != Sign::positive;
    }) && box_of({pair.cp, 1}).interiors_meet(box_of({pair.tp, 1})));
    const std::optional<Penetration> depth =
        may_overlap ? penetration<Policy>(*pair.cp, *pair.tp) : std::optional<Penetration>();
    std::vector<ContactConstraint> found;
    std::vector<char> closed;
    for (const Decision& d : pair.decisions) {
      if (d.unseparated) continue;
      found.push_back(construct(d, frame));
      closed.push_back(d.gap_sign != Sign::positive);
    }
    if (depth) fit_to_penetration(pair, *depth, found, closed);
    for (ContactConstraint& c : found) out.push_back(std::move(c));
  }
  Box3 pair = box_of(cp_parts);
  pair.add(tp_parts);
  merge_coincident(out, same_contact_tolerance * pair.size());
  return out;
}

template <NumberPolicy Policy>
std::vector<ContactConstraint> contact_constraints(const ConvexPolyhedron& cp, const ConvexPolyhedron& tp,
                                                   double tolerance) {
  return contact_constraints<Policy>(std::span<const ConvexPolyhedron>(&cp, 1),
                                     std::span<const ConvexPolyhedron>(&tp, 1), tolerance);
}

void merge_coincident(std::vector<ContactConstraint>& constraints, double near) {
  // The midpoints of the two constraints' points: the same position when they agree across the
  // plane, and along it within the deeper gap (a vertex of cp on tp's face and tp's vertex at
  // the same place on cp's face, as where two cut blocks share a corner).
  const auto same = [&](const ContactConstraint& a, const ContactConstraint& b) {
    if (dot3(a.normal, b.normal) < 1.0 - same_contact_tolerance) return false;
    const Point3 d{0.5 * (a.point_cp.x + a.point_tp.x - b.point_cp.x - b.point_tp.x),
                   0.5 * (a.point_cp.y + a.point_tp.y - b.point_cp.y - b.point_tp.y),
                   0.5 * (a.point_cp.z + a.point_tp.z - b.point_cp.z - b.point_tp.z)};
    const double along = dot3(d, a.normal);
    const double across = std::sqrt(std::max(0.0, dot3(d, d) - along * along));
    return across <= near && std::fabs(along) <= std::max(std::fabs(a.gap), std::fabs(b.gap)) + near;
  };
  std::vector<ContactConstraint> kept;
  for (ContactConstraint& c : constraints) {
    const auto twin = std::find_if(kept.begin(), kept.end(), [&](const ContactConstraint& k) { return same(k, c); });
    if (twin == kept.end()) {
      kept.push_back(std::move(c));
    } else if (c.gap < twin->gap - near) {
      *twin = std::move(c);
    }
  }
  constraints = std::move(kept);
}

std::optional<Point3> sliding_direction(const Point3& normal, const Point3& relative, double tolerance) {
  const double along = relative.x * normal.x + relative.y * normal.y + relative.z * normal.z;
  const Point3 t{relative.x - along * normal.x, relative.y - along * normal.y, relative.z - along * normal.z};
  const double length = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
  if (!(length > tolerance) || length == 0.0) return std::nullopt;
  return Point3{t.x / length, t.y / length, t.z / length};
}

#define ROCKCONTACT_INSTANTIATE(P)                                                                              \
  template std::vector<ContactConstraint> contact_constraints<P>(const ConvexPolyhedron&, const ConvexPolyhedron&, \
                                                                 double);                                       \
  template std::vector<ContactConstraint> contact_constraints<P>(                                                \
      std::span<const ConvexPolyhedron>, std::span<const ConvexPolyhedron>, double);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
