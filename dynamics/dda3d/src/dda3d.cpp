#include "rockcontact/dynamics/dda3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "block_matrices3d.hpp"
#include "contact_terms3d.hpp"
#include "rockcontact/kernel/3d/contact_constraints.hpp"

namespace rockcontact::dynamics {
namespace {

using kernel::ConvexPolyhedron;
using kernel::Point3;

// Growth of the step after an accepted one, back towards Dda3dParams::dt.
constexpr double step_growth = 1.5;

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

std::string block_name(const std::string& id) { return "block '" + id + "'"; }

Eigen::Vector3d vec(const Point3& p) { return {p.x, p.y, p.z}; }
Point3 point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// The axis-aligned box of a block's vertices.
struct Box {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  void add(const Point3& p) {
    lo = lo.cwiseMin(vec(p));
    hi = hi.cwiseMax(vec(p));
  }
  bool meets(const Box& o, double range) const {
    return ((lo.array() - range) <= o.hi.array()).all() && ((o.lo.array() - range) <= hi.array()).all();
  }
};

Box box_of(const std::vector<ConvexPolyhedron>& parts) {
  Box b;
  for (const ConvexPolyhedron& part : parts) {
    for (const Point3& p : part.vertices()) b.add(p);
  }
  return b;
}

// Area of a planar polygon given as vertex ids of `part` (Newell's formula).
double face_area(const ConvexPolyhedron& part, const ConvexPolyhedron::Face& loop) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const Eigen::Vector3d o = vec(part[loop[0]]);
  for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
    sum += (vec(part[loop[k]]) - o).cross(vec(part[loop[k + 1]]) - o);
  }
  return 0.5 * sum.norm();
}

struct Block {
  Block3dSpec spec;
  std::vector<ConvexPolyhedron> parts;  // current
  detail::CentralMoments3d moments;     // of the current parts
  double mass = 0.0;
  int dof = 0;                          // 0 (fixed), 6 (rigid) or 12
  std::size_t offset = 0;               // of its unknowns in the global vector
  Eigen::VectorXd velocity;             // dof entries
  Eigen::Matrix<double, 6, 1> stress = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d reference_centroid = Eigen::Vector3d::Zero();
  detail::Matrix6 elasticity = detail::Matrix6::Zero();
  Box box;

  Eigen::MatrixXd mass_matrix() const { return detail::mass_matrix(moments, mass).topLeftCorner(dof, dof); }
};

// What identifies a constraint from step to step (§4.2): its pair and its two features.
using ConstraintKey = std::tuple<std::size_t, std::size_t, int, int, std::uint32_t, std::uint32_t, int,
                                 std::uint32_t, std::uint32_t>;

ConstraintKey key_of(std::size_t a, std::size_t b, const kernel::ContactConstraint& c) {
  return {a,
          b,
          static_cast<int>(c.type),
          static_cast<int>(c.cp_feature.kind),
          c.cp_feature.index,
          c.cp_feature.part,
          static_cast<int>(c.tp_feature.kind),
          c.tp_feature.index,
          c.tp_feature.part};
}

struct Constraint {
  std::size_t a = 0, b = 0;  // blocks: a the kernel's cp, b its tp
  kernel::ContactConstraint geometry;
  detail::ContactLaw3d law;
  detail::ContactKinematics3d kinematics;
  detail::ContactState3d state;     // of the start of the step, then of the iteration
  detail::ContactUpdate3d update;   // of the last solve
  double slip_work = 0.0;           // friction work of the last solve, J
  double start_energy = 0.0;        // held by its springs at the start of the step, J
};

ContactMode3d public_mode(detail::ContactMode mode) {
  switch (mode) {
    case detail::ContactMode::open: return ContactMode3d::open;
    case detail::ContactMode::locked: return ContactMode3d::stick;
    case detail::ContactMode::sliding: return ContactMode3d::slide;
  }
  return ContactMode3d::open;
}

void check_range(bool ok, const std::string& field, const std::string& expected, double value) {
  if (!ok) throw std::invalid_argument(field + ": expected " + expected + ", got " + number(value));
}

}  // namespace

struct Dda3d::Impl {
  std::vector<Block> blocks;
  std::vector<Block3dState> states;
  ContactLaw3d law;
  Dda3dParams params;
  double size = 0.0;   // the scene's bounding-box diagonal at the start, m
  double range = 0.0;  // the contact detection range, m
  double h = 0.0;      // the step the next attempt takes, s
  double time = 0.0;
  std::size_t steps = 0;
  std::size_t unknowns = 0;
  std::vector<Constraint> constraints;  // the contact list after the last accepted step
  // The deepest constraint detect() dropped (deeper than the range), for the check at t = 0.
  struct Dropped {
    double depth = 0.0;
    std::size_t a = 0, b = 0;
  } deepest;
  Step3dStats last;
  double friction_dissipated = 0.0, numerical_dissipated = 0.0;
  kernel::PredicateCounters predicates;

  Impl(std::vector<Block3dSpec> specs, ContactLaw3d contact_law, Dda3dParams p);
  void validate_law() const;
  detail::ContactLaw3d pair_law(const Block& a, const Block& b) const;
  std::vector<Constraint> detect();
  bool attempt(std::vector<Constraint>& list, Eigen::VectorXd& d, std::size_t& iterations,
               double& numerical) const;
  void solve(const std::vector<Constraint>& list, Eigen::VectorXd& d, double& numerical) const;
  double largest_displacement(const Eigen::VectorXd& d) const;
  void accept(std::vector<Constraint> list, const Eigen::VectorXd& d, std::size_t iterations, double numerical);
  void refresh_state(std::size_t i);
};

Dda3d::Impl::Impl(std::vector<Block3dSpec> specs, ContactLaw3d contact_law, Dda3dParams p)
    : law(std::move(contact_law)), params(p) {
  check_range(std::isfinite(params.dt) && params.dt > 0.0, "time.dt", "a finite step > 0 s", params.dt);
  check_range(params.max_displacement_ratio > 0.0 && params.max_displacement_ratio < 1.0,
              "time.max_displacement_ratio", "a ratio in (0, 1)", params.max_displacement_ratio);
  check_range(params.min_dt_ratio > 0.0 && params.min_dt_ratio < 1.0, "time.min_dt_ratio", "a ratio in (0, 1)",
              params.min_dt_ratio);
  if (params.max_open_close == 0) throw std::invalid_argument("max_open_close: expected at least 1 iteration");
  for (double g : params.gravity) check_range(std::isfinite(g), "gravity", "finite components", g);
  validate_law();
  if (specs.empty()) throw std::invalid_argument("blocks: expected at least one block");
  std::set<std::string> ids;
  Box scene;
  for (Block3dSpec& spec : specs) {
    const std::string name = block_name(spec.id);
    if (spec.id.empty()) throw std::invalid_argument("blocks: a block has an empty id");
    if (!ids.insert(spec.id).second) throw std::invalid_argument(name + ": the id is used twice");
    if (spec.parts.empty()) throw std::invalid_argument(name + ": expected at least one part");
    const Material& m = spec.material;
    check_range(std::isfinite(m.density) && m.density > 0.0, name + " material density", "> 0 kg/m³", m.density);
    check_range(std::isfinite(m.youngs_modulus) && m.youngs_modulus > 0.0, name + " material youngs_modulus",
                "> 0 Pa", m.youngs_modulus);
    check_range(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5, name + " material poisson_ratio",
                "a ratio in (-1, 0.5)", m.poisson_ratio);
    for (double v : spec.velocity) check_range(std::isfinite(v), name + " velocity", "finite components", v);
    Block b;
    b.parts = spec.parts;
    b.moments = detail::central_moments3d(b.parts);
    if (!(b.moments.volume > 0.0)) throw std::invalid_argument(name + ": zero volume");
    b.mass = m.density * b.moments.volume;
    b.dof = spec.fixed ? 0 : spec.rigid ? detail::rigid_dof3d : detail::dof3d;
    b.offset = unknowns;
    unknowns += static_cast<std::size_t>(b.dof);
    b.velocity = Eigen::VectorXd::Zero(b.dof);
    if (!spec.fixed) {
      for (int k = 0; k < 6; ++k) b.velocity[k] = spec.velocity[static_cast<std::size_t>(k)];
    }
    b.reference_centroid = b.moments.centroid;
    b.elasticity = detail::elasticity_matrix3d(m.youngs_modulus, m.poisson_ratio);
    b.box = box_of(b.parts);
    scene.add(point(b.box.lo));
    scene.add(point(b.box.hi));
    b.spec = std::move(spec);
    blocks.push_back(std::move(b));
  }
  size = (scene.hi - scene.lo).norm();
  range = 2.0 * params.max_displacement_ratio * size;
  h = params.dt;
  states.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) refresh_state(i);
  constraints = detect();
  if (deepest.depth > 0.0) {
    throw std::invalid_argument(block_name(blocks[deepest.a].spec.id) + " and " + block_name(blocks[deepest.b].spec.id) +
                                " overlap by " + number(deepest.depth) +
                                " m at the start; expected at most the contact detection range " + number(range) +
                                " m (2 x max_displacement_ratio x the scene's size), within which the penalty acts");
  }
}

void Dda3d::Impl::validate_law() const {
  check_range(std::isfinite(law.kn) && law.kn > 0.0, "contact.kn", "a finite penalty > 0 N/m", law.kn);
  check_range(std::isfinite(law.kt) && law.kt > 0.0, "contact.kt", "a finite penalty > 0 N/m", law.kt);
  const auto check_strengths = [](const std::string& where, double phi, double c, double t) {
    check_range(phi >= 0.0 && phi < 90.0, where + ".friction_angle_deg", "degrees in [0, 90)", phi);
    check_range(std::isfinite(c) && c >= 0.0, where + ".cohesion", "a finite cohesion >= 0 Pa", c);
    check_range(std::isfinite(t) && t >= 0.0, where + ".tensile_strength", "a finite strength >= 0 Pa", t);
  };
  check_strengths("contact", law.friction_angle_deg, law.cohesion, law.tensile_strength);
  std::set<std::pair<std::string, std::string>> seen;
  for (std::size_t k = 0; k < law.interfaces.size(); ++k) {
    const Interface3d& f = law.interfaces[k];
    const std::string where = "interfaces[" + std::to_string(k) + "]";
    check_strengths(where, f.friction_angle_deg, f.cohesion, f.tensile_strength);
    const auto pair = std::minmax(f.groups[0], f.groups[1]);
    if (!seen.insert(pair).second) {
      throw std::invalid_argument(where + ": a second interface between groups '" + pair.first + "' and '" +
                                  pair.second + "'");
    }
  }
}

detail::ContactLaw3d Dda3d::Impl::pair_law(const Block& a, const Block& b) const {
  detail::ContactLaw3d out{law.kn, law.kt, law.friction_angle_deg, law.cohesion, law.tensile_strength};
  const auto groups = std::minmax(a.spec.group, b.spec.group);
  for (const Interface3d& f : law.interfaces) {
    if (std::minmax(f.groups[0], f.groups[1]) == groups) {
      out.friction_angle_deg = f.friction_angle_deg;
      out.cohesion = f.cohesion;
      out.tensile_strength = f.tensile_strength;
    }
  }
  return out;
}

// Step 1 of the header: the constraints of every pair within the detection range, each keeping
// the record of the same constraint in the previous list.
std::vector<Constraint> Dda3d::Impl::detect() {
  std::map<ConstraintKey, const Constraint*> previous;
  for (const Constraint& c : constraints) previous.emplace(key_of(c.a, c.b, c.geometry), &c);
  std::vector<Constraint> out;
  const kernel::PredicateCounters before = kernel::predicate_counters();
  for (std::size_t a = 0; a < blocks.size(); ++a) {
    for (std::size_t b = a + 1; b < blocks.size(); ++b) {
      const Block &ba = blocks[a], &bb = blocks[b];
      if (ba.dof == 0 && bb.dof == 0) continue;
      if (!ba.box.meets(bb.box, range)) continue;
      std::vector<kernel::ContactConstraint> found = kernel::with_policy(law.policy, [&](auto policy) {
        using Policy = decltype(policy);
        return kernel::contact_constraints<Policy>(std::span<const ConvexPolyhedron>(ba.parts),
                                                   std::span<const ConvexPolyhedron>(bb.parts), range);
      });
      // No step moves a vertex farther than half the range (step 4), so a vertex deeper than
      // the range has not entered where the kernel's shortest exit says: it crossed an internal
      // face of a non-convex block, and its exit through the far side of that part would fling
      // the blocks apart. The neighbouring part's constraint is the one that holds it.
      for (const kernel::ContactConstraint& c : found) {
        if (c.gap < -range && -c.gap > deepest.depth) deepest = {-c.gap, a, b};
      }
      std::erase_if(found, [&](const kernel::ContactConstraint& c) { return c.gap < -range; });
      // The area a vertex-face constraint stands for: its face's, shared by the pair's
      // vertex-face constraints on that face.
      std::map<std::tuple<int, std::uint32_t, std::uint32_t>, int> on_face;
      const auto face_of = [](const kernel::ContactConstraint& c) {
        const bool cp_face = c.cp_feature.kind == kernel::Feature::Kind::face;
        const kernel::Feature& f = cp_face ? c.cp_feature : c.tp_feature;
        return std::tuple<int, std::uint32_t, std::uint32_t>{cp_face ? 0 : 1, f.part, f.index};
      };
      for (const kernel::ContactConstraint& c : found) {
        if (c.type == kernel::ConstraintType::vertex_face) ++on_face[face_of(c)];
      }
      const detail::ContactLaw3d pair = pair_law(ba, bb);
      for (const kernel::ContactConstraint& c : found) {
        Constraint k;
        k.a = a;
        k.b = b;
        k.geometry = c;
        k.law = pair;
        double area = 0.0;
        if (c.type == kernel::ConstraintType::vertex_face) {
          const auto [side, part, index] = face_of(c);
          const ConvexPolyhedron& poly = (side == 0 ? ba : bb).parts[part];
          area = face_area(poly, poly.faces()[index]) / on_face[face_of(c)];
        }
        k.kinematics = detail::contact_kinematics({c.point_cp, point(ba.moments.centroid), ba.dof},
                                                  {c.point_tp, point(bb.moments.centroid), bb.dof}, c.normal, area);
        if (const auto it = previous.find(key_of(a, b, c)); it != previous.end()) {
          k.state = it->second->state;
        } else {
          k.state.mode = c.gap > 0.0 ? detail::ContactMode::open : detail::ContactMode::locked;
        }
        if (k.state.mode != detail::ContactMode::open) {
          k.start_energy = 0.5 * k.law.kn * k.kinematics.gap * k.kinematics.gap +
                           0.5 * k.law.kt * k.state.shear.squaredNorm();
        }
        if (k.state.sliding_direction.isZero()) {
          // §2.3 eq. 6: the sliding direction assumed first is that of the points' relative
          // velocity; the open-close iteration takes it from the solution after that (eq. 8).
          const Eigen::Vector3d relative = k.kinematics.t_j * bb.velocity - k.kinematics.t_i * ba.velocity;
          if (const auto v = kernel::sliding_direction(c.normal, point(relative))) k.state.sliding_direction = vec(*v);
        }
        out.push_back(std::move(k));
      }
    }
  }
  predicates += kernel::predicate_counters() - before;
  return out;
}

// Step 2: assemble and solve for the increments d; `numerical` receives the elastic springs'
// share of the integrator's dissipation, ½ dᵀ K_e d.
void Dda3d::Impl::solve(const std::vector<Constraint>& list, Eigen::VectorXd& d, double& numerical) const {
  const auto n = static_cast<Eigen::Index>(unknowns);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  const Eigen::Vector3d g(params.gravity[0], params.gravity[1], params.gravity[2]);
  const auto scatter = [&](std::size_t row, std::size_t col, const Eigen::MatrixXd& m) {
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      for (Eigen::Index c = 0; c < m.cols(); ++c) {
        if (m(r, c) != 0.0) {
          triplets.emplace_back(static_cast<Eigen::Index>(row) + r, static_cast<Eigen::Index>(col) + c, m(r, c));
        }
      }
    }
  };
  std::vector<Eigen::MatrixXd> springs(blocks.size());  // K_e per block, for the dissipation
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Block& b = blocks[i];
    if (b.dof == 0) continue;
    const Eigen::MatrixXd m = b.mass_matrix();
    Eigen::MatrixXd k = (2.0 / (h * h)) * m;
    Eigen::VectorXd f = detail::gravity_load(b.mass, g).head(b.dof) + (2.0 / h) * m * b.velocity;
    springs[i] = Eigen::MatrixXd::Zero(b.dof, b.dof);
    if (b.dof == detail::dof3d) {
      springs[i] = detail::elastic_stiffness(b.elasticity, b.moments.volume);
      k += springs[i];
      f.tail<6>() -= b.moments.volume * b.stress;
    }
    scatter(b.offset, b.offset, k);
    rhs.segment(static_cast<Eigen::Index>(b.offset), b.dof) += f;
  }
  for (std::size_t c = 0; c < list.size(); ++c) {
    const Constraint& k = list[c];
    const Block &ba = blocks[k.a], &bb = blocks[k.b];
    Eigen::MatrixXd kii = Eigen::MatrixXd::Zero(ba.dof, ba.dof), kij = Eigen::MatrixXd::Zero(ba.dof, bb.dof),
                    kjj = Eigen::MatrixXd::Zero(bb.dof, bb.dof);
    Eigen::VectorXd fi = Eigen::VectorXd::Zero(ba.dof), fj = Eigen::VectorXd::Zero(bb.dof);
    detail::add_contact_terms(k.kinematics, k.state, k.law, {kii, kij, kjj, fi, fj});
    if (ba.dof > 0) {
      scatter(ba.offset, ba.offset, kii);
      rhs.segment(static_cast<Eigen::Index>(ba.offset), ba.dof) += fi;
    }
    if (bb.dof > 0) {
      scatter(bb.offset, bb.offset, kjj);
      rhs.segment(static_cast<Eigen::Index>(bb.offset), bb.dof) += fj;
    }
    if (ba.dof > 0 && bb.dof > 0) {
      scatter(ba.offset, bb.offset, kij);
      scatter(bb.offset, ba.offset, kij.transpose());
    }
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
  if (ldlt.info() != Eigen::Success) {
    d = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
    return;
  }
  d = ldlt.solve(rhs);
  numerical = 0.0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Block& b = blocks[i];
    if (b.dof == 0) continue;
    const auto di = d.segment(static_cast<Eigen::Index>(b.offset), b.dof);
    numerical += 0.5 * di.dot(springs[i] * di);
  }
}

// Steps 2-3: the open-close iteration on `list`; false when it does not converge or the solution
// is not finite.
bool Dda3d::Impl::attempt(std::vector<Constraint>& list, Eigen::VectorXd& d, std::size_t& iterations,
                          double& numerical) const {
  for (iterations = 1; iterations <= params.max_open_close; ++iterations) {
    solve(list, d, numerical);
    if (!d.allFinite()) return false;
    bool changed = false;
    for (Constraint& k : list) {
      const Block &ba = blocks[k.a], &bb = blocks[k.b];
      const Eigen::VectorXd di = ba.dof > 0 ? Eigen::VectorXd(d.segment(static_cast<Eigen::Index>(ba.offset), ba.dof))
                                            : Eigen::VectorXd();
      const Eigen::VectorXd dj = bb.dof > 0 ? Eigen::VectorXd(d.segment(static_cast<Eigen::Index>(bb.offset), bb.dof))
                                            : Eigen::VectorXd();
      k.update = detail::evaluate_contact(k.kinematics, k.state, k.law, di, dj);
      const bool was_closed = k.state.mode != detail::ContactMode::open;
      const bool is_closed = k.update.mode != detail::ContactMode::open;
      // §4.3: the iteration converges when no contact changes between open and closed; a
      // locked/sliding change is taken over for the next iteration without forcing one.
      changed = changed || was_closed != is_closed;
      // The friction work of a sliding contact: its force times the slip, the tangential
      // relative displacement less what the spring took up elastically.
      k.slip_work = 0.0;
      if (was_closed && k.update.mode == detail::ContactMode::sliding) {
        const Eigen::Vector3d& n = k.kinematics.normal;
        const Eigen::Vector3d relative = k.kinematics.t_j * dj - k.kinematics.t_i * di;
        const Eigen::Vector3d stretch0 = k.state.shear - k.state.shear.dot(n) * n;
        const Eigen::Vector3d slip = relative - relative.dot(n) * n - (k.update.shear - stretch0);
        k.slip_work = k.update.tangential_force.norm() * slip.norm();
      }
    }
    if (!changed) {
      // The contacts' share of the integrator's dissipation (header): what the spring law
      // stores and the slip dissipates over the step, less the work of the end-of-step force
      // the scheme applies, -(U_1 - U_0) - W_slip - f_1 . Δr per constraint.
      for (const Constraint& k : list) {
        const Block &ba = blocks[k.a], &bb = blocks[k.b];
        const Eigen::VectorXd di = ba.dof > 0 ? Eigen::VectorXd(d.segment(static_cast<Eigen::Index>(ba.offset), ba.dof))
                                              : Eigen::VectorXd();
        const Eigen::VectorXd dj = bb.dof > 0 ? Eigen::VectorXd(d.segment(static_cast<Eigen::Index>(bb.offset), bb.dof))
                                              : Eigen::VectorXd();
        const Eigen::Vector3d relative = k.kinematics.t_j * dj - k.kinematics.t_i * di;
        const bool closed = k.update.mode != detail::ContactMode::open;
        const Eigen::Vector3d end_force =
            closed ? Eigen::Vector3d(k.update.normal_force * k.kinematics.normal + k.update.tangential_force)
                   : Eigen::Vector3d::Zero();
        const double end_energy =
            closed ? 0.5 * k.law.kn * k.update.gap * k.update.gap + 0.5 * k.law.kt * k.update.shear.squaredNorm() : 0.0;
        numerical += k.start_energy - end_energy - k.slip_work - end_force.dot(relative);
      }
      return true;
    }
    for (Constraint& k : list) detail::next_iteration(k.state, k.update);
  }
  return false;
}

double Dda3d::Impl::largest_displacement(const Eigen::VectorXd& d) const {
  double largest = 0.0;
  for (const Block& b : blocks) {
    if (b.dof == 0) continue;
    const auto di = d.segment(static_cast<Eigen::Index>(b.offset), b.dof);
    const detail::StepMap map = detail::step_map(b.moments.centroid, di);
    for (const ConvexPolyhedron& part : b.parts) {
      for (const Point3& x : part.vertices()) largest = std::max(largest, (vec(detail::apply(map, x)) - vec(x)).norm());
    }
  }
  return largest;
}

// Step 5: the blocks, their velocities, stresses and rotations, the contact list.
void Dda3d::Impl::accept(std::vector<Constraint> list, const Eigen::VectorXd& d, std::size_t iterations,
                         double numerical) {
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    Block& b = blocks[i];
    if (b.dof == 0) continue;
    const Eigen::VectorXd di = d.segment(static_cast<Eigen::Index>(b.offset), b.dof);
    b.velocity = 2.0 / h * di - b.velocity;
    if (b.dof == detail::dof3d) b.stress += b.elasticity * di.tail<6>();
    b.rotation = detail::accumulate_rotation(b.rotation, di.segment<3>(3));
    b.parts = detail::moved_parts(b.parts, detail::step_map(b.moments.centroid, di));
    b.moments = detail::central_moments3d(b.parts);
    b.box = box_of(b.parts);
    refresh_state(i);
  }
  for (Constraint& k : list) {
    detail::commit_step(k.state, k.update);
    friction_dissipated += k.slip_work;
  }
  numerical_dissipated += numerical;
  constraints = std::move(list);
  time += h;
  ++steps;
  last.dt = h;
  last.open_close_iterations = iterations;
  last.constraints = constraints.size();
  last.closed = static_cast<std::size_t>(std::count_if(constraints.begin(), constraints.end(), [](const Constraint& k) {
    return k.state.mode != detail::ContactMode::open;
  }));
}

void Dda3d::Impl::refresh_state(std::size_t i) {
  const Block& b = blocks[i];
  Block3dState& s = states[i];
  s.id = b.spec.id;
  s.parts = b.parts;
  s.centroid = point(b.moments.centroid);
  const Eigen::Vector3d r = detail::rotation_vector(b.rotation);
  s.rotation = {r.x(), r.y(), r.z()};
  s.velocity.assign(b.velocity.data(), b.velocity.data() + b.velocity.size());
  for (int k = 0; k < 6; ++k) s.stress[static_cast<std::size_t>(k)] = b.stress[k];
  s.volume = b.moments.volume;
  s.mass = b.mass;
  s.fixed = b.spec.fixed;
  s.rigid = b.spec.rigid;
}

Dda3d::Dda3d(std::vector<Block3dSpec> blocks, ContactLaw3d law, Dda3dParams params)
    : impl_(std::make_shared<Impl>(std::move(blocks), std::move(law), params)) {}

void Dda3d::step() {
  Impl& s = *impl_;
  const double min_dt = s.params.dt * s.params.min_dt_ratio;
  if (s.steps > 0) s.constraints = s.detect();
  const double limit = s.params.max_displacement_ratio * s.size;
  for (;;) {
    std::vector<Constraint> list = s.constraints;
    Eigen::VectorXd d;
    std::size_t iterations = 0;
    double numerical = 0.0;
    const bool converged = s.attempt(list, d, iterations, numerical);
    const double moved = converged ? s.largest_displacement(d) : 0.0;
    if (converged && moved <= limit) {
      s.accept(std::move(list), d, iterations, numerical);
      s.h = std::min(s.params.dt, step_growth * s.h);
      return;
    }
    const double next = 0.5 * s.h;
    ++s.last.cuts;
    if (next < min_dt) {
      throw Stability3dError(
          "at t = " + number(s.time) + " s the step would shrink to " + number(next) + " s, below " +
          number(min_dt) + " s: " +
          (converged ? "a vertex moves " + number(moved) + " m in a step, more than max_displacement_ratio x size = " +
                           number(limit) + " m"
                     : "the open-close iteration does not converge in " +
                           std::to_string(s.params.max_open_close) + " iterations"));
    }
    s.h = next;
  }
}

double Dda3d::time() const noexcept { return impl_->time; }
std::size_t Dda3d::steps() const noexcept { return impl_->steps; }
const std::vector<Block3dState>& Dda3d::blocks() const noexcept { return impl_->states; }
const Step3dStats& Dda3d::last_step() const noexcept { return impl_->last; }
kernel::PredicateCounters Dda3d::predicate_counters() const noexcept { return impl_->predicates; }

std::vector<Contact3dState> Dda3d::contacts() const {
  std::vector<Contact3dState> out;
  out.reserve(impl_->constraints.size());
  for (const Constraint& k : impl_->constraints) {
    Contact3dState c;
    c.block_a = k.a;
    c.block_b = k.b;
    c.point = k.geometry.point_tp;
    c.normal = k.geometry.normal;
    c.gap = k.update.gap;
    c.normal_force = k.update.normal_force;
    c.tangential_force = k.update.tangential_force.norm();
    c.mode = public_mode(k.state.mode);
    out.push_back(c);
  }
  return out;
}

Energies3d Dda3d::energies() const {
  const Impl& s = *impl_;
  Energies3d e;
  const Eigen::Vector3d g(s.params.gravity[0], s.params.gravity[1], s.params.gravity[2]);
  for (const Block& b : s.blocks) {
    if (b.dof == 0) continue;
    e.kinetic += 0.5 * b.velocity.dot(b.mass_matrix() * b.velocity);
    e.gravitational -= b.mass * g.dot(b.moments.centroid - b.reference_centroid);
    if (b.dof == detail::dof3d) {
      e.strain += 0.5 * b.moments.volume * b.stress.dot(b.elasticity.ldlt().solve(b.stress));
    }
  }
  for (const Constraint& k : s.constraints) {
    if (k.state.mode == detail::ContactMode::open) continue;
    e.contact += 0.5 * k.law.kn * k.update.gap * k.update.gap + 0.5 * k.law.kt * k.state.shear.squaredNorm();
  }
  e.friction_dissipated = s.friction_dissipated;
  e.numerical_dissipated = s.numerical_dissipated;
  return e;
}

}  // namespace rockcontact::dynamics
