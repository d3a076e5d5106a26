#define BOOST_TEST_MODULE dynamics_non_convex_potential
#include <boost/test/unit_test.hpp>

// The convex-part approximation of a non-convex block's potential (dda2d.hpp, "Non-convex
// blocks"), measured against an independent reference: the force of seed 000 eq. 11 with the
// potential of the WHOLE block (§3.2.2, Fig. 5), integrated numerically along the boundary of
// the intersection polygon IP, for a non-convex CP (an L) against a convex TP (a small square).
//
// ## Reference (everything below is divided by kn / H, so forces are in m²)
//   f_ref = ∮_{∂IP} (phi_L - phi_TP) n dL,   phi_L(p) = min over the L's 6 edges of the
//   point-SEGMENT distance (the distance to the L's boundary, p inside the L), phi_TP(p) = min
//   over TP's edges of the distance to the edge LINE; n the outward unit normal of IP; IP by
//   hand. Each IP edge is integrated by composite 3-point Gauss-Legendre on `subintervals`
//   equal pieces. The same code on a convex CP (a rectangle, where the segment and line
//   distances agree) must reproduce contact::evaluate_pair, which validates it.
// Engine side: f_parts = Σ over the parts of kernel::convex_partition(L) of evaluate_pair(part,
// TP).force / (kn / H).
//
// ## The L and its partition
// L = [0,4]×[0,1] ∪ [0,1]×[1,4], reflex corner (1,1). The only two-part partition on the L's
// own vertices cuts along the diagonal from (1,1) to (0,0): part A = (0,0) (4,0) (4,1) (1,1)
// (the bottom arm, x >= y) and part B = (0,0) (1,1) (1,4) (0,4) (x <= y); the test checks that
// convex_partition returns it, since everything below depends on it. In A, d_A = min(1 - y,
// (x - y)/√2, y, 4 - x): the top-face LINE and the partition diagonal are what matter here.
//
// ## The exact deficit and its bound (derived by hand)
// IP_k = part_k ∩ TP. Both phi_L and phi_TP are continuous, so their integrals over the
// diagonal cancel between IP_A and IP_B and f_ref = Σ_k ∮_{∂IP_k} (phi_L - phi_TP) n dL; on the
// diagonal phi_A = phi_B = 0 with opposite normals, so it drops out of f_parts too. Hence
//   f_ref - f_parts = ∮_{∂IP} Δ n dL,   Δ = d_L - d_part >= 0 (the part lies inside the L),
//   |f_ref - f_parts| <= ∮_{∂IP} Δ dL =: B,
// and Δ > 0 only where the diagonal is nearer than the L's boundary. (The cruder bound
// max Δ × affected length is also stated; it is vacuous in (c), hence B.)
// TP w × w, w = 0.2, pressed δ = 0.05 into the top face y = 1 of the bottom arm, x >= 1: d_L =
// 1 - y on IP (the reflex vertex is no nearer), so with c = 1 - 1/√2:
//   Δ > 0 iff (x - y)/√2 < 1 - y, i.e. x < 1 + (√2 - 1)(1 - y) <= 1 + (√2 - 1)δ = 1.0207.
//   (a), (b) s >= (√2 - 1)δ: Δ ≡ 0 on IP, f_parts = f_ref (to the quadrature tolerance).
//   (b) s = 0: left edge x = 1: Δ = c (1 - y), ∫ = c δ²/2 along n = (-1, 0); bottom edge
//       y = 1 - δ: Δ = cδ → 0 linearly over (√2 - 1)δ, ∫ = c (√2 - 1) δ²/2 along (0, -1):
//       f_ref - f_parts = -(c δ²/2) (1, √2 - 1), B = c δ²/√2 = 5.18e-4 m²;
//       crude bound: max Δ = cδ times affected length √2 δ = (√2 - 1)δ² = 1.04e-3 m².
//   f_ref by the gradient form ∫_IP (∇phi_L - ∇phi_TP) dA (potential_contact_test.cpp): ∇d_L =
//   (0, -1) on the w × δ strip; TP's bottom region minus its two corner triangles gives
//   (0, wδ - δ²): f_ref = (0, -(2wδ - δ²)) = (0, -0.0175) m² for (a) and every s of (b).
// (c) TP = [1-a, 1+a]², a = 0.1, in the reflex corner: IP = TP minus the quadrant x, y > 1.
//   Bottom edge y = 1 - a (part A): d_L = sqrt((1-x)² + a²) for x < 1 (the reflex vertex),
//   a for x >= 1; d_A = (x - 1 + a)/√2 up to x = 1 + (√2 - 1)a, then a. Right edge x = 1 + a:
//   (1 + a - y)/√2 >= 1 - y on y ∈ [1-a, 1], so Δ = 0; the edge on y = 1 lies on the L: Δ = 0.
//   With ∫_0^1 sqrt(1 + t²) dt = (√2 + asinh 1)/2 and K = that - 1/2 = 0.6478:
//   I = ∫_bottom Δ = a² (K + 1/2) - a²/(2√2) + c (√2 - 1) a²/2 = a² (K - 1/2 + 1/√2);
//   by the symmetry about y = x the left edge gives the same along (-1, 0):
//   f_ref - f_parts = -I (1, 1), B = 2I = 0.0171 m² (crude bound √2 a × 2√2 a = 4a² = 0.04).
//   f_ref: ∇d_L = (0,-1), (-1,0) on the two a × a squares beside the corner and (p - (1,1))/|..|
//   on the corner square (integral -a² K (1,1)); ∫_IP ∇d_TP = -(TP's quadrant x, y > 1) =
//   (a²/2)(1, 1). f_ref = -a² (3/2 + K) (1, 1), so f_parts falls short by (K - 1/2 + 1/√2) /
//   (3/2 + K) = 39.8 % in the same direction.
//
// ## Quadrature tolerance
// On each IP edge the integrand is piecewise smooth: a min of distances, each with gradient of
// norm <= 1, so at a kink the slope jumps by J <= 2. Gauss-Legendre is exact for linear
// functions, so a piece of length h holding one kink errs by at most J h²/4: the kink minus its
// chord has one sign and magnitude <= J h/4, so its integral and the rule (positive weights
// summing to h) both lie between 0 and ±J h²/4. The smooth sqrt pieces (distance to the reflex
// vertex, curvature <= 1/a) contribute O(h⁶), nothing at this h. With at most 8 kinks per edge
// in these configurations (both potentials together), 6 edges and h <= 0.2 m / 2^15 = 6.1e-6 m:
// error <= 48 × 2 × h²/4 = 9e-10 m². So quadrature_tol = 1e-9 m² absolute, 7e-8 relative to the
// smallest |f| here (0.014 m²). The test also shows that N/2 and N pieces agree within it
// (measured: ~1e-14 m², the kinks mostly fall on or symmetrically about piece ends).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/kernel/2d/block_cutting.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"

namespace {

namespace rc = rockcontact::contact;
namespace rk = rockcontact::kernel;
using rk::Point2;
using rk::Vector2;

constexpr double kn = 1.0e7;  // Pa
constexpr double H = 1.0;     // m
constexpr int subintervals = 1 << 15;  // per IP edge
constexpr double quadrature_tol = 1e-9;  // m², f / (kn / H); derived in the header comment
constexpr double sqrt2 = std::numbers::sqrt2;
constexpr double c = 1.0 - 1.0 / sqrt2;  // Δ / depth at the foot of the diagonal (header)

const std::vector<Point2> l_block{{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};

std::vector<Point2> box(double x0, double x1, double y0, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

double norm(Vector2 v) { return std::hypot(v.x, v.y); }
Vector2 minus(Vector2 a, Vector2 b) { return {a.x - b.x, a.y - b.y}; }

double segment_distance(Point2 p, Point2 a, Point2 b) {
  const double ex = b.x - a.x, ey = b.y - a.y;
  const double t = std::clamp(((p.x - a.x) * ex + (p.y - a.y) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
  return std::hypot(p.x - a.x - t * ex, p.y - a.y - t * ey);
}

// Distance from p (inside) to the boundary of a simple polygon: min over edge SEGMENTS.
double block_depth(Point2 p, std::span<const Point2> poly) {
  double d = INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    d = std::min(d, segment_distance(p, poly[i], poly[(i + 1) % poly.size()]));
  }
  return d;
}

// d_exit of a convex CCW polygon at p (inside): min over edge LINES of the signed distance.
double convex_depth(Point2 p, std::span<const Point2> poly) {
  double d = INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2 a = poly[i], b = poly[(i + 1) % poly.size()];
    d = std::min(d, ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / std::hypot(b.x - a.x, b.y - a.y));
  }
  return d;
}

// ∫_a^b (phi_CP - phi_TP) dL by composite 3-point Gauss-Legendre on n pieces.
double edge_integral(Point2 a, Point2 b, std::span<const Point2> cp, std::span<const Point2> tp, int n) {
  static constexpr double node[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};  // ±sqrt(3/5)
  static constexpr double weight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const double t = (i + 0.5 + 0.5 * node[k]) / n;
      const Point2 p{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
      sum += weight[k] * (block_depth(p, cp) - convex_depth(p, tp));
    }
  }
  return sum * std::hypot(b.x - a.x, b.y - a.y) / (2.0 * n);  // rule on [-1, 1] mapped to length/n
}

// f_ref / (kn / H) = ∮_{∂IP} (phi_CP - phi_TP) n dL, IP counter-clockwise.
Vector2 reference_force(std::span<const Point2> cp, std::span<const Point2> tp, std::span<const Point2> ip,
                        int n = subintervals) {
  Vector2 f;
  for (std::size_t i = 0; i < ip.size(); ++i) {
    const Point2 a = ip[i], b = ip[(i + 1) % ip.size()];
    const double len = std::hypot(b.x - a.x, b.y - a.y), g = edge_integral(a, b, cp, tp, n);
    f.x += g * (b.y - a.y) / len;  // outward normal of a CCW edge: (ey, -ex) / len
    f.y -= g * (b.x - a.x) / len;
  }
  return f;
}

rc::PotentialContactParams params() {
  rc::PotentialContactParams p = rc::default_potential_contact_params();
  p.kn = kn;
  p.H = H;
  return p;
}

Vector2 engine_force(const std::vector<Point2>& cp, const std::vector<Point2>& tp) {
  const rc::PairResult r = rc::evaluate_pair(rk::PolicyKind::filtered, rk::ConvexPolygon::make("cp", cp),
                                             rk::ConvexPolygon::make("tp", tp), params());
  return {r.force.x / (kn / H), r.force.y / (kn / H)};
}

// f_parts / (kn / H): the engine's sum over the convex parts, each with its own potential.
Vector2 part_sum_force(const std::vector<std::vector<Point2>>& parts, const std::vector<Point2>& tp) {
  Vector2 f;
  for (const auto& part : parts) {
    const Vector2 g = engine_force(part, tp);
    f = {f.x + g.x, f.y + g.y};
  }
  return f;
}

double angle_deg(Vector2 a, Vector2 b) {
  return std::atan2(std::fabs(a.x * b.y - a.y * b.x), a.x * b.x + a.y * b.y) * 180.0 / std::numbers::pi;
}

std::string to_string(const std::vector<Point2>& poly) {
  std::ostringstream s;
  for (const Point2& p : poly) s << " (" << p.x << "," << p.y << ")";
  return s.str();
}

// True when `a` is `b` up to the starting vertex.
bool same_cycle(const std::vector<Point2>& a, const std::vector<Point2>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t s = 0; s < b.size(); ++s) {
    bool all = true;
    for (std::size_t k = 0; k < a.size() && all; ++k) all = a[k] == b[(s + k) % b.size()];
    if (all) return true;
  }
  return false;
}

struct Config {
  std::string name;
  std::vector<Point2> tp, ip;  // CCW; ip = L ∩ tp by hand
  Vector2 reference;           // closed form of f_ref / (kn / H), m²
  Vector2 deficit;             // closed form of (f_ref - f_parts) / (kn / H), m²
  double bound;                // B = ∮ Δ dL >= |f_ref - f_parts| / (kn / H), m²
};

// (a), (b) and (c) of the header comment.
std::vector<Config> configs() {
  constexpr double w = 0.2, delta = 0.05, y0 = 1.0 - delta, a = 0.1;
  const Vector2 strip{0.0, -(2 * w * delta - delta * delta)};
  std::vector<Config> out{
      {"(a) far, x in [2.4,2.6]", box(2.4, 2.6, y0, y0 + w), box(2.4, 2.6, y0, 1.0), strip, {}, 0.0}};
  for (double s : {0.5, 0.2, 0.1, 0.05, 0.0}) {
    std::ostringstream name;
    name << "(b) s = " << s << ", x in [" << 1 + s << "," << 1.2 + s << "]";
    const bool near = s < (sqrt2 - 1) * delta;
    out.push_back({name.str(), box(1 + s, 1.2 + s, y0, y0 + w), box(1 + s, 1.2 + s, y0, 1.0), strip,
                   near ? Vector2{-c * delta * delta / 2, -c * (sqrt2 - 1) * delta * delta / 2} : Vector2{},
                   near ? c * delta * delta / sqrt2 : 0.0});
  }
  const double k = (sqrt2 + std::asinh(1.0)) / 2 - 0.5, i = a * a * (k - 0.5 + 1 / sqrt2);
  out.push_back({"(c) reflex corner, [0.9,1.1]^2", box(1 - a, 1 + a, 1 - a, 1 + a),
                 {{1 - a, 1 - a}, {1 + a, 1 - a}, {1 + a, 1}, {1, 1}, {1, 1 + a}, {1 - a, 1 + a}},
                 {-a * a * (1.5 + k), -a * a * (1.5 + k)}, {-i, -i}, 2 * i});
  return out;
}

}  // namespace

// The reference quadrature itself, on convex CPs where evaluate_pair is the oracle: a 4 x 1
// rectangle against a strip overlap, a corner overlap and a slanted triangle (IP by hand; the
// triangle's edges from (2, 0.8) cross y = 1 at x = 2 ± 0.15). Tolerance quadrature_tol (header);
// the engine's own rounding (~1e-16 relative) is far below it. The same cases at N/2 pieces
// agree with N within the tolerance too, which shows the a priori bound is not optimistic.
BOOST_AUTO_TEST_CASE(reference_quadrature_reproduces_evaluate_pair_on_a_convex_cp) {
  const std::vector<Point2> rect = box(0, 4, 0, 1);
  const std::vector<std::vector<Point2>> tps{box(2.4, 2.6, 0.95, 1.15), box(3.9, 4.1, 0.9, 1.1),
                                             {{2, 0.8}, {2.3, 1.2}, {1.7, 1.2}}};
  const std::vector<std::vector<Point2>> ips{box(2.4, 2.6, 0.95, 1), box(3.9, 4, 0.9, 1),
                                             {{2, 0.8}, {2.15, 1}, {1.85, 1}}};
  for (std::size_t j = 0; j < tps.size(); ++j) {
    const Vector2 engine = engine_force(rect, tps[j]), ref = reference_force(rect, tps[j], ips[j]);
    const Vector2 coarse = reference_force(rect, tps[j], ips[j], subintervals / 2);
    BOOST_TEST_MESSAGE("convex CP, TP" << to_string(tps[j]) << ": engine (" << engine.x << ", " << engine.y
                       << ") m², |ref - engine| = " << norm(minus(ref, engine)) << " m², |ref(N) - ref(N/2)| = "
                       << norm(minus(ref, coarse)) << " m²");
    BOOST_TEST(norm(minus(ref, engine)) <= quadrature_tol);
    BOOST_TEST(norm(minus(ref, coarse)) <= quadrature_tol);
  }
}

// Everything in the header comment rests on the diagonal (0,0)-(1,1) partition.
BOOST_AUTO_TEST_CASE(convex_partition_of_the_l_cuts_along_the_reflex_diagonal) {
  const std::vector<std::vector<Point2>> parts = rk::convex_partition(l_block);
  for (std::size_t k = 0; k < parts.size(); ++k) BOOST_TEST_MESSAGE("part " << k << ":" << to_string(parts[k]));
  const std::vector<Point2> arm_a{{0, 0}, {4, 0}, {4, 1}, {1, 1}}, arm_b{{0, 0}, {1, 1}, {1, 4}, {0, 4}};
  BOOST_TEST_REQUIRE(parts.size() == 2u);
  const bool a_then_b = same_cycle(parts[0], arm_a) && same_cycle(parts[1], arm_b);
  const bool b_then_a = same_cycle(parts[0], arm_b) && same_cycle(parts[1], arm_a);
  BOOST_TEST(a_then_b != b_then_a);
}

// The measurement. Per configuration: the quadrature reference equals its closed form (a check
// of the reference on the non-convex CP), the measured deficit f_ref - f_parts equals the one
// derived in the header, and |f_parts - f_ref| <= B; all within quadrature_tol (header).
BOOST_AUTO_TEST_CASE(part_potentials_against_the_whole_block_potential) {
  const std::vector<std::vector<Point2>> parts = rk::convex_partition(l_block);
  std::ostringstream table;
  table << "L = [0,4]x[0,1] u [0,1]x[1,4] against a 0.2 m square TP, kn = 1e7 Pa, H = 1 m; parts:";
  for (const auto& part : parts) table << to_string(part) << ";";
  table << "\n" << std::left << std::setw(34) << "configuration" << std::right << std::setw(13) << "|f_ref| N/m"
        << std::setw(14) << "|f_parts| N/m" << std::setw(11) << "rel. err" << std::setw(11) << "predicted"
        << std::setw(11) << "B/|f_ref|" << std::setw(11) << "angle deg" << "\n";
  for (const Config& cfg : configs()) {
    const Vector2 ref = reference_force(l_block, cfg.tp, cfg.ip), sum = part_sum_force(parts, cfg.tp);
    const Vector2 deficit = minus(ref, sum);
    BOOST_TEST(norm(minus(ref, cfg.reference)) <= quadrature_tol, cfg.name);
    BOOST_TEST(norm(minus(deficit, cfg.deficit)) <= quadrature_tol, cfg.name);
    BOOST_TEST(norm(deficit) <= cfg.bound + quadrature_tol, cfg.name);
    table << std::left << std::setw(34) << cfg.name << std::right << std::scientific << std::setprecision(4)
          << std::setw(13) << norm(ref) * kn / H << std::setw(14) << norm(sum) * kn / H << std::setprecision(3)
          << std::setw(11) << norm(deficit) / norm(ref) << std::setw(11) << norm(cfg.deficit) / norm(ref)
          << std::setw(11) << cfg.bound / norm(ref) << std::fixed << std::setprecision(3) << std::setw(11)
          << angle_deg(ref, sum) << std::defaultfloat << "\n";
  }
  table << "rel. err = |f_parts - f_ref| / |f_ref| (measured); predicted = the closed-form deficit / |f_ref|;\n"
        << "B = the derived bound ∮ Δ dL on |f_parts - f_ref|; angle between f_parts and f_ref.";
  BOOST_TEST_MESSAGE(table.str());
}
