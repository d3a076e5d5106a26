#define BOOST_TEST_MODULE dynamics_dda3d_contact_terms
#include <boost/test/unit_test.hpp>

// One contact constraint of the implicit 3D DDA (dynamics/dda3d/src/contact_terms3d.hpp): its
// terms against the derivatives of the energies they come from, a block resting on and pushed
// along a fixed plane against statics and the elastoplastic friction law, the mode transitions
// of Table 2, and the revised contact point of §5.1.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "../dda3d/src/contact_terms3d.hpp"

namespace {

namespace d = rockcontact::dynamics::detail;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using rockcontact::kernel::BlockRole;
using rockcontact::kernel::Point3;

const double tan30 = std::tan(std::numbers::pi / 6);

Point3 point(const Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Vector3d vec(const Point3& p) { return {p.x, p.y, p.z}; }

// The terms of one constraint as the full (n_i + n_j) matrix and load, unknowns [D_i; D_j].
struct Terms {
  MatrixXd k;
  VectorXd f;
  MatrixXd k_ii, k_jj;
};

Terms terms_of(const d::ContactKinematics3d& kin, const d::ContactState3d& state,
               const d::ContactLaw3d& law) {
  const auto ni = kin.t_i.cols(), nj = kin.t_j.cols();
  MatrixXd k_ii = MatrixXd::Zero(ni, ni), k_ij = MatrixXd::Zero(ni, nj),
           k_jj = MatrixXd::Zero(nj, nj);
  VectorXd f_i = VectorXd::Zero(ni), f_j = VectorXd::Zero(nj);
  d::add_contact_terms(kin, state, law, {k_ii, k_ij, k_jj, f_i, f_j});
  Terms out;
  out.k.resize(ni + nj, ni + nj);
  out.k << k_ii, k_ij, k_ij.transpose(), k_jj;
  out.f.resize(ni + nj);
  out.f << f_i, f_j;
  out.k_ii = k_ii;
  out.k_jj = k_jj;
  return out;
}

// ---- The energies of the header, written out again in long double ---------------------------

using Real = long double;
using RVec = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
using RVec3 = Eigen::Matrix<Real, 3, 1>;

// ½ kn d1² (closed) + ½ kt |(I - n nᵀ)(Δr + r_acc)|² (locked) + f v . Δr (sliding), at D.
Real energy(const d::ContactKinematics3d& kin, const d::ContactState3d& state,
            const d::ContactLaw3d& law, const RVec& D) {
  if (state.mode == d::ContactMode::open) return 0;
  const auto ni = kin.t_i.cols(), nj = kin.t_j.cols();
  const RVec3 dr = kin.t_j.cast<Real>() * D.tail(nj) - kin.t_i.cast<Real>() * D.head(ni);
  const RVec3 n = kin.normal.cast<Real>();
  const Eigen::Matrix<Real, 3, 3> P = Eigen::Matrix<Real, 3, 3>::Identity() - n * n.transpose();
  const Real d1 = Real(kin.gap) + n.dot(dr);
  Real e = Real(law.kn) * d1 * d1 / 2;
  if (state.mode == d::ContactMode::locked) {
    const RVec3 s = P * (dr + state.shear.cast<Real>());
    return e + Real(law.kt) * s.squaredNorm() / 2;
  }
  RVec3 v = P * state.sliding_direction.cast<Real>();
  v /= v.norm();
  const Real f = std::tan(Real(law.friction_angle_deg) * std::numbers::pi_v<Real> / 180) *
                     Real(std::max(state.normal_force, 0.0)) +
                 Real(law.cohesion) * Real(kin.area);
  return e + f * v.dot(dr);
}

// Central differences with step h = 1: for a quadratic energy they are its exact gradient and
// Hessian (no truncation error at any h), so only the rounding of the long-double energies is
// left, and h = 1 keeps that relative to the energies themselves.
void finite_differences(const d::ContactKinematics3d& kin, const d::ContactState3d& state,
                        const d::ContactLaw3d& law, MatrixXd& hessian, VectorXd& minus_gradient) {
  const auto n = kin.t_i.cols() + kin.t_j.cols();
  hessian.resize(n, n);
  minus_gradient.resize(n);
  const auto at = [&](Eigen::Index a, Real sa, Eigen::Index b, Real sb) {
    RVec D = RVec::Zero(n);
    D(a) += sa;
    D(b) += sb;
    return energy(kin, state, law, D);
  };
  for (Eigen::Index a = 0; a < n; ++a) {
    minus_gradient(a) = double(-(at(a, 1, a, 0) - at(a, -1, a, 0)) / 2);
    for (Eigen::Index b = 0; b < n; ++b) {
      hessian(a, b) =
          double((at(a, 1, b, 1) - at(a, 1, b, -1) - at(a, -1, b, 1) + at(a, -1, b, -1)) / 4);
    }
  }
}

Vector3d random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Vector3d v(normal(rng), normal(rng), normal(rng));
  return v.normalized();
}

}  // namespace

namespace rockcontact::dynamics::detail {
std::ostream& operator<<(std::ostream& out, ContactMode mode) {
  return out << (mode == ContactMode::open     ? "open"
                 : mode == ContactMode::locked ? "locked"
                                               : "sliding");
}
}  // namespace rockcontact::dynamics::detail

// Random constraints between two deformable blocks, a rigid and a deformable block (both ways),
// and against a fixed block (both sides), in each mode: K and F are the Hessian and minus the
// gradient at D = 0 of the header's energies. Scales: offsets of contact points from centroids
// up to 1 m, gaps and stretches up to 1 mm, kn = 1e9 N/m, so K ~ 1e9 and F ~ 1e6. Tolerance
// 1e-12 of the largest entry: the code's entries carry a few dozen roundings (~1e-14 of the
// largest), the long-double differences ~1e-17; a wrong sign, factor or a missing projection
// errs by O(1) of it. The blocks k_ii, k_jj are exactly symmetric (outer products of one vector
// with itself), K is positive semidefinite (eigenvalues >= -1e-12 of the largest entry, the
// eigensolver's backward error being ~n² ε of it) of rank 1 (closed, sliding) or 3 (locked).
BOOST_AUTO_TEST_CASE(terms_are_hessian_and_minus_gradient_of_the_energies) {
  const std::uint64_t seed = 20240601;
  std::cout << "terms vs energies: seed " << seed << '\n';
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::array<std::array<int, 2>, 6> dofs{
      {{12, 12}, {6, 12}, {12, 6}, {6, 6}, {0, 12}, {6, 0}}};
  d::ContactLaw3d law;
  law.kn = 1.0e9;
  law.kt = 4.0e8;
  law.friction_angle_deg = 30.0;
  law.cohesion = 1.0e5;
  for (const auto& [ni, nj] : dofs) {
    for (const d::ContactMode mode :
         {d::ContactMode::open, d::ContactMode::locked, d::ContactMode::sliding}) {
      for (int trial = 0; trial < 10; ++trial) {
        const Vector3d n = random_unit(rng);
        const Vector3d c_i(100 * unit(rng), 100 * unit(rng), 100 * unit(rng));
        const Vector3d c_j = c_i + Vector3d(2, 0, 0);
        const Vector3d p_i = c_i + Vector3d(unit(rng), unit(rng), unit(rng));
        const double d0 = 1e-3 * unit(rng);
        const Vector3d p_j = p_i + d0 * n;
        const d::ContactKinematics3d kin = d::contact_kinematics(
            {point(p_i), point(c_i), ni}, {point(p_j), point(c_j), nj}, point(n), 0.01);
        BOOST_TEST(kin.t_i.cols() == ni);
        BOOST_TEST(kin.t_j.cols() == nj);
        // Forming p_j ~ 100 m rounds each coordinate by up to 7e-15 m (half an ulp of 128),
        // which the dot with the unit normal turns into at most √3 times that.
        BOOST_TEST(std::fabs(kin.gap - d0) <= 2e-14);
        d::ContactState3d state;
        state.mode = mode;
        state.shear = 1e-3 * Vector3d(unit(rng), unit(rng), unit(rng));  // not tangent: projected
        state.normal_force = 1e6 * unit(rng);        // negative: tension, no friction from it
        state.sliding_direction = random_unit(rng);  // neither tangent nor unit once projected
        const Terms t = terms_of(kin, state, law);
        MatrixXd hessian;
        VectorXd minus_gradient;
        finite_differences(kin, state, law, hessian, minus_gradient);
        if (mode == d::ContactMode::open) {
          BOOST_TEST(t.k.isZero(0.0));
          BOOST_TEST(t.f.isZero(0.0));
          BOOST_TEST(hessian.isZero(0.0));
          continue;
        }
        const double k_scale = hessian.cwiseAbs().maxCoeff();
        const double f_scale = minus_gradient.cwiseAbs().maxCoeff();
        BOOST_TEST((t.k - hessian).cwiseAbs().maxCoeff() <= 1e-12 * k_scale);
        BOOST_TEST((t.f - minus_gradient).cwiseAbs().maxCoeff() <= 1e-12 * f_scale);
        BOOST_TEST((t.k_ii - t.k_ii.transpose()).isZero(0.0));
        BOOST_TEST((t.k_jj - t.k_jj.transpose()).isZero(0.0));
        const VectorXd eigen = Eigen::SelfAdjointEigenSolver<MatrixXd>(t.k).eigenvalues();
        BOOST_TEST(eigen.minCoeff() >= -1e-12 * k_scale);
        const auto rank = (eigen.array() > 1e-9 * k_scale).count();
        BOOST_TEST(rank == (mode == d::ContactMode::locked ? 3 : 1));
      }
    }
  }
}

namespace {

// A rigid a x b x h box of density rho resting with its bottom face on the plane z = c.z - h/2,
// one vertex-face constraint at each bottom corner, the plane a fixed block (or a slab whose
// four contact points lie at level = 0, in the plane of its centroid). The box is tp (the
// plane cp, normal +z) or cp (the plane tp, normal -z). Small displacements: contact points and
// normals stay those of the start, only the gaps follow the box.
struct Box {
  double a = 2.0, b = 1.0, h = 0.5, rho = 2500.0, g = 9.81;
  Vector3d centroid{10.0, -5.0, 3.25};
  double level = -0.25;  // the contact points' height above the centroid, m
  BlockRole role = BlockRole::tp;
  d::ContactLaw3d law;
  std::vector<d::ContactKinematics3d> contacts;
  std::vector<d::ContactState3d> states;

  double mass() const { return rho * a * b * h; }
  Eigen::Matrix<double, 6, 6> mass_matrix() const {
    const double m = mass();
    Eigen::Matrix<double, 6, 1> diagonal;
    diagonal << m, m, m, m * (b * b + h * h) / 12, m * (a * a + h * h) / 12,
        m * (a * a + b * b) / 12;
    return diagonal.asDiagonal();
  }
  Vector3d corner(int k) const {
    return centroid + Vector3d((k & 1 ? 0.5 : -0.5) * a, (k & 2 ? 0.5 : -0.5) * b, level);
  }
  // The sign taking a force on j, or a displacement of j relative to i, to the box's.
  double on_box() const { return role == BlockRole::tp ? 1.0 : -1.0; }

  void place(double gap, d::ContactMode mode, double normal_force) {
    contacts.clear();
    states.assign(4, {});
    for (int k = 0; k < 4; ++k) {
      const Vector3d p = corner(k);
      const d::ContactSide3d box{point(p), point(centroid), d::rigid_dof3d};
      const d::ContactSide3d plane{point(p), point(p), 0};
      const Vector3d n(0, 0, on_box());
      contacts.push_back(role == BlockRole::tp ? d::contact_kinematics(plane, box, point(n), 0.0)
                                               : d::contact_kinematics(box, plane, point(n), 0.0));
      contacts.back().gap = gap;
      states[k].mode = mode;
      states[k].normal_force = normal_force;
    }
  }
  // A point load on the box (N) at x: T(x - c)ᵀ force.
  VectorXd load_at(const Vector3d& x, const Vector3d& force) const {
    return d::displacement_matrix(point(x - centroid)).leftCols(d::rigid_dof3d).transpose() * force;
  }
  VectorXd gravity() const { return load_at(centroid, Vector3d(0, 0, -mass() * g)); }
};

struct StepResult {
  VectorXd d;
  std::vector<d::ContactUpdate3d> updates;
  int iterations = 0;
};

// One step of the static analysis (velocities reset, so the load has no inertia term):
// open-close iterations of (2M/dt² + K_contact) D = F + F_contact until no mode changes, then
// the states committed and the gaps moved to d1.
StepResult static_step(Box& box, const VectorXd& load, double dt) {
  const VectorXd none(0);
  StepResult out;
  for (out.iterations = 1; out.iterations <= 10; ++out.iterations) {
    MatrixXd k = 2.0 / (dt * dt) * box.mass_matrix();
    VectorXd f = load;
    MatrixXd empty(0, 0), empty_ij(0, d::rigid_dof3d), empty_ji(d::rigid_dof3d, 0);
    VectorXd empty_f(0);
    for (std::size_t c = 0; c < box.contacts.size(); ++c) {
      if (box.role == BlockRole::tp) {
        d::add_contact_terms(box.contacts[c], box.states[c], box.law,
                             {empty, empty_ij, k, empty_f, f});
      } else {
        d::add_contact_terms(box.contacts[c], box.states[c], box.law,
                             {k, empty_ji, empty, f, empty_f});
      }
    }
    out.d = k.ldlt().solve(f);
    out.updates.clear();
    bool changed = false;
    for (std::size_t c = 0; c < box.contacts.size(); ++c) {
      const VectorXd& d_i = box.role == BlockRole::cp ? out.d : none;
      const VectorXd& d_j = box.role == BlockRole::tp ? out.d : none;
      out.updates.push_back(d::evaluate_contact(box.contacts[c], box.states[c], box.law, d_i, d_j));
      changed = changed || out.updates.back().mode != box.states[c].mode;
    }
    if (!changed) {
      for (std::size_t c = 0; c < box.contacts.size(); ++c) {
        d::commit_step(box.states[c], out.updates[c]);
        box.contacts[c].gap = out.updates[c].gap;
      }
      return out;
    }
    for (std::size_t c = 0; c < box.contacts.size(); ++c)
      d::next_iteration(box.states[c], out.updates[c]);
  }
  throw std::runtime_error("the open-close iteration did not converge in 10 iterations");
}

// Static steps until the step's increment is below `small` (m or rad); returns the total.
VectorXd settle(Box& box, const VectorXd& load, double dt, double small) {
  VectorXd total = VectorXd::Zero(d::rigid_dof3d);
  for (int step = 0; step < 400; ++step) {
    const VectorXd d = static_step(box, load, dt).d;
    total += d;
    if (d.cwiseAbs().maxCoeff() <= small) return total;
  }
  throw std::runtime_error("the static analysis did not settle in 400 steps");
}

Box resting_box(BlockRole role) {
  Box box;
  box.role = role;
  box.law.kn = 1.0e9;
  box.law.kt = 4.0e8;
  box.law.friction_angle_deg = 30.0;
  return box;
}

}  // namespace

// A box (2 x 1 x 0.5 m, 2500 kg) set on a fixed plane, touching (gap 0, locked) at its four
// bottom corners, under gravity: the static analysis settles at the penetration m g / (4 kn) =
// 6.13e-6 m at each corner, without rotation or horizontal motion. Then a vertical point load
// P off the centre (ex, ey) = (0.3, -0.2) m: a rigid plate on four equal springs at (±a/2, ±b/2)
// carries f_k = (m g + P)/4 + P ex x_k / a² + P ey y_k / b² at each corner (the corner forces
// balance the load and its moments about both axes; x_k = ±a/2, so Σ x_k² = a²). dt = 0.01 s:
// each static step leaves (2m/dt²)/(2m/dt² + 4 kn) ~ 1.2% of the remaining error, and the steps
// run until the increment is below 1e-20 m. Tolerance 1e-10 of the penetration: what is left is
// the rounding of the solves (conditioning ~1e2, ~1e-14) and of the summed increments; a spring
// too many, a wrong stiffness or a moment arm errs by O(1).
BOOST_AUTO_TEST_CASE(box_on_a_plane_settles_at_the_static_penetration) {
  for (const BlockRole role : {BlockRole::tp, BlockRole::cp}) {
    Box box = resting_box(role);
    box.place(0.0, d::ContactMode::locked, 0.0);
    const double dt = 0.01, m = box.mass(), kn = box.law.kn;
    const double penetration = m * box.g / (4 * kn);
    const VectorXd total = settle(box, box.gravity(), dt, 1e-20);
    for (int k = 0; k < 4; ++k) {
      BOOST_TEST(box.states[k].mode == d::ContactMode::locked);
      BOOST_TEST(std::fabs(box.contacts[k].gap + penetration) <= 1e-10 * penetration);
      BOOST_TEST(std::fabs(box.states[k].normal_force - m * box.g / 4) <= 1e-10 * m * box.g);
    }
    // Every corner sank by the same amount: rotation none (a tilt that would move a corner by
    // 1e-10 of the penetration at 1 m), nor any horizontal motion.
    BOOST_TEST(std::fabs(total(2) + penetration) <= 1e-10 * penetration);
    BOOST_TEST(total.segment(3, 3).cwiseAbs().maxCoeff() <= 1e-10 * penetration);
    BOOST_TEST(total.head(2).cwiseAbs().maxCoeff() <= 1e-10 * penetration);

    const double P = 1.0e4, ex = 0.3, ey = -0.2;
    const Vector3d at = box.centroid + Vector3d(ex, ey, box.h / 2);
    settle(box, box.gravity() + box.load_at(at, Vector3d(0, 0, -P)), dt, 1e-20);
    for (int k = 0; k < 4; ++k) {
      const Vector3d x = box.corner(k) - box.centroid;
      const double f =
          (m * box.g + P) / 4 + P * ex * x.x() / (box.a * box.a) + P * ey * x.y() / (box.b * box.b);
      BOOST_TEST(std::fabs(box.states[k].normal_force - f) <= 1e-10 * f);
      BOOST_TEST(std::fabs(box.contacts[k].gap + f / kn) <= 1e-10 * f / kn);
    }
  }
}

// A slab resting on its four contact points (each at the penetration m g / (4 kn), fn = m g / 4),
// then pushed along q = (cos 30°, sin 30°, 0) by Q at its centroid. The contact points lie in the
// plane of the centroid, so neither Q nor the unbalanced friction of a dynamic step tips the
// slab (a box would rock on its corners and share the normal force unequally: the rocking is not
// what is checked here). φ = 30°, kt = 4e8 N/m at each contact.
//  * Q = ½ tan φ m g, below the Coulomb limit: it settles locked, each contact carrying Q/4
//    back on the slab, equal to kt times the slab's displacement Q / (4 kt).
//  * Q = 2 tan φ m g (dynamic steps of dt = 1 ms from rest, no velocity kept): after the springs
//    reach the cap every contact slides, its friction force on the slab exactly tan φ fn against q
//    with the stretch at the cap tan φ fn / kt, and each step moves the slab by
//    (Q - tan φ m g) / (2m/dt²): the friction load of eq. 32.
//  * Released (Q = 0): the friction load alone would carry the slab back by tan φ m g / (2m/dt²),
//    less than the cap, so the contacts lock, and the kept stretch unloads: the slab moves back
//    by tan φ m g / (2m/dt² + 4 kt) and the stretch is the cap less that (a reset spring would
//    hold the negative of it). Left to settle, the slab recovers only the cap: what it slid
//    beyond the cap is permanent.
// Tolerances: 1e-10 relative (the solves' rounding, as above); the friction magnitude against
// tan φ fn, both computed from the same fn, 1e-13 (a few roundings of the return mapping).
BOOST_AUTO_TEST_CASE(slab_pushed_along_a_plane_locks_slides_and_keeps_its_stretch) {
  for (const BlockRole role : {BlockRole::tp, BlockRole::cp}) {
    Box box = resting_box(role);
    const double m = box.mass(), g = box.g, kn = box.law.kn, kt = box.law.kt;
    const Vector3d q(std::cos(std::numbers::pi / 6), std::sin(std::numbers::pi / 6), 0);
    box.level = 0.0;
    const Vector3d base = box.centroid;
    const double s = box.on_box();  // the box's relative displacement is s times Δr

    box.place(-m * g / (4 * kn), d::ContactMode::locked, m * g / 4);
    const double Q_low = 0.5 * tan30 * m * g;
    const VectorXd moved = settle(box, box.gravity() + box.load_at(base, Q_low * q), 0.01, 1e-20);
    BOOST_TEST((moved.head(3) - Q_low / (4 * kt) * q).norm() <= 1e-10 * Q_low / (4 * kt));
    const StepResult still = static_step(box, box.gravity() + box.load_at(base, Q_low * q), 0.01);
    for (int k = 0; k < 4; ++k) {
      BOOST_TEST(still.updates[k].mode == d::ContactMode::locked);
      const Vector3d on_box = s * still.updates[k].tangential_force;
      BOOST_TEST((on_box + Q_low / 4 * q).norm() <= 1e-10 * Q_low);
      BOOST_TEST((on_box + kt * moved.head(3)).norm() <= 1e-10 * Q_low);
    }

    box.place(-m * g / (4 * kn), d::ContactMode::locked, m * g / 4);
    const double dt = 1e-3, inertia = 2 * m / (dt * dt);
    const double Q = 2 * tan30 * m * g;
    const VectorXd push = box.gravity() + box.load_at(base, Q * q);
    int steps = 0;
    while (box.states[0].mode != d::ContactMode::sliding && steps < 20) {
      static_step(box, push, dt);
      ++steps;
    }
    BOOST_TEST_REQUIRE(steps < 20);
    Vector3d at_last_push = Vector3d::Zero();
    for (int step = 0; step < 3; ++step) {
      const StepResult r = static_step(box, push, dt);
      BOOST_TEST((r.d.head(3) - (Q - tan30 * m * g) / inertia * q).norm() <=
                 1e-10 * (Q - tan30 * m * g) / inertia);
      for (int k = 0; k < 4; ++k) {
        const d::ContactUpdate3d& u = r.updates[k];
        BOOST_TEST(u.mode == d::ContactMode::sliding);
        const double fn = u.normal_force;
        BOOST_TEST(std::fabs(fn - m * g / 4) <= 1e-10 * m * g);
        const Vector3d on_box = s * u.tangential_force;
        BOOST_TEST((on_box + tan30 * fn * q).norm() <= 1e-13 * tan30 * fn);
        BOOST_TEST((s * u.shear - tan30 * fn / kt * q).norm() <= 1e-13 * tan30 * fn / kt);
      }
      at_last_push = s * box.states[0].shear;
    }

    const double cap = tan30 * m * g / (4 * kt);
    const StepResult back = static_step(box, box.gravity(), dt);
    BOOST_TEST(back.iterations == 2);  // sliding -> locked, then confirmed
    const double back_by = tan30 * m * g / (inertia + 4 * kt);
    BOOST_TEST((back.d.head(3) + back_by * q).norm() <= 1e-10 * back_by);
    for (int k = 0; k < 4; ++k) {
      BOOST_TEST(back.updates[k].mode == d::ContactMode::locked);
      BOOST_TEST((s * back.updates[k].shear - (cap - back_by) * q).norm() <= 1e-10 * cap);
      BOOST_TEST((s * back.updates[k].tangential_force + kt * (cap - back_by) * q).norm() <=
                 1e-10 * kt * cap);
    }
    BOOST_TEST((at_last_push - cap * q).norm() <= 1e-10 * cap);
    const VectorXd recovered = back.d + settle(box, box.gravity(), dt, 1e-20);
    BOOST_TEST((recovered.head(3) + cap * q).norm() <= 1e-10 * cap);
    BOOST_TEST(box.states[0].mode == d::ContactMode::locked);
    BOOST_TEST(box.states[0].shear.norm() <= 1e-10 * cap);
  }
}

namespace {

// One constraint: a fixed plane z = 0 (cp) and a rigid block (tp) whose centroid is 1 m above
// its contact point, moved by a translation; normal +z, gap d0, contact area 0.01 m².
struct Single {
  d::ContactKinematics3d kin;
  d::ContactLaw3d law;
  d::ContactState3d state;

  explicit Single(double d0) {
    const Point3 p{0.3, -0.2, d0};
    kin = d::contact_kinematics({{0.3, -0.2, 0.0}, {0, 0, 0}, 0},
                                {p, {0.3, -0.2, d0 + 1}, d::rigid_dof3d}, {0, 0, 1}, 0.01);
    law.kn = 1.0e9;
    law.kt = 1.0e8;
    law.friction_angle_deg = 30.0;
  }
  d::ContactUpdate3d move(const Vector3d& translation) const {
    VectorXd d_j = VectorXd::Zero(d::rigid_dof3d);
    d_j.head(3) = translation;
    return d::evaluate_contact(kin, state, law, VectorXd(0), d_j);
  }
};

// Values below are a handful of roundings away from the closed forms: 1e-12 relative.
bool close(double x, double y) { return std::fabs(x - y) <= 1e-12 * std::fabs(y); }
bool close(const Vector3d& x, const Vector3d& y) { return (x - y).norm() <= 1e-12 * y.norm(); }

}  // namespace

// Open <-> closed (Table 2): an open contact closes, locked, when the step ends in penetration,
// with the normal force of that penetration and its spring still to come; it stays open when the
// step ends apart. A closed one opens when it ends apart, dropping its stretch, unless its
// tension kn d1 is within the tensile strength σt A.
BOOST_AUTO_TEST_CASE(open_and_closed) {
  Single c(1e-3);
  c.state.sliding_direction = Vector3d(0, 1, 0);
  d::ContactUpdate3d u = c.move({1e-4, 0, -3e-3});
  BOOST_TEST(u.mode == d::ContactMode::locked);
  BOOST_TEST(close(u.gap, -2e-3));
  BOOST_TEST(close(u.normal_force, 2e6));
  BOOST_TEST(u.tangential_force.isZero(0.0));
  BOOST_TEST(u.shear.isZero(0.0));
  BOOST_TEST(close(u.sliding_direction, Vector3d(1, 0, 0)));  // eq. 8: this iteration's motion

  u = c.move({0, 0, -0.5e-3});
  BOOST_TEST(u.mode == d::ContactMode::open);
  BOOST_TEST(close(u.gap, 0.5e-3));
  BOOST_TEST(u.normal_force == 0.0);
  BOOST_TEST(close(u.sliding_direction, Vector3d(0, 1, 0)));  // no tangential motion: kept

  Single closed(-1e-4);
  closed.state.mode = d::ContactMode::locked;
  closed.state.shear = Vector3d(1e-5, 0, 0);
  u = closed.move({0, 0, 2e-4});  // ends 0.1 mm apart: a tension of kn 1e-4 = 1e5 N
  BOOST_TEST(u.mode == d::ContactMode::open);
  BOOST_TEST(u.normal_force == 0.0);
  BOOST_TEST(u.shear.isZero(0.0));
  BOOST_TEST(u.tangential_force.isZero(0.0));
  closed.law.tensile_strength = 1.5e5 / 0.01;  // holds 1.5e5 N over 0.01 m²
  u = closed.move({0, 0, 2e-4});
  BOOST_TEST(close(u.normal_force, -1e5));
  // In tension the limit is c A only (here 0): the stretch slides, and no friction is left.
  BOOST_TEST(u.mode == d::ContactMode::sliding);
  BOOST_TEST(u.tangential_force.isZero(0.0));
  closed.state.mode = d::ContactMode::sliding;
  closed.law.tensile_strength = 0.5e5 / 0.01;
  BOOST_TEST(closed.move({0, 0, 2e-4}).mode == d::ContactMode::open);
  BOOST_TEST(closed.move({0, 0, 0.5e-4}).mode != d::ContactMode::open);  // still penetrating
}

// A constraint born inside an overlap (offset = its gap at birth, -1 mm): its normal spring acts
// on d - offset, so at the birth gap it carries no force and stays closed, 0.5 mm deeper it
// pushes with kn 0.5e-3 = 5e5 N; it opens once back above the birth gap, and an open one with
// that offset closes only below it. spring_energy is ½ kn (d - offset)² (plus the shear's).
BOOST_AUTO_TEST_CASE(offset_spring_resists_only_further_penetration) {
  Single c(-1e-3);
  c.state.mode = d::ContactMode::locked;
  c.state.offset = -1e-3;
  d::ContactUpdate3d u = c.move({0, 0, 0});
  BOOST_TEST(u.mode != d::ContactMode::open);
  BOOST_TEST(u.normal_force == 0.0);
  u = c.move({0, 0, -0.5e-3});
  BOOST_TEST(u.mode != d::ContactMode::open);
  BOOST_TEST(close(u.normal_force, 5e5));
  BOOST_TEST(std::fabs(d::spring_energy(c.law, u.mode, c.state.offset, u.gap, Vector3d::Zero()) - 0.5 * 1e9 * 0.25e-6) <=
             1e-9 * 125.0);
  BOOST_TEST(c.move({0, 0, 0.2e-3}).mode == d::ContactMode::open);
  c.state.mode = d::ContactMode::open;
  BOOST_TEST(c.move({0, 0, -0.1e-3}).mode == d::ContactMode::locked);
  BOOST_TEST(c.move({0, 0, 0.1e-3}).mode == d::ContactMode::open);
  // The terms: the spring's load is kn (d0 - offset) = 0 here, so no load from the normal spring.
  c.state.mode = d::ContactMode::locked;
  const Terms t = terms_of(c.kin, c.state, c.law);
  BOOST_TEST(t.f.norm() <= 1e-9);
}

// Such a constraint that opens short of its birth gap (back above -1 mm, still 0.8 mm into the
// other block) ends the step open with that penetration as its offset (commit_step): at the
// next step it stays open at -0.8 mm and closes only deeper, 0.1 mm deeper pushing with
// kn 1e-4 = 1e5 N. With the offset dropped to 0 it would close at once with kn 0.8e-3 = 8e5 N
// and 320 J in its spring, energy no force had worked for.
BOOST_AUTO_TEST_CASE(an_open_contact_keeps_its_penetration_as_offset) {
  Single c(-1e-3);
  c.state.mode = d::ContactMode::locked;
  c.state.offset = -1e-3;
  const d::ContactUpdate3d opened = c.move({0, 0, 0.2e-3});
  BOOST_TEST(opened.mode == d::ContactMode::open);
  BOOST_TEST(close(opened.gap, -0.8e-3));
  d::commit_step(c.state, opened);
  BOOST_TEST(close(c.state.offset, -0.8e-3));
  Single next(-0.8e-3);
  next.state = c.state;
  BOOST_TEST(next.move({0, 0, 0}).mode == d::ContactMode::open);
  const d::ContactUpdate3d deeper = next.move({0, 0, -0.1e-3});
  BOOST_TEST(deeper.mode == d::ContactMode::locked);
  BOOST_TEST(close(deeper.normal_force, 1e5));
  // Apart, the offset is 0 again.
  d::commit_step(c.state, c.move({0, 0, 1.5e-3}));
  BOOST_TEST(c.state.offset == 0.0);
}

// Locked <-> sliding: fn = kn 1e-4 = 1e5 N, tan φ fn = 57 735 N, cap = tan φ fn / kt = 0.577 mm.
// A stretch under the cap stays locked with kt times it; over the cap it slides with the
// stretch held at the cap and the force tan φ fn (+ c A with a cohesion). A sliding contact
// whose slip reverses locks again with the stretch the cap less the reversal; one that goes on
// slides on. The normal part of a stored stretch is ignored.
BOOST_AUTO_TEST_CASE(locked_and_sliding) {
  Single c(-1e-4);
  c.state.mode = d::ContactMode::locked;
  const double fn = 1e5, limit = tan30 * fn, cap = limit / c.law.kt;
  c.state.shear = Vector3d(0.1e-3, 0, 0.7);  // tangential part 0.1 mm along x
  d::ContactUpdate3d u = c.move({0.3e-3, 0, 0});
  BOOST_TEST(u.mode == d::ContactMode::locked);
  BOOST_TEST(close(u.normal_force, fn));
  BOOST_TEST(close(u.shear, Vector3d(0.4e-3, 0, 0)));
  BOOST_TEST(close(u.tangential_force, Vector3d(-c.law.kt * 0.4e-3, 0, 0)));

  u = c.move({0.3e-3, 0.4e-3, 0});  // stretch (0.4, 0.4) mm, 0.566 mm: under the cap
  BOOST_TEST(u.mode == d::ContactMode::locked);
  u = c.move({0.6e-3, 0.4e-3, 0});  // stretch (0.7, 0.4) mm, 0.806 mm: over it
  BOOST_TEST(u.mode == d::ContactMode::sliding);
  const Vector3d along = Vector3d(0.7, 0.4, 0).normalized();
  BOOST_TEST(close(u.shear, cap * along));
  BOOST_TEST(close(u.tangential_force, -limit * along));
  BOOST_TEST(close(u.sliding_direction, along));

  c.law.cohesion = 2e6;  // c A = 2e4 N
  u = c.move({0.6e-3, 0.4e-3, 0});
  BOOST_TEST(u.mode == d::ContactMode::sliding);
  BOOST_TEST(close(u.tangential_force.norm(), limit + 2e4));
  c.law.cohesion = 0.0;

  Single s(-1e-4);
  s.state.mode = d::ContactMode::sliding;
  s.state.shear = Vector3d(cap, 0, 0);
  s.state.sliding_direction = Vector3d(1, 0, 0);
  u = s.move({0.1e-3, 0, 0});
  BOOST_TEST(u.mode == d::ContactMode::sliding);
  BOOST_TEST(close(u.shear, Vector3d(cap, 0, 0)));
  u = s.move({-0.2e-3, 0, 0});
  BOOST_TEST(u.mode == d::ContactMode::locked);
  BOOST_TEST(close(u.shear, Vector3d(cap - 0.2e-3, 0, 0)));  // kept: a reset would give -0.2 mm
  BOOST_TEST(close(u.tangential_force, Vector3d(-c.law.kt * (cap - 0.2e-3), 0, 0)));

  // The iteration and step records: the stretch moves only at the end of the step.
  d::ContactState3d state = s.state;
  d::next_iteration(state, u);
  BOOST_TEST(state.mode == d::ContactMode::locked);
  BOOST_TEST(state.shear == Vector3d(cap, 0, 0));
  BOOST_TEST(state.normal_force == u.normal_force);
  d::commit_step(state, u);
  BOOST_TEST(state.shear == u.shear);
}

namespace {

// The blocks' translations over a step for the §5.1 tests: u_cp at random, and u_tp with a
// tangential part and a normal part that ends the step 0.02 to 1.02 m past a contact d0 apart.
std::pair<Vector3d, Vector3d> closing_motion(std::mt19937_64& rng, const Vector3d& n, double d0) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Vector3d u_cp(unit(rng), unit(rng), unit(rng));
  const Vector3d w(unit(rng), unit(rng), unit(rng));
  return {u_cp, u_cp + w - w.dot(n) * n - (d0 + 0.02 + 0.5 * (unit(rng) + 1)) * n};
}

// What every §5.1 revision keeps (to 1e-14 m, a few roundings of ~1 m inputs): the crossing is
// within the step, the revised points meet at it, the gap is d0, and the stretch the spring
// starts from leaves (1 - t) of the tangential motion in it at the end of the step.
void check_revision(const d::RevisedContact3d& r, const Vector3d& u_cp, const Vector3d& u_tp, const Vector3d& n,
                    double d0) {
  const double t = r.fraction;
  BOOST_TEST(t > 0.0);
  BOOST_TEST(t < 1.0);
  const Vector3d q_cp = vec(r.point_cp), q_tp = vec(r.point_tp);
  BOOST_TEST(((q_tp + t * u_tp) - (q_cp + t * u_cp)).norm() <= 1e-14);
  BOOST_TEST(std::fabs((q_tp - q_cp).dot(n) - d0) <= 1e-14);
  const Vector3d relative = u_tp - u_cp;
  const Vector3d tangential_motion = relative - relative.dot(n) * n;
  BOOST_TEST((r.shear + tangential_motion - (1 - t) * tangential_motion).norm() <= 1e-14);
  BOOST_TEST(std::fabs(r.shear.dot(n)) <= 1e-14);
}

}  // namespace

// §5.1 on a vertex crossing a tilted face while both blocks translate (a linear relative motion):
// the revised face point lies on the face's plane at the start, the vertex meets that material
// point of the face block at the fraction t of the step, and the gap does not change; the
// stretch starts at the tangential offset, so the step's motion leaves (1 - t) of its tangential
// part in the spring, the motion after the crossing. Either block may own the vertex. Inputs
// are ~1 m, so 1e-14 m is a few roundings.
BOOST_AUTO_TEST_CASE(revised_point_is_the_crossing_point) {
  const std::uint64_t seed = 7;
  std::cout << "revision: seed " << seed << '\n';
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const BlockRole vertex : {BlockRole::cp, BlockRole::tp}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Vector3d n = random_unit(rng);
      const double d0 = 0.05 + 0.2 * (unit(rng) + 1);
      const Vector3d face(unit(rng), unit(rng), unit(rng));
      // The face point is the vertex's projection on the face's plane.
      const Vector3d p_cp = vertex == BlockRole::cp ? face - d0 * n : face;
      const Vector3d p_tp = vertex == BlockRole::cp ? face : face + d0 * n;
      const auto [u_cp, u_tp] = closing_motion(rng, n, d0);
      const auto r = d::revise_vertex_face(point(p_cp), point(p_tp), n, vertex, u_tp - u_cp);
      BOOST_TEST_REQUIRE(r.has_value());
      check_revision(*r, u_cp, u_tp, n, d0);
      const Vector3d q_cp = vec(r->point_cp), q_tp = vec(r->point_tp);
      const Vector3d vertex_point = vertex == BlockRole::cp ? q_cp : q_tp;
      const Vector3d face_point = vertex == BlockRole::cp ? q_tp : q_cp;
      BOOST_TEST((vertex_point - (vertex == BlockRole::cp ? p_cp : p_tp)).norm() == 0.0);
      BOOST_TEST(std::fabs((face_point - face).dot(n)) <= 1e-14);
    }
  }
  const Vector3d n(0, 0, 1);
  // Not a crossing: the step ends apart, or it began penetrating.
  BOOST_TEST(
      !d::revise_vertex_face({0, 0, 0}, {0, 0, 0.1}, n, BlockRole::cp, {0, 0, -0.05}).has_value());
  BOOST_TEST(
      !d::revise_vertex_face({0, 0, 0}, {0, 0, -0.1}, n, BlockRole::cp, {0, 0, -0.05}).has_value());
  // Touching at the start: the crossing is at t = 0, the points stay.
  const auto touch = d::revise_vertex_face({1, 2, 3}, {1, 2, 3}, n, BlockRole::tp, {0.5, 0, -0.05});
  BOOST_TEST_REQUIRE(touch.has_value());
  BOOST_TEST(touch->fraction == 0.0);
  BOOST_TEST((vec(touch->point_cp) - Vector3d(1, 2, 3)).norm() == 0.0);
}

// §5.1 eq. 44-46 on random crossings: two edges through p_cp (cp) and p_tp = p_cp + d0 n (tp),
// n = e_cp x e_tp, the blocks translating so that the step ends 0.02 to 1.02 m deep. The revised
// points are material points of each edge (on its line) that meet at the fraction t, with the
// gap d0 kept, and the spring's stretch at the end is (1 - t) P Δr. Same scale as above: 1e-14 m.
BOOST_AUTO_TEST_CASE(revised_crossing_is_where_the_edges_meet) {
  const std::uint64_t seed = 11;
  std::cout << "crossing revision: seed " << seed << '\n';
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const Vector3d e_cp = random_unit(rng);
    Vector3d e_tp = random_unit(rng);
    if (e_cp.cross(e_tp).norm() < 0.1) continue;  // the engine drops nearly parallel crossings
    const Vector3d n = e_cp.cross(e_tp).normalized();
    const double d0 = 0.05 + 0.2 * (unit(rng) + 1);
    const Vector3d p_cp(unit(rng), unit(rng), unit(rng));
    const Vector3d p_tp = p_cp + d0 * n;
    const auto [u_cp, u_tp] = closing_motion(rng, n, d0);
    const auto r = d::revise_edge_edge(point(p_cp), point(p_tp), n, e_cp, e_tp, u_tp - u_cp);
    BOOST_TEST_REQUIRE(r.has_value());
    check_revision(*r, u_cp, u_tp, n, d0);
    BOOST_TEST((vec(r->point_cp) - p_cp).cross(e_cp).norm() <= 1e-14);
    BOOST_TEST((vec(r->point_tp) - p_tp).cross(e_tp).norm() <= 1e-14);
  }
  const Vector3d n(0, 0, 1), x(1, 0, 0), y(0, 1, 0);
  // Not a crossing: the step ends apart; parallel edges.
  BOOST_TEST(!d::revise_edge_edge({0, 0, 0}, {0, 0, 0.1}, n, x, y, {0, 0, -0.05}).has_value());
  BOOST_TEST(!d::revise_edge_edge({0, 0, 0}, {0, 0, 0.1}, n, x, x, {0.3, 0, -0.2}).has_value());
}

BOOST_AUTO_TEST_CASE(bad_laws_are_refused_naming_the_field) {
  const auto message = [](d::ContactLaw3d law) -> std::string {
    try {
      d::check_contact_law3d(law);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  BOOST_TEST(message(d::default_contact_law3d()).empty());
  d::ContactLaw3d law;
  law.kn = 0.0;
  BOOST_TEST(message(law).find("kn must be finite and > 0") != std::string::npos);
  law = {};
  law.friction_angle_deg = 90.0;
  BOOST_TEST(message(law).find("friction_angle_deg") != std::string::npos);
  law = {};
  law.tensile_strength = -1.0;
  BOOST_TEST(message(law).find("tensile_strength") != std::string::npos);
}
