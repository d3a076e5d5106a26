#include "rockcontact/kernel/2d/potential_integral.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "rockcontact/kernel/2d/crossing_point.hpp"
#include "rockcontact/kernel/2d/detail/potential_impl.hpp"
#include "rockcontact/kernel/core/detail/exact_number.hpp"

namespace rockcontact::kernel {
namespace {

namespace kd = detail;

template <class FT>
using Pt = kd::PointT<FT>;

// An IP vertex's coordinates: exact rationals under Exact, else the Policy's double crossing
// (under Filtered certified to ~2^-40 of the edge, crossing_point.hpp).
template <NumberPolicy Policy, class FT, class Poly>
Pt<FT> vertex_point(const Poly& cp, const Poly& tp, const IpVertex& v) {
  switch (v.kind) {
    case IpVertex::Kind::cp_vertex: return kd::lift<FT>(cp[v.cp]);
    case IpVertex::Kind::tp_vertex: return kd::lift<FT>(tp[v.tp]);
    case IpVertex::Kind::crossing: break;
  }
  // The crossing of the lines the predicates decided on (the polygons' own coordinates),
  // constructed relative to the frame's origin.
  const ConvexPolygon &a = kd::global_polygon(cp), &b = kd::global_polygon(tp);
  const Point2 &p = a[v.cp], &q = a[a.next(v.cp)], &t0 = b[v.tp], &t1 = b[b.next(v.tp)];
  if constexpr (std::is_same_v<FT, double>) {
    return kd::lift<FT>(construct_crossing_point<Policy>(p, q, t0, t1, kd::frame_origin(cp)));
  } else {
    return kd::construct_crossing<FT>(p, q, t0, t1);
  }
}

// The demarcation parameters of `poly` on segment p -> q, appended to t.
template <NumberPolicy Policy, class FT, class Poly>
void add_demarcation(const Poly& poly, const Pt<FT>& p, const Pt<FT>& q,
                     kd::LinearPieces<FT>& distance, const PotentialParams& params,
                     std::vector<FT>& t) {
  if (params.demarcation == Demarcation::exact) {
    kd::envelope_breakpoints<Policy>(distance, t);
  } else {
    kd::paper_breakpoints(poly, p, q, params.small_edge_length, t);
  }
}

// Integral terms of one IP edge p -> q (eq. 16-18): with g(t) = d_CP(t) - d_TP(t) (the
// potentials divided by kn/H), returns G = ∫0^1 g dt and the first moment
// m = ∫0^1 g(t) (p(t) - c) dt about c. g is linear between consecutive parameters, so the
// trapezoid rule for G and the closed form
//   ∫ g p dt over [ta, tb] = (tb - ta) [pa (2 ga + gb) + pb (ga + 2 gb)] / 6
// for m are exact.
template <class FT>
struct EdgeIntegral {
  FT G;
  Pt<FT> m;
};

template <NumberPolicy Policy, class FT, class Poly>
EdgeIntegral<FT> integrate_edge(const Poly& cp, const Poly& tp, const IpEdge& edge,
                                const Pt<FT>& p, const Pt<FT>& q, const Pt<FT>& c,
                                const PotentialParams& params, kd::ForceScratch<FT>& s) {
  // On its own boundary a polygon's potential is zero (seed 000 §3.2.3 steps 2-3).
  const bool cp_zero = edge.on == IpEdge::On::cp_edge;
  const bool tp_zero = edge.on == IpEdge::On::tp_edge;
  s.t.clear();
  s.t.push_back(FT(0));
  s.t.push_back(FT(1));
  if (!cp_zero) {
    kd::edge_distance_functions(cp, s.cp_edges, p, q, s.cp_distance);
    add_demarcation<Policy>(cp, p, q, s.cp_distance, params, s.t);
  }
  if (!tp_zero) {
    kd::edge_distance_functions(tp, s.tp_edges, p, q, s.tp_distance);
    add_demarcation<Policy>(tp, p, q, s.tp_distance, params, s.t);
  }
  std::sort(s.t.begin(), s.t.end());
  s.t.erase(std::unique(s.t.begin(), s.t.end()), s.t.end());
  std::erase_if(s.t, [](const FT& x) { return x < FT(0) || x > FT(1); });

  // Every IP point lies in both polygons, so each exit distance is >= 0. In double a
  // near-parallel crossing, correct to a few ulps across its edge, may slide along it out of
  // the other polygon; there the envelope is negative and would flip the sign of a sliver's
  // force. Clamping at 0 keeps the sliver's force at its true, rounding-sized, magnitude.
  // (In exact arithmetic the points are inside and the clamp never acts.)
  const auto inside = [](const FT& d) { return d < FT(0) ? FT(0) : d; };
  const auto g = [&](const FT& t) {
    FT value(0);
    if (!cp_zero) value += inside(s.cp_distance.at(t));
    if (!tp_zero) value -= inside(s.tp_distance.at(t));
    return value;
  };
  const FT dx = q.x - p.x, dy = q.y - p.y;
  const FT px = p.x - c.x, py = p.y - c.y;
  EdgeIntegral<FT> out{FT(0), {FT(0), FT(0)}};
  FT ta = s.t[0], ga = g(ta);
  for (std::size_t k = 1; k < s.t.size(); ++k) {
    const FT& tb = s.t[k];
    const FT gb = g(tb);
    const FT h = tb - ta;
    out.G += h * (ga + gb) / FT(2);
    // (p(t) - c) = (p - c) + t d, so pa - c, pb - c are linear in ta, tb.
    const FT wa = FT(2) * ga + gb, wb = ga + FT(2) * gb;
    out.m.x += h * ((px + ta * dx) * wa + (px + tb * dx) * wb) / FT(6);
    out.m.y += h * ((py + ta * dy) * wa + (py + tb * dy) * wb) / FT(6);
    ta = tb;
    ga = gb;
  }
  return out;
}

// Force, area and contact point from the symbolic IP, all in FT, each rounded once.
template <NumberPolicy Policy, class FT, class Poly>
PotentialResultant integrate_force(const Poly& cp, const Poly& tp,
                                   const IntersectionPolygon& ip, const PotentialParams& params,
                                   kd::ForceScratch<FT>& scratch, std::vector<Point2>& out_ip) {
  using Ops = kd::NumberOps<FT>;
  PotentialResultant out;
  std::vector<Pt<FT>>& v = scratch.vertices;
  v.clear();
  for (const IpVertex& iv : ip.vertices) v.push_back(vertex_point<Policy, FT>(cp, tp, iv));
  const kd::AreaCentroid<FT> ac = kd::area_centroid<FT>(v);
  const Pt<FT>& c = ac.centroid;
  kd::tabulate_edges(cp, scratch.cp_edges);
  kd::tabulate_edges(tp, scratch.tp_edges);

  // f = (kn/H) Σ_edges G_e (dy, -dx): (dy, -dx) = n L is the outward normal times the length
  // of a CCW edge (eq. 11, 18). The moment about c is Σ m_e x (dy, -dx) (eq. 17, 20).
  FT fx(0), fy(0), moment(0), magnitude(0);
  for (std::size_t k = 0; k < v.size(); ++k) {
    const Pt<FT>& p = v[k];
    const Pt<FT>& q = v[k + 1 == v.size() ? 0 : k + 1];
    const EdgeIntegral<FT> e = integrate_edge<Policy>(cp, tp, ip.edges[k], p, q, c, params, scratch);
    const FT nx = q.y - p.y, ny = p.x - q.x;
    fx += e.G * nx;
    fy += e.G * ny;
    moment += kd::cross(e.m.x, e.m.y, nx, ny);
    magnitude += Ops::abs(e.G) * (Ops::abs(nx) + Ops::abs(ny));
  }
  const FT scale = Ops::from(params.kn) / Ops::from(params.H);
  out.area = Ops::to_double(ac.area);
  out_ip.clear();
  for (const auto& p : v) out_ip.push_back(kd::round(p));
  out.force = {Ops::to_double(scale * fx), Ops::to_double(scale * fy)};

  // pg = c + lambda (-fy, fx) with lambda = -M / |f|^2 puts the resultant on its line of action
  // and is the foot of the perpendicular from c (§3.2.4). In double a resultant that is pure
  // rounding noise of its own sum (opposite pushes cancelling exactly in exact arithmetic) has
  // no line of action: below 64 u times the sum of magnitudes it is reported without a point.
  const FT f2 = fx * fx + fy * fy;
  FT noise(0);
  if constexpr (std::is_same_v<FT, double>) noise = 64.0 * 0x1p-53 * magnitude;
  if (f2 == FT(0) || f2 <= noise * noise) return out;
  const FT lambda = -moment / f2;
  out.point = kd::round(Pt<FT>{FT(c.x - lambda * fy), FT(c.y + lambda * fx)});
  return out;
}

// The origin of a pair's construction frame: the point of a grid of spacing 2^k >= 4 x CP's
// extent nearest CP's first vertex. A pair whose coordinates are within its own size of the
// origin gets (0, 0), so nothing is translated and its constructions round as they always did;
// a pair far away gets a round number near it, from which its coordinates differ by a few
// times its size: exactly (Sterbenz) once the pair is farther out than it is large. The origin
// is always finite.
Point2 frame_origin(const ConvexPolygon& cp) {
  const Point2 first = cp[0];
  double extent = 0.0;
  for (const Point2& v : cp.vertices()) {
    extent = std::max({extent, std::fabs(v.x - first.x), std::fabs(v.y - first.y)});
  }
  int exponent = 0;
  std::frexp(4.0 * extent, &exponent);  // 4 extent < 2^exponent
  const double spacing = std::ldexp(1.0, exponent);
  const Point2 origin{std::nearbyint(first.x / spacing) * spacing,
                      std::nearbyint(first.y / spacing) * spacing};
  // A polygon whose extent or position is near double's range has no finite grid point to
  // move to: it stays where it is (its constructions overflow with or without a frame).
  const bool finite = std::isfinite(spacing) && std::isfinite(origin.x) && std::isfinite(origin.y);
  return finite ? origin : Point2{0.0, 0.0};
}

}  // namespace

PotentialWorkspace::PotentialWorkspace() : scratch_(std::make_unique<detail::ForceScratch<double>>()) {}
PotentialWorkspace::~PotentialWorkspace() = default;
PotentialWorkspace::PotentialWorkspace(const PotentialWorkspace&) : PotentialWorkspace() {}
PotentialWorkspace& PotentialWorkspace::operator=(const PotentialWorkspace&) { return *this; }
PotentialWorkspace::PotentialWorkspace(PotentialWorkspace&&) noexcept = default;
PotentialWorkspace& PotentialWorkspace::operator=(PotentialWorkspace&&) noexcept = default;

template <NumberPolicy Policy>
PotentialResultant integrate_potential(const ConvexPolygon& cp, const ConvexPolygon& tp,
                                       const IntersectionPolygon& features,
                                       const PotentialParams& params,
                                       PotentialWorkspace& workspace, std::vector<Point2>& ip) {
  if constexpr (Policy::kind == PolicyKind::exact) {
    kd::ForceScratch<kd::ExactRational> scratch;
    return integrate_force<Policy>(cp, tp, features, params, scratch, ip);
  } else {
    // In double, in a frame near the pair: coordinates far from the origin would leave the
    // shoelace sums, moments and crossings with the rounding of their magnitude, not of the
    // pair's size (1e-7 of the force at 10^6 m on the contact2d pairs; 4e-13 in the frame).
    const Point2 o = frame_origin(cp);
    const kd::TranslatedPolygon local_cp{cp, o}, local_tp{tp, o};
    PotentialResultant r =
        integrate_force<Policy>(local_cp, local_tp, features, params, workspace.scratch(), ip);
    for (Point2& p : ip) p = {p.x + o.x, p.y + o.y};
    if (r.point) r.point = Point2{r.point->x + o.x, r.point->y + o.y};
    return r;
  }
}

#define ROCKCONTACT_INSTANTIATE(P)                                                           \
  template PotentialResultant integrate_potential<P>(                                        \
      const ConvexPolygon&, const ConvexPolygon&, const IntersectionPolygon&,                \
      const PotentialParams&, PotentialWorkspace&, std::vector<Point2>&);
ROCKCONTACT_FOR_EACH_POLICY(ROCKCONTACT_INSTANTIATE)
#undef ROCKCONTACT_INSTANTIATE

}  // namespace rockcontact::kernel
