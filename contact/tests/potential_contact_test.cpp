#define BOOST_TEST_MODULE contact_potential_contact
#include <boost/test/unit_test.hpp>

#include "rockcontact/testing/contact2d.hpp"
#include "rockcontact/testing/seed.hpp"

// Potential contact of a pair (seed 000 §3.2, eq. 11-20) against independent references:
//   (a) closed forms for overlapping axis-aligned rectangles, derived below by hand;
//   (b) Newton's third law, evaluate_pair(cp, tp) = -evaluate_pair(tp, cp);
//   (c) invariance under translation by 1e6 m and rotation by 90 degrees;
//   (d) the independent contact2d reference data (robustness_tests/data/contact2d);
//   (e) the paper demarcation mode: equal to the exact mode on triangles, and its known
//       deficit on a rectangle, in closed form.
//
// ## The closed form for rectangles (used by (a) and (e))
// eq. 11 is the boundary form of eq. 10: by the gradient theorem (phi is Lipschitz)
//   f = ∮_{∂IP} (phi_CP - phi_TP) n dL = ∫_IP (∇phi_CP - ∇phi_TP) dA,
// and likewise the moment of the boundary load about the IP centroid c,
//   M = ∮ (x - c) × (g n) dL = ∫_IP (x - c) × ∇g dA,   g = phi_CP - phi_TP,
// since ∮ ((x-c)_x n_y - (x-c)_y n_x) g dL = ∫ ((x-c)_x ∂_y g - (x-c)_y ∂_x g) dA.
// For a rectangle, d_exit = min(x - x0, x1 - x, y - y0, y1 - y), so ∇d_exit is the inward unit
// normal of the nearest edge: constant on the four regions cut out by the medial axis (the 45°
// corner bisectors and the central segment). Hence, with kn/H factored out,
//   f = Σ_regions R of CP  |IP ∩ R| ν_R  -  Σ_regions R of TP  |IP ∩ R| ν_R,
//   M = Σ_R of CP |IP ∩ R| (centroid(IP ∩ R) - c) × ν_R  -  (same over TP),
// with ν_R the region's inward normal. The loading point is the foot of the perpendicular from
// c to the line of action {x : (x - c) × f = M} (§3.2.4): pg = c + λ (-f_y, f_x) with
// λ = -M / |f|² (then (pg - c) × f = -λ |f|² = M).
//
// Case "corner": CP = [0,2]×[0,1], TP = [1.25,4]×[0.25,2], IP = [1.25,2]×[0.25,1], area 9/16,
// c = (13/8, 5/8). CP's medial axis runs from (2,0) and (2,1) at 45° to (1.5,0.5) and along
// y = 0.5 to the left. Inside IP:
//   right region  (x >= 2 - y for y <= 1/2, x >= 1 + y above): (7/4,1/4) (2,1/4) (2,1) (3/2,1/2),
//                 area 7/32, ν = (-1, 0);
//   bottom region (1.25,1/4) (7/4,1/4) (3/2,1/2) (5/4,1/2), area 3/32, ν = (0, 1);
//   top region    (5/4,1/2) (3/2,1/2) (2,1) (5/4,1), area 1/4, ν = (0, -1).
// TP (2.75 × 1.75) near its corner (1.25, 0.25): IP lies within 0.75 < 0.875 (half height) of
// its left and bottom edges and at least 1 from the others, so the diagonal y - 1/4 = x - 5/4
// splits it: above, triangle (5/4,1/4) (2,1) (5/4,1), 9/32, ν = (1, 0); below, triangle
// (5/4,1/4) (2,1/4) (2,1), 9/32, ν = (0, 1).
//   f = (-7/32, 3/32 - 1/4) - (9/32, 9/32) = (-1/2, -7/16);   M = -1/128 (region centroids
//   above), |f|² = 113/256, λ = 2/113, pg = (369/226, 557/904).
// Case "strip" (thin overlap along CP's top side): CP = [0,2]×[0,1], TP = [0.5,3]×[0.875,2],
// IP = [0.5,2]×[0.875,1], area 3/16, c = (5/4, 15/16).
//   CP: right corner triangle (15/8,7/8) (2,7/8) (2,1), 1/128, ν = (-1,0); the rest of IP is
//   in the top region, 23/128, ν = (0,-1). TP: left corner triangle (1/2,7/8) (5/8,1) (1/2,1),
//   1/128, ν = (1,0); the rest in its bottom region, 23/128, ν = (0,1).
//   f = (-1/128, -23/128) - (1/128, 23/128) = (-1/64, -23/64); M = 0 (the two corner triangles
//   and the two remainders balance about c), pg = c.
// Case "half" (TP covers CP's right half up to y = 0.75): CP = [0,2]×[0,1],
// TP = [1,3]×[-1,0.75], IP = [1,2]×[0,0.75], area 3/4, c = (3/2, 3/8).
//   CP: right region (2,0) (2,3/4) (7/4,3/4) (3/2,1/2), 7/32, ν = (-1,0); bottom region
//   (1,0) (2,0) (3/2,1/2) (1,1/2), 3/8, ν = (0,1); top region (1,1/2) (3/2,1/2) (7/4,3/4)
//   (1,3/4), 5/32, ν = (0,-1). TP (2 × 1.75): its left edge x = 1 and top edge y = 0.75 are
//   the nearest in IP (bottom and right are at least 1 away): left triangle (1,0) (7/4,0)
//   (1,3/4), 9/32, ν = (1,0); the rest 15/32, ν = (0,-1).
//   f = (-7/32, 3/8 - 5/32) - (9/32, -15/32) = (-1/2, 11/16); M = 5/128, |f|² = 185/256,
//   λ = -2/37, pg = (455/296, 119/296).
//   Boundary check of the same case: the IP edges give, with kn/H factored out, left x = 1:
//   ∫0^0.75 min(y, 1-y) dy (-1,0) = (-7/32, 0); top: ∫1^2 min(2-x, 1/4) dx (0,1) = (0, 7/32);
//   right: -∫0^0.75 (3/4 - y) dy (1,0) = (-9/32, 0); bottom: -∫1^2 min(x-1, 3/4) dx (0,-1) =
//   (0, 15/32). Sum (-1/2, 11/16).
// Paper demarcation on "half": on the left edge x = 1 the kink of min(y, 1-y) at y = 1/2 lies
// on CP's central medial-axis segment, which no bisector ray represents; the paper points there
// are the ends and the centre y = 3/8 only, and the trapezoid rule gives
// (3/8)(0 + 3/8)/2 + (3/8)(3/8 + 1/4)/2 = 3/16 instead of 7/32. Every other kink of "half" is on
// a corner bisector. So f_paper = f + (1/32, 0) = (-15/32, 11/16).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/contact/potential2d/potential_contact.hpp"

namespace rc = rockcontact::contact;
namespace rk = rockcontact::kernel;
using rk::ConvexPolygon;
using rk::Demarcation;
using rk::Overlap;
using rk::Point2;
using rk::PolicyKind;
using rk::Vector2;

namespace {

using rockcontact::testing::seed_for;

constexpr double u = rockcontact::testing::unit_roundoff;

ConvexPolygon rectangle(const std::string& name, double x0, double x1, double y0, double y1) {
  return ConvexPolygon::make(name, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

rc::PotentialContactParams params(double kn, double H, Demarcation mode = Demarcation::exact) {
  rc::PotentialContactParams p = rc::default_potential_contact_params();
  p.kn = kn;
  p.H = H;
  p.demarcation = mode;
  return p;
}

double distance(const Point2& a, const Point2& b) { return std::hypot(a.x - b.x, a.y - b.y); }

// `actual` equals `expected` up to the start vertex, vertex by vertex within tol (both CCW).
bool same_shape(const std::vector<Point2>& actual, const std::vector<Point2>& expected, double tol) {
  if (actual.size() != expected.size()) return false;
  for (std::size_t s = 0; s < expected.size(); ++s) {
    bool all = true;
    for (std::size_t k = 0; k < actual.size() && all; ++k) {
      all = distance(actual[k], expected[(s + k) % expected.size()]) <= tol;
    }
    if (all) return true;
  }
  return actual.empty();
}

std::string policy_name(PolicyKind p) { return std::string(rk::to_string(p)); }

struct ClosedForm {
  std::string name;
  ConvexPolygon cp, tp;
  std::vector<Point2> ip;
  double area;
  Vector2 force;  // divided by kn / H
  Point2 point;
};

std::vector<ClosedForm> closed_forms() {
  return {
      {"corner", rectangle("CP", 0, 2, 0, 1), rectangle("TP", 1.25, 4, 0.25, 2),
       {{1.25, 0.25}, {2, 0.25}, {2, 1}, {1.25, 1}}, 9.0 / 16, {-1.0 / 2, -7.0 / 16}, {369.0 / 226, 557.0 / 904}},
      {"strip", rectangle("CP", 0, 2, 0, 1), rectangle("TP", 0.5, 3, 0.875, 2),
       {{0.5, 0.875}, {2, 0.875}, {2, 1}, {0.5, 1}}, 3.0 / 16, {-1.0 / 64, -23.0 / 64}, {5.0 / 4, 15.0 / 16}},
      {"half", rectangle("CP", 0, 2, 0, 1), rectangle("TP", 1, 3, -1, 0.75),
       {{1, 0}, {2, 0}, {2, 0.75}, {1, 0.75}}, 3.0 / 4, {-1.0 / 2, 11.0 / 16}, {455.0 / 296, 119.0 / 296}},
  };
}

// Random convex polygon on the 2^-10 grid (so that moving it by 1e6 or turning it by 90
// degrees is exact): points on an ellipse at sorted random angles, rounded, retried until
// strictly convex.
ConvexPolygon dyadic_convex(std::mt19937_64& rng, const std::string& name, Point2 centre, double size) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (;;) {
    const int n = 3 + static_cast<int>(unit(rng) * 6);
    std::vector<double> angle(n);
    for (double& x : angle) x = 6.283185307179586 * unit(rng);
    std::sort(angle.begin(), angle.end());
    const double ra = size * (0.5 + unit(rng)), rb = size * (0.5 + unit(rng)), tilt = 3.14 * unit(rng);
    std::vector<Point2> v;
    for (double x : angle) {
      const double px = ra * std::cos(x), py = rb * std::sin(x);
      v.push_back({std::round((centre.x + px * std::cos(tilt) - py * std::sin(tilt)) * 1024) / 1024,
                   std::round((centre.y + px * std::sin(tilt) + py * std::cos(tilt)) * 1024) / 1024});
    }
    try {
      return ConvexPolygon::make(name, v);
    } catch (const rk::InvalidPolygon&) {
    }
  }
}

std::vector<std::pair<ConvexPolygon, ConvexPolygon>> random_overlapping_pairs(std::mt19937_64& rng, int count) {
  std::uniform_real_distribution<double> offset(-0.8, 0.8);
  std::vector<std::pair<ConvexPolygon, ConvexPolygon>> pairs;
  while (static_cast<int>(pairs.size()) < count) {
    ConvexPolygon cp = dyadic_convex(rng, "cp", {0, 0}, 0.6);
    ConvexPolygon tp = dyadic_convex(rng, "tp", {offset(rng), offset(rng)}, 0.5);
    if (rc::evaluate_pair(PolicyKind::exact, cp, tp).status == Overlap::overlap) pairs.emplace_back(cp, tp);
  }
  return pairs;
}

double size_of(const ConvexPolygon& a, const ConvexPolygon& b) {
  const auto diagonal = [](const ConvexPolygon& p) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const Point2& v : p.vertices()) {
      x0 = std::min(x0, v.x), x1 = std::max(x1, v.x), y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
    }
    return std::hypot(x1 - x0, y1 - y0);
  };
  return std::max(diagonal(a), diagonal(b));
}

ConvexPolygon moved(const ConvexPolygon& p, Point2 t) {
  std::vector<Point2> v;
  for (const Point2& q : p.vertices()) v.push_back({q.x + t.x, q.y + t.y});
  return ConvexPolygon::make(p.name(), v);
}

ConvexPolygon turned(const ConvexPolygon& p) {  // by +90 degrees: (x, y) -> (-y, x), exact
  std::vector<Point2> v;
  for (const Point2& q : p.vertices()) v.push_back({-q.y, q.x});
  return ConvexPolygon::make(p.name(), v);
}

}  // namespace

// (a) Closed forms, under Filtered and Exact with exact demarcation. All inputs and results
// are dyadic or short rationals and every step is a few roundings of O(1) numbers, so 1e-12
// relative (about 4500 u) is a loose bound.
BOOST_AUTO_TEST_CASE(rectangles_match_closed_form) {
  const double kn = 1e7, H = 0.5, scale = kn / H;
  for (const ClosedForm& c : closed_forms()) {
    for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
      const rc::PairResult r = rc::evaluate_pair(policy, c.cp, c.tp, params(kn, H));
      const std::string context = c.name + " " + policy_name(policy);
      BOOST_TEST_INFO(context);
      BOOST_TEST_REQUIRE((r.status == Overlap::overlap));
      BOOST_TEST_INFO(context);
      BOOST_TEST(same_shape(r.ip, c.ip, 1e-12));
      BOOST_TEST_INFO(context);
      BOOST_TEST(std::fabs(r.area - c.area) <= 1e-12 * c.area);
      const double f = std::hypot(c.force.x, c.force.y) * scale;
      BOOST_TEST_INFO(context << " force " << r.force.x << ", " << r.force.y);
      BOOST_TEST(std::fabs(r.force.x - c.force.x * scale) <= 1e-12 * f);
      BOOST_TEST_INFO(context << " force " << r.force.x << ", " << r.force.y);
      BOOST_TEST(std::fabs(r.force.y - c.force.y * scale) <= 1e-12 * f);
      BOOST_TEST_INFO(context);
      BOOST_TEST_REQUIRE(r.point.has_value());
      BOOST_TEST_INFO(context << " point " << r.point->x << ", " << r.point->y);
      BOOST_TEST(distance(*r.point, c.point) <= 1e-12 * size_of(c.cp, c.tp));
    }
  }
}

// (b) f_CP = ∮ (phi_CP - phi_TP) n dL over IP; swapping the roles swaps the two potentials
// over the same IP, so the force is exactly the negative and the line of action (hence the
// contact point, the foot of the perpendicular from the same centroid) is the same.
// Exact: the IP vertices are the same rationals, the edge lengths the same 256-bit roots, the
// sums differ only in order, so the rounded outputs are equal to the bit.
// Filtered: each evaluation sums O(10) pieces per IP edge, each bounded by (kn/H) size L_edge
// (Σ L_edge <= 4 size), with a few roundings each: error below ~1e-13 (kn/H) size², so
// 1e-12 (kn/H) size² for the sum of the two. The point moves by the moment error over |f|:
// 1e-12 size (1 + (kn/H) size² / |f|).
BOOST_AUTO_TEST_CASE(newtons_third_law) {
  std::mt19937_64 rng(seed_for("newtons_third_law", 20240801));
  std::vector<std::pair<ConvexPolygon, ConvexPolygon>> pairs = random_overlapping_pairs(rng, 60);
  for (const ClosedForm& c : closed_forms()) pairs.emplace_back(c.cp, c.tp);
  const double kn = 1e7, H = 1.0, scale = kn / H;
  int index = 0;
  for (const auto& [cp, tp] : pairs) {
    const double size = size_of(cp, tp);
    for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
      const rc::PairResult ab = rc::evaluate_pair(policy, cp, tp, params(kn, H));
      const rc::PairResult ba = rc::evaluate_pair(policy, tp, cp, params(kn, H));
      const std::string context = "pair " + std::to_string(index) + " " + policy_name(policy);
      BOOST_TEST_INFO(context);
      BOOST_TEST_REQUIRE((ab.status == Overlap::overlap && ba.status == Overlap::overlap));
      BOOST_TEST_INFO(context);
      BOOST_TEST(same_shape(ab.ip, ba.ip, policy == PolicyKind::exact ? 0.0 : 1e-12 * size));
      BOOST_TEST_REQUIRE((ab.point.has_value() && ba.point.has_value()));
      if (policy == PolicyKind::exact) {
        BOOST_TEST_INFO(context);
        BOOST_TEST((ab.force.x == -ba.force.x && ab.force.y == -ba.force.y));
        BOOST_TEST_INFO(context);
        BOOST_TEST((*ab.point == *ba.point));
        BOOST_TEST_INFO(context);
        BOOST_TEST(ab.area == ba.area);
      } else {
        const double f = std::hypot(ab.force.x, ab.force.y);
        BOOST_TEST_INFO(context << " f = " << ab.force.x << ", " << ab.force.y);
        BOOST_TEST(std::hypot(ab.force.x + ba.force.x, ab.force.y + ba.force.y) <= 1e-12 * scale * size * size);
        BOOST_TEST_INFO(context);
        BOOST_TEST(distance(*ab.point, *ba.point) <= 1e-12 * size * (1 + scale * size * size / f));
      }
    }
    ++index;
  }
}

// (c) Rigid motions that are exact on 2^-10-grid inputs: translation by (1e6, -1e6) and
// rotation by 90 degrees.
// Exact: every quantity is a function of coordinate differences (translation) or turns with
// the input (rotation), in exact rationals with the same 256-bit edge lengths, so the force is
// equal to the bit (rotated: (-f_y, f_x)), and the turned point is the turned point. The
// moved IP vertices and point are the exact ones plus (1e6, -1e6), rounded once there, while
// the reference is the rounded original plus (1e6, -1e6), rounded again: within one ulp of 1e6
// (2^-33) per coordinate, 1.5 ulp in distance.
// Filtered: the moved IP crossings are constructed at 1e6, within a few ulps of it unless the
// edges are nearly parallel (64 ulp allowed). Moving one IP vertex by δ changes
// f = ∫_IP ∇g dA by at most |∇g| <= 2 (kn/H) times the swept area <= 2 δ size:
// 64 ulp (kn/H) size n_IP in all. The point moves by the moment error over |f|, about that
// times size / |f|, plus a few ulps of its own rounding. The turned pair differs only by
// rounding: the (b) tolerances.
BOOST_AUTO_TEST_CASE(invariant_under_translation_and_rotation) {
  std::mt19937_64 rng(seed_for("invariant_under_translation_and_rotation", 20240802));
  std::vector<std::pair<ConvexPolygon, ConvexPolygon>> pairs = random_overlapping_pairs(rng, 40);
  for (const ClosedForm& c : closed_forms()) pairs.emplace_back(c.cp, c.tp);
  const double kn = 1e7, H = 1.0, scale = kn / H;
  const Point2 far{1e6, -1e6};
  const double ulp = 0x1p-33;  // spacing of doubles in [2^19, 2^20)
  int index = 0;
  for (const auto& [cp, tp] : pairs) {
    const double size = size_of(cp, tp);
    const ConvexPolygon cp_far = moved(cp, far), tp_far = moved(tp, far);
    const ConvexPolygon cp_turned = turned(cp), tp_turned = turned(tp);
    for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
      const rc::PairResult r = rc::evaluate_pair(policy, cp, tp, params(kn, H));
      const rc::PairResult rf = rc::evaluate_pair(policy, cp_far, tp_far, params(kn, H));
      const rc::PairResult rt = rc::evaluate_pair(policy, cp_turned, tp_turned, params(kn, H));
      const std::string context = "pair " + std::to_string(index) + " " + policy_name(policy);
      BOOST_TEST_INFO(context);
      BOOST_TEST_REQUIRE((r.status == Overlap::overlap && rf.status == Overlap::overlap && rt.status == Overlap::overlap));
      BOOST_TEST_REQUIRE((r.point && rf.point && rt.point));
      std::vector<Point2> ip_far, ip_turned;
      for (const Point2& p : r.ip) ip_far.push_back({p.x + far.x, p.y + far.y}), ip_turned.push_back({-p.y, p.x});
      const Point2 point_far{r.point->x + far.x, r.point->y + far.y}, point_turned{-r.point->y, r.point->x};
      const double f = std::hypot(r.force.x, r.force.y);
      const double n = static_cast<double>(r.ip.size());
      if (policy == PolicyKind::exact) {
        BOOST_TEST_INFO(context << " moved");
        BOOST_TEST((rf.force.x == r.force.x && rf.force.y == r.force.y));
        BOOST_TEST_INFO(context << " moved");
        BOOST_TEST(same_shape(rf.ip, ip_far, 1.5 * ulp));
        BOOST_TEST_INFO(context << " moved");
        BOOST_TEST(distance(*rf.point, point_far) <= 1.5 * ulp);
        BOOST_TEST_INFO(context << " turned");
        BOOST_TEST((rt.force.x == -r.force.y && rt.force.y == r.force.x));
        BOOST_TEST_INFO(context << " turned");
        BOOST_TEST(same_shape(rt.ip, ip_turned, 0.0));
        BOOST_TEST_INFO(context << " turned");
        BOOST_TEST((*rt.point == point_turned));
      } else {
        const double force_tol = 64 * ulp * scale * size * n;
        BOOST_TEST_INFO(context << " moved: f = " << rf.force.x << ", " << rf.force.y);
        BOOST_TEST(std::hypot(rf.force.x - r.force.x, rf.force.y - r.force.y) <= force_tol);
        BOOST_TEST_INFO(context << " moved");
        BOOST_TEST(same_shape(rf.ip, ip_far, 64 * ulp));
        BOOST_TEST_INFO(context << " moved");
        BOOST_TEST(distance(*rf.point, point_far) <= 4 * ulp + force_tol / f * size);
        BOOST_TEST_INFO(context << " turned");
        BOOST_TEST(std::hypot(rt.force.x + r.force.y, rt.force.y - r.force.x) <= 1e-12 * scale * size * size);
        BOOST_TEST_INFO(context << " turned");
        BOOST_TEST(same_shape(rt.ip, ip_turned, 1e-12 * size));
        BOOST_TEST_INFO(context << " turned");
        BOOST_TEST(distance(*rt.point, point_turned) <= 1e-12 * size * (1 + scale * size * size / f));
      }
    }
    ++index;
  }
}

// (d) The contact2d reference data, computed independently in exact arithmetic (see its
// README). Tolerances as supplied with the data: status exact; IP vertices 1e-9 size (shapes
// from any start vertex); area 1e-9 size²; force 1e-9 max(|f|, 1e-6 (kn/H) size²); point
// 1e-9 size, absent exactly when the expected point is null. Filtered and Exact must meet
// them; Float disagreements in status and IP vertex count are counted and printed.
namespace {

struct ReferencePair {
  std::string id;
  ConvexPolygon cp, tp;
  nlohmann::json expected;
};

struct ReferenceData {
  double kn, H;
  std::vector<ReferencePair> pairs;
};

// The contact2d pairs as validated polygons.
const ReferenceData& reference_data() {
  static const ReferenceData data = [] {
    const rockcontact::testing::Contact2dData& raw = rockcontact::testing::contact2d_data();
    ReferenceData d{raw.kn, raw.H, {}};
    for (const auto& pair : raw.pairs) {
      d.pairs.push_back({pair.id, ConvexPolygon::make(pair.id + ".cp", pair.cp),
                         ConvexPolygon::make(pair.id + ".tp", pair.tp), pair.expected});
    }
    return d;
  }();
  return data;
}

}  // namespace

BOOST_AUTO_TEST_CASE(contact2d_reference_data) {
  const ReferenceData& data = reference_data();
  const double scale = data.kn / data.H;
  BOOST_TEST_MESSAGE("contact2d: " << data.pairs.size() << " pairs, kn = " << data.kn << " Pa, H = " << data.H << " m");
  int float_status = 0, float_ip = 0;
  for (const ReferencePair& ref : data.pairs) {
    const nlohmann::json& e = ref.expected;
    const double size = e.at("size").get<double>();
    const std::string status = e.at("status").get<std::string>();
    const std::vector<Point2> ip = rockcontact::testing::json_points(e.at("ip"));
    const Vector2 force{e.at("force").at(0).get<double>(), e.at("force").at(1).get<double>()};
    std::optional<Point2> point;
    if (!e.at("point").is_null()) point = Point2{e.at("point").at(0).get<double>(), e.at("point").at(1).get<double>()};
    for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
      const rc::PairResult r = rc::evaluate_pair(policy, ref.cp, ref.tp, params(data.kn, data.H));
      const std::string context = ref.id + " " + policy_name(policy);
      BOOST_TEST_INFO(context);
      BOOST_TEST(std::string(rk::to_string(r.status)) == status);
      BOOST_TEST_INFO(context);
      BOOST_TEST(same_shape(r.ip, ip, 1e-9 * size));
      BOOST_TEST_INFO(context << " area " << r.area);
      BOOST_TEST(std::fabs(r.area - e.at("area").get<double>()) <= 1e-9 * size * size);
      const double ftol = 1e-9 * std::max(std::hypot(force.x, force.y), 1e-6 * scale * size * size);
      BOOST_TEST_INFO(context << " force " << r.force.x << ", " << r.force.y);
      BOOST_TEST(std::hypot(r.force.x - force.x, r.force.y - force.y) <= ftol);
      BOOST_TEST_INFO(context << " point");
      BOOST_TEST(r.point.has_value() == point.has_value());
      if (r.point && point) {
        BOOST_TEST_INFO(context << " point " << r.point->x << ", " << r.point->y);
        BOOST_TEST(distance(*r.point, *point) <= 1e-9 * size);
      }
    }
    const rc::PairResult f = rc::evaluate_pair(PolicyKind::float_, ref.cp, ref.tp, params(data.kn, data.H));
    if (std::string(rk::to_string(f.status)) != status) {
      ++float_status;
      BOOST_TEST_MESSAGE("Float: " << ref.id << " status " << rk::to_string(f.status) << ", expected " << status);
    }
    if (f.ip.size() != ip.size()) {
      ++float_ip;
      BOOST_TEST_MESSAGE("Float: " << ref.id << " IP has " << f.ip.size() << " vertices, expected " << ip.size());
    }
  }
  BOOST_TEST_MESSAGE("Float disagreements: status " << float_status << ", IP vertex count " << float_ip << " of "
                                                    << data.pairs.size());
}

// Far from the origin: the contact2d pairs moved by (10^6, -10^6) m (each coordinate rounded
// once; Filtered and Exact see the same doubles). Filtered constructs in a frame near the pair
// (potential_integral.cpp), so its force matches Exact's to the rounding of the pair's own
// size: at most 1e-12 of the force (scaled as in contact2d_reference_data), the bound the
// origin's pairs meet with a margin (the worst, a near-parallel pair, is 4.2e-13 at the origin
// and moved by (10^6, 10^6) m alike). In global coordinates the shoelace sums and the crossing
// points kept the rounding of 10^6 m: up to 1e-7 of the force.
BOOST_AUTO_TEST_CASE(filtered_force_far_from_the_origin_matches_exact) {
  const ReferenceData& data = reference_data();
  const double scale = data.kn / data.H;
  std::size_t forces = 0;
  for (const ReferencePair& ref : data.pairs) {
    const auto far = [](const ConvexPolygon& p, const std::string& name) {
      std::vector<Point2> v;
      for (const Point2& q : p.vertices()) v.push_back({q.x + 1e6, q.y - 1e6});
      return ConvexPolygon::make(name, v);
    };
    const ConvexPolygon cp = far(ref.cp, ref.id + ".cp"), tp = far(ref.tp, ref.id + ".tp");
    const rc::PairResult f = rc::evaluate_pair(PolicyKind::filtered, cp, tp, params(data.kn, data.H));
    const rc::PairResult e = rc::evaluate_pair(PolicyKind::exact, cp, tp, params(data.kn, data.H));
    const double size = ref.expected.at("size").get<double>();
    BOOST_TEST_INFO(ref.id << " filtered " << f.force.x << ", " << f.force.y << " exact " << e.force.x << ", " << e.force.y);
    BOOST_TEST(std::hypot(f.force.x - e.force.x, f.force.y - e.force.y) <=
               1e-12 * std::max(std::hypot(e.force.x, e.force.y), 1e-6 * scale * size * size));
    forces += e.point ? 1 : 0;
  }
  BOOST_TEST(forces >= 50u);  // most reference pairs overlap: the test compares real forces
}

// Newton's third law on the reference pairs too (degenerate families included): under Exact
// the swapped evaluation is the exact negative (see newtons_third_law).
BOOST_AUTO_TEST_CASE(contact2d_pairs_swapped_exactly_opposite) {
  const ReferenceData& data = reference_data();
  for (const ReferencePair& ref : data.pairs) {
    const rc::PairResult ab = rc::evaluate_pair(PolicyKind::exact, ref.cp, ref.tp, params(data.kn, data.H));
    const rc::PairResult ba = rc::evaluate_pair(PolicyKind::exact, ref.tp, ref.cp, params(data.kn, data.H));
    BOOST_TEST_INFO(ref.id);
    BOOST_TEST((ab.status == ba.status));
    BOOST_TEST_INFO(ref.id << " f = " << ab.force.x << ", " << ab.force.y << " vs " << ba.force.x << ", " << ba.force.y);
    BOOST_TEST((ab.force.x == -ba.force.x && ab.force.y == -ba.force.y));
    BOOST_TEST_INFO(ref.id);
    BOOST_TEST((ab.point == ba.point));
  }
}

// (e) Paper demarcation. On triangles every medial-axis branch is a vertex bisector, which the
// paper's rays contain; extra points only split linear pieces, so the integral is the same:
// within the Filtered rounding of (b), and for Exact within a few ulps (the bisector
// directions carry the 256-bit roots, so a paper point sits 1e-70 off the exact kink).
// Triangles with an edge shorter than small_edge_fraction H exercise the virtual node.
BOOST_AUTO_TEST_CASE(paper_demarcation_equals_exact_on_triangles) {
  std::mt19937_64 rng(seed_for("paper_demarcation_equals_exact_on_triangles", 20240803));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double kn = 1e7, H = 1.0, scale = kn / H;
  const auto triangle = [&](const std::string& name, Point2 centre, double size) {
    for (;;) {
      std::vector<Point2> v;
      for (int k = 0; k < 3; ++k) v.push_back({centre.x + size * unit(rng), centre.y + size * unit(rng)});
      try {
        return ConvexPolygon::make(name, v, rk::VertexOrder::normalise);
      } catch (const rk::InvalidPolygon&) {
      }
    }
  };
  std::vector<std::pair<ConvexPolygon, ConvexPolygon>> pairs;
  while (pairs.size() < 80) {
    ConvexPolygon cp = triangle("cp", {0, 0}, 1.0);
    ConvexPolygon tp = triangle("tp", {0.5 * unit(rng), 0.5 * unit(rng)}, 0.8);
    if (rc::evaluate_pair(PolicyKind::exact, cp, tp).status == Overlap::overlap) pairs.emplace_back(cp, tp);
  }
  // Named: a triangle with a 0.05 m edge (< 0.1 H: a virtual node at the incentre).
  pairs.emplace_back(ConvexPolygon::make("short edge", {{0, 0}, {1, 0.3}, {0.98, 0.345}}),
                     ConvexPolygon::make("tp", {{0.5, 0.1}, {1.2, 0.2}, {0.6, 0.5}}));
  int index = 0;
  for (const auto& [cp, tp] : pairs) {
    const double size = size_of(cp, tp);
    for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
      const rc::PairResult exact = rc::evaluate_pair(policy, cp, tp, params(kn, H, Demarcation::exact));
      const rc::PairResult paper = rc::evaluate_pair(policy, cp, tp, params(kn, H, Demarcation::paper));
      const double f = std::hypot(exact.force.x, exact.force.y);
      const double tol = policy == PolicyKind::exact ? 8 * u * scale * size * size : 1e-12 * scale * size * size;
      BOOST_TEST_INFO("triangles " << index << " " << policy_name(policy) << ": exact " << exact.force.x << ", "
                                   << exact.force.y << " paper " << paper.force.x << ", " << paper.force.y);
      BOOST_TEST(std::hypot(paper.force.x - exact.force.x, paper.force.y - exact.force.y) <= tol);
      BOOST_TEST_REQUIRE((exact.point.has_value() && paper.point.has_value()));
      BOOST_TEST_INFO("triangles " << index << " " << policy_name(policy));
      BOOST_TEST(distance(*paper.point, *exact.point) <= 1e-12 * size * (1 + scale * size * size / f));
    }
    ++index;
  }
}

// The rectangle case "half" (derivation at the top): exact mode = closed form, paper mode =
// closed form + (1/32, 0) kn/H, i.e. 3.7 % of |f| in the x component only.
BOOST_AUTO_TEST_CASE(paper_demarcation_on_rectangle_misses_central_axis) {
  const ClosedForm half = closed_forms().at(2);
  BOOST_TEST_REQUIRE(half.name == "half");
  const double kn = 1e7, H = 1.0, scale = kn / H;
  for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
    const rc::PairResult exact = rc::evaluate_pair(policy, half.cp, half.tp, params(kn, H, Demarcation::exact));
    const rc::PairResult paper = rc::evaluate_pair(policy, half.cp, half.tp, params(kn, H, Demarcation::paper));
    const double f = std::hypot(half.force.x, half.force.y) * scale;
    BOOST_TEST_INFO(policy_name(policy));
    BOOST_TEST(std::fabs(exact.force.x - half.force.x * scale) <= 1e-12 * f);
    BOOST_TEST_INFO(policy_name(policy));
    BOOST_TEST(std::fabs(exact.force.y - half.force.y * scale) <= 1e-12 * f);
    BOOST_TEST_INFO(policy_name(policy) << " paper " << paper.force.x << ", " << paper.force.y);
    BOOST_TEST(std::fabs(paper.force.x - (half.force.x + 1.0 / 32) * scale) <= 1e-12 * f);
    BOOST_TEST_INFO(policy_name(policy) << " paper " << paper.force.x << ", " << paper.force.y);
    BOOST_TEST(std::fabs(paper.force.y - half.force.y * scale) <= 1e-12 * f);
    BOOST_TEST_MESSAGE("rectangle 'half', " << policy_name(policy) << ": paper demarcation differs from exact by "
                                            << std::hypot(paper.force.x - exact.force.x, paper.force.y - exact.force.y) / f * 100
                                            << " % of |f|");
  }
}

BOOST_AUTO_TEST_CASE(non_overlapping_pairs_have_no_force) {
  const ConvexPolygon cp = rectangle("cp", 0, 1, 0, 1);
  struct Case {
    std::string name;
    ConvexPolygon tp;
    Overlap status;
  };
  const std::vector<Case> cases{
      {"separate", rectangle("tp", 1.5, 2, 0, 1), Overlap::separate},
      {"touch edge on edge", rectangle("tp", 1, 2, 0.25, 0.75), Overlap::touch},
      {"touch vertex on vertex", rectangle("tp", 1, 2, 1, 2), Overlap::touch},
      {"touch vertex on edge", ConvexPolygon::make("tp", {{1, 0.5}, {2, 0}, {2, 1}}), Overlap::touch},
  };
  for (const Case& c : cases) {
    for (const PolicyKind policy : {PolicyKind::float_, PolicyKind::filtered, PolicyKind::exact}) {
      const rc::PairResult r = rc::evaluate_pair(policy, cp, c.tp, params(1e7, 1.0));
      BOOST_TEST_INFO(c.name << " " << policy_name(policy));
      BOOST_TEST((r.status == c.status));
      BOOST_TEST_INFO(c.name << " " << policy_name(policy));
      BOOST_TEST((r.ip.empty() && r.ip_features.empty() && r.area == 0.0 && r.force == Vector2{} && !r.point));
    }
  }
}

// (f) Two neighbours from a joint-set cut (seed 000 §6.1 geometry) whose shared edge ends at
// vertices rounded independently: the exact predicates find a genuine overlap, a sliver thinner
// than the rounding, whose constructed IP has two equal vertices and zero area in double. The
// contact must still be finite: the force at most (kn/H) times the sliver's thickness (below
// 2 ulp of the coordinates, 4e-15 m) times its perimeter (8 m), 3.2e-5 N/m for kn/H = 1e9; and
// a contact point on the sliver, within its bounding box.
BOOST_AUTO_TEST_CASE(sliver_overlap_thinner_than_rounding_stays_finite) {
  const ConvexPolygon cp = ConvexPolygon::make(
      "cp", {{12.997460632137537, 0.0}, {14.520600549966153, 0.0},
             {15.313125286178266, 4.49463112807708}, {13.525494897286952, 2.9946311280770814}});
  const ConvexPolygon tp = ConvexPolygon::make(
      "tp", {{14.637753767459932, 0.6644089124821909}, {16.42538415635125, 2.1644089124821932},
             {17.100755675069585, 5.994631128077082}, {15.313125286178266, 4.49463112807708}});
  for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
    BOOST_TEST_CONTEXT(policy_name(policy)) {
      const rc::PairResult r = rc::evaluate_pair(policy, cp, tp, params(2e9, 2.0));
      BOOST_TEST((r.status == Overlap::overlap));
      BOOST_TEST(std::isfinite(r.force.x));
      BOOST_TEST(std::isfinite(r.force.y));
      BOOST_TEST(std::hypot(r.force.x, r.force.y) <= 1e9 * 4e-15 * 8.0);
      if (r.point) {
        BOOST_TEST(r.point->x >= 14.637753767459932 - 1e-9);
        BOOST_TEST(r.point->x <= 15.313125286178266 + 1e-9);
        BOOST_TEST(r.point->y >= 0.6644089124821909 - 1e-9);
        BOOST_TEST(r.point->y <= 4.49463112807708 + 1e-9);
      }
    }
  }
}

// (g) Two pairs on which Filtered once disagreed with Exact (10^7-case campaign, seed 20261124),
// checked in both role orders against an independent oracle: the area form of eq. 11,
//   f = (kn/H) ∫_IP (∇d_CP - ∇d_TP) dA,
// where ∇d of a convex polygon is the inward unit normal of the nearest edge line, constant on
// the region {x : d_k(x) <= d_j(x) for all j} of edge k (a convex polygon: IP clipped by the
// bisector half-planes). So f = (kn/H) Σ_k |IP ∩ V_k^CP| ν_k - Σ_j |IP ∩ V_j^TP| ν_j, computed
// here by clipping in double: no demarcation, no envelope, no crossing construction of the
// kernel. Each region's area is a continuous function of its half-planes, so rounding moves it
// by a few ulps of the IP's area (~1e-16 m^2 here); the tolerance 1e-9 (kn/H) area(IP) is far
// above that and far below what the two faults cost (4e-2 and 3e-4 of the force).
//   lattice_touch 394832: lattice polygons (step 1/8 m) whose edge-distance lines meet three at
//     a time; the exact demarcation's envelope walk took a wrong line at such a point under
//     Filtered and Float: force (-1957838.93, -1586494.31) instead of (-2041520.22,
//     -1598448.78) N/m.
//   rotated 384916, swapped: the IP is cp itself, but cp's first edge lies along a tp edge to
//     within rounding, so its vertex 1 is the IP vertex "crossing of cp edge 0 with tp edge 2";
//     built in double that near-parallel crossing slid 3e-5 m along the tp edge and the IP lost
//     7.6e-6 m^2 (area 0.167258029 instead of 0.167265615).
namespace {

using Polygon = std::vector<Point2>;

// The part of `poly` where a x + b y + c >= 0 (Sutherland-Hodgman, one half-plane).
Polygon clip_half_plane(const Polygon& poly, double a, double b, double c) {
  Polygon out;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point2& p = poly[k];
    const Point2& q = poly[(k + 1) % poly.size()];
    const double fp = a * p.x + b * p.y + c, fq = a * q.x + b * q.y + c;
    if (fp >= 0) out.push_back(p);
    if ((fp > 0 && fq < 0) || (fp < 0 && fq > 0)) {
      const double t = fp / (fp - fq);
      out.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
    }
  }
  return out;
}

double shoelace_area(const Polygon& poly) {
  double twice = 0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point2& p = poly[k];
    const Point2& q = poly[(k + 1) % poly.size()];
    twice += p.x * q.y - p.y * q.x;
  }
  return twice / 2;
}

// Σ_k |region ∩ V_k| ν_k over the edges k of `poly` (ν_k its inward unit normal).
Vector2 nearest_edge_normal_integral(const ConvexPolygon& poly, const Polygon& region) {
  const std::size_t n = poly.size();
  std::vector<std::array<double, 3>> line(n);  // d_k(x) = a x + b y + c, unit normal (a, b)
  for (std::size_t k = 0; k < n; ++k) {
    const Point2 &p = poly[k], &q = poly[poly.next(k)];
    const double len = std::hypot(q.x - p.x, q.y - p.y);
    const double a = -(q.y - p.y) / len, b = (q.x - p.x) / len;
    line[k] = {a, b, -(a * p.x + b * p.y)};
  }
  Vector2 sum;
  for (std::size_t k = 0; k < n; ++k) {
    Polygon cell = region;
    for (std::size_t j = 0; j < n && !cell.empty(); ++j) {
      if (j != k) cell = clip_half_plane(cell, line[j][0] - line[k][0], line[j][1] - line[k][1], line[j][2] - line[k][2]);
    }
    const double area = cell.size() >= 3 ? shoelace_area(cell) : 0.0;
    sum.x += area * line[k][0];
    sum.y += area * line[k][1];
  }
  return sum;
}

Vector2 area_form_force(const ConvexPolygon& cp, const ConvexPolygon& tp, const Polygon& ip, double kn_over_h) {
  const Vector2 a = nearest_edge_normal_integral(cp, ip), b = nearest_edge_normal_integral(tp, ip);
  return {kn_over_h * (a.x - b.x), kn_over_h * (a.y - b.y)};
}

}  // namespace

BOOST_AUTO_TEST_CASE(campaign_disagreements_match_the_area_form) {
  struct Case {
    std::string name;
    Polygon cp, tp;
    Vector2 independent;  // the campaign's independent exact value (N/m), 0 if none was printed
  };
  const std::vector<Case> cases{
      {"lattice_touch_394832",
       {{0.125, 1}, {0.125, 0.5}, {0.375, 0}, {0.875, 0.125}, {0.75, 0.5}, {0.375, 1}},
       {{0.625, 0.25}, {1, 0.625}, {0.75, 1.125}, {0.25, 1.125}, {0.375, 0.25}},
       {-2041520.22, -1598448.78}},
      {"rotated_384916_swapped",
       {{0.98381236333282418, 0.5251086276796626}, {0.98103122165498879, 0.54221165052562981},
        {0.44247058457721161, 0.79359532052621629}, {0.1462627303319326, 0.69416141018537236},
        {0.17652634178160839, 0.45802029989432375}},
       {{-0.040657774262168739, 0.3858069530099727}, {0.98490767365121412, 0.4059127630904964},
        {0.98659350501065912, 0.50800560483369539}, {0.97546893829931847, 0.57641769621756422},
        {0.36509025584840959, 0.93798711007538649}, {-0.011580993937640088, 0.61194250590478316}},
       {}}};
  const double kn = 1e7, H = 1;
  for (const Case& c : cases) {
    for (const bool swapped : {false, true}) {
      const ConvexPolygon cp = ConvexPolygon::make("cp", swapped ? c.tp : c.cp);
      const ConvexPolygon tp = ConvexPolygon::make("tp", swapped ? c.cp : c.tp);
      const rc::PairResult exact = rc::evaluate_pair(PolicyKind::exact, cp, tp, params(kn, H));
      BOOST_TEST_REQUIRE((exact.status == Overlap::overlap));
      const Vector2 oracle = area_form_force(cp, tp, exact.ip, kn / H);
      const double tolerance = 1e-9 * (kn / H) * exact.area;
      const double sign = swapped ? -1.0 : 1.0;
      for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
        BOOST_TEST_CONTEXT(c.name << (swapped ? " swapped" : "") << ", " << policy_name(policy)) {
          const rc::PairResult r = rc::evaluate_pair(policy, cp, tp, params(kn, H));
          BOOST_TEST(r.ip_features.vertices == exact.ip_features.vertices);
          BOOST_TEST(std::fabs(r.area - exact.area) <= 1e-12 * exact.area);
          BOOST_TEST(std::fabs(r.force.x - oracle.x) <= tolerance);
          BOOST_TEST(std::fabs(r.force.y - oracle.y) <= tolerance);
          if (c.independent.x != 0.0) {  // printed to 0.01 N/m
            BOOST_TEST(std::fabs(r.force.x - sign * c.independent.x) <= 0.01);
            BOOST_TEST(std::fabs(r.force.y - sign * c.independent.y) <= 0.01);
          }
        }
      }
    }
  }
  // The swapped rotated pair's IP is cp: its area is cp's.
  const ConvexPolygon inner = ConvexPolygon::make("cp", cases[1].cp);
  const ConvexPolygon outer = ConvexPolygon::make("tp", cases[1].tp);
  const rc::PairResult r = rc::evaluate_pair(PolicyKind::filtered, inner, outer, params(kn, H));
  Polygon inner_vertices(inner.vertices().begin(), inner.vertices().end());
  BOOST_TEST(std::fabs(r.area - shoelace_area(inner_vertices)) <= 1e-15);
}

BOOST_AUTO_TEST_CASE(invalid_parameters_throw) {
  const ConvexPolygon cp = rectangle("cp", 0, 1, 0, 1), tp = rectangle("tp", 0.5, 2, 0, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const auto& [kn, H] : std::vector<std::pair<double, double>>{{0, 1}, {-1e7, 1}, {nan, 1}, {inf, 1}, {1e7, 0}, {1e7, -1}, {1e7, nan}, {1e7, inf}}) {
    BOOST_TEST_INFO("kn = " << kn << ", H = " << H);
    BOOST_CHECK_THROW(rc::evaluate_pair(PolicyKind::filtered, cp, tp, params(kn, H)), std::invalid_argument);
  }
}

// The method a simulation holds (PotentialContactMethod) is evaluate_pair under the policy it
// was made with: the same verdict, IP, force and point to the bit, under every policy, on
// random dyadic convex polygons and on a face-to-face pair. Its monitors against
// closed forms: two unit squares 0.25 apart along x are separated by 0.25 and do not
// penetrate; overlapping by 0.125 they penetrate by 0.125 (the minimum translation, along x,
// since the overlap is 1 high) and are not separated. Dyadic numbers: exact in double.
BOOST_AUTO_TEST_CASE(contact_method_is_evaluate_pair_under_its_policy) {
  std::mt19937_64 rng(seed_for("contact_method_is_evaluate_pair_under_its_policy", 20261125));
  std::vector<std::pair<ConvexPolygon, ConvexPolygon>> pairs{
      {rectangle("cp", 0, 1, 0, 1), rectangle("tp", 0.5, 2, 0.25, 0.75)}};
  for (int k = 0; k < 20; ++k) {
    pairs.emplace_back(dyadic_convex(rng, "cp", {0, 0}, 1.0), dyadic_convex(rng, "tp", {0.5, 0.25}, 1.0));
  }
  const rc::PotentialContactParams law = params(1e7, 0.5);
  for (const PolicyKind policy : {PolicyKind::float_, PolicyKind::filtered, PolicyKind::exact}) {
    const rc::PotentialContactMethod method(policy);
    BOOST_TEST((method.policy() == policy));
    for (const auto& [cp, tp] : pairs) {
      const rc::PairResult direct = rc::evaluate_pair(policy, cp, tp, law);
      rc::PairWorkspace workspace;
      rc::PairResult held;
      method.evaluate(cp, tp, law, workspace, held);
      BOOST_TEST((held.status == direct.status));
      BOOST_TEST((held.ip == direct.ip));
      BOOST_TEST(held.force.x == direct.force.x);
      BOOST_TEST(held.force.y == direct.force.y);
      BOOST_TEST((held.point == direct.point));
    }
  }
  const ConvexPolygon a = rectangle("a", 0, 1, 0, 1);
  BOOST_TEST(rc::PotentialContactMethod::separation(a, rectangle("b", 1.25, 2.25, 0, 1)) == 0.25);
  BOOST_TEST(rc::PotentialContactMethod::penetration_depth(a, rectangle("b", 1.25, 2.25, 0, 1)) == 0.0);
  BOOST_TEST(rc::PotentialContactMethod::penetration_depth(a, rectangle("c", 0.875, 1.875, 0, 1)) == 0.125);
  BOOST_TEST(rc::PotentialContactMethod::separation(a, rectangle("c", 0.875, 1.875, 0, 1)) == 0.0);
}

// Polygons whose extent is near double's range: CP's is 3e307, so the construction frame's
// grid spacing, the power of two above 4 x 3e307 = 1.2e308, is 2^1024 = inf. The frame must
// then leave the pair where it is. Before, the NaN origin (0 x inf) reached GMP on the exact
// path of a crossing whose cross products overflow, and GMP raised SIGFPE (found by
// fuzz_pair_kernel). The verdict is decided exactly whatever the magnitudes: overlap, and the
// IP has the four vertices of the two squares' overlap.
BOOST_AUTO_TEST_CASE(polygons_near_the_range_of_double_keep_a_finite_frame) {
  const ConvexPolygon cp = rectangle("cp", -1.5e307, 1.5e307, -1.5e307, 1.5e307);
  const ConvexPolygon tp = rectangle("tp", -1e307, 2e307, -1e307, 2e307);
  for (const PolicyKind policy : {PolicyKind::float_, PolicyKind::filtered, PolicyKind::exact}) {
    const rc::PairResult r = rc::evaluate_pair(policy, cp, tp, params(1e7, 1.0));
    BOOST_TEST((r.status == Overlap::overlap), policy_name(policy));
    BOOST_TEST(r.ip.size() == 4u, policy_name(policy));
  }
}
