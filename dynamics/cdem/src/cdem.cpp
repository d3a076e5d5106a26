#include "rockcontact/dynamics/cdem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <omp.h>

#include "rockcontact/kernel/2d/predicates.hpp"
#include "rockcontact/kernel/2d/touch_time.hpp"
#include "rockcontact/kernel/2d/triangle_mesh.hpp"

namespace rockcontact::dynamics {
namespace {

using kernel::Point2;
using Vec2 = std::array<double, 2>;

// The stability monitor's energy floor: every movable node's kinetic energy at this speed (m/s),
// as in the DDA engines, so that a run starting at rest has a budget.
constexpr double energy_floor_speed = 1.0e-3;
constexpr std::size_t energy_check_every = 16;
// Below this many elements (nodes) a step's loops run on one thread: a parallel region costs a
// few microseconds to open, and its threads spin for busy cores; a mesh of a few hundred
// elements steps in about as long.
constexpr std::int64_t parallel_threshold = 4096;
// Gauss-Seidel sweeps over the clone-node ties of one step, and the rounds of the separation
// and slip decisions (each round re-solves the ties that remain).
constexpr int tie_sweeps = 60;
constexpr int tie_rounds = 24;
constexpr double separation_noise = 1.0e-9;
// A node of a straight stretch of outline touches an edge only when the two faces meet within
// 60 degrees of head-on (their outward normals' dot product at most -cos 60°).
constexpr double flat_contact_cosine = 0.5;
// The most parts per edge a subdivided element is cut into (seed 003 §5), k² sub-triangles.
constexpr int max_subdivision = 8;
// The most substeps a patch takes per step (an element flattened to a sliver would ask for more).
constexpr double max_substeps = 1000.0;
// A touch that leaves no contact: at most this many touch batches in one step (a guard against a
// node that touches, separates and touches again forever inside one step).
constexpr int max_touch_batches = 10000;
// Up to this many blocks the touch search first tests the blocks' swept boxes pairwise.
constexpr std::size_t block_pretest_limit = 64;

double dot(const Vec2& a, const Vec2& b) { return a[0] * b[0] + a[1] * b[1]; }
double cross(const Vec2& a, const Vec2& b) { return a[0] * b[1] - a[1] * b[0]; }

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

std::string block_name(const std::string& id) { return "block '" + id + "'"; }

// The 2D elasticity of a constant-strain triangle (plane strain or plane stress):
// sigma = [d11 d12 0; d12 d11 0; 0 0 d33] (exx, eyy, gxy).
struct Elasticity {
  double d11 = 0.0, d12 = 0.0, d33 = 0.0;
  double wave_speed = 0.0;  // P-wave speed sqrt(d11 / rho), m/s

  static Elasticity of(const CdemMaterial& m, CdemPlane plane) {
    const double e = m.youngs_modulus, nu = m.poisson_ratio;
    Elasticity d;
    if (plane == CdemPlane::strain) {
      const double lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
      const double mu = e / (2.0 * (1.0 + nu));
      d.d11 = lambda + 2.0 * mu;
      d.d12 = lambda;
      d.d33 = mu;
    } else {
      d.d11 = e / (1.0 - nu * nu);
      d.d12 = nu * d.d11;
      d.d33 = e / (2.0 * (1.0 + nu));
    }
    d.wave_speed = std::sqrt(d.d11 / m.density);
    return d;
  }

  // Strain energy per unit volume of the stress s (xx, yy, xy): s . D^-1 s / 2.
  double energy_density(const std::array<double, 3>& s) const {
    const double det = d11 * d11 - d12 * d12;
    return 0.5 * ((d11 * (s[0] * s[0] + s[1] * s[1]) - 2.0 * d12 * s[0] * s[1]) / det +
                  s[2] * s[2] / d33);
  }
};

// One constant-strain triangle of the incremental strain-matrix method (seed 003 eq. 2-3): the
// strain increment from its corners' displacement (start -> end), with the strain matrix B of the
// mid-step configuration (a rigid rotation then gives no strain at all: the displacement
// gradient (R - I) over the mid-step shape (R + I) / 2 is purely skew); the stress turned by the
// increment's rotation (Hughes-Winget: cos and sin from tan(theta / 2), no trigonometry) plus D
// times the strain increment; the nodal forces -A t B^T sigma with B of the end configuration,
// into f (x, y of each corner). `incremental` false: forces of the current stress only.
void cst_forces(const double xs[3], const double ys[3], const double xe[3], const double ye[3],
                const Elasticity& d, double thickness, bool incremental, std::array<double, 3>& s, double f[6]) {
  if (incremental) {
    double mx[3], my[3], du[3], dv[3];
    for (int k = 0; k < 3; ++k) {
      du[k] = xe[k] - xs[k];
      dv[k] = ye[k] - ys[k];
      mx[k] = xs[k] + 0.5 * du[k];
      my[k] = ys[k] + 0.5 * dv[k];
    }
    const double two_area = (mx[1] - mx[0]) * (my[2] - my[0]) - (my[1] - my[0]) * (mx[2] - mx[0]);
    double exx = 0.0, eyy = 0.0, gxy = 0.0, spin = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double b = (my[(k + 1) % 3] - my[(k + 2) % 3]) / two_area;
      const double c = (mx[(k + 2) % 3] - mx[(k + 1) % 3]) / two_area;
      exx += b * du[k];
      eyy += c * dv[k];
      gxy += c * du[k] + b * dv[k];
      spin += 0.5 * (b * dv[k] - c * du[k]);
    }
    // Rotation by theta with tan(theta / 2) = spin / 2 (exact for a rigid rotation).
    const double half = 0.5 * spin, denom = 1.0 + half * half;
    const double cs = (1.0 - half * half) / denom, sn = 2.0 * half / denom;
    const double sxx = s[0], syy = s[1], sxy = s[2];
    const double rxx = cs * cs * sxx - 2.0 * cs * sn * sxy + sn * sn * syy;
    const double ryy = sn * sn * sxx + 2.0 * cs * sn * sxy + cs * cs * syy;
    const double rxy = cs * sn * (sxx - syy) + (cs * cs - sn * sn) * sxy;
    s[0] = rxx + d.d11 * exx + d.d12 * eyy;
    s[1] = ryy + d.d12 * exx + d.d11 * eyy;
    s[2] = rxy + d.d33 * gxy;
  }
  for (int k = 0; k < 3; ++k) {
    // -A t B^T sigma with b = dy / 2A, c = dx / 2A: the areas cancel.
    const double b = ye[(k + 1) % 3] - ye[(k + 2) % 3];
    const double c = xe[(k + 2) % 3] - xe[(k + 1) % 3];
    f[2 * k] = -0.5 * thickness * (b * s[0] + c * s[2]);
    f[2 * k + 1] = -0.5 * thickness * (c * s[1] + b * s[2]);
  }
}

// The area of triangle t (counter-clockwise: positive) and its smallest altitude (twice the area
// over the longest edge), on coordinate arrays x, y.
double triangle_area(const std::vector<double>& x, const std::vector<double>& y,
                     const std::array<std::uint32_t, 3>& t) {
  return 0.5 * ((x[t[1]] - x[t[0]]) * (y[t[2]] - y[t[0]]) - (y[t[1]] - y[t[0]]) * (x[t[2]] - x[t[0]]));
}

double smallest_altitude(const std::vector<double>& x, const std::vector<double>& y,
                         const std::array<std::uint32_t, 3>& t) {
  double longest = 0.0;
  for (int k = 0; k < 3; ++k) {
    longest = std::max(longest, std::hypot(x[t[(k + 1) % 3]] - x[t[k]], y[t[(k + 1) % 3]] - y[t[k]]));
  }
  return 2.0 * triangle_area(x, y, t) / longest;
}

// Where a point lies against a block's boundary loop (a simple counter-clockwise polygon).
enum class Location { inside, boundary, outside };

// The winding number of the loop around p by Sunday's crossing rule: an upward edge that p is
// strictly left of counts +1, a downward edge that p is strictly right of -1, each edge taken
// half-open in y so that a vertex at p's height counts once. The only decisions are coordinate
// comparisons (exact on doubles) and the kernel's orientation predicate (exact under Filtered), so
// a node exactly on an edge is `boundary`, never inside or outside by a rounding.
Location locate(const Point2& p, const std::vector<std::uint32_t>& loop, const std::vector<double>& x,
                const std::vector<double>& y) {
  int winding = 0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Point2 a{x[loop[k]], y[loop[k]]};
    const Point2 b{x[loop[(k + 1) % loop.size()]], y[loop[(k + 1) % loop.size()]]};
    const kernel::Sign side = kernel::orientation<kernel::Filtered>(a, b, p);
    if (side == kernel::Sign::zero && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
        std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y)) {
      return Location::boundary;
    }
    if (a.y <= p.y) {
      if (b.y > p.y && side == kernel::Sign::positive) ++winding;
    } else if (b.y <= p.y && side == kernel::Sign::negative) {
      --winding;
    }
  }
  return winding != 0 ? Location::inside : Location::outside;
}

// The distance from p to the nearest point of the loop's edges, m (a construction in double).
double distance_to_loop(const Point2& p, const std::vector<std::uint32_t>& loop, const std::vector<double>& x,
                        const std::vector<double>& y) {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const std::uint32_t a = loop[k], b = loop[(k + 1) % loop.size()];
    const Vec2 d{x[b] - x[a], y[b] - y[a]}, r{p.x - x[a], p.y - y[a]};
    const double along = std::clamp(dot(r, d) / dot(d, d), 0.0, 1.0);
    nearest = std::min(nearest, std::hypot(r[0] - along * d[0], r[1] - along * d[1]));
  }
  return nearest;
}

struct BlockData {
  CdemBlockSpec spec;
  std::uint32_t first_node = 0, node_count = 0;
  std::uint32_t first_element = 0, element_count = 0;
  std::vector<std::uint32_t> boundary;  // global node ids, counter-clockwise loop
  Elasticity elasticity;
  double mass = 0.0;
  Vec2 centre0{};          // mass centre at the start
  double rotation = 0.0;   // mean rotation since the start, unwrapped
  // The mesh in the block's own numbering, for CdemMeshView (positions kept in step with the
  // global arrays when the view is asked for).
  mutable std::vector<Point2> view_nodes;
  mutable std::vector<Vec2> view_velocities;
  std::vector<std::array<std::uint32_t, 3>> view_triangles;
  mutable std::vector<std::array<double, 3>> view_stresses;
};

// A clone node (seed 003 §4): the main block's boundary node `node` joined to the material point
// (1 - lambda) a + lambda b of the target block's boundary edge a -> b.
struct Tie {
  std::uint32_t node = 0, a = 0, b = 0;
  std::uint32_t edge = 0;  // index of a in the target block's boundary loop
  std::uint32_t main_block = 0, target_block = 0;
  double lambda = 0.0;
  double area = 0.0;        // Ac, m²: the node's share of its block's boundary times thickness
  bool sliding = false;
  double slide_force = 0.0;  // N along the edge's tangent on the main node, while sliding
  Vec2 force{};              // the tie's force on the main node at the last solve, N
  // The node's offset from its material point when the tie formed, along the edge's outward
  // normal and tangent (m): the tie holds it rather than closing it in one step, which would
  // throw the node out of a block it was found a little inside of (see find_touches).
  double offset_n = 0.0, offset_t = 0.0;
  bool separate = false;     // decided this step
  int patch = -1;            // the target element's subdivision that carries it (Patch), or -1
  bool applied = false;      // its force this step came from its patch (release_patches)
};

// A subdivided element (seed 003 §5): the target element T = (a, b, c) whose boundary edge a -> b
// a clone node touched, replaced while the clone node lives by k x k sub-triangles on the
// barycentric grid of T (sub-node (i, j) at weights (1 - (i + j) / k, i / k, j / k) on a, b, c).
// The sub-nodes inside T and on the touched edge are free, with their lumped share of T's mass;
// the corners, the sub-nodes on T's other two edges (shared with the unrefined neighbours) and the
// contact point P (the clone node: the sub-node of the touched edge moved onto the touch point)
// are driven: the corners and edge nodes by the coarse motion of the step interpolated in time,
// P by the main node. Each coarse step the free sub-nodes integrate eq. 12 in substeps of
// h / substeps; the sub-elements' forces on the driven nodes at the end of the step go to T's
// corners (by the weights) and, at P, to the main node: the contact force of the clone node.
struct Patch {
  std::uint32_t element = 0;
  std::array<std::uint32_t, 3> corner{};  // a, b, c (global nodes)
  std::uint32_t main_node = 0;
  int k = 0, substeps = 0;
  std::uint32_t p = 0;  // P's index among the sub-nodes
  Vec2 p_offset{};      // P minus the main node's position when the clone node formed
  std::vector<std::array<double, 3>> w;  // weights on a, b, c of each sub-node
  std::vector<char> free;
  std::vector<double> x, y, vx, vy, ax, ay, x0, y0, m, xs, ys;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<double, 3>> stress;
  std::array<double, 3> mass_moved{};  // taken from each corner to the free sub-nodes
  // The forces the coarse step gives a, b, c (N): the sub-elements' impulse on the driven nodes
  // over the step (the substeps' trapezoid rule, as the free nodes' half kicks) divided by the
  // step, their mean force, so that momentum is conserved exactly; it acts half a step late,
  // which costs the energy accuracy docs/validation.md measures. The contact force on the main
  // node is applied on the substeps themselves, except in the patch's first step, where the
  // main node has already moved: there it gets the end force, and the difference from the
  // step's impulse (the debt, N) is paid when the patch merges (Cdem::Impl::tails).
  std::array<Vec2, 3> corner_force{};
  Vec2 contact_force{};
  Vec2 contact_debt{};
  std::vector<double> driven_fx, driven_fy;  // on the driven nodes at the last substep
  // A patch made inside a step integrates the rest of it, from where the coarse nodes were then
  // (a, b, c, the main node) over the fraction 1 - start of the step.
  double start = 0.0;
  std::array<Vec2, 4> from{};
  // After its first step the clone node itself moves on the substeps (Cdem::Impl::run_patches).
  bool fresh = true;
  Vec2 contact_end{};  // the sub-elements' force on P at the end of the step, N (eq. 6-10)
};

// A penalty contact of a boundary node with a target block's edge.
struct PenaltyContact {
  std::uint32_t node = 0, a = 0, b = 0;
  std::uint32_t main_block = 0, target_block = 0;
  double lambda = 0.0;
  double depth = 0.0;        // m, > 0 inside
  double shear = 0.0;        // N, the tangential spring's force on the node along the edge
  double area = 0.0;
};

// A node-edge touch found in a step, with its exact instant.
struct Touch {
  std::uint32_t node = 0, edge = 0, target_block = 0;
  kernel::NodeEdgeMotion motion;
  kernel::TouchTime time;
  bool at_start = false;  // on the edge's line at the start of the motion, moving in
};

std::uint64_t pair_key(std::uint32_t x, std::uint32_t y) {
  return (static_cast<std::uint64_t>(x) << 32) | y;
}

}  // namespace

struct Cdem::Impl {
  CdemParams params;
  int thread_count = 1;  // of the element loops (CdemParams::threads)
  std::vector<BlockData> blocks;
  // Nodes, global numbering (block after block).
  std::vector<double> x, y, vx, vy, ax, ay, x_start, y_start, x0, y0, mass, inv_mass;
  std::vector<std::uint32_t> node_block;
  std::vector<double> boundary_share;  // m: half the boundary edges next to a boundary node
  // Boundary nodes inside a straight stretch of their block's outline (the mesher's points on a
  // polygon edge; a vertex with collinear neighbours).
  std::vector<char> flat_node;
  // Elements.
  std::vector<std::array<std::uint32_t, 3>> elements;
  std::vector<std::array<double, 3>> stress;
  std::vector<std::uint32_t> element_block;
  std::vector<std::array<double, 6>> element_force;
  // Node -> (element, corner) adjacency for the deterministic gather of element forces.
  std::vector<std::uint32_t> adjacency_first;
  std::vector<std::uint32_t> adjacency;  // element * 3 + corner
  std::vector<char> patched;  // per element: replaced by a Patch
  // The element of each boundary edge a -> b, keyed (a, b).
  std::unordered_map<std::uint64_t, std::uint32_t> boundary_element;
  std::vector<Patch> patches;
  // The debts of merged patches (Patch::contact_debt), applied as forces in the next step.
  std::vector<std::pair<std::uint32_t, Vec2>> tails;
  // Contacts.
  std::vector<Tie> ties;
  std::vector<PenaltyContact> penalty;
  std::unordered_set<std::uint64_t> engaged;  // (node, block) pairs in contact
  struct PairCount {
    std::size_t count = 0;
    std::uint32_t block_a = 0, block_b = 0;
  };
  std::unordered_map<std::uint64_t, PairCount> pair_contacts;  // unordered block pair -> count
  std::vector<CdemEvent> events;
  CdemCounters counters;
  // Time and energy.
  std::size_t steps = 0;
  double time = 0.0;
  double dt_critical = 0.0;
  double onset_loss = 0.0, friction = 0.0, damping_work = 0.0, tie_work = 0.0;
  CdemEnergies start;
  double energy_floor = 0.0;
  double max_gravitational = 0.0;
  double min_altitude = std::numeric_limits<double>::infinity();

  Impl(std::vector<CdemBlockSpec> specs, CdemParams p);

  bool two_scale() const { return params.contact.law == CdemLaw::two_scale; }
  std::size_t node_total() const { return x.size(); }

  // Geometry of a target edge.
  Vec2 position(std::uint32_t n) const { return {x[n], y[n]}; }
  Vec2 velocity(std::uint32_t n) const { return {vx[n], vy[n]}; }

  void validate_params() const;
  void add_block(CdemBlockSpec spec);
  void build_adjacency();
  void check_initial_overlaps() const;
  void check_critical_step();

  // Contact events of the pair counts (events.csv).
  void contact_added(std::uint32_t main_block, std::uint32_t target_block, double t);
  void contact_removed(std::uint32_t main_block, std::uint32_t target_block, double t);

  std::vector<Touch> find_touches(double remaining, bool resting = false) const;
  bool faces_meet(std::uint32_t node, const kernel::NodeEdgeMotion& motion) const;
  void move(double h);
  void form_tie(const Touch& touch, double t);
  void engage(std::uint32_t node, std::uint32_t block, double lambda, std::uint32_t a, std::uint32_t b,
              std::uint32_t main_block, bool add);

  void internal_forces(bool incremental);
  int create_patch(std::uint32_t main_node, std::uint32_t a, std::uint32_t b, double lambda, double contact_time);
  void run_patches(double h);
  void merge_patch(int index);
  void apply_patch_forces();
  void release_patches();
  void penalty_forces(double t);
  void follow_sliding_ties(double t);
  void remove_separated(double t);
  void solve_ties(double h, double t);
  void apply_node_edge_force(std::uint32_t node, std::uint32_t a, std::uint32_t b, double lambda, const Vec2& f);
  Vec2 edge_normal(const Tie& tie) const;

  void initial_ties();
  CdemEnergies energies() const;
  void update_rotations();
  void monitor();
  void step();
};

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void Cdem::Impl::validate_params() const {
  require(finite_positive(params.dt), "time.dt: expected a finite step > 0 s, got " + number(params.dt));
  require(finite_positive(params.thickness),
          "thickness: expected a finite thickness > 0 m, got " + number(params.thickness));
  require(std::isfinite(params.damping) && params.damping >= 0.0,
          "damping: expected a finite rate >= 0 1/s, got " + number(params.damping));
  require(std::isfinite(params.gravity[0]) && std::isfinite(params.gravity[1]),
          "gravity: expected two finite numbers");
  const CdemContactParams& c = params.contact;
  require(std::isfinite(c.friction_angle_deg) && c.friction_angle_deg >= 0.0 && c.friction_angle_deg < 90.0,
          "contact.friction_angle_deg: expected an angle in [0, 90) degrees, got " +
              number(c.friction_angle_deg));
  require(std::isfinite(c.cohesion) && c.cohesion >= 0.0,
          "contact.cohesion: expected a stress >= 0 Pa, got " + number(c.cohesion));
  require(std::isfinite(c.tensile_strength) && c.tensile_strength >= 0.0,
          "contact.tensile_strength: expected a stress >= 0 Pa, got " + number(c.tensile_strength));
  require(finite_positive(c.search_tolerance),
          "contact.search_tolerance: expected a distance > 0 m, got " + number(c.search_tolerance));
  if (c.law == CdemLaw::penalty) {
    require(finite_positive(c.kn), "contact.kn: the penalty law needs a stiffness > 0 N/m, got " + number(c.kn));
    require(c.kt == 0.0 || finite_positive(c.kt),
            "contact.kt: expected a stiffness > 0 N/m, got " + number(c.kt));
  }
}

void Cdem::Impl::add_block(CdemBlockSpec spec) {
  const std::string name = block_name(spec.id);
  const CdemMaterial& m = spec.material;
  require(finite_positive(m.density), name + ": density: expected > 0 kg/m³, got " + number(m.density));
  require(finite_positive(m.youngs_modulus),
          name + ": youngs_modulus: expected > 0 Pa, got " + number(m.youngs_modulus));
  require(std::isfinite(m.poisson_ratio) && m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5,
          name + ": poisson_ratio: expected -1 < nu < 0.5, got " + number(m.poisson_ratio));
  require(finite_positive(spec.max_edge),
          name + ": mesh.max_edge: expected a length > 0 m, got " + number(spec.max_edge));
  for (double v : spec.velocity) require(std::isfinite(v), name + ": velocity: expected finite numbers");
  require(!spec.fixed || spec.velocity == std::array<double, 3>{},
          name + ": velocity: a fixed block cannot move");

  kernel::TriangleMesh mesh;
  try {
    mesh = kernel::mesh_polygon(spec.vertices, spec.max_edge);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(name + ": " + e.what());
  }

  BlockData block;
  block.elasticity = Elasticity::of(m, params.plane);
  block.first_node = static_cast<std::uint32_t>(x.size());
  block.node_count = static_cast<std::uint32_t>(mesh.nodes.size());
  block.first_element = static_cast<std::uint32_t>(elements.size());
  block.element_count = static_cast<std::uint32_t>(mesh.triangles.size());
  const auto index = static_cast<std::uint32_t>(blocks.size());
  for (const Point2& p : mesh.nodes) {
    x.push_back(p.x);
    y.push_back(p.y);
    node_block.push_back(index);
    mass.push_back(0.0);
  }
  // Lumped masses: a third of each element's mass to each of its corners.
  for (const auto& t : mesh.triangles) {
    const std::array<std::uint32_t, 3> g{t[0] + block.first_node, t[1] + block.first_node,
                                         t[2] + block.first_node};
    const double area = triangle_area(x, y, g);
    for (std::uint32_t n : g) mass[n] += m.density * params.thickness * area / 3.0;
    elements.push_back(g);
    element_block.push_back(index);
    block.view_triangles.push_back(t);
  }
  for (std::uint32_t n : mesh.boundary) block.boundary.push_back(n + block.first_node);
  // Mass centre and the initial velocity field of a rigid motion (vx, vy, omega about it).
  Vec2 c{};
  for (std::uint32_t n = block.first_node; n < block.first_node + block.node_count; ++n) {
    block.mass += mass[n];
    c[0] += mass[n] * x[n];
    c[1] += mass[n] * y[n];
  }
  c[0] /= block.mass;
  c[1] /= block.mass;
  block.centre0 = c;
  for (std::uint32_t n = block.first_node; n < block.first_node + block.node_count; ++n) {
    vx.push_back(spec.velocity[0] - spec.velocity[2] * (y[n] - c[1]));
    vy.push_back(spec.velocity[1] + spec.velocity[2] * (x[n] - c[0]));
    inv_mass.push_back(spec.fixed ? 0.0 : 1.0 / mass[n]);
  }
  block.spec = std::move(spec);
  blocks.push_back(std::move(block));
}

void Cdem::Impl::build_adjacency() {
  const std::size_t n = node_total();
  adjacency_first.assign(n + 1, 0);
  for (const auto& e : elements)
    for (std::uint32_t v : e) ++adjacency_first[v + 1];
  for (std::size_t i = 0; i < n; ++i) adjacency_first[i + 1] += adjacency_first[i];
  adjacency.assign(adjacency_first[n], 0);
  std::vector<std::uint32_t> fill(adjacency_first.begin(), adjacency_first.end() - 1);
  for (std::size_t e = 0; e < elements.size(); ++e)
    for (std::uint32_t k = 0; k < 3; ++k) adjacency[fill[elements[e][k]]++] = static_cast<std::uint32_t>(e * 3 + k);
  patched.assign(elements.size(), 0);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      boundary_element.emplace(pair_key(elements[e][k], elements[e][(k + 1) % 3]), static_cast<std::uint32_t>(e));
    }
  }
  // Boundary shares: half of each boundary edge to each of its ends.
  boundary_share.assign(n, 0.0);
  flat_node.assign(n, 0);
  for (const BlockData& b : blocks) {
    const std::size_t m = b.boundary.size();
    for (std::size_t k = 0; k < m; ++k) {
      const std::uint32_t i = b.boundary[k], j = b.boundary[(k + 1) % m], l = b.boundary[(k + 2) % m];
      const double half = 0.5 * std::hypot(x[j] - x[i], y[j] - y[i]);
      boundary_share[i] += half;
      boundary_share[j] += half;
      // The mesher puts its points on a sloped polygon edge within rounding of the line: flat
      // means a turn below 1e-9 rad.
      const Vec2 in{x[j] - x[i], y[j] - y[i]}, out{x[l] - x[j], y[l] - y[j]};
      flat_node[j] = std::abs(std::atan2(cross(in, out), dot(in, out))) < 1e-9;
    }
  }
}

// Blocks that start inside each other. The contact only ever sees a boundary node on an edge of
// another block or at most contact.search_tolerance inside it (find_touches, penalty_forces): a
// node deeper than that is never found, and the blocks pass through each other. So an overlap is
// measured as the contact would meet it, by the deepest boundary node of either block inside the
// other (its distance to that block's boundary), and refused beyond the contact's reach, as the
// 3D engine refuses an overlap beyond its detection range. (The 2D DDA allows half the smaller
// inradius, what its potential pushes apart; CDEM's contact has no such reach.) Exact touch, the
// nodes on the other block's edges (blocks resting on each other, jointed masses sharing faces),
// is depth 0; a Steiner node of an oblique shared face, a rounding off its line, is far below any
// usable tolerance. Two fixed blocks never meet in the contact and are not checked. The pairs
// whose boxes meet are found by a sweep along x.
void Cdem::Impl::check_initial_overlaps() const {
  struct Box {
    double lo_x = std::numeric_limits<double>::infinity(), lo_y = std::numeric_limits<double>::infinity();
    double hi_x = -std::numeric_limits<double>::infinity(), hi_y = -std::numeric_limits<double>::infinity();
  };
  std::vector<Box> box(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (std::uint32_t n : blocks[i].boundary) {
      box[i] = {std::min(box[i].lo_x, x[n]), std::min(box[i].lo_y, y[n]), std::max(box[i].hi_x, x[n]),
                std::max(box[i].hi_y, y[n])};
    }
  }
  struct Deepest {
    double depth = 0.0;  // m
    std::uint32_t node = 0, block = 0, other = 0;
  } deepest;
  const auto nodes_inside = [&](std::uint32_t from, std::uint32_t into) {
    const Box& b = box[into];
    for (std::uint32_t q : blocks[from].boundary) {
      const Point2 p{x[q], y[q]};
      if (p.x < b.lo_x || p.x > b.hi_x || p.y < b.lo_y || p.y > b.hi_y) continue;
      if (locate(p, blocks[into].boundary, x, y) != Location::inside) continue;
      const double depth = distance_to_loop(p, blocks[into].boundary, x, y);
      if (depth > deepest.depth) deepest = {depth, q, from, into};
    }
  };
  std::vector<std::uint32_t> order(blocks.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
    return box[i].lo_x < box[j].lo_x || (box[i].lo_x == box[j].lo_x && i < j);
  });
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::uint32_t i = order[k];
    for (std::size_t l = k + 1; l < order.size() && box[order[l]].lo_x <= box[i].hi_x; ++l) {
      const std::uint32_t j = order[l];
      if (blocks[i].spec.fixed && blocks[j].spec.fixed) continue;
      if (box[j].hi_y < box[i].lo_y || box[i].hi_y < box[j].lo_y) continue;
      nodes_inside(i, j);
      nodes_inside(j, i);
    }
  }
  if (deepest.depth <= params.contact.search_tolerance) return;
  const std::string a = block_name(blocks[deepest.block].spec.id), b = block_name(blocks[deepest.other].spec.id);
  throw std::invalid_argument(
      a + " and " + b + " overlap by " + number(deepest.depth) + " m at the start (a boundary node of " + a +
      " at (" + number(x[deepest.node]) + ", " + number(y[deepest.node]) + ") is that far inside " + b +
      "), more than contact.search_tolerance (" + number(params.contact.search_tolerance) +
      " m): the contact sees a node only within that distance of an edge, and the blocks would pass through "
      "each other; move them apart so that they touch or overlap by less (blocks resting on each other may "
      "share a face)");
}

// Central differences are stable for h < 2 / omega_max. For a constant-strain triangle with
// lumped masses omega_max <= 2 c / h_min, with c the P-wave speed and h_min its smallest altitude
// (the classical estimate: the time a wave takes to cross the element). A penalty spring kn
// between a node of mass m and an edge adds at most 2 kn / m_min to omega² (both ends as light as
// the lightest boundary node); the two add (Weyl: the largest eigenvalue of a sum of positive
// semi-definite operators is at most the sum of theirs).
void Cdem::Impl::check_critical_step() {
  double omega_elements = 0.0;
  std::size_t worst = 0;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const double altitude = smallest_altitude(x, y, elements[e]);
    min_altitude = std::min(min_altitude, altitude);
    const double omega = 2.0 * blocks[element_block[e]].elasticity.wave_speed / altitude;
    if (omega > omega_elements) {
      omega_elements = omega;
      worst = e;
    }
  }
  double omega_penalty_sq = 0.0;
  if (params.contact.law == CdemLaw::penalty) {
    double lightest = std::numeric_limits<double>::infinity();
    for (const BlockData& b : blocks)
      for (std::uint32_t n : b.boundary) lightest = std::min(lightest, mass[n]);
    omega_penalty_sq = 2.0 * params.contact.kn / lightest;
  }
  dt_critical = 2.0 / std::sqrt(omega_elements * omega_elements + omega_penalty_sq);
  if (params.dt > dt_critical) {
    const BlockData& b = blocks[element_block[worst]];
    std::string why = "element " + std::to_string(worst - b.first_element) + " of " + block_name(b.spec.id) +
                      " (wave speed " + number(b.elasticity.wave_speed) + " m/s)";
    if (omega_penalty_sq > 0.0) why += " and the penalty stiffness kn on the lightest boundary node";
    throw std::invalid_argument("time.dt: dt = " + number(params.dt) + " s is above the critical step " +
                                number(dt_critical) + " s set by " + why +
                                "; use a smaller dt or a coarser mesh (mesh.max_edge)");
  }
}

Cdem::Impl::Impl(std::vector<CdemBlockSpec> specs, CdemParams p) : params(p) {
  validate_params();
  require(!specs.empty(), "blocks: expected at least one block");
  if (params.contact.kt == 0.0) params.contact.kt = params.contact.kn;
  thread_count = params.threads == 0 ? omp_get_max_threads() : static_cast<int>(params.threads);
  for (CdemBlockSpec& s : specs) add_block(std::move(s));
  build_adjacency();
  check_initial_overlaps();
  check_critical_step();
  const std::size_t n = node_total();
  x0 = x;
  y0 = y;
  x_start = x;
  y_start = y;
  ax.assign(n, 0.0);
  ay.assign(n, 0.0);
  stress.assign(elements.size(), {0.0, 0.0, 0.0});
  element_force.assign(elements.size(), {});
  for (std::size_t i = 0; i < n; ++i) {
    if (inv_mass[i] > 0.0) energy_floor += 0.5 * mass[i] * energy_floor_speed * energy_floor_speed;
  }
  if (two_scale()) initial_ties();
  // The accelerations at t = 0: gravity, contacts and the ties (the stresses start at zero).
  internal_forces(false);
  if (!two_scale()) penalty_forces(0.0);
  solve_ties(params.dt, 0.0);
  start = energies();
}

void Cdem::Impl::contact_added(std::uint32_t main_block, std::uint32_t target_block, double t) {
  const std::uint64_t key = pair_key(std::min(main_block, target_block), std::max(main_block, target_block));
  PairCount& pc = pair_contacts[key];
  if (pc.count++ == 0) {
    pc.block_a = main_block;
    pc.block_b = target_block;
    events.push_back({t, CdemEvent::Kind::touch, main_block, target_block});
  }
}

void Cdem::Impl::contact_removed(std::uint32_t main_block, std::uint32_t target_block, double t) {
  const std::uint64_t key = pair_key(std::min(main_block, target_block), std::max(main_block, target_block));
  PairCount& pc = pair_contacts[key];
  if (--pc.count == 0) events.push_back({t, CdemEvent::Kind::separate, pc.block_a, pc.block_b});
}

// The (node, block) pairs in contact are not searched again. A clone node at an edge's end
// (lambda 0 or 1: node on node) engages the end node with the main block too, so that the same
// contact is not found a second time from the other side.
void Cdem::Impl::engage(std::uint32_t node, std::uint32_t block, double lambda, std::uint32_t a,
                        std::uint32_t b, std::uint32_t main_block, bool add) {
  const auto apply = [&](std::uint64_t key) {
    if (add) {
      engaged.insert(key);
    } else {
      engaged.erase(key);
    }
  };
  apply(pair_key(node, block));
  if (lambda == 0.0) apply(pair_key(a, main_block));
  if (lambda == 1.0) apply(pair_key(b, main_block));
}

// Every boundary node against every boundary edge of the other blocks whose boxes swept over the
// rest of the step come within the search tolerance (a uniform grid over the edges' swept boxes),
// then the exact first touch of each such pair (kernel/2d/touch_time.hpp) on the linear motion
// from the current positions to x + remaining * v.
// A node on a straight stretch of its block's outline (a flat node) touching an edge nearly
// perpendicular to that stretch is the target's corner arriving on, or sliding along, the flat
// face: the corner's own contact with this block's edge holds it (found the other way round).
// Taken as a collision of the flat node, it would strike the block sideways at every mesh node
// its corner slides over (the end of the side edge of a block sliding on a face sweeps each
// node of the face). Head-on meetings of faces stay contacts of the flat nodes.
bool Cdem::Impl::faces_meet(std::uint32_t node, const kernel::NodeEdgeMotion& motion) const {
  const BlockData& b = blocks[node_block[node]];
  const std::size_t m = b.boundary.size();
  const auto at = static_cast<std::size_t>(std::find(b.boundary.begin(), b.boundary.end(), node) - b.boundary.begin());
  const std::uint32_t before = b.boundary[(at + m - 1) % m], after = b.boundary[(at + 1) % m];
  const Vec2 face{x[after] - x[before], y[after] - y[before]};
  const Vec2 edge{motion.b.start.x - motion.a.start.x, motion.b.start.y - motion.a.start.y};
  // Outward normals: (dy, -dx) of each counter-clockwise direction.
  const double cosine = (face[1] * edge[1] + face[0] * edge[0]) / (std::hypot(face[0], face[1]) * std::hypot(edge[0], edge[1]));
  return cosine <= -flat_contact_cosine;
}

// `resting`: the nodes on an edge at the start (the scene's blocks built resting on each other)
// count as touching whatever their motion.
std::vector<Touch> Cdem::Impl::find_touches(double remaining, bool resting) const {
  const double tol = params.contact.search_tolerance;
  struct EdgeRef {
    std::uint32_t block, edge;
    double x_lo, y_lo, x_hi, y_hi;
  };
  std::vector<EdgeRef> edges;
  double cell = 0.0;
  for (std::uint32_t bi = 0; bi < blocks.size(); ++bi) {
    const BlockData& b = blocks[bi];
    const std::size_t m = b.boundary.size();
    for (std::uint32_t k = 0; k < m; ++k) {
      const std::uint32_t i = b.boundary[k], j = b.boundary[(k + 1) % m];
      const double xs[4] = {x[i], x[i] + remaining * vx[i], x[j], x[j] + remaining * vx[j]};
      const double ys[4] = {y[i], y[i] + remaining * vy[i], y[j], y[j] + remaining * vy[j]};
      EdgeRef r{bi, k, *std::min_element(xs, xs + 4) - tol, *std::min_element(ys, ys + 4) - tol,
                *std::max_element(xs, xs + 4) + tol, *std::max_element(ys, ys + 4) + tol};
      cell = std::max({cell, r.x_hi - r.x_lo, r.y_hi - r.y_lo});
      edges.push_back(r);
    }
  }
  if (edges.empty() || blocks.size() < 2) return {};
  // A runaway motion (a node thrown out to infinity, or so far that the grid's cell index would
  // not fit) stops the run here, before the grid is built, as the monitor would after the step.
  double extent = 0.0;
  for (const EdgeRef& r : edges) extent = std::max({extent, std::abs(r.x_lo), std::abs(r.x_hi), std::abs(r.y_lo), std::abs(r.y_hi)});
  if (!std::isfinite(extent) || !(extent / cell < 0x1p60)) {
    throw CdemStabilityError("a boundary node's motion over the step reaches " +
                             number(extent) + " m, beyond what the contact search can follow: the motion ran away");
  }
  // Blocks whose swept boxes meet no other block's need no grid: with a few blocks (the pairs test
  // is quadratic) the search is left out for them, and for the whole step when they are apart.
  std::vector<char> near(blocks.size(), 1);
  if (blocks.size() <= block_pretest_limit) {
    std::vector<std::array<double, 4>> box(blocks.size(), {std::numeric_limits<double>::infinity(),
                                                          std::numeric_limits<double>::infinity(),
                                                          -std::numeric_limits<double>::infinity(),
                                                          -std::numeric_limits<double>::infinity()});
    for (const EdgeRef& r : edges) {
      auto& b = box[r.block];
      b = {std::min(b[0], r.x_lo), std::min(b[1], r.y_lo), std::max(b[2], r.x_hi), std::max(b[3], r.y_hi)};
    }
    std::fill(near.begin(), near.end(), 0);
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      for (std::size_t j = i + 1; j < blocks.size(); ++j) {
        if (blocks[i].spec.fixed && blocks[j].spec.fixed) continue;
        if (box[i][2] < box[j][0] || box[j][2] < box[i][0] || box[i][3] < box[j][1] || box[j][3] < box[i][1]) continue;
        near[i] = near[j] = 1;
      }
    }
    if (std::find(near.begin(), near.end(), 1) == near.end()) return {};
  }
  // Each edge goes into every cell its box covers; with the cell as large as the largest box,
  // that is at most four.
  const auto cell_of = [cell](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  const auto key_of = [](std::int64_t i, std::int64_t j) {
    return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(j & 0xffffffff);
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  grid.reserve(edges.size() * 2);
  for (std::uint32_t e = 0; e < edges.size(); ++e) {
    if (!near[edges[e].block]) continue;
    for (std::int64_t i = cell_of(edges[e].x_lo); i <= cell_of(edges[e].x_hi); ++i)
      for (std::int64_t j = cell_of(edges[e].y_lo); j <= cell_of(edges[e].y_hi); ++j) grid[key_of(i, j)].push_back(e);
  }
  std::vector<Touch> touches;
  std::vector<std::uint32_t> seen;
  for (std::uint32_t bi = 0; bi < blocks.size(); ++bi) {
    if (!near[bi]) continue;
    for (std::uint32_t q : blocks[bi].boundary) {
      const double qx1 = x[q] + remaining * vx[q], qy1 = y[q] + remaining * vy[q];
      const double lo_x = std::min(x[q], qx1), hi_x = std::max(x[q], qx1);
      const double lo_y = std::min(y[q], qy1), hi_y = std::max(y[q], qy1);
      seen.clear();
      for (std::int64_t i = cell_of(lo_x); i <= cell_of(hi_x); ++i) {
        for (std::int64_t j = cell_of(lo_y); j <= cell_of(hi_y); ++j) {
          const auto it = grid.find(key_of(i, j));
          if (it == grid.end()) continue;
          for (std::uint32_t e : it->second) {
            const EdgeRef& r = edges[e];
            if (r.block == bi || hi_x < r.x_lo || lo_x > r.x_hi || hi_y < r.y_lo || lo_y > r.y_hi) continue;
            if (std::find(seen.begin(), seen.end(), e) != seen.end()) continue;
            seen.push_back(e);
            if (inv_mass[q] == 0.0 && blocks[r.block].spec.fixed) continue;
            if (engaged.contains(pair_key(q, r.block))) continue;
            const BlockData& target = blocks[r.block];
            const std::uint32_t a = target.boundary[r.edge];
            const std::uint32_t b = target.boundary[(r.edge + 1) % target.boundary.size()];
            Touch t;
            t.node = q;
            t.edge = r.edge;
            t.target_block = r.block;
            t.motion = {{{x[q], y[q]}, {qx1, qy1}},
                        {{x[a], y[a]}, {x[a] + remaining * vx[a], y[a] + remaining * vy[a]}},
                        {{x[b], y[b]}, {x[b] + remaining * vx[b], y[b] + remaining * vy[b]}}};
            const auto found = kernel::with_policy(params.contact.policy, [&](auto policy) {
              return kernel::first_touch<decltype(policy)>(t.motion);
            });
            if (found) {
              if (flat_node[q] && !faces_meet(q, t.motion)) continue;
              t.time = *found;
              touches.push_back(t);
              continue;
            }
            // On or just inside the edge's line at the start (first_touch needs the node
            // outside): a node left a rounding error inside when its clone node separated, or one
            // that rests on the edge. Within the edge's span and the search tolerance, and moving
            // further in over the motion (or resting, for the scene's initial contacts), it
            // touches at the start of the motion.
            const auto& mo = t.motion;
            const kernel::Sign side = kernel::with_policy(params.contact.policy, [&](auto policy) {
              return kernel::orientation<decltype(policy)>(mo.a.start, mo.b.start, mo.node.start);
            });
            if (side == kernel::Sign::negative || (resting && side != kernel::Sign::zero)) continue;
            const Vec2 d{mo.b.start.x - mo.a.start.x, mo.b.start.y - mo.a.start.y};
            const Vec2 r0{mo.node.start.x - mo.a.start.x, mo.node.start.y - mo.a.start.y};
            const double along = dot(r0, d), length_sq = dot(d, d);
            if (along < 0.0 || along > length_sq) continue;
            const double depth = cross(d, r0) / std::sqrt(length_sq);
            if (depth > tol) continue;
            if (!resting) {
              const Vec2 d1{mo.b.end.x - mo.a.end.x, mo.b.end.y - mo.a.end.y};
              const Vec2 r1{mo.node.end.x - mo.a.end.x, mo.node.end.y - mo.a.end.y};
              if (!(cross(d1, r1) / std::hypot(d1[0], d1[1]) > depth)) continue;
            }
            if (flat_node[q] && !faces_meet(q, t.motion)) continue;
            t.at_start = true;
            t.time.s = 0.0;
            t.time.lambda = along / length_sq;
            touches.push_back(t);
          }
        }
      }
    }
  }
  return touches;
}

// The motion stage of a step (seed 003 §3): every node moves with its step velocity; when a node
// reaches an edge inside the step (the exact first touch of all pairs), everything is advanced to
// that instant (the free-motion stage), the contact is formed (the clone node's inelastic onset
// changes the velocities of the node and the edge's ends), and the rest of the step follows
// with the new velocities (the contact stage), until no further touch falls inside the step.
// Under the penalty law the touches change no velocity: they only date the pairs' first contact.
void Cdem::Impl::move(double h) {
  const std::size_t n = node_total();
  x_start = x;
  y_start = y;
  double done = 0.0;  // fraction of the step behind
  if (two_scale() && blocks.size() > 1) {
    for (int batch = 0; batch < max_touch_batches; ++batch) {
      const double remaining = (1.0 - done) * h;
      std::vector<Touch> touches = find_touches(remaining);
      if (touches.empty()) break;
      // The earliest touch, by the exact comparison of the touch instants.
      const auto earlier = [&](const Touch& p, const Touch& q) {
        if (p.at_start || q.at_start) return p.at_start && !q.at_start;
        return kernel::with_policy(params.contact.policy, [&](auto policy) {
                 return kernel::compare_touch<decltype(policy)>(p.motion, p.time, q.motion, q.time);
               }) == kernel::Sign::negative;
      };
      const auto first = std::min_element(touches.begin(), touches.end(), earlier);
      const Touch lead = *first;
      const double s = lead.time.s;
      for (std::size_t i = 0; i < n; ++i) {
        x[i] += s * remaining * vx[i];
        y[i] += s * remaining * vy[i];
      }
      done += s * (1.0 - done);
      const double t = time + done * h;
      // Every touch at the same exact instant forms at once (a face meeting a face).
      for (const Touch& touch : touches) {
        if (&touch != &*first && earlier(lead, touch)) continue;
        if (engaged.contains(pair_key(touch.node, touch.target_block))) continue;
        form_tie(touch, t);
      }
      if (done >= 1.0) break;
    }
  }
  const double remaining = (1.0 - done) * h;
  for (std::size_t i = 0; i < n; ++i) {
    x[i] += remaining * vx[i];
    y[i] += remaining * vy[i];
  }
}

// The clone node's onset (seed 003 eq. 4): a perfectly inelastic collision of the node (mass M_m)
// with the edge's material point P = (1 - lambda) a + lambda b. P's mass is the effective mass of
// the edge at P, M_t = 1 / ((1 - lambda)² / m_a + lambda² / m_b): an impulse J at P spread to a and
// b by the shape functions changes P's velocity by J / M_t, so the common velocity
// v = (M_m v_m + M_t v_P) / (M_m + M_t) is reached exactly and the momentum of the three nodes is
// conserved. The loss (eq. 5) is mu |v_m - v_P|² / 2, mu = M_m M_t / (M_m + M_t). The tangential
// share of the impulse obeys Coulomb's law for impulses, |J_t| <= tan(phi) J_n: beyond it the clone
// node starts sliding with J_t at the limit (the seed assumes no slip at the onset; a frictionless
// contact cannot stop a tangential velocity).
void Cdem::Impl::form_tie(const Touch& touch, double t) {
  const BlockData& target = blocks[touch.target_block];
  Tie tie;
  tie.node = touch.node;
  tie.edge = touch.edge;
  tie.a = target.boundary[touch.edge];
  tie.b = target.boundary[(touch.edge + 1) % target.boundary.size()];
  tie.main_block = node_block[touch.node];
  tie.target_block = touch.target_block;
  tie.lambda = std::clamp(touch.time.lambda, 0.0, 1.0);
  tie.area = boundary_share[touch.node] * params.thickness;
  const double wa = 1.0 - tie.lambda, wb = tie.lambda;
  {
    const Vec2 n = edge_normal(tie);
    const Vec2 d{x[tie.node] - wa * x[tie.a] - wb * x[tie.b], y[tie.node] - wa * y[tie.a] - wb * y[tie.b]};
    tie.offset_n = dot(d, n);
    tie.offset_t = cross(n, d);
  }
  // With subdivision the touched point is a sub-node of the target element: its mass, not the
  // element's corners', meets the node (the collision of thin surface layers, §4.1), and the
  // impulse's momentum goes to the element's corners, where the sub-node's inertia is lumped.
  if (two_scale() && params.contact.subdivide) tie.patch = create_patch(tie.node, tie.a, tie.b, tie.lambda, t);
  double k = inv_mass[tie.node] + wa * wa * inv_mass[tie.a] + wb * wb * inv_mass[tie.b];
  if (tie.patch >= 0) {
    const Patch& patch = patches[static_cast<std::size_t>(tie.patch)];
    k = inv_mass[tie.node] + 1.0 / patch.m[patch.p];
  }
  if (k > 0.0) {
    const auto kinetic = [&] {
      double e = 0.0;
      for (std::uint32_t i : {tie.node, tie.a, tie.b}) {
        if (inv_mass[i] > 0.0) e += 0.5 * mass[i] * (vx[i] * vx[i] + vy[i] * vy[i]);
      }
      return e;
    };
    const double before = kinetic();
    const Vec2 w{vx[tie.node] - wa * vx[tie.a] - wb * vx[tie.b], vy[tie.node] - wa * vy[tie.a] - wb * vy[tie.b]};
    const Vec2 n = edge_normal(tie), tg{-n[1], n[0]};
    // The impulse on the node that stops the relative motion: J = -w / k.
    double jn = -dot(w, n) / k, jt = -dot(w, tg) / k;
    const double limit = std::tan(params.contact.friction_angle_deg * std::numbers::pi / 180.0) * std::max(jn, 0.0);
    if (std::abs(jt) > limit) {
      jt = std::copysign(limit, jt);
      tie.sliding = true;
    }
    const Vec2 j{jn * n[0] + jt * tg[0], jn * n[1] + jt * tg[1]};
    vx[tie.node] += inv_mass[tie.node] * j[0];
    vy[tie.node] += inv_mass[tie.node] * j[1];
    vx[tie.a] -= wa * inv_mass[tie.a] * j[0];
    vy[tie.a] -= wa * inv_mass[tie.a] * j[1];
    vx[tie.b] -= wb * inv_mass[tie.b] * j[0];
    vy[tie.b] -= wb * inv_mass[tie.b] * j[1];
    onset_loss += before - kinetic();
  }
  if (tie.sliding && tie.patch >= 0) {
    // A clone node that slides from its onset stays on the coarse scale (Tie: sliding clone
    // nodes follow the target's boundary, which a patch's driven contact point cannot).
    merge_patch(tie.patch);
    tie.patch = -1;
  }
  engage(tie.node, tie.target_block, tie.lambda, tie.a, tie.b, tie.main_block, true);
  ties.push_back(tie);
  ++counters.touches;
  ++counters.clone_nodes_formed;
  contact_added(tie.main_block, tie.target_block, t);
}

// Subdivides the target element of the boundary edge a -> b for a clone node touching it at
// lambda (Patch). The characteristic length of the contact is c dt2 (seed 003 §5, Fig. 10): the
// distance the elastic wave travels in the contact stage dt2 = t_n+1 - contact_time of the step;
// T is divided into k = ceil(h_T / (c dt2)) parts per edge, h_T its longest edge, at least 2 and
// at most max_subdivision (a touch at the very end of a step asks for an unbounded k). Returns
// the patch's index, or -1 when the element is fixed, already subdivided, or the touch is within
// half a sub-edge of a corner (P would be the corner itself, a coarse node).
int Cdem::Impl::create_patch(std::uint32_t main_node, std::uint32_t a, std::uint32_t b, double lambda,
                             double contact_time) {
  const auto found = boundary_element.find(pair_key(a, b));
  if (found == boundary_element.end()) return -1;
  const std::uint32_t e = found->second;
  const BlockData& block = blocks[element_block[e]];
  if (block.spec.fixed || patched[e]) return -1;
  for (const Patch& other : patches) {
    if (other.main_node == main_node) return -1;  // it moves on one patch's substeps only
  }
  const auto& g = elements[e];
  const int at = g[0] == a ? 0 : g[1] == a ? 1 : 2;
  Patch patch;
  patch.element = e;
  patch.corner = {g[at], g[(at + 1) % 3], g[(at + 2) % 3]};
  patch.main_node = main_node;
  const double c = block.elasticity.wave_speed;
  const double stage = std::max(time + params.dt - contact_time, 0.0);
  double longest = 0.0;
  for (int q = 0; q < 3; ++q) {
    const std::uint32_t i = patch.corner[q], j = patch.corner[(q + 1) % 3];
    longest = std::max(longest, std::hypot(x[j] - x[i], y[j] - y[i]));
  }
  const double length = c * stage;
  patch.k = length > 0.0 ? static_cast<int>(std::clamp(std::ceil(longest / length), 2.0, double(max_subdivision)))
                         : max_subdivision;
  const int k = patch.k;
  const int ip = static_cast<int>(std::lround(lambda * k));
  if (ip < 1 || ip > k - 1) return -1;
  // Sub-nodes row by row (j = 0 is the touched edge a -> b).
  std::vector<int> row_start(static_cast<std::size_t>(k + 2), 0);
  for (int j = 0; j <= k; ++j) row_start[static_cast<std::size_t>(j + 1)] = row_start[static_cast<std::size_t>(j)] + (k - j + 1);
  const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(row_start[static_cast<std::size_t>(j)] + i); };
  for (int j = 0; j <= k; ++j) {
    for (int i = 0; i + j <= k; ++i) {
      std::array<double, 3> w{1.0 - double(i + j) / k, double(i) / k, double(j) / k};
      if (j == 0 && i == ip) w = {1.0 - lambda, lambda, 0.0};
      patch.w.push_back(w);
      const bool on_other_edge = i == 0 || i + j == k;
      patch.free.push_back(!on_other_edge && !(j == 0 && i == ip));
      double px = 0.0, py = 0.0, pvx = 0.0, pvy = 0.0, px0 = 0.0, py0 = 0.0;
      for (int q = 0; q < 3; ++q) {
        const std::uint32_t n = patch.corner[q];
        px += w[q] * x[n];
        py += w[q] * y[n];
        pvx += w[q] * vx[n];
        pvy += w[q] * vy[n];
        px0 += w[q] * x0[n];
        py0 += w[q] * y0[n];
      }
      patch.x.push_back(px);
      patch.y.push_back(py);
      patch.vx.push_back(pvx);
      patch.vy.push_back(pvy);
      patch.x0.push_back(px0);
      patch.y0.push_back(py0);
    }
  }
  patch.p = id(ip, 0);
  patch.p_offset = {patch.x[patch.p] - x[main_node], patch.y[patch.p] - y[main_node]};
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i + j < k; ++i) {
      patch.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
      if (i + j < k - 1) patch.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  // Lumped masses of the sub-triangles; the critical step of the smallest one sets the substeps.
  const std::size_t count = patch.x.size();
  patch.m.assign(count, 0.0);
  double min_altitude_sub = std::numeric_limits<double>::infinity();
  for (const auto& t : patch.triangles) {
    const double area = triangle_area(patch.x, patch.y, t);
    min_altitude_sub = std::min(min_altitude_sub, smallest_altitude(patch.x, patch.y, t));
    for (std::uint32_t v : t) patch.m[v] += block.spec.material.density * params.thickness * area / 3.0;
  }
  const double substeps = std::ceil(params.dt / (0.9 * min_altitude_sub / c));
  if (!(substeps >= 1.0 && substeps <= max_substeps)) return -1;  // a flattened element: stay coarse
  patch.substeps = static_cast<int>(substeps);
  // The free sub-nodes' mass comes from the corners by the weights, so that the element's mass,
  // momentum and centre of mass stay what they were; the driven sub-nodes have no inertia of their
  // own (it stays lumped at the corners).
  for (std::size_t v = 0; v < count; ++v) {
    if (!patch.free[v]) continue;
    for (int q = 0; q < 3; ++q) patch.mass_moved[q] += patch.m[v] * patch.w[v][q];
  }
  for (int q = 0; q < 3; ++q) {
    const std::uint32_t n = patch.corner[q];
    mass[n] -= patch.mass_moved[q];
    inv_mass[n] = 1.0 / mass[n];
  }
  patch.stress.assign(patch.triangles.size(), stress[e]);
  patch.start = std::clamp((contact_time - time) / params.dt, 0.0, 1.0);
  for (int q = 0; q < 4; ++q) {
    const std::uint32_t n = q < 3 ? patch.corner[static_cast<std::size_t>(q)] : main_node;
    patch.from[static_cast<std::size_t>(q)] = {x[n], y[n]};
  }
  patch.ax.assign(count, 0.0);
  patch.ay.assign(count, 0.0);
  patch.driven_fx.assign(count, 0.0);
  patch.driven_fy.assign(count, 0.0);
  patched[e] = 1;
  element_force[e] = {};
  counters.subdivided_elements += patch.triangles.size();
  patches.push_back(std::move(patch));
  return static_cast<int>(patches.size() - 1);
}

// One coarse step of every patch (eq. 12 with velocity boundary conditions): the driven sub-nodes
// follow the coarse motion of the step (x_start -> x, linear in time), P the main node; the free
// ones take `substeps` velocity-Verlet substeps under the sub-elements' forces and gravity. The
// forces on the driven nodes at the end of the step are what the element gives its corners (by
// the weights) and what the target gives the clone node (at P).
void Cdem::Impl::run_patches(double h) {
  for (Patch& patch : patches) {
    const std::size_t count = patch.x.size();
    const double hs = (1.0 - patch.start) * h / patch.substeps;
    // Where each driven coarse node (a, b, c, main) is at the fraction tau of what is left.
    const auto coarse = [&](int q, double tau) -> Vec2 {
      const std::uint32_t n = q < 3 ? patch.corner[static_cast<std::size_t>(q)] : patch.main_node;
      const Vec2& f = patch.from[static_cast<std::size_t>(q)];
      return {f[0] + tau * (x[n] - f[0]), f[1] + tau * (y[n] - f[1])};
    };
    const Elasticity& d = blocks[element_block[patch.element]].elasticity;
    std::vector<double> fx(count), fy(count);
    const auto drive = [&](double tau) {
      for (std::size_t v = 0; v < count; ++v) {
        if (patch.free[v]) continue;
        double px = 0.0, py = 0.0;
        if (v == patch.p) {
          const Vec2 m = patch.fresh ? coarse(3, tau) : Vec2{x[patch.main_node], y[patch.main_node]};
          px = m[0] + patch.p_offset[0];
          py = m[1] + patch.p_offset[1];
        } else {
          for (int q = 0; q < 3; ++q) {
            const Vec2 c = coarse(q, tau);
            px += patch.w[v][q] * c[0];
            py += patch.w[v][q] * c[1];
          }
        }
        patch.x[v] = px;
        patch.y[v] = py;
      }
    };
    std::vector<double> ix(count, 0.0), iy(count, 0.0);  // driven nodes' impulse, N s
    // The clone node on the substeps: it starts from its position at t_n with the velocity of
    // the coarse half kick (its coarse forces: its own block's elements, gravity, other ties) and
    // takes the contact force of the sub-elements at P as the free sub-nodes take theirs, so that
    // the contact's stiffness, which the coarse step cannot follow, is integrated on the scale
    // that resolves it, and the impulses at P are equal and opposite substep by substep.
    const std::uint32_t main = patch.main_node;
    const double main_inverse_mass = inv_mass[main];
    if (!patch.fresh) {
      x[main] = x_start[main];
      y[main] = y_start[main];
    }
    for (int sub = 1; sub <= patch.substeps; ++sub) {
      if (!patch.fresh) {
        vx[main] += 0.5 * hs * patch.driven_fx[patch.p] * main_inverse_mass;
        vy[main] += 0.5 * hs * patch.driven_fy[patch.p] * main_inverse_mass;
        x[main] += hs * vx[main];
        y[main] += hs * vy[main];
      }
      for (std::size_t v = 0; v < count; ++v) {
        if (patch.free[v]) {
          patch.vx[v] += 0.5 * hs * patch.ax[v];
          patch.vy[v] += 0.5 * hs * patch.ay[v];
        } else {
          ix[v] += 0.5 * hs * patch.driven_fx[v];
          iy[v] += 0.5 * hs * patch.driven_fy[v];
        }
      }
      patch.xs = patch.x;
      patch.ys = patch.y;
      for (std::size_t v = 0; v < count; ++v) {
        if (!patch.free[v]) continue;
        patch.x[v] += hs * patch.vx[v];
        patch.y[v] += hs * patch.vy[v];
      }
      drive(double(sub) / patch.substeps);
      std::fill(fx.begin(), fx.end(), 0.0);
      std::fill(fy.begin(), fy.end(), 0.0);
      for (std::size_t t = 0; t < patch.triangles.size(); ++t) {
        const auto& tri = patch.triangles[t];
        const double xs[3] = {patch.xs[tri[0]], patch.xs[tri[1]], patch.xs[tri[2]]};
        const double ys[3] = {patch.ys[tri[0]], patch.ys[tri[1]], patch.ys[tri[2]]};
        const double xe[3] = {patch.x[tri[0]], patch.x[tri[1]], patch.x[tri[2]]};
        const double ye[3] = {patch.y[tri[0]], patch.y[tri[1]], patch.y[tri[2]]};
        double f[6];
        cst_forces(xs, ys, xe, ye, d, params.thickness, true, patch.stress[t], f);
        for (int q = 0; q < 3; ++q) {
          fx[tri[q]] += f[2 * q];
          fy[tri[q]] += f[2 * q + 1];
        }
      }
      for (std::size_t v = 0; v < count; ++v) {
        if (patch.free[v]) {
          patch.ax[v] = fx[v] / patch.m[v] + params.gravity[0];
          patch.ay[v] = fy[v] / patch.m[v] + params.gravity[1];
          patch.vx[v] += 0.5 * hs * patch.ax[v];
          patch.vy[v] += 0.5 * hs * patch.ay[v];
        } else {
          patch.driven_fx[v] = fx[v];
          patch.driven_fy[v] = fy[v];
          ix[v] += 0.5 * hs * fx[v];
          iy[v] += 0.5 * hs * fy[v];
        }
      }
      if (!patch.fresh) {
        vx[main] += 0.5 * hs * fx[patch.p] * main_inverse_mass;
        vy[main] += 0.5 * hs * fy[patch.p] * main_inverse_mass;
      }
    }
    patch.contact_end = {fx[patch.p], fy[patch.p]};
    // The next step starts where this one ends.
    patch.start = 0.0;
    for (int q = 0; q < 4; ++q) {
      const std::uint32_t n = q < 3 ? patch.corner[static_cast<std::size_t>(q)] : patch.main_node;
      patch.from[static_cast<std::size_t>(q)] = {x[n], y[n]};
    }
    std::array<Vec2, 3> corner_mean{};
    Vec2 contact_mean{};
    for (std::size_t v = 0; v < count; ++v) {
      if (patch.free[v]) continue;
      if (v == patch.p) {
        contact_mean = {ix[v] / h, iy[v] / h};
        continue;
      }
      for (int q = 0; q < 3; ++q) {
        corner_mean[q][0] += patch.w[v][q] * ix[v] / h;
        corner_mean[q][1] += patch.w[v][q] * iy[v] / h;
      }
    }
    const Vec2 contact_end{patch.driven_fx[patch.p], patch.driven_fy[patch.p]};
    for (int q = 0; q < 3; ++q) patch.corner_force[q] = corner_mean[q];
    if (patch.fresh) {
      patch.contact_force = contact_end;
      patch.contact_debt[0] += contact_mean[0] - contact_end[0];
      patch.contact_debt[1] += contact_mean[1] - contact_end[1];
    } else {
      patch.contact_force = {};  // applied on the substeps
    }
    patch.fresh = false;
  }
}

// A clone node whose contact force over the step breaks eq. 6 (tension) or eq. 9 (shear) leaves
// the fine scale: the step keeps the forces its patch gave (they acted while the tie held, and
// the free sub-nodes' momentum already answers them), the patch merges back, and the tie
// separates, or goes on as a coarse sliding tie against the limited shear (solve_ties leaves it
// out of this step's solve: its force is already applied).
void Cdem::Impl::release_patches() {
  const double tan_phi = std::tan(params.contact.friction_angle_deg * std::numbers::pi / 180.0);
  for (Tie& tie : ties) {
    if (tie.patch < 0) continue;
    const Vec2 f = patches[static_cast<std::size_t>(tie.patch)].contact_end;
    const Vec2 n = edge_normal(tie), tg{-n[1], n[0]};
    const double fn = dot(f, n), fs = dot(f, tg);
    const double limit = std::max(fn, 0.0) * tan_phi + params.contact.cohesion * tie.area;
    const bool tension = -fn > params.contact.tensile_strength * tie.area + separation_noise * std::hypot(fn, fs);
    if (!tension && std::abs(fs) <= limit) continue;
    merge_patch(tie.patch);
    // The coarse tie holds the node where the patch left it (its indentation of the edge, which
    // the unrefined element cannot show), rather than closing that offset in one step.
    const double wa = 1.0 - tie.lambda, wb = tie.lambda;
    const Vec2 d{x[tie.node] - wa * x[tie.a] - wb * x[tie.b], y[tie.node] - wa * y[tie.a] - wb * y[tie.b]};
    tie.offset_n = dot(d, n);
    tie.offset_t = dot(d, tg);
    tie.force = f;
    tie.applied = true;
    if (tension) {
      tie.separate = true;
    } else {
      tie.sliding = true;
      tie.slide_force = std::copysign(limit, fs);
    }
  }
}

// The patches' forces on the coarse nodes, after internal_forces: the corners' share of the
// sub-elements, and the contact force on each clone node's main node.
void Cdem::Impl::apply_patch_forces() {
  for (const auto& [n, f] : tails) {
    ax[n] += f[0] * inv_mass[n];
    ay[n] += f[1] * inv_mass[n];
  }
  tails.clear();
  for (const Patch& patch : patches) {
    for (int q = 0; q < 3; ++q) {
      const std::uint32_t n = patch.corner[q];
      ax[n] += patch.corner_force[q][0] * inv_mass[n];
      ay[n] += patch.corner_force[q][1] * inv_mass[n];
    }
    ax[patch.main_node] += patch.contact_force[0] * inv_mass[patch.main_node];
    ay[patch.main_node] += patch.contact_force[1] * inv_mass[patch.main_node];
  }
}

// The subdivision removed (seed 003 §5: "the subdivided elements will be deleted"): the free
// sub-nodes' mass and momentum return to the corners by the weights, the element takes the
// sub-elements' area-weighted mean stress. What the averaging takes out of the kinetic and strain
// energy (the sub-elements' own motion and stress variation) is booked with the onset losses.
void Cdem::Impl::merge_patch(int index) {
  Patch& patch = patches[static_cast<std::size_t>(index)];
  const Elasticity& d = blocks[element_block[patch.element]].elasticity;
  double before = 0.0, after = 0.0;
  std::array<double, 3> mean{};
  double area_sum = 0.0;
  for (std::size_t t = 0; t < patch.triangles.size(); ++t) {
    const auto& tri = patch.triangles[t];
    const double area = triangle_area(patch.x, patch.y, tri);
    before += d.energy_density(patch.stress[t]) * area * params.thickness;
    for (int q = 0; q < 3; ++q) mean[q] += area * patch.stress[t][q];
    area_sum += area;
  }
  for (double& v : mean) v /= area_sum;
  after += d.energy_density(mean) * area_sum * params.thickness;
  for (std::size_t v = 0; v < patch.x.size(); ++v) {
    if (patch.free[v]) before += 0.5 * patch.m[v] * (patch.vx[v] * patch.vx[v] + patch.vy[v] * patch.vy[v]);
  }
  for (int q = 0; q < 3; ++q) {
    const std::uint32_t n = patch.corner[q];
    before += 0.5 * mass[n] * (vx[n] * vx[n] + vy[n] * vy[n]);
    double px = mass[n] * vx[n], py = mass[n] * vy[n];
    for (std::size_t v = 0; v < patch.x.size(); ++v) {
      if (!patch.free[v]) continue;
      px += patch.m[v] * patch.w[v][q] * patch.vx[v];
      py += patch.m[v] * patch.w[v][q] * patch.vy[v];
    }
    // The forces already assembled for the step's second half kick stay forces.
    ax[n] *= mass[n] / (mass[n] + patch.mass_moved[q]);
    ay[n] *= mass[n] / (mass[n] + patch.mass_moved[q]);
    mass[n] += patch.mass_moved[q];
    inv_mass[n] = 1.0 / mass[n];
    vx[n] = px / mass[n];
    vy[n] = py / mass[n];
    after += 0.5 * mass[n] * (vx[n] * vx[n] + vy[n] * vy[n]);
  }
  onset_loss += before - after;
  tails.push_back({patch.main_node, patch.contact_debt});
  stress[patch.element] = mean;
  patched[patch.element] = 0;
  for (Tie& tie : ties) {
    if (tie.patch == index) tie.patch = -1;
    if (tie.patch > index) --tie.patch;
  }
  patches.erase(patches.begin() + index);
}

// The outward unit normal of the tie's edge (the target's interior is on the left of a -> b).
Vec2 Cdem::Impl::edge_normal(const Tie& tie) const {
  const Vec2 d{x[tie.b] - x[tie.a], y[tie.b] - y[tie.a]};
  const double length = std::hypot(d[0], d[1]);
  return {d[1] / length, -d[0] / length};
}

// Nodes that touch an edge exactly at the start (blocks built resting on each other) are joined
// without an onset: their relative velocity is whatever the scene gives (usually zero).
void Cdem::Impl::initial_ties() {
  for (const Touch& touch : find_touches(0.0, true)) {
    if (engaged.contains(pair_key(touch.node, touch.target_block))) continue;
    form_tie(touch, 0.0);
  }
}

// Element forces of every movable block's triangles (cst_forces, in parallel), gathered per node
// in a fixed order, then gravity. An element replaced by its subdivision (a Patch) is skipped: its
// patch gives its corners their forces.
void Cdem::Impl::internal_forces(bool incremental) {
  const auto count = static_cast<std::int64_t>(elements.size());
#pragma omp parallel for schedule(static) if (count >= parallel_threshold) num_threads(thread_count)
  for (std::int64_t ei = 0; ei < count; ++ei) {
    const auto e = static_cast<std::size_t>(ei);
    // Fixed blocks are at rest, unstressed and force-free.
    if (blocks[element_block[e]].spec.fixed || patched[e]) continue;
    const auto& g = elements[e];
    const double xs[3] = {x_start[g[0]], x_start[g[1]], x_start[g[2]]};
    const double ys[3] = {y_start[g[0]], y_start[g[1]], y_start[g[2]]};
    const double xe[3] = {x[g[0]], x[g[1]], x[g[2]]}, ye[3] = {y[g[0]], y[g[1]], y[g[2]]};
    cst_forces(xs, ys, xe, ye, blocks[element_block[e]].elasticity, params.thickness, incremental, stress[e],
               element_force[e].data());
  }
  const auto nodes = static_cast<std::int64_t>(node_total());
  const double gx = params.gravity[0], gy = params.gravity[1];
#pragma omp parallel for schedule(static) if (nodes >= parallel_threshold) num_threads(thread_count)
  for (std::int64_t ii = 0; ii < nodes; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (inv_mass[i] == 0.0) {
      ax[i] = ay[i] = 0.0;
      continue;
    }
    double fx = mass[i] * gx, fy = mass[i] * gy;
    for (std::uint32_t k = adjacency_first[i]; k < adjacency_first[i + 1]; ++k) {
      const std::uint32_t ref = adjacency[k];
      fx += element_force[ref / 3][2 * (ref % 3)];
      fy += element_force[ref / 3][2 * (ref % 3) + 1];
    }
    ax[i] = fx * inv_mass[i];
    ay[i] = fy * inv_mass[i];
  }
}

// Node-to-edge penalty contact (the comparison law): a boundary node inside another block by at
// most the search tolerance, within an edge's span, is pushed out along that edge's outward normal
// by kn times its depth (the edge with the smallest depth); the edge's ends take the reaction by
// the shape functions. The tangential spring (kt) follows the relative tangential displacement of
// the node and the edge's material point and is capped at tan(phi) fn + c Ac (elastoplastic
// Coulomb, as the 2D DDA's default law: never reset while the contact lasts).
void Cdem::Impl::penalty_forces(double t) {
  const double tol = params.contact.search_tolerance;
  const double tan_phi = std::tan(params.contact.friction_angle_deg * std::numbers::pi / 180.0);
  std::unordered_map<std::uint64_t, PenaltyContact> previous;
  for (const PenaltyContact& c : penalty) previous.emplace(pair_key(c.node, c.target_block), c);
  std::vector<PenaltyContact> found;
  if (blocks.size() > 1) {
    for (std::uint32_t bi = 0; bi < blocks.size(); ++bi) {
      for (std::uint32_t q : blocks[bi].boundary) {
        for (std::uint32_t ti = 0; ti < blocks.size(); ++ti) {
          if (ti == bi || (inv_mass[q] == 0.0 && blocks[ti].spec.fixed)) continue;
          const BlockData& target = blocks[ti];
          const std::size_t m = target.boundary.size();
          std::optional<PenaltyContact> best;
          for (std::uint32_t k = 0; k < m; ++k) {
            const std::uint32_t a = target.boundary[k], b = target.boundary[(k + 1) % m];
            const double xl = std::min(x[a], x[b]) - tol, xh = std::max(x[a], x[b]) + tol;
            const double yl = std::min(y[a], y[b]) - tol, yh = std::max(y[a], y[b]) + tol;
            if (x[q] < xl || x[q] > xh || y[q] < yl || y[q] > yh) continue;
            const Vec2 d{x[b] - x[a], y[b] - y[a]}, r{x[q] - x[a], y[q] - y[a]};
            const double length = std::hypot(d[0], d[1]);
            const double depth = cross(d, r) / length;  // > 0: on the interior side
            const double lambda = dot(r, d) / (length * length);
            if (depth <= 0.0 || depth > tol || lambda < 0.0 || lambda > 1.0) continue;
            if (!best || depth < best->depth) {
              best = PenaltyContact{q, a, b, bi, ti, lambda, depth, 0.0, boundary_share[q] * params.thickness};
            }
          }
          if (best) found.push_back(*best);
        }
      }
    }
  }
  // Dating new pairs' first contact, and the separations.
  for (PenaltyContact& c : found) {
    const auto it = previous.find(pair_key(c.node, c.target_block));
    if (it != previous.end()) {
      // The tangential spring goes on: stretched by the relative tangential displacement of the
      // step, capped at the Coulomb limit (the excess is dissipated).
      const PenaltyContact& p = it->second;
      const double wa = 1.0 - p.lambda, wb = p.lambda;
      const Vec2 rel{(x[c.node] - x_start[c.node]) - wa * (x[p.a] - x_start[p.a]) - wb * (x[p.b] - x_start[p.b]),
                     (y[c.node] - y_start[c.node]) - wa * (y[p.a] - y_start[p.a]) - wb * (y[p.b] - y_start[p.b])};
      const Vec2 d{x[c.b] - x[c.a], y[c.b] - y[c.a]};
      const double length = std::hypot(d[0], d[1]);
      const double slip = dot(rel, d) / length;
      const double trial = p.shear - params.contact.kt * slip;
      const double limit = tan_phi * params.contact.kn * c.depth + params.contact.cohesion * c.area;
      c.shear = std::clamp(trial, -limit, limit);
      if (c.shear != trial) friction += std::abs(trial - c.shear) * limit / params.contact.kt;
      previous.erase(it);
    } else {
      ++counters.touches;
      const double s = kernel::with_policy(params.contact.policy, [&](auto policy) {
        const kernel::NodeEdgeMotion m{{{x_start[c.node], y_start[c.node]}, {x[c.node], y[c.node]}},
                                       {{x_start[c.a], y_start[c.a]}, {x[c.a], y[c.a]}},
                                       {{x_start[c.b], y_start[c.b]}, {x[c.b], y[c.b]}}};
        const auto touch = kernel::first_touch<decltype(policy)>(m);
        return touch ? touch->s : 1.0;
      });
      contact_added(c.main_block, c.target_block, time - params.dt + s * params.dt);
    }
  }
  for (const auto& [key, c] : previous) contact_removed(c.main_block, c.target_block, t);
  penalty = std::move(found);
  for (const PenaltyContact& c : penalty) {
    const Vec2 d{x[c.b] - x[c.a], y[c.b] - y[c.a]};
    const double length = std::hypot(d[0], d[1]);
    const Vec2 n{d[1] / length, -d[0] / length}, tg{d[0] / length, d[1] / length};
    const double fn = params.contact.kn * c.depth;
    apply_node_edge_force(c.node, c.a, c.b, c.lambda, {fn * n[0] + c.shear * tg[0], fn * n[1] + c.shear * tg[1]});
  }
}

// A sliding clone node follows its node along the target's boundary: lambda is the node's
// projection on the edge; past an end it moves to the neighbouring edge, and off the boundary's
// corner it separates.
void Cdem::Impl::follow_sliding_ties(double t) {
  for (Tie& tie : ties) {
    if (!tie.sliding) continue;
    const BlockData& target = blocks[tie.target_block];
    const std::size_t m = target.boundary.size();
    bool placed = false;
    for (int hop = 0; hop < 3 && !placed; ++hop) {
      const Vec2 d{x[tie.b] - x[tie.a], y[tie.b] - y[tie.a]};
      const Vec2 r{x[tie.node] - x[tie.a], y[tie.node] - y[tie.a]};
      const double lambda = dot(r, d) / dot(d, d);
      if (lambda >= 0.0 && lambda <= 1.0) {
        engage(tie.node, tie.target_block, tie.lambda, tie.a, tie.b, tie.main_block, false);
        tie.lambda = lambda;
        tie.offset_t = 0.0;
        engage(tie.node, tie.target_block, tie.lambda, tie.a, tie.b, tie.main_block, true);
        placed = true;
        break;
      }
      engage(tie.node, tie.target_block, tie.lambda, tie.a, tie.b, tie.main_block, false);
      tie.edge = static_cast<std::uint32_t>(lambda > 1.0 ? (tie.edge + 1) % m : (tie.edge + m - 1) % m);
      tie.a = target.boundary[tie.edge];
      tie.b = target.boundary[(tie.edge + 1) % m];
      tie.lambda = lambda > 1.0 ? 0.0 : 1.0;
      engage(tie.node, tie.target_block, tie.lambda, tie.a, tie.b, tie.main_block, true);
      // Round a convex corner only while the node stays on the new edge's outward side within
      // the search tolerance; otherwise it has slid off.
      const Vec2 n = edge_normal(tie);
      const double gap = (x[tie.node] - x[tie.a]) * n[0] + (y[tie.node] - y[tie.a]) * n[1];
      if (std::abs(gap) > params.contact.search_tolerance) break;
    }
    if (!placed) tie.separate = true;
  }
  remove_separated(t);
}

// Separated clone nodes leave the list; the pair's last one dates its "separate" event.
void Cdem::Impl::remove_separated(double t) {
  for (const Tie& tie : ties) {
    if (tie.separate && tie.patch >= 0) merge_patch(tie.patch);
  }
  const auto end = std::remove_if(ties.begin(), ties.end(), [&](const Tie& tie) {
    if (!tie.separate) return false;
    engage(tie.node, tie.target_block, tie.lambda, tie.a, tie.b, tie.main_block, false);
    ++counters.clone_nodes_separated;
    contact_removed(tie.main_block, tie.target_block, t);
    return true;
  });
  ties.erase(end, ties.end());
}

// The force f on `node` and -f on the edge's point (1 - lambda) a + lambda b, spread to a and b by
// the shape functions, as accelerations.
void Cdem::Impl::apply_node_edge_force(std::uint32_t node, std::uint32_t a, std::uint32_t b, double lambda,
                                       const Vec2& f) {
  ax[node] += inv_mass[node] * f[0];
  ay[node] += inv_mass[node] * f[1];
  ax[a] -= (1.0 - lambda) * inv_mass[a] * f[0];
  ay[a] -= (1.0 - lambda) * inv_mass[a] * f[1];
  ax[b] -= lambda * inv_mass[b] * f[0];
  ay[b] -= lambda * inv_mass[b] * f[1];
}

// The clone nodes after the onset (seed 003 §4.2, eq. 6-11). A tie keeps the node on the edge's
// material point: its force F on the node (and -F spread to the edge's ends) is the one that
// gives the two points the same acceleration, plus the correction that closes their drift d and
// relative velocity w within the next step (a_rel = (-d / h - w) / h: exact velocity Verlet
// bookkeeping of the two half kicks). Ties sharing nodes are solved together by Gauss-Seidel
// sweeps (one sweep is exact for ties that share nothing). F is the interaction force F_mt of
// eq. 11; its normal part Fn (compression > 0) and shear part Fs decide:
//   eq. 6: tension -Fn > sigma_t Ac           -> the clone node separates;
//   eq. 7-10: |Fs| > max(Fn, 0) tan(phi) + c Ac -> the shear force is reduced to that limit.
// Sliding clone nodes (seed 003 §7 leaves them to future work): the node keeps its normal tie and
// slides along the target's boundary against the limited shear force, which keeps the direction
// of the stick force it replaced (opposing the relative slip); every step it is first tried as
// stuck again, so it sticks when the stick force falls within the limit.
void Cdem::Impl::solve_ties(double h, double t) {
  if (ties.empty()) return;
  follow_sliding_ties(t);
  // The accelerations without the ties, of the nodes the ties touch (each round starts again
  // from them).
  std::vector<std::uint32_t> tied;
  for (const Tie& tie : ties) tied.insert(tied.end(), {tie.node, tie.a, tie.b});
  std::sort(tied.begin(), tied.end());
  tied.erase(std::unique(tied.begin(), tied.end()), tied.end());
  std::vector<Vec2> free_acceleration(tied.size());
  for (std::size_t k = 0; k < tied.size(); ++k) free_acceleration[k] = {ax[tied[k]], ay[tied[k]]};
  const double tan_phi = std::tan(params.contact.friction_angle_deg * std::numbers::pi / 180.0);
  for (Tie& tie : ties) {
    if (!tie.applied) tie.sliding = false;
  }
  for (int round = 0; round < tie_rounds; ++round) {
    for (std::size_t k = 0; k < tied.size(); ++k) {
      ax[tied[k]] = free_acceleration[k][0];
      ay[tied[k]] = free_acceleration[k][1];
    }
    for (Tie& tie : ties) {
      if (tie.applied) continue;
      tie.force = {0.0, 0.0};
      if (tie.separate) continue;
      if (tie.patch >= 0) {
        tie.force = patches[static_cast<std::size_t>(tie.patch)].contact_end;
        continue;
      }
      if (tie.sliding) {
        const Vec2 n = edge_normal(tie), tg{-n[1], n[0]};
        tie.force = {tie.slide_force * tg[0], tie.slide_force * tg[1]};
        apply_node_edge_force(tie.node, tie.a, tie.b, tie.lambda, tie.force);
      }
    }
    for (int sweep = 0; sweep < tie_sweeps; ++sweep) {
      double change = 0.0, scale = 0.0;
      for (Tie& tie : ties) {
        if (tie.separate || tie.patch >= 0 || tie.applied) continue;
        const double wa = 1.0 - tie.lambda, wb = tie.lambda;
        const double k = inv_mass[tie.node] + wa * wa * inv_mass[tie.a] + wb * wb * inv_mass[tie.b];
        if (k == 0.0) continue;
        const Vec2 n = edge_normal(tie), tg{-n[1], n[0]};
        const Vec2 d{x[tie.node] - wa * x[tie.a] - wb * x[tie.b] - tie.offset_n * n[0] - tie.offset_t * tg[0],
                     y[tie.node] - wa * y[tie.a] - wb * y[tie.b] - tie.offset_n * n[1] - tie.offset_t * tg[1]};
        const Vec2 w{vx[tie.node] - wa * vx[tie.a] - wb * vx[tie.b], vy[tie.node] - wa * vy[tie.a] - wb * vy[tie.b]};
        const Vec2 r{ax[tie.node] - wa * ax[tie.a] - wb * ax[tie.b], ay[tie.node] - wa * ay[tie.a] - wb * ay[tie.b]};
        Vec2 df{((-d[0] / h - w[0]) / h - r[0]) / k, ((-d[1] / h - w[1]) / h - r[1]) / k};
        if (tie.sliding) {
          const double dn = dot(df, n);
          df = {dn * n[0], dn * n[1]};
        }
        apply_node_edge_force(tie.node, tie.a, tie.b, tie.lambda, df);
        tie.force[0] += df[0];
        tie.force[1] += df[1];
        change = std::max(change, std::hypot(df[0], df[1]));
        scale = std::max(scale, std::hypot(tie.force[0], tie.force[1]));
      }
      if (change <= 1e-13 * scale) break;
    }
    // Slip first: a stick trial's shear (it stops the relative slip within one step) pushes on
    // the normal forces of the ties it shares nodes with, so tension is judged only once the
    // ties that slip carry their limited shear.
    bool slipped = false;
    for (Tie& tie : ties) {
      if (tie.separate || tie.patch >= 0 || tie.applied) continue;
      const Vec2 n = edge_normal(tie), tg{-n[1], n[0]};
      const double fn = dot(tie.force, n), fs = dot(tie.force, tg);
      const double limit = std::max(fn, 0.0) * tan_phi + params.contact.cohesion * tie.area;
      if (!tie.sliding && std::abs(fs) > limit) {
        tie.sliding = true;
        tie.slide_force = std::copysign(limit, fs);
        slipped = true;
      } else if (tie.sliding && std::abs(std::abs(tie.slide_force) - limit) > 1e-6 * limit) {
        // The normal force moved with the other ties: the limit follows it (a fixed point).
        tie.slide_force = std::copysign(limit, tie.slide_force);
        slipped = true;
      }
    }
    if (slipped) continue;
    bool separated = false;
    for (Tie& tie : ties) {
      if (tie.separate || tie.patch >= 0 || tie.applied) continue;
      const Vec2 n = edge_normal(tie), tg{-n[1], n[0]};
      const double fn = dot(tie.force, n), fs = dot(tie.force, tg);
      // Rounding leaves a tie that carries nothing with a force of ~1e-16 of those around it in
      // either direction: tension counts from 1e-9 of the tie's own force up.
      if (-fn > params.contact.tensile_strength * tie.area + separation_noise * std::hypot(fn, fs)) {
        tie.separate = true;
        separated = true;
      }
    }
    if (!separated) break;
  }
  // The work of the ties over the step: their normal force against the relative velocity (zero
  // for a tie held exactly), and the sliding ties' shear force against the slip (friction).
  for (Tie& tie : ties) {
    const bool skip = tie.separate || tie.patch >= 0 || tie.applied;  // a patch's point moves with its node
    tie.applied = false;
    if (skip) continue;
    const double wa = 1.0 - tie.lambda, wb = tie.lambda;
    const Vec2 w{vx[tie.node] - wa * vx[tie.a] - wb * vx[tie.b], vy[tie.node] - wa * vy[tie.a] - wb * vy[tie.b]};
    const Vec2 n = edge_normal(tie), tg{-n[1], n[0]};
    if (tie.sliding) {
      friction -= h * tie.slide_force * dot(w, tg);
      tie_work -= h * dot(tie.force, n) * dot(w, n);
    } else {
      tie_work -= h * dot(tie.force, w);
    }
  }
  remove_separated(t);
}

CdemEnergies Cdem::Impl::energies() const {
  CdemEnergies e;
  for (std::size_t i = 0; i < node_total(); ++i) {
    if (inv_mass[i] == 0.0) continue;
    e.kinetic += 0.5 * mass[i] * (vx[i] * vx[i] + vy[i] * vy[i]);
    e.gravitational -= mass[i] * (params.gravity[0] * (x[i] - x0[i]) + params.gravity[1] * (y[i] - y0[i]));
  }
  for (std::size_t k = 0; k < elements.size(); ++k) {
    if (patched[k]) continue;
    const double area = triangle_area(x, y, elements[k]);
    e.strain += blocks[element_block[k]].elasticity.energy_density(stress[k]) * area * params.thickness;
  }
  for (const Patch& patch : patches) {
    const Elasticity& d = blocks[element_block[patch.element]].elasticity;
    for (std::size_t v = 0; v < patch.x.size(); ++v) {
      if (!patch.free[v]) continue;
      e.kinetic += 0.5 * patch.m[v] * (patch.vx[v] * patch.vx[v] + patch.vy[v] * patch.vy[v]);
      e.gravitational -= patch.m[v] * (params.gravity[0] * (patch.x[v] - patch.x0[v]) +
                                       params.gravity[1] * (patch.y[v] - patch.y0[v]));
    }
    for (std::size_t t = 0; t < patch.triangles.size(); ++t) {
      const double area = triangle_area(patch.x, patch.y, patch.triangles[t]);
      e.strain += d.energy_density(patch.stress[t]) * area * params.thickness;
    }
  }
  for (const PenaltyContact& c : penalty) {
    e.contact += 0.5 * params.contact.kn * c.depth * c.depth + 0.5 * c.shear * c.shear / params.contact.kt;
  }
  e.onset_loss = onset_loss;
  e.friction = friction;
  e.damping = damping_work;
  e.tie_work = tie_work;
  return e;
}

// A block's mean rotation: the angle of the best rotation taking the nodes' initial offsets from
// the mass centre to their current ones (mass-weighted), unwrapped from step to step.
void Cdem::Impl::update_rotations() {
  for (BlockData& b : blocks) {
    if (b.spec.fixed) continue;
    Vec2 c{};
    for (std::uint32_t n = b.first_node; n < b.first_node + b.node_count; ++n) {
      c[0] += mass[n] * x[n];
      c[1] += mass[n] * y[n];
    }
    c[0] /= b.mass;
    c[1] /= b.mass;
    double sdot = 0.0, scross = 0.0;
    for (std::uint32_t n = b.first_node; n < b.first_node + b.node_count; ++n) {
      const Vec2 r0{x0[n] - b.centre0[0], y0[n] - b.centre0[1]}, r{x[n] - c[0], y[n] - c[1]};
      sdot += mass[n] * dot(r0, r);
      scross += mass[n] * cross(r0, r);
    }
    const double angle = std::atan2(scross, sdot);
    const double turn = std::remainder(angle - b.rotation, 2.0 * std::numbers::pi);
    b.rotation += turn;
  }
}

void Cdem::Impl::monitor() {
  for (std::size_t i = 0; i < node_total(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !std::isfinite(vx[i]) || !std::isfinite(vy[i])) {
      throw CdemStabilityError("a non-finite position or velocity at a node of " +
                               block_name(blocks[node_block[i]].spec.id));
    }
  }
  // The energy check costs a pass over the elements: every few steps (a diverging run grows
  // geometrically, so a few steps' delay changes nothing).
  if (steps % energy_check_every != 0) return;
  const CdemEnergies e = energies();
  // The largest gravitational energy released, sampled with the checks.
  max_gravitational = std::max(max_gravitational, std::abs(e.gravitational));
  const double budget = 2.0 * (start.kinetic + start.strain + max_gravitational + energy_floor);
  if (e.total() - start.total() > budget) {
    throw CdemStabilityError("the energy grew by " + number(e.total() - start.total()) +
                             " J, beyond twice what the run can draw on (" + number(budget / 2.0) +
                             " J): the integration is unstable");
  }
  for (const PenaltyContact& c : penalty) {
    if (c.depth > 0.5 * min_altitude) {
      throw CdemStabilityError("a node of " + block_name(blocks[c.main_block].spec.id) +
                               " is " + number(c.depth) + " m inside " + block_name(blocks[c.target_block].spec.id) +
                               ", beyond half the smallest element; kn is too small for the load");
    }
  }
}

// One step of velocity Verlet (the same positions as central differences, eq. 1), with the
// mass-proportional damping implicit in the second half kick:
//   v_half = v_n (1 - alpha h / 2) + h / 2 a_n;  x_n+1 = x_n + h v_half (with the touches);
//   a_n+1 from the forces at x_n+1 and the ties;  v_n+1 = (v_half + h / 2 a_n+1) / (1 + alpha h / 2).
void Cdem::Impl::step() {
  const double h = params.dt, alpha = params.damping;
  const std::size_t n = node_total();
  double damped = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (inv_mass[i] == 0.0) {
      vx[i] = vy[i] = 0.0;
      continue;
    }
    const double before = vx[i] * vx[i] + vy[i] * vy[i];
    vx[i] = vx[i] * (1.0 - 0.5 * alpha * h) + 0.5 * h * ax[i];
    vy[i] = vy[i] * (1.0 - 0.5 * alpha * h) + 0.5 * h * ay[i];
    damped += 0.5 * alpha * h * mass[i] * before;
  }
  move(h);
  ++steps;
  time = static_cast<double>(steps) * h;
  run_patches(h);
  internal_forces(true);
  apply_patch_forces();
  release_patches();
  if (!two_scale()) penalty_forces(time);
  solve_ties(h, time);
  for (std::size_t i = 0; i < n; ++i) {
    if (inv_mass[i] == 0.0) continue;
    vx[i] = (vx[i] + 0.5 * h * ax[i]) / (1.0 + 0.5 * alpha * h);
    vy[i] = (vy[i] + 0.5 * h * ay[i]) / (1.0 + 0.5 * alpha * h);
    damped += 0.5 * alpha * h * mass[i] * (vx[i] * vx[i] + vy[i] * vy[i]);
  }
  damping_work += damped;
  update_rotations();
  monitor();
}

Cdem::Cdem(std::vector<CdemBlockSpec> blocks, CdemParams params)
    : impl_(std::make_unique<Impl>(std::move(blocks), params)) {}
Cdem::~Cdem() = default;
Cdem::Cdem(Cdem&&) noexcept = default;
Cdem& Cdem::operator=(Cdem&&) noexcept = default;

void Cdem::step() { impl_->step(); }
double Cdem::time() const { return impl_->time; }
std::size_t Cdem::steps() const { return impl_->steps; }
double Cdem::critical_dt() const { return impl_->dt_critical; }
std::size_t Cdem::block_count() const { return impl_->blocks.size(); }
const CdemBlockSpec& Cdem::block(std::size_t i) const { return impl_->blocks.at(i).spec; }
std::size_t Cdem::element_count() const { return impl_->elements.size(); }
std::size_t Cdem::node_count() const { return impl_->node_total(); }
CdemEnergies Cdem::energies() const { return impl_->energies(); }
const std::vector<CdemEvent>& Cdem::events() const { return impl_->events; }
const CdemCounters& Cdem::counters() const { return impl_->counters; }

std::array<double, 2> Cdem::momentum() const {
  const Impl& m = *impl_;
  std::array<double, 2> p{};
  for (std::size_t i = 0; i < m.node_total(); ++i) {
    if (m.inv_mass[i] == 0.0) continue;
    p[0] += m.mass[i] * m.vx[i];
    p[1] += m.mass[i] * m.vy[i];
  }
  for (const Patch& patch : m.patches) {
    for (std::size_t v = 0; v < patch.x.size(); ++v) {
      if (!patch.free[v]) continue;
      p[0] += patch.m[v] * patch.vx[v];
      p[1] += patch.m[v] * patch.vy[v];
    }
  }
  return p;
}

CdemBlockState Cdem::block_state(std::size_t i) const {
  const Impl& m = *impl_;
  const BlockData& b = m.blocks.at(i);
  CdemBlockState s;
  double inertia = 0.0, angular = 0.0;
  for (std::uint32_t n = b.first_node; n < b.first_node + b.node_count; ++n) {
    s.centre[0] += m.mass[n] * m.x[n];
    s.centre[1] += m.mass[n] * m.y[n];
    s.velocity[0] += m.mass[n] * m.vx[n];
    s.velocity[1] += m.mass[n] * m.vy[n];
  }
  for (const Patch& patch : m.patches) {
    if (m.element_block[patch.element] != i) continue;
    for (std::size_t v = 0; v < patch.x.size(); ++v) {
      if (!patch.free[v]) continue;
      s.centre[0] += patch.m[v] * patch.x[v];
      s.centre[1] += patch.m[v] * patch.y[v];
      s.velocity[0] += patch.m[v] * patch.vx[v];
      s.velocity[1] += patch.m[v] * patch.vy[v];
    }
  }
  for (int k = 0; k < 2; ++k) {
    s.centre[k] /= b.mass;
    s.velocity[k] /= b.mass;
  }
  // The mean angular velocity: the nodes' angular momentum about the mass centre over their
  // moment of inertia there.
  for (std::uint32_t n = b.first_node; n < b.first_node + b.node_count; ++n) {
    const Vec2 r{m.x[n] - s.centre[0], m.y[n] - s.centre[1]};
    const Vec2 v{m.vx[n] - s.velocity[0], m.vy[n] - s.velocity[1]};
    inertia += m.mass[n] * dot(r, r);
    angular += m.mass[n] * cross(r, v);
  }
  s.omega = inertia > 0.0 ? angular / inertia : 0.0;
  s.rotation = b.rotation;
  return s;
}

CdemMeshView Cdem::mesh(std::size_t i) const {
  const Impl& m = *impl_;
  const BlockData& b = m.blocks.at(i);
  b.view_nodes.resize(b.node_count);
  b.view_velocities.resize(b.node_count);
  for (std::uint32_t k = 0; k < b.node_count; ++k) {
    b.view_nodes[k] = {m.x[b.first_node + k], m.y[b.first_node + k]};
    b.view_velocities[k] = {m.vx[b.first_node + k], m.vy[b.first_node + k]};
  }
  b.view_stresses.assign(m.stress.begin() + b.first_element, m.stress.begin() + b.first_element + b.element_count);
  return {&b.view_nodes, &b.view_velocities, &b.view_triangles, &b.view_stresses};
}

}  // namespace rockcontact::dynamics
