#include "rockcontact/kernel/3d/convex_polyhedron.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
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

  // Faces are index loops; every directed edge is matched by its reverse exactly once. Returns
  // the edges. `faces` are the input faces or the facets; `face_id` names a face for errors.
  template <class FaceId>
  std::vector<ConvexPolyhedron::Edge> topology(const std::vector<ConvexPolyhedron::Face>& faces,
                                               FaceId face_id) const {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> directed;  // edge -> its face
    std::vector<bool> used(v_.size(), false);
    for (std::size_t fi = 0; fi < faces.size(); ++fi) {
      const auto& face = faces[fi];
      if (face.size() < 3) fail(face_id(fi), -1, Reason::bad_face, "a face needs at least 3 vertices");
      for (std::size_t k = 0; k < face.size(); ++k) {
        if (face[k] >= v_.size()) {
          fail(face_id(fi), -1, Reason::bad_face, "vertex index " + std::to_string(face[k]) + " is out of range");
        }
        if (std::count(face.begin(), face.end(), face[k]) > 1) {
          fail(face_id(fi), face[k], Reason::bad_face, "the face lists the vertex twice");
        }
        used[face[k]] = true;
        const auto edge = std::pair(face[k], face[(k + 1) % face.size()]);
        if (!directed.emplace(edge, fi).second) {
          fail(face_id(fi), edge.first, Reason::not_closed,
               "edge " + std::to_string(edge.first) + " -> " + std::to_string(edge.second) +
                   " is traversed in the same direction by face " + std::to_string(face_id(directed.at(edge))) +
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
        fail(face_id(face), edge.first, Reason::not_closed,
             "edge " + std::to_string(edge.first) + " -> " + std::to_string(edge.second) +
                 " has no neighbouring face traversing it back: the faces do not close the solid");
      }
      if (edge.first < edge.second) edges.push_back(edge);
    }
    return edges;
  }

  // The facets of every face (convex_polyhedron.hpp), each with the index of its face.
  std::pair<std::vector<ConvexPolyhedron::Face>, std::vector<std::size_t>> facets() const {
    const double size = block_size();
    std::vector<ConvexPolyhedron::Face> facets;
    std::vector<std::size_t> input_face;
    for (std::size_t fi = 0; fi < f_.size(); ++fi) {
      const auto& face = f_[fi];
      const Point3 &a = v_[face[0]], &b = v_[face[1]], &c = v_[face[2]];
      // A face whose first three vertices are in a straight line is left whole for geometry()
      // to refuse.
      const bool planar = parallel<Filtered>(a, b, a, c) ||
                          std::all_of(face.begin() + 3, face.end(), [&](std::uint32_t i) {
                            return orient3d<Filtered>(a, b, c, v_[i]) == Sign::zero;
                          });
      if (planar) {
        facets.push_back(face);
        input_face.push_back(fi);
        continue;
      }
      check_nearly_planar(fi, size);
      for (auto& facet : outward_hull(face)) {
        facets.push_back(std::move(facet));
        input_face.push_back(fi);
      }
    }
    return {std::move(facets), std::move(input_face)};
  }

  // Planarity, strict convexity and outward orientation of the facets, each decided exactly.
  // `face_id` names a facet's face as given.
  template <class FaceId>
  void geometry(const std::vector<ConvexPolyhedron::Face>& facets, FaceId face_id) const {
    for (std::size_t fi = 0; fi < facets.size(); ++fi) {
      const auto& face = facets[fi];
      const std::ptrdiff_t id = face_id(fi);
      const Point3 &a = v_[face[0]], &b = v_[face[1]], &c = v_[face[2]];
      if (parallel<Filtered>(a, b, a, c)) {
        fail(id, face[1], Reason::not_convex, "the face goes straight on at this vertex: faces must be strictly convex");
      }
      // A vertex off the facet's plane, to orient every corner of the facet against.
      std::ptrdiff_t below = -1;
      for (std::size_t i = 0; i < v_.size(); ++i) {
        // Facets are exactly planar (facets()), so only the other vertices need a test.
        if (std::find(face.begin(), face.end(), i) != face.end()) continue;
        const Sign s = orient3d<Filtered>(a, b, c, v_[i]);
        if (s != Sign::negative) {
          fail(id, static_cast<std::ptrdiff_t>(i), Reason::not_convex,
               s == Sign::zero ? "lies on the face's plane but not on the face: merge coplanar faces"
                               : "lies above the face's plane: the solid is not convex, or the face is "
                                 "clockwise seen from outside");
        } else if (below < 0) {
          below = static_cast<std::ptrdiff_t>(i);
        }
      }
      if (below < 0) fail(id, -1, Reason::not_convex, "every vertex lies on the face's plane: zero volume");
      for (std::size_t k = 0; k < face.size(); ++k) {
        const std::uint32_t p = face[k], q = face[(k + 1) % face.size()], r = face[(k + 2) % face.size()];
        if (orient3d<Filtered>(v_[p], v_[q], v_[r], v_[static_cast<std::size_t>(below)]) != Sign::negative) {
          fail(id, q, Reason::not_convex,
               "the face turns the wrong way or goes straight on at this vertex: faces must be "
               "strictly convex and counter-clockwise seen from outside");
        }
      }
    }
  }

  // The largest extent of the bounding box: the length face_planarity_tolerance scales.
  double block_size() const {
    Point3 lo = v_[0], hi = v_[0];
    for (const Point3& p : v_) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    return std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  }

  // Refuses a face bent beyond the tolerance, naming its farthest vertex. The mean plane goes
  // through the vertices' mean with Newell's normal (the face's vector area), both taken relative
  // to the first vertex so a block far from the origin loses no digits; a measurement, not a
  // decision, so double suffices.
  void check_nearly_planar(std::size_t fi, double size) const {
    const auto& face = f_[fi];
    const Point3& o = v_[face[0]];
    const auto local = [&](std::uint32_t i) { return Point3{v_[i].x - o.x, v_[i].y - o.y, v_[i].z - o.z}; };
    Point3 n, mean;
    for (std::size_t k = 0; k < face.size(); ++k) {
      const Point3 p = local(face[k]), q = local(face[(k + 1) % face.size()]);
      n = {n.x + (p.y - q.y) * (p.z + q.z), n.y + (p.z - q.z) * (p.x + q.x), n.z + (p.x - q.x) * (p.y + q.y)};
      mean = {mean.x + p.x, mean.y + p.y, mean.z + p.z};
    }
    const double k = static_cast<double>(face.size()), length = std::hypot(n.x, n.y, n.z);
    mean = {mean.x / k, mean.y / k, mean.z / k};
    std::size_t worst = face[0];
    double worst_distance = 0.0;
    for (const std::uint32_t i : face) {
      const Point3 p = local(i);
      const double d = std::fabs((p.x - mean.x) * n.x + (p.y - mean.y) * n.y + (p.z - mean.z) * n.z) / length;
      if (!(d <= worst_distance)) {
        worst = i;
        worst_distance = d;
      }
    }
    if (!(worst_distance <= face_planarity_tolerance * size)) {
      std::ostringstream what;
      what << "is " << worst_distance << " m off the face's mean plane; a face must be planar to within "
           << face_planarity_tolerance << " of the block's size (" << face_planarity_tolerance * size << " m)";
      fail(static_cast<std::ptrdiff_t>(fi), static_cast<std::ptrdiff_t>(worst), Reason::not_planar, what.str());
    }
  }

  // The facets of the exact hull that a nearly planar face covers: the triples of its vertices,
  // taken in the face's (counter-clockwise) order, with no vertex of the face above their plane,
  // each merged with the face's vertices on that plane. The face's vertices are in convex position
  // seen along its normal, so these triples are the faces of the hull of its vertices that look
  // outward, and they tile the face; make() then validates them as faces (manifold, convex, the
  // rest of the block below), so a face whose split does not tile it is refused there.
  // O(k^4) predicates for a face of k vertices; faces from rotation or cutting have few.
  std::vector<ConvexPolyhedron::Face> outward_hull(const ConvexPolyhedron::Face& face) const {
    std::vector<ConvexPolyhedron::Face> out;
    const std::size_t k = face.size();
    for (std::size_t i = 0; i < k; ++i) {
      for (std::size_t j = i + 1; j < k; ++j) {
        for (std::size_t l = j + 1; l < k; ++l) {
          const Point3 &a = v_[face[i]], &b = v_[face[j]], &c = v_[face[l]];
          if (parallel<Filtered>(a, b, a, c)) continue;
          ConvexPolyhedron::Face facet;
          bool outward = true;
          for (std::size_t m = 0; m < k && outward; ++m) {
            const Sign s = m == i || m == j || m == l ? Sign::zero : orient3d<Filtered>(a, b, c, v_[face[m]]);
            outward = s != Sign::positive;
            if (s == Sign::zero) facet.push_back(face[m]);
          }
          if (outward && std::find(out.begin(), out.end(), facet) == out.end()) out.push_back(std::move(facet));
        }
      }
    }
    return out;
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
  const auto as_given = [](std::size_t face) { return static_cast<std::ptrdiff_t>(face); };
  static_cast<void>(check.topology(faces, as_given));
  auto split = check.facets();
  std::vector<Face>& facets = split.first;
  std::vector<std::size_t>& input_face = split.second;
  const auto facet_face = [&input_face](std::size_t facet) { return static_cast<std::ptrdiff_t>(input_face[facet]); };
  std::vector<Edge> edges = check.topology(facets, facet_face);
  check.geometry(facets, facet_face);
  ConvexPolyhedron out;
  out.name_ = std::move(name);
  out.vertices_ = std::move(vertices);
  out.input_faces_ = std::move(faces);
  out.facets_ = std::move(facets);
  out.input_face_ = std::move(input_face);
  out.edges_ = std::move(edges);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> facet_of;  // directed edge -> facet
  for (std::size_t f = 0; f < out.facets_.size(); ++f) {
    const Face& loop = out.facets_[f];
    for (std::size_t k = 0; k < loop.size(); ++k) facet_of[{loop[k], loop[(k + 1) % loop.size()]}] = static_cast<std::uint32_t>(f);
  }
  for (const auto& [p, q] : out.edges_) out.edge_faces_.push_back({facet_of.at({p, q}), facet_of.at({q, p})});
  return out;
}

ConvexPolyhedron ConvexPolyhedron::moved(std::vector<Point3> vertices) const {
  return make(name_, std::move(vertices), input_faces_);
}

}  // namespace rockcontact::kernel
