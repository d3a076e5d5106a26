// convex_hull3 (pair3d_generators.hpp): CGAL's 3D hull with exact predicates, turned into a
// ConvexPolyhedron. CGAL is confined to this file.
//
// Steps:
//   1. CGAL::convex_hull_3 (quickhull) on the points as Epick points: its predicates are
//      exact on double input, so the hull's combinatorics are those of the exact points. Its
//      output is a triangulated Surface_mesh, outward oriented. (CGAL 5.5's overload that
//      writes an indexed triangle set instead returned non-convex surfaces on inputs with many
//      coplanar points, e.g. the near_parallel family's bottom faces; the Surface_mesh
//      overload did not.)
//   2. Neighbouring triangles whose fourth point is exactly coplanar (CGAL::orientation) are
//      merged (union-find), and each merged region's boundary is walked into one loop: a
//      convex polygon, so every vertex on it leaves by exactly one boundary edge.
//   3. Loop vertices exactly collinear with their neighbours (CGAL::collinear) are dropped:
//      they lie inside a hull edge (quickhull keeps such points when a degenerate input puts
//      them in its initial simplex), as are vertices on no loop (inside a merged face); the
//      rest are renumbered.
//   4. The result is numbered canonically, and ConvexPolyhedron::make validates it exactly
//      (a failure would be a bug here).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "rockcontact/generators/pair3d_generators.hpp"

namespace rockcontact::robustness {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;
using Triangle = std::array<std::size_t, 3>;

// Union-find with path halving.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

using EdgeOwner = std::map<std::pair<std::size_t, std::size_t>, std::size_t>;  // directed edge -> triangle

EdgeOwner edge_owner(const std::vector<Triangle>& tris) {
  EdgeOwner owner;
  for (std::size_t t = 0; t < tris.size(); ++t) {
    for (int k = 0; k < 3; ++k) owner[{tris[t][k], tris[t][(k + 1) % 3]}] = t;
  }
  return owner;
}

// Step 2: each triangle's coplanar region, named by one of its triangles.
std::vector<std::size_t> coplanar_regions(const std::vector<P3>& p, const std::vector<Triangle>& tris,
                                          const EdgeOwner& owner) {
  std::vector<std::size_t> parent(tris.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const Triangle& f = tris[t];
    for (int k = 0; k < 3; ++k) {
      const std::size_t n = owner.at({f[(k + 1) % 3], f[k]});
      const Triangle& g = tris[n];
      for (std::size_t v : g) {
        if (v != f[0] && v != f[1] && v != f[2] &&
            CGAL::orientation(p[f[0]], p[f[1]], p[f[2]], p[v]) == CGAL::COPLANAR) {
          parent[root(parent, t)] = root(parent, n);
        }
      }
    }
  }
  for (std::size_t t = 0; t < tris.size(); ++t) parent[t] = root(parent, t);
  return parent;
}

// Step 2, continued: each region's boundary loop (outward CCW, as the triangles are).
std::vector<std::vector<std::size_t>> region_loops(const EdgeOwner& owner, const std::vector<std::size_t>& region) {
  std::map<std::size_t, std::map<std::size_t, std::size_t>> next;  // region -> (from -> to)
  for (const auto& [edge, t] : owner) {
    if (region[owner.at({edge.second, edge.first})] != region[t]) next[region[t]][edge.first] = edge.second;
  }
  std::vector<std::vector<std::size_t>> loops;
  for (const auto& [r, step] : next) {
    std::vector<std::size_t> loop;
    const std::size_t start = step.begin()->first;
    std::size_t v = start;
    do {
      loop.push_back(v);
      v = step.at(v);
    } while (v != start && loop.size() <= step.size());  // one cycle; the bound only stops a bug
    loops.push_back(std::move(loop));
  }
  return loops;
}

bool solid(const std::vector<P3>& p) {
  std::size_t i = 1;
  while (i < p.size() && p[i] == p[0]) ++i;
  std::size_t j = i + 1;
  while (j < p.size() && CGAL::collinear(p[0], p[i], p[j])) ++j;
  if (j >= p.size()) return false;
  for (std::size_t k = 1; k < p.size(); ++k) {
    if (!CGAL::coplanar(p[0], p[i], p[j], p[k])) return true;
  }
  return false;
}

}  // namespace

std::optional<kernel::ConvexPolyhedron> convex_hull3(std::string name, std::span<const kernel::Point3> points) {
  std::vector<P3> input;
  input.reserve(points.size());
  for (const kernel::Point3& q : points) input.emplace_back(q.x, q.y, q.z);
  // A solid hull needs four points that are not coplanar (convex_hull_3's triangle-set
  // output is for 3D hulls only): a point other than the first, a third off their line, a
  // fourth off their plane.
  if (!solid(input)) return std::nullopt;

  CGAL::Surface_mesh<P3> mesh;
  CGAL::convex_hull_3(input.begin(), input.end(), mesh);
  std::vector<P3> hull_points;
  for (const auto v : mesh.vertices()) hull_points.push_back(mesh.point(v));
  std::vector<Triangle> tris;
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    tris.push_back({static_cast<std::size_t>(mesh.source(h)), static_cast<std::size_t>(mesh.target(h)),
                    static_cast<std::size_t>(mesh.target(mesh.next(h)))});
  }
  const EdgeOwner owner = edge_owner(tris);
  const std::vector<std::size_t> region = coplanar_regions(hull_points, tris, owner);
  std::vector<std::vector<std::size_t>> loops = region_loops(owner, region);

  // Step 3.
  for (std::vector<std::size_t>& loop : loops) {
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const P3& prev = hull_points[loop[(i + loop.size() - 1) % loop.size()]];
      const P3& next = hull_points[loop[(i + 1) % loop.size()]];
      if (!CGAL::collinear(prev, hull_points[loop[i]], next)) kept.push_back(loop[i]);
    }
    loop = std::move(kept);
  }
  // Step 4: a canonical numbering (vertices in lexicographic order, each face from its
  // smallest vertex, faces in order): convex_hull_3 orders its output by where its internal
  // structures were allocated, and the generators promise the same pair in every run.
  std::vector<std::size_t> used;
  for (const std::vector<std::size_t>& loop : loops) used.insert(used.end(), loop.begin(), loop.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::sort(used.begin(), used.end(), [&](std::size_t i, std::size_t j) { return hull_points[i] < hull_points[j]; });
  std::vector<std::uint32_t> number(hull_points.size());
  std::vector<kernel::Point3> vertices;
  for (std::size_t v : used) {
    number[v] = static_cast<std::uint32_t>(vertices.size());
    vertices.push_back({hull_points[v].x(), hull_points[v].y(), hull_points[v].z()});
  }
  std::vector<kernel::ConvexPolyhedron::Face> faces;
  for (const std::vector<std::size_t>& loop : loops) {
    kernel::ConvexPolyhedron::Face face;
    for (std::size_t v : loop) face.push_back(number[v]);
    std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
    faces.push_back(std::move(face));
  }
  std::sort(faces.begin(), faces.end());
  return kernel::ConvexPolyhedron::make(std::move(name), std::move(vertices), std::move(faces));
}

}  // namespace rockcontact::robustness
