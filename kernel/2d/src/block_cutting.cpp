#include "rockcontact/kernel/2d/block_cutting.hpp"

// The only library source that includes CGAL (it is slow to compile); see the header for the
// method.

#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_observer.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Partition_traits_2.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/partition_2.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <list>
#include <numbers>
#include <queue>
#include <string>
#include <unordered_map>
#include <utility>

namespace rockcontact::kernel {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using ExactPoint = K::Point_2;
using Traits = CGAL::Arr_segment_traits_2<K>;
using Segment = Traits::Curve_2;
// The face flag is true for the faces inside the region.
using Arrangement = CGAL::Arrangement_2<Traits, CGAL::Arr_face_extended_dcel<Traits, bool>>;
using Polygon = std::vector<Point2>;

// ---------------------------------------------------------------------------------------------
// Messages and conversions

[[noreturn]] void fail(const std::string& subject, const std::string& problem) {
  throw InvalidCut(subject, problem);
}

// Shortest decimal form that reads back as the same double ("-1", "0.1", "nan").
std::string num(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

std::string near(const ExactPoint& p) {
  return "block near (" + num(CGAL::to_double(p.x())) + ", " + num(CGAL::to_double(p.y())) + ")";
}

// The double nearest to an exact coordinate: CGAL's interval of a GMP rational is the tightest
// pair of doubles around it, and the exact midpoint of the pair decides.
double round_to_double(const FT& v) {
  const std::pair<double, double> bounds = CGAL::to_interval(CGAL::exact(v));
  if (bounds.first == bounds.second) return bounds.first;
  const FT midpoint = (FT(bounds.first) + FT(bounds.second)) / 2;
  return v < midpoint ? bounds.first : bounds.second;
}

Polygon to_doubles(const std::vector<ExactPoint>& v) {
  Polygon out;
  out.reserve(v.size());
  for (const ExactPoint& p : v) out.push_back({round_to_double(p.x()), round_to_double(p.y())});
  return out;
}

std::vector<ExactPoint> to_exact(std::span<const Point2> v) {
  std::vector<ExactPoint> out;
  out.reserve(v.size());
  for (const Point2& p : v) out.emplace_back(p.x, p.y);
  return out;
}

// Drops every vertex collinear with its neighbours (exact). On a simple polygon such a vertex
// lies between them, and a vertex whose neighbours are both dropped sits on the same line, so
// testing against the original neighbours in one pass is the same as dropping them one by one.
std::vector<ExactPoint> drop_collinear(const std::vector<ExactPoint>& v) {
  const std::size_t n = v.size();
  std::vector<ExactPoint> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!CGAL::collinear(v[(i + n - 1) % n], v[i], v[(i + 1) % n])) out.push_back(v[i]);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Input validation

// The first defect that makes `v` non-simple, for the message (only called on failure: O(n²)).
std::string why_not_simple(const std::vector<ExactPoint>& v) {
  const std::size_t n = v.size();
  for (std::size_t j = 1; j < n; ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      if (v[i] == v[j]) return "vertex " + std::to_string(j) + " repeats vertex " + std::to_string(i);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const ExactPoint& prev = v[(i + n - 1) % n];
    const ExactPoint& next = v[(i + 1) % n];
    if (CGAL::collinear(prev, v[i], next) &&
        !CGAL::collinear_are_strictly_ordered_along_line(prev, v[i], next)) {
      return "vertex " + std::to_string(i) + ": the boundary folds back on itself";
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      if (CGAL::do_intersect(K::Segment_2(v[i], v[i + 1]), K::Segment_2(v[j], v[(j + 1) % n]))) {
        return "edges " + std::to_string(i) + " and " + std::to_string(j) + " intersect";
      }
    }
  }
  return "the boundary intersects itself";
}

// Checks a polygon argument (`name` is "region" or "polygon") and returns it exactly.
std::vector<ExactPoint> validate_polygon(const std::string& name, std::span<const Point2> v) {
  if (v.size() < 3) fail(name, "needs at least 3 vertices, got " + std::to_string(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y)) {
      fail(name, "vertex " + std::to_string(i) + ": coordinates must be finite, got (" +
           num(v[i].x) + ", " + num(v[i].y) + ")");
    }
  }
  std::vector<ExactPoint> exact = to_exact(v);
  if (!CGAL::is_simple_2(exact.begin(), exact.end(), K())) {
    fail(name, why_not_simple(exact) + " (a simple polygon is required)");
  }
  const CGAL::Orientation orientation = CGAL::orientation_2(exact.begin(), exact.end(), K());
  if (orientation == CGAL::CLOCKWISE) {
    fail(name, "vertices are clockwise; counter-clockwise order is required");
  }
  if (orientation != CGAL::COUNTERCLOCKWISE) fail(name, "the polygon has zero area");
  return exact;
}

void validate_set(std::size_t i, const JointSet& set) {
  const std::string field = "joint_sets[" + std::to_string(i) + "].";
  if (!(set.dip_deg >= 0.0 && set.dip_deg < 180.0)) {
    fail(field + "dip_deg", "expected a value in [0, 180), got " + num(set.dip_deg));
  }
  if (!(std::isfinite(set.spacing) && set.spacing > 0.0)) {
    fail(field + "spacing", "expected a finite value > 0, got " + num(set.spacing));
  }
  if (!std::isfinite(set.offset)) fail(field + "offset", "expected a finite value, got " + num(set.offset));
  if (!(std::isfinite(set.trace_length) && set.trace_length >= 0.0)) {
    fail(field + "trace_length", "expected a finite value >= 0, got " + num(set.trace_length));
  }
  if (!(std::isfinite(set.gap) && set.gap >= 0.0)) {
    fail(field + "gap", "expected a finite value >= 0, got " + num(set.gap));
  }
  if (set.trace_length == 0.0 && set.gap != 0.0) {
    fail(field + "gap", "expected 0 for persistent traces (trace_length 0), got " + num(set.gap) +
         "; set trace_length > 0 for non-persistent traces");
  }
}

// ---------------------------------------------------------------------------------------------
// Trace generation (step 3)

// Unit normal n and direction t of a set; exact along the axes.
struct Frame {
  double nx, ny, tx, ty;
};

Frame frame_of(double dip_deg) {
  if (dip_deg == 0.0) return {0.0, 1.0, 1.0, 0.0};
  if (dip_deg == 90.0) return {-1.0, 0.0, 0.0, 1.0};
  const double radians = dip_deg * (std::numbers::pi / 180.0);
  const double s = std::sin(radians);
  const double c = std::cos(radians);
  return {-s, c, c, s};
}

// A disc around the region's bounding box, 6 % wider than the box's circumscribed circle. The
// points of a line inside the box lie within the box's half-diagonal of the projection of the
// centre onto the line, so clipping every line to [t . centre -+ radius] keeps all of it that
// matters, and its end points lie outside the box by a margin far above their rounding.
struct Disc {
  double cx, cy, radius;
};

Disc disc_around(std::span<const Point2> region) {
  double x0 = region[0].x, x1 = x0, y0 = region[0].y, y1 = y0;
  for (const Point2& p : region) {
    x0 = std::min(x0, p.x);
    x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y);
    y1 = std::max(y1, p.y);
  }
  const Disc disc{0.5 * x0 + 0.5 * x1, 0.5 * y0 + 0.5 * y1, 1.0625 * 0.5 * std::hypot(x1 - x0, y1 - y0)};
  if (!std::isfinite(disc.radius)) fail("region", "coordinates span more than the double range");
  return disc;
}

// The traces of one set: lines k_first..k_last, and on every line the pieces j_first..j_last
// (one piece, the whole clipped line, for a persistent set), clipped to [s_lo, s_hi].
struct TracePlan {
  Frame frame;
  std::int64_t k_first, k_last, j_first, j_last;
  double s_lo, s_hi;
  double lines() const { return static_cast<double>(k_last - k_first + 1); }
  double pieces() const { return lines() * static_cast<double>(j_last - j_first + 1); }
};

// Indices beyond 2^52 would no longer step by one in double.
bool index_range_ok(double lo, double hi) { return std::abs(lo) < 0x1p52 && std::abs(hi) < 0x1p52; }

TracePlan plan_set(std::size_t i, const JointSet& set, std::span<const Point2> region, const Disc& disc) {
  const std::string field = "joint_sets[" + std::to_string(i) + "].";
  TracePlan plan{frame_of(set.dip_deg), 0, 0, 0, 0, 0.0, 0.0};
  const Frame& f = plan.frame;
  double p_lo = f.nx * region[0].x + f.ny * region[0].y, p_hi = p_lo;
  for (const Point2& p : region) {
    p_lo = std::min(p_lo, f.nx * p.x + f.ny * p.y);
    p_hi = std::max(p_hi, f.nx * p.x + f.ny * p.y);
  }
  // One extra line on each side, so no line through an extreme vertex is lost to rounding.
  const double k_lo = std::ceil((p_lo - set.offset) / set.spacing) - 1.0;
  const double k_hi = std::floor((p_hi - set.offset) / set.spacing) + 1.0;
  if (!(k_hi - k_lo < static_cast<double>(max_cut_trace_lines))) {
    fail(field + "spacing", num(set.spacing) + " gives about " + num(k_hi - k_lo) +
         " trace lines across the region (at most " + std::to_string(max_cut_trace_lines) + " in all)");
  }
  if (!index_range_ok(k_lo, k_hi)) {
    fail(field + "offset", num(set.offset) + " is more than 2^52 spacings away from the region");
  }
  plan.k_first = static_cast<std::int64_t>(k_lo);
  plan.k_last = static_cast<std::int64_t>(k_hi);
  const double s_centre = f.tx * disc.cx + f.ty * disc.cy;  // t . n = 0: same for every line
  plan.s_lo = s_centre - disc.radius;
  plan.s_hi = s_centre + disc.radius;
  if (set.trace_length == 0.0) return plan;
  const double period = set.trace_length + set.gap;
  const double j_lo = std::ceil((plan.s_lo - set.trace_length) / period);
  const double j_hi = std::floor(plan.s_hi / period);
  if (!(j_hi - j_lo < static_cast<double>(max_cut_trace_pieces))) {
    fail(field + "trace_length", "traces of " + num(set.trace_length) + " m with gaps of " +
         num(set.gap) + " m give about " + num(j_hi - j_lo) + " traces per line (at most " +
         std::to_string(max_cut_trace_pieces) + " in all)");
  }
  if (!index_range_ok(j_lo, j_hi)) {
    fail(field + "trace_length", "traces of " + num(set.trace_length) + " m with gaps of " + num(set.gap) +
         " m are numbered beyond 2^52 along the lines near the region");
  }
  plan.j_first = static_cast<std::int64_t>(j_lo);
  plan.j_last = static_cast<std::int64_t>(j_hi);
  return plan;
}

// Step 1's work bounds over all sets; each message names the set that crosses the bound.
void check_work(std::span<const JointSet> sets, const std::vector<TracePlan>& plans) {
  double lines = 0.0, pieces = 0.0, crossings = 0.0;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    const std::string field = "joint_sets[" + std::to_string(i) + "]";
    lines += plans[i].lines();
    pieces += plans[i].pieces();
    if (lines > static_cast<double>(max_cut_trace_lines)) {
      fail(field, "the sets up to this one give " + num(lines) + " trace lines across the region (at most " +
           std::to_string(max_cut_trace_lines) + ")");
    }
    if (pieces > static_cast<double>(max_cut_trace_pieces)) {
      fail(field, "the sets up to this one give " + num(pieces) + " traces near the region (at most " +
           std::to_string(max_cut_trace_pieces) + ")");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (sets[j].dip_deg != sets[i].dip_deg) crossings += plans[i].lines() * plans[j].lines();
    }
    if (crossings > max_cut_trace_crossings) {
      fail(field, "the sets up to this one can cross up to " + num(crossings) +
           " times in the region (at most " + num(max_cut_trace_crossings) + ")");
    }
  }
}

void add_segment(const Frame& f, double h, double s0, double s1, std::vector<Segment>& out) {
  const Point2 a{h * f.nx + s0 * f.tx, h * f.ny + s0 * f.ty};
  const Point2 b{h * f.nx + s1 * f.tx, h * f.ny + s1 * f.ty};
  if (a != b) out.emplace_back(ExactPoint(a.x, a.y), ExactPoint(b.x, b.y));
}

void add_traces(const JointSet& set, const TracePlan& plan, std::vector<Segment>& out) {
  const double period = set.trace_length + set.gap;
  for (std::int64_t k = plan.k_first; k <= plan.k_last; ++k) {
    const double h = set.offset + static_cast<double>(k) * set.spacing;
    if (set.trace_length == 0.0) {
      add_segment(plan.frame, h, plan.s_lo, plan.s_hi, out);
      continue;
    }
    for (std::int64_t j = plan.j_first; j <= plan.j_last; ++j) {
      const double start = static_cast<double>(j) * period;
      const double s0 = std::max(start, plan.s_lo);
      const double s1 = std::min(start + set.trace_length, plan.s_hi);
      if (s0 < s1) add_segment(plan.frame, h, s0, s1, out);
    }
  }
}

std::vector<Segment> make_traces(std::span<const Point2> region, std::span<const JointSet> sets) {
  const Disc disc = disc_around(region);
  std::vector<TracePlan> plans;
  for (std::size_t i = 0; i < sets.size(); ++i) plans.push_back(plan_set(i, sets[i], region, disc));
  check_work(sets, plans);
  std::vector<Segment> traces;
  for (std::size_t i = 0; i < sets.size(); ++i) add_traces(sets[i], plans[i], traces);
  return traces;
}

// ---------------------------------------------------------------------------------------------
// The arrangement (steps 2, 4)

// A face split off another face lies where that face was, so it inherits its inside flag.
class InsideFlagObserver : public CGAL::Arr_observer<Arrangement> {
 public:
  explicit InsideFlagObserver(Arrangement& arrangement) : CGAL::Arr_observer<Arrangement>(arrangement) {}
  void after_split_face(Arrangement::Face_handle face, Arrangement::Face_handle new_face, bool) override {
    new_face->set_data(face->data());
  }
};

void build_arrangement(Arrangement& arrangement, const std::vector<ExactPoint>& region,
                       const std::vector<Segment>& traces) {
  InsideFlagObserver observer(arrangement);
  arrangement.unbounded_face()->set_data(false);
  std::vector<Segment> boundary;
  for (std::size_t i = 0; i < region.size(); ++i) {
    boundary.emplace_back(region[i], region[(i + 1) % region.size()]);
  }
  CGAL::insert_non_intersecting_curves(arrangement, boundary.begin(), boundary.end());
  for (auto face = arrangement.faces_begin(); face != arrangement.faces_end(); ++face) {
    if (!face->is_unbounded()) face->set_data(true);
  }
  CGAL::insert(arrangement, traces.begin(), traces.end());
}

// Step 4: the bridges of inside faces, all in one pass (see the header).
void remove_dead_ends(Arrangement& arrangement) {
  std::vector<Arrangement::Halfedge_handle> bridges;
  for (auto edge = arrangement.edges_begin(); edge != arrangement.edges_end(); ++edge) {
    if (edge->face() == edge->twin()->face() && edge->face()->data()) bridges.push_back(edge);
  }
  for (const Arrangement::Halfedge_handle edge : bridges) arrangement.remove_edge(edge);
}

// ---------------------------------------------------------------------------------------------
// Merging small blocks (step 5)

using Face = Arrangement::Face_handle;
using Halfedge = Arrangement::Halfedge_handle;
using FaceId = const Arrangement::Face*;

// Exact area of a face: the shoelace sum over its outer boundary (counter-clockwise) and the
// boundaries of its holes (clockwise seen from the face, so subtracted; an antenna adds 0),
// taken relative to one vertex so that the interval filter stays tight far from the origin.
FT face_area(Arrangement::Face_const_handle face) {
  const ExactPoint& origin = face->outer_ccb()->source()->point();
  FT twice = 0;
  const auto add_cycle = [&](Arrangement::Ccb_halfedge_const_circulator first) {
    auto edge = first;
    do {
      const K::Vector_2 a = edge->source()->point() - origin;
      const K::Vector_2 b = edge->target()->point() - origin;
      twice += a.x() * b.y() - a.y() * b.x();
    } while (++edge != first);
  };
  add_cycle(face->outer_ccb());
  for (auto hole = face->inner_ccbs_begin(); hole != face->inner_ccbs_end(); ++hole) add_cycle(*hole);
  return twice / 2;
}

bool lower_left(const ExactPoint& a, const ExactPoint& b) { return CGAL::compare_yx(a, b) == CGAL::SMALLER; }

// A face's outer boundary from its lowest, then leftmost vertex: the tie-breaking key of step 5
// (two faces never have the same one: the edges leaving a shared first vertex differ).
std::vector<ExactPoint> face_key(Arrangement::Face_const_handle face) {
  std::vector<ExactPoint> points;
  const auto first = face->outer_ccb();
  auto edge = first;
  do points.push_back(edge->source()->point());
  while (++edge != first);
  std::rotate(points.begin(), std::min_element(points.begin(), points.end(), lower_left), points.end());
  return points;
}

bool key_less(const std::vector<ExactPoint>& a, const std::vector<ExactPoint>& b) {
  return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), lower_left);
}

// In double, from the exact edge vector rounded once.
double edge_length(Halfedge edge) {
  const ExactPoint& a = edge->source()->point();
  const ExactPoint& b = edge->target()->point();
  return std::hypot(round_to_double(b.x() - a.x()), round_to_double(b.y() - a.y()));
}

std::vector<Halfedge> outer_boundary(Face face) {
  std::vector<Halfedge> edges;
  const auto first = face->outer_ccb();
  auto edge = first;
  do edges.push_back(edge);
  while (++edge != first);
  return edges;
}

// A maximal run of consecutive halfedges of a fragment's outer boundary with the same inside
// face across them; `first` is the index of edges.front() in the boundary.
struct SharedChain {
  Face neighbour;
  std::vector<Halfedge> edges;
  std::size_t first = 0;
  double length = 0.0;
};

// The chains of `boundary` (the outer boundary of `fragment`) shared with inside faces. The
// scan starts where the face across changes, so no chain is split at the start; when the same
// face lies across every edge, the whole boundary is one chain.
std::vector<SharedChain> shared_chains(Face fragment, const std::vector<Halfedge>& boundary) {
  const std::size_t n = boundary.size();
  const auto across = [&](std::size_t i) { return boundary[i % n]->twin()->face(); };
  std::size_t start = 0;
  while (start < n && across(start) == across(start + n - 1)) ++start;
  if (start == n) start = 0;
  std::vector<SharedChain> chains;
  for (std::size_t i = start; i < start + n; ++i) {
    const Face face = across(i);
    if (face == fragment || !face->data()) continue;
    if (i == start || across(i - 1) != face) chains.push_back({face, {}, i % n, 0.0});
    chains.back().edges.push_back(boundary[i % n]);
    chains.back().length += edge_length(boundary[i % n]);
  }
  return chains;
}

// True when the chain's neighbour meets the fragment nowhere else: no other chain, and no
// vertex of the fragment's outer boundary off the chain lies on the neighbour's boundary. The
// chain's vertices are the sources of its edges and of the edge after it; the others follow.
bool meets_only_along(const SharedChain& chain, const std::vector<SharedChain>& chains,
                      const std::vector<Halfedge>& boundary) {
  for (const SharedChain& other : chains) {
    if (&other != &chain && other.neighbour == chain.neighbour) return false;
  }
  const std::size_t n = boundary.size();
  for (std::size_t k = chain.edges.size() + 1; k < n; ++k) {
    const auto first = boundary[(chain.first + k) % n]->source()->incident_halfedges();
    auto incoming = first;
    do {
      if (incoming->face() == chain.neighbour) return false;
    } while (++incoming != first);
  }
  return true;
}

// The chain along which a fragment merges (see the header), or null when there is none.
const SharedChain* chosen_chain(const std::vector<SharedChain>& chains, const std::vector<Halfedge>& boundary) {
  const SharedChain* best = nullptr;
  for (const SharedChain& chain : chains) {
    if (!meets_only_along(chain, chains, boundary)) continue;
    if (best == nullptr || chain.length > best->length ||
        (chain.length == best->length && key_less(face_key(chain.neighbour), face_key(best->neighbour)))) {
      best = &chain;
    }
  }
  return best;
}

// Removes the chain's edges (and the vertices inside it, left isolated); returns the merged face.
Face merge_along(Arrangement& arrangement, const SharedChain& chain) {
  Face merged;
  for (const Halfedge edge : chain.edges) merged = arrangement.remove_edge(edge);
  return merged;
}

// Step 5. Fragments wait in a priority queue (smallest area, then face_key); an entry is stale
// once its face has been merged or re-queued (the generation no longer matches).
class FragmentMerger {
 public:
  FragmentMerger(Arrangement& arrangement, double min_area) : arrangement_(arrangement), min_area_(min_area) {}

  void run() {
    for (auto face = arrangement_.faces_begin(); face != arrangement_.faces_end(); ++face) {
      if (face->is_unbounded() || !face->data()) continue;
      FT area = face_area(face);
      if (area < min_area_) track(face, std::move(area));
    }
    while (!queue_.empty()) {
      const Entry next = queue_.top();
      queue_.pop();
      const auto state = fragments_.find(next.id);
      if (state != fragments_.end() && state->second.generation == next.generation) merge_or_wait(next.face);
    }
  }

 private:
  struct State {
    FT area;
    std::uint64_t generation;
    bool waiting;  // no neighbour to merge with, until a neighbour changes
  };
  struct Entry {
    FT area;
    std::vector<ExactPoint> key;
    Face face;
    FaceId id;  // &*face, taken while the face existed: a stale entry's face may be gone
    std::uint64_t generation;
  };
  // Orders the queue so that its top is the entry to process first.
  struct Later {
    bool operator()(const Entry& a, const Entry& b) const {
      if (a.area != b.area) return b.area < a.area;
      if (key_less(b.key, a.key)) return true;
      if (key_less(a.key, b.key)) return false;
      return b.generation < a.generation;
    }
  };

  void track(Face face, FT area) {
    fragments_[&*face] = State{std::move(area), 0, false};
    enqueue(face);
  }

  void enqueue(Face face) {
    State& state = fragments_.at(&*face);
    state.generation = ++generation_;
    queue_.push(Entry{state.area, face_key(face), face, &*face, state.generation});
  }

  FT area_of(Face face) const {
    const auto state = fragments_.find(&*face);
    return state != fragments_.end() ? state->second.area : face_area(face);
  }

  void merge_or_wait(Face fragment) {
    const std::vector<Halfedge> boundary = outer_boundary(fragment);
    const std::vector<SharedChain> chains = shared_chains(fragment, boundary);
    const SharedChain* chain = chosen_chain(chains, boundary);
    if (chain == nullptr) {
      fragments_.at(&*fragment).waiting = true;
      return;
    }
    FT area = area_of(fragment) + area_of(chain->neighbour);
    fragments_.erase(&*fragment);
    fragments_.erase(&*chain->neighbour);
    const Face merged = merge_along(arrangement_, *chain);
    if (area < min_area_) track(merged, std::move(area));
    wake_neighbours(merged);
  }

  // A waiting fragment next to the merged face may now find a neighbour to merge with.
  void wake_neighbours(Face merged) {
    const auto wake_across = [&](Arrangement::Ccb_halfedge_circulator first) {
      auto edge = first;
      do {
        const Face face = edge->twin()->face();
        const auto state = fragments_.find(&*face);
        if (state != fragments_.end() && state->second.waiting) {
          state->second.waiting = false;
          enqueue(face);
        }
      } while (++edge != first);
    };
    wake_across(merged->outer_ccb());
    for (auto hole = merged->inner_ccbs_begin(); hole != merged->inner_ccbs_end(); ++hole) wake_across(*hole);
  }

  Arrangement& arrangement_;
  FT min_area_;
  std::uint64_t generation_ = 0;
  std::unordered_map<FaceId, State> fragments_;  // faces below min_area_; looked up, never iterated
  std::priority_queue<Entry, std::vector<Entry>, Later> queue_;
};

// ---------------------------------------------------------------------------------------------
// Blocks (step 6)

// The exact outer boundary of an inside face, counter-clockwise, collinear vertices dropped.
std::vector<ExactPoint> face_boundary(Arrangement::Face_const_handle face) {
  std::vector<ExactPoint> points;
  std::vector<const void*> vertices;
  const auto first = face->outer_ccb();
  auto halfedge = first;
  do {
    points.push_back(halfedge->source()->point());
    vertices.push_back(&*halfedge->source());
  } while (++halfedge != first);
  if (face->number_of_inner_ccbs() > 0) {
    const ExactPoint& on_loop = (*face->inner_ccbs_begin())->source()->point();
    fail(near(points.front()), "a closed loop of traces through (" + num(CGAL::to_double(on_loop.x())) +
         ", " + num(CGAL::to_double(on_loop.y())) + ") lies strictly inside it, so the block has a hole "
         "and is not a simple polygon; lengthen or move the traces so that the loop touches another "
         "trace or the region boundary");
  }
  std::sort(vertices.begin(), vertices.end());
  if (std::adjacent_find(vertices.begin(), vertices.end()) != vertices.end()) {
    fail(near(points.front()), "its boundary touches itself at a vertex (traces meet the rest "
         "of the boundary in a single point), so the block is not a simple polygon");
  }
  return drop_collinear(points);
}

// True when the rounded block is still counter-clockwise, simple and free of collinear vertices
// (exact predicates on the rounded doubles).
bool valid_after_rounding(const Polygon& block) {
  const std::vector<ExactPoint> v = to_exact(block);
  const std::size_t n = v.size();
  if (n < 3 || !CGAL::is_simple_2(v.begin(), v.end(), K())) return false;
  for (std::size_t i = 0; i < n; ++i) {
    if (CGAL::collinear(v[(i + n - 1) % n], v[i], v[(i + 1) % n])) return false;
  }
  return CGAL::orientation_2(v.begin(), v.end(), K()) == CGAL::COUNTERCLOCKWISE;
}

std::vector<Polygon> collect_blocks(const Arrangement& arrangement) {
  std::vector<Polygon> blocks;
  for (auto face = arrangement.faces_begin(); face != arrangement.faces_end(); ++face) {
    if (face->is_unbounded() || !face->data()) continue;
    const std::vector<ExactPoint> exact = face_boundary(face);
    Polygon block = to_doubles(exact);
    if (!valid_after_rounding(block)) {
      fail(near(exact.front()), "its vertices no longer form a valid polygon once rounded to "
           "double (a sliver thinner than the rounding); move the traces or the region apart");
    }
    blocks.push_back(std::move(block));
  }
  return blocks;
}

bool below_or_left(const Point2& a, const Point2& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; }

// Each polygon starts at its lowest, then leftmost vertex; polygons are sorted by their vertex
// sequences under the same order.
void order_polygons(std::vector<Polygon>& polygons) {
  for (Polygon& p : polygons) std::rotate(p.begin(), std::min_element(p.begin(), p.end(), below_or_left), p.end());
  std::sort(polygons.begin(), polygons.end(), [](const Polygon& a, const Polygon& b) {
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), below_or_left);
  });
}

bool strictly_convex(const std::vector<ExactPoint>& v) {
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!CGAL::left_turn(v[(i + n - 1) % n], v[i], v[(i + 1) % n])) return false;
  }
  return true;
}

}  // namespace

std::vector<std::vector<Point2>> cut_region(std::span<const Point2> region, std::span<const JointSet> sets,
                                            const CutOptions& options) {
  const std::vector<ExactPoint> boundary = validate_polygon("region", region);
  for (std::size_t i = 0; i < sets.size(); ++i) validate_set(i, sets[i]);
  if (!(std::isfinite(options.min_block_area) && options.min_block_area >= 0.0)) {
    fail("min_block_area", "expected a finite value >= 0, got " + num(options.min_block_area));
  }
  const std::vector<Segment> traces = make_traces(region, sets);
  Arrangement arrangement;
  build_arrangement(arrangement, boundary, traces);
  remove_dead_ends(arrangement);
  if (options.min_block_area > 0.0) FragmentMerger(arrangement, options.min_block_area).run();
  std::vector<Polygon> blocks = collect_blocks(arrangement);
  order_polygons(blocks);
  return blocks;
}

std::vector<std::vector<Point2>> convex_partition(std::span<const Point2> polygon) {
  const std::vector<ExactPoint> vertices = drop_collinear(validate_polygon("polygon", polygon));
  std::vector<Polygon> parts;
  if (strictly_convex(vertices)) {
    parts.push_back(to_doubles(vertices));
  } else {
    using PartitionTraits = CGAL::Partition_traits_2<K>;
    std::list<PartitionTraits::Polygon_2> pieces;
    CGAL::optimal_convex_partition_2(vertices.begin(), vertices.end(), std::back_inserter(pieces),
                                     PartitionTraits());
    for (const PartitionTraits::Polygon_2& piece : pieces) {
      const std::vector<ExactPoint> part(piece.vertices_begin(), piece.vertices_end());
      parts.push_back(to_doubles(drop_collinear(part)));
    }
  }
  order_polygons(parts);
  return parts;
}

double polygon_area(std::span<const Point2> polygon) {
  if (polygon.size() < 3) return 0.0;
  const Point2 origin = polygon[0];
  double twice_area = 0.0;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const double ax = polygon[i].x - origin.x, ay = polygon[i].y - origin.y;
    const double bx = polygon[i + 1].x - origin.x, by = polygon[i + 1].y - origin.y;
    twice_area += ax * by - ay * bx;
  }
  return 0.5 * twice_area;
}

}  // namespace rockcontact::kernel
