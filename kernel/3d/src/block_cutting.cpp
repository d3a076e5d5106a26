#include "rockcontact/kernel/3d/block_cutting.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <sstream>
#include <utility>

#include "box3.hpp"
#include "convex_clip2.hpp"
#include "rockcontact/kernel/3d/contact_set.hpp"
#include "rockcontact/kernel/3d/moments.hpp"
#include "rockcontact/kernel/3d/plane_cut.hpp"
#include "rockcontact/kernel/3d/tolerances.hpp"

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

// The parts named "<prefix>_<k>" (block k, from 1), or "<prefix>_<k>.<j>" for part j of a block
// of several.
void name_blocks(std::vector<CutBlock3>& blocks, const std::string& id_prefix) {
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    std::vector<ConvexPolyhedron>& parts = blocks[b].parts;
    const std::string name = id_prefix + "_" + std::to_string(b + 1);
    for (std::size_t j = 0; j < parts.size(); ++j) {
      parts[j] = parts[j].renamed(parts.size() == 1 ? name : name + "." + std::to_string(j + 1));
    }
  }
}

void check_options(const CutOptions3& options) {
  if (!(std::isfinite(options.min_block_volume) && options.min_block_volume >= 0.0)) {
    throw InvalidCut("min_block_volume",
                     "expected a finite number of m³ >= 0, got " + number_text(options.min_block_volume));
  }
}

using Vec3 = std::array<double, 3>;
using Vec2 = std::array<double, 2>;

Vec3 minus(const Point3& p, const Point3& o) { return {p.x - o.x, p.y - o.y, p.z - o.z}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

using detail::Box3;

// A face as given, ready for the shared-area test: its loop (counter-clockwise seen from outside),
// its outward unit normal (Newell's sum of cross products about the first vertex) and the axis of
// the normal's largest component.
struct FaceLoop {
  std::vector<Point3> loop;
  Vec3 normal{};
  int axis = 0;
};

FaceLoop face_loop(const ConvexPolyhedron& part, const ConvexPolyhedron::Face& face) {
  FaceLoop f;
  for (const std::uint32_t v : face) f.loop.push_back(part[v]);
  for (std::size_t i = 1; i + 1 < f.loop.size(); ++i) {
    const Vec3 a = minus(f.loop[i], f.loop[0]), b = minus(f.loop[i + 1], f.loop[0]);
    f.normal[0] += a[1] * b[2] - a[2] * b[1];
    f.normal[1] += a[2] * b[0] - a[0] * b[2];
    f.normal[2] += a[0] * b[1] - a[1] * b[0];
  }
  const double length = std::sqrt(dot(f.normal, f.normal));
  for (double& c : f.normal) c /= length;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(f.normal[i]) > std::abs(f.normal[f.axis])) f.axis = i;
  }
  return f;
}

// A part with its box and faces.
struct PartFaces {
  Box3 box;
  std::vector<FaceLoop> faces;
};

PartFaces part_faces(const ConvexPolyhedron& part) {
  PartFaces p{detail::box_of({&part, 1}), {}};
  for (const auto& face : part.input_faces()) p.faces.push_back(face_loop(part, face));
  return p;
}

// `loop` about `origin`, projected along `axis` onto the other two axes in cyclic order, so a
// loop counter-clockwise about a normal whose `axis` component is positive stays
// counter-clockwise; reversed when `reverse`.
std::vector<Vec2> projected(const std::vector<Point3>& loop, const Point3& origin, int axis, bool reverse) {
  std::vector<Vec2> out;
  for (const Point3& p : loop) {
    const Vec3 d = minus(p, origin);
    out.push_back({d[(axis + 1) % 3], d[(axis + 2) % 3]});
  }
  if (reverse) std::reverse(out.begin(), out.end());
  return out;
}

double shoelace_area(const std::vector<Vec2>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
    twice += p[0] * q[1] - p[1] * q[0];
  }
  return twice / 2;
}

// The area faces a and b share (header, merge_small_blocks step 2), m²; 0 unless they lie on one
// plane with opposite normals within shared_face_tolerance (`slack` is that times S).
double shared_area(const FaceLoop& a, const FaceLoop& b, double slack) {
  if (1.0 + dot(a.normal, b.normal) > shared_face_tolerance) return 0.0;
  const Point3& origin = a.loop.front();
  for (const Point3& p : b.loop) {
    if (std::abs(dot(a.normal, minus(p, origin))) > slack) return 0.0;
  }
  // b's normal points the other way along the axis, so its projected loop turns the other way.
  const bool positive = a.normal[a.axis] > 0;
  const std::vector<Vec2> pa = projected(a.loop, origin, a.axis, !positive);
  const std::vector<Vec2> pb = projected(b.loop, origin, a.axis, positive);
  return shoelace_area(detail::clip_convex2(pa, pb)) / std::abs(a.normal[a.axis]);
}

// Merges the fragments of a set of blocks (header, merge_small_blocks steps 1-4).
class FragmentMerger {
 public:
  FragmentMerger(std::vector<CutBlock3>& blocks, double min_volume)
      : blocks_(blocks), min_volume_(min_volume), merged_(blocks.size(), false) {
    Box3 all;
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      double volume = 0.0;
      Box3 box;
      std::vector<PartFaces>& faces = faces_.emplace_back();
      for (const ConvexPolyhedron& part : blocks_[b].parts) {
        volume += moments(part).volume;
        faces.push_back(part_faces(part));
        box.add(faces.back().box);
      }
      volumes_.push_back(volume);
      boxes_.push_back(box);
      all.add(box);
      if (volume < min_volume_) queue_.insert({volume, b});
    }
    const double size = all.size();
    slack_ = shared_face_tolerance * size;
    least_area_ = shared_face_tolerance * size * size;
  }

  // The blocks left, in their order.
  std::vector<CutBlock3> run() {
    while (!queue_.empty()) {
      const std::size_t fragment = queue_.begin()->second;
      queue_.erase(queue_.begin());
      const std::size_t neighbour = largest_neighbour(fragment);
      if (neighbour != blocks_.size()) merge(fragment, neighbour);
    }
    std::vector<CutBlock3> left;
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      if (!merged_[b]) left.push_back(std::move(blocks_[b]));
    }
    return left;
  }

 private:
  // The block `fragment` shares the largest face area with (ties to the lower index), or
  // blocks_.size() for none.
  std::size_t largest_neighbour(std::size_t fragment) const {
    std::size_t best = blocks_.size();
    double best_area = least_area_;
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      if (b == fragment || merged_[b] || !boxes_[b].meets(boxes_[fragment], slack_)) continue;
      const double area = block_shared_area(fragment, b);
      if (area > best_area) {
        best = b;
        best_area = area;
      }
    }
    return best;
  }

  double block_shared_area(std::size_t i, std::size_t j) const {
    double area = 0.0;
    for (const PartFaces& p : faces_[i]) {
      for (const PartFaces& q : faces_[j]) {
        if (!p.box.meets(q.box, slack_)) continue;
        for (const FaceLoop& a : p.faces) {
          for (const FaceLoop& b : q.faces) area += shared_area(a, b, slack_);
        }
      }
    }
    return area;
  }

  void merge(std::size_t fragment, std::size_t neighbour) {
    const bool queued = queue_.erase({volumes_[neighbour], neighbour}) > 0;
    auto& parts = blocks_[neighbour].parts;
    auto& moved = blocks_[fragment].parts;
    parts.insert(parts.end(), std::make_move_iterator(moved.begin()), std::make_move_iterator(moved.end()));
    faces_[neighbour].insert(faces_[neighbour].end(), std::make_move_iterator(faces_[fragment].begin()),
                             std::make_move_iterator(faces_[fragment].end()));
    boxes_[neighbour].add(boxes_[fragment]);
    volumes_[neighbour] += volumes_[fragment];
    merged_[fragment] = true;
    if (queued && volumes_[neighbour] < min_volume_) queue_.insert({volumes_[neighbour], neighbour});
  }

  std::vector<CutBlock3>& blocks_;
  double min_volume_;
  std::vector<std::vector<PartFaces>> faces_;  // per block, per part
  std::vector<double> volumes_;                // m³, per block
  std::vector<Box3> boxes_;                    // per block
  std::set<std::pair<double, std::size_t>> queue_;  // the fragments to process: (volume, block)
  std::vector<bool> merged_;                        // per block: merged into another
  double slack_ = 0.0;       // m: shared_face_tolerance S
  double least_area_ = 0.0;  // m²: shared_face_tolerance S², the largest area that is none
};

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
                                  const std::string& id_prefix, const CutOptions3& options) {
  check_options(options);
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
  for (const std::vector<std::size_t>& block_members : members) {
    CutBlock3& block = blocks.emplace_back();
    for (const std::size_t i : block_members) block.parts.push_back(std::move(solids[i]));
  }
  return merge_small_blocks(std::move(blocks), options, id_prefix);
}

std::vector<CutBlock3> merge_small_blocks(std::vector<CutBlock3> blocks, const CutOptions3& options,
                                          const std::string& id_prefix) {
  check_options(options);
  if (options.min_block_volume > 0.0) blocks = FragmentMerger(blocks, options.min_block_volume).run();
  name_blocks(blocks, id_prefix);
  return blocks;
}

#define ROCKCONTACT_INSTANTIATE(P)                                                                       \
  template std::vector<CutPiece3> cut_by_joint_sets<P>(std::span<const ConvexPolyhedron>,             \
                                                       std::span<const JointSet3>);                    \
  template std::vector<CutBlock3> cut_region<P>(std::span<const ConvexPolyhedron>, std::span<const JointSet3>, \
                                                const std::string&, const CutOptions3&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
