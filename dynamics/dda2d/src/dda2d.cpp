#include "rockcontact/dynamics/dda2d.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>

#include <Eigen/Dense>
#include <omp.h>

#include "block_matrices.hpp"
#include "../../common/src/block_cholesky.hpp"
#include "broad_phase.hpp"
#include "rockcontact/contact/potential2d/contact_springs.hpp"
#include "rockcontact/kernel/2d/block_cutting.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"

namespace rockcontact::dynamics {
namespace {

using detail::BlockPair;
using detail::Vector6;

// Above this many blocks the candidate pairs come from the uniform grid; below, every pair is
// tried (the broad phase would cost more than it saves).
constexpr std::size_t broad_phase_threshold = 8;
// Stability monitor (dda2d.hpp): growth bound factor, floor speed (m/s), penetration fraction.
constexpr double energy_growth_factor = 2.0;
constexpr double energy_floor_speed = 1.0e-3;
constexpr double penetration_fraction = 0.5;
// Below this many candidate pairs (or blocks) a parallel pass runs on the calling thread only:
// starting the workers would cost more than it saves.
constexpr std::ptrdiff_t parallel_threshold = 64;
// Static analysis (dda2d.hpp): omega h of the relaxation steps. On the 205-block rock mass of
// examples/scenes/collapse_*.json, 0.8, 1.0 and 1.2 took 10 160, 5 065 and 4 481 iterations, and
// 1.6 diverged (its stiffest modes exceed the Gershgorin estimate there): 1.0 keeps a margin.
constexpr double relaxation_omega_h = 1.0;
// Initial equilibrium (dda2d.hpp): Newton iterations before dynamic relaxation finishes, and
// the relaxation's (a block on a slope took ~700); the largest move of one iteration, of the
// block's inradius; the smallest Levenberg-Marquardt damping once it is on; the
// regularisation of the stiffness, of a block's own contact scale (kn / H times its perimeter),
// which leaves a free mode a move 10⁹ times the contacts' and the solve finite. The open-close
// iteration within one Newton iteration: its solves, and how much force (of the equilibrium
// tolerance times the reference force) a line's closed part may move and count as unchanged:
// a tenth, so that the parts it stops with leave the ratio an order below the tolerance. Judged
// by how far its ends move instead, a part stops off where the forces are: 5 % of a 1 m line
// whose gap changes by 3 µm along it is ~15 N at kn = 2 GPa, a bias Newton's iterations do
// not remove (a 2 x 2 grid of deformable blocks stalled at a ratio of 5.8·10⁻⁵).
constexpr std::size_t newton_iterations = 30;
constexpr std::size_t relaxation_iterations = 20000;
// How often the relaxation reports progress and looks for a new least ratio, and after how
// many iterations without one it gives up.
constexpr std::size_t relaxation_check = 100;
constexpr std::size_t relaxation_patience = 5000;
constexpr double newton_step_cap = 0.25;
constexpr double min_damping = 1.0e-3;
constexpr double newton_regularization = 1.0e-9;
constexpr std::size_t max_open_close = 20;
constexpr double part_force_fraction = 0.1;
// The stability probe (unstable_blocks): its power iterations, the largest move of a probe (of
// the smallest inradius), the growth that marks a mode unstable, and the share of the mode's
// largest move that names a block in it.
constexpr std::size_t probe_iterations = 12;
constexpr double probe_move = 1.0e-6;
constexpr double probe_growth = 1.02;
constexpr double probe_amplitude = 0.25;
constexpr double probe_damping = 1.0;
// Pairs apart by at most this fraction of the smaller perimeter count as resting on each other.
constexpr double resting_gap = 1.0e-6;

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

std::string block_name(const std::string& id) { return "block '" + id + "'"; }

double dot6(const Vector6& a, const Vector6& b) {
  double sum = 0.0;
  for (std::size_t k = 0; k < 6; ++k) sum += a[k] * b[k];
  return sum;
}

bool finite(double x) { return std::isfinite(x); }

// R A R^T for the symmetric A = [[a, q], [q, b]] and R the rotation by the angle (cos c, sin s).
std::array<double, 3> rotate_tensor(double a, double b, double q, double c, double s) {
  return {c * c * a - 2.0 * c * s * q + s * s * b, s * s * a + 2.0 * c * s * q + c * c * b,
          c * s * (a - b) + (c * c - s * s) * q};
}

void check_params(const ContactLaw& law, const DdaParams& params) {
  if (!finite(params.dt) || !(params.dt > 0.0)) {
    throw std::invalid_argument("dda2d: dt must be finite and > 0 (s), got " + number(params.dt));
  }
  if (!finite(params.gravity.x) || !finite(params.gravity.y)) {
    throw std::invalid_argument("dda2d: gravity must be finite (m/s²)");
  }
  if (params.threads > 1024) {
    throw std::invalid_argument("dda2d: threads must be 0 (one per core) or at most 1024, got " +
                                std::to_string(params.threads));
  }
  if (!finite(params.mass_damping) || !(params.mass_damping >= 0.0)) {
    throw std::invalid_argument("dda2d: mass_damping must be finite and >= 0 (1/s), got " +
                                number(params.mass_damping));
  }
  contact::check_params(law.normal);  // kn, H, small_edge_fraction
  if (law.friction) contact::check_friction_law(*law.friction);
  if (!(params.equilibrium_tolerance > 0.0 && params.equilibrium_tolerance < 1.0)) {
    throw std::invalid_argument("dda2d: equilibrium_tolerance must be in (0, 1), got " +
                                number(params.equilibrium_tolerance));
  }
  if (!finite(law.damping_ratio) || !(law.damping_ratio >= 0.0)) {
    throw std::invalid_argument("dda2d: contact damping_ratio must be finite and >= 0, got " +
                                number(law.damping_ratio));
  }
  std::set<std::pair<std::string, std::string>> seen;
  for (const Interface& face : law.interfaces) {
    const std::string name = "dda2d: interface between groups '" + face.groups[0] + "' and '" +
                             face.groups[1] + "'";
    if (!finite(face.kn) || !(face.kn > 0.0)) {
      throw std::invalid_argument(name + ": kn must be finite and > 0 (Pa), got " + number(face.kn));
    }
    if (face.friction) contact::check_friction_law(*face.friction);
    const auto key = std::minmax(face.groups[0], face.groups[1]);
    if (!seen.emplace(key.first, key.second).second) {
      throw std::invalid_argument(name + " is given twice");
    }
  }
}

void check_spec(const BlockSpec& spec, std::set<std::string>& ids) {
  if (spec.id.empty()) throw std::invalid_argument("dda2d: a block has an empty id");
  const std::string name = block_name(spec.id);
  if (!ids.insert(spec.id).second) throw std::invalid_argument("dda2d: duplicate " + name);
  const Material& m = spec.material;
  if (!finite(m.density) || !(m.density > 0.0)) {
    throw std::invalid_argument("dda2d: " + name + ": density must be finite and > 0 (kg/m³), got " +
                                number(m.density));
  }
  if (!finite(m.youngs_modulus) || !(m.youngs_modulus > 0.0)) {
    throw std::invalid_argument("dda2d: " + name +
                                ": youngs_modulus must be finite and > 0 (Pa), got " +
                                number(m.youngs_modulus));
  }
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5)) {
    throw std::invalid_argument("dda2d: " + name + ": poisson_ratio must be in (-1, 0.5), got " +
                                number(m.poisson_ratio));
  }
  if (!finite(spec.velocity.x) || !finite(spec.velocity.y) || !finite(spec.omega)) {
    throw std::invalid_argument("dda2d: " + name + ": velocity and omega must be finite");
  }
  if (spec.fixed && (spec.velocity.x != 0.0 || spec.velocity.y != 0.0 || spec.omega != 0.0)) {
    throw std::invalid_argument("dda2d: " + name + ": a fixed block cannot have a velocity");
  }
}

// A block's convex parts (the block itself when it is convex): each part's vertices are
// outline vertices, by index, so the parts follow the outline's motion exactly.
struct Parts {
  std::vector<kernel::ConvexPolygon> polygons;   // current
  std::vector<std::vector<std::size_t>> corners;  // indices into BlockState::vertices
  std::vector<detail::BroadPhaseBox> boxes;       // current, m (only when there are several)
};

// The contact properties of one pair of groups (or the defaults).
struct PairLaw {
  contact::PotentialContactParams normal;
  std::optional<FrictionLaw> friction;
};

// Friction records are kept per pair of parts.
struct PartPair {
  std::size_t cp, tp, cp_part, tp_part;
  auto operator<=>(const PartPair&) const = default;
};

// A candidate pair of parts and what the parallel pass measured for it.
struct PartContact {
  PartPair parts;
  bool touching = false;  // overlap with a non-zero force
  Vector2 force;          // normal force on CP, N/m
  Point2 point;           // contact point, m
  double depth = 0.0;     // minimum translation distance, m
  std::size_t ip_size = 0;
  double area = 0.0;      // IP area, m²
  double length = 0.0;    // contact length L: half the IP's perimeter, m
};

// Scratch of one thread's pair evaluations.
struct PairScratch {
  contact::PairWorkspace workspace;
  contact::PairResult result;
  std::vector<PartPair> found;  // gather_candidates' finds
};

detail::BroadPhaseBox bounding_box(std::span<const Point2> vertices) {
  detail::BroadPhaseBox box;
  box.xmin = box.ymin = std::numeric_limits<double>::infinity();
  box.xmax = box.ymax = -std::numeric_limits<double>::infinity();
  for (const Point2& p : vertices) {
    box.xmin = std::min(box.xmin, p.x);
    box.xmax = std::max(box.xmax, p.x);
    box.ymin = std::min(box.ymin, p.y);
    box.ymax = std::max(box.ymax, p.y);
  }
  return box;
}

// Whether the interiors of two boxes intersect. A box is the exact extremes of its polygon's
// vertex coordinates (min and max do not round), so when the interiors of the boxes are disjoint
// those of the polygons are too: the kernel could only answer touch or separate, and the pair
// has no force. The grid's closed boxes pair up touching blocks, and the blocks of a jointed
// mass start in exact touch: at 10⁴ blocks (bench/dda_scale, step 40) this leaves 1 398 of the
// grid's 38 869 pairs to the kernel, 1 396 of them in contact.
bool interiors_overlap(const detail::BroadPhaseBox& a, const detail::BroadPhaseBox& b) {
  return a.xmin < b.xmax && b.xmin < a.xmax && a.ymin < b.ymax && b.ymin < a.ymax;
}

// What the engine keeps per block besides the public BlockState.
struct Body {
  explicit Body(Parts p) : parts(std::move(p)) {}

  Parts parts;
  std::size_t group = 0;  // index into the engine's group table
  Material material;
  Eigen::Matrix3d elasticity;   // E of eq. 5b, Pa
  Eigen::Matrix3d flexibility;  // E^-1, 1/Pa
  Point2 initial_centroid;      // m
  double inradius = 0.0;        // m, smallest over the parts, at the start (strains are small)
  double perimeter = 0.0;       // m, at the start
  double compliance = 0.0;      // largest point compliance, 1/kg (0 when fixed)
  double elastic_omega2 = 0.0;  // rad²/s², 0 unless deformable
  Eigen::Matrix4d rs_mass;      // (r0, ex, ey, gxy) block of M (deformable)
  Eigen::LLT<Eigen::Matrix4d> rs_factor;
  double inertia = 0.0;         // rigid: kg m²/m
  Vector6 force{};              // generalized force at the current instant
  Vector6 contact_force{};      // its contact part
  Vector6 dashpot_force{};      // the contact dashpots' part of contact_force
  Vector6 acceleration{};       // M^-1 force
  Vector6 increment{};          // Δd of the last step
};

}  // namespace

struct Dda2d::Impl {
  // `from`: resume that snapshot instead of starting (Dda2d's constructors).
  Impl(std::vector<BlockSpec> specs, ContactLaw contact_law, DdaParams dda_params,
       const Snapshot* from);

  void advance();
  void static_step();
  Energies energies() const;
  // A movable block's share of the energies, J/m: kinetic, gravitational (relative to its
  // start) and strain (zero when rigid).
  struct BlockEnergy {
    double kinetic = 0.0, gravitational = 0.0, strain = 0.0;
  };
  BlockEnergy block_energy(std::size_t i) const;
  template <class Share>
  Energies sum_energies(Share&& share) const;

  // Construction.
  void add_block(const BlockSpec& spec);
  void restore(const Snapshot& from);
  Snapshot snapshot() const;
  void rebuild_parts(std::size_t i);
  void estimate_critical_step();
  void settle();
  void start_static_analysis();
  struct Resting {
    std::vector<std::vector<std::size_t>> adjacent;  // per block, once per resting pair of parts
    std::vector<PartPair> parts;                     // in pair order
  };
  Resting resting_pairs() const;
  double reference_force(const std::vector<char>& moving) const;
  SettleRound newton(const std::vector<char>& moving, const Resting& resting);
  struct SettleState;
  struct BestState;
  void restore(const SettleState& saved, const std::vector<char>& moving);
  void keep_if_best(BestState& best) const;
  bool relax_to_tolerance(const std::vector<char>& moving, const Resting& resting, BestState& best);
  struct LinearModel;
  void build_model(const std::vector<char>& moving, const std::vector<PartPair>& resting, bool first,
                   LinearModel& model) const;
  void solve_model(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                   const LinearModel& model, double damping, Eigen::VectorXd& delta) const;
  bool factorize_model(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                       const LinearModel& model, double damping, Eigen::VectorXd& rhs) const;
  std::vector<std::size_t> unstable_blocks(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                                           const LinearModel& model);
  double farthest_move(std::size_t i, const Eigen::VectorXd& d, const std::vector<Eigen::Index>& offset) const;
  void set_increments(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                      const Eigen::VectorXd& d, double scale);
  void solve_open_close(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                        LinearModel& model, double damping, double force_tolerance,
                        Eigen::VectorXd& delta) const;
  void prepare_relaxation(std::vector<char> moving, const std::vector<std::vector<std::size_t>>& adjacent);
  void relax_once();
  void move_by_increments(const std::vector<char>& moving);
  double balance_ratio() const;
  double out_of_balance(const std::vector<char>& moving, double reference, std::size_t& worst) const;
  double gyration_squared(std::size_t i) const;
  double unbalanced_force(std::size_t i) const;
  // A block's unknowns in the pre-solve: (u0, v0, r0), and (ex, ey, gxy) when deformable.
  Eigen::Index unknowns_of(std::size_t i) const { return states[i].rigid ? 3 : 6; }
  // Geometry-dependent data after the vertices moved.
  void refresh(std::size_t i);
  // Forces and accelerations at the current instant.
  void evaluate_forces();
  void evaluate_contacts();
  const std::vector<BlockPair>& candidate_pairs();
  void gather_candidates(const std::vector<BlockPair>& list);
  void resolve_groups(const std::vector<BlockSpec>& specs);
  void measure_candidates();
  void measure(PartContact& c, PairScratch& mine) const;
  void record_contact(const PartContact& m);
  std::size_t carry_friction(const PartPair& parts);
  void count_worker(const kernel::PredicateCounters& before);
  void check_penetration(const PartContact& m);
  std::size_t law_index(std::size_t i, std::size_t j) const {
    return law_of_groups[bodies[i].group * group_count + bodies[j].group];
  }
  void apply_contact(const ContactState& c);
  void solve_acceleration(std::size_t i);
  // The step's parts.
  void first_half_kick(std::size_t i);
  void second_half_kick(std::size_t i);
  void advance_friction_records();
  // The map of a movable block's material points over the step: the point at p (current
  // position) moves by Δt + R (I + Δε) r - r, r = p - centroid, R the rotation by Δr0 whose
  // cosine and sine are taken once per block (once per vertex they were 5 % of a step's
  // instructions at 10⁴ blocks).
  struct StepMap {
    Vector6 d;
    Point2 centroid;
    double cos = 1.0, sin = 0.0;
    Vector2 operator()(Point2 p) const {
      const double rx = p.x - centroid.x, ry = p.y - centroid.y;
      const double sx = rx + d[3] * rx + 0.5 * d[5] * ry;
      const double sy = ry + 0.5 * d[5] * rx + d[4] * ry;
      return {d[0] + (cos * sx - sin * sy) - rx, d[1] + (sin * sx + cos * sy) - ry};
    }
  };
  StepMap step_map(std::size_t i) const;
  Vector2 point_increment(std::size_t i, Point2 p) const;
  Vector2 point_velocity(std::size_t i, Point2 p) const;
  void dashpot(ContactState& c, const PartContact& m) const;
  void move(std::size_t i);
  void check_block(std::size_t i);
  void check_energy();
  void share_work(std::size_t i);
  void add_work();
  template <class F>
  void for_each_movable(F&& body);
  double kinetic(std::size_t i, const std::array<double, 6>& v) const;
  std::string at_step() const;

  ContactLaw law;
  contact::PotentialContactMethod method;  // the policy, chosen once
  DdaParams params;
  std::vector<PairLaw> laws;              // laws[0]: the defaults; then one per interface
  std::vector<std::size_t> law_of_groups;  // groups² table of indices into laws
  std::size_t group_count = 0;
  std::vector<Body> bodies;
  std::vector<BlockState> states;
  std::vector<ContactState> contacts;
  // The friction records of the pairs of parts in contact at the last evaluation, in pair order
  // (the order the contacts are found in); friction_of[k] indexes that of contacts[k] (no_record
  // on a frictionless interface). An evaluation builds the next list in one walk along the
  // previous one (carry_friction): a pair still in contact keeps its record, a new one starts
  // in stick with d = 0, a pair no longer in contact loses its record. A flat list replaced a
  // map stamped and swept at every evaluation.
  struct FrictionRecord {
    PartPair parts;
    contact::FrictionState state;
  };
  static constexpr std::size_t no_record = static_cast<std::size_t>(-1);
  std::vector<FrictionRecord> friction;
  std::vector<FrictionRecord> previous_friction;  // the last evaluation's, while one runs
  std::size_t carried = 0;                        // walk position in previous_friction
  std::vector<std::size_t> friction_of;
  std::vector<double> contact_length;  // L of contacts[k] (PartContact::length), m
  std::vector<PartContact> candidates;
  std::vector<PairScratch> thread_scratch;  // one per thread
  int thread_count = 1;
  detail::VerletList broad_phase;
  std::vector<BlockPair> pairs;  // every pair, when there are few blocks
  std::vector<detail::BroadPhaseBox> boxes;  // per block, current
  // Per block, computed on the worker threads and summed in block order, so the sums are the
  // same numbers for any thread count: half the step's work against the contact forces and the
  // dashpots (share_work), the kinetic energy the mass damping took in the step (the kicks),
  // and the energies (check_block). Kept apart from the blocks, so that the serial sums read
  // contiguous memory; a fixed block's shares stay zero.
  struct StepShare {
    double contact_work = 0.0, dashpot_work = 0.0, damped = 0.0;  // J/m
  };
  std::vector<StepShare> step_shares;
  std::vector<BlockEnergy> energy_shares;
  std::vector<Point2> scratch;

  double time = 0.0;
  std::size_t steps = 0;
  double contact_work = 0.0;         // J/m, work done against contact forces
  double friction_dissipated = 0.0;  // J/m
  double damping_dissipated = 0.0;   // J/m, by the mass damping
  double dashpot_dissipated = 0.0;   // J/m, work done against the contact dashpots
  double initial_total = 0.0;        // J/m
  double initial_budget = 0.0;       // kinetic(0) + strain(0) + E_floor, J/m
  double max_gravitational = 0.0;    // max |gravitational| seen, J/m
  double critical = std::numeric_limits<double>::infinity();
  std::string critical_source;
  double max_penetration = 0.0;
  bool settling = false;  // inside settle(): tangential springs locked, no dashpots
  // Inside settle(): the blocks a round leaves out (without a static state, resting only on
  // those, or unsupported). They stay where they are, and their contacts have no friction: a
  // neighbour that settles slides along a block that will topple or slide away instead of
  // hanging on it.
  std::vector<char> released;
  // Inside settle(): the stability probe has run. It runs once: each round it ends starts the
  // Newton iterations again from the start, and on a mass with many such columns (a 100 x 100
  // grid) a probe in every round named more blocks each round, still in its third round after
  // 700 s.
  bool equilibrium_probed = false;
  Equilibrium equilibrium;
  // The dynamic relaxation of the pre-solve and of the static analysis (dda2d.hpp).
  struct Relaxation {
    std::vector<char> moving;       // the blocks it moves
    std::vector<double> mass_scale;  // M' / M per block
    std::vector<Vector6> velocity;  // fictitious, per unit step
    double reference = 0.0;         // F_ref of the out-of-balance ratio, N/m
    double kinetic = 0.0;           // fictitious kinetic energy after the last iteration
  } relaxation;
  kernel::PredicateCounters counters;
};

namespace {

// Adds the predicate work of its scope to a total, also when the scope throws.
class CountInto {
 public:
  explicit CountInto(kernel::PredicateCounters& total)
      : total_(total), before_(kernel::predicate_counters()) {}
  ~CountInto() { total_ += kernel::predicate_counters() - before_; }
  CountInto(const CountInto&) = delete;
  CountInto& operator=(const CountInto&) = delete;

 private:
  kernel::PredicateCounters& total_;
  kernel::PredicateCounters before_;
};

}  // namespace

Dda2d::Impl::Impl(std::vector<BlockSpec> specs, ContactLaw contact_law, DdaParams dda_params,
                  const Snapshot* from)
    : law(std::move(contact_law)), method(law.policy), params(dda_params) {
  check_params(law, params);
  thread_count = params.threads == 0 ? omp_get_max_threads() : static_cast<int>(params.threads);
  thread_scratch.resize(static_cast<std::size_t>(thread_count));
  if (specs.empty()) throw std::invalid_argument("dda2d: no blocks");
  std::set<std::string> ids;
  for (const BlockSpec& spec : specs) check_spec(spec, ids);
  bodies.reserve(specs.size());
  states.reserve(specs.size());
  for (const BlockSpec& spec : specs) add_block(spec);
  resolve_groups(specs);
  estimate_critical_step();
  if (from != nullptr) {
    restore(*from);
    return;
  }
  evaluate_forces();
  if (params.initial_equilibrium != InitialEquilibrium::off) settle();
  if (params.analysis == Analysis::static_equilibrium) start_static_analysis();
  const Energies e = energies();
  initial_total = e.total();
  double floor = 0.0;
  for (const BlockState& s : states) {
    if (!s.fixed) floor += 0.5 * s.mass * energy_floor_speed * energy_floor_speed;
  }
  initial_budget = e.kinetic + e.strain + floor;
}

// The convex parts of a block: itself when convex, else its exact convex partition.
Parts make_parts(const BlockSpec& spec) {
  const std::string name = block_name(spec.id);
  Parts parts;
  try {
    parts.polygons.push_back(kernel::ConvexPolygon::make(name, spec.vertices));
    std::vector<std::size_t>& all = parts.corners.emplace_back(spec.vertices.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
    return parts;
  } catch (const kernel::InvalidPolygon& e) {
    if (e.reason() != kernel::InvalidPolygon::Reason::not_convex) throw;
  }
  std::vector<std::vector<Point2>> pieces;
  try {
    pieces = kernel::convex_partition(spec.vertices);
  } catch (const kernel::InvalidCut& e) {
    throw std::invalid_argument("dda2d: " + name + " is neither convex nor a simple CCW polygon: " +
                                e.what());
  }
  std::map<std::pair<double, double>, std::size_t> index;
  for (std::size_t k = 0; k < spec.vertices.size(); ++k) {
    index.emplace(std::pair{spec.vertices[k].x, spec.vertices[k].y}, k);
  }
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    std::vector<std::size_t>& corners = parts.corners.emplace_back();
    for (const Point2& v : pieces[p]) corners.push_back(index.at({v.x, v.y}));
    parts.polygons.push_back(
        kernel::ConvexPolygon::make(name + " part " + std::to_string(p), pieces[p]));
  }
  parts.boxes.resize(pieces.size());
  return parts;
}

void Dda2d::Impl::add_block(const BlockSpec& spec) {
  Body& b = bodies.emplace_back(make_parts(spec));
  BlockState& s = states.emplace_back();
  s.id = spec.id;
  s.vertices = spec.vertices;
  s.fixed = spec.fixed;
  s.rigid = spec.rigid;
  if (!spec.fixed) s.velocity = {spec.velocity.x, spec.velocity.y, spec.omega, 0.0, 0.0, 0.0};
  const detail::CentralMoments m = detail::central_moments(s.vertices, scratch);
  s.mass = spec.material.density * m.area;
  b.material = spec.material;
  b.elasticity = detail::elasticity_matrix(spec.material, params.plane);
  b.flexibility = b.elasticity.inverse();
  b.initial_centroid = m.centroid;
  b.inradius = std::numeric_limits<double>::infinity();
  for (const kernel::ConvexPolygon& part : b.parts.polygons) {
    b.inradius = std::min(b.inradius, kernel::inscribed_radius(part.vertices()));
  }
  b.perimeter = detail::perimeter(s.vertices);
  boxes.emplace_back();
  step_shares.emplace_back();
  energy_shares.emplace_back();
  if (!spec.fixed) {
    b.compliance = detail::max_vertex_compliance(s.vertices, m, s.mass, spec.rigid);
    if (!spec.rigid) b.elastic_omega2 = detail::elastic_omega_squared(m, s.mass, b.elasticity);
  }
  refresh(bodies.size() - 1);
}

// laws[0] is the scene default; each interface adds one law and fills the groups² table.
void Dda2d::Impl::resolve_groups(const std::vector<BlockSpec>& specs) {
  std::map<std::string, std::size_t, std::less<>> groups;
  const auto group_index = [&](const std::string& g) {
    return groups.emplace(g, groups.size()).first->second;
  };
  for (std::size_t i = 0; i < specs.size(); ++i) bodies[i].group = group_index(specs[i].group);
  for (const Interface& face : law.interfaces) {
    group_index(face.groups[0]);
    group_index(face.groups[1]);
  }
  group_count = groups.size();
  laws.assign(1, PairLaw{law.normal, law.friction});
  law_of_groups.assign(group_count * group_count, 0);
  for (const Interface& face : law.interfaces) {
    PairLaw& l = laws.emplace_back(PairLaw{law.normal, face.friction});
    l.normal.kn = face.kn;
    const std::size_t a = group_index(face.groups[0]), b = group_index(face.groups[1]);
    law_of_groups[a * group_count + b] = law_of_groups[b * group_count + a] = laws.size() - 1;
  }
}

void Dda2d::Impl::estimate_critical_step() {
  // The O(n) pair bound of dda2d.hpp, with the stiffest of all laws.
  double kn = 0.0, kt = 0.0;
  for (const PairLaw& l : laws) {
    kn = std::max(kn, l.normal.kn);
    if (l.friction) kt = std::max(kt, l.friction->kt);
  }
  const double kn_per_length = kn / law.normal.H;
  const auto movable = static_cast<std::size_t>(
      std::count_if(states.begin(), states.end(), [](const BlockState& s) { return !s.fixed; }));
  const bool any_fixed = movable < states.size();
  const double partners = movable >= 2 ? 2.0 : (any_fixed ? 1.0 : 0.0);
  // Per block, the elastic and the contact bound add: both stiffnesses act on the same degrees
  // of freedom (a block squeezed on all faces dilates against both), and the largest eigenvalue
  // of M^-1 (Ke + Kc) is at most the sum of those of M^-1 Ke and M^-1 Kc (Weyl). Taking the
  // larger of the two alone overestimated the step by up to sqrt(2) when they are equal.
  double worst = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& b = bodies[i];
    const double contact_w2 = partners * (kn_per_length * b.perimeter + kt) * b.compliance;
    const double w2 = b.elastic_omega2 + contact_w2;
    if (w2 <= worst) continue;
    worst = w2;
    const Material& m = b.material;
    const std::string elastic = "elastic stiffness (E = " + number(m.youngs_modulus) +
                                " Pa, nu = " + number(m.poisson_ratio) + ", mass " +
                                number(states[i].mass) + " kg/m)";
    const std::string contact_bound =
        "contacts (kn/H P + kt = " + number(kn_per_length * b.perimeter + kt) +
        " N/m with P = " + number(b.perimeter) + " m its perimeter, point compliance " +
        number(b.compliance) + " 1/kg" +
        (partners == 2.0 ? ", doubled for a partner as compliant" : "") + ")";
    critical_source = block_name(states[i].id) + ": " +
                      (b.elastic_omega2 == 0.0 ? contact_bound
                       : contact_w2 == 0.0     ? elastic
                                               : elastic + " plus its " + contact_bound);
  }
  if (worst == 0.0) return;
  critical = 2.0 / std::sqrt(worst);
  if (law.damping_ratio > 0.0) {
    const double zeta = law.damping_ratio;
    critical *= std::sqrt(1.0 + zeta * zeta) - zeta;
    critical_source += ", with contact dashpots of damping ratio " + number(zeta);
  }
  if (params.dt > critical) {
    throw StabilityError("dda2d: dt = " + number(params.dt) + " s is above the critical time step " +
                         number(critical) + " s (2 / omega_max, omega_max = " +
                         number(std::sqrt(worst)) + " rad/s) set by the " + critical_source +
                         "; use dt <= " + number(critical) + " s");
  }
}

void Dda2d::Impl::refresh(std::size_t i) {
  Body& b = bodies[i];
  BlockState& s = states[i];
  thread_local std::vector<Point2> shifted;  // refresh runs on the worker threads
  const detail::CentralMoments m = detail::central_moments(s.vertices, shifted);
  s.area = m.area;
  s.centroid = m.centroid;
  if (s.rigid) {
    b.inertia = detail::rotational_inertia(m, s.mass);
  } else {
    b.rs_mass = detail::rotation_strain_mass(m, s.mass);
    b.rs_factor.compute(b.rs_mass);
  }
  boxes[i] = bounding_box(s.vertices);
  boxes[i].fixed = s.fixed;
  for (std::size_t p = 0; p < b.parts.boxes.size(); ++p) {
    b.parts.boxes[p] = bounding_box(b.parts.polygons[p].vertices());
  }
}

std::string Dda2d::Impl::at_step() const {
  return "dda2d: step " + std::to_string(steps) + " (t = " + number(time) + " s): ";
}

// ---- forces ------------------------------------------------------------------------------

// A fixed block's forces stay zero: contacts apply nothing to it.
void Dda2d::Impl::evaluate_forces() {
  for_each_movable([this](std::size_t i) {
    bodies[i].contact_force = {};
    bodies[i].dashpot_force = {};
  });
  evaluate_contacts();
  for_each_movable([this](std::size_t i) {
    Body& b = bodies[i];
    const BlockState& s = states[i];
    b.force = {};
    b.force[0] = s.mass * params.gravity.x;
    b.force[1] = s.mass * params.gravity.y;
    if (!s.rigid) {
      for (std::size_t k = 0; k < 3; ++k) b.force[3 + k] = -s.area * s.stress[k];
    }
    for (std::size_t k = 0; k < 6; ++k) b.force[k] += b.contact_force[k];
    solve_acceleration(i);
  });
}


// The pairs of blocks whose boxes may overlap, in (i, j) order.
const std::vector<BlockPair>& Dda2d::Impl::candidate_pairs() {
  if (bodies.size() <= broad_phase_threshold) {
    if (pairs.empty()) detail::all_pairs(boxes, pairs);  // every pair, fixed once
    return pairs;
  }
  broad_phase.update(boxes);
  return broad_phase.pairs();
}

void Dda2d::Impl::evaluate_contacts() {
  gather_candidates(candidate_pairs());
  measure_candidates();
  contacts.clear();
  friction_of.clear();
  contact_length.clear();
  friction.swap(previous_friction);
  friction.clear();
  carried = 0;
  for (const PartContact& c : candidates) {
    if (c.touching) record_contact(c);
  }
}

// The pairs of parts of the listed pairs of blocks whose boxes' interiors overlap, in pair
// order, as `candidates`. Each thread filters one contiguous run of the list, the k-th run on
// the k-th thread, and the runs' finds are joined in that order: the same candidates for any
// thread count. (Serial, the filter was 5 % of a step at 10⁴ blocks: ~39 000 pairs.)
void Dda2d::Impl::gather_candidates(const std::vector<BlockPair>& list) {
  const auto count = static_cast<std::ptrdiff_t>(list.size());
  const int threads = count >= parallel_threshold ? thread_count : 1;
  for (PairScratch& mine : thread_scratch) mine.found.clear();
#pragma omp parallel num_threads(threads)
  {
    const std::ptrdiff_t me = omp_get_thread_num(), team = omp_get_num_threads();
    std::vector<PartPair>& found = thread_scratch[static_cast<std::size_t>(me)].found;
    for (std::ptrdiff_t k = count * me / team; k < count * (me + 1) / team; ++k) {
      const auto [i, j] = list[static_cast<std::size_t>(k)];
      const Parts& a = bodies[i].parts;
      const Parts& b = bodies[j].parts;
      for (std::size_t p = 0; p < a.polygons.size(); ++p) {
        for (std::size_t q = 0; q < b.polygons.size(); ++q) {
          if (interiors_overlap(a.boxes.empty() ? boxes[i] : a.boxes[p],
                                b.boxes.empty() ? boxes[j] : b.boxes[q])) {
            found.push_back({i, j, p, q});
          }
        }
      }
    }
  }
  candidates.clear();
  for (const PairScratch& mine : thread_scratch) {
    for (const PartPair& parts : mine.found) candidates.emplace_back().parts = parts;
  }
}

// The index in `friction` of the record of `parts` for this evaluation: the previous
// evaluation's record when the pair was in contact then, else a fresh one (stick, d = 0). The
// pairs come in increasing order, so one forward walk over the previous records finds them.
std::size_t Dda2d::Impl::carry_friction(const PartPair& parts) {
  assert(friction.empty() || friction.back().parts < parts);
  while (carried < previous_friction.size() && previous_friction[carried].parts < parts) ++carried;
  FrictionRecord& record = friction.emplace_back(FrictionRecord{parts, {}});
  if (carried < previous_friction.size() && previous_friction[carried].parts == parts) {
    record.state = previous_friction[carried].state;
  }
  return friction.size() - 1;
}

// The geometric work of every candidate (the IP, the normal force and the penetration depth),
// spread over the threads; each candidate is independent and its result stored in place, so the
// serial pass that follows sees the same numbers in the same order for any thread count.
// Predicate counters are thread-local: the workers' share is added to `counters` here, the
// calling thread's by the CountInto of step().
void Dda2d::Impl::measure_candidates() {
  const auto count = static_cast<std::ptrdiff_t>(candidates.size());
  const int threads = count >= parallel_threshold ? thread_count : 1;
#pragma omp parallel num_threads(threads)
  {
    const int me = omp_get_thread_num();
    PairScratch& mine = thread_scratch[static_cast<std::size_t>(me)];
    const kernel::PredicateCounters before = kernel::predicate_counters();
#pragma omp for schedule(dynamic, 64)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      measure(candidates[static_cast<std::size_t>(k)], mine);
    }
    count_worker(before);
  }
}

// Inside a parallel region: adds what a worker thread spent on predicates since `before` to the
// simulation's counters (the calling thread's share is counted by the CountInto around it), so
// the counts do not depend on the thread count either.
void Dda2d::Impl::count_worker(const kernel::PredicateCounters& before) {
  if (omp_get_thread_num() == 0) return;
  const kernel::PredicateCounters spent = kernel::predicate_counters() - before;
#pragma omp critical(rockcontact_dda2d_counters)
  counters += spent;
}

void Dda2d::Impl::measure(PartContact& c, PairScratch& mine) const {
  const auto [i, j, p, q] = c.parts;
  const kernel::ConvexPolygon& cp = bodies[i].parts.polygons[p];
  const kernel::ConvexPolygon& tp = bodies[j].parts.polygons[q];
  contact::PairResult& r = mine.result;
  method.evaluate(cp, tp, laws[law_index(i, j)].normal, mine.workspace, r);
  c.touching = r.status == kernel::Overlap::overlap && r.point.has_value();
  if (!c.touching) return;
  c.force = r.force;
  c.point = *r.point;
  c.ip_size = r.ip.size();
  c.area = r.area;
  c.length = 0.5 * detail::perimeter(r.ip);
  c.depth = contact::PotentialContactMethod::penetration_depth(cp, tp);
}

// A measured contact: checked, given its friction force and applied to both blocks.
void Dda2d::Impl::record_contact(const PartContact& m) {
  const auto [i, j, p, q] = m.parts;
  if (!finite(m.force.x) || !finite(m.force.y) || !finite(m.point.x) || !finite(m.point.y)) {
    throw StabilityError(at_step() + "the contact of " + block_name(states[i].id) + " with " +
                         block_name(states[j].id) + " gave a non-finite force or contact point " +
                         "(IP of " + std::to_string(m.ip_size) + " vertices, area " +
                         number(m.area) + " m²)");
  }
  check_penetration(m);
  ContactState c;
  c.cp = i;
  c.tp = j;
  c.cp_part = p;
  c.tp_part = q;
  c.point = m.point;
  c.normal_force = m.force;
  c.penetration = m.depth;
  std::size_t record = no_record;
  const std::optional<FrictionLaw>& friction_law = laws[law_index(i, j)].friction;
  if (friction_law && !(settling && (released[i] || released[j]))) {
    record = carry_friction(m.parts);
    contact::FrictionState& state = friction[record].state;
    const contact::FrictionResult r = contact::evaluate_friction(
        state, c.normal_force, *friction_law, m.length,
        settling ? contact::Slip::locked : contact::Slip::allowed);
    contact::commit_friction(state, r);
    c.friction_force = r.force;
    c.sliding = r.sliding;
    friction_dissipated += r.dissipated;
  } else {
    c.sliding = true;  // the Coulomb limit of a frictionless interface is zero
  }
  if (law.damping_ratio > 0.0 && !settling) dashpot(c, m);
  apply_contact(c);
  contacts.push_back(c);
  friction_of.push_back(record);
  contact_length.push_back(m.length);
}

void Dda2d::Impl::check_penetration(const PartContact& m) {
  const auto [i, j, p, q] = m.parts;
  max_penetration = std::max(max_penetration, m.depth);
  const double limit = penetration_fraction * std::min(bodies[i].inradius, bodies[j].inradius);
  if (m.depth > limit && steps == 0 && !settling) {
    throw std::invalid_argument(
        "dda2d: " + block_name(states[i].id) + " and " + block_name(states[j].id) + " overlap by " +
        number(m.depth) + " m at the start (minimum translation distance), more than half the "
        "smaller inradius (" + number(limit) + " m): the starting geometry overlaps beyond what "
        "the contact can push apart; move the blocks apart (blocks resting on each other may "
        "overlap by a small fraction of their size)");
  }
  if (m.depth > limit) {
    throw StabilityError(at_step() + block_name(states[i].id) + " and " + block_name(states[j].id) +
                         " overlap by " + number(m.depth) +
                         " m (minimum translation distance), more than half the smaller inradius (" +
                         number(limit) + " m): the contact no longer holds them apart; kn = " +
                         number(laws[law_index(i, j)].normal.kn) +
                         " Pa is too soft for the load, or the blocks move too far in one step of " +
                         "dt = " + number(params.dt) + " s");
  }
}

// The dashpot force and moment on CP (dda2d.hpp, "Contact damping") at the current instant.
void Dda2d::Impl::dashpot(ContactState& c, const PartContact& m) const {
  const double fn = std::hypot(c.normal_force.x, c.normal_force.y);
  if (!(fn > 0.0)) return;
  const Vector2 n{c.normal_force.x / fn, c.normal_force.y / fn};
  const Vector2 a = point_velocity(c.cp, c.point), b = point_velocity(c.tp, c.point);
  const Vector2 v{a.x - b.x, a.y - b.y};
  const double mi = states[c.cp].fixed ? 0.0 : states[c.cp].mass;
  const double mj = states[c.tp].fixed ? 0.0 : states[c.tp].mass;
  const double reduced = mi == 0.0 ? mj : mj == 0.0 ? mi : mi * mj / (mi + mj);
  const PairLaw& pair = laws[law_index(c.cp, c.tp)];
  const double kn = 2.0 * pair.normal.kn * m.length / pair.normal.H;
  const double cn = 2.0 * law.damping_ratio * std::sqrt(reduced * kn);
  const double along = v.x * n.x + v.y * n.y;
  Vector2 f{-cn * along * n.x, -cn * along * n.y};
  if (pair.friction && !c.sliding) {
    const double ct = 2.0 * law.damping_ratio * std::sqrt(reduced * pair.friction->kt);
    f.x -= ct * (v.x - along * n.x);
    f.y -= ct * (v.y - along * n.y);
  }
  c.damping_force = f;
  const double spin = (states[c.cp].fixed ? 0.0 : states[c.cp].velocity[2]) -
                      (states[c.tp].fixed ? 0.0 : states[c.tp].velocity[2]);
  c.damping_moment = -cn * m.length * m.length / 12.0 * spin;
}

void Dda2d::Impl::apply_contact(const ContactState& c) {
  const Vector2 f{c.normal_force.x + c.friction_force.x + c.damping_force.x,
                  c.normal_force.y + c.friction_force.y + c.damping_force.y};
  const auto add = [&](std::size_t i, double sign) {
    if (states[i].fixed) return;
    const Point2& o = states[i].centroid;
    const Vector2 r{c.point.x - o.x, c.point.y - o.y};
    const Vector6 g = detail::transform_transpose(r, f);
    for (std::size_t k = 0; k < 6; ++k) bodies[i].contact_force[k] += sign * g[k];
    if (c.damping_force.x == 0.0 && c.damping_force.y == 0.0 && c.damping_moment == 0.0) return;
    Vector6 d = detail::transform_transpose(r, c.damping_force);
    d[2] += c.damping_moment;
    bodies[i].contact_force[2] += sign * c.damping_moment;
    for (std::size_t k = 0; k < 6; ++k) bodies[i].dashpot_force[k] += sign * d[k];
  };
  add(c.cp, 1.0);
  add(c.tp, -1.0);
}

void Dda2d::Impl::solve_acceleration(std::size_t i) {
  Body& b = bodies[i];
  const BlockState& s = states[i];
  b.acceleration = {b.force[0] / s.mass, b.force[1] / s.mass, 0.0, 0.0, 0.0, 0.0};
  if (s.rigid) {
    b.acceleration[2] = b.force[2] / b.inertia;
    return;
  }
  const Eigen::Vector4d rhs(b.force[2], b.force[3], b.force[4], b.force[5]);
  const Eigen::Vector4d a = b.rs_factor.solve(rhs);
  for (std::size_t k = 0; k < 4; ++k) b.acceleration[2 + k] = a(static_cast<Eigen::Index>(k));
}

// ---- initial equilibrium (dda2d.hpp) -----------------------------------------------------

double Dda2d::Impl::gyration_squared(std::size_t i) const {
  const double inertia = states[i].rigid ? bodies[i].inertia : bodies[i].rs_mass(0, 0);
  return inertia / states[i].mass;
}

// |F_i| of the out-of-balance ratio (dda2d.hpp), N/m.
double Dda2d::Impl::unbalanced_force(std::size_t i) const {
  const Vector6& f = bodies[i].force;
  double moments = f[2] * f[2];
  if (!states[i].rigid) moments += f[3] * f[3] + f[4] * f[4] + f[5] * f[5];
  return std::sqrt(f[0] * f[0] + f[1] * f[1] + moments / gyration_squared(i));
}

// max_i |F_i| / reference over the blocks marked in `moving`; `worst` is the block of the max.
double Dda2d::Impl::out_of_balance(const std::vector<char>& moving, double reference,
                                   std::size_t& worst) const {
  double most = 0.0;
  worst = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!moving[i]) continue;
    const double size = unbalanced_force(i);
    if (size > most) {
      most = size;
      worst = i;
    }
  }
  return most / reference;
}

// The pairs of blocks resting on each other at the start: overlapping, touching, or apart by at
// most resting_gap of the smaller perimeter (coordinates typed or computed to ~7 digits put a
// block "on" a slope within that), as adjacency lists with a block's neighbour listed once per
// resting pair of their parts.
Dda2d::Impl::Resting Dda2d::Impl::resting_pairs() const {
  const std::size_t n = bodies.size();
  std::vector<detail::BroadPhaseBox> inflated(n);
  for (std::size_t i = 0; i < n; ++i) {
    detail::BroadPhaseBox box = bounding_box(states[i].vertices);
    const double margin = resting_gap * bodies[i].perimeter;
    box.xmin -= margin;
    box.ymin -= margin;
    box.xmax += margin;
    box.ymax += margin;
    box.fixed = states[i].fixed;
    inflated[i] = box;
  }
  std::vector<BlockPair> near;
  if (n <= broad_phase_threshold) {
    detail::all_pairs(inflated, near);
  } else {
    detail::UniformGrid().find_pairs(inflated, near);
  }
  std::sort(near.begin(), near.end());
  Resting resting;
  resting.adjacent.resize(n);
  for (const auto& [i, j] : near) {
    const double gap = resting_gap * std::min(bodies[i].perimeter, bodies[j].perimeter);
    const std::vector<kernel::ConvexPolygon>& a = bodies[i].parts.polygons;
    const std::vector<kernel::ConvexPolygon>& b = bodies[j].parts.polygons;
    for (std::size_t p = 0; p < a.size(); ++p) {
      for (std::size_t q = 0; q < b.size(); ++q) {
        if (contact::PotentialContactMethod::separation(a[p], b[q]) > gap) continue;
        resting.adjacent[i].push_back(j);  // once per resting pair of parts
        resting.adjacent[j].push_back(i);
        resting.parts.push_back({i, j, p, q});
      }
    }
  }
  return resting;
}

// F_ref of the out-of-balance ratio over the blocks in `moving`: the largest weight or normal
// contact force among them (zero: nothing loads them).
double Dda2d::Impl::reference_force(const std::vector<char>& moving) const {
  double reference = 0.0;
  const double g = std::hypot(params.gravity.x, params.gravity.y);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (moving[i]) reference = std::max(reference, states[i].mass * g);
  }
  for (const ContactState& c : contacts) {
    if (moving[c.cp] || moving[c.tp]) {
      reference = std::max(reference, std::hypot(c.normal_force.x, c.normal_force.y));
    }
  }
  return reference;
}

// Relaxation of the blocks in `moving` with h = 1: M' = (omega_i / relaxation_omega_h)² M keeps
// every block at omega' h = relaxation_omega_h, with omega_i² bounding the block's row of M^-1 K
// over all the contacts it can have (Gershgorin: its own stiffness and, as much again, its
// neighbours' coupling): the normal springs of all its contacts lie along its boundary, kn / H
// times at most twice its perimeter (both faces of each thin overlap); each resting pair of
// parts adds one tangential spring. The critical-step estimate's single-pair bound is not
// enough in a packed assembly. The reference force is the largest weight or normal contact
// force among them (zero: nothing loads them).
void Dda2d::Impl::prepare_relaxation(std::vector<char> moving,
                                     const std::vector<std::vector<std::size_t>>& adjacent) {
  const std::size_t n = bodies.size();
  relaxation.moving = std::move(moving);
  relaxation.velocity.assign(n, Vector6{});
  relaxation.mass_scale.assign(n, 0.0);
  relaxation.reference = reference_force(relaxation.moving);
  double kn = 0.0, kt = 0.0;
  for (const PairLaw& l : laws) {
    kn = std::max(kn, l.normal.kn);
    if (l.friction) kt = std::max(kt, l.friction->kt);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!relaxation.moving[i]) continue;
    const Body& b = bodies[i];
    const double springs = 2.0 * kn / law.normal.H * b.perimeter +
                           static_cast<double>(adjacent[i].size()) * kt;
    const double omega2 = b.elastic_omega2 + 2.0 * b.compliance * springs;
    relaxation.mass_scale[i] = omega2 / (relaxation_omega_h * relaxation_omega_h);
  }
}

// One relaxation iteration under kinetic damping: a kick of the scaled masses by the
// out-of-balance forces; when the assembly's fictitious kinetic energy falls, it has just passed
// a minimum of the potential energy along its path, so every velocity is zeroed there and the
// motion starts again from rest (no move in that iteration). Otherwise the move and the forces
// at the new configuration.
void Dda2d::Impl::relax_once() {
  for (Body& b : bodies) b.increment = {};
  for_each_movable([&](std::size_t i) {
    if (!relaxation.moving[i]) return;
    Vector6& velocity = relaxation.velocity[i];
    for (std::size_t k = 0; k < 6; ++k) {
      velocity[k] += bodies[i].acceleration[k] / relaxation.mass_scale[i];
    }
  });
  double energy = 0.0;  // summed in block order: the same for any thread count
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (relaxation.moving[i]) energy += relaxation.mass_scale[i] * kinetic(i, relaxation.velocity[i]);
  }
  if (energy < relaxation.kinetic) {
    std::fill(relaxation.velocity.begin(), relaxation.velocity.end(), Vector6{});
    relaxation.kinetic = 0.0;
    return;
  }
  relaxation.kinetic = energy;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (relaxation.moving[i]) bodies[i].increment = relaxation.velocity[i];
  }
  move_by_increments(relaxation.moving);
}

// The pre-solve's move: the blocks in `moving` by their increments, their springs with them,
// and the forces there.
void Dda2d::Impl::move_by_increments(const std::vector<char>& moving) {
  advance_friction_records();
  for_each_movable([&](std::size_t i) {
    if (moving[i]) move(i);
  });
  evaluate_forces();
}

// The pre-solve's state: positions, stresses and springs.
struct Dda2d::Impl::SettleState {
  std::vector<BlockState> states;
  std::vector<FrictionRecord> friction;
};

// Back to `saved`: the blocks in `moving` (the others have not moved since), the springs,
// and the forces there.
void Dda2d::Impl::restore(const SettleState& saved, const std::vector<char>& moving) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i].increment = {};
    if (!moving[i]) continue;
    states[i] = saved.states[i];
    rebuild_parts(i);
    refresh(i);
  }
  friction = saved.friction;
  evaluate_forces();
}

// The pre-solve (dda2d.hpp, "Initial equilibrium"): rounds of Newton's method over the blocks
// resting on a support (dynamics/common/equilibrium.hpp); then the release.
void Dda2d::Impl::settle() {
  const WallTimer timer(equilibrium.seconds);
  const Resting resting = resting_pairs();
  std::vector<char> fixed(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) fixed[i] = states[i].fixed;
  settling = true;
  const SettleState start{states, friction};
  const std::vector<std::size_t> unsettled = settle_in_rounds<StabilityError>(
      params.initial_equilibrium, resting.adjacent, fixed, [&](const std::vector<char>& moving) {
        released.assign(bodies.size(), 0);
        for (std::size_t i = 0; i < bodies.size(); ++i) released[i] = !fixed[i] && !moving[i];
        evaluate_forces();
        SettleRound round = newton(moving, resting);
        if (!round.unsettled.empty()) restore(start, moving);  // back to the start for the next round
        return round;
      });
  settling = false;
  for (const std::size_t i : unsettled) equilibrium.unsettled.push_back(states[i].id);
  if (equilibrium.blocks == 0) equilibrium.converged = true;  // nothing left to settle
  for (Body& b : bodies) b.increment = {};
  // Released: the forces under the real friction law, and the energies counted from here.
  evaluate_forces();
  contact_work = friction_dissipated = damping_dissipated = dashpot_dissipated = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) bodies[i].initial_centroid = states[i].centroid;
}

// The linear model of one Newton iteration (dda2d.hpp): the contact line of every pair of parts
// that is closed or may close (contact_springs.hpp), and where along it the gap is closed, now
// (`now`) and in the open-close iteration's latest solution (`part`). A pair that overlaps has
// its measured contact (`contact`, an index into `contacts`) and, in stick, its friction spring.
struct Dda2d::Impl::LinearModel {
  struct Line {
    std::size_t cp = 0, tp = 0;
    std::size_t contact = no_record;
    contact::ContactLine geometry;
    double kn = 0.0, H = 1.0;
    contact::Interval now, part;
    double kt = 0.0;  // the locked friction spring, along the tangent (0: frictionless)
  };
  std::vector<Line> lines;
  // Assembly scratch, kept between solves: the stiffness's blocks, the solver's block of each
  // body (-1: none) and the unknowns of each solver block.
  mutable std::vector<BlockCholesky<6>::Term> terms;
  mutable std::vector<int> block, sizes;
  mutable BlockCholesky<6> solver;  // K's factor, its analysis kept while the lines stay
};

// The lines of the model at the current configuration: the pairs resting at the start and the
// candidates of the last contact pass (their boxes overlap), with a contact line within a step's
// reach.
void Dda2d::Impl::build_model(const std::vector<char>& moving, const std::vector<PartPair>& resting,
                              bool first, LinearModel& model) const {
  model.lines.clear();
  std::vector<std::pair<PartPair, std::size_t>> near;  // with the measured contact, if any
  std::size_t k = 0;
  for (const PartContact& c : candidates) near.emplace_back(c.parts, c.touching ? k++ : no_record);
  for (const PartPair& parts : resting) near.emplace_back(parts, no_record);
  std::sort(near.begin(), near.end());
  for (std::size_t n = 0; n < near.size(); ++n) {
    if (n > 0 && near[n].first == near[n - 1].first) continue;  // the measured one comes first
    const auto [i, j, p, q] = near[n].first;
    if (!moving[i] && !moving[j]) continue;
    const double reach = newton_step_cap * (bodies[i].inradius + bodies[j].inradius);
    const std::optional<contact::ContactLine> geometry =
        contact::contact_line(bodies[i].parts.polygons[p], bodies[j].parts.polygons[q], reach);
    if (!geometry) continue;
    const PairLaw& pair = laws[law_index(i, j)];
    LinearModel::Line& line = model.lines.emplace_back();
    line.cp = i;
    line.tp = j;
    line.contact = near[n].second;
    line.geometry = *geometry;
    line.kn = pair.normal.kn;
    line.H = pair.normal.H;
    // Every closed pair has its locked friction spring: a loaded one's is in F with its
    // stretch, a pair in touch starts one at its first overlap (as Table 1 of seed 001 starts a
    // new contact locked).
    if (pair.friction && !released[i] && !released[j]) line.kt = pair.friction->kt;
    // The open-close iteration starts from the parts that overlap, and in a round's first
    // iteration also from those that touch (to resting_gap): from the parts that overlap alone,
    // a column of blocks in touch would close one joint per solve. Later iterations start from
    // the overlaps the last step left: a pair within a touch of each other but apart is then
    // mostly one the last solve opened, and closing it again cost every iteration of a 150 x 30
    // mass four solves to reopen ~850 of them (docs/performance.md).
    const double touch = first ? resting_gap * std::min(bodies[i].perimeter, bodies[j].perimeter) : 0.0;
    line.now = contact::closed_part(line.geometry);
    line.part = contact::closed_part(line.geometry, -touch, -touch);
  }
}

namespace {

// T^T direction of block b's point `at` (its generalized force per unit force along direction).
Vector6 generalized(const BlockState& b, Point2 at, Vector2 direction) {
  return detail::transform_transpose({at.x - b.centroid.x, at.y - b.centroid.y}, direction);
}

}  // namespace

// Solves the model for Δd with the closed parts as they stand (dda2d.hpp):
//   (K + damping diag K) Δd = F + Σ_part k (-g) G - Σ_now k (-g) G - (friction of a loaded pair
//   the model opens),
// F the engine's out-of-balance forces, K the blocks' S E, the Gauss springs of each line's
// closed part and the friction springs of the loaded pairs still closed, plus the
// regularisation. offset[i]: block i's first unknown (-1: not one).
void Dda2d::Impl::solve_model(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                              const LinearModel& model, double damping, Eigen::VectorXd& delta) const {
  Eigen::VectorXd rhs(delta.size());
  const bool factored = factorize_model(moving, offset, model, damping, rhs);
  if (factored) delta = model.solver.solve(rhs);
  if (!factored || !delta.allFinite()) {
    throw StabilityError("dda2d: the initial equilibrium's stiffness could not be solved (" +
                         std::to_string(delta.size()) + " unknowns)");
  }
}

// Assembles K (with the damping) by blocks and F into rhs (solve_model), and factorises K into
// model.solver.
bool Dda2d::Impl::factorize_model(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                                  const LinearModel& model, double damping, Eigen::VectorXd& rhs) const {
  using Term = BlockCholesky<6>::Term;
  std::vector<Term>& terms = model.terms;
  std::vector<int>& block = model.block;
  std::vector<int>& sizes = model.sizes;
  terms.clear();
  sizes.clear();
  block.assign(bodies.size(), -1);
  double kn_scale = 0.0;
  for (const PairLaw& l : laws) kn_scale = std::max(kn_scale, l.normal.kn / l.normal.H);
  const auto dofs = [&](std::size_t b) { return unknowns_of(b); };
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!moving[i]) continue;
    block[i] = static_cast<int>(sizes.size());
    sizes.push_back(static_cast<int>(dofs(i)));
    const Eigen::Index o = offset[i];
    for (Eigen::Index k = 0; k < dofs(i); ++k) rhs(o + k) = bodies[i].force[static_cast<std::size_t>(k)];
    Term& t = terms.emplace_back(Term{block[i], block[i], Eigen::Matrix<double, 6, 6>::Zero()});
    const double k = newton_regularization * kn_scale * bodies[i].perimeter;
    const double arm2 = gyration_squared(i);
    for (Eigen::Index r = 0; r < dofs(i); ++r) t.value(r, r) = r < 2 ? k : k * arm2;
    if (!states[i].rigid) t.value.bottomRightCorner<3, 3>() += states[i].area * bodies[i].elasticity;
  }
  // A force f along `direction` at `at`, on CP (and -f on TP); a spring of stiffness k there.
  const auto add_force = [&](const LinearModel::Line& line, Point2 at, Vector2 direction, double f) {
    for (const std::size_t b : {line.cp, line.tp}) {
      if (!moving[b]) continue;
      const Vector6 g = generalized(states[b], at, direction);
      const double sign = b == line.cp ? f : -f;
      for (Eigen::Index k = 0; k < dofs(b); ++k) rhs(offset[b] + k) += sign * g[static_cast<std::size_t>(k)];
    }
  };
  // The springs of one line, summed over the unknowns of CP then TP before they go into the
  // matrix: k a a^T, a = (T_CP^T direction, -T_TP^T direction) at the spring's point.
  Eigen::Matrix<double, 12, 12> local;
  bool springs = false;
  const auto add_spring = [&](const LinearModel::Line& line, Point2 at, Vector2 direction, double k) {
    const Vector6 on_cp = generalized(states[line.cp], at, direction);
    const Vector6 on_tp = generalized(states[line.tp], at, direction);
    Eigen::Matrix<double, 12, 1> a;
    for (std::size_t r = 0; r < 6; ++r) {
      a(static_cast<Eigen::Index>(r)) = on_cp[r];
      a(static_cast<Eigen::Index>(r + 6)) = -on_tp[r];
    }
    local.noalias() += k * a * a.transpose();
    springs = true;
  };
  const auto add_line_springs = [&](const LinearModel::Line& line) {
    const bool cp = moving[line.cp] != 0, tp = moving[line.tp] != 0;
    if (cp) terms.push_back({block[line.cp], block[line.cp], local.topLeftCorner<6, 6>()});
    if (tp) terms.push_back({block[line.tp], block[line.tp], local.bottomRightCorner<6, 6>()});
    if (cp && tp) terms.push_back({block[line.cp], block[line.tp], local.topRightCorner<6, 6>()});
  };
  for (const LinearModel::Line& line : model.lines) {
    const Vector2 n = line.geometry.normal;
    local.setZero();
    springs = false;
    if (!line.part.empty()) {
      for (const contact::GaussSpring& s : contact::gauss_springs(line.geometry, line.part, line.kn, line.H)) {
        add_force(line, s.at, n, -s.k * s.gap);
        add_spring(line, s.at, n, s.k);
      }
    }
    if (!line.now.empty()) {
      for (const contact::GaussSpring& s : contact::gauss_springs(line.geometry, line.now, line.kn, line.H)) {
        add_force(line, s.at, n, s.k * s.gap);
      }
    }
    if (line.kt != 0.0 && line.contact == no_record) {
      if (!line.part.empty()) {
        const Point2 centre{0.5 * (line.geometry.from.x + line.geometry.to.x), 0.5 * (line.geometry.from.y + line.geometry.to.y)};
        add_spring(line, centre, {-n.y, n.x}, line.kt);
      }
    } else if (line.kt != 0.0) {
      const ContactState& c = contacts[line.contact];
      if (line.part.empty()) {  // the model opens it: its friction goes too
        const double f = std::hypot(c.friction_force.x, c.friction_force.y);
        if (f > 0.0) add_force(line, c.point, {c.friction_force.x / f, c.friction_force.y / f}, -f);
      } else {
        add_spring(line, c.point, {-n.y, n.x}, line.kt);
      }
    }
    if (springs) add_line_springs(line);
  }
  if (damping > 0.0) {
    std::vector<Eigen::Matrix<double, 6, 1>> diagonal(sizes.size(), Eigen::Matrix<double, 6, 1>::Zero());
    for (const Term& t : terms) {
      if (t.row == t.col) diagonal[static_cast<std::size_t>(t.row)] += t.value.diagonal();
    }
    for (std::size_t b = 0; b < diagonal.size(); ++b) {
      terms.push_back({static_cast<int>(b), static_cast<int>(b), (damping * diagonal[b]).asDiagonal().toDenseMatrix()});
    }
  }
  return model.solver.factorize(sizes, terms);
}

// The open-close iteration of one Newton iteration: solve, then move each line's closed part to
// where the solution leaves its gap negative, until no part moves more than `force_tolerance`
// (N/m) of its springs' force (contact::part_force_change; at most max_open_close solves; after
// half of them a part only
// grows, as the 3D engine keeps a closed contact closed: parts at exact touch that carry no
// load otherwise alternate between a rounding's tension and a rounding's overlap).
void Dda2d::Impl::solve_open_close(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                                   LinearModel& model, double damping, double force_tolerance,
                                   Eigen::VectorXd& delta) const {
  // CP's move from TP at `at`, along `direction`.
  const auto relative = [&](const LinearModel::Line& line, Point2 at, Vector2 direction) {
    double along = 0.0;
    for (const std::size_t b : {line.cp, line.tp}) {
      if (!moving[b]) continue;
      const Vector6 g = generalized(states[b], at, direction);
      double x = 0.0;
      for (Eigen::Index k = 0; k < unknowns_of(b); ++k) x += g[static_cast<std::size_t>(k)] * delta(offset[b] + k);
      along += b == line.cp ? x : -x;
    }
    return along;
  };
  const auto approach = [&](const LinearModel::Line& line, Point2 at) {
    return relative(line, at, line.geometry.normal);
  };
  for (std::size_t round = 0;; ++round) {
    solve_model(moving, offset, model, damping, delta);
    std::size_t changes = 0;
    for (LinearModel::Line& line : model.lines) {
      const double from = approach(line, line.geometry.from), to = approach(line, line.geometry.to);
      contact::Interval part = contact::closed_part(line.geometry, from, to);
      const bool late = 2 * round >= max_open_close;
      if (late && !line.part.empty()) {
        part = part.empty() ? line.part
                            : contact::Interval{std::min(part.first, line.part.first), std::max(part.last, line.part.last)};
      }
      if (contact::part_force_change(line.geometry, line.part, part, line.kn, line.H, from, to) > force_tolerance) {
        ++changes;
      }
      line.part = part;
    }
    if (changes == 0 || round + 1 == max_open_close) return;
  }
}

// Each block's increment: `scale` times its unknowns in `d` (zero for blocks not moving).
void Dda2d::Impl::set_increments(const std::vector<char>& moving, const std::vector<Eigen::Index>& offset,
                                 const Eigen::VectorXd& d, double scale) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i].increment = {};
    if (!moving[i]) continue;
    for (Eigen::Index k = 0; k < unknowns_of(i); ++k) {
      bodies[i].increment[static_cast<std::size_t>(k)] = scale * d(offset[i] + k);
    }
  }
}

// The move of block i's farthest vertex under the unknowns `d` (m).
double Dda2d::Impl::farthest_move(std::size_t i, const Eigen::VectorXd& d,
                                  const std::vector<Eigen::Index>& offset) const {
  Vector6 increment{};
  for (Eigen::Index k = 0; k < unknowns_of(i); ++k) increment[static_cast<std::size_t>(k)] = d(offset[i] + k);
  double farthest = 0.0;
  const Point2& o = states[i].centroid;
  for (const Point2& v : states[i].vertices) {
    const Vector2 u = detail::transform({v.x - o.x, v.y - o.y}, increment);
    farthest = std::max(farthest, std::hypot(u.x, u.y));
  }
  return farthest;
}

// The stability probe of a stalled pre-solve (dda2d.hpp): the blocks of a mode along which the
// engine's forces push further the more the blocks move, so that no static state is near.
//
// Newton's iteration d <- d + K^-1 F(d) carries an error e to M e, M = I + K^-1 J, with J the
// engine's tangent dF/dd and K the model's stiffness (no turn of the forces with the blocks).
// Where the model is right M vanishes; along a mode v with J v = -lambda K v, M v = (1 - lambda)
// v. A column whose weight's turning moment outgrows its joints' rocking stiffness (a free
// column of blocks buckles above a height h where q h³ = 7.84 EI) has lambda < 0 there: M's
// eigenvalue exceeds 1, Newton's steps stall, and the column topples in the run. Power
// iteration on M from Newton's step finds its dominant eigenvalue; J v is a finite difference of
// the engine's forces (the blocks moved along v by probe_move of their inradius at most, and
// restored). An eigenvalue above probe_growth names the blocks that move more than
// probe_amplitude of the mode's largest move.
std::vector<std::size_t> Dda2d::Impl::unstable_blocks(const std::vector<char>& moving,
                                                      const std::vector<Eigen::Index>& offset,
                                                      const LinearModel& model) {
  const std::size_t n = bodies.size();
  Eigen::Index unknowns = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (moving[i]) unknowns += unknowns_of(i);
  }
  const auto gather = [&](Eigen::VectorXd& out) {
    out.resize(unknowns);
    for (std::size_t i = 0; i < n; ++i) {
      if (!moving[i]) continue;
      for (Eigen::Index k = 0; k < unknowns_of(i); ++k) out(offset[i] + k) = bodies[i].force[static_cast<std::size_t>(k)];
    }
  };
  const auto largest_move = [&](const Eigen::VectorXd& d) {
    double most = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (moving[i]) most = std::max(most, farthest_move(i, d, offset));
    }
    return most;
  };
  double reach = std::numeric_limits<double>::infinity();  // the smallest inradius
  for (std::size_t i = 0; i < n; ++i) {
    if (moving[i]) reach = std::min(reach, bodies[i].inradius);
  }
  Eigen::VectorXd rhs(unknowns);
  LinearModel tangent;  // at the state reached: each line closed where it overlaps now
  tangent.lines = model.lines;
  for (LinearModel::Line& line : tangent.lines) line.part = line.now;
  if (!factorize_model(moving, offset, tangent, 0.0, rhs)) return {};
  Eigen::VectorXd forces;
  gather(forces);
  Eigen::VectorXd v = tangent.solver.solve(forces);
  const SettleState here{states, friction};
  double growth = 0.0;
  for (std::size_t k = 0; k < probe_iterations; ++k) {
    const double most = largest_move(v);
    if (!(most > 0.0) || !v.allFinite()) return {};
    const double scale = probe_move * reach / most;
    set_increments(moving, offset, v, scale);
    move_by_increments(moving);
    Eigen::VectorXd moved;
    gather(moved);
    restore(here, moving);
    const Eigen::VectorXd jv = (moved - forces) / scale;
    const Eigen::VectorXd w = v + tangent.solver.solve(jv);
    growth = v.dot(w) > 0.0 ? largest_move(w) / most : 0.0;
    v = w;
  }
  std::vector<std::size_t> unstable;
  if (!(growth > probe_growth)) return unstable;
  const double most = largest_move(v);
  for (std::size_t i = 0; i < n; ++i) {
    if (moving[i] && farthest_move(i, v, offset) > probe_amplitude * most) unstable.push_back(i);
  }
  return unstable;
}

// The pre-solve's least out-of-balance state so far: where it starts from when it ends above
// the tolerance.
struct Dda2d::Impl::BestState {
  double ratio = std::numeric_limits<double>::infinity();
  SettleState state;
};

// One round of the pre-solve over the blocks in `moving` (dda2d.hpp): Newton's iterations to
// the tolerance, or the blocks without a static state.
SettleRound Dda2d::Impl::newton(const std::vector<char>& moving, const Resting& resting) {
  const std::size_t n = bodies.size();
  std::vector<Eigen::Index> offset(n, -1);
  Eigen::Index unknowns = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!moving[i]) continue;
    offset[i] = unknowns;
    unknowns += unknowns_of(i);
  }
  if (reference_force(moving) == 0.0) return {};
  equilibrium.ran = true;
  equilibrium.blocks = 0;  // until the round settles them
  LinearModel model;
  Eigen::VectorXd delta(unknowns);
  double damping = 0.0, previous_ratio = 0.0;
  BestState best;
  for (std::size_t iteration = 0;; ++iteration) {
    std::size_t worst = 0;
    const double reference = reference_force(moving);
    equilibrium.ratio = out_of_balance(moving, reference, worst);
    if (params.equilibrium_progress) params.equilibrium_progress(equilibrium.iterations, equilibrium.ratio);
    if (equilibrium.ratio < params.equilibrium_tolerance) {
      equilibrium.converged = true;
      equilibrium.blocks = static_cast<std::size_t>(std::count(moving.begin(), moving.end(), 1));
      return {};
    }
    keep_if_best(best);
    if (!equilibrium_probed && (iteration == newton_iterations || damping >= probe_damping)) {
      equilibrium_probed = true;
      build_model(moving, resting.parts, iteration == 0, model);
      SettleRound round;
      round.unsettled = unstable_blocks(moving, offset, model);
      if (!round.unsettled.empty()) {
        round.why = "dda2d: the initial equilibrium has no static state near the start for " +
                    block_name(states[round.unsettled.front()].id) + " and " +
                    std::to_string(round.unsettled.size() - 1) +
                    " more blocks: the more they move, the more their weight pushes them on (they "
                    "topple or buckle); set initial_equilibrium to \"auto\" to start them from their "
                    "given state, or to false";
        return round;
      }
    }
    if (iteration == newton_iterations) {
      // Every block is held (none ran away), but Newton's steps no longer lower the ratio: a
      // contact keeps crossing a kink (a part that opens and closes, a block rocking on a short
      // line). Dynamic relaxation, which needs no tangent, finishes from the state reached; if
      // it does not get there, the run starts from the least out-of-balance state either found.
      equilibrium.converged = relax_to_tolerance(moving, resting, best);
      if (!equilibrium.converged && best.ratio < equilibrium.ratio) {
        restore(best.state, moving);
        equilibrium.ratio = best.ratio;
      }
      equilibrium.blocks = static_cast<std::size_t>(std::count(moving.begin(), moving.end(), 1));
      if (!equilibrium.converged && params.initial_equilibrium == InitialEquilibrium::strict) {
        throw StabilityError("dda2d: the initial equilibrium was not reached in " + std::to_string(equilibrium.iterations) +
                             " iterations: the out-of-balance force ratio is " + number(equilibrium.ratio) +
                             " (tolerance " + number(params.equilibrium_tolerance) + "), largest at " +
                             block_name(states[worst].id) + "; raise equilibrium_tolerance, or set "
                             "initial_equilibrium to \"auto\" to start from the state reached");
      }
      return {};
    }
    ++equilibrium.iterations;
    build_model(moving, resting.parts, iteration == 0, model);
    // Levenberg-Marquardt: an iteration that did not lower the ratio crossed a kink of the
    // contacts (a part that opened or closed): the next step is damped by diag K, ten times
    // more each time, and relaxed by three for each that lowers it.
    if (iteration > 0) {
      damping = equilibrium.ratio < previous_ratio ? damping / 3.0 : std::max(10.0 * damping, min_damping);
    }
    previous_ratio = equilibrium.ratio;
    solve_open_close(moving, offset, model, damping, part_force_fraction * params.equilibrium_tolerance * reference,
                     delta);
    // The move of each block's farthest vertex, against its inradius.
    SettleRound round;
    double scale = 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Body& b = bodies[i];
      if (!moving[i]) continue;
      const double farthest = farthest_move(i, delta, offset);
      if (farthest > b.inradius) {
        if (round.unsettled.empty()) {
          round.why = "dda2d: the initial equilibrium would move " + block_name(states[i].id) + " by " +
                      number(farthest) + " m, more than its inradius (" + number(b.inradius) +
                      " m): the blocks it rests on at the start do not hold it (it topples, slides or "
                      "is unsupported), or its contacts are too soft for its weight (kn); set "
                      "initial_equilibrium to \"auto\" to start it from its given state, or to false";
        }
        round.unsettled.push_back(i);
      }
      scale = std::min(scale, newton_step_cap * b.inradius / std::max(farthest, 1e-300));
    }
    if (!round.unsettled.empty()) return round;
    set_increments(moving, offset, delta, scale);
    move_by_increments(moving);
  }
}

// The pre-solve's finish (newton): dynamic relaxation ("Static analysis", dda2d.hpp) of the
// blocks in `moving`, contacts locked, from the state reached, to the tolerance (true) or
// relaxation_iterations. Its iterations count in Equilibrium::iterations.
bool Dda2d::Impl::relax_to_tolerance(const std::vector<char>& moving, const Resting& resting, BestState& best) {
  prepare_relaxation(moving, resting.adjacent);
  std::size_t last_best = 0;
  for (std::size_t k = 0; k < relaxation_iterations; ++k, ++equilibrium.iterations) {
    std::size_t worst = 0;
    equilibrium.ratio = out_of_balance(moving, reference_force(moving), worst);
    if (equilibrium.ratio < params.equilibrium_tolerance) return true;
    if (k % relaxation_check == 0) {
      if (params.equilibrium_progress) params.equilibrium_progress(equilibrium.iterations, equilibrium.ratio);
      if (equilibrium.ratio < best.ratio) {
        keep_if_best(best);
        last_best = k;
      } else if (k - last_best >= relaxation_patience) {
        return false;
      }
    }
    relax_once();
  }
  return false;
}

void Dda2d::Impl::keep_if_best(BestState& best) const {
  if (!(equilibrium.ratio < best.ratio)) return;
  best.ratio = equilibrium.ratio;
  best.state = {states, friction};
}

// Static analysis: every movable block relaxes, under the scene's friction law.
void Dda2d::Impl::start_static_analysis() {
  std::vector<char> moving(bodies.size(), 0);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    moving[i] = !states[i].fixed;
    states[i].velocity = {};
  }
  prepare_relaxation(std::move(moving), resting_pairs().adjacent);
}

double Dda2d::Impl::balance_ratio() const {
  if (params.analysis != Analysis::static_equilibrium || relaxation.reference == 0.0) return 0.0;
  std::size_t worst = 0;
  return out_of_balance(relaxation.moving, relaxation.reference, worst);
}

// ---- the step ----------------------------------------------------------------------------

// Runs body(i) for every block that is not fixed, spread over the threads when there are many.
// Each call touches its own block only. An exception leaves the loop as the one of the lowest
// block index that threw, whatever the thread count.
template <class F>
void Dda2d::Impl::for_each_movable(F&& body) {
  const auto n = static_cast<std::ptrdiff_t>(bodies.size());
  const int threads = n >= parallel_threshold ? thread_count : 1;
  std::exception_ptr error;
  std::ptrdiff_t error_at = n;
#pragma omp parallel num_threads(threads)
  {
    const kernel::PredicateCounters before = kernel::predicate_counters();
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < n; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (states[i].fixed) continue;
      try {
        body(i);
      } catch (...) {
#pragma omp critical(rockcontact_dda2d_block_error)
        if (k < error_at) {
          error_at = k;
          error = std::current_exception();
        }
      }
    }
    count_worker(before);
  }
  if (error) std::rethrow_exception(error);
}

double Dda2d::Impl::kinetic(std::size_t i, const std::array<double, 6>& v) const {
  const BlockState& s = states[i];
  double e = 0.5 * s.mass * (v[0] * v[0] + v[1] * v[1]);
  if (s.rigid) return e + 0.5 * bodies[i].inertia * v[2] * v[2];
  const Eigen::Vector4d w(v[2], v[3], v[4], v[5]);
  return e + 0.5 * w.dot(bodies[i].rs_mass * w);
}

void Dda2d::Impl::first_half_kick(std::size_t i) {
  std::array<double, 6>& v = states[i].velocity;
  const Vector6& a = bodies[i].acceleration;
  const double half = 0.5 * params.dt;
  std::array<double, 6> kicked;
  for (std::size_t k = 0; k < 6; ++k) kicked[k] = v[k] + half * a[k];
  if (params.mass_damping > 0.0) {
    const double damp = half * params.mass_damping;
    std::array<double, 6> damped;
    for (std::size_t k = 0; k < 6; ++k) damped[k] = kicked[k] - damp * v[k];
    step_shares[i].damped += kinetic(i, kicked) - kinetic(i, damped);
    kicked = damped;
  }
  v = kicked;
  for (std::size_t k = 0; k < 6; ++k) bodies[i].increment[k] = params.dt * v[k];
}

void Dda2d::Impl::second_half_kick(std::size_t i) {
  std::array<double, 6>& v = states[i].velocity;
  const Vector6& a = bodies[i].acceleration;
  const double half = 0.5 * params.dt;
  for (std::size_t k = 0; k < 6; ++k) v[k] += half * a[k];
  if (params.mass_damping > 0.0) {
    const double before = kinetic(i, v);
    for (double& x : v) x /= 1.0 + half * params.mass_damping;
    step_shares[i].damped += before - kinetic(i, v);
  }
}

Dda2d::Impl::StepMap Dda2d::Impl::step_map(std::size_t i) const {
  const Vector6& d = bodies[i].increment;
  return {d, states[i].centroid, std::cos(d[2]), std::sin(d[2])};
}

// Displacement over the step of the material point at p (current position) of block i, under
// the same map as move().
Vector2 Dda2d::Impl::point_increment(std::size_t i, Point2 p) const {
  if (states[i].fixed) return {};
  return step_map(i)(p);
}

// Velocity of the material point at p (current position) of block i: T(p) d' (eq. 3).
Vector2 Dda2d::Impl::point_velocity(std::size_t i, Point2 p) const {
  if (states[i].fixed) return {};
  const Point2& o = states[i].centroid;
  return detail::transform({p.x - o.x, p.y - o.y}, states[i].velocity);
}

void Dda2d::Impl::advance_friction_records() {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (friction_of[k] == no_record) continue;  // a frictionless interface
    const ContactState& c = contacts[k];
    const Vector2 a = point_increment(c.cp, c.point), b = point_increment(c.tp, c.point);
    const Vector2 relative{a.x - b.x, a.y - b.y};
    contact::FrictionState& record = friction[friction_of[k]].state;
    const FrictionLaw& friction_law = *laws[law_index(c.cp, c.tp)].friction;
    if (friction_law.model == contact::FrictionModel::paper && record.sliding) {
      const double fn = std::hypot(c.normal_force.x, c.normal_force.y);
      const double nx = c.normal_force.x / fn, ny = c.normal_force.y / fn;
      const double along = relative.x * nx + relative.y * ny;
      const double slip = std::hypot(relative.x - along * nx, relative.y - along * ny);
      friction_dissipated += std::hypot(c.friction_force.x, c.friction_force.y) * slip;
    }
    contact::advance_friction(record, relative, friction_law);
  }
}

void Dda2d::Impl::move(std::size_t i) {
  Body& b = bodies[i];
  BlockState& s = states[i];
  const Vector6& d = b.increment;
  for (double x : d) {
    if (!finite(x)) {
      throw StabilityError(at_step() + block_name(s.id) + " has a non-finite displacement increment");
    }
  }
  const Point2 o = s.centroid;
  const StepMap map = step_map(i);
  for (Point2& p : s.vertices) {
    const Vector2 u = map(p);
    p = {p.x + u.x, p.y + u.y};
  }
  s.rotation += d[2];
  if (!s.rigid) {
    const double c = map.cos, sn = map.sin;
    const Eigen::Vector3d dsigma = b.elasticity * Eigen::Vector3d(d[3], d[4], d[5]);
    s.stress = rotate_tensor(s.stress[0] + dsigma(0), s.stress[1] + dsigma(1),
                             s.stress[2] + dsigma(2), c, sn);
    const std::array<double, 3> rate = rotate_tensor(s.velocity[3], s.velocity[4],
                                                     0.5 * s.velocity[5], c, sn);
    s.velocity[3] = rate[0];
    s.velocity[4] = rate[1];
    s.velocity[5] = 2.0 * rate[2];
  }
  try {
    rebuild_parts(i);
  } catch (const kernel::InvalidPolygon& e) {
    throw StabilityError(at_step() + block_name(s.id) + " is no longer a valid convex polygon (" +
                         e.what() + "); its strain increment was (" + number(d[3]) + ", " +
                         number(d[4]) + ", " + number(d[5]) + ") around " + number(o.x) + ", " +
                         number(o.y));
  }
  refresh(i);
}

// The convex parts from the block's current vertices, in place: make() copied the name and
// allocated four vectors per part and step, 9 % of a step's instructions at 10⁴ blocks; assign()
// validates in one pass into the storage the part already has. Throws kernel::InvalidPolygon
// when a part is no longer strictly convex.
void Dda2d::Impl::rebuild_parts(std::size_t i) {
  thread_local std::vector<Point2> corners;  // move runs on the worker threads
  Parts& parts = bodies[i].parts;
  for (std::size_t p = 0; p < parts.polygons.size(); ++p) {
    corners.clear();
    for (const std::size_t k : parts.corners[p]) corners.push_back(states[i].vertices[k]);
    parts.polygons[p].assign(corners);
  }
}

// The stability monitor (dda2d.hpp) on the worker threads, block by block (serial, the checks
// and the energies were 6 % of a step at 10⁴ blocks): a non-finite state, and the block's
// energy for check_energy.
void Dda2d::Impl::check_block(std::size_t i) {
  const BlockState& s = states[i];
  const bool ok = std::all_of(s.velocity.begin(), s.velocity.end(), finite) &&
                  std::all_of(s.stress.begin(), s.stress.end(), finite) &&
                  finite(s.centroid.x) && finite(s.centroid.y);
  if (!ok) throw StabilityError(at_step() + block_name(s.id) + " has a non-finite velocity or stress");
  energy_shares[i] = block_energy(i);
}

// The monitor's energy growth, from the blocks' energies summed in block order.
void Dda2d::Impl::check_energy() {
  const Energies e = sum_energies([this](std::size_t i) { return energy_shares[i]; });
  max_gravitational = std::max(max_gravitational, std::fabs(e.gravitational));
  const double bound = energy_growth_factor * (initial_budget + max_gravitational);
  const double growth = e.total() - initial_total;
  if (!(growth <= bound)) {
    std::size_t fastest = 0;
    double most = -1.0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      if (states[i].fixed) continue;
      const double k = kinetic(i, states[i].velocity);
      if (k > most) {
        most = k;
        fastest = i;
      }
    }
    throw StabilityError(at_step() + "the total energy grew from " + number(initial_total) + " to " +
                         number(e.total()) + " J/m, more than the bound " + number(bound) +
                         " J/m; " + block_name(states[fastest].id) +
                         " holds the most kinetic energy (" + number(most) +
                         " J/m). dt = " + number(params.dt) + " s against the critical estimate " +
                         number(critical) + " s: the run is diverging (a block pressed by several " +
                         "contacts at once is stiffer than any single pair)");
  }
}

// Half of the trapezoid rule's work against the contact forces (and their dashpots) over the
// step, taken with the forces at t_n and again with those at t_n+1: each block's share on the
// worker threads (share_work), the sums in block order (add_work).
void Dda2d::Impl::share_work(std::size_t i) {
  const Body& b = bodies[i];
  step_shares[i].contact_work = 0.5 * dot6(b.contact_force, b.increment);
  step_shares[i].dashpot_work = 0.5 * dot6(b.dashpot_force, b.increment);
}

void Dda2d::Impl::add_work() {
  for (const StepShare& share : step_shares) {
    contact_work -= share.contact_work;
    dashpot_dissipated -= share.dashpot_work;
  }
}

// A step of the static analysis: one relaxation iteration; the blocks' velocities stay zero.
void Dda2d::Impl::static_step() {
  ++steps;
  time = static_cast<double>(steps) * params.dt;
  relax_once();
}

void Dda2d::Impl::advance() {
  // Messages during the step name the step being taken and the time it reaches.
  ++steps;
  time = static_cast<double>(steps) * params.dt;
  for_each_movable([this](std::size_t i) {
    step_shares[i].damped = 0.0;
    first_half_kick(i);
    share_work(i);
  });
  add_work();
  advance_friction_records();
  for_each_movable([this](std::size_t i) { move(i); });
  evaluate_forces();
  for_each_movable([this](std::size_t i) {
    share_work(i);
    second_half_kick(i);
    check_block(i);
  });
  add_work();
  for (const StepShare& share : step_shares) damping_dissipated += share.damped;
  check_energy();
}

Dda2d::Impl::BlockEnergy Dda2d::Impl::block_energy(std::size_t i) const {
  const BlockState& s = states[i];
  const Body& b = bodies[i];
  BlockEnergy e;
  e.kinetic = kinetic(i, s.velocity);
  e.gravitational = -(s.mass * (params.gravity.x * (s.centroid.x - b.initial_centroid.x) +
                                params.gravity.y * (s.centroid.y - b.initial_centroid.y)));
  if (!s.rigid) {
    const Eigen::Vector3d sigma(s.stress[0], s.stress[1], s.stress[2]);
    e.strain = 0.5 * s.area * sigma.dot(b.flexibility * sigma);
  }
  return e;
}

// The movable blocks' shares summed in block order, so the totals are the same numbers whether
// the shares were computed on one thread or several, and the work the engine accumulated.
template <class Share>
Energies Dda2d::Impl::sum_energies(Share&& share) const {
  Energies e;
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (states[i].fixed) continue;
    const BlockEnergy b = share(i);
    e.kinetic += b.kinetic;
    e.gravitational += b.gravitational;
    e.strain += b.strain;
  }
  e.contact = contact_work - friction_dissipated - dashpot_dissipated;
  e.friction_dissipated = friction_dissipated;
  e.damping_dissipated = damping_dissipated + dashpot_dissipated;
  return e;
}

Energies Dda2d::Impl::energies() const {
  return sum_energies([this](std::size_t i) { return block_energy(i); });
}

// ---- snapshots ---------------------------------------------------------------------------

Snapshot Dda2d::Impl::snapshot() const {
  Snapshot out;
  out.time = time;
  out.steps = steps;
  out.blocks.reserve(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    const BlockState& s = states[i];
    const Body& b = bodies[i];
    out.blocks.push_back({s.vertices, s.rotation, s.velocity, s.stress, b.initial_centroid,
                          b.force, b.contact_force, b.dashpot_force, b.acceleration});
  }
  out.contacts = contacts;
  for (const FrictionRecord& r : friction) {
    out.springs.push_back({r.parts.cp, r.parts.tp, r.parts.cp_part, r.parts.tp_part, r.state});
  }
  if (params.analysis == Analysis::static_equilibrium) {
    out.relaxation = {relaxation.moving, relaxation.mass_scale, relaxation.velocity,
                      relaxation.reference, relaxation.kinetic};
  }
  out.contact_work = contact_work;
  out.friction_dissipated = friction_dissipated;
  out.mass_damping_dissipated = damping_dissipated;
  out.dashpot_dissipated = dashpot_dissipated;
  out.initial_total = initial_total;
  out.initial_budget = initial_budget;
  out.max_gravitational = max_gravitational;
  out.max_penetration = max_penetration;
  out.equilibrium = equilibrium;
  out.predicates = counters;
  return out;
}

namespace {

void snapshot_misfit(const std::string& what) {
  throw std::invalid_argument("dda2d: the snapshot does not fit these blocks: " + what);
}

}  // namespace

// Takes over the state of `from` after the blocks were added (dda2d.hpp, Snapshot).
void Dda2d::Impl::restore(const Snapshot& from) {
  const std::size_t n = bodies.size();
  if (from.blocks.size() != n) {
    snapshot_misfit("it holds " + std::to_string(from.blocks.size()) + " blocks, the simulation " +
                    std::to_string(n));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Snapshot::Block& b = from.blocks[i];
    BlockState& s = states[i];
    if (b.vertices.size() != s.vertices.size()) {
      snapshot_misfit(block_name(s.id) + " has " + std::to_string(s.vertices.size()) +
                      " vertices, the snapshot " + std::to_string(b.vertices.size()));
    }
    s.vertices = b.vertices;
    s.rotation = b.rotation;
    s.velocity = b.velocity;
    s.stress = b.stress;
    Body& body = bodies[i];
    body.initial_centroid = b.reference_centroid;
    body.force = b.force;
    body.contact_force = b.contact_force;
    body.dashpot_force = b.dashpot_force;
    body.acceleration = b.acceleration;
    try {
      rebuild_parts(i);
    } catch (const kernel::InvalidPolygon& e) {
      snapshot_misfit(e.what());
    }
    refresh(i);
  }
  const auto check_parts = [&](std::size_t cp, std::size_t tp, std::size_t p, std::size_t q,
                               const std::string& what) {
    if (!(cp < tp && tp < n && p < bodies[cp].parts.polygons.size() &&
          q < bodies[tp].parts.polygons.size())) {
      snapshot_misfit(what + " names blocks " + std::to_string(cp) + " and " + std::to_string(tp) +
                      " (parts " + std::to_string(p) + ", " + std::to_string(q) +
                      "), which are not a pair of this simulation");
    }
  };
  for (const Snapshot::Spring& spring : from.springs) {
    check_parts(spring.cp, spring.tp, spring.cp_part, spring.tp_part, "a spring");
    const PartPair parts{spring.cp, spring.tp, spring.cp_part, spring.tp_part};
    if (!friction.empty() && !(friction.back().parts < parts)) {
      snapshot_misfit("its springs are not in pair order");
    }
    friction.push_back({parts, spring.state});
  }
  contacts = from.contacts;
  for (const ContactState& c : contacts) {
    check_parts(c.cp, c.tp, c.cp_part, c.tp_part, "a contact");
    std::size_t record = no_record;
    if (laws[law_index(c.cp, c.tp)].friction) {
      const PartPair parts{c.cp, c.tp, c.cp_part, c.tp_part};
      const auto it = std::lower_bound(
          friction.begin(), friction.end(), parts,
          [](const FrictionRecord& r, const PartPair& key) { return r.parts < key; });
      if (it == friction.end() || it->parts != parts) {
        snapshot_misfit("the frictional contact of " + block_name(states[c.cp].id) + " and " +
                        block_name(states[c.tp].id) + " has no spring");
      }
      record = static_cast<std::size_t>(it - friction.begin());
    }
    friction_of.push_back(record);
  }
  if (params.analysis == Analysis::static_equilibrium) {
    const Snapshot::Relaxation& r = from.relaxation;
    if (r.moving.size() != n || r.mass_scale.size() != n || r.velocity.size() != n) {
      snapshot_misfit("a static analysis needs the relaxation state of every block");
    }
    relaxation = {r.moving, r.mass_scale, r.velocity, r.reference, r.kinetic};
  }
  time = from.time;
  steps = from.steps;
  contact_work = from.contact_work;
  friction_dissipated = from.friction_dissipated;
  damping_dissipated = from.mass_damping_dissipated;
  dashpot_dissipated = from.dashpot_dissipated;
  initial_total = from.initial_total;
  initial_budget = from.initial_budget;
  max_gravitational = from.max_gravitational;
  max_penetration = from.max_penetration;
  equilibrium = from.equilibrium;
  counters = from.predicates;
}

// ---- public face -------------------------------------------------------------------------

Dda2d::Dda2d(std::vector<BlockSpec> blocks, ContactLaw law, DdaParams params) {
  kernel::PredicateCounters spent;
  {
    const CountInto count(spent);
    impl_ = std::make_shared<Impl>(std::move(blocks), std::move(law), params, nullptr);
  }
  impl_->counters += spent;
}

Dda2d::Dda2d(std::vector<BlockSpec> blocks, ContactLaw law, DdaParams params,
             const Snapshot& from)
    : impl_(std::make_shared<Impl>(std::move(blocks), std::move(law), params, &from)) {}

Snapshot Dda2d::snapshot() const { return impl_->snapshot(); }

void Dda2d::step() {
  const CountInto count(impl_->counters);
  if (impl_->params.analysis == Analysis::static_equilibrium) {
    impl_->static_step();
  } else {
    impl_->advance();
  }
}

double Dda2d::balance_ratio() const { return impl_->balance_ratio(); }

double Dda2d::time() const noexcept { return impl_->time; }
std::size_t Dda2d::steps() const noexcept { return impl_->steps; }
const std::vector<BlockState>& Dda2d::blocks() const noexcept { return impl_->states; }
const std::vector<ContactState>& Dda2d::contacts() const noexcept { return impl_->contacts; }
Energies Dda2d::energies() const { return impl_->energies(); }
double Dda2d::critical_time_step() const noexcept { return impl_->critical; }
const std::string& Dda2d::critical_time_step_source() const noexcept {
  return impl_->critical_source;
}
double Dda2d::max_penetration() const noexcept { return impl_->max_penetration; }
const Equilibrium& Dda2d::initial_equilibrium() const noexcept { return impl_->equilibrium; }
kernel::PredicateCounters Dda2d::predicate_counters() const noexcept { return impl_->counters; }

}  // namespace rockcontact::dynamics
