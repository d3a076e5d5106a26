#include "rockcontact/dynamics/apps/safety_factor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>
#include <utility>

namespace rockcontact::dynamics {
namespace {

constexpr double degrees_per_radian = 180.0 / std::numbers::pi;

std::string number_text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

void check_params(const SafetyFactorParams& p) {
  const auto refuse = [](const std::string& field, const std::string& expected, double got) {
    throw std::invalid_argument("safety_factor." + field + ": expected " + expected + ", got " + number_text(got));
  };
  if (!(std::isfinite(p.settle_time) && p.settle_time >= 0.0)) refuse("settle_time", "a finite time >= 0 s", p.settle_time);
  if (!(std::isfinite(p.time) && p.time > p.settle_time)) refuse("time", "a finite time > settle_time", p.time);
  if (!(p.slip_ratio > 0.0 && p.slip_ratio < 1.0)) refuse("slip_ratio", "a ratio in (0, 1)", p.slip_ratio);
  if (!(std::isfinite(p.min_factor) && p.min_factor > 0.0)) refuse("min_factor", "a finite factor > 0", p.min_factor);
  if (!(std::isfinite(p.max_factor) && p.max_factor > p.min_factor)) {
    refuse("max_factor", "a finite factor > min_factor", p.max_factor);
  }
  if (!(p.tolerance > 0.0 && p.tolerance < 1.0)) refuse("tolerance", "a ratio in (0, 1)", p.tolerance);
  if (!(std::isfinite(p.damping_ratio) && p.damping_ratio >= 0.0)) {
    refuse("damping_ratio", "a finite ratio >= 0", p.damping_ratio);
  }
}

// The strength properties of a law, as an interface carries them.
Interface3d strength_of(const ContactLaw3d& law, const std::string& a, const std::string& b) {
  for (const Interface3d& f : law.interfaces) {
    if (std::minmax(f.groups[0], f.groups[1]) == std::minmax(a, b)) return f;
  }
  return {{a, b}, law.friction_angle_deg, law.cohesion, law.tensile_strength};
}

Interface3d reduced(Interface3d f, double factor) {
  f.friction_angle_deg = std::atan(std::tan(f.friction_angle_deg / degrees_per_radian) / factor) * degrees_per_radian;
  f.cohesion /= factor;
  return f;
}

// Step 1 of the header: the blocks with `block` in a group of its own, and the law with one
// interface per group of the others, each the one that governed the pair, reduced by F.
class Reduction {
 public:
  Reduction(const std::vector<Block3dSpec>& blocks, const ContactLaw3d& law, std::size_t block)
      : blocks_(blocks), law_(law), block_(block) {
    std::set<std::string> groups;
    for (const Block3dSpec& b : blocks) groups.insert(b.group);
    for (const Interface3d& f : law.interfaces) groups.insert(f.groups.begin(), f.groups.end());
    own_ = "safety_factor:" + blocks[block].id;
    while (groups.count(own_) != 0) own_ += "'";
    std::set<std::string> others;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      if (i != block) others.insert(blocks[i].group);
    }
    const std::string& group = blocks[block].group;
    for (const std::string& other : others) {
      Interface3d f = strength_of(law, group, other);
      f.groups = {own_, other};
      governing_.push_back(f);
    }
    const auto first = std::find_if(law.interfaces.begin(), law.interfaces.end(), [&](const Interface3d& f) {
      return f.groups[0] == group || f.groups[1] == group;
    });
    first_ = first != law.interfaces.end()
                 ? *first
                 : Interface3d{{group, group}, law.friction_angle_deg, law.cohesion, law.tensile_strength};
  }

  std::vector<Block3dSpec> blocks() const {
    std::vector<Block3dSpec> out = blocks_;
    out[block_].group = own_;
    return out;
  }

  ContactLaw3d law(double factor) const {
    ContactLaw3d out = law_;
    for (const Interface3d& f : governing_) out.interfaces.push_back(reduced(f, factor));
    return out;
  }

  // The friction angle of the first law governing a pair with the block, reduced by F.
  double first_angle_deg(double factor) const { return reduced(first_, factor).friction_angle_deg; }

 private:
  const std::vector<Block3dSpec>& blocks_;
  const ContactLaw3d& law_;
  std::size_t block_;
  std::string own_;
  std::vector<Interface3d> governing_;
  Interface3d first_;
};

double distance(const kernel::Point3& p, const kernel::Point3& q) { return std::hypot(p.x - q.x, p.y - q.y, p.z - q.z); }

// Step 2: one trial, a fresh run judged by the header's criterion against `slip` (m).
SafetyTrial run_trial(const Reduction& reduction, const Dda3dParams& params, std::size_t block,
                      const SafetyFactorParams& safety, double factor, double slip) {
  const auto start = std::chrono::steady_clock::now();
  SafetyTrial trial;
  trial.factor = factor;
  ContactLaw3d law = reduction.law(factor);
  law.damping_ratio = std::max(law.damping_ratio, safety.damping_ratio);
  Dda3d sim(reduction.blocks(), law, params);
  // The step's times are sums of binary fractions of dt: a relative slack keeps t = 0.05 s from
  // taking one more step for its rounding.
  const double slack = 1e-9 * safety.time;
  while (sim.time() < safety.settle_time - slack) sim.step();
  const kernel::Point3 settled = sim.blocks()[block].centroid;
  while (sim.time() < safety.time - slack && !trial.slid) {
    sim.step();
    trial.displacement = std::max(trial.displacement, distance(sim.blocks()[block].centroid, settled));
    trial.slid = trial.displacement > slip;
  }
  trial.run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return trial;
}

// The closed constraints the block takes part in (header, "Settling").
std::size_t closed_constraints(const Dda3d& sim, std::size_t block) {
  std::size_t closed = 0;
  for (const Contact3dState& c : sim.contacts()) {
    closed += (c.block_a == block || c.block_b == block) && c.mode != ContactMode3d::open;
  }
  return closed;
}

}  // namespace

SafetyFactorResult safety_factor(const std::vector<Block3dSpec>& blocks, const ContactLaw3d& law,
                                 const Dda3dParams& params, const std::string& block_id,
                                 const SafetyFactorParams& safety) {
  check_params(safety);
  const auto it = std::find_if(blocks.begin(), blocks.end(), [&](const Block3dSpec& b) { return b.id == block_id; });
  if (it == blocks.end()) throw std::invalid_argument("safety_factor: block '" + block_id + "': no such block");
  if (it->fixed) throw std::invalid_argument("safety_factor: block '" + block_id + "': is fixed, it cannot slide");
  const auto block = static_cast<std::size_t>(it - blocks.begin());
  const Reduction reduction(blocks, law, block);

  SafetyFactorResult out;
  const Dda3d start(blocks, law, params);
  out.slip = safety.slip_ratio * std::cbrt(start.blocks()[block].volume);
  const std::size_t closed = closed_constraints(start, block);
  if (closed > 0) {
    const double weight = start.blocks()[block].mass * std::hypot(params.gravity[0], params.gravity[1], params.gravity[2]);
    out.settling = weight / (static_cast<double>(closed) * std::min(law.kn, law.kt));
  }
  if (out.settling >= settling_warning * out.slip) {
    out.warnings.push_back("the contacts let block '" + block_id + "' settle about " + number_text(out.settling) +
                           " m (its weight over " + std::to_string(closed) + " closed constraints times min(kn, kt)), " +
                           number_text(out.settling / out.slip) + " of the slip threshold " + number_text(out.slip) +
                           " m: a trial may be called sliding for its settling alone; raise kn and kt, or the "
                           "threshold (--slip)");
  }
  const auto trial = [&](double factor) {
    out.trials.push_back(run_trial(reduction, params, block, safety, factor, out.slip));
    return out.trials.back().slid;
  };
  double lo = safety.min_factor, hi = safety.max_factor;
  if (!trial(hi)) {
    out.status = SafetyStatus::stable_at_max;
    out.factor_of_safety = hi;
  } else if (trial(lo)) {
    out.status = SafetyStatus::slides_at_min;
    out.factor_of_safety = lo;
  } else {
    while (hi / lo - 1.0 > safety.tolerance) {
      const double mid = std::sqrt(lo * hi);
      (trial(mid) ? hi : lo) = mid;
    }
    out.factor_of_safety = std::sqrt(lo * hi);
  }
  out.iterations = out.trials.size();
  out.critical_friction_angle_deg = reduction.first_angle_deg(out.factor_of_safety);
  return out;
}

}  // namespace rockcontact::dynamics
