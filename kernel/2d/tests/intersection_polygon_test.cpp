#define BOOST_TEST_MODULE kernel_intersection_polygon
#include "rockcontact/kernel/2d/intersection_polygon.hpp"

#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <vector>

#include <cmath>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

// The intersection polygon's labels must name existing edges under every policy, also when
// Float's rounded signs contradict each other. The pair below was found by the pair-kernel
// fuzzer (robustness_tests/fuzz): a CP sliver reaching 1.8e45 m, where Float's side tests of
// one node against two clip lines disagree and a crossing of two CP lines survived every clip;
// its label became IpVertex{crossing, cp, tp = -1}, read out of bounds by construct_points.

namespace rk = rockcontact::kernel;
using rk::ConvexPolygon;
using rk::IntersectionPolygon;
using rk::IpEdge;
using rk::IpVertex;

namespace {

const ConvexPolygon sliver_cp = ConvexPolygon::make(
    "cp", {{-57, -57}, {19, -88}, {105, -57}, {23, 1.8063603610809802e+45}, {-57, 23}});
const ConvexPolygon lattice_tp =
    ConvexPolygon::make("tp", {{-120, -120}, {105, -120}, {105, -57}, {23, 105}, {-57, 23}});

void check_labels(const IntersectionPolygon& ip) {
  const auto n = static_cast<std::int32_t>(sliver_cp.size());
  const auto m = static_cast<std::int32_t>(lattice_tp.size());
  BOOST_TEST((ip.vertices.empty() || ip.vertices.size() >= 3u));
  BOOST_TEST(ip.edges.size() == ip.vertices.size());
  for (const IpVertex& v : ip.vertices) {
    if (v.kind != IpVertex::Kind::tp_vertex) BOOST_TEST((v.cp >= 0 && v.cp < n));
    if (v.kind != IpVertex::Kind::cp_vertex) BOOST_TEST((v.tp >= 0 && v.tp < m));
  }
  for (const IpEdge& e : ip.edges) {
    BOOST_TEST((e.index >= 0 && e.index < (e.on == IpEdge::On::cp_edge ? n : m)));
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(float_contradictions_leave_well_formed_labels) {
  const IntersectionPolygon ip = rk::compute_intersection_polygon<rk::Float>(sliver_cp, lattice_tp);
  check_labels(ip);
  std::vector<rk::Point2> points;
  rk::construct_points<rk::Float>(sliver_cp, lattice_tp, ip, points);
  BOOST_TEST(points.size() == ip.vertices.size());
}

// The exact policies decide the same pair consistently: both give the same labels, all valid.
BOOST_AUTO_TEST_CASE(filtered_and_exact_agree_on_the_same_pair) {
  const IntersectionPolygon filtered =
      rk::compute_intersection_polygon<rk::Filtered>(sliver_cp, lattice_tp);
  const IntersectionPolygon exact = rk::compute_intersection_polygon<rk::Exact>(sliver_cp, lattice_tp);
  check_labels(exact);
  BOOST_TEST((filtered.vertices == exact.vertices));
  BOOST_TEST((filtered.edges == exact.edges));
  BOOST_TEST((rk::classify_overlap<rk::Exact>(sliver_cp, lattice_tp) == rk::Overlap::overlap));
  BOOST_TEST(exact.vertices.size() >= 3u);
}

// A crossing of nearly collinear edges whose two cross products both round to zero in double
// (the pair campaign's rotated edge_on_edge case, robustness_tests: rotated seed
// 104372539491857 index 12698): the parameter along the TP edge was 0 / 0, and the NaN passed
// the clamp into the IP point and the force. Every constructed point must be finite and, as
// the clamp promises, on its TP edge's bounding box.
BOOST_AUTO_TEST_CASE(crossings_of_edges_parallel_within_rounding_are_finite) {
  const ConvexPolygon cp = ConvexPolygon::make(
      "cp", {{-1.6921099825647343, 1.6827693565318407},
             {-1.6160887193340063, 0.99379916643229249},
             {-1.0978762235104063, 0.36298628086594953},
             {-0.34051933563739267, 1.2248404552113632},
             {-1.228912442731608, 1.8744616191248014}});
  const ConvexPolygon tp = ConvexPolygon::make(
      "tp", {{-0.66247864327865014, 0.52546194347025166},
             {-0.15118011366913919, 1.4403039987977166},
             {-1.192545834494533, 0.25525450907277281}});
  const IntersectionPolygon ip = rk::compute_intersection_polygon<rk::Filtered>(cp, tp);
  BOOST_TEST_REQUIRE(ip.vertices.size() >= 3u);
  std::vector<rk::Point2> points;
  rk::construct_points<rk::Filtered>(cp, tp, ip, points);
  for (std::size_t k = 0; k < points.size(); ++k) {
    BOOST_TEST_CONTEXT("IP vertex " << k) {
      BOOST_TEST(std::isfinite(points[k].x));
      BOOST_TEST(std::isfinite(points[k].y));
      if (ip.vertices[k].kind == IpVertex::Kind::crossing) {
        const rk::Point2& a = tp[ip.vertices[k].tp];
        const rk::Point2& b = tp[tp.next(ip.vertices[k].tp)];
        BOOST_TEST((points[k].x >= std::fmin(a.x, b.x) && points[k].x <= std::fmax(a.x, b.x)));
        BOOST_TEST((points[k].y >= std::fmin(a.y, b.y) && points[k].y <= std::fmax(a.y, b.y)));
      }
    }
  }
}
