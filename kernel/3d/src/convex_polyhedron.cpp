#include "rockcontact/kernel/3d/convex_polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "rockcontact/kernel/3d/predicates.hpp"

namespace rockcontact::kernel {

InvalidPolyhedron::InvalidPolyhedron(std::string block, std::ptrdiff_t face, std::ptrdiff_t vertex,
                                     Reason reason, const std::string& what)
    : std::invalid_argument(what), block_(std::move(block)), face_(face), vertex_(vertex), reason_(reason) {}

namespace {

using Reason = InvalidPolyhedron::Reason;

class Validator {
 public:
  Validator(const std::string& name, const std::vector<Point3>& v, const std::vector<ConvexPolyhedron::Face>& f)
      : name_(name), v_(v), f_(f) {}

  [[noreturn]] void fail(std::ptrdiff_t face, std::ptrdiff_t vertex, Reason reason, const std::string& what) const {
    std::string where = "polyhedron '" + name_ + "'";
    if (face >= 0) where += ", face " + std::to_string(face);
    if (vertex >= 0) where += ", vertex " + std::to_string(vertex);
    throw InvalidPolyhedron(name_, face, vertex, reason, where + ": " + what);
  }

  void vertices() const {
    if (v_.size() < 4) fail(-1, -1, Reason::too_few_vertices, "needs at least 4 vertices, got " + std::to_string(v_.size()));
    for (std::size_t i = 0; i < v_.size(); ++i) {
      const Point3& p = v_[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        fail(-1, static_cast<std::ptrdiff_t>(i), Reason::non_finite, "coordinates must be finite numbers");
      }
    }
    std::vector<std::size_t> order(v_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const auto key = [&](std::size_t i) { return std::tuple(v_[i].x, v_[i].y, v_[i].z); };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
    for (std::size_t k = 1; k < order.size(); ++k) {
      if (v_[order[k]] == v_[order[k - 1]]) {
        const auto [first, second] = std::minmax(order[k - 1], order[k]);
        fail(-1, static_cast<std::ptrdiff_t>(second), Reason::repeated_vertex,
             "repeats vertex " + std::to_string(first) + "; vertices must be distinct");
      }
    }
  }

  // Faces are index loops; every directed edge is matched by its reverse exactly once.
  std::vector<ConvexPolyhedron::Edge> topology() const {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> directed;  // edge -> its face
    std::vector<bool> used(v_.size(), false);
    for (std::size_t fi = 0; fi < f_.size(); ++fi) {
      const auto& face = f_[fi];
      const auto face_id = static_cast<std::ptrdiff_t>(fi);
      if (face.size() < 3) fail(face_id, -1, Reason::bad_face, "a face needs at least 3 vertices");
      for (std::size_t k = 0; k < face.size(); ++k) {
        if (face[k] >= v_.size()) {
          fail(face_id, -1, Reason::bad_face, "vertex index " + std::to_string(face[k]) + " is out of range");
        }
        if (std::count(face.begin(), face.end(), face[k]) > 1) {
          fail(face_id, face[k], Reason::bad_face, "the face lists the vertex twice");
        }
        used[face[k]] = true;
        const auto edge = std::pair(face[k], face[(k + 1) % face.size()]);
        if (!directed.emplace(edge, fi).second) {
          fail(face_id, edge.first, Reason::not_closed,
               "edge " + std::to_string(edge.first) + " -> " + std::to_string(edge.second) +
                   " is traversed in the same direction by face " + std::to_string(directed.at(edge)) +
                   " (faces must be counter-clockwise seen from outside, each edge shared by two faces)");
        }
      }
    }
    for (std::size_t i = 0; i < used.size(); ++i) {
      if (!used[i]) fail(-1, static_cast<std::ptrdiff_t>(i), Reason::unused_vertex, "is on no face");
    }
    std::vector<ConvexPolyhedron::Edge> edges;
    for (const auto& [edge, face] : directed) {
      if (!directed.contains({edge.second, edge.first})) {
        fail(static_cast<std::ptrdiff_t>(face), edge.first, Reason::not_closed,
             "edge " + std::to_string(edge.first) + " -> " + std::to_string(edge.second) +
                 " has no neighbouring face traversing it back: the faces do not close the solid");
      }
      if (edge.first < edge.second) edges.push_back(edge);
    }
    return edges;
  }

  // Planarity, strict convexity and outward orientation, each decided exactly.
  void geometry() const {
    for (std::size_t fi = 0; fi < f_.size(); ++fi) {
      const auto& face = f_[fi];
      const auto face_id = static_cast<std::ptrdiff_t>(fi);
      const Point3 &a = v_[face[0]], &b = v_[face[1]], &c = v_[face[2]];
      if (parallel<Filtered>(a, b, a, c)) {
        fail(face_id, face[1], Reason::not_convex,
             "the face goes straight on at this vertex: faces must be strictly convex");
      }
      // A vertex off the face's plane, to orient every corner of the face against.
      std::ptrdiff_t below = -1;
      for (std::size_t i = 0; i < v_.size(); ++i) {
        const bool on_face = std::find(face.begin(), face.end(), i) != face.end();
        const Sign s = orient3d<Filtered>(a, b, c, v_[i]);
        if (on_face) {
          if (s != Sign::zero && i != face[0] && i != face[1] && i != face[2]) {
            fail(face_id, static_cast<std::ptrdiff_t>(i), Reason::not_planar,
                 "is off the plane of the face's first three vertices; a face must be exactly "
                 "planar (give a face that is planar only to rounding as triangles)");
          }
        } else if (s != Sign::negative) {
          fail(face_id, static_cast<std::ptrdiff_t>(i),
               Reason::not_convex,
               s == Sign::zero ? "lies on the face's plane but not on the face: merge coplanar faces"
                               : "lies above the face's plane: the solid is not convex, or the face is "
                                 "clockwise seen from outside");
        } else if (below < 0) {
          below = static_cast<std::ptrdiff_t>(i);
        }
      }
      if (below < 0) fail(face_id, -1, Reason::not_convex, "every vertex lies on the face's plane: zero volume");
      for (std::size_t k = 0; k < face.size(); ++k) {
        const std::uint32_t p = face[k], q = face[(k + 1) % face.size()], r = face[(k + 2) % face.size()];
        if (orient3d<Filtered>(v_[p], v_[q], v_[r], v_[static_cast<std::size_t>(below)]) != Sign::negative) {
          fail(face_id, q, Reason::not_convex,
               "the face turns the wrong way or goes straight on at this vertex: faces must be "
               "strictly convex and counter-clockwise seen from outside");
        }
      }
    }
  }

 private:
  const std::string& name_;
  const std::vector<Point3>& v_;
  const std::vector<ConvexPolyhedron::Face>& f_;
};

}  // namespace

ConvexPolyhedron ConvexPolyhedron::make(std::string name, std::vector<Point3> vertices,
                                        std::vector<Face> faces) {
  const Validator check(name, vertices, faces);
  check.vertices();
  std::vector<Edge> edges = check.topology();
  check.geometry();
  ConvexPolyhedron out;
  out.name_ = std::move(name);
  out.vertices_ = std::move(vertices);
  out.faces_ = std::move(faces);
  out.edges_ = std::move(edges);
  return out;
}

}  // namespace rockcontact::kernel
