#pragma once
// A deliberately naive 3D pair kernel in plain double, the baseline of bench/pair3d_bench.cpp:
// what a convex-polyhedron contact code "written the obvious way" does. No exact predicate, no
// filter, no tolerance.
//
//   sat_verdict       the separating axis test: the face normals of both blocks and the cross
//                     products of every edge pair, each normal computed in double; both vertex
//                     sets projected on it; separate if some gap max_a < min_b (or the
//                     reverse) is positive, touch if none is but some is exactly zero, overlap
//                     otherwise.
//   clip_volume       Sutherland-Hodgman generalised to polyhedra: `a` (as its face polygons)
//                     clipped by the plane n . x <= n . f0 of each face of `b` (n the double
//                     cross product of the face's first two edges): every face polygon is
//                     clipped against the plane (points with n . x <= d kept, an edge crossing
//                     cut at s_p / (s_p - s_q)), and the crossing points, ordered by angle
//                     around their mean in the plane, close the solid with a cap face. The
//                     volume of the result is the sum over its faces of the fan tetrahedra
//                     from its first vertex (det / 6).
// Inputs are vertex lists and faces as index loops, CCW from outside (ConvexPolyhedron's).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace naive3d {

struct V3 {
  double x, y, z;
};
inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator*(double s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

struct Block {
  std::vector<V3> vertices;
  std::vector<std::vector<std::uint32_t>> faces;
  std::vector<std::array<std::uint32_t, 2>> edges;
};

enum class Verdict { separate, touch, overlap };

namespace detail {

inline void project(const std::vector<V3>& v, const V3& n, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (const V3& p : v) {
    const double s = dot(n, p);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
}

// The larger of the two gaps along n (positive: separated).
inline double gap(const Block& a, const Block& b, const V3& n) {
  double alo, ahi, blo, bhi;
  project(a.vertices, n, alo, ahi);
  project(b.vertices, n, blo, bhi);
  return std::max(blo - ahi, alo - bhi);
}

}  // namespace detail

inline Verdict sat_verdict(const Block& a, const Block& b) {
  bool touching = false;
  const auto axis = [&](const V3& n) {
    if (n.x == 0 && n.y == 0 && n.z == 0) return false;
    const double g = detail::gap(a, b, n);
    touching = touching || g == 0.0;
    return g > 0.0;
  };
  for (const Block* p : {&a, &b}) {
    for (const auto& f : p->faces) {
      const V3 &f0 = p->vertices[f[0]], &f1 = p->vertices[f[1]], &f2 = p->vertices[f[2]];
      if (axis(cross(f1 - f0, f2 - f0))) return Verdict::separate;
    }
  }
  for (const auto& e : a.edges) {
    for (const auto& f : b.edges) {
      const V3 n = cross(a.vertices[e[1]] - a.vertices[e[0]], b.vertices[f[1]] - b.vertices[f[0]]);
      if (axis(n)) return Verdict::separate;
    }
  }
  return touching ? Verdict::touch : Verdict::overlap;
}

// The clipped solid as face polygons of points.
using Solid = std::vector<std::vector<V3>>;

inline void clip_by_plane(Solid& solid, const V3& n, double d, Solid& scratch, std::vector<V3>& cap) {
  scratch.clear();
  cap.clear();
  for (const auto& face : solid) {
    std::vector<V3> out;
    V3 p = face.back();
    double sp = dot(n, p) - d;
    for (const V3& q : face) {
      const double sq = dot(n, q) - d;
      if ((sp <= 0.0) != (sq <= 0.0)) {
        const V3 x = p + (sp / (sp - sq)) * (q - p);
        out.push_back(x);
        cap.push_back(x);
      }
      if (sq <= 0.0) out.push_back(q);
      p = q;
      sp = sq;
    }
    if (out.size() >= 3) scratch.push_back(std::move(out));
  }
  if (cap.size() >= 3) {
    // Order the cap's points by angle about their mean, CCW seen along +n (outward).
    V3 c{0, 0, 0};
    for (const V3& x : cap) c = c + x;
    c = (1.0 / static_cast<double>(cap.size())) * c;
    const V3 u = cap[0] - c;
    const V3 v = cross(n, u);
    std::sort(cap.begin(), cap.end(), [&](const V3& p, const V3& q) {
      return std::atan2(dot(p - c, v), dot(p - c, u)) < std::atan2(dot(q - c, v), dot(q - c, u));
    });
    scratch.push_back(cap);
  }
  solid.swap(scratch);
}

inline double volume(const Solid& solid) {
  if (solid.empty()) return 0.0;
  const V3 o = solid[0][0];
  double six_v = 0.0;
  for (const auto& face : solid) {
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      six_v += dot(face[0] - o, cross(face[k] - o, face[k + 1] - o));
    }
  }
  return six_v / 6.0;
}

// Volume of a ∩ b (m³).
inline double clip_volume(const Block& a, const Block& b) {
  Solid solid;
  for (const auto& f : a.faces) {
    std::vector<V3> poly;
    for (std::uint32_t i : f) poly.push_back(a.vertices[i]);
    solid.push_back(std::move(poly));
  }
  Solid scratch;
  std::vector<V3> cap;
  for (const auto& f : b.faces) {
    const V3 &f0 = b.vertices[f[0]], &f1 = b.vertices[f[1]], &f2 = b.vertices[f[2]];
    const V3 n = cross(f1 - f0, f2 - f0);
    clip_by_plane(solid, n, dot(n, f0), scratch, cap);
    if (solid.empty()) return 0.0;
  }
  return volume(solid);
}

}  // namespace naive3d
