#include "rockcontact/contact/embed/pair_contact.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact {
namespace {

contact::PotentialContactParams law_params(const PairContactParams& p) {
  contact::PotentialContactParams law;
  law.kn = p.kn;
  law.H = p.H;
  law.demarcation = p.demarcation;
  law.small_edge_fraction = p.small_edge_fraction;
  return law;
}

// A placeholder until the first evaluate(): ConvexPolygon is always a valid polygon.
kernel::ConvexPolygon unit_triangle(std::string name) {
  return kernel::ConvexPolygon::make(std::move(name), {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}});
}

// World vertices of a posed polygon into `out` (reusing its storage). With theta = 0 only the
// translation is added, so a host's axis-aligned or world-frame input keeps its exact values.
void place(const char* name, std::span<const double> xy, const Pose2& pose,
           std::vector<kernel::Point2>& out) {
  if (xy.size() % 2 != 0) {
    throw std::invalid_argument(std::string("polygon ") + name + ": " + std::to_string(xy.size()) +
                                " coordinates given; interleaved x, y pairs expected");
  }
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw std::invalid_argument(std::string("polygon ") + name +
                                ": the pose (x, y, theta) must be finite");
  }
  const std::size_t n = xy.size() / 2;
  out.resize(n);
  if (pose.theta == 0.0) {
    for (std::size_t k = 0; k < n; ++k) out[k] = {pose.x + xy[2 * k], pose.y + xy[2 * k + 1]};
    return;
  }
  const double c = std::cos(pose.theta), s = std::sin(pose.theta);
  for (std::size_t k = 0; k < n; ++k) {
    const double u = xy[2 * k], v = xy[2 * k + 1];
    out[k] = {pose.x + (c * u - s * v), pose.y + (s * u + c * v)};
  }
}

double perimeter(std::span<const kernel::Point2> polygon) {
  double sum = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const kernel::Point2 p = polygon[k], q = polygon[(k + 1) % polygon.size()];
    sum += std::hypot(q.x - p.x, q.y - p.y);
  }
  return sum;
}

}  // namespace

PairContactParams default_pair_contact_params() { return {}; }

struct PairEvaluator::Impl {
  explicit Impl(const PairContactParams& p) : params(p), law(law_params(p)) {}

  template <kernel::NumberPolicy Policy>
  void evaluate(PairContact& out) {
    contact::evaluate_pair<Policy>(a, b, law, workspace, result);
    out.status = static_cast<PairStatus>(result.status);
    out.force[0] = result.force.x;
    out.force[1] = result.force.y;
    out.has_point = result.point.has_value();
    if (out.has_point) {
      out.point[0] = result.point->x;
      out.point[1] = result.point->y;
    }
    out.area = result.area;
    if (result.status == kernel::Overlap::overlap) {
      out.penetration = kernel::compute_penetration_depth<Policy>(a, b);
      out.length = 0.5 * perimeter(result.ip);
    }
  }

  PairContactParams params;
  contact::PotentialContactParams law;
  std::vector<kernel::Point2> world_a, world_b;
  kernel::ConvexPolygon a = unit_triangle("a");
  kernel::ConvexPolygon b = unit_triangle("b");
  contact::PairWorkspace workspace;
  contact::PairResult result;
};

PairEvaluator::PairEvaluator(const PairContactParams& params)
    : impl_(std::make_unique<Impl>(params)) {
  contact::check_params(impl_->law);
}

PairEvaluator::~PairEvaluator() = default;
PairEvaluator::PairEvaluator(PairEvaluator&&) noexcept = default;
PairEvaluator& PairEvaluator::operator=(PairEvaluator&&) noexcept = default;

PairContact PairEvaluator::evaluate(std::span<const double> a_xy, const Pose2& a_pose,
                                    std::span<const double> b_xy, const Pose2& b_pose) {
  Impl& m = *impl_;
  const kernel::PredicateCounters before = kernel::predicate_counters();
  place("a", a_xy, a_pose, m.world_a);
  place("b", b_xy, b_pose, m.world_b);
  m.a.assign(m.world_a);
  m.b.assign(m.world_b);
  PairContact out;
  kernel::with_policy(m.params.policy, [&](auto policy) { m.evaluate<decltype(policy)>(out); });
  const kernel::PredicateCounters spent = kernel::predicate_counters() - before;
  out.predicates = spent.total_calls();
  out.fallbacks = spent.total_fallbacks();
  return out;
}

std::span<const kernel::Point2> PairEvaluator::intersection_polygon() const noexcept {
  return impl_->result.ip;
}

const PairContactParams& PairEvaluator::params() const noexcept { return impl_->params; }

}  // namespace rockcontact
