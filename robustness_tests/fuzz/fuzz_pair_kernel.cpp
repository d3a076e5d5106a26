// libFuzzer target: the pair kernel and the potential contact law under Filtered and Exact.
// The Filtered side runs under the Checked policy: Filtered's signs and constructions, each
// sign also evaluated exactly on its own, a disagreement thrown as PolicyDisagreement with the
// predicate's input (Exact shares Filtered's staged predicates, so only Checked compares them
// with an independent evaluation).
//
// The input bytes decode into two point sets (pair_input.hpp: raw IEEE bit patterns, small
// integers, dyadic numbers far from the origin, or a mix), which become polygons either
// through ConvexPolygon::make as they stand (most are invalid: make must reject them with
// InvalidPolygon and a message naming the polygon, never crash) or through the generators'
// strict convex_hull (always valid when it keeps three vertices). On a valid pair it aborts on
//   * any disagreement between Filtered and Exact: classify_overlap, the entrance block's
//     status, the symbolic IP (vertex and edge labels), evaluate_pair's status and labels;
//   * an inconsistency within one policy: IP non-empty but verdict not `overlap` (or the
//     reverse), an asymmetric verdict, a force without overlap, an input vertex of the IP not
//     copied bit for bit, a polygon make accepted that is not its own strict convex hull;
//   * a non-finite force, contact point, area, IP point or entrance distance when the input is
//     in the sane range below;
//   * any exception but InvalidPolygon from make (the parameters are valid, so evaluate_pair
//     must not throw).
// Float runs too, for crashes and sanitizer reports only: its answers may be wrong by design.
//
// Sane range: every coordinate 0 or of magnitude in [2^-60, 2^32] m. Differences of such
// numbers are 0 or >= 2^-112, so their squares and the products of four of them (the degree of
// the potential's integrands) stay normal doubles, and |force| <= (kn / H) S^2 stays far below
// the overflow threshold. Outside it a non-finite force is the honest answer of double
// constructions (an edge of 1e-300 m, a block of 1e300 m), not a bug.
//
// Exact cost: each input double is a rational with a power-of-two denominator, so even the
// extreme exponents (2^-1074, 2^1023) make numbers of ~2100 bits; the Exact verdict and IP
// stay cheap on every input. The Exact force, whose demarcation points and integrals combine
// many such numbers, runs only in the sane range and below max_exact_force_vertices vertices
// per polygon, which keeps every run far below libFuzzer's -timeout.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rockcontact/generators/pair_generators.hpp"
#include "pair_input.hpp"
#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/2d/intersection_polygon.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace {

namespace rc = rockcontact;
namespace rk = rockcontact::kernel;
using rc::contact::PairResult;
using rc::contact::PairWorkspace;
using rc::contact::PotentialContactParams;
using rc::fuzz::PairInput;
using rk::ConvexPolygon;
using rk::Exact;
using Filtered = rk::Checked;
using rk::Float;
using rk::IntersectionPolygon;
using rk::IpVertex;
using rk::Overlap;
using rk::Point2;

constexpr double sane_min = 0x1p-60;
constexpr double sane_max = 0x1p32;
constexpr std::size_t max_exact_force_vertices = 16;

void print_polygon(const char* name, std::span<const Point2> polygon) {
  std::fprintf(stderr, "  %s = [", name);
  for (const Point2& p : polygon) std::fprintf(stderr, "(%a, %a) ", p.x, p.y);
  std::fprintf(stderr, "]\n");
}

// Prints the failed property and the pair (hexadecimal floats: exact), then aborts so that
// libFuzzer records the input as a crash.
[[noreturn]] void fail(const char* what, std::span<const Point2> cp, std::span<const Point2> tp) {
  std::fprintf(stderr, "fuzz_pair_kernel: %s\n", what);
  print_polygon("cp", cp);
  print_polygon("tp", tp);
  std::abort();
}

bool sane(std::span<const Point2> polygon) {
  const auto ok = [](double c) {
    const double m = std::fabs(c);
    return m == 0.0 || (m >= sane_min && m <= sane_max);
  };
  for (const Point2& p : polygon) {
    if (!ok(p.x) || !ok(p.y)) return false;
  }
  return true;
}

bool finite(const Point2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

struct Pair {
  ConvexPolygon cp;
  ConvexPolygon tp;
};

// A polygon make accepted is strictly convex and CCW, hence its own strict convex hull.
void check_accepted(const ConvexPolygon& polygon, std::span<const Point2> cp, std::span<const Point2> tp) {
  const std::vector<Point2> vertices(polygon.vertices().begin(), polygon.vertices().end());
  for (const Point2& p : vertices) {
    if (!finite(p)) fail("make accepted a non-finite vertex", cp, tp);
  }
  if (rc::robustness::convex_hull(vertices).size() != vertices.size()) {
    fail("make accepted a polygon that is not strictly convex", cp, tp);
  }
}

std::optional<ConvexPolygon> make(const std::string& name, std::vector<Point2> vertices, bool normalise,
                                  std::span<const Point2> cp, std::span<const Point2> tp) {
  const std::size_t n = vertices.size();
  try {
    ConvexPolygon polygon = ConvexPolygon::make(
        name, std::move(vertices), normalise ? rk::VertexOrder::normalise : rk::VertexOrder::require_ccw);
    check_accepted(polygon, cp, tp);
    return polygon;
  } catch (const rk::InvalidPolygon& e) {
    const bool vertex_ok = e.vertex() >= -1 && e.vertex() < static_cast<std::ptrdiff_t>(n);
    if (std::string(e.what()).empty() || e.polygon() != name || !vertex_ok) {
      fail("InvalidPolygon without a message, the polygon's name or a valid vertex index", cp, tp);
    }
    return std::nullopt;
  }
}

std::optional<Pair> build(const PairInput& input) {
  if (!input.hull) {
    auto cp = make("cp", input.cp, input.normalise, input.cp, input.tp);
    auto tp = make("tp", input.tp, input.normalise, input.cp, input.tp);
    if (!cp || !tp) return std::nullopt;
    return Pair{std::move(*cp), std::move(*tp)};
  }
  // The hull is only defined for finite points; the others are dropped.
  const auto hull = [](std::span<const Point2> points) {
    std::vector<Point2> kept;
    for (const Point2& p : points) {
      if (finite(p)) kept.push_back(p);
    }
    return rc::robustness::convex_hull(std::move(kept));
  };
  std::vector<Point2> cp = hull(input.cp), tp = hull(input.tp);
  if (cp.size() < 3 || tp.size() < 3) return std::nullopt;
  try {
    return Pair{ConvexPolygon::make("cp", cp), ConvexPolygon::make("tp", tp)};
  } catch (const rk::InvalidPolygon& e) {
    std::fprintf(stderr, "%s\n", e.what());
    fail("make rejected a strict convex hull", cp, tp);
  }
}

bool same_labels(const IntersectionPolygon& a, const IntersectionPolygon& b) {
  return a.vertices == b.vertices && a.edges == b.edges;
}

struct Scratch {
  rk::ClipWorkspace clip;
  IntersectionPolygon ip_float, ip_filtered, ip_exact;
  std::vector<Point2> points_filtered, points_exact;
  PairWorkspace pair;
  PairResult force_float, force_filtered, force_exact;
};

// Reused across inputs, as a host code reuses its workspaces: stale state from the previous
// pair must not leak into the next.
Scratch& scratch() {
  static Scratch s;
  return s;
}

void check_points(const Pair& pair, Scratch& s, bool in_range) {
  const auto cp = pair.cp.vertices();
  const auto tp = pair.tp.vertices();
  rk::construct_points<Filtered>(pair.cp, pair.tp, s.ip_filtered, s.points_filtered);
  rk::construct_points<Exact>(pair.cp, pair.tp, s.ip_exact, s.points_exact);
  for (std::size_t k = 0; k < s.ip_exact.vertices.size(); ++k) {
    const IpVertex& v = s.ip_exact.vertices[k];
    if (in_range && !(finite(s.points_filtered[k]) && finite(s.points_exact[k]))) {
      fail("a non-finite IP point in the sane range", cp, tp);
    }
    if (v.kind == IpVertex::Kind::crossing) continue;
    const Point2& input = v.kind == IpVertex::Kind::cp_vertex ? pair.cp[v.cp] : pair.tp[v.tp];
    if (!(s.points_filtered[k] == input) || !(s.points_exact[k] == input)) {
      fail("an input vertex of the IP was not copied", cp, tp);
    }
  }
}

void check_verdicts(const Pair& pair, Scratch& s, bool in_range) {
  const auto cp = pair.cp.vertices();
  const auto tp = pair.tp.vertices();
  const Overlap filtered = rk::classify_overlap<Filtered>(pair.cp, pair.tp);
  const Overlap exact = rk::classify_overlap<Exact>(pair.cp, pair.tp);
  if (filtered != exact) fail("classify_overlap: Filtered != Exact", cp, tp);
  if (rk::classify_overlap<Filtered>(pair.tp, pair.cp) != filtered) fail("verdict not symmetric", cp, tp);

  const rk::EntranceBlock block_filtered = rk::compute_entrance_block<Filtered>(pair.cp, pair.tp);
  const rk::EntranceBlock block_exact = rk::compute_entrance_block<Exact>(pair.cp, pair.tp);
  if (block_filtered.status != exact || block_exact.status != exact) {
    fail("entrance block status != classify_overlap", cp, tp);
  }
  if (in_range && !(std::isfinite(block_filtered.distance) && block_filtered.distance >= 0.0 &&
                    std::isfinite(block_exact.distance) && block_exact.distance >= 0.0)) {
    fail("entrance block distance not finite and >= 0 in the sane range", cp, tp);
  }

  rk::compute_intersection_polygon<Filtered>(pair.cp, pair.tp, s.ip_filtered, s.clip);
  rk::compute_intersection_polygon<Exact>(pair.cp, pair.tp, s.ip_exact, s.clip);
  if (!same_labels(s.ip_filtered, s.ip_exact)) fail("IP labels: Filtered != Exact", cp, tp);
  if (s.ip_exact.empty() != (exact != Overlap::overlap)) fail("IP non-empty != verdict overlap", cp, tp);
  check_points(pair, s, in_range);
}

void check_force(const char* policy, const PairResult& r, Overlap verdict, const IntersectionPolygon& ip,
                 bool in_range, std::span<const Point2> cp, std::span<const Point2> tp) {
  const std::string what = std::string("evaluate_pair<") + policy + ">: ";
  if (r.status != verdict || !same_labels(r.ip_features, ip)) {
    fail((what + "status or IP labels differ from the kernel's").c_str(), cp, tp);
  }
  if (verdict != Overlap::overlap && (!(r.force == rk::Vector2{}) || r.point || !r.ip.empty())) {
    fail((what + "a force, point or IP without overlap").c_str(), cp, tp);
  }
  if (!in_range) return;
  const bool all_finite = std::isfinite(r.force.x) && std::isfinite(r.force.y) && std::isfinite(r.area) &&
                          (!r.point || finite(*r.point));
  if (!all_finite) fail((what + "a non-finite result in the sane range").c_str(), cp, tp);
}

void check_pair(const Pair& pair, const PotentialContactParams& params) {
  Scratch& s = scratch();
  const auto cp = pair.cp.vertices();
  const auto tp = pair.tp.vertices();
  const bool in_range = sane(cp) && sane(tp);
  check_verdicts(pair, s, in_range);
  const Overlap verdict = rk::classify_overlap<Exact>(pair.cp, pair.tp);

  rc::contact::evaluate_pair<Filtered>(pair.cp, pair.tp, params, s.pair, s.force_filtered);
  check_force("Filtered", s.force_filtered, verdict, s.ip_exact, in_range, cp, tp);
  const bool exact_force_cheap = in_range && pair.cp.size() <= max_exact_force_vertices &&
                                 pair.tp.size() <= max_exact_force_vertices;
  if (exact_force_cheap) {
    rc::contact::evaluate_pair<Exact>(pair.cp, pair.tp, params, s.pair, s.force_exact);
    check_force("Exact", s.force_exact, verdict, s.ip_exact, in_range, cp, tp);
  }

  // Float: answers unchecked, only crashes and sanitizer reports count.
  rk::classify_overlap<Float>(pair.cp, pair.tp);
  rk::compute_entrance_block<Float>(pair.cp, pair.tp);
  rk::compute_intersection_polygon<Float>(pair.cp, pair.tp, s.ip_float, s.clip);
  rk::construct_points<Float>(pair.cp, pair.tp, s.ip_float, s.points_filtered);
  rc::contact::evaluate_pair<Float>(pair.cp, pair.tp, params, s.pair, s.force_float);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const PairInput input = rc::fuzz::decode_pair({data, size});
  PotentialContactParams params = rc::contact::default_potential_contact_params();
  if (input.paper_demarcation) params.demarcation = rk::Demarcation::paper;
  try {
    const std::optional<Pair> pair = build(input);
    if (pair) check_pair(*pair, params);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unexpected exception: %s\n", e.what());
    fail("an exception escaped the kernel", input.cp, input.tp);
  }
  return 0;
}
