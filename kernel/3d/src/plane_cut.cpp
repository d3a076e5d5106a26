// Clipping and cutting a HalfspacePolyhedron by a plane (plane_cut.hpp): the vertex signs are
// decided first; the rest is combinatorial and policy-free.

#include "rockcontact/kernel/3d/plane_cut.hpp"

#include <cassert>
#include <cstdint>
#include <limits>
#include <vector>


namespace rockcontact::kernel {
namespace {

constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

// The pieces of the result under construction: the old vertices kept, renumbered on first use,
// and one new implicit vertex per cut edge.
class ClipBuilder {
 public:
  ClipBuilder(const HalfspacePolyhedron& p, const std::vector<Sign>& side, std::uint32_t cut)
      : p_(p), side_(side), cut_(cut), renumbered_(p.vertices().size(), none) {}

  std::uint32_t kept(std::uint32_t v) {
    if (renumbered_[v] == none) {
      renumbered_[v] = static_cast<std::uint32_t>(vertices_.size());
      vertices_.push_back(p_.vertices()[v]);
      on_plane_.push_back(side_[v] == Sign::zero);
    }
    return renumbered_[v];
  }

  // The new vertex on edge u -> v of the face with plane `plane`; its first face records one
  // plane, the second (which traverses v -> u) the other.
  std::uint32_t crossing(std::uint32_t u, std::uint32_t v, std::uint32_t plane) {
    const std::uint32_t lo = u < v ? u : v, hi = u < v ? v : u;
    for (const Crossing& c : crossings_) {
      if (c.lo == lo && c.hi == hi) {
        vertices_[c.id].planes[1] = plane;
        return c.id;
      }
    }
    const auto id = static_cast<std::uint32_t>(vertices_.size());
    vertices_.push_back({false, {}, {plane, none, cut_}});
    on_plane_.push_back(true);
    crossings_.push_back({lo, hi, id});
    return id;
  }

  bool on_plane(std::uint32_t id) const { return on_plane_[id]; }
  // A new vertex's second plane is set by the second face of its edge. Under the exact
  // policies both faces of a cut edge are kept; a polyhedron left open by an earlier Float clip
  // may lack one, and the vertex then repeats its first plane (its coordinates come out
  // non-finite, a wrong Float result rather than an invalid index).
  std::vector<HalfspacePolyhedron::Vertex> take_vertices() {
    for (auto& v : vertices_) {
      if (!v.input && v.planes[1] == none) v.planes[1] = v.planes[0];
    }
    return std::move(vertices_);
  }
  std::size_t size() const { return vertices_.size(); }

 private:
  struct Crossing {
    std::uint32_t lo, hi, id;
  };
  const HalfspacePolyhedron& p_;
  const std::vector<Sign>& side_;
  std::uint32_t cut_;
  std::vector<std::uint32_t> renumbered_;
  std::vector<HalfspacePolyhedron::Vertex> vertices_;
  std::vector<bool> on_plane_;
  std::vector<Crossing> crossings_;
};

// The loop of the new face from its edges y -> x. Under the exact policies the edges form one
// cycle (plane_cut.hpp, step 4); Float's signs may be inconsistent, so the walk stops at a
// missing or repeated link instead of trusting it, and a cap of fewer than three vertices is
// dropped (the result is then wrong, as Float may be, but the call stays defined).
std::vector<std::uint32_t> section_loop(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& section,
                                        std::size_t vertex_count) {
  std::vector<std::uint32_t> next(vertex_count, none);
  for (const auto& [from, to] : section) next[from] = to;
  std::vector<std::uint32_t> loop;
  if (section.empty()) return loop;
  std::uint32_t v = section.front().first;
  do {
    loop.push_back(v);
    v = next[v];
  } while (v != none && v != section.front().first && loop.size() < section.size());
  return loop;
}

// Steps 3 and 4 of plane_cut.hpp, for signs with both a negative and a positive entry.
HalfspacePolyhedron clip_by_signs(const HalfspacePolyhedron& p, const Plane3& plane, const std::vector<Sign>& side) {
  std::vector<Plane3> planes(p.planes().begin(), p.planes().end());
  planes.push_back(plane);
  const auto cut = static_cast<std::uint32_t>(planes.size() - 1);
  ClipBuilder builder(p, side, cut);
  std::vector<HalfspacePolyhedron::Face> faces;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> section;  // edges y -> x of the new face
  for (const HalfspacePolyhedron::Face& face : p.faces()) {
    bool below = false;
    for (std::uint32_t v : face.loop) below = below || side[v] == Sign::negative;
    if (!below) continue;
    HalfspacePolyhedron::Face out{face.plane, {}};
    const std::size_t n = face.loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t u = face.loop[i], v = face.loop[(i + 1) % n];
      if (side[u] != Sign::positive) out.loop.push_back(builder.kept(u));
      if (side[u] * side[v] == Sign::negative) out.loop.push_back(builder.crossing(u, v, face.plane));
    }
    const std::size_t m = out.loop.size();
    for (std::size_t i = 0; i < m; ++i) {
      const std::uint32_t x = out.loop[i], y = out.loop[(i + 1) % m];
      if (builder.on_plane(x) && builder.on_plane(y)) section.emplace_back(y, x);
    }
    faces.push_back(std::move(out));
  }
  std::vector<std::uint32_t> cap = section_loop(section, builder.size());
  if (cap.size() >= 3) faces.push_back({cut, std::move(cap)});
  return HalfspacePolyhedron(std::move(planes), std::move(faces), builder.take_vertices());
}

// Steps 2 to 4: the part below, from the signs of p's vertices against `plane`.
HalfspacePolyhedron below(const HalfspacePolyhedron& p, const Plane3& plane, const std::vector<Sign>& side) {
  bool negative = false, positive = false;
  for (Sign s : side) {
    negative = negative || s == Sign::negative;
    positive = positive || s == Sign::positive;
  }
  if (!negative) return {};
  if (!positive) return p;
  return clip_by_signs(p, plane, side);
}

}  // namespace

template <NumberPolicy Policy>
HalfspacePolyhedron clip(const HalfspacePolyhedron& p, const Plane3& plane) {
  return below(p, plane, p.sides<Policy>(plane));
}

template <NumberPolicy Policy>
std::pair<HalfspacePolyhedron, HalfspacePolyhedron> cut_by_plane(const HalfspacePolyhedron& p,
                                                                   const Plane3& plane) {
  std::vector<Sign> side = p.sides<Policy>(plane);
  HalfspacePolyhedron lower = below(p, plane, side);
  for (Sign& s : side) s = -s;
  return {std::move(lower), below(p, plane.opposite(), side)};
}

#define ROCKCONTACT_INSTANTIATE(P)                                                    \
  template HalfspacePolyhedron clip<P>(const HalfspacePolyhedron&, const Plane3&); \
  template std::pair<HalfspacePolyhedron, HalfspacePolyhedron> cut_by_plane<P>(const HalfspacePolyhedron&, const Plane3&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
