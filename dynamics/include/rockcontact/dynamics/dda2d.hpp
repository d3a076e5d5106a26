#pragma once
// Explicit 2D DDA with potential contact and Coulomb friction (seed 000 §2, §3.2.4-§3.3).
//
// Each block carries d = (u0, v0, r0, ex, ey, gxy) (eq. 2): centroid translation, rotation and
// constant strain, with u(x, y) = T(x, y) d (eq. 3). Per step, from t_n to t_n+1 = t_n + h:
//   1. contacts: broad phase (skipped for a handful of blocks) -> overlap -> IP -> normal force
//      f_n and contact point pg (contact/potential_contact.hpp); tangential force by Coulomb
//      stick/slide on the accumulated relative displacement of pg (eq. 24-26); both applied
//      as T(xg, yg)^T f to CP and its negative to TP (eq. 22-23, 28-29);
//   2. F = gravity + contact + initial-stress force (K d folded into F as a step initial
//      stress, §2.3); M d'' = F with M = rho ∫ T^T T dA from the polygon moments (eq. 5a);
//   3. velocity Verlet (eq. 7-8): d'_{n+1/2} = d'_{n-1/2} + h d''_n, Δd = h d'_{n+1/2};
//   4. configuration update: vertices moved by the exact rotation about the centroid plus the
//      strain and translation, so a freely spinning block keeps its area (the first-order map
//      T inflates it by (1 + r0²) per step: the classic DDA free-rotation error);
//      friction records advanced by the relative displacement of pg (§3.2.6).
// Rigid blocks carry 3 DOF and skip every strain term; fixed blocks (§3.3 virtual polygons)
// take part in contact only. Frictionless laws keep no tangential state at all.

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/contact/potential_contact.hpp"
#include "rockcontact/kernel/number_policy.hpp"
#include "rockcontact/kernel/point.hpp"
#include "rockcontact/kernel/predicate_stats.hpp"

namespace rockcontact::dynamics {

using kernel::Point2;
using kernel::Vector2;

struct Material {
  double density = 2000.0;       // kg/m³
  double youngs_modulus = 1.0e9;  // Pa
  double poisson_ratio = 0.25;    // -
};

enum class PlaneMode { stress, strain };

struct BlockSpec {
  std::string id;
  std::vector<Point2> vertices;  // CCW, strictly convex, m
  Material material;
  bool fixed = false;  // a virtual polygon (§3.3): takes part in contact, never moves
  bool rigid = false;  // 3 DOF (u0, v0, r0): no strain terms
  Vector2 velocity;    // of the centroid, m/s
  double omega = 0.0;  // angular velocity, rad/s (CCW)
};

struct FrictionLaw {
  double kt = 1.0e7;               // tangential penalty, N/m (per metre of thickness)
  double friction_angle_deg = 0.0;  // phi
};

struct ContactLaw {
  contact::PotentialContactParams normal;
  std::optional<FrictionLaw> friction;  // empty: frictionless, no tangential state is kept
  kernel::PolicyKind policy = kernel::PolicyKind::filtered;
};

struct DdaParams {
  double dt = 1.0e-4;                // s
  Vector2 gravity{0.0, -9.81};       // m/s²
  PlaneMode plane = PlaneMode::stress;
  double mass_damping = 0.0;         // alpha of eq. 5c, 1/s (off by default, as in the paper)
};

struct BlockState {
  std::string id;
  std::vector<Point2> vertices;      // current, m, CCW
  Point2 centroid;                   // current, m
  double rotation = 0.0;             // rad since the start
  std::array<double, 6> velocity{};  // d' = (u0', v0', r0', ex', ey', gxy'), m/s, rad/s, 1/s
  std::array<double, 3> stress{};    // sigma_x, sigma_y, tau_xy, Pa (zero for rigid blocks)
  double area = 0.0;                 // m²
  double mass = 0.0;                 // kg per m of thickness
  bool fixed = false;
  bool rigid = false;
};

// All in J per metre of thickness. total() is conserved without friction and damping, up to
// the O(h²) error of the integrator and the contact penalty's stored energy.
struct Energies {
  double kinetic = 0.0;
  double gravitational = 0.0;  // m g·x relative to the start
  double strain = 0.0;
  double contact = 0.0;        // energy stored in the normal (and stick) penalty springs
  double friction_dissipated = 0.0;
  double damping_dissipated = 0.0;
  double total() const {
    return kinetic + gravitational + strain + contact + friction_dissipated + damping_dissipated;
  }
};

// The run cannot go on meaningfully; what() says why and with which numbers.
class StabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Dda2d {
 public:
  // Validates everything (throws kernel::InvalidPolygon naming the block, std::invalid_argument
  // naming the parameter) and refuses dt above the critical estimate 2 / omega_max from the
  // largest block and contact stiffness (StabilityError).
  Dda2d(std::vector<BlockSpec> blocks, ContactLaw law, DdaParams params);

  // One step; throws StabilityError on NaN, on energy growth beyond what the integrator can
  // explain, or on penetration deeper than the blocks themselves.
  void step();

  double time() const noexcept;
  std::size_t steps() const noexcept;
  const std::vector<BlockState>& blocks() const noexcept;
  Energies energies() const;
  double critical_time_step() const noexcept;  // s
  double max_penetration() const noexcept;     // largest minimum-translation distance seen, m
  kernel::PredicateCounters predicate_counters() const noexcept;  // spent by this simulation

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace rockcontact::dynamics
