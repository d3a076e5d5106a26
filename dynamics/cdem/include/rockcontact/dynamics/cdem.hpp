#pragma once
// CDEM (seed 003): deformable blocks meshed into constant-strain triangles, explicit time
// integration, and contact between blocks by seed 003's two-scale model without springs (exact
// touch time, clone node, separation by eq. 6-10, subdivided elements) or, for comparison on the
// same meshes, by node-to-edge penalty springs. 2D, plane strain or plane stress.
//
// ## Blocks and time integration (§2, eq. 1-3)
// Each block is meshed by kernel::mesh_polygon (CGAL's Delaunay mesher, longest edge <= max_edge,
// smallest angle >= 20.7°) into constant-strain triangles with lumped masses (a third of each
// triangle's mass to each corner). Element forces by the incremental strain-matrix method: the
// strain increment of a step from the corners' displacement with B of the mid-step shape (a rigid
// rotation gives no strain, so a spinning block keeps its area), the stress turned with the
// element and incremented by D times the strain increment, forces -A t B^T sigma with B of the new
// shape. Eq. 1, M u'' + C u' = F - P with C = damping * M, by velocity Verlet (the positions of
// central differences), damping implicit in the second half kick. Fixed blocks do not move and
// carry no stress.
//
// ## The two-scale contact (law two_scale)
// * Detection (§2-3): every boundary node against the boundary edges of the other blocks whose
//   boxes, swept over the step, come within the search tolerance (a grid over the edges). Within
//   a step a node and an edge's ends move linearly, so the node meets the edge at a root of a
//   quadratic in time: kernel::first_touch finds it exactly (filtered root isolation, exact surd
//   signs), and kernel::compare_touch orders touches exactly, also when two are 1e-12 s apart or
//   closer than a double can tell. The step is split at the first touch (the free-motion stage),
//   the contact forms, and the rest of the step follows (the contact stage), touch by touch; all
//   touches at the same exact instant form together. A node found a little inside an edge at the
//   start of a motion (within the search tolerance, moving further in) touches at once.
//   A node on a straight stretch of its outline touches only edges that face it within 60° (a
//   block's corner arriving on a face is the corner's contact, found from the corner).
// * Clone node (§4.1, eq. 4-5): the node and the edge's material point P = (1 - l) a + l b take the
//   common velocity of a perfectly inelastic collision, P's mass being the edge's effective mass
//   there, 1 / ((1 - l)² / m_a + l² / m_b), the impulse reaching a and b by the shape functions:
//   momentum is conserved exactly, the loss (eq. 5) is booked as onset_loss. The tangential
//   impulse obeys Coulomb's law for impulses; beyond it the clone node starts sliding.
// * Afterwards (§4.2, eq. 6-11) the clone node is a tie: the force F between the node and P that
//   gives them the same acceleration (and closes their drift within a step; ties sharing nodes are
//   solved together by Gauss-Seidel sweeps). Eq. 6: tension -F.n > tensile_strength * Ac separates
//   it; eq. 7-10: a shear |F.t| > max(F.n, 0) tan(phi) + c Ac is reduced to that limit. Ac is the
//   node's half of its two boundary edges times the thickness. Slip is decided before tension, as
//   the stick trial's shear pushes on neighbouring ties' normal forces.
// * Sliding clone nodes (left to future work by §7; the library's design): the node keeps its
//   normal tie and slides along the target's boundary, moving on to the next edge past a corner,
//   against the limited shear force in the direction of the stick force it replaced; each step it
//   is tried as stuck first, so it sticks again when the stick force falls within the limit.
//   A block sliding down a slope follows g (sin theta - cos theta tan phi) t² / 2 (cdem_test).
// * Subdivided elements (§5, CdemContactParams::subdivide, off by default): when a clone node
//   touches the inside of an edge, the target element is divided into k x k sub-triangles,
//   k = ceil(h / (c dt2)) (dt2 the contact stage of the step, c the P-wave speed), between 2 and 8.
//   P becomes a sub-node, so the onset's contact mass is a sub-node's (the seed's thin surface
//   layer: the onset loss falls); the sub-nodes move on substeps of the step under the
//   sub-elements' forces with the element's corners and its shared edges driven by the coarse
//   motion (the velocity boundary condition of §5 (3)), the clone node's own node moving on the
//   substeps under the contact force at P, and the sub-elements' forces reach the corners each
//   step. The patch merges back (mass, momentum and mean stress to the element) when the clone node
//   separates or slips. Momentum stays exact; the energy does not: the corners take the patch's
//   forces as the mean over the step (half a step late), and a merge in mid-contact loses the
//   local indentation the coarse element cannot hold. docs/validation.md gives the figures; that
//   is why it is off by default.
//
// ## Penalty contact (law penalty)
// A boundary node inside another block by at most the search tolerance, within an edge's span, is
// pushed out along the edge's normal by kn times its depth (the least deep edge), the edge's ends
// taking the reaction by the shape functions; a tangential spring kt, capped at tan(phi) fn + c Ac,
// as the 2D DDA's elastoplastic Coulomb law. Touch events carry the exact crossing time.
//
// ## Initial overlaps
// Blocks may start touching (exactly: a shared face, a block resting on another) but not inside
// each other deeper than contact.search_tolerance, the contact's reach: a node deeper than that
// is never found (under either law), and the blocks would pass through each other. The depth is
// that of the deepest boundary node of either block inside the other, to that block's boundary,
// the inside test by exact predicates, so that exact touch is depth 0.
//
// ## Critical step and monitor
// dt must be below 2 / omega_max, omega_max² <= (2 c / h_min)² + 2 kn / m_min (h_min the smallest
// altitude of an element, m_min the lightest boundary node, kn under the penalty law only); the
// constructor refuses a larger dt naming the critical value and the element. step() throws
// CdemStabilityError for a non-finite state, an energy growth beyond twice what the run can draw
// on (checked every 16 steps), or a penalty contact deeper than half the smallest altitude.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::dynamics {

struct CdemMaterial {
  double density = 0.0;         // kg/m³ > 0
  double youngs_modulus = 0.0;  // Pa > 0
  double poisson_ratio = 0.0;   // -1 < nu < 0.5
};

enum class CdemPlane { strain, stress };
enum class CdemLaw { two_scale, penalty };

struct CdemBlockSpec {
  std::string id;
  std::vector<kernel::Point2> vertices;  // a simple polygon, counter-clockwise, m
  CdemMaterial material;
  double max_edge = 0.0;  // m > 0: the mesh's longest element edge
  bool fixed = false;     // every node held at rest
  std::array<double, 3> velocity{};  // vx, vy (m/s) of the mass centre, omega (rad/s) about it
};

struct CdemContactParams {
  CdemLaw law = CdemLaw::two_scale;
  double friction_angle_deg = 0.0;  // [0, 90)
  double cohesion = 0.0;            // Pa >= 0, times the contact area of a node
  double tensile_strength = 0.0;    // Pa >= 0, times the contact area of a node
  double search_tolerance = 0.0;    // m > 0: node-edge pairs closer than this are watched
  double kn = 0.0;                  // N/m per node (penalty law only)
  double kt = 0.0;                  // N/m per node (penalty law only; default kn)
  bool subdivide = false;           // two-scale: subdivided elements at the clone nodes (§5)
  kernel::PolicyKind policy = kernel::PolicyKind::filtered;  // of the touch-time predicates
};

struct CdemParams {
  double dt = 0.0;                           // s > 0, below the critical step
  std::array<double, 2> gravity{0.0, 0.0};   // m/s²
  CdemPlane plane = CdemPlane::strain;
  double thickness = 1.0;  // m, out of plane (masses, areas of contact)
  double damping = 0.0;    // 1/s >= 0: mass-proportional damping C = damping * M (eq. 1)
  CdemContactParams contact;
  // Threads of the element loops (0: one per core, OpenMP's default team), which run on one
  // thread below 4096 elements. The result does not depend on it: each element's forces are
  // computed on their own and gathered per node in a fixed order.
  std::size_t threads = 0;
};

// One row of events.csv: "touch" at the exact time the pair's first node meets an edge,
// "separate" when the pair's last contact releases. block_a is the block whose node touches.
struct CdemEvent {
  enum class Kind { touch, separate };
  double t = 0.0;
  Kind kind = Kind::touch;
  std::size_t block_a = 0;
  std::size_t block_b = 0;
};

// A block's state as tracks.csv reports it.
struct CdemBlockState {
  std::array<double, 2> centre{};    // mass centre, m
  std::array<double, 2> velocity{};  // mass-averaged velocity, m/s
  double rotation = 0.0;             // mean rotation since the start, rad (counter-clockwise)
  double omega = 0.0;                // mean angular velocity, rad/s
};

struct CdemEnergies {
  double kinetic = 0.0;        // J
  double strain = 0.0;         // J
  double gravitational = 0.0;  // J, relative to the start
  double contact = 0.0;        // J, stored in penalty springs
  double onset_loss = 0.0;     // J, dissipated by the inelastic onsets of clone nodes (eq. 5)
  double friction = 0.0;       // J, dissipated by sliding (clone nodes and penalty contacts)
  double damping = 0.0;        // J, dissipated by the mass-proportional damping
  double tie_work = 0.0;       // J, taken out by the clone-node ties' normal forces (zero for a
                               // tie held exactly; the share of their position corrections)
  // Mechanical energy plus everything dissipated: constant for an exact integrator.
  double total() const {
    return kinetic + strain + gravitational + contact + onset_loss + friction + damping + tie_work;
  }
};

struct CdemCounters {
  std::size_t touches = 0;              // touch events (clone nodes or penalty contacts formed)
  std::size_t clone_nodes_formed = 0;
  std::size_t clone_nodes_separated = 0;
  std::size_t subdivided_elements = 0;  // sub-elements created over the run
};

// A block's mesh as the outputs draw it: nodes (current positions), velocities, triangles
// (counter-clockwise, indices into nodes) and each triangle's stress (xx, yy, xy; Pa).
struct CdemMeshView {
  const std::vector<kernel::Point2>* nodes = nullptr;
  const std::vector<std::array<double, 2>>* velocities = nullptr;
  const std::vector<std::array<std::uint32_t, 3>>* triangles = nullptr;
  const std::vector<std::array<double, 3>>* stresses = nullptr;
};

// Thrown by step() when the run must stop: a non-finite state, energy growth, or a node deep
// inside another block.
class CdemStabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Cdem {
 public:
  // Meshes the blocks and builds the engine. Throws std::invalid_argument naming the block or
  // the parameter for a bad polygon, a non-positive mesh size, a dt above the critical step
  // (stating the critical value and the element that sets it), bad contact parameters, or two
  // blocks (not both fixed) that start inside each other deeper than the search tolerance
  // (naming both and the depth: "Initial overlaps" above).
  Cdem(std::vector<CdemBlockSpec> blocks, CdemParams params);
  ~Cdem();
  Cdem(Cdem&&) noexcept;
  Cdem& operator=(Cdem&&) noexcept;

  void step();  // one step of params.dt

  double time() const;
  std::size_t steps() const;
  double critical_dt() const;  // s: the stability limit of the meshes (and penalty springs)
  std::size_t block_count() const;
  const CdemBlockSpec& block(std::size_t i) const;
  CdemBlockState block_state(std::size_t i) const;
  CdemMeshView mesh(std::size_t i) const;
  std::size_t element_count() const;
  std::size_t node_count() const;
  CdemEnergies energies() const;
  std::array<double, 2> momentum() const;  // kg m/s, of every movable node
  const std::vector<CdemEvent>& events() const;
  const CdemCounters& counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockcontact::dynamics
