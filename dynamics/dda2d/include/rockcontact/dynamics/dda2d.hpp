#pragma once
// Explicit 2D DDA with potential contact, Coulomb friction and contact damping (seed 000 §2,
// §3.2.4-§3.3).
//
// Each block carries d = (u0, v0, r0, ex, ey, gxy) (eq. 2): centroid translation, rotation and
// constant strain, with u(x, y) = T(x, y) d (eq. 3). Per step, from t_n to t_n+1 = t_n + h:
//   1. contacts: broad phase (above 8 blocks a uniform grid, kept from step to step as a Verlet
//      list; every pair below) -> pairs whose bounding boxes' interiors overlap -> overlap ->
//      IP -> normal force f_n and contact point pg (contact/potential_contact.hpp), measured
//      for all candidate pairs in parallel (OpenMP), then assembled in pair order;
//      tangential force from the relative displacement of pg (contact/friction.hpp: the
//      elastoplastic law by default, the paper's eq. 24-26 on request); the contact dashpot f_d
//      (below); f = f_n + f_t + f_d applied as T(xg, yg)^T f to CP and its negative to TP
//      (eq. 22-23, 28-29). For a pair of blocks (i, j), i < j, CP is block i;
//   2. F = gravity (m g on u0, v0) + contact + initial-stress force (-S sigma on ex, ey, gxy:
//      K d folded into F as a step initial stress, §2.3); M d'' = F with M = rho ∫ T^T T dA
//      from the polygon's central moments (eq. 5a; the translation block decouples);
//   3. velocity Verlet (eq. 7-8), kept with full-step velocities:
//      d'_{n+1/2} = d'_n + h/2 d''_n,  Δd = h d'_{n+1/2},  d'_{n+1} = d'_{n+1/2} + h/2 d''_{n+1}
//      (the same positions as eq. 7's d'_{n+1/2} = d'_{n-1/2} + h d''_n);
//   4. configuration update: every vertex v moves to c + Δ(u0, v0) + R(Δr0) (I + Δε) (v - c),
//      with R the exact rotation matrix and Δε the strain increment, and the centroid is
//      recomputed from the new vertices. A freely spinning block therefore keeps its area; the
//      first-order map I + T would inflate it by (1 + Δr0²) per step (the classic DDA
//      free-rotation error). Friction records advance by the relative displacement of pg
//      under the same map (§3.2.6).
// Rigid blocks carry 3 DOF and skip every strain term; fixed blocks (§3.3 virtual polygons)
// take part in contact only. Frictionless laws keep no tangential state at all.
//
// ## Contact damping (not in seed 000)
// With a critical damping ratio zeta > 0 every contact carries a viscous dashpot on the relative
// velocity v of pg (CP's material point minus TP's, v = T d' of each block at pg):
//   f_d = -c_n (v . n) n - c_t (v - (v . n) n),   c = 2 zeta sqrt(m k)
// with n the unit normal force direction, m = m_i m_j / (m_i + m_j) the pair's reduced mass (the
// movable block's mass against a fixed one), k_n = 2 kn L / H the normal stiffness of a
// face-on-face overlap of length L (L = half the IP's perimeter, see the critical step below)
// and k_t = kt. The tangential dashpot acts only while the friction sticks (a sliding contact's
// shear force is the Coulomb limit alone). The normal springs are spread along the contact, and
// so is the normal dashpot: a relative rotation w = r0'_CP - r0'_TP of the two blocks opens one
// end of a contact of length L and closes the other, and c_n / L per unit length at a velocity
// w s over -L/2 <= s <= L/2 resists with the moment
//   m_d = -c_n L² / 12 w   (on CP; on TP the opposite).
// Without it a block rocking on a face would be undamped: its contact point is near the pivot,
// where the relative velocity vanishes (a lone block rocking on the floor lost 15 % of its
// kinetic energy a second with zeta = 0.1, and a 221-block pile stayed above 1e-6 of its
// released energy for 10 s). The force at t_n+1 uses the velocities d'_{n+1/2} of
// the step (the full-step velocities are not known before the force), the usual explicit DEM
// dashpot; its work is reported as damping dissipation. A dashpot lowers the stability limit of
// a spring-mass pair to 2 / omega (sqrt(1 + zeta²) - zeta), applied to the whole estimate.
//
// ## Non-convex blocks
// A non-convex block is split exactly into convex parts (kernel::convex_partition: the block's
// own vertices, no Steiner points) that move as one: one set of DOF, mass and moments of the
// whole outline. Contacts are found part against part, parts of one block never contact each
// other, and friction records are kept per pair of parts. Each part carries its own potential
// (seed 000 eq. 12-14 on the part), not the whole block's that §3.2.2 Fig. 5 asks for: inside a
// part, the exit distance through an internal partition edge is shorter than the distance to the
// block's boundary, so a block pressed into the region next to a partition edge (near a reflex
// corner) feels a weaker force than the whole-block potential would give. On the partition edge
// itself the two parts' contributions cancel exactly (equal φ of the other block, opposite
// normals), so the approximation adds no spurious force there.
//
// Departures from the paper, each for a stated reason:
//   * mass is conserved: the density is m / S with m = rho S at the start and S the current
//     area, so a strained block keeps its mass and momentum exactly;
//   * stress and strain rate turn with the block: sigma <- R (sigma + E Δε) R^T and the
//     strain-rate part of d' is rotated likewise, so a rotating stressed block keeps its strain
//     energy and kinetic energy (the paper accumulates sigma in fixed axes);
//   * mass damping (eq. 5c, off by default as in the paper) is integrated implicitly in the
//     second half kick, d'_{n+1} = (d'_{n+1/2} + h/2 M^-1 F_{n+1}) / (1 + alpha h/2).
//
// ## Initial equilibrium (not in seed 000; dynamics/common/equilibrium.hpp)
// Unless DdaParams::initial_equilibrium is off, the constructor settles the blocks connected to
// a fixed block through pairs resting on each other at t = 0 (overlapping, touching, or apart
// by at most 10⁻⁶ of the smaller perimeter, so that a block typed "on" a slope to 7 digits
// counts) into static equilibrium with gravity and their stresses, and releases them with their
// initial velocities. Blocks that start apart are untouched. The method is Newton's on the
// DDA's own system. The out-of-balance forces F(d) are the engine's (eq. 11's potential forces,
// gravity, -S sigma, and every tangential spring locked, contact::Slip::locked: no slip). The
// stiffness K stands for them: S E on the strains; along each contact line
// (contact_springs.hpp) the distributed normal spring 2 kn / H over the part where the gap is
// closed, at two Gauss points; the friction spring kt of each closed pair. Each iteration solves
// K Δd = F (a sparse Cholesky on the blocks' 6 x 6 blocks, common/src/block_cholesky.hpp)
// inside an open-close iteration that moves each line's closed part to where the solution
// leaves its gap negative (starting from the parts that overlap, and in a round's first
// iteration from those that touch as well), until no part's move changes its springs' force by
// more than a tenth of the tolerance times F_ref (below), then moves the blocks by Δd (at most a
// quarter of a block's inradius at once) and evaluates F again. An iteration that does not
// lower the ratio is followed by Levenberg-Marquardt damping (diag K). It stops when the
// out-of-balance force ratio
//   R = max_i |F_i| / F_ref,   |F_i|² = F_x² + F_y² + (F_r0² + F_ex² + F_ey² + F_gxy²) / r_i²
// (r_i the radius of gyration, so moments count as forces at that arm; F_ref = the largest
// block weight or normal contact force of the settling blocks, in the configuration reached)
// is below the tolerance. After 30 iterations without it, dynamic relaxation (as in "Static
// analysis" below, contacts locked) goes on from the state reached, for at most 20 000
// iterations, and gives up after 5 000 without a new least ratio (Equilibrium::converged says
// whether it got there; strict refuses it if not). A run whose pre-solve did not get there
// starts from the least out-of-balance state it found (Equilibrium::ratio is that state's).
// Rigid blocks settle in two or three iterations, a joint-cut mass of 32 x 32 deformable
// blocks in 8 (docs/performance.md, "The 2D initial equilibrium").
// A block whose solve would move it by more than its inradius (its resting contacts do not
// hold it: it topples, slides on a frictionless face or hangs in the air) has no static state
// there. Nor have blocks that drift off with small steps: K does not turn the contact forces
// with the blocks, so it misses the weight's turning moment on a leaning column, and a column
// taller than it can stand (a free column of blocks of width L and height s buckles where
// q h³ = 7.84 EI, EI = 2 kn L³ s / (12 H), a joint's rocking stiffness times the joints'
// spacing: 46 m for 1 m blocks at kn = 2 GPa, 23 m for 0.5 m blocks, 92 m for 2 m blocks)
// only stalls Newton's iterations. When they first stall (the damping reaches 1, or after 30
// iterations) a stability probe looks for such a mode. Newton's iteration carries an error e
// to (I + K⁻¹ J) e, J the engine's tangent; along a mode with J v = -lambda K v that is
// (1 - lambda) v, and lambda < 0 (the engine's stiffness along v is negative) shows as an
// eigenvalue above 1. Twelve power iterations from Newton's step find the dominant one, J v
// by finite differences of the engine's forces (the blocks moved by at most 10⁻⁶ of the
// smallest inradius, then restored); above 1.02, the blocks that move more than a quarter of the
// mode's largest move have no static state there. (For a free column the eigenvalue is about
// (h / h_cr)³: 1.31 at 50 m and 1.82 at 56 m in the case above.)
// Automatic (the default): blocks without a static state start from their given state, with
// the blocks resting on a support only through them, and are named in Equilibrium::unsettled;
// the rest are solved again from the start, without friction against the blocks left out (a
// neighbour that settles slides along a block that will topple or slide away instead of
// hanging on it). Strict: it is an error naming the first.
// The friction records keep the locked stretch: the run starts with the static tangential
// forces already in the springs, and a contact whose locked force exceeds its limit slips from
// the first step. The time, the energies and their reference positions start after it.
//
// ## Static analysis (Analysis::static_equilibrium)
// Dynamic relaxation, a run of its own: every movable block, the scene's friction law (a
// contact beyond its limit slips), one iteration per step, until the caller finds
// balance_ratio() (R above, F_ref at the start) below its tolerance. Each iteration is a step of
// h = 1 with each block's mass scaled so that a Gershgorin bound of its stiffness over all the
// contacts it can have gives omega h = 1, under kinetic damping (whenever the assembly's
// fictitious kinetic energy falls, every velocity is zeroed). It replaces Shi's static analysis
// (a dynamic step with the velocities zeroed after each), which at the scene's dt needs ~10⁶
// steps for a 20 m block. Velocities are zero throughout; the energies are not meaningful.
//
// ## Critical time step
// Velocity Verlet is stable for h < 2 / omega_max. The estimate of omega_max (documented
// conservative bounds, computed once at construction; the message of a rejection names the
// block or pair that set it):
//   * strain modes of each deformable block: the largest generalized eigenvalue of (K, M) on
//     (r0, ex, ey, gxy), K = S E (exact for the block alone);
//   * each pair with a movable block: omega² = (kn / H · L + kt) (c_i + c_j). The potential force
//     over a contact is kn / H · (depth) per unit length of the IP boundary (a face-on-face
//     contact of length l gives 2 kn l / H per unit depth: both faces of the thin IP count), and
//     that boundary is no longer than L = min(perimeter_i, perimeter_j) since the IP lies in
//     both blocks; c is the largest compliance of a point of the block (max over vertices of the
//     largest eigenvalue of T M^-1 T^T; zero for a fixed block). By the Rayleigh quotient this
//     bounds the pair's stiffest mode; kt enters only with friction. To stay O(n) the estimate
//     takes, over movable blocks i, (kn / H · P_i + kt) c_i times 2 when two movable blocks
//     exist (a partner as compliant as i: min(A_i, A_j)(c_i + c_j) <= 2 max(A_i c_i, A_j c_j)
//     with A = kn / H · P + kt) or times 1 when i can only meet fixed blocks (c_j = 0), with the
//     largest kn and kt of all interfaces. A block pressed by several neighbours at once can
//     exceed a single pair's estimate; the monitor below stops such a run.
//   * per block, the two add: omega_i² = strain bound + contact bound. Both stiffnesses act on
//     the same degrees of freedom (a block squeezed on every face dilates against its elastic
//     and its contact stiffness at once), and the largest eigenvalue of a sum of two symmetric
//     positive semi-definite operators is at most the sum of theirs (Weyl). The larger of the
//     two alone overestimated the limit by up to sqrt(2): robustness_tests/stiff measured a
//     squeezed square diverging at 0.878 of that older estimate.
// For the paper's sets (seed 000 Tables 4-5: rho 2000, E 0.1-1 GPa, kn 1e7-5e7 Pa, H ~ 1 m,
// blocks ~1 m, dt 1e-5 ... 1e-3 s) the estimate is 0.7 ms for a deformable 1 m square with
// E = 1 GPa (the strain modes limit it; the contact allows ~3.8 ms), above every listed dt.
//
// ## Stability monitor (StabilityError after the step that found it)
//   * a non-finite velocity, stress or vertex, naming the block;
//   * energy growth: total() - total(0) > 2 (kinetic(0) + strain(0) + max_t |gravitational(t)| +
//     E_floor), E_floor = Σ m (1 mm/s)² / 2: the energy tripled beyond all it could draw on.
//     A stable velocity-Verlet run keeps its energy within a factor 1 / (1 - (omega h / 2)²) of
//     the start, which stays below 3 for omega h < 1.63; a diverging run grows geometrically
//     and crosses the bound within a few steps;
//   * penetration: the minimum translation distance of an overlapping pair (entrance block,
//     computed under the Filtered policy) above half the smaller inradius of the two blocks:
//     the contact no longer holds the blocks apart (kn too small for the load, or too fast).

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/contact/friction/law.hpp"
#include "rockcontact/contact/potential2d/potential_contact.hpp"
#include "rockcontact/dynamics/equilibrium.hpp"
#include "rockcontact/dynamics/material.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::dynamics {

using kernel::Point2;
using kernel::Vector2;

enum class PlaneMode { stress, strain };

// dynamic: the explicit DDA. static_equilibrium: each step is one iteration of the dynamic
// relaxation of "Static analysis" over every movable block, under the scene's friction law
// (contacts may slip); the blocks' velocities stay zero and time only counts the steps.
enum class Analysis { dynamic, static_equilibrium };

struct BlockSpec {
  std::string id;                // non-empty, unique; names the block in every message
  // CCW, simple, no repeated or collinear vertex, m. A non-convex block is split exactly into
  // convex parts (kernel::convex_partition) that share the block's DOF; see "Non-convex blocks".
  std::vector<Point2> vertices;
  std::string group;  // selects the ContactLaw::interfaces that apply to it ("" : none)
  Material material;
  bool fixed = false;  // a virtual polygon (§3.3): takes part in contact, never moves
  bool rigid = false;  // 3 DOF (u0, v0, r0): no strain terms
  Vector2 velocity;    // of the centroid, m/s (zero for a fixed block)
  double omega = 0.0;  // angular velocity, rad/s (CCW; zero for a fixed block)
};

// kt (N/m per metre of thickness) and friction_angle_deg (phi, degrees in [0, 90)).
using FrictionLaw = contact::FrictionLaw;

// The contact properties between blocks of two groups, replacing the defaults of ContactLaw
// for every pair with one block in each (the order of `groups` does not matter).
struct Interface {
  std::array<std::string, 2> groups;
  double kn = 1.0e7;                    // Pa, finite > 0
  std::optional<FrictionLaw> friction;  // empty: frictionless
};

struct ContactLaw {
  contact::PotentialContactParams normal;  // kn, H and demarcation of every pair
  std::optional<FrictionLaw> friction;  // empty: frictionless, no tangential state is kept
  double damping_ratio = 0.0;           // zeta of the contact dashpots, finite >= 0 (0: none)
  kernel::PolicyKind policy = kernel::PolicyKind::filtered;
  // Per pair of groups: kn and friction (H and the demarcation stay those of `normal`). At most
  // one interface per pair of groups.
  std::vector<Interface> interfaces;
};

struct DdaParams {
  double dt = 1.0e-4;                // s, finite > 0 and <= the critical estimate
  Vector2 gravity{0.0, -9.81};       // m/s²
  PlaneMode plane = PlaneMode::stress;
  double mass_damping = 0.0;         // alpha of eq. 5c, 1/s, >= 0 (off by default, as in the paper)
  // Threads of the contact pass (0: one per core). The result does not depend on it: every
  // candidate pair is measured independently and the contacts are assembled in pair order.
  std::size_t threads = 0;
  // Bring the contacts present at the start into static equilibrium with the loads before the
  // run ("Initial equilibrium" above), to an out-of-balance force ratio below the tolerance.
  InitialEquilibrium initial_equilibrium = InitialEquilibrium::automatic;
  double equilibrium_tolerance = 1.0e-6;  // in (0, 1)
  EquilibriumProgress equilibrium_progress;  // optional
  Analysis analysis = Analysis::dynamic;
};


struct BlockState {
  std::string id;
  std::vector<Point2> vertices;      // current, m, CCW
  Point2 centroid;                   // current, m
  double rotation = 0.0;             // rad since the start
  std::array<double, 6> velocity{};  // d' = (u0', v0', r0', ex', ey', gxy'), m/s, rad/s, 1/s
  std::array<double, 3> stress{};    // sigma_x, sigma_y, tau_xy, Pa (zero for rigid blocks)
  double area = 0.0;                 // m²
  double mass = 0.0;                 // kg per m of thickness (constant)
  bool fixed = false;
  bool rigid = false;
};

// A pair in contact at the current instant: its polygons overlap and the force is non-zero.
struct ContactState {
  std::size_t cp = 0;        // index of CP in blocks(): the lower index of the pair
  std::size_t tp = 0;        // index of TP: the higher
  std::size_t cp_part = 0;   // convex part of CP (0 for a convex block)
  std::size_t tp_part = 0;   // convex part of TP
  Point2 point;              // contact point pg, m
  Vector2 normal_force;      // on CP, N/m; on TP the opposite
  Vector2 friction_force;    // on CP, N/m; on TP the opposite; zero when frictionless
  Vector2 damping_force;     // the dashpot's, on CP, N/m; on TP the opposite; zero without one
  double damping_moment = 0.0;  // the rocking dashpot's, on CP, N m/m; on TP the opposite
  bool sliding = false;      // the friction force is at the Coulomb limit (always, when
                             // frictionless: the limit is zero)
  double penetration = 0.0;  // minimum translation distance that separates the pair, m
};

// All in J per metre of thickness, at the current instant. total() is conserved up to the
// O(h²) error of the integrator.
struct Energies {
  double kinetic = 0.0;        // ½ d'^T M d' summed over blocks
  double gravitational = 0.0;  // -m g·(c - c_0) summed over blocks: relative to the start
  double strain = 0.0;         // ½ S sigma^T E^-1 sigma summed over deformable blocks
  // Work done against the contact forces since the start, minus friction_dissipated and the
  // dashpots' share of damping_dissipated: the energy held by the normal and tangential penalty
  // springs. Accumulated per step as -½ (F_c(t_n) + F_c(t_n+1))·Δd over the blocks (trapezoid
  // in time, F_c the generalized contact force), so it is zero at the start even for blocks
  // that start overlapping.
  double contact = 0.0;
  // Energy the friction slip dissipated: paper law Σ |f_t|·|tangential slip increment| over
  // sliding steps; elastoplastic law the return mapping's (contact/friction.hpp).
  double friction_dissipated = 0.0;
  // Kinetic energy removed by the mass damping plus the work done against the contact dashpots.
  double damping_dissipated = 0.0;
  double total() const {
    return kinetic + gravitational + strain + contact + friction_dissipated + damping_dissipated;
  }
};

// Everything a simulation carries from one step to the next, so that a run resumed from it
// (the Dda2d constructor taking a Snapshot) goes on bit-identically. What the geometry
// determines (areas, centroids, mass matrices, convex parts, stability estimates) is not in it:
// it is recomputed from the blocks as given and the vertices below, which gives the same bits.
struct Snapshot {
  struct Block {
    std::vector<Point2> vertices;      // current, m
    double rotation = 0.0;             // rad since the start
    std::array<double, 6> velocity{};  // d'
    std::array<double, 3> stress{};    // Pa
    Point2 reference_centroid;         // of the gravitational energy, m
    // The generalized forces at the current instant: total, its contact part, the dashpots'
    // part of that, and the acceleration M^-1 force the next step starts from.
    std::array<double, 6> force{}, contact_force{}, dashpot_force{}, acceleration{};
  };
  // The friction record of a pair of convex parts in contact.
  struct Spring {
    std::size_t cp = 0, tp = 0, cp_part = 0, tp_part = 0;
    contact::FrictionState state;
  };
  // The relaxation of a static analysis (empty in a dynamic run).
  struct Relaxation {
    std::vector<char> moving;                      // per block
    std::vector<double> mass_scale;                // per block
    std::vector<std::array<double, 6>> velocity;  // per block
    double reference = 0.0;                        // N/m
    double kinetic = 0.0;                          // of the kinetic damping, J/m
  };
  double time = 0.0;  // s
  std::size_t steps = 0;
  std::vector<Block> blocks;           // one per block, in the simulation's order
  std::vector<ContactState> contacts;  // as contacts() returns them
  std::vector<Spring> springs;         // in pair order
  Relaxation relaxation;
  // The energy bookkeeping (J/m) and the monitor's baseline.
  double contact_work = 0.0, friction_dissipated = 0.0, mass_damping_dissipated = 0.0,
         dashpot_dissipated = 0.0;
  double initial_total = 0.0, initial_budget = 0.0, max_gravitational = 0.0;
  double max_penetration = 0.0;  // m
  Equilibrium equilibrium;
  kernel::PredicateCounters predicates;
};

// The run cannot go on meaningfully; what() says why and with which numbers.
class StabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Dda2d {
 public:
  // Validates everything (throws kernel::InvalidPolygon naming the block, std::invalid_argument
  // naming the parameter or block, or the two blocks that overlap at the start by more than the
  // monitor's penetration limit below) and refuses dt above the critical estimate 2 / omega_max
  // from the largest block and contact stiffness (StabilityError naming dt, the estimate and
  // the block or pair that set it). Evaluates the forces at t = 0 (contacts() is valid).
  Dda2d(std::vector<BlockSpec> blocks, ContactLaw law, DdaParams params);

  // Resumes the simulation `from` was taken of, which was built from the same blocks, law and
  // params: no pre-solve, no first force evaluation, the state and bookkeeping as they were.
  // Throws what the other constructor throws, and std::invalid_argument when `from` does not
  // fit the blocks (their count or a block's vertex count differs, a contact or spring names a
  // block or part that does not exist, a frictional contact has no spring).
  Dda2d(std::vector<BlockSpec> blocks, ContactLaw law, DdaParams params, const Snapshot& from);

  // The state at the current instant, to resume from later (checkpoint.hpp writes it to a file).
  Snapshot snapshot() const;

  // One step; throws StabilityError on NaN, on energy growth beyond what the integrator can
  // explain, or on penetration deeper than the blocks themselves (see the monitor above).
  // After a StabilityError the state is that of the failed step, for inspection only.
  void step();

  double time() const noexcept;
  std::size_t steps() const noexcept;
  const std::vector<BlockState>& blocks() const noexcept;
  const std::vector<ContactState>& contacts() const noexcept;  // at the current instant
  Energies energies() const;
  double critical_time_step() const noexcept;  // s; +infinity when nothing limits it
  // What set critical_time_step(): "block 'A': elastic stiffness (...)", "block 'A': contacts
  // (...)" or "block 'A': elastic stiffness (...) plus its contacts (...)"; empty when nothing
  // limits it.
  const std::string& critical_time_step_source() const noexcept;
  double max_penetration() const noexcept;     // largest minimum-translation distance seen, m
  const Equilibrium& initial_equilibrium() const noexcept;
  // Static analysis: the out-of-balance force ratio R of "Initial equilibrium" over the movable
  // blocks at the current instant (0 when nothing loads them). Dynamic analysis: 0.
  double balance_ratio() const;
  kernel::PredicateCounters predicate_counters() const noexcept;  // spent by this simulation

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace rockcontact::dynamics
