#define BOOST_TEST_MODULE kernel_intersection_polygon
#include "rockcontact/kernel/2d/intersection_polygon.hpp"

#include <boost/test/unit_test.hpp>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/generators/pair_generators.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/2d/predicates.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/testing/contact2d.hpp"
#include "rockcontact/testing/counting_new.hpp"
#include "rockcontact/testing/seed.hpp"

// The intersection polygon and the verdict of its clip (intersection_polygon.hpp):
//   (a) well-formed labels under every policy, also when Float's signs contradict each other
//       (a fuzzer-found sliver), and finite crossings of edges parallel within rounding;
//   (b) the clip's verdict equals classify_overlap, on named degenerate cases, on every
//       generator family and on the independent contact2d reference data;
//   (c) the labels equal those of a plain reference clip written below;
//   (d) no allocation for polygons of up to ClipWorkspace::inline_vertices vertices.
// Verdicts and labels are combinatorial: both sides of each comparison are decided by exact
// predicates (Filtered and Exact), so they must be equal, with no tolerance.

// The allocation counter for (d): rockcontact/testing/counting_new.hpp.
using rockcontact::testing::heap_allocations;

namespace rk = rockcontact::kernel;
using rk::ConvexPolygon;
using rk::IntersectionPolygon;
using rk::IpEdge;
using rk::IpVertex;

namespace {

// (a) The intersection polygon's labels must name existing edges under every policy, also when
// Float's rounded signs contradict each other. The pair below was found by the pair-kernel
// fuzzer (robustness_tests/fuzz): a CP sliver reaching 1.8e45 m, where Float's side tests of
// one node against two clip lines disagree and a crossing of two CP lines survived every clip;
// its label became IpVertex{crossing, cp, tp = -1}, read out of bounds by construct_points.
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

namespace {

using rk::Overlap;
using rockcontact::testing::seed_for;

// A straightforward reference for the labels: Sutherland-Hodgman over std::vector with every
// side recomputed by the policy's orientation (input vertices) or crossing_side (crossings) at
// every clip, no memo and no shortcut, stopping once fewer than 3 nodes remain. A node is an
// input vertex (`vertex` >= 0: CP's 0..n-1, TP's n..n+m-1) or the crossing of lines a and b
// (CP's lines 0..n-1, TP's n..n+m-1); `edge` is the line of the edge leaving it.
struct ReferenceNode {
  int vertex = -1;
  int a = -1, b = -1;
  int edge = -1;
};

template <rk::NumberPolicy Policy>
IntersectionPolygon reference_clip(const ConvexPolygon& cp, const ConvexPolygon& tp) {
  const int n = static_cast<int>(cp.size()), m = static_cast<int>(tp.size());
  const auto line = [&](int id) {
    return id < n ? rk::Line{cp[id], cp[cp.next(id)]} : rk::Line{tp[id - n], tp[tp.next(id - n)]};
  };
  const auto side = [&](const ReferenceNode& node, int k) {
    const rk::Line clip = line(k);
    if (node.vertex >= 0) {
      return rk::orientation<Policy>(clip.p, clip.q, node.vertex < n ? cp[node.vertex] : tp[node.vertex - n]);
    }
    if (node.a == k || node.b == k) return rk::Sign::zero;
    return rk::crossing_side<Policy>(line(node.a), line(node.b), clip);
  };
  std::vector<ReferenceNode> polygon;
  for (int j = 0; j < m; ++j) polygon.push_back({n + j, -1, -1, n + j});
  for (int k = 0; k < n && polygon.size() >= 3; ++k) {
    std::vector<int> sides;
    for (const ReferenceNode& node : polygon) sides.push_back(static_cast<int>(side(node, k)));
    std::vector<ReferenceNode> next;
    std::vector<bool> on_k;
    for (std::size_t v = 0; v < polygon.size(); ++v) {
      const std::size_t w = (v + 1) % polygon.size();
      if (sides[v] >= 0) {
        next.push_back(polygon[v]);
        on_k.push_back(sides[v] == 0);
      }
      if (sides[v] * sides[w] < 0) {
        // Adjacent CP lines meet at their shared CP vertex.
        const int e = polygon[v].edge;
        ReferenceNode crossing{-1, k, e, e};
        if (e == (k + n - 1) % n) crossing = {k, -1, -1, e};
        if (e == (k + 1) % n) crossing = {(k + 1) % n, -1, -1, e};
        next.push_back(crossing);
        on_k.push_back(true);
      }
    }
    for (std::size_t v = 0; v < next.size(); ++v) {
      if (on_k[v] && on_k[(v + 1) % next.size()]) next[v].edge = k;
    }
    polygon = next;
  }
  IntersectionPolygon ip;
  if (polygon.size() < 3) return ip;
  for (const ReferenceNode& node : polygon) {
    if (node.vertex >= 0) {
      ip.vertices.push_back(node.vertex < n ? IpVertex{IpVertex::Kind::cp_vertex, node.vertex, -1}
                                            : IpVertex{IpVertex::Kind::tp_vertex, -1, node.vertex - n});
    } else {
      ip.vertices.push_back({IpVertex::Kind::crossing, node.a, node.b - n});
    }
    ip.edges.push_back(node.edge < n ? IpEdge{IpEdge::On::cp_edge, node.edge}
                                     : IpEdge{IpEdge::On::tp_edge, node.edge - n});
  }
  return ip;
}

struct Pair {
  std::string name;
  ConvexPolygon cp, tp;
};

// The generator pools: `per_family` pairs of every family, from one printed seed.
const std::vector<Pair>& generated_pairs() {
  constexpr std::uint64_t per_family = 200;
  static const std::vector<Pair> pairs = [] {
    const std::uint64_t seed = seed_for("intersection_polygon generated pairs", 20261125);
    std::vector<Pair> out;
    for (const rockcontact::robustness::Family family : rockcontact::robustness::all_families) {
      for (std::uint64_t index = 0; index < per_family; ++index) {
        const rockcontact::robustness::PolygonPair pair = rockcontact::robustness::generate_pair(family, seed, index);
        out.push_back({pair.recipe, ConvexPolygon::make("cp", pair.cp), ConvexPolygon::make("tp", pair.tp)});
      }
    }
    return out;
  }();
  return pairs;
}

// The contact2d reference pairs (robustness_tests/data/contact2d) with their exact status.
struct ReferencePair {
  Pair pair;
  std::string status;
};

const std::vector<ReferencePair>& contact2d_pairs() {
  static const std::vector<ReferencePair> pairs = [] {
    std::vector<ReferencePair> out;
    for (const auto& raw : rockcontact::testing::contact2d_data().pairs) {
      out.push_back({{raw.id, ConvexPolygon::make(raw.id + ".cp", raw.cp), ConvexPolygon::make(raw.id + ".tp", raw.tp)},
                     raw.expected.at("status").get<std::string>()});
    }
    return out;
  }();
  return pairs;
}

template <rk::NumberPolicy Policy>
Overlap clip_verdict(const ConvexPolygon& cp, const ConvexPolygon& tp) {
  IntersectionPolygon ip;
  rk::ClipWorkspace workspace;
  return rk::compute_intersection_polygon<Policy>(cp, tp, ip, workspace);
}

// The clip's verdict under Filtered and Exact against classify_overlap under both, for the
// pair and for the pair swapped (CP and TP change roles, the clip another polygon). Counts the
// verdicts seen so that a pool that lost its touching pairs is noticed.
struct VerdictTally {
  std::size_t separate = 0, touch = 0, overlap = 0;
};

void check_verdict(const Pair& pair, VerdictTally& tally) {
  for (const auto& [cp, tp] : {std::pair{&pair.cp, &pair.tp}, std::pair{&pair.tp, &pair.cp}}) {
    const Overlap exact = rk::classify_overlap<rk::Exact>(*cp, *tp);
    const Overlap filtered = rk::classify_overlap<rk::Filtered>(*cp, *tp);
    BOOST_TEST_INFO(pair.name << (cp == &pair.cp ? "" : " (swapped)"));
    BOOST_TEST((filtered == exact));
    BOOST_TEST_INFO(pair.name << (cp == &pair.cp ? "" : " (swapped)"));
    BOOST_TEST(rk::to_string(clip_verdict<rk::Exact>(*cp, *tp)) == rk::to_string(exact));
    BOOST_TEST_INFO(pair.name << (cp == &pair.cp ? "" : " (swapped)"));
    BOOST_TEST(rk::to_string(clip_verdict<rk::Filtered>(*cp, *tp)) == rk::to_string(exact));
    if (cp == &pair.cp) {
      tally.separate += exact == Overlap::separate;
      tally.touch += exact == Overlap::touch;
      tally.overlap += exact == Overlap::overlap;
    }
  }
}

// The labels under Filtered and Exact against the reference clip under Exact: the same
// vertices and edges, in the same order from the same first vertex.
void check_labels_against_reference(const Pair& pair) {
  const IntersectionPolygon reference = reference_clip<rk::Exact>(pair.cp, pair.tp);
  const IntersectionPolygon exact = rk::compute_intersection_polygon<rk::Exact>(pair.cp, pair.tp);
  const IntersectionPolygon filtered = rk::compute_intersection_polygon<rk::Filtered>(pair.cp, pair.tp);
  BOOST_TEST_INFO(pair.name);
  BOOST_TEST((exact.vertices == reference.vertices && exact.edges == reference.edges));
  BOOST_TEST_INFO(pair.name);
  BOOST_TEST((filtered.vertices == reference.vertices && filtered.edges == reference.edges));
}

// Float's labels against the reference clip under Float: equal unless Float's signs
// contradict each other, since the clip derives a crossing's side from its edge's endpoints
// where the reference asks crossing_side. Counted, with how many of those differing pairs the
// clip labels as Exact does, and printed, not asserted: Float promises no consistency.
struct FloatDifferences {
  std::size_t differing = 0, of_which_exact = 0;
};

FloatDifferences float_label_differences(const std::vector<Pair>& pairs) {
  FloatDifferences count;
  for (const Pair& pair : pairs) {
    const IntersectionPolygon reference = reference_clip<rk::Float>(pair.cp, pair.tp);
    const IntersectionPolygon ip = rk::compute_intersection_polygon<rk::Float>(pair.cp, pair.tp);
    if (ip.vertices == reference.vertices && ip.edges == reference.edges) continue;
    const IntersectionPolygon exact = reference_clip<rk::Exact>(pair.cp, pair.tp);
    ++count.differing;
    count.of_which_exact += ip.vertices == exact.vertices && ip.edges == exact.edges;
  }
  return count;
}

ConvexPolygon square(const std::string& name, double x0, double y0, double side) {
  return ConvexPolygon::make(name, {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}});
}

}  // namespace

// (b) Degenerate contacts by name, each with its verdict by hand. CP is the unit square
// (lines 0 bottom, 1 right, 2 top, 3 left). "edge on a longer edge" makes the clip a
// segment along line 0 that lines 1 and 3 then cut at CP's vertices; "edge on a longer edge,
// pentagon" cuts such a segment with a CP line not adjacent to it (a crossing of two CP lines);
// "apart across a TP edge" is separated by a TP edge line only, so the clip runs until the
// set is empty.
BOOST_AUTO_TEST_CASE(named_degenerate_contacts_give_classify_overlap_verdicts) {
  const ConvexPolygon cp = square("cp", 0, 0, 1);
  const ConvexPolygon pentagon = ConvexPolygon::make("cp", {{0, 0}, {2, 0}, {3, 1}, {1, 3}, {-1, 1}});
  struct Case {
    std::string name;
    const ConvexPolygon* cp;
    ConvexPolygon tp;
    Overlap verdict;
  };
  const std::vector<Case> cases{
      {"edge on a longer edge", &cp, ConvexPolygon::make("tp", {{-1, -1}, {2, -1}, {2, 0}, {-1, 0}}), Overlap::touch},
      {"edge on a shorter edge", &cp, ConvexPolygon::make("tp", {{0.25, -1}, {0.75, -1}, {0.75, 0}, {0.25, 0}}),
       Overlap::touch},
      {"edge on a longer edge, pentagon", &pentagon, ConvexPolygon::make("tp", {{-3, -1}, {5, -1}, {5, 0}, {-3, 0}}),
       Overlap::touch},
      {"edge overlapping an edge", &cp, ConvexPolygon::make("tp", {{0.5, -1}, {2, -1}, {2, 0}, {0.5, 0}}),
       Overlap::touch},
      {"vertex on vertex", &cp, square("tp", 1, 1, 1), Overlap::touch},
      {"vertex on edge", &cp, ConvexPolygon::make("tp", {{0.5, 1}, {1, 2}, {0, 2}}), Overlap::touch},
      {"edge on vertex", &cp, ConvexPolygon::make("tp", {{1, 1}, {2, 0}, {3, 3}}), Overlap::touch},
      {"apart across a CP edge", &cp, square("tp", 2, 0, 1), Overlap::separate},
      {"apart across a TP edge", &cp, ConvexPolygon::make("tp", {{3, -0.5}, {3, 3}, {-0.5, 3}}), Overlap::separate},
      {"sharing an edge inside", &cp, ConvexPolygon::make("tp", {{0, 0}, {1, 0}, {0.5, 0.5}}), Overlap::overlap},
      {"identical", &cp, square("tp", 0, 0, 1), Overlap::overlap},
  };
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.name) {
      BOOST_TEST(rk::to_string(rk::classify_overlap<rk::Exact>(*c.cp, c.tp)) == rk::to_string(c.verdict));
      BOOST_TEST(rk::to_string(clip_verdict<rk::Exact>(*c.cp, c.tp)) == rk::to_string(c.verdict));
      BOOST_TEST(rk::to_string(clip_verdict<rk::Filtered>(*c.cp, c.tp)) == rk::to_string(c.verdict));
      BOOST_TEST(rk::to_string(clip_verdict<rk::Float>(*c.cp, c.tp)) == rk::to_string(c.verdict));
    }
  }
}

// (b) On every generator family (pairs and swapped pairs): the verdict of the clip equals
// classify_overlap under Filtered and Exact. Every family has touching pairs, so the
// continued clip of segments and points is exercised, not only the polygons.
BOOST_AUTO_TEST_CASE(clip_verdict_equals_classify_overlap_on_every_family) {
  VerdictTally tally;
  for (const Pair& pair : generated_pairs()) check_verdict(pair, tally);
  BOOST_TEST_MESSAGE("generated pairs: " << tally.separate << " separate, " << tally.touch << " touch, "
                                         << tally.overlap << " overlap");
  BOOST_TEST(tally.touch > 0u);
  BOOST_TEST(tally.separate > 0u);
  BOOST_TEST(tally.overlap > 0u);
}

// (b) On the contact2d reference data: the clip's verdict equals classify_overlap and the
// data's own status, computed independently in exact arithmetic.
BOOST_AUTO_TEST_CASE(clip_verdict_equals_classify_overlap_on_contact2d_data) {
  VerdictTally tally;
  for (const ReferencePair& ref : contact2d_pairs()) {
    check_verdict(ref.pair, tally);
    BOOST_TEST_INFO(ref.pair.name);
    BOOST_TEST(rk::to_string(clip_verdict<rk::Filtered>(ref.pair.cp, ref.pair.tp)) == ref.status);
  }
  BOOST_TEST_MESSAGE("contact2d: " << tally.separate << " separate, " << tally.touch << " touch, " << tally.overlap
                                   << " overlap");
}

// (c) The labels of the memoised clip equal the reference clip's on every generator family
// and on the contact2d data; Float's differences from the reference under Float are printed.
BOOST_AUTO_TEST_CASE(labels_equal_the_reference_clip) {
  for (const Pair& pair : generated_pairs()) check_labels_against_reference(pair);
  std::vector<Pair> reference_pairs;
  for (const ReferencePair& ref : contact2d_pairs()) {
    check_labels_against_reference(ref.pair);
    reference_pairs.push_back(ref.pair);
  }
  for (const auto& [name, pairs] : {std::pair{"generated", &generated_pairs()}, std::pair{"contact2d", &std::as_const(reference_pairs)}}) {
    const FloatDifferences d = float_label_differences(*pairs);
    BOOST_TEST_MESSAGE("Float labels differing from the reference clip under Float: " << d.differing << " of "
                       << pairs->size() << " " << name << " pairs, " << d.of_which_exact
                       << " of them equal to Exact's labels");
  }
}

// (d) Two 12-gons, overlapping, touching and apart: once `out` has room for the largest IP,
// the clip allocates nothing under Float and Filtered (these general-position pairs never
// reach GMP), not even with a fresh workspace. Counted with the replaced operator new above.
BOOST_AUTO_TEST_CASE(clip_of_twelve_gons_does_not_allocate) {
  const auto twelve_gon = [](const std::string& name, double cx, double cy, double r) {
    std::vector<rk::Point2> v;
    for (int k = 0; k < 12; ++k) {
      const double t = 2.0 * 3.141592653589793 * k / 12.0;
      v.push_back({cx + r * std::cos(t), cy + r * std::sin(t)});
    }
    return ConvexPolygon::make(name, v);
  };
  const ConvexPolygon cp = twelve_gon("cp", 0, 0, 1);
  const std::vector<ConvexPolygon> tps{twelve_gon("tp", 0.3, 0.2, 1), twelve_gon("tp", 0.1, -0.05, 0.7),
                                       twelve_gon("tp", 3, 1, 1), twelve_gon("tp", 0.5, 0.5, 2)};
  IntersectionPolygon out;
  out.vertices.reserve(24);
  out.edges.reserve(24);
  std::size_t overlapping = 0;
  const long before = heap_allocations.load();
  rk::ClipWorkspace workspace;
  for (const ConvexPolygon& tp : tps) {
    overlapping += rk::compute_intersection_polygon<rk::Filtered>(cp, tp, out, workspace) == Overlap::overlap;
    overlapping += rk::compute_intersection_polygon<rk::Float>(cp, tp, out, workspace) == Overlap::overlap;
  }
  BOOST_TEST(heap_allocations.load() - before == 0);
  BOOST_TEST(overlapping == 6u);
}
