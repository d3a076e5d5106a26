#include "pair_campaign.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <thread>
#include <utility>

#include "rockcontact/kernel/2d/crossing_point.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/policy_disagreement.hpp"

namespace rockcontact::robustness {
namespace {

namespace rk = kernel;
using contact::PairResult;
using contact::PairWorkspace;
using contact::PotentialContactParams;
using rk::ConvexPolygon;
using rk::Exact;
// The campaign's Filtered side runs under Checked: Filtered's signs and constructions, each
// sign also evaluated exactly on its own. Exact shares Filtered's staged predicates, so only
// Checked compares them with an independent evaluation; a disagreement (PolicyDisagreement)
// is counted with the Filtered disagreements, its message naming the predicate's input.
using Filtered = rk::Checked;
using rk::Float;
using rk::IntersectionPolygon;
using rk::IpEdge;
using rk::IpVertex;
using rk::Overlap;

constexpr double u = 0x1p-53;  // unit roundoff of double
// Relative slack for evaluating a bound in double: each bound here takes fewer than 40
// rounded operations on non-negative terms, so it is under-estimated by at most (1 - u)^40.
constexpr double bound_slack = 1.0 + 0x1p-40;

double diameter(std::span<const Point2> v) {
  double best = 0.0;
  for (const Point2& a : v) {
    for (const Point2& b : v) best = std::max(best, std::hypot(b.x - a.x, b.y - a.y));
  }
  return best;
}

double perimeter(const ConvexPolygon& poly) {
  double sum = 0.0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point2& p = poly[k];
    const Point2& q = poly[poly.next(k)];
    sum += std::hypot(q.x - p.x, q.y - p.y);
  }
  return sum;
}

double max_error(const Vector2& a, const Vector2& b) {
  return std::max(std::fabs(a.x - b.x), std::fabs(a.y - b.y));
}

// error / bound, where a zero error meets a zero bound (an exactly constructed crossing).
double ratio(double error, double bound) { return error == 0.0 ? 0.0 : error / bound; }

bool same_labels(const IntersectionPolygon& a, const IntersectionPolygon& b) {
  return a.vertices == b.vertices && a.edges == b.edges;
}

}  // namespace

// ## Bound on a constructed crossing (construct_points under Filtered vs Exact)
// The crossing of CP edge p -> q with TP edge t0 -> t1 is X = t0 + s d with s = N / D,
// N = l x w, D = l x d, l = q - p, d = t1 - t0, w = p - t0. In double:
//   * N and D are cross products of rounded differences of inputs: by Shewchuk's bound
//     (the kernel's cross filter) the exact difference of the rounded products is within
//     (3 + 16u) u Nbar of N, and its rounding adds u |fl(N)| <= u (1 + u) Nbar, so
//     |fl(N) - N| <= e Nbar, |fl(D) - D| <= e Dbar with e = (4 + 32u) u (covering the rounding
//     of the computed Nbar = |lx wy| + |ly wx|, Dbar = |lx dy| + |ly dx| too);
//   * fl(N)/fl(D) - N/D = ((fl(N) - N) D - N (fl(D) - D)) / (fl(D) D), so with |s| <= 1 (the
//     combinatorics put X on the TP edge) |s' - s| <= ds = e (Nbar + Dbar) / |fl(D)| + u|s'|;
//     the clamp of s' to [0, 1] projects onto a set containing s and cannot increase the error,
//     which is therefore also <= 1. This is the near-parallel ill-conditioning: 1/|D|.
//   * The kernel keeps the double crossing only when its own certificate of this bound is at
//     most 2^-40 (crossing_point.hpp); otherwise it rounds the exact crossing, exactly as Exact
//     does (error 0 against Exact). Either way the error of s' is at most min(ds, 2^-40), where
//     ds is computed here independently of the kernel's certificate.
//   * X_c = fl(t0_c + fl(s' fl(d_c))) adds |d_c| 2u (1 + u) + u |X'_c| (1 + u);
//   * Exact rounds the exact X_c once: u |X_c| <= u |X^e_c| (1 + u).
// Hence per coordinate c:
//   |X'_c - X^e_c| <= (|d_c| (min(ds, 2^-40) + 2u) + u (|X'_c| + |X^e_c|)) (1 + 2u).
CrossingBound crossing_bound(const ConvexPolygon& cp, const ConvexPolygon& tp, const IpVertex& v,
                             const Point2& filtered, const Point2& exact) {
  const Point2& p = cp[v.cp];
  const Point2& q = cp[cp.next(v.cp)];
  const Point2& t0 = tp[v.tp];
  const Point2& t1 = tp[tp.next(v.tp)];
  const double lx = q.x - p.x, ly = q.y - p.y, dx = t1.x - t0.x, dy = t1.y - t0.y;
  const double wx = p.x - t0.x, wy = p.y - t0.y;
  const double n_bar = std::fabs(lx * wy) + std::fabs(ly * wx);
  const double d_bar = std::fabs(lx * dy) + std::fabs(ly * dx);
  const double d = lx * dy - ly * dx;
  const double e = (4.0 + 32.0 * u) * u;
  const double ds_formula = d == 0.0 ? 1.0 : std::min(1.0, e * (n_bar + d_bar) / std::fabs(d) + u);
  const double ds = std::min(ds_formula, rk::crossing_parameter_tolerance * bound_slack);
  const auto coordinate = [&](double dc, double xf, double xe) {
    return (std::fabs(dc) * (ds + 2.0 * u) + u * (std::fabs(xf) + std::fabs(xe))) * (1.0 + 2.0 * u) *
           bound_slack;
  };
  return {coordinate(dx, filtered.x, exact.x), coordinate(dy, filtered.y, exact.y)};
}

// ## Bound on the force (evaluate_pair under Filtered vs Exact)
//   |f_filtered - f_exact| <= (kn/H) (32 u S (S + R) + 2 sum_k delta_k (L_k-1 + L_k + 2 Delta))
// per component, S the larger diameter of cp and tp, R the largest coordinate magnitude of the
// IP (m), delta_k = |crossing_bound| of IP vertex k (m; 0 for input vertices), L_k-1 and L_k the
// lengths of the two exact IP edges at vertex k, Delta = sum_k delta_k. The combinatorics are
// identical (checked), so the two computations differ only by rounding:
//   * At fixed vertices: every value g = d_CP - d_TP (cross products of differences of
//     coordinates of size R and lengths <= S, divided by an edge length) is off by
//     <= ~4u (R + S); f = (kn/H) sum_e G_e (dy, -dx), G_e = int g over IP edge e, sums them over
//     the IP boundary (perimeter <= pi S), and the normals (dy, -dx) are off by u R each with
//     |g| <= S: together <= ~2 (4 pi + 2) u (kn/H) S (S + R), under 32. A relative term is not
//     needed: |f| <= 2 (kn/H) area(IP) <= (kn/H) S^2, so u |f| is inside it.
//   * Moved vertices: by the divergence theorem f = (kn/H) int_IP grad g dA, and Filtered
//     integrates the same Lipschitz function (g with each distance clamped at 0, equal to g on
//     the exact IP, |grad| <= 2 per component) over the polygon of its constructed vertices.
//     Moving vertex k by delta_k sweeps two triangles of area <= delta_k L / 2 each, L the
//     adjacent edge lengths (grown by at most Delta by the other moves): the area integrals
//     differ by <= sum_k delta_k (L_k-1 + L_k + 2 Delta). The clamp adds a kink the
//     demarcation does not know where a moved vertex left a polygon: there the clamped
//     distance is <= delta_k on at most the two adjacent edges, so the trapezoid rule is off by
//     no more than the same sum again. This is first order in delta_k: a crossing that slides
//     along its TP edge off the line of the next IP edge cuts a triangle off the IP (the
//     rotated pair 384916 of seed 20261124, swapped, lost 7.6e-6 m^2 that way before
//     crossings were certified to 2^-40).
// The campaign reports the worst observed ratio error / bound per family: the bound is not
// loose by many orders of magnitude, and not tight enough to flake.
double force_bound(const ConvexPolygon& cp, const ConvexPolygon& tp, const IntersectionPolygon& ip,
                   std::span<const Point2> filtered, std::span<const Point2> exact,
                   const PotentialContactParams& params) {
  constexpr double first_order_factor = 32.0;
  const std::size_t n = ip.vertices.size();
  std::vector<double> delta(n, 0.0);
  double r = 0.0, total_delta = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    r = std::max({r, std::fabs(exact[k].x), std::fabs(exact[k].y)});
    if (ip.vertices[k].kind != IpVertex::Kind::crossing) continue;
    const CrossingBound b = crossing_bound(cp, tp, ip.vertices[k], filtered[k], exact[k]);
    delta[k] = std::hypot(b.x, b.y);
    total_delta += delta[k];
  }
  const auto edge_length = [&](std::size_t k) {  // exact IP edge from vertex k to k + 1
    const Point2 &a = exact[k], &b = exact[k + 1 == n ? 0 : k + 1];
    return std::hypot(b.x - a.x, b.y - a.y);
  };
  double moved = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (delta[k] == 0.0) continue;
    moved += delta[k] * (edge_length(k == 0 ? n - 1 : k - 1) + edge_length(k) + 2.0 * total_delta);
  }
  const double s = std::max(diameter(cp.vertices()), diameter(tp.vertices()));
  return (params.kn / params.H) * (first_order_factor * u * s * (s + r) + 2.0 * moved) * bound_slack *
         (1.0 + 4.0 * u);
}

std::string_view to_string(Property property) {
  switch (property) {
    case Property::ip_matches_verdict: return "ip_matches_verdict";
    case Property::ip_convex_ccw: return "ip_convex_ccw";
    case Property::ip_inside_both: return "ip_inside_both";
    case Property::ip_edge_labels: return "ip_edge_labels";
    case Property::ip_area: return "ip_area";
    case Property::exact_rounding: return "exact_rounding";
    case Property::translation: return "translation";
    case Property::rotation: return "rotation";
    case Property::swap: return "swap";
    case Property::touch_continuity: return "touch_continuity";
    case Property::count: break;
  }
  return "?";
}

namespace {

// ---- exact geometry of the IP, written here independently of the kernel ---------------------

struct QPoint {
  mpq_class x;
  mpq_class y;
};

QPoint lift(const Point2& p) { return {mpq_class(p.x), mpq_class(p.y)}; }

int orientation(const QPoint& a, const QPoint& b, const QPoint& c) {
  const mpq_class det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return sgn(det);
}

// The crossing of the lines p q and r s by Cramer's rule on a x + b y = c; nullopt when they
// are parallel.
std::optional<QPoint> line_crossing(const Point2& p, const Point2& q, const Point2& r, const Point2& s) {
  const QPoint P = lift(p), Q = lift(q), R = lift(r), S = lift(s);
  const mpq_class a1 = Q.y - P.y, b1 = P.x - Q.x, c1 = a1 * P.x + b1 * P.y;
  const mpq_class a2 = S.y - R.y, b2 = R.x - S.x, c2 = a2 * R.x + b2 * R.y;
  const mpq_class det = a1 * b2 - a2 * b1;
  if (sgn(det) == 0) return std::nullopt;
  return QPoint{mpq_class((c1 * b2 - c2 * b1) / det), mpq_class((a1 * c2 - a2 * c1) / det)};
}

// The exact IP vertices named by `ip`; false when a crossing names parallel edges.
bool exact_vertices(const ConvexPolygon& cp, const ConvexPolygon& tp, const IntersectionPolygon& ip,
                    std::vector<QPoint>& out) {
  out.clear();
  for (const IpVertex& v : ip.vertices) {
    switch (v.kind) {
      case IpVertex::Kind::cp_vertex: out.push_back(lift(cp[v.cp])); break;
      case IpVertex::Kind::tp_vertex: out.push_back(lift(tp[v.tp])); break;
      case IpVertex::Kind::crossing: {
        const auto x = line_crossing(cp[v.cp], cp[cp.next(v.cp)], tp[v.tp], tp[tp.next(v.tp)]);
        if (!x) return false;
        out.push_back(*x);
        break;
      }
    }
  }
  return true;
}

mpq_class twice_area(std::span<const QPoint> v) {
  mpq_class sum(0);
  for (std::size_t k = 0; k < v.size(); ++k) {
    const QPoint& p = v[k];
    const QPoint& q = v[k + 1 == v.size() ? 0 : k + 1];
    sum += p.x * q.y - p.y * q.x;
  }
  return sum;
}

mpq_class twice_area(const ConvexPolygon& poly) {
  std::vector<QPoint> v;
  for (const Point2& p : poly.vertices()) v.push_back(lift(p));
  return twice_area(v);
}

// Every vertex strictly left of every edge it is not an end of. Then every edge is an edge of
// the convex hull with the polygon on its left, the vertices are distinct and all on the hull,
// so the n edges are the hull's n edges: a strictly convex CCW polygon.
bool strictly_convex_ccw(std::span<const QPoint> v) {
  const std::size_t n = v.size();
  if (n < 3) return false;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t next = k + 1 == n ? 0 : k + 1;
    for (std::size_t j = 0; j < n; ++j) {
      if (j != k && j != next && orientation(v[k], v[next], v[j]) <= 0) return false;
    }
  }
  return true;
}

bool inside(std::span<const QPoint> v, const ConvexPolygon& poly) {
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const QPoint a = lift(poly[k]), b = lift(poly[poly.next(k)]);
    for (const QPoint& p : v) {
      if (orientation(a, b, p) < 0) return false;
    }
  }
  return true;
}

bool edges_on_their_lines(std::span<const QPoint> v, const IntersectionPolygon& ip, const ConvexPolygon& cp,
                          const ConvexPolygon& tp) {
  for (std::size_t k = 0; k < ip.edges.size(); ++k) {
    const IpEdge& e = ip.edges[k];
    const ConvexPolygon& poly = e.on == IpEdge::On::cp_edge ? cp : tp;
    const QPoint a = lift(poly[e.index]), b = lift(poly[poly.next(e.index)]);
    if (orientation(a, b, v[k]) != 0 || orientation(a, b, v[k + 1 == v.size() ? 0 : k + 1]) != 0) return false;
  }
  return true;
}

// `d` is a double nearest to x: neither neighbouring double is strictly closer.
bool nearest_double(double d, const mpq_class& x) {
  if (!std::isfinite(d)) return false;
  const mpq_class error = abs(mpq_class(d) - x);
  for (double neighbour : {std::nextafter(d, -HUGE_VAL), std::nextafter(d, HUGE_VAL)}) {
    if (std::isfinite(neighbour) && abs(mpq_class(neighbour) - x) < error) return false;
  }
  return true;
}

// ---- transformed pairs -------------------------------------------------------------------------

// (x, y) -> (-y, x): a negation and a swap, exact in floating point, and orientation-preserving,
// so the polygons stay CCW with the same vertex numbering.
Point2 rotate90(const Point2& p) { return {-p.y, p.x}; }
Vector2 rotate90(const Vector2& v) { return {-v.y, v.x}; }

PolygonPair rotate90(const PolygonPair& pair) {
  PolygonPair out = pair;
  for (auto* poly : {&out.cp, &out.tp}) {
    for (Point2& p : *poly) p = rotate90(p);
  }
  return out;
}

// a + b when the sum is exact (Knuth's two-sum error is zero).
std::optional<double> exact_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  const double error = (a - (s - bb)) + (b - bb);
  if (error != 0.0 || !std::isfinite(s)) return std::nullopt;
  return s;
}

// The pair with tp alone translated by `offset`, when every coordinate sum is exact.
std::optional<PolygonPair> push_tp(const PolygonPair& pair, Vector2 offset) {
  PolygonPair out = pair;
  for (Point2& p : out.tp) {
    const auto x = exact_sum(p.x, offset.x), y = exact_sum(p.y, offset.y);
    if (!x || !y) return std::nullopt;
    p = {*x, *y};
  }
  return out;
}

Point2 vertex_mean(const std::vector<Point2>& v) {
  Point2 sum;
  for (const Point2& p : v) sum = {sum.x + p.x, sum.y + p.y};
  const double n = static_cast<double>(v.size());
  return {sum.x / n, sum.y / n};
}

std::string reproducer(std::string_view what, const PolygonPair& pair) {
  std::string out(what);
  out += ": ";
  out += pair.recipe;
  char buffer[96];
  for (const auto& [name, poly] : {std::pair{" cp", &pair.cp}, std::pair{" tp", &pair.tp}}) {
    out += name;
    out += " = [";
    for (const Point2& p : *poly) {
      std::snprintf(buffer, sizeof buffer, "(%.17g, %.17g) ", p.x, p.y);
      out += buffer;
    }
    out += "]";
  }
  return out;
}

struct Polygons {
  ConvexPolygon cp;
  ConvexPolygon tp;
};

Polygons make_polygons(const PolygonPair& pair) {
  return {ConvexPolygon::make("cp", pair.cp), ConvexPolygon::make("tp", pair.tp)};
}

// Scratch reused across the cases of one thread.
struct Work {
  IntersectionPolygon ip_float, ip_filtered, ip_exact, ip_other, ip_other_exact;
  rk::ClipWorkspace clip;
  std::vector<Point2> points_filtered, points_exact, points_other;
  std::vector<QPoint> exact_ip;
  PairWorkspace pair;
  PairResult forward, rotated, swapped, pushed, exact, exact_other;
};

// One case: the pair, its polygons and every check on it, in the order of the header.
class Case {
 public:
  Case(const CampaignOptions& options, FamilyStats& stats, Work& work, const PolygonPair& pair)
      : options_(options), params_(options.params), stats_(stats), w_(work), pair_(pair),
        polys_(make_polygons(pair)), rotated_pair_(rotate90(pair)), rotated_(make_polygons(rotated_pair_)) {}

  void run(bool exact_force) {
    check_decisions();
    count_float();
    check_translation();
    rk::construct_points<Exact>(polys_.cp, polys_.tp, w_.ip_exact, w_.points_exact);
    if (agree_) check_points();
    check_exact_ip();
    // Force checks need the Filtered and Exact IPs to agree (force_bound assumes it).
    if (!agree_) return;
    contact::evaluate_pair<Filtered>(polys_.cp, polys_.tp, params_, w_.pair, w_.forward);
    if (w_.forward.status != filtered_ || !same_labels(w_.forward.ip_features, w_.ip_exact)) {
      fail(stats_.filtered_ip, "evaluate_pair: Filtered status or IP differ from classify and clip");
      return;
    }
    forward_bound_ = force_bound(polys_.cp, polys_.tp, w_.ip_exact, w_.forward.ip, w_.points_exact, params_);
    check_rotation();
    check_swap();
    check_touch_continuity();
    if (exact_force) check_exact_force();
  }

 private:
  void fail(std::size_t& counter, std::string_view what) {
    ++counter;
    if (stats_.reproducers.size() < options_.reproducers_per_family) {
      stats_.reproducers.push_back(reproducer(what, pair_));
    }
  }
  void violated(Property property, std::string_view what) {
    fail(stats_.violations[static_cast<std::size_t>(property)], what);
  }

  void check_decisions();
  void count_float();
  void check_points();
  void check_exact_ip();
  void check_translation();
  void check_rotation();
  void check_swap();
  void check_touch_continuity();
  bool push_and_check(const Polygons& pushed, double h, double direction_length);
  void check_exact_force();

  const CampaignOptions& options_;
  const PotentialContactParams& params_;
  FamilyStats& stats_;
  Work& w_;
  const PolygonPair& pair_;
  Polygons polys_;
  PolygonPair rotated_pair_;
  Polygons rotated_;
  Overlap filtered_ = Overlap::separate;
  Overlap exact_ = Overlap::separate;
  bool agree_ = false;  // Filtered and Exact verdicts and IP labels agree
  double forward_bound_ = 0.0;
};

void Case::check_decisions() {
  const rk::PredicateCounters before = rk::predicate_counters();
  filtered_ = rk::classify_overlap<Filtered>(polys_.cp, polys_.tp);
  rk::compute_intersection_polygon<Filtered>(polys_.cp, polys_.tp, w_.ip_filtered, w_.clip);
  const rk::PredicateCounters spent = rk::predicate_counters() - before;
  stats_.filtered_counters += spent;
  exact_ = rk::classify_overlap<Exact>(polys_.cp, polys_.tp);
  rk::compute_intersection_polygon<Exact>(polys_.cp, polys_.tp, w_.ip_exact, w_.clip);
  ++stats_.verdicts[static_cast<std::size_t>(exact_)];
  if (filtered_ != exact_) fail(stats_.filtered_verdict, "classify_overlap: Filtered != Exact");
  const bool same_ip = same_labels(w_.ip_filtered, w_.ip_exact);
  if (!same_ip) fail(stats_.filtered_ip, "IP labels: Filtered != Exact");
  agree_ = filtered_ == exact_ && same_ip;
  if (w_.ip_exact.empty() != (exact_ != Overlap::overlap)) {
    violated(Property::ip_matches_verdict, "Exact IP non-empty != verdict overlap");
  }
  if (w_.ip_filtered.empty() != (filtered_ != Overlap::overlap)) {
    violated(Property::ip_matches_verdict, "Filtered IP non-empty != verdict overlap");
  }
}

// Float may decide inconsistently; whatever it does, including throwing, is counted.
void Case::count_float() {
  try {
    const Overlap by_float = rk::classify_overlap<Float>(polys_.cp, polys_.tp);
    rk::compute_intersection_polygon<Float>(polys_.cp, polys_.tp, w_.ip_float, w_.clip);
    stats_.float_verdict += by_float != exact_;
    stats_.float_ip += !same_labels(w_.ip_float, w_.ip_exact);
    stats_.float_inconsistent += w_.ip_float.empty() != (by_float != Overlap::overlap);
  } catch (const std::exception&) {
    ++stats_.float_exceptions;
  }
}

void Case::check_points() {
  rk::construct_points<Filtered>(polys_.cp, polys_.tp, w_.ip_filtered, w_.points_filtered);
  for (std::size_t k = 0; k < w_.points_exact.size(); ++k) {
    const IpVertex& v = w_.ip_exact.vertices[k];
    const Point2& pf = w_.points_filtered[k];
    const Point2& pe = w_.points_exact[k];
    if (v.kind != IpVertex::Kind::crossing) {
      if (!(pf == pe)) fail(stats_.filtered_points, "an input vertex of the IP was not copied");
      continue;
    }
    ++stats_.crossings;
    const CrossingBound b = crossing_bound(polys_.cp, polys_.tp, v, pf, pe);
    const double ex = std::fabs(pf.x - pe.x), ey = std::fabs(pf.y - pe.y);
    stats_.worst_crossing_ratio = std::max({stats_.worst_crossing_ratio, ratio(ex, b.x), ratio(ey, b.y)});
    if (!(ex <= b.x && ey <= b.y)) fail(stats_.filtered_points, "a Filtered crossing exceeds crossing_bound");
  }
}

void Case::check_exact_ip() {
  if (w_.ip_exact.empty()) return;
  if (w_.ip_exact.edges.size() != w_.ip_exact.vertices.size()) {
    violated(Property::ip_edge_labels, "IP edge and vertex counts differ");
    return;
  }
  if (!exact_vertices(polys_.cp, polys_.tp, w_.ip_exact, w_.exact_ip)) {
    violated(Property::ip_edge_labels, "an IP crossing of two parallel edges");
    return;
  }
  const std::span<const QPoint> v = w_.exact_ip;
  if (!strictly_convex_ccw(v)) violated(Property::ip_convex_ccw, "exact IP not strictly convex CCW");
  if (!inside(v, polys_.cp) || !inside(v, polys_.tp)) {
    violated(Property::ip_inside_both, "an exact IP vertex outside cp or tp");
  }
  if (!edges_on_their_lines(v, w_.ip_exact, polys_.cp, polys_.tp)) {
    violated(Property::ip_edge_labels, "an IP edge not on the line it is labelled with");
  }
  const mpq_class area = twice_area(v);
  if (area > twice_area(polys_.cp) || area > twice_area(polys_.tp)) {
    violated(Property::ip_area, "area(IP) > min(area(cp), area(tp))");
  }
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!nearest_double(w_.points_exact[k].x, v[k].x) || !nearest_double(w_.points_exact[k].y, v[k].y)) {
      violated(Property::exact_rounding, "an Exact IP point is not the exact vertex rounded to nearest");
      break;
    }
  }
}

// Translating by (2^20, -2^20) is exact once the coordinates are on the grid 2^(k - 53), where
// 2^k exceeds every coordinate plus 2^20 in magnitude (the grid 2^-32 for a pair within 1 m of
// the origin): every snapped coordinate, the offset and each sum are then multiples of the grid
// below 2^k, hence doubles. Exact predicates see the same question, so the Filtered verdict and
// labels must not change. Far from the origin the double filters fail more often; that is the
// point. Snapping may collapse a sliver (nothing to translate).
void Case::check_translation() {
  constexpr Vector2 offset{0x1p20, -0x1p20};
  double largest = 0.0;
  for (const auto* poly : {&pair_.cp, &pair_.tp}) {
    for (const Point2& p : *poly) largest = std::max({largest, std::fabs(p.x), std::fabs(p.y)});
  }
  // One bit to spare above the sum's magnitude: snapping may round a coordinate up.
  const int k = std::ilogb(largest + 0x1p20) + 2;
  const auto snapped = snap_to_grid(pair_, k - 53);
  if (!snapped) return;
  const auto moved = translate_exactly(*snapped, offset);
  if (!moved) {
    violated(Property::translation, "translation by 2^20 of the snapped pair was not exact");
    return;
  }
  const Polygons here = make_polygons(*snapped);
  const Polygons there = make_polygons(*moved);
  rk::compute_intersection_polygon<Filtered>(here.cp, here.tp, w_.ip_other, w_.clip);
  rk::compute_intersection_polygon<Filtered>(there.cp, there.tp, w_.ip_other_exact, w_.clip);
  if (rk::classify_overlap<Filtered>(here.cp, here.tp) != rk::classify_overlap<Filtered>(there.cp, there.tp) ||
      !same_labels(w_.ip_other, w_.ip_other_exact)) {
    violated(Property::translation, "verdict or IP labels changed by the exact translation (2^20, -2^20)");
  }
}

// Under Filtered each pair's force is within its force_bound of its Exact force, and the Exact
// force of the rotated pair is the rotated Exact force (check_exact_force), so the two Filtered
// forces differ by at most the sum of the two bounds. The Exact points of the rotated IP are
// the rotated Exact points: rounding to nearest commutes with negation.
void Case::check_rotation() {
  rk::compute_intersection_polygon<Filtered>(rotated_.cp, rotated_.tp, w_.ip_other, w_.clip);
  if (rk::classify_overlap<Filtered>(rotated_.cp, rotated_.tp) != filtered_ ||
      !same_labels(w_.ip_other, w_.ip_filtered)) {
    violated(Property::rotation, "verdict or IP labels changed by the rotation (x, y) -> (-y, x)");
    return;
  }
  contact::evaluate_pair<Filtered>(rotated_.cp, rotated_.tp, params_, w_.pair, w_.rotated);
  w_.points_other.clear();
  for (const Point2& p : w_.points_exact) w_.points_other.push_back(rotate90(p));
  const double bound = forward_bound_ + force_bound(rotated_.cp, rotated_.tp, w_.ip_exact, w_.rotated.ip,
                                                    w_.points_other, params_);
  if (!(max_error(w_.rotated.force, rotate90(w_.forward.force)) <= bound)) {
    violated(Property::rotation, "Filtered force of the rotated pair is not the rotated force within the bounds");
  }
}

// f_TP = ∮(phi_TP - phi_CP) n dL over the same IP (the same point set, strictly convex, hence the
// same vertices) is -f_CP, in either demarcation mode (both polygons' points are merged on every
// IP edge). Under Filtered each order is within its force_bound of its exact value.
void Case::check_swap() {
  if (rk::classify_overlap<Filtered>(polys_.tp, polys_.cp) != filtered_) {
    violated(Property::swap, "verdict not symmetric under swapping cp and tp");
    return;
  }
  contact::evaluate_pair<Filtered>(polys_.tp, polys_.cp, params_, w_.pair, w_.swapped);
  if (w_.swapped.status != w_.forward.status) {
    violated(Property::swap, "evaluate_pair status not symmetric");
    return;
  }
  rk::construct_points<Exact>(polys_.tp, polys_.cp, w_.swapped.ip_features, w_.points_other);
  const double bound = forward_bound_ + force_bound(polys_.tp, polys_.cp, w_.swapped.ip_features,
                                                    w_.swapped.ip, w_.points_other, params_);
  const Vector2 sum{w_.forward.force.x + w_.swapped.force.x, w_.forward.force.y + w_.swapped.force.y};
  if (!(max_error(sum, {}) <= bound)) {
    violated(Property::swap, "Filtered f(tp, cp) != -f(cp, tp) within the bounds");
  }
}

// ## Continuity at touch
// CP and TP touch (interiors disjoint). Push TP by t = h d. Any p in IP = CP ∩ (TP + t):
//   * p - t is in TP, outside int CP, so the segment p -> p - t leaves CP: d_CP(p) <= |t|;
//   * p is in CP, outside int TP, so p + t is outside int(TP + t): d_TP'(p) <= |t|;
// hence |g| = |d_CP - d_TP'| <= h |d| on the IP and
//   |f| = (kn/H) |∮ g n dL| <= (kn/H) h |d| perimeter(IP) <= (kn/H) h |d| min(perimeter(CP), perimeter(TP))
// (a convex subset has the smaller perimeter). Also f = (kn/H) ∫_IP grad g dA with |grad g| <= 2,
// so |f| <= 2 (kn/H) area(IP). The force therefore vanishes at least linearly in h: no jump at
// touch. The exact demarcation integrates g without error, so Exact's force obeys these bounds
// and Filtered's obeys them plus force_bound. d points from TP's vertex mean to CP's: for
// touching polygons 0 is on the boundary of the convex set CP - TP of translations that make
// them overlap and this difference of interior points is inside it, so small pushes along d
// overlap (rounding d to multiples of 2^-8 can tilt it out of a very thin cone of overlap
// directions; the bound then still holds with a zero force, and the overlap count shows it).
void Case::check_touch_continuity() {
  if (exact_ != Overlap::touch) return;
  if (!(w_.forward.force == Vector2{})) violated(Property::touch_continuity, "a touching pair has a force");
  const Point2 a = vertex_mean(pair_.cp), b = vertex_mean(pair_.tp);
  const double cx = a.x - b.x, cy = a.y - b.y;
  // Equal means would be a common interior point: impossible for touching polygons, unless
  // the rounding of two means of a sliver coincided; nothing to push along then.
  if (cx == 0.0 && cy == 0.0) return;
  const double scale = 256.0 / std::max(std::fabs(cx), std::fabs(cy));
  const Vector2 d{std::round(cx * scale) / 256.0, std::round(cy * scale) / 256.0};
  constexpr std::array<double, 3> steps{0x1p-8, 0x1p-16, 0x1p-24};
  const auto pushable = [&](const PolygonPair& pair) {
    return std::all_of(steps.begin(), steps.end(),
                       [&](double h) { return push_tp(pair, {h * d.x, h * d.y}).has_value(); });
  };
  // Offsets are multiples of 2^-32 m: exact on the generators' grids (2^-50 below 4 m, 2^-33
  // for the far pairs); other pairs are snapped to 2^-40 first and kept only if still touching.
  std::optional<PolygonPair> snapped;
  const PolygonPair* base = &pair_;
  if (!pushable(pair_)) {
    snapped = snap_to_grid(pair_, -40);
    if (!snapped || !pushable(*snapped)) return;
    const Polygons s = make_polygons(*snapped);
    if (rk::classify_overlap<Exact>(s.cp, s.tp) != Overlap::touch) return;
    base = &*snapped;
  }
  for (const double h : steps) {
    if (!push_and_check(make_polygons(*push_tp(*base, {h * d.x, h * d.y})), h, std::hypot(d.x, d.y))) return;
  }
}

bool Case::push_and_check(const Polygons& pushed, double h, double direction_length) {
  PairResult& r = w_.pushed;
  contact::evaluate_pair<Filtered>(pushed.cp, pushed.tp, params_, w_.pair, r);
  rk::compute_intersection_polygon<Exact>(pushed.cp, pushed.tp, w_.ip_other_exact, w_.clip);
  if (!same_labels(r.ip_features, w_.ip_other_exact)) {
    fail(stats_.filtered_ip, "IP labels: Filtered != Exact on a touching pair pushed into contact");
    return false;
  }
  ++stats_.touch_pushes;
  if (r.status != Overlap::overlap) return true;
  ++stats_.touch_push_overlaps;
  if (!exact_vertices(pushed.cp, pushed.tp, r.ip_features, w_.exact_ip)) return true;
  const double area = mpq_class(twice_area(w_.exact_ip) / 2).get_d();
  rk::construct_points<Exact>(pushed.cp, pushed.tp, r.ip_features, w_.points_other);
  const double rounding = force_bound(pushed.cp, pushed.tp, r.ip_features, r.ip, w_.points_other, params_);
  const double kn_h = params_.kn / params_.H;
  const double linear = kn_h * h * direction_length * std::min(perimeter(pushed.cp), perimeter(pushed.tp));
  const double bound = std::min(2.0 * kn_h * area, linear) * bound_slack + rounding;
  const double magnitude = std::max(std::fabs(r.force.x), std::fabs(r.force.y));
  stats_.worst_continuity_ratio = std::max(stats_.worst_continuity_ratio, magnitude / linear);
  if (!(magnitude <= bound)) {
    violated(Property::touch_continuity,
             "force of a pushed touching pair above (kn/H) min(2 area, h |d| perimeter)");
  }
  return true;
}

void Case::check_exact_force() {
  PairResult& e = w_.exact;
  const PairResult& f = w_.forward;
  contact::evaluate_pair<Exact>(polys_.cp, polys_.tp, params_, w_.pair, e);
  if (e.status != f.status || !same_labels(e.ip_features, f.ip_features)) {
    fail(stats_.filtered_ip, "evaluate_pair: Filtered and Exact differ in status or IP");
    return;
  }
  if (e.status != Overlap::overlap) {
    if (!(f.force == Vector2{}) || !(e.force == Vector2{})) fail(stats_.filtered_force, "a force without overlap");
    return;
  }
  ++stats_.exact_force_cases;
  const double error = max_error(f.force, e.force);
  stats_.worst_force_ratio = std::max(stats_.worst_force_ratio, ratio(error, forward_bound_));
  if (!(error <= forward_bound_)) fail(stats_.filtered_force, "Filtered force exceeds force_bound");

  // Every step under Exact is rational except the edge lengths, the same 256-bit square roots
  // in the rotated and swapped pairs (rotation and swap keep each edge's squared length), so
  // the rounded forces are exactly rotated and negated.
  contact::evaluate_pair<Exact>(rotated_.cp, rotated_.tp, params_, w_.pair, w_.exact_other);
  if (!(w_.exact_other.force == rotate90(e.force)) || w_.exact_other.area != e.area) {
    violated(Property::rotation, "Exact force of the rotated pair is not the rotated force, bitwise");
  }
  contact::evaluate_pair<Exact>(polys_.tp, polys_.cp, params_, w_.pair, w_.exact_other);
  if (!(w_.exact_other.force == Vector2{-e.force.x, -e.force.y}) || w_.exact_other.area != e.area) {
    violated(Property::swap, "Exact f(tp, cp) != -f(cp, tp) bitwise, or the areas differ");
  }

  PotentialContactParams paper = params_;
  paper.demarcation = rk::Demarcation::paper;
  contact::evaluate_pair<Exact>(polys_.cp, polys_.tp, paper, w_.pair, w_.exact_other);
  const double magnitude = std::hypot(e.force.x, e.force.y);
  if (magnitude > 0.0) {
    const Vector2 diff{w_.exact_other.force.x - e.force.x, w_.exact_other.force.y - e.force.y};
    stats_.paper_error.push_back(std::hypot(diff.x, diff.y) / magnitude);
  }
}

void run_case(const CampaignOptions& options, Family family, std::uint64_t index, Work& work, FamilyStats& stats) {
  ++stats.cases;
  std::optional<PolygonPair> pair;
  try {
    pair = generate_pair(family, options.seed, index);
    Case(options, stats, work, *pair).run(index % options.exact_force_stride == 0);
  } catch (const rk::PolicyDisagreement& error) {
    ++stats.filtered_verdict;
    if (stats.reproducers.size() < options.reproducers_per_family) {
      stats.reproducers.push_back(reproducer(error.what(), *pair));
    }
  } catch (const std::exception& error) {
    ++stats.crashes;
    if (stats.reproducers.size() < options.reproducers_per_family) {
      const std::string what = std::string("exception: ") + error.what();
      stats.reproducers.push_back(pair ? reproducer(what, *pair)
                                       : what + ": " + std::string(to_string(family)) + " seed " +
                                             std::to_string(options.seed) + " index " + std::to_string(index));
    }
  }
}

void merge(FamilyStats& into, const FamilyStats& part, std::size_t reproducer_limit) {
  into.cases += part.cases;
  for (std::size_t i = 0; i < into.verdicts.size(); ++i) into.verdicts[i] += part.verdicts[i];
  into.float_verdict += part.float_verdict;
  into.float_ip += part.float_ip;
  into.float_inconsistent += part.float_inconsistent;
  into.float_exceptions += part.float_exceptions;
  into.filtered_verdict += part.filtered_verdict;
  into.filtered_ip += part.filtered_ip;
  into.filtered_points += part.filtered_points;
  into.filtered_force += part.filtered_force;
  into.crashes += part.crashes;
  for (std::size_t i = 0; i < property_count; ++i) into.violations[i] += part.violations[i];
  into.filtered_counters += part.filtered_counters;
  into.crossings += part.crossings;
  into.exact_force_cases += part.exact_force_cases;
  into.worst_crossing_ratio = std::max(into.worst_crossing_ratio, part.worst_crossing_ratio);
  into.worst_force_ratio = std::max(into.worst_force_ratio, part.worst_force_ratio);
  into.touch_pushes += part.touch_pushes;
  into.touch_push_overlaps += part.touch_push_overlaps;
  into.worst_continuity_ratio = std::max(into.worst_continuity_ratio, part.worst_continuity_ratio);
  into.paper_error.insert(into.paper_error.end(), part.paper_error.begin(), part.paper_error.end());
  into.seconds += part.seconds;
  for (const std::string& r : part.reproducers) {
    if (into.reproducers.size() < reproducer_limit) into.reproducers.push_back(r);
  }
}

struct Unit {
  std::size_t family_slot;
  std::size_t begin;
  std::size_t end;
};

}  // namespace

std::size_t FamilyStats::property_violations() const {
  std::size_t sum = 0;
  for (std::size_t v : violations) sum += v;
  return sum;
}

double FamilyStats::interval_fallback_rate() const {
  const std::uint64_t calls = filtered_counters.total_calls();
  return calls == 0 ? 0.0
                    : static_cast<double>(filtered_counters.total_interval_fallbacks()) / static_cast<double>(calls);
}

double FamilyStats::fallback_rate() const {
  const auto calls = filtered_counters.total_calls();
  return calls == 0 ? 0.0 : static_cast<double>(filtered_counters.total_fallbacks()) / static_cast<double>(calls);
}

double FamilyStats::paper_error_max() const {
  return paper_error.empty() ? 0.0 : *std::max_element(paper_error.begin(), paper_error.end());
}

double FamilyStats::paper_error_median() const {
  if (paper_error.empty()) return 0.0;
  std::vector<double> sorted = paper_error;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  return n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

double FamilyStats::paper_error_p99() const {
  if (paper_error.empty()) return 0.0;
  std::vector<double> sorted = paper_error;
  std::sort(sorted.begin(), sorted.end());
  return sorted[(sorted.size() - 1) * 99 / 100];
}

std::size_t FamilyStats::paper_error_nonzero() const {
  return static_cast<std::size_t>(std::count_if(paper_error.begin(), paper_error.end(), [](double e) { return e != 0.0; }));
}

FamilyStats CampaignResult::total() const {
  FamilyStats sum;
  for (const FamilyStats& f : families) merge(sum, f, 0);
  return sum;
}

CampaignResult run_campaign(const CampaignOptions& options) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const std::size_t chunk = std::max<std::size_t>(options.chunk, 1);
  std::vector<Unit> units;
  for (std::size_t slot = 0; slot < options.families.size(); ++slot) {
    for (std::size_t begin = 0; begin < options.cases_per_family; begin += chunk) {
      units.push_back({slot, begin, std::min(begin + chunk, options.cases_per_family)});
    }
  }
  std::vector<FamilyStats> parts(units.size());
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    Work work;
    for (std::size_t i = next++; i < units.size(); i = next++) {
      const Unit& unit = units[i];
      const Family family = options.families[unit.family_slot];
      const Clock::time_point unit_start = Clock::now();
      for (std::size_t index = unit.begin; index < unit.end; ++index) {
        run_case(options, family, index, work, parts[i]);
      }
      parts[i].seconds = std::chrono::duration<double>(Clock::now() - unit_start).count();
    }
  };
  const unsigned threads = std::max(1u, options.threads);
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();

  // Merged in unit order, so counts, maxima, samples and reproducers do not depend on which
  // thread ran which unit.
  CampaignResult result;
  result.options = options;
  for (Family family : options.families) {
    result.families.emplace_back();
    result.families.back().family = family;
  }
  for (std::size_t i = 0; i < units.size(); ++i) {
    merge(result.families[units[i].family_slot], parts[i], options.reproducers_per_family);
  }
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

namespace {

std::string table_row(std::string_view name, const FamilyStats& s) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "| %s | %zu | %zu / %zu | %zu | %zu | %.2e / %.2e | %.2e / %.2e (%zu) | %zu | %.1f |\n",
                std::string(name).c_str(), s.cases, s.float_verdict, s.float_ip + s.float_exceptions,
                s.filtered_disagreements(), s.crashes, s.interval_fallback_rate(), s.fallback_rate(),
                s.paper_error_max(),
                s.paper_error_median(), s.paper_error.size(), s.property_violations(), s.seconds);
  return buffer;
}

std::string details_row(std::string_view name, const FamilyStats& s) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "| %s | %zu | %zu | %zu | %zu | %zu | %zu | %.2e | %.2e | %.2e | %zu (%zu) | %.2e | %zu | %zu |\n",
                std::string(name).c_str(), s.verdicts[0], s.verdicts[1], s.verdicts[2], s.crossings,
                s.exact_force_cases, s.paper_error_nonzero(), s.paper_error_p99(), s.worst_crossing_ratio,
                s.worst_force_ratio, s.touch_pushes,
                s.touch_push_overlaps, s.worst_continuity_ratio, s.float_inconsistent, s.float_exceptions);
  return buffer;
}

}  // namespace

std::string format_table(const CampaignResult& result) {
  std::string out =
      "| family | cases | Float disagreements (verdict / IP) | Filtered disagreements | crashes | "
      "fallback rate (interval / exact) | paper-vs-exact force error: max rel / median rel (samples) | property violations | "
      "seconds |\n|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const FamilyStats& f : result.families) out += table_row(to_string(f.family), f);
  out += table_row("**total**", result.total());
  char buffer[256];
  std::snprintf(buffer, sizeof buffer,
                "\nseed %llu, %zu cases per family, Exact force on every %zu-th case, %u thread(s), "
                "%.1f s wall (the seconds column is thread time)\n",
                static_cast<unsigned long long>(result.options.seed), result.options.cases_per_family,
                result.options.exact_force_stride, result.options.threads, result.wall_seconds);
  return out + buffer;
}

std::string format_details(const CampaignResult& result) {
  std::string out =
      "| family | separate | touch | overlap | crossings | Exact forces | paper != exact | paper-vs-exact p99 | "
      "worst crossing err/bound | "
      "worst force err/bound | touch pushes (overlapping) | worst |f| / ((kn/H) h |d| P) | Float IP "
      "contradicts its verdict | Float exceptions |\n|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const FamilyStats& f : result.families) out += details_row(to_string(f.family), f);
  out += details_row("**total**", result.total());
  for (const FamilyStats& f : result.families) {
    for (std::size_t i = 0; i < property_count; ++i) {
      if (f.violations[i] == 0) continue;
      out += std::string(to_string(f.family)) + ": " + std::to_string(f.violations[i]) + " violations of " +
             std::string(to_string(static_cast<Property>(i))) + "\n";
    }
    for (const std::string& r : f.reproducers) out += "reproducer: " + r + "\n";
  }
  return out;
}

}  // namespace rockcontact::robustness
