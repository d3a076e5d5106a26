#include "rockcontact/kernel/3d/contact_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "local_vector.hpp"
#include "rockcontact/kernel/3d/detail/separating_plane.hpp"
#include "rockcontact/kernel/3d/overlap.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/detail/exact_number.hpp"

namespace rockcontact::kernel {
namespace {

constexpr Point3 zero_point{0, 0, 0};
constexpr std::array<Point3, 3> axes = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

// A plane given by input points: normal (p1 - p0) x (q1 - q0), through `through`.
struct Plane {
  Point3 p0, p1, q0, q1, through;
};

// Under Float, whose signs may contradict each other, the searches below can come back empty;
// under the staged policies they cannot (the comments say why).
template <NumberPolicy Policy>
std::optional<Plane> zero_gap_plane(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  using detail::Gap;
  for (const auto& f : a.faces()) {
    if (detail::face_gap<Policy>(a, f, b) == Gap::zero) return Plane{a[f[0]], a[f[1]], a[f[0]], a[f[2]], a[f[0]]};
  }
  for (const auto& f : b.faces()) {
    if (detail::face_gap<Policy>(b, f, a) == Gap::zero) return Plane{b[f[0]], b[f[1]], b[f[0]], b[f[2]], b[f[0]]};
  }
  // A touching pair's zero-gap plane is a facet plane of the Minkowski difference: only the
  // edge pairs that may give a facet are tried.
  const detail::MinkowskiEdgePairs<Policy> pairs(a, b);
  for (std::size_t i = 0; i < a.edges().size(); ++i) {
    for (std::size_t j = 0; j < b.edges().size(); ++j) {
      const auto& ea = a.edges()[i];
      const auto& eb = b.edges()[j];
      if (pairs.may_be_facet(i, j) && detail::edge_gap<Policy>(a, ea, b, eb) == Gap::zero) {
        return Plane{a[ea.first], a[ea.second], b[eb.first], b[eb.second], a[ea.first]};
      }
    }
  }
  return std::nullopt;  // classify_overlap said touch: some candidate has a zero gap
}

// The block's feature on a supporting plane: its vertices on the plane, in the order of the
// face when there are three or more (a face, since the plane supports the block).
template <NumberPolicy Policy>
std::optional<std::vector<Point3>> feature(const ConvexPolyhedron& p, const Plane& plane) {
  std::vector<bool> on(p.size());
  std::vector<Point3> points;
  for (std::size_t i = 0; i < p.size(); ++i) {
    on[i] = triple_sign<Policy>(plane.p0, plane.p1, plane.q0, plane.q1, plane.through, p[i]) == Sign::zero;
    if (on[i]) points.push_back(p[i]);
  }
  if (points.size() < 3) return points;
  for (const auto& face : p.faces()) {
    if (std::all_of(face.begin(), face.end(), [&](std::uint32_t i) { return on[i]; })) {
      std::vector<Point3> loop;
      for (std::uint32_t i : face) loop.push_back(p[i]);
      return loop;
    }
  }
  return std::nullopt;  // a supporting plane meets a convex polyhedron in a face
}

// A corner of the intersection: an input vertex, or the crossing of segment p q with r s.
struct Corner {
  bool crossing;
  Point3 p, q, r, s;
};

template <NumberPolicy Policy>
struct PlanarIntersection {
  int axis;  // k: the normal's k-th component is non-zero

  // The in-plane orientation of coplanar input points, times a sign fixed by the plane.
  Sign orient(const Point3& p, const Point3& q, const Point3& r) const {
    return triple_sign<Policy>(p, q, p, r, zero_point, axes[axis]);
  }

  static bool between(const Point3& x, const Point3& p, const Point3& q) {
    return std::min(p.x, q.x) <= x.x && x.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= x.y &&
           x.y <= std::max(p.y, q.y) && std::min(p.z, q.z) <= x.z && x.z <= std::max(p.z, q.z);
  }

  // Is x in the closed convex feature f (a point, a segment or a strictly convex polygon)? A
  // point of a segment's line is on it when each coordinate lies between the ends'. A point
  // is outside a polygon exactly when its orientations against the edges take both signs: the
  // signed areas of the triangles (f_i, f_i+1, x) sum to the polygon's, so one has the
  // polygon's sign, and a point outside is on the other side of some edge.
  bool contains(const std::vector<Point3>& f, const Point3& x) const {
    if (f.size() == 1) return f[0] == x;
    if (f.size() == 2) return orient(f[0], f[1], x) == Sign::zero && between(x, f[0], f[1]);
    bool positive = false, negative = false;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const Sign s = orient(f[i], f[(i + 1) % f.size()], x);
      positive |= s == Sign::positive;
      negative |= s == Sign::negative;
    }
    return !(positive && negative);
  }

  bool crosses(const Point3& p, const Point3& q, const Point3& r, const Point3& s) const {
    return orient(p, q, r) * orient(p, q, s) == Sign::negative && orient(r, s, p) * orient(r, s, q) == Sign::negative;
  }

  static std::size_t edge_count(const std::vector<Point3>& f) { return f.size() < 3 ? f.size() - 1 : f.size(); }

  std::vector<Corner> corners(const std::vector<Point3>& fa, const std::vector<Point3>& fb) const {
    std::vector<Corner> out;
    for (const Point3& x : fa) {
      if (contains(fb, x)) out.push_back({false, x, {}, {}, {}});
    }
    for (const Point3& x : fb) {
      if (std::find(fa.begin(), fa.end(), x) == fa.end() && contains(fa, x)) out.push_back({false, x, {}, {}, {}});
    }
    for (std::size_t i = 0; i < edge_count(fa); ++i) {
      const Point3 &p = fa[i], &q = fa[(i + 1) % fa.size()];
      for (std::size_t j = 0; j < edge_count(fb); ++j) {
        const Point3 &r = fb[j], &s = fb[(j + 1) % fb.size()];
        if (crosses(p, q, r, s)) out.push_back({true, p, q, r, s});
      }
    }
    return out;
  }
};

// The plane normal's axes by decreasing magnitude of its double estimate.
std::array<int, 3> axes_by_magnitude(const Plane& plane) {
  const detail::Vector3<double> n = detail::cross(detail::local<double>(plane.p1, plane.p0),
                                                  detail::local<double>(plane.q1, plane.q0));
  const std::array<double, 3> m = {std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
  std::array<int, 3> order = {0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return m[i] > m[j]; });
  return order;
}

template <class FT>
FT coordinate(const detail::Vector3<FT>& v, int i) {
  return i == 0 ? v.x : i == 1 ? v.y : v.z;
}

// The crossing of segment p q with segment r s (coplanar, crossing properly): p + t (q - p),
// t = [(r - p) x (s - r)]_k / [(q - p) x (s - r)]_k, the 2D cross products in the projection
// along axis k.
template <class FT>
Point3 construct_crossing(const Corner& c, int k, const Point3& origin) {
  using detail::Vector3;
  const Vector3<FT> p = detail::local<FT>(c.p, origin), q = detail::local<FT>(c.q, origin);
  const Vector3<FT> r = detail::local<FT>(c.r, origin), s = detail::local<FT>(c.s, origin);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const auto cross2 = [&](const Vector3<FT>& u, const Vector3<FT>& v) -> FT {
    return coordinate(u, i) * coordinate(v, j) - coordinate(u, j) * coordinate(v, i);
  };
  const FT t = cross2(r - p, s - r) / cross2(q - p, s - r);
  return detail::global(p + t * (q - p), origin);
}

}  // namespace

template <NumberPolicy Policy>
std::optional<ContactSet> contact_set(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  if (classify_overlap<Policy>(a, b) != Overlap::touch) return std::nullopt;
  const std::optional<Plane> plane = zero_gap_plane<Policy>(a, b);
  if (!plane) return std::nullopt;
  const std::optional<std::vector<Point3>> fa = feature<Policy>(a, *plane), fb = feature<Policy>(b, *plane);
  if (!fa || !fb) return std::nullopt;
  const std::array<int, 3> order = axes_by_magnitude(*plane);
  int axis = order[0];
  for (int k : order) {
    axis = k;
    if (triple_sign<Policy>(plane->p0, plane->p1, plane->q0, plane->q1, zero_point, axes[k]) != Sign::zero) break;
  }
  const std::vector<Corner> corners = PlanarIntersection<Policy>{axis}.corners(*fa, *fb);
  if (corners.empty()) return std::nullopt;  // Float only: a touching pair's features meet
  ContactSet out{corners.size() >= 3 ? 2 : static_cast<int>(corners.size()) - 1, {}};
  for (const Corner& c : corners) {
    out.vertices.push_back(c.crossing ? construct_crossing<detail::ConstructionType<Policy>>(c, axis, plane->through)
                                      : c.p);
  }
  return out;
}

#define ROCKCONTACT_INSTANTIATE(P) \
  template std::optional<ContactSet> contact_set<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
