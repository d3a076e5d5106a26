#pragma once
// What one contact constraint contributes to the global equilibrium equation of the implicit 3D
// DDA, and its contact mode (seed 001 §2.4, §3.2-§3.5, §4.3, §5.1). Private to dynamics/dda3d;
// Eigen-typed, so the engine scatters the dense blocks into its sparse matrix.
//
// A constraint joins block i (the kernel's cp) and block j (tp) at the contact points p_i, p_j
// of the start of the step, with the unit normal n from i towards j, constant over the step
// (§3.1), and the initial gap d0 = (p_j - p_i) . n (negative = penetration; eq. 20). With
// T_i = T(p_i - c_i), T_j = T(p_j - c_j) (block_matrices3d.hpp, eq. 10-12; 3 x 12, 3 x 6 for a
// rigid block, 3 x 0 for a fixed block, which has no unknowns) and the step's increments D_i, D_j:
//   Δr = T_j D_j - T_i D_i                                  relative displacement (eq. 14-15)
//   d1 = d0 + n . Δr                                        gap at the end of the step (eq. 21)
// and the total potential energy of eq. 13 gains, by mode:
//   closed (locked or sliding)  ½ kn (d1 - offset)²                                (eq. 22-24)
//   locked                      ½ kt |P (Δr + r_acc)|²,  P = I - n nᵀ               (eq. 25-29)
//   sliding                     f v . Δr,  f = tan φ fn* + c A,  v = unit(P v*)     (eq. 30-32)
// with r_acc the spring's accumulated tangential stretch (of p_j relative to p_i) carried from the
// previous steps, fn* the normal force of the previous iteration (-kn d*, compression > 0; in
// the first iteration of a step that of the last step, -kn d0 for points that follow the blocks;
// offset the state's, normally 0)
// and v* the assumed sliding direction of p_j relative to p_i (§2.3). A spring along a unit
// direction e with offset s0 (d0 for the normal, t . r_acc for each vector t of a tangent
// basis) has the energy ½ k (s0 + eᵀ Δr)², so with g_i = T_iᵀ e and g_j = T_jᵀ e it adds
//   K_ii += k g_i g_iᵀ, K_ij -= k g_i g_jᵀ, K_jj += k g_j g_jᵀ, F_i += k s0 g_i, F_j -= k s0 g_j
// (K_ji = K_ijᵀ): the Hessian and the negative gradient at D = 0. The friction term is a load
// only (F_i += f T_iᵀ v, F_j -= f T_jᵀ v), so K stays symmetric positive semidefinite (§3.5).
//
// The mode after a solve (Table 2, §2.4 method 3; the table itself was lost in the text of the
// seed and is rebuilt from the prose and the open-close check of Shi's DDA):
//   open   -> closed (locked) when d1 < offset - tol, the spring then enters the next iteration;
//   closed -> open when the normal spring's tension kn (d1 - offset) exceeds the tensile
//             strength σt A + kn tol (with σt = 0: when d1 > offset + tol);
// tol = ContactLaw3d::gap_tolerance, a hysteresis (0 in the steps; the initial equilibrium's
// static solve uses 1e-9 of the scene's size) so that a contact at exact touch carrying no load
// does not open and close from one iteration to the next.
//   closed -> locked or sliding by the Mohr-Coulomb test on the tangential spring: the trial
//             stretch s = P (r_acc + Δr) is kept when kt |s| <= tan φ max(fn, 0) + c A, and is
//             otherwise stretched only to that cap along s (sliding), never reset.
//
// Departures from the paper, and why:
//   * The tangential law is the project's elastoplastic one (contact/friction/law.hpp): the
//     Mohr-Coulomb test applies to the whole spring, r_acc plus the step's increment, and a
//     sliding contact keeps its stretch at the cap. A reversal of the slip unloads the spring from
//     the cap, so sliding -> locked needs no separate direction test, and a load below the limit
//     cannot ratchet a block. The sliding direction handed to the next iteration (eq. 8) is that
//     of the trial stretch, which is the direction of the increment while the slip continues the
//     way the spring is stretched, and the direction the friction force then opposes in any case.
//   * The friction limit uses max(fn, 0), not |d*| of eq. 30: a contact held in tension by its
//     tensile strength carries cohesion but no friction from its tension.
//   * r_acc is projected onto the current tangent plane (the plane turns 1-3 degrees per step at
//     most, §5.2, so the projection loses at most 1 - cos 3° = 0.14% of it).
//   * Eq. 47 (the stretch of a contact revised in §5.1) is taken as the tangential offset of the
//     revised pair, so the spring starts from the crossing point: after a linear motion its
//     stretch is (1 - t) P Δr, the motion after the crossing.
//   * A contact opening drops its stretch (the 2D friction record is dropped on separation too).
//
// One open-close iteration: add_contact_terms with the state, solve, evaluate_contact; then
// next_iteration (mode, fn*, v* change; r_acc stays that of the start of the step) until no
// mode changes, and commit_step with the last evaluation.

#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "block_matrices3d.hpp"
#include "rockcontact/kernel/3d/contact_constraints.hpp"
#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::dynamics::detail {

enum class ContactMode : std::uint8_t { open, locked, sliding };

// The contact law of a pair of materials.
struct ContactLaw3d {
  double kn = 1.0e9;                // normal penalty, N/m, finite > 0
  double kt = 1.0e9;                // tangential penalty, N/m, finite > 0
  double friction_angle_deg = 0.0;  // φ, degrees, in [0, 90)
  double cohesion = 0.0;            // c, Pa, finite >= 0
  double tensile_strength = 0.0;    // σt, Pa, finite >= 0
  double gap_tolerance = 0.0;       // m, >= 0: the open-close decision's hysteresis (below)
};

inline ContactLaw3d default_contact_law3d() { return {}; }

// Throws std::invalid_argument naming the field that is out of its range above.
void check_contact_law3d(const ContactLaw3d& law);

// One side of a constraint: its contact point and its block's centroid (metres), and the block's
// unknowns: dof3d, rigid_dof3d, or 0 for a fixed block.
struct ContactSide3d {
  kernel::Point3 point;
  kernel::Point3 centroid;
  int dof = dof3d;
};

// What is fixed over the step (§3.1, §3.2).
struct ContactKinematics3d {
  Eigen::Matrix3Xd t_i;    // T(p_i - c_i), 3 x n_i; block i = cp
  Eigen::Matrix3Xd t_j;    // T(p_j - c_j), 3 x n_j; block j = tp
  Eigen::Vector3d normal;  // n, unit, from i towards j
  double gap = 0.0;        // d0 = (p_j - p_i) . n, metres; negative = penetration
  double area = 0.0;       // A, m², the contact area the constraint stands for (c A, σt A)
};

// `normal` must be unit (the kernel's is); area >= 0.
ContactKinematics3d contact_kinematics(const ContactSide3d& cp, const ContactSide3d& tp,
                                       const kernel::Point3& normal, double area);

// The per-step record of a constraint, kept by the engine across iterations and steps.
struct ContactState3d {
  ContactMode mode = ContactMode::open;
  // r_acc: the tangential spring's stretch, p_j relative to p_i, metres, at the start of the step.
  Eigen::Vector3d shear = Eigen::Vector3d::Zero();
  // The gap at which the normal spring is unloaded, metres, <= 0: 0, except for a constraint the
  // engine found already penetrating inside an overlap other constraints resist (born loaded it
  // would push the overlap out a second time); the spring then acts on d - offset. Dropped
  // (zero) when the contact opens.
  double offset = 0.0;
  // fn*: the normal force of the previous iteration (or step), N, compression > 0.
  double normal_force = 0.0;
  // v*: the assumed sliding direction of p_j relative to p_i, unit, or zero when unknown (a
  // sliding contact without a direction then carries no friction load; the engine may seed it
  // from kernel::sliding_direction, eq. 6-7).
  Eigen::Vector3d sliding_direction = Eigen::Vector3d::Zero();
};

// The relative motion of p_j to p_i, T_j d_j - T_i d_i (eq. 14-15), for increments or velocities
// d_i (n_i), d_j (n_j); a fixed side (no unknowns) contributes nothing.
Eigen::Vector3d relative_motion(const ContactKinematics3d& kin, const Eigen::Ref<const Eigen::VectorXd>& d_i,
                                const Eigen::Ref<const Eigen::VectorXd>& d_j);

// The caller's dense blocks the terms are added into: k_ii n_i x n_i, k_ij n_i x n_j (the block
// K_ji is its transpose), k_jj n_j x n_j, f_i n_i, f_j n_j. Blocks of a fixed side are 0-sized.
struct ContactBlocks3d {
  Eigen::Ref<Eigen::MatrixXd> k_ii;
  Eigen::Ref<Eigen::MatrixXd> k_ij;
  Eigen::Ref<Eigen::MatrixXd> k_jj;
  Eigen::Ref<Eigen::VectorXd> f_i;
  Eigen::Ref<Eigen::VectorXd> f_j;
};

// Adds the terms of the state's mode (eq. 24, 29, 32): nothing when open. The matrix blocks
// are exactly symmetric (k_ii, k_jj) and K is positive semidefinite.
void add_contact_terms(const ContactKinematics3d& kin, const ContactState3d& state,
                       const ContactLaw3d& law, ContactBlocks3d out);

// The dashpots of a closed constraint as springs on the step's relative displacement (dda3d.hpp,
// "Contact damping"): stiffness `normal` (c_n / h, N/m) along the normal and, when the state is
// locked, `tangential` (c_t / h) on the tangent plane; nothing for an open one. Returns nothing:
// the work is (c / h) |Δr|², dashpot_work below.
void add_dashpots(const ContactKinematics3d& kin, const ContactState3d& state, double normal, double tangential,
                  ContactBlocks3d out);

// The energy the dashpots of add_dashpots took over a step with relative displacement `relative`.
double dashpot_work(const ContactKinematics3d& kin, const ContactState3d& state, double normal, double tangential,
                    const Eigen::Vector3d& relative);

// A constraint after a solve.
struct ContactUpdate3d {
  ContactMode mode = ContactMode::open;
  double gap = 0.0;           // d1, metres; negative = penetration
  double normal_force = 0.0;  // on j along +n, N: -kn d1 when closed (< 0: tension), 0 open
  Eigen::Vector3d tangential_force = Eigen::Vector3d::Zero();  // on j, N; on i its negative
  Eigen::Vector3d shear = Eigen::Vector3d::Zero();  // the stretch kept, metres; zero when open
  Eigen::Vector3d sliding_direction = Eigen::Vector3d::Zero();  // v for the next iteration
};

// The Coulomb cap of a closed constraint, N: tan φ times its compressive normal force plus the
// cohesion over its contact area (eq. 30).
double friction_limit(const ContactLaw3d& law, double normal_force, double area);

// The mode decision of Table 2 and the forces, for the increments d_i (n_i) and d_j (n_j) of the
// solve that used `state`. An open -> closed contact is locked with the stretch P r_acc and no
// tangential force yet: its spring enters with the next iteration.
ContactUpdate3d evaluate_contact(const ContactKinematics3d& kin, const ContactState3d& state,
                                 const ContactLaw3d& law,
                                 const Eigen::Ref<const Eigen::VectorXd>& d_i,
                                 const Eigen::Ref<const Eigen::VectorXd>& d_j);

// The energy of the springs of a closed contact at gap `gap` with tangential stretch `shear`,
// ½ kn (gap - offset)² + ½ kt |shear|², J; 0 for an open one.
double spring_energy(const ContactLaw3d& law, ContactMode mode, double offset, double gap,
                     const Eigen::Vector3d& shear);

// Between iterations of one step: the new mode, fn* and v*; r_acc stays the step's.
void next_iteration(ContactState3d& state, const ContactUpdate3d& update);

// At the end of a step: everything, the stretch included. An open contact keeps as its offset
// the penetration it ends the step with (0 when apart; a contact born inside an overlap that
// opened short of it): closed later, its spring acts on further penetration only, and does not
// create the energy of a penetration no force worked against.
void commit_step(ContactState3d& state, const ContactUpdate3d& update);

// §5.1, eq. 41-43: a vertex-face constraint found open at the start of the step (d0 >= 0) and
// penetrating after the solve (d1 = d0 + n . Δr < 0, Δr the relative displacement of p_j to p_i
// of that solve). The vertex's relative motion is taken linear, so it crosses the face's plane
// at the fraction t = d0 / (d0 - d1) of the step, at the face block's material point
//   p_face* = p_vertex - t Δr   (vertex on cp),      p_face* = p_vertex + t Δr   (vertex on tp)
// which replaces the face point; the gap d0 is unchanged. The engine recomputes the kinematics
// at the revised point and starts the stretch from `shear` (eq. 47). nullopt unless d0 >= 0 > d1.
struct RevisedContact3d {
  kernel::Point3 point_cp;
  kernel::Point3 point_tp;
  double fraction = 0.0;                            // t, in [0, 1)
  Eigen::Vector3d shear = Eigen::Vector3d::Zero();  // P (point_tp - point_cp), metres
};

std::optional<RevisedContact3d> revise_vertex_face(const kernel::Point3& point_cp,
                                                   const kernel::Point3& point_tp,
                                                   const Eigen::Vector3d& normal,
                                                   kernel::BlockRole vertex,
                                                   const Eigen::Vector3d& relative);

// §5.1, eq. 44-46: the same for a crossing of cp's edge (direction e_cp) and tp's (e_tp), whose
// closest points point_cp, point_tp lie on the line of the normal. The tangential relative
// motion P Δr = a e_cp + b e_tp (eq. 44-45, the edges span the contact plane) moves the
// crossing along both edges; at the fraction t it is at
//   p_cp* = p_cp + t a e_cp,   p_tp* = p_tp - t b e_tp                        (eq. 46)
// (material points of each block at the start of the step), with the same gap d0, and the stretch
// starts from P (p_tp* - p_cp*) = -t P Δr (eq. 47), as for a vertex. nullopt unless d0 >= 0 > d1
// or when the edges are parallel.
std::optional<RevisedContact3d> revise_edge_edge(const kernel::Point3& point_cp, const kernel::Point3& point_tp,
                                                 const Eigen::Vector3d& normal, const Eigen::Vector3d& e_cp,
                                                 const Eigen::Vector3d& e_tp, const Eigen::Vector3d& relative);

}  // namespace rockcontact::dynamics::detail
