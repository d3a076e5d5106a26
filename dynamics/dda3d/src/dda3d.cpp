#include "rockcontact/dynamics/dda3d.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <numeric>
#include <span>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include <omp.h>

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "block_matrices3d.hpp"
#include "contact_terms3d.hpp"
#include "rockcontact/kernel/3d/contact_constraints.hpp"

namespace rockcontact::dynamics {
namespace {

using kernel::ConvexPolyhedron;
using kernel::Point3;

// Growth of the step after an accepted one, back towards Dda3dParams::dt.
constexpr double step_growth = 1.5;
constexpr double degrees_per_radian = 180.0 / std::numbers::pi;
// Initial equilibrium (header): the inertia term's share left in the static solve, and the gap
// (of the scene's size) up to which blocks count as resting on each other at the start.
constexpr double settle_regularization = 1.0e-9;
constexpr double resting_gap = 1.0e-6;
// The sliding start (sliding_start): its Coulomb iterations at most, and the change of every
// slip direction (a unit vector) below which they end.
constexpr int max_sliding_rounds = 12;
constexpr double sliding_turn_tolerance = 1.0e-6;
// The sliding start's held contacts (sliding_start) slide when their friction passes the cap by
// more than this fraction of it.
constexpr double friction_tolerance = 1.0e-3;
// The stability monitor's energy floor: every movable block's kinetic energy at this speed, m/s
// (as in 2D), so that a run starting at rest has a budget.
constexpr double energy_floor_speed = 1.0e-3;
// The initial equilibrium's open-close hysteresis, of the scene's size (contact_terms3d.hpp):
// contacts at exact touch that carry no load (the sides of stacked blocks) otherwise open and
// close by 1e-8 m from one iteration of the static solve to the next. (Not in the dynamic steps:
// there it changed the toppling scene's course, a motion that hinges on such contacts.)
constexpr double open_close_tolerance = 1.0e-9;
// One contact per position (hold_contacts): constraints of a pair with one normal closer than
// this fraction of the smaller block's size (and than the detection range) are one contact. A
// vertex held on a face and the face's own corner found on the vertex's block start as one
// point and drift apart by the contact's settling and slip; counted twice, that corner takes
// twice its share of the load. 1e-3 covers the settling and a slip up to the safety factor's
// threshold; 0.05 merged a real corner into a held one that had slid off its face, and the
// generated wedges' slides came out 30-60 % long.
constexpr double merge_ratio = 1.0e-3;
// Contact transfer (detect): the largest angle between the normals of a vanished constraint and
// the new one that continues it, radians (15 degrees).
constexpr double transfer_angle = std::numbers::pi / 12.0;
// §5.1's revision (revise) is applied when it moves the contact points by more than this fraction
// of the scene's size: a contact closing head-on (no tangential motion) keeps its points, and its
// step is not solved again for a rounding.
constexpr double revision_floor = 1.0e-9;
// §4.3's new choice of plane (replane) takes a candidate whose end gap exceeds the present one's
// by more than this fraction of the scene's size: at an exact touch the candidates tie, and the
// kernel's tie-break stands.
constexpr double replane_margin = 1.0e-9;
// Vertices of a block's parts closer than this fraction of its size are one corner (corners_of).
constexpr double corner_tolerance = 1.0e-9;

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

std::string block_name(const std::string& id) { return "block '" + id + "'"; }

// "1 iteration", "30 iterations".
std::string iterations_text(std::size_t n) { return std::to_string(n) + (n == 1 ? " iteration" : " iterations"); }

Eigen::Vector3d vec(const Point3& p) { return {p.x, p.y, p.z}; }
Point3 point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// The axis-aligned box of a block's vertices.
struct Box {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  void add(const Point3& p) {
    lo = lo.cwiseMin(vec(p));
    hi = hi.cwiseMax(vec(p));
  }
  bool meets(const Box& o, double range) const {
    return ((lo.array() - range) <= o.hi.array()).all() && ((o.lo.array() - range) <= hi.array()).all();
  }
};

Box box_of(const std::vector<ConvexPolyhedron>& parts) {
  Box b;
  for (const ConvexPolyhedron& part : parts) {
    for (const Point3& p : part.vertices()) b.add(p);
  }
  return b;
}

// Twice the vector area of a planar polygon given as vertex ids of `part` (Newell's formula): it
// points outward, the loop being counter-clockwise seen from outside.
Eigen::Vector3d doubled_vector_area(const ConvexPolyhedron& part, const ConvexPolyhedron::Face& loop) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const Eigen::Vector3d o = vec(part[loop[0]]);
  for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
    sum += (vec(part[loop[k]]) - o).cross(vec(part[loop[k + 1]]) - o);
  }
  return sum;
}

// A corner of a block: a part and the index of its vertex there. The parts of a non-convex
// block share corners (each part meeting at a corner has its own copy of the vertex).
using Corner = std::pair<std::uint32_t, std::uint32_t>;

// corners[p][v]: the corner of the parts' vertex v of part p, the first (part, index) at the same
// place, within corner_tolerance of the block's size (the parts' copies of a corner are each
// rounded from the planes that cut them).
std::vector<std::vector<Corner>> corners_of(const std::vector<ConvexPolyhedron>& parts, double size) {
  std::vector<std::pair<Eigen::Vector3d, Corner>> all;
  std::vector<std::vector<Corner>> out(parts.size());
  for (std::uint32_t p = 0; p < parts.size(); ++p) {
    for (std::uint32_t v = 0; v < parts[p].vertices().size(); ++v) all.push_back({vec(parts[p][v]), {p, v}});
    out[p].resize(parts[p].vertices().size());
  }
  std::sort(all.begin(), all.end(), [](const auto& x, const auto& y) { return x.first.x() < y.first.x(); });
  const double tolerance = corner_tolerance * size;
  for (std::size_t i = 0; i < all.size(); ++i) {
    Corner first = all[i].second;
    for (std::size_t j = i; j-- > 0 && all[i].first.x() - all[j].first.x() <= tolerance;) {
      if ((all[i].first - all[j].first).norm() <= tolerance) first = std::min(first, all[j].second);
    }
    for (std::size_t j = i + 1; j < all.size() && all[j].first.x() - all[i].first.x() <= tolerance; ++j) {
      if ((all[i].first - all[j].first).norm() <= tolerance) first = std::min(first, all[j].second);
    }
    out[all[i].second.first][all[i].second.second] = first;
  }
  return out;
}

struct Block {
  Block3dSpec spec;
  std::vector<ConvexPolyhedron> parts;  // current
  detail::CentralMoments3d moments;     // of the current parts
  double mass = 0.0;
  int dof = 0;                          // 0 (fixed), 6 (rigid) or 12
  std::size_t offset = 0;               // of its unknowns in the global vector
  Eigen::VectorXd velocity;             // dof entries
  Eigen::Matrix<double, 6, 1> stress = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d reference_centroid = Eigen::Vector3d::Zero();
  detail::Matrix6 elasticity = detail::Matrix6::Zero();
  Box box;

  Eigen::MatrixXd mass_matrix;          // dof x dof, of the current moments
  double size = 0.0;                    // m, the cube root of its volume
  std::vector<std::vector<Corner>> corners;  // corners_of its parts (they move as one)

  void refresh_mass_matrix() { mass_matrix = detail::mass_matrix(moments, mass).topLeftCorner(dof, dof); }
};

// A vertex of one block of a pair: its block's role and its corner.
using ContactVertex = std::pair<kernel::BlockRole, Corner>;

// The vertices among a constraint's two features, as corners of their blocks: the same corner
// whichever part of a non-convex block the kernel found it in.
std::vector<ContactVertex> vertices_of(const Block& cp, const Block& tp, const kernel::ContactConstraint& c) {
  std::vector<ContactVertex> out;
  for (const auto& [side, f] : {std::pair{kernel::BlockRole::cp, c.cp_feature}, std::pair{kernel::BlockRole::tp, c.tp_feature}}) {
    const Block& block = side == kernel::BlockRole::cp ? cp : tp;
    if (f.kind == kernel::Feature::Kind::vertex) out.push_back({side, block.corners[f.part][f.index]});
  }
  return out;
}

// The area of the convex hull of points in a plane (Andrew's monotone chain, shoelace formula).
double hull_area(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(),
            [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) { return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y()); });
  const auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
  };
  std::vector<Eigen::Vector2d> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = hull.size();
    for (const Eigen::Vector2d& p : points) {
      while (hull.size() >= base + 2 && turn(hull[hull.size() - 2], hull.back(), p) <= 0.0) hull.pop_back();
      hull.push_back(p);
    }
    hull.pop_back();
    std::reverse(points.begin(), points.end());
  }
  double twice = 0.0;
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Eigen::Vector2d &p = hull[k], &q = hull[(k + 1) % hull.size()];
    twice += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * std::abs(twice);
}

// The contact area each constraint of a pair stands for (cohesion and tensile strength act
// through it, Pa times m²): constraints whose normals agree within 5° are the corners of one
// contact polygon (a face resting on a face gives the corners of their overlap: vertices of each
// on the other's face, crossings of their edges); the polygon's area, the convex hull of their
// midpoints in the plane, is shared equally among them. Fewer than three (a vertex, an edge on a
// face) stand for no area.
std::vector<double> contact_areas(const std::vector<kernel::ContactConstraint>& found) {
  const double agree = std::cos(5.0 / degrees_per_radian);
  std::vector<double> out(found.size(), 0.0);
  std::vector<char> grouped(found.size(), 0);
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (grouped[i]) continue;
    const Eigen::Vector3d n = vec(found[i].normal);
    std::vector<std::size_t> members{i};
    for (std::size_t j = i + 1; j < found.size(); ++j) {
      if (!grouped[j] && n.dot(vec(found[j].normal)) > agree) members.push_back(j), grouped[j] = 1;
    }
    if (members.size() < 3) continue;
    const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    std::vector<Eigen::Vector2d> points;
    for (const std::size_t m : members) {
      const Eigen::Vector3d p = 0.5 * (vec(found[m].point_cp) + vec(found[m].point_tp));
      points.emplace_back(p.dot(t1), p.dot(t2));
    }
    const double share = hull_area(std::move(points)) / static_cast<double>(members.size());
    for (const std::size_t m : members) out[m] = share;
  }
  return out;
}

// A feature that stays the same feature from step to step (convex_polyhedron.hpp, "Feature
// ids"): a vertex by its index, an edge by its two vertices, a face by its index as given, not
// by the facet or the edge index, which change when the rounding of a moved block's vertices
// splits a face into facets differently.
struct StableFeature {
  kernel::Feature::Kind kind = kernel::Feature::Kind::vertex;
  std::uint32_t part = 0;
  std::uint64_t id = 0;  // vertex index; (i << 32) | j of an edge's vertices, i < j; input face
  auto tied() const { return std::tuple(kind, part, id); }
  friend bool operator<(const StableFeature& x, const StableFeature& y) { return x.tied() < y.tied(); }
};

StableFeature stable(const Block& block, const kernel::Feature& f) {
  const ConvexPolyhedron& part = block.parts[f.part];
  switch (f.kind) {
    case kernel::Feature::Kind::vertex: return {f.kind, f.part, f.index};
    case kernel::Feature::Kind::edge: {
      const auto [i, j] = part.edges()[f.index];
      return {f.kind, f.part, (std::uint64_t{std::min(i, j)} << 32) | std::max(i, j)};
    }
    case kernel::Feature::Kind::face: return {f.kind, f.part, part.input_face(f.index)};
  }
  return {};
}

// The block's current index (vertex, edge, or the first facet of the face) of a stable feature;
// nullopt when it has none (a diagonal of a face split differently now).
std::optional<std::uint32_t> current_index(const Block& block, const StableFeature& f) {
  const ConvexPolyhedron& part = block.parts[f.part];
  switch (f.kind) {
    case kernel::Feature::Kind::vertex: return static_cast<std::uint32_t>(f.id);
    case kernel::Feature::Kind::edge:
      for (std::uint32_t e = 0; e < part.edges().size(); ++e) {
        const auto [i, j] = part.edges()[e];
        if (((std::uint64_t{std::min(i, j)} << 32) | std::max(i, j)) == f.id) return e;
      }
      return std::nullopt;
    case kernel::Feature::Kind::face:
      for (std::uint32_t facet = 0; facet < part.faces().size(); ++facet) {
        if (part.input_face(facet) == f.id) return facet;
      }
      return std::nullopt;
  }
  return std::nullopt;
}

// What identifies a constraint from step to step (§4.2): its pair, its type and its two features.
using ConstraintKey = std::tuple<std::size_t, std::size_t, int, StableFeature, StableFeature>;

ConstraintKey key_of(std::size_t a, std::size_t b, const Block& cp, const Block& tp, const kernel::ContactConstraint& c) {
  return {a, b, static_cast<int>(c.type), stable(cp, c.cp_feature), stable(tp, c.tp_feature)};
}

// What the contact list holds of a closed constraint for the next step (§4.2): a vertex of one
// block on a face of the other (`other` is that face), or a vertex of cp pressed on a vertex of
// tp along a plane that is no face (an edge pair's plane or the line of the points; `other` is
// tp's vertex, the normal turns with tp).
struct Hold {
  kernel::BlockRole vertex_side = kernel::BlockRole::cp;  // the vertex's block
  StableFeature vertex;
  StableFeature other;  // on the other block
  auto tied() const { return std::tuple(vertex_side, vertex, other); }
  friend bool operator<(const Hold& x, const Hold& y) { return x.tied() < y.tied(); }
};

// The vertex and face of a constraint whose plane `source` is a face of one block and whose
// point on the other block is a vertex; nullopt otherwise.
std::optional<Hold> vertex_on_face(const Block& cp, const Block& tp, const kernel::ContactConstraint& c,
                                   const kernel::PlaneSource& source) {
  using Kind = kernel::PlaneSource::Kind;
  if (source.kind != Kind::cp_face && source.kind != Kind::tp_face) return std::nullopt;
  const bool face_on_cp = source.kind == Kind::cp_face;
  const kernel::Feature& vertex = face_on_cp ? c.tp_feature : c.cp_feature;
  if (vertex.kind != kernel::Feature::Kind::vertex) return std::nullopt;
  const kernel::Feature& face_side = face_on_cp ? c.cp_feature : c.tp_feature;
  const kernel::Feature face{kernel::Feature::Kind::face, face_on_cp ? source.cp_index : source.tp_index, face_side.part};
  return Hold{face_on_cp ? kernel::BlockRole::tp : kernel::BlockRole::cp, stable(face_on_cp ? tp : cp, vertex),
              stable(face_on_cp ? cp : tp, face)};
}

// The hold of a constraint itself: its vertex on its face, or its two vertices; nullopt for an
// edge-edge or a vertex-edge constraint whose plane is no face.
std::optional<Hold> own_hold(const Block& cp, const Block& tp, const kernel::ContactConstraint& c) {
  if (auto h = vertex_on_face(cp, tp, c, c.plane)) return h;
  if (c.type != kernel::ConstraintType::vertex_vertex) return std::nullopt;
  return Hold{kernel::BlockRole::cp, stable(cp, c.cp_feature), stable(tp, c.tp_feature)};
}

// What a closed constraint holds for the next step: its own hold and, for a vertex-vertex
// constraint whose plane is a face, the other vertex on each candidate face of the other block.
// Two vertices that coincide (blocks cut from one region) are then both held, each on the faces
// of the other block it rests on: the kernel reports such a contact once, from one of the
// vertices, and the other would have no contact of its own once they part.
std::vector<Hold> holds_of(const Block& cp, const Block& tp, const kernel::ContactConstraint& c) {
  std::vector<Hold> out;
  const std::optional<Hold> own = own_hold(cp, tp, c);
  if (!own) return out;
  out.push_back(*own);
  if (c.type != kernel::ConstraintType::vertex_vertex || own->other.kind != kernel::Feature::Kind::face) return out;
  for (const kernel::CandidatePlane& candidate : c.candidates) {
    const std::optional<Hold> h = vertex_on_face(cp, tp, c, candidate.source);
    if (h && h->vertex_side != own->vertex_side) out.push_back(*h);
  }
  return out;
}

// The constraint of a hold with the blocks where they are now; nullopt once the vertex has left
// (the kernel then decides its contacts afresh).
//   Vertex on face: the plane of the face as given (its current vertices), the vertex's distance
//   from it as the gap and its foot on the plane as the face's point; left when farther than
//   `range` from the plane or outside the face by more than `range`.
//   Two vertices: `normal` (unit, from cp towards tp), `from`'s plane source; left when the
//   vertices are farther apart than `range`.
std::optional<kernel::ContactConstraint> held_contact(const Block& cp, const Block& tp, const Hold& h,
                                                      const kernel::ContactConstraint& from,
                                                      const Eigen::Vector3d& normal, double range) {
  const bool vertex_on_cp = h.vertex_side == kernel::BlockRole::cp;
  const Block& vertex_block = vertex_on_cp ? cp : tp;
  const Block& other_block = vertex_on_cp ? tp : cp;
  const std::optional<std::uint32_t> other = current_index(other_block, h.other);
  if (!other) return std::nullopt;
  const auto vertex_index = static_cast<std::uint32_t>(h.vertex.id);
  const Eigen::Vector3d v = vec(vertex_block.parts[h.vertex.part][vertex_index]);
  kernel::ContactConstraint c;
  c.entering = h.vertex_side;
  (vertex_on_cp ? c.cp_feature : c.tp_feature) = {kernel::Feature::Kind::vertex, vertex_index, h.vertex.part};
  (vertex_on_cp ? c.tp_feature : c.cp_feature) = {h.other.kind, *other, h.other.part};
  Eigen::Vector3d n = normal;
  if (h.other.kind == kernel::Feature::Kind::vertex) {
    const Eigen::Vector3d w = vec(other_block.parts[h.other.part][*other]);
    if ((w - v).norm() > range) return std::nullopt;
    c.type = kernel::ConstraintType::vertex_vertex;
    c.entering = from.entering;
    c.plane = from.plane;
    c.point_cp = point(v);
    c.point_tp = point(w);
    c.gap = (w - v).dot(n);
  } else {
    const ConvexPolyhedron& part = other_block.parts[h.other.part];
    const ConvexPolyhedron::Face& loop = part.input_faces()[h.other.id];
    const Eigen::Vector3d outward = doubled_vector_area(part, loop).normalized();
    const double distance = (v - vec(part[loop[0]])).dot(outward);
    if (std::abs(distance) > range) return std::nullopt;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Eigen::Vector3d a = vec(part[loop[k]]), b = vec(part[loop[(k + 1) % loop.size()]]);
      // n x (b - a) points into the face from its edge (the loop is counter-clockwise about n).
      if (outward.cross(b - a).normalized().dot(v - a) < -range) return std::nullopt;
    }
    const Eigen::Vector3d foot = v - distance * outward;
    c.type = kernel::ConstraintType::vertex_face;
    c.point_cp = point(vertex_on_cp ? v : foot);
    c.point_tp = point(vertex_on_cp ? foot : v);
    n = vertex_on_cp ? Eigen::Vector3d(-outward) : outward;
    c.plane = vertex_on_cp ? kernel::PlaneSource{kernel::PlaneSource::Kind::tp_face, 0, *other}
                           : kernel::PlaneSource{kernel::PlaneSource::Kind::cp_face, *other, 0};
    c.gap = distance;
  }
  c.normal = point(n);
  const Eigen::Vector3d t1 = n.unitOrthogonal();
  c.tangent1 = point(t1);
  c.tangent2 = point(n.cross(t1));
  return c;
}

// Edges closer to parallel than this (the sine of their angle) make no edge-edge constraint in
// the engine: the crossing of two nearly collinear edges (a block's edge sliding along the edge it
// rests in) moves along them by the lateral motion over this sine, so it comes and goes from step
// to step and each time starts a new spring; the vertex contacts at the ends of their overlap
// carry the contact.
constexpr double parallel_edges = 1.0e-3;

// Puts a constraint on the plane of unit normal n (from cp towards tp) through its points: the
// normal, the gap of the points along it and a tangent basis of the plane.
void set_plane(kernel::ContactConstraint& c, const Eigen::Vector3d& n) {
  c.normal = point(n);
  c.gap = (vec(c.point_tp) - vec(c.point_cp)).dot(n);
  const Eigen::Vector3d t1 = n.unitOrthogonal();
  c.tangent1 = point(t1);
  c.tangent2 = point(n.cross(t1));
}

// The unit direction of the edge feature `f` of block b.
Eigen::Vector3d edge_direction(const Block& b, const kernel::Feature& f) {
  const ConvexPolyhedron& part = b.parts[f.part];
  const auto [i, j] = part.edges()[f.index];
  return Eigen::Vector3d(vec(part[j]) - vec(part[i])).normalized();
}

// A vertex-edge or vertex-vertex constraint whose two points lie apart along its plane by more
// than `tolerance`: a vertex that has slid along a face's plane past the face's edge (a wedge's
// daylight vertex past the slope's free face). Its gap along the plane's normal (about zero) is
// not its distance from the other block, and a spring on it would hold the vertex on the plane
// beyond the face, as far as the detection range: a wedge that had slid out of its slope was
// still carried there, where it should tip over the free face's edge.
bool apart_along_plane(const kernel::ContactConstraint& c, double tolerance) {
  if (c.type != kernel::ConstraintType::vertex_edge && c.type != kernel::ConstraintType::vertex_vertex) return false;
  const Eigen::Vector3d apart = vec(c.point_tp) - vec(c.point_cp), n = vec(c.normal);
  return (apart - apart.dot(n) * n).norm() > tolerance;
}

// Such a constraint on the line of its two points (the kernel's plane for a vertex contact
// whose candidate planes all fail, contact_constraints.hpp): its gap is their distance, so it
// closes only when the vertex comes back to the other block's edge or vertex.
void to_contact_line(kernel::ContactConstraint& c) {
  set_plane(c, (vec(c.point_tp) - vec(c.point_cp)).normalized());
  c.plane = {kernel::PlaneSource::Kind::contact_line, 0, 0};
  c.candidates.clear();
}

bool nearly_parallel(const Block& cp, const Block& tp, const kernel::ContactConstraint& c) {
  return edge_direction(cp, c.cp_feature).cross(edge_direction(tp, c.tp_feature)).norm() < parallel_edges;
}

// A closed edge-edge constraint with the blocks where they are now: the closest points of the two
// edges' lines (the edges `key` names), the normal their cross product turned to the side of
// `from`'s; nullopt when an edge is gone (a diagonal of a face split differently now), the edges
// have turned nearly parallel, their lines are farther apart than `range`, a closest point is
// off its edge by more than `range` (the crossing has left the edges), or the gap differs from
// `end_gap`, the one the last solve left, by more than a quarter of the range (half a step's
// largest motion: the lines' closest points have jumped, as they do where the crossing runs off
// an edge's end, and the distance of the lines there is no penetration). Held so, a crossing
// near the end of an edge does not come and go with the rounding of its parameters.
std::optional<kernel::ContactConstraint> held_crossing(const Block& cp, const Block& tp, const ConstraintKey& key,
                                                       const kernel::ContactConstraint& from, double end_gap,
                                                       double range) {
  const StableFeature &e = std::get<3>(key), &g = std::get<4>(key);
  const std::optional<std::uint32_t> e_index = current_index(cp, e), g_index = current_index(tp, g);
  if (!e_index || !g_index) return std::nullopt;
  const ConvexPolyhedron& x = cp.parts[e.part];
  const ConvexPolyhedron& y = tp.parts[g.part];
  const auto [i, j] = x.edges()[*e_index];
  const auto [k, l] = y.edges()[*g_index];
  const Eigen::Vector3d p = vec(x[i]), u = vec(x[j]) - p, q = vec(y[k]), w = vec(y[l]) - q;
  Eigen::Vector3d n = u.cross(w);
  if (n.norm() < parallel_edges * u.norm() * w.norm()) return std::nullopt;
  n.normalize();
  if (n.dot(vec(from.normal)) < 0.0) n = -n;
  // Closest points p + s u, q + t w: (p + s u - q - t w) orthogonal to u and w.
  const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w), du = (p - q).dot(u), dw = (p - q).dot(w);
  const double det = uu * ww - uw * uw;
  const double s = (uw * dw - ww * du) / det, t = (uu * dw - uw * du) / det;
  const auto on_edge = [&](double parameter, double length) {
    return parameter * length >= -range && (parameter - 1.0) * length <= range;
  };
  if (!on_edge(s, std::sqrt(uu)) || !on_edge(t, std::sqrt(ww))) return std::nullopt;
  const Eigen::Vector3d on_cp = p + s * u, on_tp = q + t * w;
  const double gap = (on_tp - on_cp).dot(n);
  if (std::abs(gap) > range || std::abs(gap - end_gap) > 0.25 * range) return std::nullopt;
  kernel::ContactConstraint c = from;
  c.cp_feature.index = *e_index;
  c.tp_feature.index = *g_index;
  c.point_cp = point(on_cp);
  c.point_tp = point(on_tp);
  set_plane(c, n);
  return c;
}

struct Constraint {
  std::size_t a = 0, b = 0;  // blocks: a the kernel's cp, b its tp
  kernel::ContactConstraint geometry;
  ConstraintKey key;        // with the blocks as they were when it was found
  std::vector<Hold> holds;  // what it holds for the next step when it ends closed
  detail::ContactLaw3d law;
  detail::ContactKinematics3d kinematics;
  detail::ContactState3d state;     // of the start of the step, then of the iteration
  detail::ContactUpdate3d update;   // of the last solve
  double slip_work = 0.0;           // friction work of the last solve, J
  double start_energy = 0.0;        // held by its springs at the start of the step, J
  // Found apart but closed by Table 1's prediction (pair_constraints) and not yet through a step:
  // its springs hold no energy, and it carries no tension (it has not touched).
  bool closing = false;
  bool revised = false;  // §5.1's revision was tried on it in this step (attempt)
  bool replaned = false;  // §4.3's new choice of plane was made for it in this step (attempt)
  bool shared = false;    // another constraint of its pair is at its position (pair_constraints)
  double dashpot_normal = 0.0;      // c_n and c_t of its dashpots, N s/m (dda3d.hpp)
  double dashpot_tangential = 0.0;
  double damping_work = 0.0;        // taken by them over the last solve, J
  Eigen::Vector3d normal_in_tp = Eigen::Vector3d::Zero();  // the normal in tp's own axes (its rotation undone)
};

// The contact an open-close iteration that did not converge could not settle: the first of
// those that changed between open and closed (or gave way from locked) in the most iterations.
struct Unsettled {
  const Constraint* contact = nullptr;  // in the attempt's list
  std::size_t changes = 0;              // iterations in which it changed
  std::size_t changed_last = 0;         // contacts that changed in the last iteration
  std::size_t contacts = 0;             // in the list
};

ContactMode3d public_mode(detail::ContactMode mode) {
  switch (mode) {
    case detail::ContactMode::open: return ContactMode3d::open;
    case detail::ContactMode::locked: return ContactMode3d::stick;
    case detail::ContactMode::sliding: return ContactMode3d::slide;
  }
  return ContactMode3d::open;
}

void check_range(bool ok, const std::string& field, const std::string& expected, double value) {
  if (!ok) throw std::invalid_argument(field + ": expected " + expected + ", got " + number(value));
}

}  // namespace

struct Dda3d::Impl {
  std::vector<Block> blocks;
  std::vector<Block3dState> states;
  ContactLaw3d law;
  Dda3dParams params;
  double size = 0.0;   // the scene's bounding-box diagonal at the start, m
  double range = 0.0;  // the contact detection range, m
  int thread_count = 1;  // of the parallel passes (Dda3dParams::threads)
  double h = 0.0;      // the step the next attempt takes, s
  double time = 0.0;
  std::size_t steps = 0;
  std::size_t unknowns = 0;
  std::vector<Constraint> constraints;  // the contact list after the last accepted step
  // The deepest constraint detect() dropped (deeper than the range), for the check at t = 0.
  struct Dropped {
    double depth = 0.0;
    std::size_t a = 0, b = 0;
  } deepest;
  // Wall seconds spent so far in detection and in the linear solves (factorization or CG).
  mutable struct {
    double detection = 0.0, solve = 0.0;
  } timing;
  Equilibrium equilibrium;  // the pre-solve's report
  Step3dStats last;
  double friction_dissipated = 0.0, damping_dissipated = 0.0, numerical_dissipated = 0.0;
  kernel::PredicateCounters predicates;

  Impl(std::vector<Block3dSpec> specs, ContactLaw3d contact_law, Dda3dParams p);
  void validate_law() const;
  detail::ContactLaw3d pair_law(const Block& a, const Block& b) const;
  std::vector<Constraint> detect(bool at_start = false);
  std::vector<std::pair<std::size_t, std::size_t>> candidate_pairs() const;
  std::vector<Constraint> pair_constraints(std::size_t a, std::size_t b, std::span<const Constraint> earlier,
                                           const std::map<ConstraintKey, const Constraint*>& previous, bool at_start,
                                           Dropped& dropped) const;
  void hold_contacts(std::size_t a, std::size_t b, std::span<const Constraint> earlier,
                     std::vector<kernel::ContactConstraint>& found) const;
  std::vector<const Constraint*> vanished_contacts(std::span<const Constraint> earlier,
                                                   const std::vector<ConstraintKey>& keys,
                                                   std::span<const kernel::ContactConstraint> found) const;
  const Constraint* transferred_from(const std::vector<const Constraint*>& vanished,
                                     const kernel::ContactConstraint& c) const;
  bool attempt(std::vector<Constraint>& list, Eigen::VectorXd& d, std::size_t& iterations, double& numerical,
               Unsettled& unsettled) const;
  std::string describe(const Unsettled& u) const;
  bool revise(Constraint& k, const Eigen::Ref<const Eigen::VectorXd>& di,
              const Eigen::Ref<const Eigen::VectorXd>& dj) const;
  bool replane(Constraint& k, const Eigen::Ref<const Eigen::VectorXd>& di,
               const Eigen::Ref<const Eigen::VectorXd>& dj) const;
  void solve(const std::vector<Constraint>& list, Eigen::VectorXd& d, double& numerical,
             const std::vector<char>* settling = nullptr, double* residual = nullptr, double tie = 1.0) const;
  void settle();
  SettleRound settle_round(const std::vector<char>& settling);
  void sliding_start(std::vector<Constraint>& list, const std::vector<char>& settling, Eigen::VectorXd& d) const;
  double largest_displacement(const Eigen::VectorXd& d) const;
  std::pair<double, std::size_t> largest_rotation(const Eigen::VectorXd& d) const;
  void accept(std::vector<Constraint> list, const Eigen::VectorXd& d, std::size_t iterations, double numerical);
  void move(std::size_t i, const Eigen::Ref<const Eigen::VectorXd>& di);
  void check_energy();
  void check_penetration() const;
  Energies3d energies() const;
  // The monitor's baseline: the energies after the initial equilibrium, the largest drop in
  // potential energy so far.
  double start_total = 0.0, start_kinetic = 0.0, start_strain = 0.0, start_contact = 0.0, largest_drop = 0.0;
  void refresh_state(std::size_t i);
};

Dda3d::Impl::Impl(std::vector<Block3dSpec> specs, ContactLaw3d contact_law, Dda3dParams p)
    : law(std::move(contact_law)), params(p) {
  check_range(std::isfinite(params.dt) && params.dt > 0.0, "time.dt", "a finite step > 0 s", params.dt);
  check_range(params.max_displacement_ratio > 0.0 && params.max_displacement_ratio < 1.0,
              "time.max_displacement_ratio", "a ratio in (0, 1)", params.max_displacement_ratio);
  check_range(params.max_rotation_deg > 0.0 && params.max_rotation_deg < 90.0, "time.max_rotation_deg",
              "an angle in (0, 90) degrees", params.max_rotation_deg);
  check_range(params.min_dt_ratio > 0.0 && params.min_dt_ratio < 1.0, "time.min_dt_ratio", "a ratio in (0, 1)",
              params.min_dt_ratio);
  if (params.max_open_close == 0) throw std::invalid_argument("max_open_close: expected at least 1 iteration");
  for (double g : params.gravity) check_range(std::isfinite(g), "gravity", "finite components", g);
  thread_count = params.threads == 0 ? omp_get_max_threads() : static_cast<int>(params.threads);
  validate_law();
  if (specs.empty()) throw std::invalid_argument("blocks: expected at least one block");
  std::set<std::string> ids;
  Box scene;
  for (Block3dSpec& spec : specs) {
    const std::string name = block_name(spec.id);
    if (spec.id.empty()) throw std::invalid_argument("blocks: a block has an empty id");
    if (!ids.insert(spec.id).second) throw std::invalid_argument(name + ": the id is used twice");
    if (spec.parts.empty()) throw std::invalid_argument(name + ": expected at least one part");
    const Material& m = spec.material;
    check_range(std::isfinite(m.density) && m.density > 0.0, name + " material density", "> 0 kg/m³", m.density);
    check_range(std::isfinite(m.youngs_modulus) && m.youngs_modulus > 0.0, name + " material youngs_modulus",
                "> 0 Pa", m.youngs_modulus);
    check_range(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5, name + " material poisson_ratio",
                "a ratio in (-1, 0.5)", m.poisson_ratio);
    for (double v : spec.velocity) check_range(std::isfinite(v), name + " velocity", "finite components", v);
    Block b;
    b.parts = spec.parts;
    b.moments = detail::central_moments3d(b.parts);
    if (!(b.moments.volume > 0.0)) throw std::invalid_argument(name + ": zero volume");
    b.mass = m.density * b.moments.volume;
    b.size = std::cbrt(b.moments.volume);
    b.corners = corners_of(b.parts, b.size);
    b.dof = spec.fixed ? 0 : spec.rigid ? detail::rigid_dof3d : detail::dof3d;
    b.refresh_mass_matrix();
    b.offset = unknowns;
    unknowns += static_cast<std::size_t>(b.dof);
    b.velocity = Eigen::VectorXd::Zero(b.dof);
    if (!spec.fixed) {
      for (int k = 0; k < 6; ++k) b.velocity[k] = spec.velocity[static_cast<std::size_t>(k)];
    }
    b.reference_centroid = b.moments.centroid;
    b.elasticity = detail::elasticity_matrix3d(m.youngs_modulus, m.poisson_ratio);
    b.box = box_of(b.parts);
    scene.add(point(b.box.lo));
    scene.add(point(b.box.hi));
    b.spec = std::move(spec);
    blocks.push_back(std::move(b));
  }
  size = (scene.hi - scene.lo).norm();
  range = 2.0 * params.max_displacement_ratio * size;
  h = params.dt;
  states.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) refresh_state(i);
  constraints = detect(true);
  if (deepest.depth > 0.0) {
    throw std::invalid_argument(block_name(blocks[deepest.a].spec.id) + " and " + block_name(blocks[deepest.b].spec.id) +
                                " overlap by " + number(deepest.depth) +
                                " m at the start; expected at most the contact detection range " + number(range) +
                                " m (2 x max_displacement_ratio x the scene's size), within which the penalty acts");
  }
  if (params.initial_equilibrium != InitialEquilibrium::off) settle();
  const Energies3d e = energies();
  start_total = e.total();
  start_kinetic = e.kinetic;
  start_strain = e.strain;
  start_contact = e.contact;
}

namespace {

// The initial equilibrium's locked constraint: locked whatever the load, its spring keeps the
// whole trial stretch of the increments d_i, d_j.
void lock_whole_stretch(Constraint& k, const Eigen::VectorXd& di, const Eigen::VectorXd& dj) {
  const Eigen::Vector3d& n = k.kinematics.normal;
  const Eigen::Vector3d trial = k.state.shear + detail::relative_motion(k.kinematics, di, dj);
  k.update.mode = detail::ContactMode::locked;
  k.update.shear = trial - trial.dot(n) * n;
  k.update.tangential_force = -k.law.kt * k.update.shear;
}

}  // namespace

// The initial equilibrium (header; dynamics/common/equilibrium.hpp): rounds over the blocks
// resting on a fixed block at the start, directly or through other resting blocks.
void Dda3d::Impl::settle() {
  const WallTimer timer(equilibrium.seconds);
  const double resting = resting_gap * size;
  std::vector<std::vector<std::size_t>> adjacent(blocks.size());
  for (const Constraint& k : constraints) {
    if (k.kinematics.gap > resting) continue;
    adjacent[k.a].push_back(k.b);
    adjacent[k.b].push_back(k.a);
  }
  std::vector<char> fixed(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) fixed[i] = blocks[i].dof == 0;
  const std::vector<std::size_t> unsettled = settle_in_rounds<Stability3dError>(
      params.initial_equilibrium, adjacent, fixed, [this](const std::vector<char>& settling) {
        return settle_round(settling);
      });
  for (const std::size_t i : unsettled) equilibrium.unsettled.push_back(blocks[i].spec.id);
  if (equilibrium.blocks == 0) equilibrium.converged = true;  // nothing left to settle
}

// One round: the blocks marked in `settling` solved for static equilibrium with every closed
// constraint locked, the open-close iteration deciding which close; then moved there, their
// stresses and springs loaded, their velocities kept. Time and the energies' references start
// after it. Or, leaving every block where it was, the blocks without a static state: those the
// solve would move farther than a step may, or those of the contacts the open-close iteration
// could not settle.
SettleRound Dda3d::Impl::settle_round(const std::vector<char>& settling) {
  const double resting = resting_gap * size;
  equilibrium.ran = true;
  std::vector<Constraint> list = constraints;
  for (Constraint& k : list) {
    k.state.mode = k.kinematics.gap <= resting ? detail::ContactMode::locked : detail::ContactMode::open;
    k.closing = false;
    k.law.gap_tolerance = open_close_tolerance * size;
  }
  Eigen::VectorXd d;
  double unused = 0.0;
  std::size_t iteration = 1;
  for (;; ++iteration) {
    ++equilibrium.iterations;
    solve(list, d, unused, &settling, &equilibrium.ratio);
    if (params.equilibrium_progress) {
      params.equilibrium_progress(equilibrium.iterations, equilibrium.ratio);
    }
    if (!d.allFinite()) throw Stability3dError("the initial equilibrium's static solve has no finite solution");
    std::vector<char> changed_blocks(blocks.size(), 0);
    bool changed = false;
    for (Constraint& k : list) {
      const Block &ba = blocks[k.a], &bb = blocks[k.b];
      const auto di = ba.dof > 0 ? Eigen::VectorXd(d.segment(static_cast<Eigen::Index>(ba.offset), ba.dof))
                                 : Eigen::VectorXd();
      const auto dj = bb.dof > 0 ? Eigen::VectorXd(d.segment(static_cast<Eigen::Index>(bb.offset), bb.dof))
                                 : Eigen::VectorXd();
      k.update = detail::evaluate_contact(k.kinematics, k.state, k.law, di, dj);
      if (k.update.mode == detail::ContactMode::sliding) lock_whole_stretch(k, di, dj);
      // After half the iterations a closed contact stays closed: contacts at exact touch that
      // carry no load (the sides of stacked blocks) can alternate between a slight tension
      // closed and a slight penetration open; kept closed they start the run with that tension
      // (1e-8 m of spring), which the first step releases.
      if (iteration > params.max_open_close / 2 && k.state.mode != detail::ContactMode::open &&
          k.update.mode == detail::ContactMode::open) {
        k.update.mode = detail::ContactMode::locked;
        k.update.normal_force = -k.law.kn * (k.update.gap - k.state.offset);
      }
      if ((k.state.mode == detail::ContactMode::open) != (k.update.mode == detail::ContactMode::open)) {
        changed = true;
        changed_blocks[k.a] = changed_blocks[k.b] = 1;
      }
    }
    if (!changed) break;
    if (iteration == params.max_open_close) {
      SettleRound round;
      for (std::size_t i = 0; i < blocks.size(); ++i) {
        if (settling[i] && changed_blocks[i]) round.unsettled.push_back(i);
      }
      round.why = "the initial equilibrium does not settle: the open-close iteration of its static solve does "
                  "not converge in " + std::to_string(params.max_open_close) + " iterations at " +
                  block_name(blocks[round.unsettled.front()].spec.id) +
                  ", which has no static equilibrium where it rests at the start even with its contacts locked "
                  "against sliding; set \"initial_equilibrium\": \"auto\" to start it from its given state, "
                  "or false";
      return round;
    }
    for (Constraint& k : list) detail::next_iteration(k.state, k.update);
  }
  const double limit = params.max_displacement_ratio * size;
  SettleRound round;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!settling[i]) continue;
    const double moved = d.segment(static_cast<Eigen::Index>(blocks[i].offset), 3).norm();
    if (moved <= limit) continue;
    if (round.unsettled.empty()) {
      round.why = "the initial equilibrium would move " + block_name(blocks[i].spec.id) + " by " + number(moved) +
                  " m, more than max_displacement_ratio x size = " + number(limit) +
                  " m: the blocks it rests on at the start do not hold it (it topples, slides or is unsupported); "
                  "set \"initial_equilibrium\": \"auto\" to start it from its given state, or false";
    }
    round.unsettled.push_back(i);
  }
  if (!round.unsettled.empty()) return round;
  sliding_start(list, settling, d);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!settling[i]) continue;
    move(i, d.segment(static_cast<Eigen::Index>(blocks[i].offset), blocks[i].dof));
    blocks[i].reference_centroid = blocks[i].moments.centroid;
  }
  for (Constraint& k : list) detail::commit_step(k.state, k.update);
  constraints = std::move(list);
  constraints = detect();
  equilibrium.converged = true;
  equilibrium.blocks = static_cast<std::size_t>(std::count(settling.begin(), settling.end(), 1));
  return {};
}

void Dda3d::Impl::validate_law() const {
  check_range(std::isfinite(law.kn) && law.kn > 0.0, "contact.kn", "a finite penalty > 0 N/m", law.kn);
  check_range(std::isfinite(law.kt) && law.kt > 0.0, "contact.kt", "a finite penalty > 0 N/m", law.kt);
  const auto check_strengths = [](const std::string& where, double phi, double c, double t) {
    check_range(phi >= 0.0 && phi < 90.0, where + ".friction_angle_deg", "degrees in [0, 90)", phi);
    check_range(std::isfinite(c) && c >= 0.0, where + ".cohesion", "a finite cohesion >= 0 Pa", c);
    check_range(std::isfinite(t) && t >= 0.0, where + ".tensile_strength", "a finite strength >= 0 Pa", t);
  };
  check_strengths("contact", law.friction_angle_deg, law.cohesion, law.tensile_strength);
  check_range(std::isfinite(law.damping_ratio) && law.damping_ratio >= 0.0, "contact.damping_ratio",
              "a finite ratio >= 0", law.damping_ratio);
  std::set<std::pair<std::string, std::string>> seen;
  for (std::size_t k = 0; k < law.interfaces.size(); ++k) {
    const Interface3d& f = law.interfaces[k];
    const std::string where = "interfaces[" + std::to_string(k) + "]";
    check_strengths(where, f.friction_angle_deg, f.cohesion, f.tensile_strength);
    const auto pair = std::minmax(f.groups[0], f.groups[1]);
    if (!seen.insert(pair).second) {
      throw std::invalid_argument(where + ": a second interface between groups '" + pair.first + "' and '" +
                                  pair.second + "'");
    }
  }
}

detail::ContactLaw3d Dda3d::Impl::pair_law(const Block& a, const Block& b) const {
  detail::ContactLaw3d out{law.kn, law.kt, law.friction_angle_deg, law.cohesion, law.tensile_strength};
  const auto groups = std::minmax(a.spec.group, b.spec.group);
  for (const Interface3d& f : law.interfaces) {
    if (std::minmax(f.groups[0], f.groups[1]) == groups) {
      out.friction_angle_deg = f.friction_angle_deg;
      out.cohesion = f.cohesion;
      out.tensile_strength = f.tensile_strength;
    }
  }
  return out;
}

// Step 1 of the header, the contact list's memory (§4.2): a closed constraint keeps its plane
// while its features stay in contact, whatever the kernel's shortest exit says now.
//   * A vertex on a face stays on that face while it is over it (held_contact). A vertex that the
//     load pressed a little into a non-convex block next to its concave edge (a wedge on its two
//     joints) may be nearer to a face it never came through (the top of the part under the
//     edge) than to the faces it rests on; the shortest exit would push it out there and the
//     block would jump.
//   * Two vertices pressed together keep their normal, turning with tp.
//   * Two crossing edges stay crossed while the crossing is on both (held_crossing): near an
//     edge's end it would otherwise come and go with the rounding of its parameters, each time
//     a new spring at zero stretch.
// The held constraints replace the kernel's with the same features (or vertex and face), and
// for a held vertex those that penetrate; and a vertex that was closed on the other block in any
// way takes no new penetrating constraint (a vertex enters a face only from outside, where the
// kernel sees it first with a positive gap). The kernel's open constraints of such a vertex stay:
// it may come to a second face.
void Dda3d::Impl::hold_contacts(std::size_t a, std::size_t b, std::span<const Constraint> earlier,
                                std::vector<kernel::ContactConstraint>& found) const {
  std::set<ContactVertex> supported, held_vertices;
  std::map<Hold, kernel::ContactConstraint> held;
  std::vector<kernel::ContactConstraint> crossings;
  std::set<ConstraintKey> continuing, crossing_keys;
  for (const Constraint& k : earlier) {
    if (k.state.mode == detail::ContactMode::open) continue;
    continuing.insert(k.key);
    for (const ContactVertex& v : vertices_of(blocks[a], blocks[b], k.geometry)) supported.insert(v);
    if (k.geometry.type == kernel::ConstraintType::edge_edge) {
      if (auto c = held_crossing(blocks[a], blocks[b], k.key, k.geometry, k.update.gap, range)) {
        crossings.push_back(std::move(*c));
      }
      continue;
    }
    const Eigen::Vector3d normal = blocks[b].rotation * k.normal_in_tp;
    for (const Hold& hold : k.holds) {
      if (held.contains(hold)) continue;
      if (auto c = held_contact(blocks[a], blocks[b], hold, k.geometry, normal, range)) held.emplace(hold, std::move(*c));
    }
  }
  for (const auto& entry : held) {
    for (const ContactVertex& v : vertices_of(blocks[a], blocks[b], entry.second)) held_vertices.insert(v);
  }
  for (const kernel::ContactConstraint& c : crossings) crossing_keys.insert(key_of(a, b, blocks[a], blocks[b], c));
  std::erase_if(found, [&](const kernel::ContactConstraint& c) {
    const ConstraintKey key = key_of(a, b, blocks[a], blocks[b], c);
    if (crossing_keys.contains(key)) return true;
    if (const std::optional<Hold> hold = own_hold(blocks[a], blocks[b], c); hold && held.contains(*hold)) return true;
    if (c.gap > 0.0) return false;
    const bool is_new = !continuing.contains(key);
    for (const ContactVertex& v : vertices_of(blocks[a], blocks[b], c)) {
      if (held_vertices.contains(v) || (is_new && supported.contains(v))) return true;
    }
    return false;
  });
  // The held constraints first: where one and a kernel constraint are the same contact (a vertex
  // held on a face while the kernel finds the face's corner on the vertex's block), the merge
  // keeps the held one and its record.
  std::vector<kernel::ContactConstraint> ordered;
  for (auto& entry : held) ordered.push_back(std::move(entry.second));
  for (kernel::ContactConstraint& c : crossings) ordered.push_back(std::move(c));
  for (kernel::ContactConstraint& c : found) ordered.push_back(std::move(c));
  found = std::move(ordered);
  kernel::merge_coincident(found, std::min(range, merge_ratio * std::min(blocks[a].size, blocks[b].size)));
}

// Is `now` (with the key of `before`) still `before`'s contact? Not when its normal turned by
// more than transfer_angle: the same two vertices, pressed together on a joint's plane before the
// initial equilibrium, are found after it a little apart along the line joining them, while the
// contact on the plane goes on as a vertex held on the face (hold_contacts); the record is the
// held constraint's to take over (by transfer), not the open one's.
namespace {
bool continues(const Constraint& before, const kernel::ContactConstraint& now) {
  return vec(before.geometry.normal).dot(vec(now.normal)) >= std::cos(transfer_angle);
}
}  // namespace

// Contact transfer: the closed constraints of the pair in the last list that no constraint found
// now continues (their features changed: a crossing moved past an edge's end, a vertex slid from
// a face onto an edge; or the features are found with another plane).
std::vector<const Constraint*> Dda3d::Impl::vanished_contacts(std::span<const Constraint> earlier,
                                                             const std::vector<ConstraintKey>& keys,
                                                             std::span<const kernel::ContactConstraint> found) const {
  std::map<ConstraintKey, std::size_t> at;
  for (std::size_t i = 0; i < keys.size(); ++i) at.emplace(keys[i], i);
  std::vector<const Constraint*> out;
  for (const Constraint& k : earlier) {
    if (k.state.mode == detail::ContactMode::open) continue;
    const auto it = at.find(k.key);
    if (it == at.end() || !continues(k, found[it->second])) out.push_back(&k);
  }
  return out;
}

// The vanished constraint a new closed one continues: the nearest whose contact point on tp was
// within a step's largest motion (max_displacement_ratio x size) of the new one's and whose
// normal is within transfer_angle of it; nullptr when none. The new constraint takes its mode and
// springs, so a contact whose features change keeps its tangential stretch instead of starting a
// new spring at zero (Shi's contact transfer), which would let a block creep by the spring's
// reloading stretch at every change.
const Constraint* Dda3d::Impl::transferred_from(const std::vector<const Constraint*>& vanished,
                                                const kernel::ContactConstraint& c) const {
  const Constraint* best = nullptr;
  double nearest = params.max_displacement_ratio * size;
  for (const Constraint* k : vanished) {
    if (vec(k->geometry.normal).dot(vec(c.normal)) < std::cos(transfer_angle)) continue;
    const double distance = (vec(k->geometry.point_tp) - vec(c.point_tp)).norm();
    if (distance <= nearest) nearest = distance, best = k;
  }
  return best;
}

// Step 1 of the header: the constraints of every pair within the detection range, each keeping
// the record of the same constraint in the previous list (by key, else by contact transfer).
// The pairs of blocks whose boxes, widened by the range, overlap (and not both fixed): sweep and
// prune along x, sorted by block indices so the list does not depend on the sort.
std::vector<std::pair<std::size_t, std::size_t>> Dda3d::Impl::candidate_pairs() const {
  std::vector<std::size_t> order(blocks.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t i, std::size_t j) { return blocks[i].box.lo.x() < blocks[j].box.lo.x(); });
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Block& bi = blocks[order[i]];
    for (std::size_t j = i + 1; j < order.size() && blocks[order[j]].box.lo.x() - range <= bi.box.hi.x(); ++j) {
      const Block& bj = blocks[order[j]];
      if ((bi.dof == 0 && bj.dof == 0) || !bi.box.meets(bj.box, range)) continue;
      pairs.push_back(std::minmax(order[i], order[j]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

namespace {

// A vertex inside a convex part has one exit (seed 001 §4.3: the face it entered by), and one
// contact position has one contact (holds_of: the coincident vertices of cut blocks are one
// corner). A vertex-face constraint not closed in the last list (open, closed ahead by Table 1,
// or born closed now) is a second exit when, at its vertex, the pair carries closed constraints
// on the face's part in another plane and none in the face's: a wedge's crest vertex, going down
// its joint, passes below the plane of the slope's top face, and the slope's toe vertex passes
// behind the plane of the wedge's free face, each by the slide alone while the joints hold it.
// Closed, such a constraint carried weight the joints should and held the wedge. It is dropped.
// (Edge-edge constraints are kept: a crossing that moved onto new edges continues a contact.)
// `fresh` marks the constraints of `list` not closed in the last list.
void drop_second_exits(double same_position, const std::vector<char>& fresh, std::vector<Constraint>& list) {
  // Most pairs of a step have all their constraints carried, or (newly met) none.
  if (std::find(fresh.begin(), fresh.end(), 0) == fresh.end() ||
      std::find(fresh.begin(), fresh.end(), 1) == fresh.end()) {
    return;
  }
  const auto face_side = [](const Constraint& k) -> std::optional<kernel::BlockRole> {
    if (k.geometry.type != kernel::ConstraintType::vertex_face) return std::nullopt;
    if (k.geometry.plane.kind == kernel::PlaneSource::Kind::cp_face) return kernel::BlockRole::cp;
    if (k.geometry.plane.kind == kernel::PlaneSource::Kind::tp_face) return kernel::BlockRole::tp;
    return std::nullopt;
  };
  const auto part_on = [](const Constraint& k, kernel::BlockRole side) {
    return side == kernel::BlockRole::cp ? k.geometry.cp_feature.part : k.geometry.tp_feature.part;
  };
  const auto second = [&](std::size_t i) {
    const Constraint& k = list[i];
    const std::optional<kernel::BlockRole> side = face_side(k);
    if (!side) return false;
    bool other_plane = false;
    for (std::size_t j = 0; j < list.size(); ++j) {
      const Constraint& c = list[j];
      if (fresh[j] || part_on(c, *side) != part_on(k, *side) ||
          (vec(c.geometry.point_tp) - vec(k.geometry.point_tp)).norm() > same_position) {
        continue;
      }
      if (vec(c.geometry.normal).dot(vec(k.geometry.normal)) >= std::cos(transfer_angle)) return false;
      other_plane = true;
    }
    return other_plane;
  };
  std::vector<char> drop(list.size(), 0);
  for (std::size_t i = 0; i < list.size(); ++i) drop[i] = fresh[i] && second(i);
  std::vector<Constraint> kept;
  kept.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!drop[i]) kept.push_back(std::move(list[i]));
  }
  list = std::move(kept);
}

}  // namespace

// The constraints of the pair (a, b) (step 1 of the header); `earlier` are the pair's constraints
// in the last list, `previous` all of them by key; `dropped` receives the deepest it dropped.
std::vector<Constraint> Dda3d::Impl::pair_constraints(std::size_t a, std::size_t b, std::span<const Constraint> earlier,
                                                      const std::map<ConstraintKey, const Constraint*>& previous,
                                                      bool at_start, Dropped& dropped) const {
  const Block &ba = blocks[a], &bb = blocks[b];
  std::vector<Constraint> out;
  std::vector<char> fresh;  // not closed in the last list: open, closed ahead, or born closed now
  std::vector<kernel::ContactConstraint> found = kernel::with_policy(law.policy, [&](auto policy) {
    using Policy = decltype(policy);
    return kernel::contact_constraints<Policy>(std::span<const ConvexPolyhedron>(ba.parts),
                                               std::span<const ConvexPolyhedron>(bb.parts), range);
  });
  // No step moves a vertex farther than half the range (step 4), so a vertex deeper than
  // the range has not entered where the kernel's shortest exit says: it crossed an internal
  // face of a non-convex block, and its exit through the far side of that part would fling
  // the blocks apart. The neighbouring part's constraint is the one that holds it.
  for (const kernel::ContactConstraint& c : found) {
    if (c.gap < -range && -c.gap > dropped.depth) dropped = {-c.gap, a, b};
  }
  std::erase_if(found, [&](const kernel::ContactConstraint& c) {
    return c.gap < -range || (c.type == kernel::ConstraintType::edge_edge && nearly_parallel(ba, bb, c));
  });
  for (kernel::ContactConstraint& c : found) {
    if (apart_along_plane(c, merge_ratio * std::min(ba.size, bb.size))) to_contact_line(c);
  }
  hold_contacts(a, b, earlier, found);
  const std::vector<double> areas = contact_areas(found);
  const double same_position = std::min(range, merge_ratio * std::min(ba.size, bb.size));
  const detail::ContactLaw3d pair = pair_law(ba, bb);
  std::vector<ConstraintKey> keys;
  for (const kernel::ContactConstraint& c : found) keys.push_back(key_of(a, b, ba, bb, c));
  const std::vector<const Constraint*> vanished = vanished_contacts(earlier, keys, found);
  // The dashpots' coefficients (dda3d.hpp), of the pair's reduced mass.
  const double reduced = ba.dof == 0 ? bb.mass : bb.dof == 0 ? ba.mass : ba.mass * bb.mass / (ba.mass + bb.mass);
  const double dashpot_normal = 2.0 * law.damping_ratio * std::sqrt(reduced * pair.kn);
  const double dashpot_tangential = 2.0 * law.damping_ratio * std::sqrt(reduced * pair.kt);
  for (std::size_t i = 0; i < found.size(); ++i) {
    const kernel::ContactConstraint& c = found[i];
    Constraint k;
    k.a = a;
    k.b = b;
    k.geometry = c;
    k.key = keys[i];
    k.holds = holds_of(ba, bb, c);
    k.law = pair;
    k.shared = std::any_of(found.begin(), found.end(), [&](const kernel::ContactConstraint& other) {
      return &other != &c && (vec(other.point_tp) - vec(c.point_tp)).norm() <= same_position;
    });
    const double area = areas[i];
    k.normal_in_tp = bb.rotation.transpose() * vec(c.normal);
    k.dashpot_normal = dashpot_normal;
    k.dashpot_tangential = dashpot_tangential;
    k.kinematics = detail::contact_kinematics({c.point_cp, point(ba.moments.centroid), ba.dof},
                                              {c.point_tp, point(bb.moments.centroid), bb.dof}, c.normal, area);
    const Eigen::Vector3d velocity = detail::relative_motion(k.kinematics, ba.velocity, bb.velocity);
    bool inherited = true;
    if (const auto it = previous.find(k.key); it != previous.end() && continues(*it->second, c)) {
      k.state = it->second->state;
    } else if (const Constraint* from = c.gap <= 0.0 ? transferred_from(vanished, c) : nullptr) {
      // The transferred spring keeps its normal force: its offset moves with the gap.
      k.state = from->state;
      k.state.shear -= k.state.shear.dot(vec(c.normal)) * vec(c.normal);
      k.state.offset = std::min(0.0, k.kinematics.gap - (from->update.gap - from->state.offset));
    } else {
      inherited = false;
      // §2.4 method (1), Table 1: a new constraint starts closed (locked) when it penetrates or
      // its points' relative velocity closes the gap within the step, d0 + h n . v0 <= 0, and
      // open otherwise: an impact predicted so is settled in the first solve instead of the
      // second. (Locked whatever the tangential velocity: the first iteration's Mohr-Coulomb
      // test turns it to sliding if its spring gives way, and the spring starts at zero.)
      const double predicted = k.kinematics.gap + h * velocity.dot(k.kinematics.normal);
      k.state.mode = c.gap > 0.0 && predicted > 0.0 ? detail::ContactMode::open : detail::ContactMode::locked;
      k.closing = c.gap > 0.0 && k.state.mode == detail::ContactMode::locked;
      // Born penetrating inside an overlap the other constraints of the pair resist (its
      // features came into contact within it, as a crossing that moved onto new edges): it
      // resists further penetration only (contact_terms3d.hpp). At the start, an overlap
      // given in the scene is pushed out in full.
      // (The kinematics' gap, which the spring acts on: the kernel's may differ by a rounding,
      // which the check below would take for tension.)
      if (!at_start && c.gap < 0.0) k.state.offset = std::min(0.0, k.kinematics.gap);
    }
    // A closed record on a pair now apart beyond what its tensile strength holds (the
    // geometry of this step, re-detected, is the judge, as after a solve) starts open: its
    // spring would otherwise pull the blocks back in the first iteration and count energy
    // it never stored.
    if (inherited && k.state.mode != detail::ContactMode::open &&
        pair.kn * (k.kinematics.gap - k.state.offset - pair.gap_tolerance) > pair.tensile_strength * k.kinematics.area) {
      k.state = detail::ContactState3d{};
    }
    k.start_energy =
        k.closing ? 0.0 : detail::spring_energy(k.law, k.state.mode, k.state.offset, k.kinematics.gap, k.state.shear);
    k.update.gap = k.kinematics.gap;  // until a solve: what energies() reads of a fresh list
    if (k.state.sliding_direction.isZero()) {
      // §2.3 eq. 6: the sliding direction assumed first is that of the points' relative
      // velocity; the open-close iteration takes it from the solution after that (eq. 8).
      if (const auto v = kernel::sliding_direction(c.normal, point(velocity))) k.state.sliding_direction = vec(*v);
    }
    fresh.push_back(!inherited || k.state.mode == detail::ContactMode::open || k.closing);
    out.push_back(std::move(k));
  }
  drop_second_exits(same_position, fresh, out);
  return out;
}

std::vector<Constraint> Dda3d::Impl::detect(bool at_start) {
  const auto started = std::chrono::steady_clock::now();
  std::map<ConstraintKey, const Constraint*> previous;
  for (const Constraint& c : constraints) previous.emplace(c.key, &c);
  // The last list is built pair by pair, so each pair's constraints are consecutive in it.
  std::map<std::pair<std::size_t, std::size_t>, std::span<const Constraint>> by_pair;
  for (std::size_t i = 0; i < constraints.size();) {
    std::size_t j = i;
    while (j < constraints.size() && constraints[j].a == constraints[i].a && constraints[j].b == constraints[i].b) ++j;
    by_pair.emplace(std::pair{constraints[i].a, constraints[i].b}, std::span<const Constraint>(constraints).subspan(i, j - i));
    i = j;
  }
  const std::vector<std::pair<std::size_t, std::size_t>> pairs = candidate_pairs();
  std::vector<std::vector<Constraint>> found(pairs.size());
  std::vector<Dropped> dropped(pairs.size());
  std::vector<kernel::PredicateCounters> spent(static_cast<std::size_t>(thread_count));
  std::exception_ptr failure;
  // The pairs are independent: each thread fills its pairs' slots, merged below in pair order,
  // so the list is the same whatever the number of threads.
#pragma omp parallel num_threads(thread_count)
  {
    const kernel::PredicateCounters before = kernel::predicate_counters();
#pragma omp for schedule(dynamic, 4)
    for (std::ptrdiff_t p = 0; p < static_cast<std::ptrdiff_t>(pairs.size()); ++p) {
      const auto [a, b] = pairs[static_cast<std::size_t>(p)];
      const auto it = by_pair.find({a, b});
      try {
        found[static_cast<std::size_t>(p)] =
            pair_constraints(a, b, it == by_pair.end() ? std::span<const Constraint>() : it->second, previous, at_start,
                             dropped[static_cast<std::size_t>(p)]);
      } catch (...) {
#pragma omp critical(rockcontact_dda3d_detect)
        if (!failure) failure = std::current_exception();
      }
    }
    spent[static_cast<std::size_t>(omp_get_thread_num())] = kernel::predicate_counters() - before;
  }
  if (failure) std::rethrow_exception(failure);
  for (const kernel::PredicateCounters& c : spent) predicates += c;
  std::vector<Constraint> out;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (dropped[p].depth > deepest.depth) deepest = dropped[p];
    for (Constraint& k : found[p]) out.push_back(std::move(k));
  }
  timing.detection += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

// Step 2: assemble and solve for the increments d; `numerical` receives the elastic springs'
// share of the integrator's dissipation, ½ dᵀ K_e d.
//
// `settling` (the initial equilibrium, header): the blocks it marks are solved for static
// equilibrium (no inertia: K D = F_g - V σ + F_c, with a stiffness of settle_regularization times
// the inertia term tying them to where they are, so that a mode their contacts leave free is
// found as a large displacement instead of a singular matrix; `tie` scales it); the others keep
// their place.
// `residual`, when given: |A d - rhs| / |rhs| of the solved system (0 when rhs = 0).
void Dda3d::Impl::solve(const std::vector<Constraint>& list, Eigen::VectorXd& d, double& numerical,
                        const std::vector<char>* settling, double* residual, double tie) const {
  const auto n = static_cast<Eigen::Index>(unknowns);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  const Eigen::Vector3d g(params.gravity[0], params.gravity[1], params.gravity[2]);
  const auto scatter = [&](std::size_t row, std::size_t col, const Eigen::MatrixXd& m) {
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      for (Eigen::Index c = 0; c < m.cols(); ++c) {
        if (m(r, c) != 0.0) {
          triplets.emplace_back(static_cast<Eigen::Index>(row) + r, static_cast<Eigen::Index>(col) + c, m(r, c));
        }
      }
    }
  };
  std::vector<Eigen::MatrixXd> springs(blocks.size());  // K_e per block, for the dissipation
  std::vector<Eigen::MatrixXd> diagonal(blocks.size());  // each block's diagonal block of K
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Block& b = blocks[i];
    if (b.dof == 0) continue;
    Eigen::MatrixXd& k = diagonal[i];
    k = (2.0 / (h * h)) * b.mass_matrix;
    Eigen::VectorXd f = detail::gravity_load(b.mass, g).head(b.dof) + (2.0 / h) * b.mass_matrix * b.velocity;
    if (settling != nullptr) {
      if (!(*settling)[i]) continue;
      k *= tie * settle_regularization;
      f = detail::gravity_load(b.mass, g).head(b.dof);
    }
    springs[i] = Eigen::MatrixXd::Zero(b.dof, b.dof);
    if (b.dof == detail::dof3d) {
      springs[i] = detail::elastic_stiffness(b.elasticity, b.moments.volume);
      k += springs[i];
      f.tail<6>() -= b.moments.volume * b.stress;
    }
    rhs.segment(static_cast<Eigen::Index>(b.offset), b.dof) += f;
  }
  // The contacts' terms, per pair of blocks (the list's runs of one pair), computed on the
  // worker threads into their own slots and added in pair order: the matrix does not depend on
  // the number of threads.
  struct PairTerms {
    std::size_t a = 0, b = 0;
    Eigen::MatrixXd kii, kij, kjj;
    Eigen::VectorXd fi, fj;
  };
  std::vector<std::pair<std::size_t, std::size_t>> runs;  // [first, last) in the list
  for (std::size_t c = 0; c < list.size();) {
    std::size_t end = c + 1;
    while (end < list.size() && list[end].a == list[c].a && list[end].b == list[c].b) ++end;
    runs.emplace_back(c, end);
    c = end;
  }
  std::vector<PairTerms> terms(runs.size());
#pragma omp parallel for schedule(dynamic, 16) num_threads(thread_count)
  for (std::ptrdiff_t r = 0; r < static_cast<std::ptrdiff_t>(runs.size()); ++r) {
    const auto [first, last_one] = runs[static_cast<std::size_t>(r)];
    PairTerms& t = terms[static_cast<std::size_t>(r)];
    t.a = list[first].a;
    t.b = list[first].b;
    const int ni = blocks[t.a].dof, nj = blocks[t.b].dof;
    t.kii = Eigen::MatrixXd::Zero(ni, ni);
    t.kij = Eigen::MatrixXd::Zero(ni, nj);
    t.kjj = Eigen::MatrixXd::Zero(nj, nj);
    t.fi = Eigen::VectorXd::Zero(ni);
    t.fj = Eigen::VectorXd::Zero(nj);
    for (std::size_t c = first; c < last_one; ++c) {
      const Constraint& k = list[c];
      detail::add_contact_terms(k.kinematics, k.state, k.law, {t.kii, t.kij, t.kjj, t.fi, t.fj});
      if (settling == nullptr && k.dashpot_normal > 0.0) {
        detail::add_dashpots(k.kinematics, k.state, k.dashpot_normal / h, k.dashpot_tangential / h,
                             {t.kii, t.kij, t.kjj, t.fi, t.fj});
      }
    }
  }
  for (const PairTerms& t : terms) {
    const Block &ba = blocks[t.a], &bb = blocks[t.b];
    if (ba.dof > 0) {
      diagonal[t.a] += t.kii;
      rhs.segment(static_cast<Eigen::Index>(ba.offset), ba.dof) += t.fi;
    }
    if (bb.dof > 0) {
      diagonal[t.b] += t.kjj;
      rhs.segment(static_cast<Eigen::Index>(bb.offset), bb.dof) += t.fj;
    }
    if (ba.dof > 0 && bb.dof > 0) {
      scatter(ba.offset, bb.offset, t.kij);
      scatter(bb.offset, ba.offset, t.kij.transpose());
    }
  }
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (blocks[i].dof > 0) scatter(blocks[i].offset, blocks[i].offset, diagonal[i]);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  const auto started = std::chrono::steady_clock::now();
  bool solved = false;
  if (params.solver == Solver3d::ldlt) {
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
    if (ldlt.info() == Eigen::Success) d = ldlt.solve(rhs), solved = true;
  } else {
    // K is symmetric positive definite (the inertia term alone is): CG with Eigen's diagonal
    // preconditioner, started from the last solution, to a residual of 1e-12 of the load.
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg(a);
    cg.setTolerance(1e-12);
    cg.setMaxIterations(10 * n);
    const Eigen::VectorXd guess = d.size() == n && d.allFinite() ? d : Eigen::VectorXd::Zero(n);
    d = cg.solveWithGuess(rhs, guess);
    solved = cg.info() == Eigen::Success;
  }
  timing.solve += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (!solved) {
    d = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
    return;
  }
  if (residual != nullptr) {
    const double load = rhs.norm();
    *residual = load > 0.0 ? (a * d - rhs).norm() / load : 0.0;
  }
  numerical = 0.0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Block& b = blocks[i];
    if (b.dof == 0) continue;
    const auto di = d.segment(static_cast<Eigen::Index>(b.offset), b.dof);
    numerical += 0.5 * di.dot(springs[i] * di);
  }
}

// Steps 2-3: the open-close iteration on `list`; false when it does not converge (`unsettled`
// then names the contact it could not settle) or the solution is not finite.
bool Dda3d::Impl::attempt(std::vector<Constraint>& list, Eigen::VectorXd& d, std::size_t& iterations,
                          double& numerical, Unsettled& unsettled) const {
  // The increments of a block in d, a view (empty for a fixed block).
  const auto increments = [&](const Block& b) { return d.segment(static_cast<Eigen::Index>(b.offset), b.dof); };
  std::vector<std::size_t> changes(list.size(), 0);  // per contact: the iterations it changed in
  std::vector<char> changed_now(list.size(), 0);
  for (iterations = 1; iterations <= params.max_open_close; ++iterations) {
    solve(list, d, numerical);
    if (!d.allFinite()) return false;
    // Each constraint's decision is its own: evaluated on the worker threads; `changed` is an
    // or over them, the same whatever the order.
    bool changed = false;
#pragma omp parallel for schedule(static) reduction(|| : changed) num_threads(thread_count)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(list.size()); ++c) {
      Constraint& k = list[static_cast<std::size_t>(c)];
      const auto di = increments(blocks[k.a]);
      const auto dj = increments(blocks[k.b]);
      detail::ContactLaw3d judged = k.law;
      if (k.closing) judged.tensile_strength = 0.0;
      k.update = detail::evaluate_contact(k.kinematics, k.state, judged, di, dj);
      const bool was_closed = k.state.mode != detail::ContactMode::open;
      const bool is_closed = k.update.mode != detail::ContactMode::open;
      // §4.3: the iteration converges when no contact changes between open and closed and no
      // locked spring gave way: the solve held it with its full stiffness, which a sliding
      // contact does not have (a step accepted so would stop a frictionless block for every new
      // contact). A sliding contact that locks again is taken over for the next iteration
      // without forcing one: it held the friction force, which the locked spring starts from.
      bool this_changed = was_closed != is_closed || (k.state.mode == detail::ContactMode::locked &&
                                                      k.update.mode == detail::ContactMode::sliding);
      // §5.1: a contact that closes within the step (open at its start, or closed ahead by
      // Table 1) moves to where its features meet; the system is solved again with it there.
      if (is_closed && (!was_closed || k.closing) && !k.revised) this_changed = revise(k, di, dj) || this_changed;
      if (is_closed && !k.replaned) this_changed = replane(k, di, dj) || this_changed;
      changed_now[static_cast<std::size_t>(c)] = this_changed;
      changes[static_cast<std::size_t>(c)] += this_changed;
      changed = changed || this_changed;
      // The friction work of a sliding contact: its force times the slip, the tangential
      // relative displacement less what the spring took up elastically.
      k.slip_work = 0.0;
      if (was_closed && k.update.mode == detail::ContactMode::sliding) {
        const Eigen::Vector3d& n = k.kinematics.normal;
        const Eigen::Vector3d relative = detail::relative_motion(k.kinematics, di, dj);
        const Eigen::Vector3d stretch0 = k.state.shear - k.state.shear.dot(n) * n;
        const Eigen::Vector3d slip = relative - relative.dot(n) * n - (k.update.shear - stretch0);
        k.slip_work = k.update.tangential_force.norm() * slip.norm();
      }
    }
    if (!changed) {
      // The contacts' share of the integrator's dissipation (header): what the spring law
      // stores and the slip dissipates over the step, less the work of the end-of-step force
      // the scheme applies, -(U_1 - U_0) - W_slip - f_1 . Δr per constraint.
      for (const Constraint& k : list) {
        const Eigen::Vector3d relative = detail::relative_motion(k.kinematics, increments(blocks[k.a]), increments(blocks[k.b]));
        const bool closed = k.update.mode != detail::ContactMode::open;
        const Eigen::Vector3d end_force =
            closed ? Eigen::Vector3d(k.update.normal_force * k.kinematics.normal + k.update.tangential_force)
                   : Eigen::Vector3d::Zero();
        const double end_energy =
            detail::spring_energy(k.law, k.update.mode, k.state.offset, k.update.gap, k.update.shear);
        numerical += k.start_energy - end_energy - k.slip_work - end_force.dot(relative);
      }
      for (Constraint& k : list) {
        if (k.dashpot_normal == 0.0) continue;
        const Eigen::Vector3d relative = detail::relative_motion(k.kinematics, increments(blocks[k.a]), increments(blocks[k.b]));
        k.damping_work = detail::dashpot_work(k.kinematics, k.state, k.dashpot_normal / h, k.dashpot_tangential / h, relative);
      }
      return true;
    }
    for (Constraint& k : list) detail::next_iteration(k.state, k.update);
  }
  if (list.empty()) return false;  // nothing to name (with no contact nothing changes)
  const auto worst = std::max_element(changes.begin(), changes.end());
  unsettled.contact = &list[static_cast<std::size_t>(worst - changes.begin())];
  unsettled.changes = *worst;
  unsettled.changed_last = static_cast<std::size_t>(std::count(changed_now.begin(), changed_now.end(), 1));
  unsettled.contacts = list.size();
  return false;
}

// Seed 001 §5.1 on a constraint whose first solve closed it within the step: a vertex-face or
// edge-edge contact found apart at d0 >= 0 and penetrating at d1 < 0 gets the contact points where
// its features meet under a linear relative motion (contact_terms3d.hpp, eq. 41-46) and its
// tangential spring starts from -t P Δr (eq. 47), so that only the motion after the touch
// stretches it. True when the constraint changed (the points moved by more than
// revision_floor of the scene's size); tried once per step.
bool Dda3d::Impl::revise(Constraint& k, const Eigen::Ref<const Eigen::VectorXd>& di,
                         const Eigen::Ref<const Eigen::VectorXd>& dj) const {
  k.revised = true;
  const kernel::ContactConstraint& c = k.geometry;
  const Eigen::Vector3d& n = k.kinematics.normal;
  const Eigen::Vector3d relative = detail::relative_motion(k.kinematics, di, dj);
  std::optional<detail::RevisedContact3d> r;
  if (c.type == kernel::ConstraintType::vertex_face) {
    r = detail::revise_vertex_face(c.point_cp, c.point_tp, n, c.entering, relative);
  } else if (c.type == kernel::ConstraintType::edge_edge) {
    r = detail::revise_edge_edge(c.point_cp, c.point_tp, n, edge_direction(blocks[k.a], c.cp_feature),
                                 edge_direction(blocks[k.b], c.tp_feature), relative);
  }
  if (!r || r->shear.norm() <= revision_floor * size) return false;
  const Block &ba = blocks[k.a], &bb = blocks[k.b];
  k.geometry.point_cp = r->point_cp;
  k.geometry.point_tp = r->point_tp;
  k.kinematics = detail::contact_kinematics({r->point_cp, point(ba.moments.centroid), ba.dof},
                                            {r->point_tp, point(bb.moments.centroid), bb.dof}, c.normal,
                                            k.kinematics.area);
  k.state.shear = r->shear;
  return true;
}

// Seed 001 §4.3 (1) on a closed vertex-edge or vertex-vertex constraint with more than one
// candidate plane (the kernel's list, §4.2) and alone at its position: the shortest exit
// (§2.2.1) run again with the points where the solve moved them. The candidate whose plane the
// end points are least deep below, by more than replane_margin of the scene's size beyond the
// present one, becomes its plane: a vertex found just above a block's edge and driven down past
// it leaves by the side face, not by the top its gap at the start chose. Made at most once per
// step, so the iteration cannot swing between two planes; true when it changed the plane.
// (Where a pair has more than one constraint at a position, a concave edge or corner of a
// non-convex block, each holds its own part's plane, §2.2.2: moved onto a sibling's plane, one
// would count that plane twice and leave the other empty; a wedge released at touch gained
// energy so at its crest.)
bool Dda3d::Impl::replane(Constraint& k, const Eigen::Ref<const Eigen::VectorXd>& di,
                          const Eigen::Ref<const Eigen::VectorXd>& dj) const {
  const std::vector<kernel::CandidatePlane>& candidates = k.geometry.candidates;
  if (candidates.size() < 2 || k.shared) return false;
  const Eigen::Vector3d end =
      vec(k.geometry.point_tp) - vec(k.geometry.point_cp) + detail::relative_motion(k.kinematics, di, dj);
  double best = end.dot(k.kinematics.normal) + replane_margin * size;
  const kernel::CandidatePlane* chosen = nullptr;
  for (const kernel::CandidatePlane& c : candidates) {
    if (const double exit = end.dot(vec(c.normal)); exit > best) best = exit, chosen = &c;
  }
  if (chosen == nullptr) return false;
  k.replaned = true;
  kernel::ContactConstraint& g = k.geometry;
  const Eigen::Vector3d n = vec(chosen->normal);
  g.plane = chosen->source;
  set_plane(g, n);
  const Block &ba = blocks[k.a], &bb = blocks[k.b];
  k.kinematics = detail::contact_kinematics({g.point_cp, point(ba.moments.centroid), ba.dof},
                                            {g.point_tp, point(bb.moments.centroid), bb.dof}, g.normal,
                                            k.kinematics.area);
  k.normal_in_tp = bb.rotation.transpose() * n;
  k.state.shear -= k.state.shear.dot(n) * n;
  const Eigen::Vector3d slide = k.state.sliding_direction - k.state.sliding_direction.dot(n) * n;
  k.state.sliding_direction = slide.norm() > 0.0 ? Eigen::Vector3d(slide.normalized()) : Eigen::Vector3d::Zero();
  return true;
}

// The start of the blocks friction cannot hold where they rest (header, "Initial equilibrium").
// The locked solve `d` of settle_round leaves them on springs stretched past their Coulomb cap,
// and in a direction that is not that of the slide; released so, a wedge slid with too little
// friction for its first 30-100 ms (+8.8 % in 1 s on the family's slowest slide at kn = 10¹⁰).
// Here they start in their sliding state instead:
//  - the constraints locked past the cap slide: no tangential spring, the friction at the cap
//    as a load along the relative slip (seed 001 eq. 30-32);
//  - the solve's regularization (settle_regularization) ties a block only weakly to its place,
//    so a block that slides is found sliding by displacement c / tie along the mode its
//    contacts leave free, and the slip of each constraint in that solve gives its direction;
//  - the constraints still locked that pass their cap in that solve join, and the solve is
//    repeated with the new directions until none joins and no direction turns (a Coulomb
//    iteration: 3-5 solves on the wedges of the family; at most max_sliding_rounds, after
//    which the last round's state starts the blocks);
//  - a block at the margin, whose friction at the cap would exceed the load that drives it,
//    turns its slip back at every round: after two turns its contacts lock, their springs
//    holding the friction against the driving load, and the next solve relaxes them to the
//    friction it needs; those the relaxation takes past their cap slide (without this, the
//    family's factors of safety came out up to 0.93 % low at ten times the default kn: trials
//    at 99 % of the factor slid from a start on friction pushing the block down the slope);
//  - two solves with the tie doubled remove the free mode: D(1) = D_e + c and D(2) = D_e + c / 2
//    give D_e = 2 D(2) - D(1), the elastic part that sets the normal forces. Along the free mode
//    each block keeps its place of the locked solve (the slide's position is not the
//    equilibrium's to choose, and the blocks around it were checked there);
//  - the sliding constraints start at their cap along their slip.
// A block whose contacts hold it once some slide (its free displacement stays within the step
// limit) keeps the Coulomb-consistent static state D_e.
void Dda3d::Impl::sliding_start(std::vector<Constraint>& list, const std::vector<char>& settling,
                                Eigen::VectorXd& d) const {
  std::vector<char> sliding(list.size(), 0), held(list.size(), 0);
  std::vector<int> reversals(list.size(), 0);            // of the slip, in successive rounds
  std::vector<Eigen::Vector3d> last_slip(list.size());   // the slip of the last round
  std::vector<Eigen::Vector3d> last_friction(list.size());  // the friction that solve applied
  std::vector<Eigen::Vector3d> last_moved(list.size());  // and its tangential motion, of D_e
  std::vector<Constraint> trial = list;
  bool any = false;
  for (std::size_t c = 0; c < list.size(); ++c) {
    const Constraint& k = list[c];
    if (k.update.mode == detail::ContactMode::open ||
        !(k.law.kt * k.update.shear.norm() > detail::friction_limit(k.law, k.update.normal_force, k.kinematics.area))) {
      continue;
    }
    sliding[c] = 1;
    any = true;
    trial[c].state.mode = detail::ContactMode::sliding;
    trial[c].state.normal_force = k.update.normal_force;
    trial[c].state.sliding_direction = k.update.shear.normalized();
  }
  if (!any) return;
  const auto of = [&](const Eigen::VectorXd& x, std::size_t i) {
    const Block& b = blocks[i];
    return b.dof > 0 ? Eigen::VectorXd(x.segment(static_cast<Eigen::Index>(b.offset), b.dof)) : Eigen::VectorXd();
  };
  Eigen::VectorXd loose, tight, elastic;
  double unused = 0.0;
  for (int round = 0; round < max_sliding_rounds; ++round) {
    solve(trial, loose, unused, &settling, nullptr, 1.0);
    solve(trial, tight, unused, &settling, nullptr, 2.0);
    if (!loose.allFinite() || !tight.allFinite()) return;  // the locked start stands
    elastic = 2.0 * tight - loose;
    bool joined = false;
    double turned = 0.0;  // the largest change of a slip direction
    for (std::size_t c = 0; c < trial.size(); ++c) {
      Constraint& k = trial[c];
      if (k.state.mode == detail::ContactMode::open) continue;
      const Eigen::Vector3d& n = k.kinematics.normal;
      if (sliding[c] || held[c]) {
        const Eigen::Vector3d moved = detail::relative_motion(k.kinematics, of(elastic, k.a), of(elastic, k.b));
        const Eigen::Vector3d moved_along = moved - moved.dot(n) * n;
        const double normal = -k.law.kn * (k.kinematics.gap + n.dot(moved) - k.state.offset);
        if (held[c]) {
          // A held contact past its cap (the normal forces move as the others relax) slides,
          // its friction at the cap along the stretch it had: the others hold the block.
          const Eigen::Vector3d stretch = k.state.shear + moved_along;
          if (k.state.mode == detail::ContactMode::locked &&
              k.law.kt * stretch.norm() > detail::friction_limit(k.law, normal, k.kinematics.area) * (1.0 + friction_tolerance)) {
            k.state.mode = detail::ContactMode::sliding;
            k.state.sliding_direction = stretch.normalized();
            joined = true;
          }
          k.state.normal_force = normal;
          continue;
        }
        const Eigen::Vector3d slip = detail::relative_motion(k.kinematics, of(loose, k.a), of(loose, k.b));
        const Eigen::Vector3d along = slip - slip.dot(n) * n;
        // The friction this round's solve applied.
        const Eigen::Vector3d friction =
            detail::friction_limit(k.law, k.state.normal_force, k.kinematics.area) * k.state.sliding_direction;
        k.state.normal_force = normal;
        if (!(along.norm() > 0.0)) continue;
        reversals[c] = along.dot(k.state.sliding_direction) < 0.0 ? reversals[c] + 1 : 0;
        if (reversals[c] >= 2) {
          // Friction at the cap turns the slip back whichever way it is taken: the load that
          // drives the block is below the friction its contacts can carry, and it is held at
          // the margin. The two slips' sum is the driving load's (the friction's parts cancel).
          // Of the two rounds, the one whose friction resisted it was in equilibrium but along
          // the slide; the contact locks with its spring holding that friction at that round's
          // place, and the next solve relaxes the springs to the friction the block needs.
          const Eigen::Vector3d drive = (along + last_slip[c]).normalized();
          const bool now = drive.dot(k.state.sliding_direction) > 0.0;
          sliding[c] = 0;
          held[c] = 1;
          joined = true;  // the state changed: solve again
          k.state.mode = detail::ContactMode::locked;
          k.state.shear = (now ? friction : last_friction[c]) / k.law.kt - (now ? moved_along : last_moved[c]);
          continue;
        }
        last_slip[c] = along;
        last_friction[c] = friction;
        last_moved[c] = moved_along;
        turned = std::max(turned, (along.normalized() - k.state.sliding_direction).norm());
        k.state.sliding_direction = along.normalized();
        continue;
      }
      const detail::ContactUpdate3d u = detail::evaluate_contact(k.kinematics, k.state, k.law, of(loose, k.a), of(loose, k.b));
      if (u.mode != detail::ContactMode::sliding) continue;
      sliding[c] = 1;
      joined = true;
      k.state.mode = detail::ContactMode::sliding;
      k.state.normal_force = u.normal_force;
      k.state.sliding_direction = u.sliding_direction;
    }
    if (!joined && turned < sliding_turn_tolerance) break;
  }
  const double limit = params.max_displacement_ratio * size;
  Eigen::VectorXd start = elastic;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (!settling[i] || blocks[i].dof == 0) continue;
    const Eigen::VectorXd free = of(loose, i) - of(tight, i);  // c / 2
    if (!(2.0 * free.head(3).norm() > limit)) continue;       // held, some of its contacts sliding
    const Eigen::VectorXd back = of(d, i) - of(elastic, i);
    start.segment(static_cast<Eigen::Index>(blocks[i].offset), blocks[i].dof) += free * (free.dot(back) / free.squaredNorm());
  }
  // A mode the contacts leave almost free (a stiffness near the tie's) is not removed so, and
  // would move a block's vertex farther than the step limit or the locked solve: then the
  // locked start stands.
  if (!(largest_displacement(start) <= std::max(limit, largest_displacement(d)))) return;
  d = start;
  for (std::size_t c = 0; c < list.size(); ++c) {
    Constraint& k = list[c];
    const Eigen::VectorXd di = of(d, k.a), dj = of(d, k.b);
    if (trial[c].state.mode != detail::ContactMode::sliding) {
      if (held[c]) k.state.shear = trial[c].state.shear;
      k.update = detail::evaluate_contact(k.kinematics, k.state, k.law, di, dj);
      if (k.update.mode == detail::ContactMode::sliding) lock_whole_stretch(k, di, dj);
      continue;
    }
    const double normal = trial[c].state.normal_force;
    k.update = {};
    k.update.gap = k.kinematics.gap + k.kinematics.normal.dot(detail::relative_motion(k.kinematics, di, dj));
    if (!(normal > 0.0)) continue;  // the slide lifts it off: open
    k.update.mode = detail::ContactMode::sliding;
    k.update.normal_force = normal;
    k.update.sliding_direction = trial[c].state.sliding_direction;
    k.update.shear = (detail::friction_limit(k.law, normal, k.kinematics.area) / k.law.kt) * k.update.sliding_direction;
    k.update.tangential_force = -k.law.kt * k.update.shear;
  }
}

// The error's account of the contact an open-close iteration could not settle.
std::string Dda3d::Impl::describe(const Unsettled& u) const {
  const Constraint& k = *u.contact;
  const Point3& x = k.geometry.point_tp;
  const Eigen::Vector3d& n = k.kinematics.normal;
  return std::to_string(u.changed_last) + " of " + std::to_string(u.contacts) +
         " contacts still changed in the last; the one that changed most often (in " + iterations_text(u.changes) +
         ") is between " + block_name(blocks[k.a].spec.id) + " and " + block_name(blocks[k.b].spec.id) + ", at (" +
         number(x.x) + ", " + number(x.y) + ", " + number(x.z) + ") m on the latter, normal (" + number(n.x()) + ", " +
         number(n.y()) + ", " + number(n.z()) + "), gap " + number(k.kinematics.gap) +
         " m. A contact that opens and closes at every step size sits at a touch that carries almost no load: "
         "check the blocks' placement there (two faces meant to touch that overlap or stand apart by a rounding), "
         "or lower kn (" + number(k.law.kn) + " N/m) so the contact settles in the penetration it allows";
}

double Dda3d::Impl::largest_displacement(const Eigen::VectorXd& d) const {
  double largest = 0.0;
  for (const Block& b : blocks) {
    if (b.dof == 0) continue;
    const auto di = d.segment(static_cast<Eigen::Index>(b.offset), b.dof);
    const detail::StepMap map = detail::step_map(b.moments.centroid, di);
    for (const ConvexPolyhedron& part : b.parts) {
      for (const Point3& x : part.vertices()) largest = std::max(largest, (vec(detail::apply(map, x)) - vec(x)).norm());
    }
  }
  return largest;
}

// The largest rotation of a block over the step's increments d (radians, the rotation vector's
// length, which is the exact angle of the map the step applies) and that block's index.
std::pair<double, std::size_t> Dda3d::Impl::largest_rotation(const Eigen::VectorXd& d) const {
  std::pair<double, std::size_t> largest{0.0, 0};
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Block& b = blocks[i];
    if (b.dof == 0) continue;
    const double angle = d.segment<3>(static_cast<Eigen::Index>(b.offset) + 3).norm();
    if (angle > largest.first) largest = {angle, i};
  }
  return largest;
}

// Step 5: the blocks, their velocities, stresses and rotations, the contact list.
void Dda3d::Impl::accept(std::vector<Constraint> list, const Eigen::VectorXd& d, std::size_t iterations,
                         double numerical) {
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    Block& b = blocks[i];
    if (b.dof == 0) continue;
    const Eigen::VectorXd di = d.segment(static_cast<Eigen::Index>(b.offset), b.dof);
    b.velocity = 2.0 / h * di - b.velocity;
    if (params.static_analysis) b.velocity.setZero();
    move(i, di);
  }
  for (Constraint& k : list) {
    detail::commit_step(k.state, k.update);
    k.closing = false;
    friction_dissipated += k.slip_work;
    damping_dissipated += k.damping_work;
  }
  numerical_dissipated += numerical;
  constraints = std::move(list);
  time += h;
  ++steps;
  last.dt = h;
  last.open_close_iterations = iterations;
  last.constraints = constraints.size();
  last.closed = static_cast<std::size_t>(std::count_if(constraints.begin(), constraints.end(), [](const Constraint& k) {
    return k.state.mode != detail::ContactMode::open;
  }));
  last.detection_seconds = timing.detection;
  last.solve_seconds = timing.solve;
}

// The stability monitor (dda3d.hpp). The energy after an accepted step: Stability3dError when it
// has grown beyond all the run could draw on. (The list detected for the next step has no
// solution yet, so its springs' energy is not evaluated.)
void Dda3d::Impl::check_energy() {
  const Energies3d e = energies();
  largest_drop = std::max(largest_drop, std::abs(e.gravitational));
  double floor = 0.0;
  for (const Block& b : blocks) {
    if (b.dof > 0) floor += 0.5 * b.mass * energy_floor_speed * energy_floor_speed;
  }
  const double budget = 2.0 * (start_kinetic + start_strain + start_contact + largest_drop + floor);
  if (e.total() - start_total > budget) {
    throw Stability3dError("at t = " + number(time) + " s the energy has grown by " + number(e.total() - start_total) +
                           " J, more than twice all the run could draw on (" + number(budget / 2.0) +
                           " J): the step diverges; lower dt or the penalties");
  }
}

// The penetration at the start of a step, on the list detected for it: Stability3dError when a
// closed constraint penetrates more than half the smaller block's size.
void Dda3d::Impl::check_penetration() const {
  for (const Constraint& k : constraints) {
    if (k.state.mode == detail::ContactMode::open) continue;
    const double depth = -k.kinematics.gap;
    const double allowed = 0.5 * std::min(blocks[k.a].size, blocks[k.b].size);
    if (depth > allowed) {
      throw Stability3dError("at t = " + number(time) + " s " + block_name(blocks[k.a].spec.id) + " and " +
                             block_name(blocks[k.b].spec.id) + " interpenetrate by " + number(depth) +
                             " m, more than half the smaller block's size (" + number(allowed) +
                             " m): the contact no longer holds them apart; raise kn or lower dt");
    }
  }
}

// Moves block i by the increments `di` of a solve: its stress, rotation, parts and moments.
void Dda3d::Impl::move(std::size_t i, const Eigen::Ref<const Eigen::VectorXd>& di) {
  Block& b = blocks[i];
  if (b.dof == detail::dof3d) b.stress += b.elasticity * di.tail<6>();
  b.rotation = detail::accumulate_rotation(b.rotation, di.segment<3>(3));
  b.parts = detail::moved_parts(b.parts, detail::step_map(b.moments.centroid, di));
  b.moments = detail::central_moments3d(b.parts);
  b.refresh_mass_matrix();
  b.box = box_of(b.parts);
  refresh_state(i);
}

void Dda3d::Impl::refresh_state(std::size_t i) {
  const Block& b = blocks[i];
  Block3dState& s = states[i];
  s.id = b.spec.id;
  s.parts = b.parts;
  s.centroid = point(b.moments.centroid);
  const Eigen::Vector3d r = detail::rotation_vector(b.rotation);
  s.rotation = {r.x(), r.y(), r.z()};
  s.velocity.assign(b.velocity.data(), b.velocity.data() + b.velocity.size());
  for (int k = 0; k < 6; ++k) s.stress[static_cast<std::size_t>(k)] = b.stress[k];
  s.volume = b.moments.volume;
  s.mass = b.mass;
  s.fixed = b.spec.fixed;
  s.rigid = b.spec.rigid;
}

double auto_normal_penalty3d(std::span<const Block3dSpec> blocks) {
  if (blocks.empty()) throw std::invalid_argument("auto_normal_penalty3d: no blocks");
  const bool any_movable = std::any_of(blocks.begin(), blocks.end(), [](const Block3dSpec& b) { return !b.fixed; });
  double smallest = std::numeric_limits<double>::infinity();
  for (const Block3dSpec& b : blocks) {
    if (any_movable && b.fixed) continue;
    const double size = std::cbrt(detail::central_moments3d(b.parts).volume);
    smallest = std::min(smallest, b.material.youngs_modulus * size);
  }
  return auto_penalty_factor3d * smallest;
}

Dda3d::Dda3d(std::vector<Block3dSpec> blocks, ContactLaw3d law, Dda3dParams params)
    : impl_(std::make_shared<Impl>(std::move(blocks), std::move(law), params)) {}

void Dda3d::step() {
  Impl& s = *impl_;
  const double min_dt = s.params.dt * s.params.min_dt_ratio;
  if (s.steps > 0) {
    s.constraints = s.detect();
    s.check_penetration();
  }
  const double limit = s.params.max_displacement_ratio * s.size;
  const double turn_limit = s.params.max_rotation_deg / degrees_per_radian;
  for (;;) {
    std::vector<Constraint> list = s.constraints;
    Eigen::VectorXd d;
    std::size_t iterations = 0;
    double numerical = 0.0;
    Unsettled unsettled;
    const bool converged = s.attempt(list, d, iterations, numerical, unsettled);
    const double moved = converged ? s.largest_displacement(d) : 0.0;
    const auto [turned, turning] = converged ? s.largest_rotation(d) : std::pair<double, std::size_t>{0.0, 0};
    if (converged && moved <= limit && turned <= turn_limit) {
      s.accept(std::move(list), d, iterations, numerical);
      s.h = std::min(s.params.dt, step_growth * s.h);
      s.check_energy();
      return;
    }
    const double next = 0.5 * s.h;
    ++s.last.cuts;
    if (next < min_dt) {
      std::string why;
      if (!converged) {
        why = unsettled.contact ? "the open-close iteration does not converge in " +
                                      iterations_text(s.params.max_open_close) + ": " + s.describe(unsettled)
                                : std::string("the solution is not finite");
      } else if (moved > limit) {
        why = "a vertex moves " + number(moved) + " m in a step, more than max_displacement_ratio x size = " +
              number(limit) + " m";
      } else {
        why = block_name(s.blocks[turning].spec.id) + " turns by " + number(turned * degrees_per_radian) +
              " degrees in a step, more than max_rotation_deg = " + number(s.params.max_rotation_deg);
      }
      throw Stability3dError("at t = " + number(s.time) + " s the step would shrink to " + number(next) +
                             " s, below " + number(min_dt) + " s: " + why);
    }
    s.h = next;
  }
}

double Dda3d::time() const noexcept { return impl_->time; }
const Equilibrium& Dda3d::initial_equilibrium() const noexcept { return impl_->equilibrium; }
std::size_t Dda3d::steps() const noexcept { return impl_->steps; }
const std::vector<Block3dState>& Dda3d::blocks() const noexcept { return impl_->states; }
const Step3dStats& Dda3d::last_step() const noexcept { return impl_->last; }
kernel::PredicateCounters Dda3d::predicate_counters() const noexcept { return impl_->predicates; }

std::vector<Contact3dState> Dda3d::contacts() const {
  std::vector<Contact3dState> out;
  out.reserve(impl_->constraints.size());
  for (const Constraint& k : impl_->constraints) {
    Contact3dState c;
    c.block_a = k.a;
    c.block_b = k.b;
    c.point = k.geometry.point_tp;
    c.normal = k.geometry.normal;
    c.gap = k.update.gap;
    c.normal_force = k.update.normal_force;
    c.tangential_force = k.update.tangential_force.norm();
    c.mode = public_mode(k.state.mode);
    out.push_back(c);
  }
  return out;
}

Energies3d Dda3d::energies() const { return impl_->energies(); }

Energies3d Dda3d::Impl::energies() const {
  const Impl& s = *this;
  Energies3d e;
  const Eigen::Vector3d g(s.params.gravity[0], s.params.gravity[1], s.params.gravity[2]);
  for (const Block& b : s.blocks) {
    if (b.dof == 0) continue;
    e.kinetic += 0.5 * b.velocity.dot(b.mass_matrix * b.velocity);
    e.gravitational -= b.mass * g.dot(b.moments.centroid - b.reference_centroid);
    if (b.dof == detail::dof3d) {
      e.strain += 0.5 * b.moments.volume * b.stress.dot(b.elasticity.ldlt().solve(b.stress));
    }
  }
  for (const Constraint& k : s.constraints) {
    if (!k.closing) e.contact += detail::spring_energy(k.law, k.state.mode, k.state.offset, k.update.gap, k.state.shear);
  }
  e.friction_dissipated = s.friction_dissipated;
  e.damping_dissipated = s.damping_dissipated;
  e.numerical_dissipated = s.numerical_dissipated;
  return e;
}

}  // namespace rockcontact::dynamics
