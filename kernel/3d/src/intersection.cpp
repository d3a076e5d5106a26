// The intersection polyhedron of two convex polyhedra (intersection.hpp).

#include "rockcontact/kernel/3d/intersection.hpp"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "rockcontact/kernel/3d/plane.hpp"
#include "rockcontact/kernel/3d/plane_cut.hpp"

namespace rockcontact::kernel {
namespace {

constexpr int not_of_b = -1;

// The vertex shared by three faces of b, if any.
std::optional<std::uint32_t> common_vertex(const ConvexPolyhedron& b, int f, int g, int h) {
  const auto has = [&](int face, std::uint32_t v) {
    const ConvexPolyhedron::Face& loop = b.faces()[static_cast<std::size_t>(face)];
    return std::find(loop.begin(), loop.end(), v) != loop.end();
  };
  for (std::uint32_t v : b.faces()[static_cast<std::size_t>(f)]) {
    if (has(g, v) && has(h, v)) return v;
  }
  return std::nullopt;
}

// A vertex of b inside a appears after three clips as the meeting point of three of b's face
// planes. It lies on those three faces of b, so (three faces of a convex polyhedron with
// distinct planes meet at most in a vertex) it is the vertex they share: stored as that input
// point, its later decisions are orient3d (degree 3, with a static filter) instead of the
// three-plane side (degree 15), and its exact zeros against b's other faces through it cost a
// degree-3 exact evaluation. b_face[i] is the face of b whose plane is p's plane i.
HalfspacePolyhedron with_vertices_of_b(HalfspacePolyhedron p, const std::vector<int>& b_face,
                                       const ConvexPolyhedron& b) {
  std::vector<HalfspacePolyhedron::Vertex> vertices;
  for (std::size_t i = 0; i < p.vertices().size(); ++i) {
    const HalfspacePolyhedron::Vertex& v = p.vertices()[i];
    if (v.input) continue;
    const int f = b_face[v.planes[0]], g = b_face[v.planes[1]], h = b_face[v.planes[2]];
    if (f == not_of_b || g == not_of_b || h == not_of_b) continue;
    const std::optional<std::uint32_t> shared = common_vertex(b, f, g, h);
    if (!shared) continue;  // only after a wrong Float decision
    if (vertices.empty()) vertices.assign(p.vertices().begin(), p.vertices().end());
    vertices[i] = {true, b[*shared], {}};
  }
  if (vertices.empty()) return p;
  return HalfspacePolyhedron(std::vector<Plane3>(p.planes().begin(), p.planes().end()),
                             std::vector<HalfspacePolyhedron::Face>(p.faces().begin(), p.faces().end()),
                             std::move(vertices));
}

}  // namespace

template <NumberPolicy Policy>
HalfspacePolyhedron intersection(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  HalfspacePolyhedron result(a);
  std::vector<int> b_face(result.planes().size(), not_of_b);
  for (std::size_t f = 0; f < b.faces().size() && !result.empty(); ++f) {
    result = clip<Policy>(result, Plane3::of_face(b, f));
    if (result.planes().size() > b_face.size()) {  // the clip cut: its plane was appended
      b_face.push_back(static_cast<int>(f));
      result = with_vertices_of_b(std::move(result), b_face, b);
    }
  }
  return result;
}

template <NumberPolicy Policy>
double intersection_volume(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  return intersection<Policy>(a, b).template volume<Policy>();
}

#define ROCKCONTACT_INSTANTIATE(P)                                                                 \
  template HalfspacePolyhedron intersection<P>(const ConvexPolyhedron&, const ConvexPolyhedron&); \
  template double intersection_volume<P>(const ConvexPolyhedron&, const ConvexPolyhedron&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
