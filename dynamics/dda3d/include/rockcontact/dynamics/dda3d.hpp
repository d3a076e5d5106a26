#pragma once
// Implicit 3D DDA with the generalized contact model (seed 001 §3-§5; the block kinematics and
// the global equation of Shi's 3D DDA).
//
// Each movable block carries the increments over a step of
//   D = (u0, v0, w0, rx, ry, rz, ex, ey, ez, gyz, gzx, gxy)      (eq. 9; rigid blocks: 6)
// with u(x) = T(x - c) D (eq. 10-12). A step from t_n to t_n+1 = t_n + h:
//   1. contacts (§4.1): candidate pairs whose boxes, widened by the detection range, overlap ->
//      the kernel's generalized constraints of each pair of blocks (two contact points, a plane,
//      feature ids; kernel/3d/contact_constraints.hpp) closer than the detection range, less
//      those deeper than it (no step moves a vertex that far: such a vertex crossed an internal
//      face of a non-convex block and the part it is in would push it out through its far
//      side; the neighbouring part's constraint holds it), and edge-edge crossings of edges
//      within 10⁻³ (sine) of parallel (the vertex contacts at the ends of their overlap carry
//      it). A vertex-edge or vertex-vertex constraint whose points lie apart along its plane
//      by more than 10⁻³ of the smaller block's size (a vertex slid along a face's plane past
//      the face's edge, as a wedge's daylight vertex past the free face) takes the line of its
//      points as its normal and their distance as its gap: on the plane its gap would be zero,
//      and the vertex would be carried beyond the rock. The contact list remembers (§4.2): a constraint closed at the previous step keeps
//      its plane while its features stay in contact (a vertex over its face, two vertices
//      within the range, a crossing on both edges), replacing the kernel's shortest exit, which
//      next to a concave edge of a non-convex block can name a face the vertex never came
//      through (dda3d.cpp, hold_contacts). The held and the found constraints of a pair are
//      one per contact position (kernel::merge_coincident, the held first): constraints with
//      one normal closer than 10⁻³ of the smaller block's size are one contact, as a vertex held
//      on a face and the face's corner found on the vertex's block are where two cut blocks
//      share a corner (seed 001 Table 4's six constraints on the §6.1 wedge, not 24 counting
//      each part and each block's vertex). A constraint identified by its pair and its two
//      features keeps its mode and tangential spring; one whose features changed (a crossing
//      past an edge's end) takes them over from the vanished constraint of the pair within a
//      step's largest motion and 15° of its normal (contact transfer); any other starts as
//      §2.4's Table 1 predicts from its gap d0 and its points' relative velocity v0: locked
//      when d0 + h n . v0 <= 0 (it penetrates, or closes within the step), open otherwise. One
//      closed by the prediction at d0 > 0 holds no spring energy and no tension until it has
//      been through a step;
//   2. the global equation (eq. 13), one sparse symmetric system in the unknowns of every movable
//      block (fixed blocks have none):
//        (2 M / h² + K_e + K_c) D = F_g + (2 / h) M v_n - V σ_n + F_c
//      M = ρ ∫ TᵀT dV, K_e = V C on the strain unknowns, F_g the gravity load, σ_n the stress at
//      t_n, and K_c, F_c the penalty terms of the closed constraints (eq. 24 normal, eq. 29
//      tangent locked, eq. 32 the explicit friction force of a sliding one); solved by
//      Eigen::SimplicialLDLT (or preconditioned CG, Dda3dParams::solver);
//   3. the open-close iteration (§4.3): every constraint's mode is re-decided from the solution
//      (contact_terms3d.hpp: Table 2 with the project's elastoplastic tangential spring); while a
//      contact changes between open and closed, or a locked one gives way to sliding (the solve
//      held it with its full stiffness), the system is re-assembled and solved again, at most
//      Dda3dParams::max_open_close times. Within it (§4.3's additional operations, once per
//      constraint and step, each forcing another solve when it changes the constraint):
//      a vertex-face or edge-edge contact that closes within the step (found apart, penetrating
//      after the solve) moves to where its features meet under a linear relative motion, its
//      tangential spring starting from -t P Δr (§5.1, eq. 41-47: only the motion after the
//      touch stretches it); and a closed vertex-edge or vertex-vertex contact re-runs the
//      shortest exit over the kernel's candidate planes with the solve's points (§4.3 (1)), so
//      a vertex driven past an edge leaves by the face it went through;
//   4. step control (§5.2, eq. 48-50): the step is cut (h / 2) and redone from t_n when the
//      iteration does not converge, when a vertex moves farther than max_displacement_ratio
//      times the scene's size (the diagonal of its bounding box at the start), or when a block
//      turns by more than max_rotation_deg (1° by default, the low end of §5.2's 1-3°: the
//      plane of a contact on the block turns with it, and the step's constant normal then errs
//      in the normal penetration by the relative displacement times sin θ, eq. 48); it grows
//      back by a factor 1.5 per accepted step up to Dda3dParams::dt;
//   5. update: v_n+1 = 2 D / h - v_n (the constant-acceleration step of DDA), σ_n+1 = σ_n + C ε,
//      every vertex moved by x -> c + u0 + R(r) (I + ε) (x - c) with the exact rotation R(r)
//      (block_matrices3d.hpp): a spinning block keeps its volume, where the first-order map
//      I + T would inflate it by 1 + |r|² a step (§5.2); the constraints' springs commit.
// Initial equilibrium (Dda3dParams::initial_equilibrium, "auto" by default; not in seed 001;
// dynamics/common/equilibrium.hpp): a block
// released at zero tangential stretch under gravity is not in equilibrium; its springs load
// from zero and overshoot, and near the friction limit the overshoot slides it (the §6.1
// wedge crept 3 cm in 1 s at a factor 2 % below its factor of safety). The constructor first
// solves for the static equilibrium of the blocks resting on a fixed block at the start,
// directly or through other resting blocks (gaps up to 10⁻⁶ of the scene's size count): one
// implicit solve without inertia, K D = F_g - V σ + F_c, every closed constraint locked
// whatever its friction, the open-close iteration deciding which close. Where that leaves
// springs stretched past their Coulomb cap (a block friction alone cannot hold, a wedge below
// its factor of safety), those contacts slide and the solve is repeated until no further
// contact passes its cap and the slip directions settle (at most 12 times): the blocks start
// in their sliding state, with the normal forces of the slide and the friction at the cap along
// the slip, where the locked solve put them along the slide (a mass whose contacts then leave a
// mode almost free keeps the locked start). A block at the margin, whose slip turns back at every
// repetition (its friction at the cap exceeds the load along the slide), is held: its contacts
// lock with the friction that resisted the load and relax to what it needs, those then past
// their cap sliding. The blocks move there with their stresses and springs loaded and
// keep their initial velocities; the energies' references start after it. A block its resting contacts do not hold (the solve would move it
// farther than a step may: it topples, slides or is unsupported), or whose contacts the
// open-close iteration cannot settle, has no static state there: automatic starts it (and the
// blocks resting on a support only through it) from its given state, names it in
// initial_equilibrium().unsettled and solves the rest again; strict is an error naming it.
// Contact damping (ContactLaw3d::damping_ratio ζ, off by default, as in 2D): each closed
// constraint gets a dashpot along its normal, c_n = 2 ζ √(m kn), and while locked one along its
// tangent plane, c_t = 2 ζ √(m kt), m = m_a m_b / (m_a + m_b) the pair's reduced mass (the movable
// block's mass against a fixed one), acting on the step's mean relative velocity Δr / h: a spring
// of stiffness c / h on the step's relative displacement, with no offset. A dashpot of ratio 1
// damps the constraint's rebound in the critical time. The energy it takes, (c / h) |Δr|² per
// step, is `damping_dissipated`; the initial equilibrium has none.
// Static analysis (Dda3dParams::static_analysis, the scene's "analysis": "static"): Shi's, the
// velocities zeroed after every step, so each step moves the blocks towards equilibrium under
// the inertia term of the step alone (no kinetic energy carries over).
// Stability monitor (Stability3dError, as in 2D): the energy has
// grown by more than twice all the run could draw on (kinetic, strain and spring energy after
// the initial equilibrium, the largest drop in potential energy so far, and every movable
// block's kinetic energy at 1 mm/s), or a closed constraint penetrates more than half the
// smaller block's size (the cube root of its volume): the contact no longer holds the blocks
// apart. The energy is checked after each step, the penetration at the start of the next one. (A block driven
// deeper than the detection range loses its constraints there; set max_displacement_ratio so
// that the range exceeds the penetration a scene may reach.) Non-finite solutions cut the step, and a step that would shrink below
// min_dt_ratio * dt is the error of step().
// Contact area of a constraint (for cohesion and tensile strength, Pa times m²): the constraints
// of a pair whose normals agree within 5° are the corners of one contact polygon (a face resting
// on a face: the vertices of each on the other's face and the crossings of their edges); the
// area of their convex hull in the plane is shared equally among them. Fewer than three (a
// vertex or an edge on a face) stand for no area: cohesion and tensile strength act through the
// faces a contact spreads over.
//
// Energy: kinetic ½ vᵀ M v, gravitational -m g·(c - c_0), strain ½ V σᵀ C⁻¹ σ, the penalty
// springs ½ kn d² + ½ kt |s|² of the closed constraints, friction dissipated (the sliding
// force times the slip, the tangential motion less what the spring took up), and the
// integrator's own dissipation as its own term. The step applies the forces of its end: the
// kinetic energy changes by exactly f_1 · D (v_n+1 - v_n = (2 / h)(D / h - v_n) and
// D = h (v_n + v_n+1) / 2), where the force laws store or dissipate
//   elastic: ΔU_e = -f_e,1 · D - ½ Dᵀ K_e D           (the scheme removes ½ Dᵀ K_e D),
//   contact: ΔU_c + W_slip, from the springs' own law at both ends of the step,
// so per step the integrator removes ½ Dᵀ K_e D plus, per constraint, -(ΔU_c + W_slip) - f_c,1 · Δr:
// a contact closing within a step is charged its end force over the whole relative motion, the
// main loss of an impact (a cube dropped 5 cm onto a slab with kn = 1e9 N/m and h = 1 ms comes
// to rest, and the term takes up all of the 1.2 kJ released). total() is then constant up to
// rounding: a test asserts it, which checks the solve against the scheme's identity.

#include <array>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <span>
#include <string>
#include <vector>

#include "rockcontact/dynamics/equilibrium.hpp"
#include "rockcontact/dynamics/material.hpp"
#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/predicate_stats.hpp"

namespace rockcontact::dynamics {

struct Block3dSpec {
  std::string id;  // non-empty, unique; names the block in every message
  // Convex parts moving as one body (one part for a convex block), valid polyhedra, metres.
  std::vector<kernel::ConvexPolyhedron> parts;
  std::string group;  // selects the interfaces that apply to it ("" : none)
  Material material;
  bool fixed = false;  // takes part in contact, never moves
  bool rigid = false;  // 6 unknowns: no strain
  // (vx, vy, vz, wx, wy, wz) of the centroid, m/s and rad/s (zero for a fixed block).
  std::array<double, 6> velocity{};
};

// The contact properties between blocks of two groups, replacing the law's for every pair with
// one block in each (the order of `groups` does not matter); kn and kt stay the law's.
struct Interface3d {
  std::array<std::string, 2> groups;
  double friction_angle_deg = 0.0;  // degrees, in [0, 90)
  double cohesion = 0.0;            // Pa, >= 0
  double tensile_strength = 0.0;    // Pa, >= 0
};

struct ContactLaw3d {
  double kn = 1.0e10;               // normal penalty, N/m per constraint, finite > 0
  double kt = 1.0e9;                // tangential penalty, N/m per constraint, finite > 0
  double friction_angle_deg = 0.0;  // degrees, in [0, 90)
  double cohesion = 0.0;            // Pa, >= 0
  double tensile_strength = 0.0;    // Pa, >= 0
  // Contact dashpots (header, "Contact damping"): their critical damping ratio, finite >= 0.
  double damping_ratio = 0.0;
  kernel::PolicyKind policy = kernel::PolicyKind::filtered;
  std::vector<Interface3d> interfaces;  // at most one per pair of groups
};

// The penalties a 3D scene gets with "kn": "auto" (the default): kn = auto_penalty_factor3d x the
// smallest E L over the movable blocks (all blocks when none moves), L the cube root of a
// block's volume, N/m; kt = kn / 10 (seed 001 §6's three scenes all take kt = kn / 10). E L is
// the stiffness of the block itself against a load on a face of its size, so the contact
// springs are ten times stiffer than the smallest block: its penalty settling stays a tenth of
// its own elastic deformation and below 10⁻⁵ of its size under its weight at the densities and
// moduli of rock (ρ g L / (10 E) with ρ = 2600 kg/m³, E = 10 GPa: 2.6·10⁻⁷ per metre of L). For
// the §6.1 wedge (E = 10 GPa, 87 m³) it gives 4.4·10¹¹ N/m, for the family's wedges of 1.9 to 80
// m³ 1.2·10¹¹ to 4.3·10¹¹ (docs/validation.md has what they give). Throws std::invalid_argument
// for no blocks.
inline constexpr double auto_penalty_factor3d = 10.0;
double auto_normal_penalty3d(std::span<const Block3dSpec> blocks);

// The sparse solver of the global equation: Eigen's SimplicialLDLT (a direct factorization each
// solve) or ConjugateGradient (diagonal preconditioner, 1e-12 relative residual, started from
// the last solution). bench/dda3d_stack.cpp measures which wins.
enum class Solver3d { ldlt, cg };

struct Dda3dParams {
  double dt = 1.0e-3;                         // s, the largest step, finite > 0
  std::array<double, 3> gravity{0.0, 0.0, -9.81};  // m/s²
  double max_displacement_ratio = 1.0e-3;     // of the scene's size per step, in (0, 1)
  double max_rotation_deg = 1.0;              // a block's rotation per step, degrees, in (0, 90)
  std::size_t max_open_close = 30;            // open-close iterations per step before a cut, >= 1
  double min_dt_ratio = 1.0e-6;               // the step may shrink to dt times this, in (0, 1)
  InitialEquilibrium initial_equilibrium = InitialEquilibrium::automatic;  // (header)
  EquilibriumProgress equilibrium_progress;  // optional
  bool static_analysis = false;               // velocities zeroed after every step (header)
  Solver3d solver = Solver3d::ldlt;
  // Threads of the parallel passes (0: one per core, OpenMP's default team). The result does
  // not depend on it: each pair's constraints and terms, and each constraint's decision, are
  // computed on their own and gathered in pair order.
  std::size_t threads = 0;
};

struct Block3dState {
  std::string id;
  std::vector<kernel::ConvexPolyhedron> parts;  // current
  kernel::Point3 centroid;                      // current, m
  std::array<double, 3> rotation{};  // since the start: angle (rad) times the unit axis
  // (vx, vy, vz, wx, wy, wz, and for a deformable block the strain rates), SI units.
  std::vector<double> velocity;
  std::array<double, 6> stress{};  // (σx, σy, σz, τyz, τzx, τxy), Pa; zero for rigid blocks
  double volume = 0.0;             // m³
  double mass = 0.0;               // kg, constant
  bool fixed = false;
  bool rigid = false;
};

enum class ContactMode3d { open, stick, slide };  // stick is the paper's "locked"

// A constraint in the contact list at the current instant (open ones included).
struct Contact3dState {
  std::size_t block_a = 0;  // the kernel's cp: the lower block index of the pair
  std::size_t block_b = 0;  // tp
  kernel::Point3 point;     // contact point on block_b, m
  kernel::Point3 normal;    // unit, from block_a towards block_b
  double gap = 0.0;         // m, negative = penetration, at the end of the last step
  double normal_force = 0.0;     // on block_b along the normal, N (compression > 0)
  double tangential_force = 0.0; // magnitude, N
  ContactMode3d mode = ContactMode3d::open;
};

struct Energies3d {  // J, at the current instant, relative to the start
  double kinetic = 0.0;
  double gravitational = 0.0;
  double strain = 0.0;
  double contact = 0.0;                  // held by the penalty springs
  double friction_dissipated = 0.0;
  double damping_dissipated = 0.0;       // by the contact dashpots
  double numerical_dissipated = 0.0;     // removed by the implicit integrator (header)
  double total() const {
    return kinetic + gravitational + strain + contact + friction_dissipated + damping_dissipated +
           numerical_dissipated;
  }
};

struct Step3dStats {
  double dt = 0.0;                       // s, of the last accepted step
  std::size_t open_close_iterations = 0; // of the last accepted step
  std::size_t cuts = 0;                  // step cuts since the start
  std::size_t constraints = 0;           // in the contact list
  std::size_t closed = 0;                // of which closed
  double detection_seconds = 0.0;        // wall s in contact detection since the start
  double solve_seconds = 0.0;            // wall s in the linear solves since the start
};

// The run cannot go on meaningfully; what() says why and with which numbers.
class Stability3dError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Dda3d {
 public:
  // Validates the blocks, law and params (std::invalid_argument naming the block or field) and
  // refuses two blocks that overlap at the start deeper than the detection range (naming both
  // and the depth): the penalty cannot resolve such an overlap.
  Dda3d(std::vector<Block3dSpec> blocks, ContactLaw3d law, Dda3dParams params);

  // One accepted step, cut as often as needed; throws Stability3dError when the step would have
  // to shrink below min_dt_ratio * dt, or on a non-finite solution.
  void step();

  double time() const noexcept;
  std::size_t steps() const noexcept;
  const std::vector<Block3dState>& blocks() const noexcept;
  std::vector<Contact3dState> contacts() const;
  Energies3d energies() const;
  const Step3dStats& last_step() const noexcept;
  kernel::PredicateCounters predicate_counters() const noexcept;  // spent by this simulation
  // What the constructor's pre-solve did (its ratio: the relative residual of the last solve).
  const Equilibrium& initial_equilibrium() const noexcept;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace rockcontact::dynamics
