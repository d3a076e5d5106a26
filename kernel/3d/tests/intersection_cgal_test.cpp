#define BOOST_TEST_MODULE kernel3d_intersection_cgal
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <boost/test/unit_test.hpp>

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "rockcontact/kernel/3d/detail/halfspace_exact.hpp"
#include "rockcontact/kernel/3d/intersection.hpp"
#include "rockcontact/kernel/3d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/testing/seed.hpp"

// The intersection volume against an independent reference: CGAL's corefinement of the two
// boundary meshes (Polygon_mesh_processing::corefine_and_compute_intersection on
// Surface_mesh<Epeck::Point_3>, exact constructions) and its volume (PMP::volume), on random
// pairs of tetrahedra and octahedra with unequal half-axes and arbitrary double coordinates,
// half of them moved by 2^20. CGAL's volume is exact: ours under Exact must equal it as a
// rational; Filtered's and Checked's rounded volumes within the contact3d README's tolerance
// (1e-9 relative, 1e-12 scale^3 absolute).

namespace rk = rockcontact::kernel;
using rk::ConvexPolyhedron;
using rk::Point3;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Epeck::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

Mesh mesh_of(const ConvexPolyhedron& p) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> v;
  for (const Point3& x : p.vertices()) v.push_back(mesh.add_vertex(Epeck::Point_3(x.x, x.y, x.z)));
  for (const auto& face : p.faces()) {
    for (std::size_t i = 1; i + 1 < face.size(); ++i) mesh.add_face(v[face[0]], v[face[i]], v[face[i + 1]]);
  }
  return mesh;
}

mpq_class cgal_volume(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  Mesh ma = mesh_of(a), mb = mesh_of(b), out;
  BOOST_TEST_REQUIRE(PMP::corefine_and_compute_intersection(ma, mb, out));
  if (out.number_of_faces() == 0) return 0;
  const auto exact = CGAL::exact(PMP::volume(out));
  static_assert(std::is_same_v<std::decay_t<decltype(exact)>, mpq_class>, "Epeck's exact FT is gmpxx's here");
  return exact;
}

ConvexPolyhedron make_tet(const std::string& name, std::vector<Point3> v) {
  if (rk::orient3d<rk::Exact>(v[0], v[1], v[2], v[3]) == rk::Sign::negative) std::swap(v[1], v[2]);
  return ConvexPolyhedron::make(name, std::move(v), {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
}

ConvexPolyhedron make_octahedron(const std::string& name, Point3 c, const std::array<double, 6>& r) {
  return ConvexPolyhedron::make(
      name,
      {{c.x + r[0], c.y, c.z}, {c.x - r[1], c.y, c.z}, {c.x, c.y + r[2], c.z}, {c.x, c.y - r[3], c.z},
       {c.x, c.y, c.z + r[4]}, {c.x, c.y, c.z - r[5]}},
      {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

}  // namespace

BOOST_AUTO_TEST_CASE(volume_against_cgal_corefinement) {
  std::mt19937_64 rng(rockcontact::testing::seed_for("volume_against_cgal_corefinement", 20261129));
  std::uniform_real_distribution<double> u(-1.0, 1.0), radius(0.2, 1.0);
  int overlapping = 0;
  for (int i = 0; i < 60; ++i) {
    const Point3 o = i % 2 == 0 ? Point3{0x1p20, -0x1p20, 0x1p20} : Point3{};
    const auto point = [&] { return Point3{o.x + u(rng), o.y + u(rng), o.z + u(rng)}; };
    const auto random_polyhedron = [&](const std::string& name) {
      if (rng() % 2 == 0) {
        std::array<double, 6> r;
        for (double& x : r) x = radius(rng);
        return make_octahedron(name, {o.x + 0.5 * u(rng), o.y + 0.5 * u(rng), o.z + 0.5 * u(rng)}, r);
      }
      for (;;) {
        std::vector<Point3> v{point(), point(), point(), point()};
        if (rk::orient3d<rk::Exact>(v[0], v[1], v[2], v[3]) != rk::Sign::zero) return make_tet(name, v);
      }
    };
    const ConvexPolyhedron a = random_polyhedron("a"), b = random_polyhedron("b");
    BOOST_TEST_INFO("pair " << i);
    const mpq_class reference = cgal_volume(a, b);
    BOOST_TEST(mpq_class(rk::detail::exact_volume_string(rk::intersection<rk::Exact>(a, b))) == reference);
    const double expected = reference.get_d();
    const double tolerance = std::max(1e-9 * std::fabs(expected), 1e-12 * 8.0);  // scale <= 2 here
    BOOST_TEST(std::fabs(rk::intersection_volume<rk::Filtered>(a, b) - expected) <= tolerance);
    BOOST_TEST(std::fabs(rk::intersection_volume<rk::Checked>(b, a) - expected) <= tolerance);
    overlapping += reference > 0;
  }
  BOOST_TEST(overlapping >= 20);
  BOOST_TEST_MESSAGE("CGAL corefinement: " << overlapping << " of 60 pairs overlap");
}
