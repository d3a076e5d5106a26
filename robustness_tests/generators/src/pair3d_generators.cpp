#include "rockcontact/generators/pair3d_generators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rng.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::robustness {
namespace {

using detail::mix;
using detail::Rng;
using kernel::ConvexPolyhedron;
using kernel::Overlap;
using kernel::Point3;
using Points = std::vector<Point3>;

// The grids of the exact families (pair3d_generators.hpp): drawn coordinates on 2^-20 m,
// chamfers on 2^-40 m, moves of 2^-j with j <= 50, all below 2 m in magnitude.
constexpr int draw_grid = -20;
constexpr int fine_grid = -40;
constexpr int min_move = 20;
constexpr int max_move = 50;
constexpr int offset_grid = -32;

double snap(double x, int grid_exponent) {
  return std::ldexp(std::round(std::ldexp(x, -grid_exponent)), grid_exponent);
}
Point3 snap(const Point3& p, int e) { return {snap(p.x, e), snap(p.y, e), snap(p.z, e)}; }
double grid(Rng& rng, double lo, double hi) { return snap(rng.uniform(lo, hi), draw_grid); }

Point3 operator+(const Point3& a, const Point3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Point3 operator-(const Point3& a, const Point3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Point3 operator*(double s, const Point3& a) { return {s * a.x, s * a.y, s * a.z}; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Point3& a, const Point3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

template <class... Args>
std::string format(const char* pattern, Args... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, pattern, args...);
  return buffer;
}

[[noreturn]] void generator_bug(const std::string& what) { throw std::logic_error("pair3d generator: " + what); }

// A point uniform in the unit ball (rejection from the cube; one draw per statement).
Point3 in_ball(Rng& rng) {
  for (;;) {
    const double x = rng.uniform(-1.0, 1.0);
    const double y = rng.uniform(-1.0, 1.0);
    const double z = rng.uniform(-1.0, 1.0);
    if (x * x + y * y + z * z <= 1.0) return {x, y, z};
  }
}

Point3 unit_direction(Rng& rng) {
  for (;;) {
    const Point3 p = in_ball(rng);
    const double n = std::sqrt(dot(p, p));
    if (n > 0.1) return (1.0 / n) * p;
  }
}

// 8-20 points in an ellipsoid of semi-axes 0.3-0.6 m about `centre`.
Points ellipsoid_points(Rng& rng, const Point3& centre) {
  const auto n = static_cast<std::size_t>(rng.integer(8, 20));
  const double ax = rng.uniform(0.3, 0.6);
  const double ay = rng.uniform(0.3, 0.6);
  const double az = rng.uniform(0.3, 0.6);
  Points points;
  for (std::size_t i = 0; i < n; ++i) {
    const Point3 u = in_ball(rng);
    points.push_back(centre + Point3{ax * u.x, ay * u.y, az * u.z});
  }
  return points;
}

// n dyadic points with x, y in [-0.7, 0.7] and z in [z_lo, z_hi] (z_lo, z_hi of one sign).
void add_slab_points(Rng& rng, Points& points, std::size_t n, double z_lo, double z_hi) {
  for (std::size_t i = 0; i < n; ++i) {
    const double x = grid(rng, -0.7, 0.7);
    const double y = grid(rng, -0.7, 0.7);
    const double z = grid(rng, z_lo, z_hi);
    points.push_back({x, y, z});
  }
}

// A top face polygon in z = 0 with one corner in each open quadrant: it contains the origin
// strictly inside (a line through the origin leaves some open quadrant strictly on one side).
Points quadrant_face(Rng& rng) {
  Points face;
  for (const auto& [sx, sy] : {std::pair{1.0, 1.0}, {-1.0, 1.0}, {-1.0, -1.0}, {1.0, -1.0}}) {
    const double x = grid(rng, 0.2, 0.6);
    const double y = grid(rng, 0.2, 0.6);
    face.push_back({sx * x, sy * y, 0.0});
  }
  return face;
}

// Raw output of a family: two point sets (hulled later), the implied verdict, parameters.
struct RawPair {
  Points a;
  Points b;
  std::optional<Overlap> expected;
  std::string recipe;
};

// The touch / gap / push variants of a construction with `a` in z <= 0, `b` in z >= 0 (or
// along `axis` for short_edges): b moved by +2^-j (separate) or -2^-j (overlap) along it,
// j in [min_exponent, 50] (a larger min_exponent when the overlap needs a shallow push).
void place(Rng& rng, RawPair& pair, const Point3& axis, int min_exponent = min_move) {
  const double choice = rng.unit();
  if (choice < 0.5) {
    pair.expected = Overlap::touch;
    pair.recipe += ", placement touch";
    return;
  }
  const auto j = static_cast<int>(rng.integer(min_exponent, max_move));
  const double h = choice < 0.75 ? std::ldexp(1.0, -j) : -std::ldexp(1.0, -j);
  for (Point3& p : pair.b) p = p + h * axis;
  pair.expected = h > 0 ? Overlap::separate : Overlap::overlap;
  pair.recipe += format(", placement %s 2^-%d", h > 0 ? "gap" : "push", j);
}

constexpr Point3 up{0.0, 0.0, 1.0};

// ---- the families --------------------------------------------------------------------------

RawPair random_pair(Rng& rng) {
  RawPair pair;
  pair.a = ellipsoid_points(rng, {0, 0, 0});
  const Point3 dir = unit_direction(rng);
  const double distance = rng.uniform(0.0, 1.6);
  pair.b = ellipsoid_points(rng, distance * dir);
  pair.recipe = format("distance %g", distance);
  return pair;
}

// a below z = 0 with the top face `top`: `top` plus 4-12 points deep below.
Points block_below(Rng& rng, Points top) {
  add_slab_points(rng, top, static_cast<std::size_t>(rng.integer(4, 12)), -1.0, -0.1);
  return top;
}
Points block_above(Rng& rng, Points bottom) {
  add_slab_points(rng, bottom, static_cast<std::size_t>(rng.integer(4, 12)), 0.1, 1.0);
  return bottom;
}

std::optional<RawPair> face_face(Rng& rng) {
  RawPair pair;
  if (rng.chance(0.5)) {
    // Two quadrant faces in z = 0: both contain the origin, so they share a polygon of
    // positive area (a pushed pair shares the interior points just below the origin).
    pair.a = block_below(rng, quadrant_face(rng));
    pair.b = block_above(rng, quadrant_face(rng));
    pair.recipe = "axis plane";
    place(rng, pair, up);
    return pair;
  }
  // A copy of a face of a random hull: b's points are k >= 3 of the face's corners (in convex
  // position, exactly in its plane) and points strictly outside the plane (checked exactly).
  const std::optional<ConvexPolyhedron> a = convex_hull3("a", ellipsoid_points(rng, {0, 0, 0}));
  if (!a) return std::nullopt;
  const ConvexPolyhedron::Face& face = a->faces()[rng.index(a->faces().size())];
  const Point3 &f0 = (*a)[face[0]], &f1 = (*a)[face[1]], &f2 = (*a)[face[2]];
  const Point3 n = cross(f1 - f0, f2 - f0);
  const Point3 normal = (1.0 / std::sqrt(dot(n, n))) * n;
  const std::size_t first = rng.index(face.size());
  const auto count = static_cast<std::size_t>(rng.integer(3, static_cast<std::int64_t>(face.size())));
  for (std::size_t k = 0; k < count; ++k) pair.b.push_back((*a)[face[(first + k) % face.size()]]);
  const Point3 c = (1.0 / 3.0) * (f0 + f1 + f2);
  const auto above = static_cast<std::size_t>(rng.integer(4, 12));
  for (std::size_t k = 0; k < above; ++k) {
    const Point3 lateral = 0.5 * in_ball(rng);
    const double height = rng.uniform(0.1, 0.8);
    const Point3 q = c + lateral + height * normal;
    if (kernel::orient3d<kernel::Filtered>(f0, f1, f2, q) == kernel::Sign::positive) pair.b.push_back(q);
  }
  if (pair.b.size() == count) return std::nullopt;
  pair.a.assign(a->vertices().begin(), a->vertices().end());
  pair.expected = Overlap::touch;
  pair.recipe = format("copied face of %zu corners, %zu kept", face.size(), count);
  return pair;
}

// a's top edge (-a1, 0, 0) -> (a2, 0, 0) with (t, +-w, -d) below the edge point (t, 0, 0):
// that point minus a small h ez is inside a (a tetrahedron's interior).
Points ridge_block(Rng& rng, double t) {
  const double a1 = grid(rng, 0.3, 0.6);
  const double a2 = grid(rng, 0.3, 0.6);
  const double w1 = grid(rng, 0.1, 0.5);
  const double w2 = grid(rng, 0.1, 0.5);
  const double d = grid(rng, 0.1, 0.8);
  Points a{{-a1, 0, 0}, {a2, 0, 0}, {t, w1, -d}, {t, -w2, -d}};
  add_slab_points(rng, a, static_cast<std::size_t>(rng.integer(2, 10)), -1.0, -0.1);
  return a;
}

RawPair edge_edge(Rng& rng) {
  RawPair pair;
  pair.a = ridge_block(rng, 0.0);
  // b's bottom edge s (dx, dy, 0), s in [-s_lo, s_hi], through the origin; (dx, dy) a small
  // integer direction not along x, so the edges cross at the origin, inside both.
  const double dx = static_cast<double>(rng.integer(-16, 16));
  const double dy = static_cast<double>(rng.integer(1, 16));
  const double scale = 1.0 / std::max(std::fabs(dx), dy);
  const double s_lo = snap(rng.uniform(0.3, 0.6) * scale, draw_grid);
  const double s_hi = snap(rng.uniform(0.3, 0.6) * scale, draw_grid);
  const double w = snap(rng.uniform(0.1, 0.4) * scale, draw_grid);
  const double h = grid(rng, 0.1, 0.8);
  pair.b = {{-s_lo * dx, -s_lo * dy, 0}, {s_hi * dx, s_hi * dy, 0}, {-w * dy, w * dx, h}, {w * dy, -w * dx, h}};
  add_slab_points(rng, pair.b, static_cast<std::size_t>(rng.integer(2, 10)), 0.1, 1.0);
  pair.recipe = format("b edge direction (%g, %g, 0)", dx, dy);
  place(rng, pair, up);
  return pair;
}

RawPair vertex_face(Rng& rng) {
  RawPair pair;
  pair.a = block_below(rng, quadrant_face(rng));
  pair.b = block_above(rng, {{0, 0, 0}});
  pair.recipe = "b apex at the origin";
  place(rng, pair, up);
  return pair;
}

RawPair vertex_edge(Rng& rng) {
  RawPair pair;
  // The apex at t on a's top edge, strictly inside it (|t| < 0.25 < a1, a2).
  const double t = grid(rng, -0.25, 0.25);
  pair.a = ridge_block(rng, t);
  pair.b = block_above(rng, {{t, 0, 0}});
  pair.recipe = format("b apex at (%.17g, 0, 0)", t);
  place(rng, pair, up);
  return pair;
}

// b's bottom face z = s (x - x0) with s a dyadic rounding of tan θ (2^-20: exact products
// with the 2^-20 grid), lowest corner (x0, y0, 0) strictly inside a's top face, the square
// [-L, L]^2; half the time a second corner (x0, y1, 0) makes the contact an edge.
RawPair near_parallel(Rng& rng, double tan_theta, const char* angle) {
  RawPair pair;
  const double s = snap(tan_theta, draw_grid);
  const double l = grid(rng, 0.4, 0.6);
  pair.a = block_below(rng, {{-l, -l, 0}, {l, -l, 0}, {l, l, 0}, {-l, l, 0}});
  const double x0 = grid(rng, -l / 2, l / 2);
  const double y0 = grid(rng, -l / 2, l / 2);
  pair.b = {{x0, y0, 0}};
  bool edge = false;
  if (rng.chance(0.5)) {
    const double y1 = grid(rng, -l / 2, l / 2);
    edge = y1 != y0;
    if (edge) pair.b.push_back({x0, y1, 0});
  }
  const auto n = static_cast<std::size_t>(rng.integer(3, 8));
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = grid(rng, 0.05, 1.0);
    const double dy = grid(rng, -0.5, 0.5);
    pair.b.push_back({x0 + dx, y0 + dy, s * dx});
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = grid(rng, 0.0, 1.0);
    const double dy = grid(rng, -0.5, 0.5);
    const double h = grid(rng, 0.1, 0.8);
    pair.b.push_back({x0 + dx, y0 + dy, s * dx + h});
  }
  pair.recipe = format("angle %s slope %.17g, %s contact", angle, s, edge ? "edge" : "vertex");
  place(rng, pair, up);
  return pair;
}

RawPair sliver(Rng& rng) {
  RawPair pair;
  const double thickness = snap(rng.log_uniform(1e-6, 1e-2), -50);
  if (rng.chance(0.5)) {
    // A slab: a quadrant face at z = 0 over the same polygon at z = -thickness; b's apex on
    // the top face, pushed by less than half the thickness (its apex stays inside the slab).
    const Points top = quadrant_face(rng);
    pair.a = top;
    for (const Point3& p : top) pair.a.push_back({p.x, p.y, -thickness});
    pair.b = block_above(rng, {{0, 0, 0}});
    pair.recipe = format("slab thickness %g", thickness);
    place(rng, pair, up, 1 - std::ilogb(thickness));
    return pair;
  }
  // A needle along x through a random hull at a random offset.
  for (const double x : {-0.5, 0.5}) {
    for (int k = 0; k < 3; ++k) {
      const double y = rng.uniform(-thickness, thickness);
      const double z = rng.uniform(-thickness, thickness);
      pair.a.push_back({x, y, z});
    }
  }
  const Point3 offset = 0.6 * in_ball(rng);
  pair.b = ellipsoid_points(rng, offset);
  pair.recipe = format("needle thickness %g", thickness);
  return pair;
}

// A cuboid of half-sizes (hx, hy, hz) with every corner cut by three points c from it along
// its edges (c = 2^-40-rounded 0.01/sqrt 2: the cut triangles have 0.01 m edges).
Points chamfered_cuboid(double hx, double hy, double hz) {
  const double c = snap(0.01 / std::sqrt(2.0), fine_grid);
  Points points;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      for (const double sz : {-1.0, 1.0}) {
        points.push_back({sx * (hx - c), sy * hy, sz * hz});
        points.push_back({sx * hx, sy * (hy - c), sz * hz});
        points.push_back({sx * hx, sy * hy, sz * (hz - c)});
      }
    }
  }
  return points;
}

RawPair short_edges(Rng& rng) {
  RawPair pair;
  const double hx = grid(rng, 0.3, 0.6);
  const double hy = grid(rng, 0.3, 0.6);
  const double hz = grid(rng, 0.3, 0.6);
  pair.a = chamfered_cuboid(hx, hy, hz);
  // The mirror image across x = hx (2 hx - x: exact on the 2^-40 grid), moved sideways by
  // less than a quarter of the face: the two x = hx faces share the origin's neighbourhood.
  const double dy = grid(rng, -hy / 4, hy / 4);
  const double dz = grid(rng, -hz / 4, hz / 4);
  for (const Point3& p : pair.a) pair.b.push_back({2 * hx - p.x, p.y + dy, p.z + dz});
  pair.recipe = format("half sizes %.17g %.17g %.17g, sideways %.17g %.17g", hx, hy, hz, dy, dz);
  place(rng, pair, {1.0, 0.0, 0.0});
  return pair;
}

RawPair deformed(Rng& rng) {
  RawPair pair;
  const double hx = grid(rng, 0.3, 0.6);
  const double hy = grid(rng, 0.3, 0.6);
  const double hz = grid(rng, 0.3, 0.6);
  const double gap = rng.uniform(-1e-3, 1e-3);
  Points box;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      for (const double sz : {-1.0, 1.0}) box.push_back({sx * hx, sy * hy, sz * hz});
    }
  }
  // x -> (I + E) x + jitter, E up to 1e-3 per entry, jitter 1e-12 .. 1e-6 per coordinate.
  const auto deform = [&rng](Points points, const Point3& shift) {
    double e[3][3];
    for (auto& row : e) {
      for (double& x : row) x = rng.uniform(-1e-3, 1e-3);
    }
    for (Point3& p : points) {
      const Point3 q = p;
      p = shift + Point3{q.x + e[0][0] * q.x + e[0][1] * q.y + e[0][2] * q.z,
                         q.y + e[1][0] * q.x + e[1][1] * q.y + e[1][2] * q.z,
                         q.z + e[2][0] * q.x + e[2][1] * q.y + e[2][2] * q.z};
      double* coordinates[3] = {&p.x, &p.y, &p.z};
      for (double* c : coordinates) {
        const double size = rng.log_uniform(1e-12, 1e-6);
        const double sign = rng.sign();
        *c += sign * size;
      }
    }
    return points;
  };
  pair.a = deform(box, {0, 0, 0});
  pair.b = deform(box, {2 * hx + gap, 0, 0});
  pair.recipe = format("gap %g", gap);
  return pair;
}

constexpr std::array<Family3d, 10> base_families{
    Family3d::random,      Family3d::face_face,          Family3d::edge_edge,
    Family3d::vertex_face, Family3d::vertex_edge,        Family3d::near_parallel_5deg,
    Family3d::near_parallel_0_5deg, Family3d::sliver,    Family3d::short_edges,
    Family3d::deformed};

PolyhedronPair base_pair(Rng& rng, std::string& recipe) {
  const Family3d family = base_families[rng.index(base_families.size())];
  const std::uint64_t seed = rng.bits();
  recipe = "base " + std::string(to_string(family)) + " seed " + std::to_string(seed) + " index 0";
  return generate_pair3d(family, seed, 0);
}

std::optional<RawPair> offset_1e6(Rng& rng) {
  RawPair pair;
  const PolyhedronPair base = base_pair(rng, pair.recipe);
  // Snapped to 2^-32 (|x| < 2 m), then + 1e6: multiples of 2^-32 below 2^21, exact sums.
  bool changed = false;
  const Point3 offset{1e6, -1e6, 1e6};
  const auto move = [&](const ConvexPolyhedron& p, Points& out) {
    for (const Point3& v : p.vertices()) {
      const Point3 s = snap(v, offset_grid);
      changed = changed || !(s == v);
      out.push_back(s + offset);
    }
  };
  move(base.a, pair.a);
  move(base.b, pair.b);
  if (!changed) pair.expected = base.expected;
  pair.recipe += changed ? ", snapped" : ", unchanged by the snap";
  return pair;
}

RawPair rotated(Rng& rng) {
  RawPair pair;
  const PolyhedronPair base = base_pair(rng, pair.recipe);
  // The rotation of the quaternion (w, x, y, z), integers in [-64, 64], not all zero:
  // R = I + 2 / n [..] with n = w² + x² + y² + z², rounded entry by entry.
  double q[4];
  double n = 0;
  do {
    n = 0;
    for (double& c : q) {
      c = static_cast<double>(rng.integer(-64, 64));
      n += c * c;
    }
  } while (n == 0);
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double r[3][3] = {{(w * w + x * x - y * y - z * z) / n, 2 * (x * y - w * z) / n, 2 * (x * z + w * y) / n},
                          {2 * (x * y + w * z) / n, (w * w - x * x + y * y - z * z) / n, 2 * (y * z - w * x) / n},
                          {2 * (x * z - w * y) / n, 2 * (y * z + w * x) / n, (w * w - x * x - y * y + z * z) / n}};
  const auto turn = [&r](const ConvexPolyhedron& p, Points& out) {
    for (const Point3& v : p.vertices()) {
      out.push_back({r[0][0] * v.x + r[0][1] * v.y + r[0][2] * v.z, r[1][0] * v.x + r[1][1] * v.y + r[1][2] * v.z,
                     r[2][0] * v.x + r[2][1] * v.y + r[2][2] * v.z});
    }
  };
  turn(base.a, pair.a);
  turn(base.b, pair.b);
  pair.recipe += format(", quaternion (%g, %g, %g, %g)", w, x, y, z);
  return pair;
}

std::optional<RawPair> generate_raw(Family3d family, Rng& rng) {
  switch (family) {
    case Family3d::random: return random_pair(rng);
    case Family3d::face_face: return face_face(rng);
    case Family3d::edge_edge: return edge_edge(rng);
    case Family3d::vertex_face: return vertex_face(rng);
    case Family3d::vertex_edge: return vertex_edge(rng);
    case Family3d::near_parallel_5deg: return near_parallel(rng, 0.08748866352592401, "5deg");
    case Family3d::near_parallel_0_5deg: return near_parallel(rng, 0.00872686779075879, "0.5deg");
    case Family3d::sliver: return sliver(rng);
    case Family3d::short_edges: return short_edges(rng);
    case Family3d::offset_1e6: return offset_1e6(rng);
    case Family3d::rotated: return rotated(rng);
    case Family3d::deformed: return deformed(rng);
  }
  generator_bug("unknown family");
}

// convex_hull3, whose result is valid by construction: a rejection is a bug, reported with
// the points (%a: exact) so it can be replayed.
std::optional<ConvexPolyhedron> hull_or_bug(const char* name, const Points& points, const std::string& recipe) {
  try {
    return convex_hull3(name, points);
  } catch (const kernel::InvalidPolyhedron& e) {
    std::string text = std::string(e.what()) + " (" + recipe + "), points";
    for (const Point3& p : points) text += format(" (%a, %a, %a)", p.x, p.y, p.z);
    generator_bug(text);
  }
}

}  // namespace

std::string_view to_string(Family3d family) {
  switch (family) {
    case Family3d::random: return "random";
    case Family3d::face_face: return "face_face";
    case Family3d::edge_edge: return "edge_edge";
    case Family3d::vertex_face: return "vertex_face";
    case Family3d::vertex_edge: return "vertex_edge";
    case Family3d::near_parallel_5deg: return "near_parallel_5deg";
    case Family3d::near_parallel_0_5deg: return "near_parallel_0_5deg";
    case Family3d::sliver: return "sliver";
    case Family3d::short_edges: return "short_edges";
    case Family3d::offset_1e6: return "offset_1e6";
    case Family3d::rotated: return "rotated";
    case Family3d::deformed: return "deformed";
  }
  return "?";
}

std::optional<Family3d> parse_family3d(std::string_view name) {
  for (Family3d f : all_families3d) {
    if (to_string(f) == name) return f;
  }
  return std::nullopt;
}

PolyhedronPair generate_pair3d(Family3d family, std::uint64_t seed, std::uint64_t index) {
  // The 3D streams are salted apart from the 2D ones of the same (family value, seed, index).
  Rng rng(mix(mix(seed) ^ mix(index) ^ (static_cast<std::uint64_t>(family) << 56) ^ 0x3d3d3d3dull));
  for (int attempt = 0; attempt < 1000; ++attempt) {
    std::optional<RawPair> raw = generate_raw(family, rng);
    if (!raw) continue;
    std::optional<ConvexPolyhedron> a = hull_or_bug("a", raw->a, raw->recipe);
    std::optional<ConvexPolyhedron> b = hull_or_bug("b", raw->b, raw->recipe);
    if (!a || !b) continue;
    return {std::move(*a), std::move(*b), family, raw->expected,
            std::string(to_string(family)) + " seed " + std::to_string(seed) + " index " + std::to_string(index) +
                (raw->recipe.empty() ? "" : ": " + raw->recipe)};
  }
  generator_bug("no valid pair of family " + std::string(to_string(family)) + " in 1000 attempts");
}

}  // namespace rockcontact::robustness
