#include "rockcontact/kernel/3d/block_cutting.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <sstream>
#include <utility>

#include "rockcontact/kernel/3d/contact_set.hpp"
#include "rockcontact/kernel/3d/plane_cut.hpp"

namespace rockcontact::kernel {
namespace {

// sin and cos of an angle in degrees, exact at multiples of 90 degrees.
std::pair<double, double> sin_cos_deg(double deg) {
  const double quarter = deg / 90.0;
  if (quarter == std::floor(quarter)) {
    static constexpr double sines[4] = {0, 1, 0, -1};
    const auto q = static_cast<int>(std::fmod(std::fmod(quarter, 4.0) + 4.0, 4.0));
    return {sines[q], sines[(q + 1) % 4]};
  }
  const double rad = deg * std::numbers::pi / 180.0;
  return {std::sin(rad), std::cos(rad)};
}

std::string field(std::size_t i, const char* name) {
  return "joint_sets[" + std::to_string(i) + "]" + (*name ? std::string(".") + name : std::string());
}

std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

// The range of k whose planes can meet `piece`: its extent along n from the rounded vertices,
// one plane more on each side for their rounding (the cut itself is exact: a plane that misses
// the piece leaves it whole).
std::pair<std::int64_t, std::int64_t> plane_range(const JointSet3& set, std::span<const Point3> vertices,
                                                  std::size_t index) {
  const Point3 n = joint_normal(set);
  double lo = INFINITY, hi = -INFINITY;
  for (const Point3& p : vertices) {
    const double t = n.x * p.x + n.y * p.y + n.z * p.z;
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  const double first = std::floor((lo - set.offset) / set.spacing) - 1;
  const double last = std::ceil((hi - set.offset) / set.spacing) + 1;
  if (!(last - first <= static_cast<double>(max_cut_planes))) {
    throw InvalidCut(field(index, ""), "its planes cross the region more than " + std::to_string(max_cut_planes) +
                                           " times: the spacing " + number_text(set.spacing) +
                                           " m is too small for the region");
  }
  return {static_cast<std::int64_t>(first), static_cast<std::int64_t>(last)};
}

// The piece's vertices that its faces use, rounded, and its faces renumbered to them.
ConvexPolyhedron rounded(const HalfspacePolyhedron& piece, std::span<const Point3> coordinates, std::string name) {
  std::vector<std::uint32_t> index(coordinates.size(), UINT32_MAX);
  std::vector<Point3> vertices;
  std::vector<ConvexPolyhedron::Face> faces;
  for (const auto& face : piece.faces()) {
    ConvexPolyhedron::Face& loop = faces.emplace_back();
    for (const std::uint32_t v : face.loop) {
      if (index[v] == UINT32_MAX) {
        index[v] = static_cast<std::uint32_t>(vertices.size());
        vertices.push_back(coordinates[v]);
      }
      loop.push_back(index[v]);
    }
  }
  try {
    return ConvexPolyhedron::make(std::move(name), std::move(vertices), std::move(faces));
  } catch (const InvalidPolyhedron& e) {
    const Point3& p = coordinates[piece.faces().front().loop.front()];
    throw InvalidCut("block near (" + number_text(p.x) + ", " + number_text(p.y) + ", " + number_text(p.z) + ")",
                     std::string("the cut makes a piece too thin for doubles to represent (") + e.what() +
                         "); move a joint set's offset so its planes do not graze a vertex or an edge "
                         "of the region");
  }
}

// Union-find over piece indices.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

void check_joint_sets(std::span<const JointSet3> sets) {
  for (std::size_t i = 0; i < sets.size(); ++i) {
    const JointSet3& s = sets[i];
    if (!(s.dip_deg >= 0 && s.dip_deg <= 90)) {
      throw InvalidCut(field(i, "dip_deg"), "expected degrees in [0, 90], got " + number_text(s.dip_deg));
    }
    if (!(s.dip_direction_deg >= 0 && s.dip_direction_deg < 360)) {
      throw InvalidCut(field(i, "dip_direction_deg"),
                       "expected degrees in [0, 360) clockwise from North, got " + number_text(s.dip_direction_deg));
    }
    if (!(std::isfinite(s.spacing) && s.spacing > 0)) {
      throw InvalidCut(field(i, "spacing"), "expected a finite number of metres > 0, got " + number_text(s.spacing));
    }
    if (!std::isfinite(s.offset)) {
      throw InvalidCut(field(i, "offset"), "expected a finite number of metres, got " + number_text(s.offset));
    }
  }
}

Point3 joint_normal(const JointSet3& set) {
  const auto [sin_dip, cos_dip] = sin_cos_deg(set.dip_deg);
  const auto [sin_dir, cos_dir] = sin_cos_deg(set.dip_direction_deg);
  return {sin_dip * sin_dir, sin_dip * cos_dir, cos_dip};
}

Plane3 joint_plane(const JointSet3& set, std::int64_t k) {
  const Point3 n = joint_normal(set);
  return Plane3::from_coefficients(n.x, n.y, n.z, set.offset + static_cast<double>(k) * set.spacing);
}

template <NumberPolicy Policy>
std::vector<CutPiece3> cut_by_joint_sets(std::span<const ConvexPolyhedron> region, std::span<const JointSet3> sets) {
  check_joint_sets(sets);
  std::vector<CutPiece3> pieces;
  for (std::size_t part = 0; part < region.size(); ++part) {
    pieces.push_back({HalfspacePolyhedron(region[part]), part, {}});
  }
  for (std::size_t s = 0; s < sets.size(); ++s) {
    std::vector<CutPiece3> next;
    for (CutPiece3& piece : pieces) {
      const auto [first, last] = plane_range(sets[s], piece.piece.vertex_coordinates<Policy>(), s);
      HalfspacePolyhedron rest = std::move(piece.piece);
      for (std::int64_t k = first; k <= last && !rest.empty(); ++k) {
        auto [below, above] = cut_by_plane<Policy>(rest, joint_plane(sets[s], k));
        if (!below.empty()) {
          std::vector<std::int64_t> cell = piece.cell;
          cell.push_back(k);
          next.push_back({std::move(below), piece.part, std::move(cell)});
          if (next.size() > max_cut_pieces) {
            throw InvalidCut(field(s, ""), "the cut makes more than " + std::to_string(max_cut_pieces) + " pieces");
          }
        }
        rest = std::move(above);
      }
    }
    pieces = std::move(next);
  }
  return pieces;
}

template <NumberPolicy Policy>
std::vector<CutBlock3> cut_region(std::span<const ConvexPolyhedron> region, std::span<const JointSet3> sets,
                                  const std::string& id_prefix) {
  const std::vector<CutPiece3> pieces = cut_by_joint_sets<Policy>(region, sets);
  std::vector<ConvexPolyhedron> solids;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    // Exact coordinates, each rounded once to the nearest double (header): a vertex shared by
    // several pieces gets the same double in each, so the blocks meet exactly where they touch.
    solids.push_back(rounded(pieces[i].piece, pieces[i].piece.vertex_coordinates<Exact>(),
                             id_prefix + " piece " + std::to_string(i + 1)));
  }
  // Pieces of one cell from different parts that meet face to face are one block.
  std::vector<std::size_t> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  std::map<std::vector<std::int64_t>, std::vector<std::size_t>> cells;
  for (std::size_t i = 0; i < pieces.size(); ++i) cells[pieces[i].cell].push_back(i);
  for (const auto& [cell, members] : cells) {
    for (std::size_t a = 0; a < members.size(); ++a) {
      for (std::size_t b = a + 1; b < members.size(); ++b) {
        const std::size_t i = members[a], j = members[b];
        if (pieces[i].part == pieces[j].part) continue;
        const auto set = contact_set<Policy>(solids[i], solids[j]);
        if (set && set->dimension == 2) parent[root(parent, j)] = root(parent, i);
      }
    }
  }
  std::vector<CutBlock3> blocks;
  std::map<std::size_t, std::size_t> block_of_root;
  std::vector<std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto [it, added] = block_of_root.emplace(root(parent, i), members.size());
    if (added) members.emplace_back();
    members[it->second].push_back(i);
  }
  for (std::size_t b = 0; b < members.size(); ++b) {
    const std::string name = id_prefix + "_" + std::to_string(b + 1);
    CutBlock3& block = blocks.emplace_back();
    for (std::size_t j = 0; j < members[b].size(); ++j) {
      const std::size_t i = members[b][j];
      const std::string part_name = members[b].size() == 1 ? name : name + "." + std::to_string(j + 1);
      block.parts.push_back(solids[i].renamed(part_name));
    }
  }
  return blocks;
}

#define ROCKCONTACT_INSTANTIATE(P)                                                                       \
  template std::vector<CutPiece3> cut_by_joint_sets<P>(std::span<const ConvexPolyhedron>,             \
                                                       std::span<const JointSet3>);                    \
  template std::vector<CutBlock3> cut_region<P>(std::span<const ConvexPolyhedron>, std::span<const JointSet3>, \
                                                const std::string&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
