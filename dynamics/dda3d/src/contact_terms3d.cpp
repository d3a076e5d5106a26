#include "contact_terms3d.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace rockcontact::dynamics::detail {
namespace {

using Eigen::Vector3d;

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

void require(bool ok, const char* field, const char* range, double value) {
  if (!ok) {
    throw std::invalid_argument(std::string("contact law: ") + field + " must be " + range +
                                ", got " + number(value));
  }
}

Vector3d vec(const kernel::Point3& p) { return {p.x, p.y, p.z}; }

kernel::Point3 point(const Vector3d& v) { return {v.x(), v.y(), v.z()}; }

Vector3d tangential(const Vector3d& v, const Vector3d& n) { return v - v.dot(n) * n; }

// The unit of v, or `otherwise` for a zero v.
Vector3d unit_or(const Vector3d& v, const Vector3d& otherwise) {
  const double length = v.norm();
  return length > 0.0 ? Vector3d(v / length) : otherwise;
}

// An orthonormal basis (t1, t2) of the plane normal to the unit n: t1 along the cross product
// of n with the axis least aligned with it.
std::pair<Vector3d, Vector3d> tangent_basis(const Vector3d& n) {
  Eigen::Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  const Vector3d t1 = n.cross(Vector3d::Unit(axis)).normalized();
  return {t1, n.cross(t1)};
}

// The spring ½ k (s0 + e . Δr)² along the unit e (header): g = sqrt(k) T e, so that every
// product of K is that of two equal factors and k_ii, k_jj come out exactly symmetric.
// T^T e: the generalized force of a force e at the point; empty for a fixed side. (A 3 x 0
// matrix has no storage, and Eigen's products with it offset a null pointer.)
Eigen::VectorXd pulled_back(const Eigen::Matrix3Xd& t, const Vector3d& e) {
  if (t.cols() == 0) return Eigen::VectorXd();
  return t.transpose() * e;
}

void add_spring(const ContactKinematics3d& kin, const Vector3d& e, double s0, double k,
                ContactBlocks3d& out) {
  const double root = std::sqrt(k);
  const Eigen::VectorXd g_i = root * pulled_back(kin.t_i, e);
  const Eigen::VectorXd g_j = root * pulled_back(kin.t_j, e);
  out.k_ii.noalias() += g_i * g_i.transpose();
  out.k_ij.noalias() -= g_i * g_j.transpose();
  out.k_jj.noalias() += g_j * g_j.transpose();
  out.f_i += (root * s0) * g_i;
  out.f_j -= (root * s0) * g_j;
}

// Closed -> locked or sliding: the elastoplastic return mapping of the trial stretch.
void judge_tangential(const ContactLaw3d& law, double area, const Vector3d& trial,
                      ContactUpdate3d& out) {
  const double limit = friction_limit(law, out.normal_force, area);
  const double length = trial.norm();
  if (law.kt * length <= limit) {
    out.mode = ContactMode::locked;
    out.shear = trial;
  } else {
    out.mode = ContactMode::sliding;
    out.shear = trial * (limit / law.kt / length);
  }
  out.tangential_force = -law.kt * out.shear;
}

}  // namespace

double friction_limit(const ContactLaw3d& law, double normal_force, double area) {
  const double tan_phi = std::tan(law.friction_angle_deg * (std::numbers::pi / 180.0));
  return tan_phi * std::max(normal_force, 0.0) + law.cohesion * area;
}

void check_contact_law3d(const ContactLaw3d& law) {
  require(std::isfinite(law.kn) && law.kn > 0.0, "kn", "finite and > 0 (N/m)", law.kn);
  require(std::isfinite(law.kt) && law.kt > 0.0, "kt", "finite and > 0 (N/m)", law.kt);
  require(law.friction_angle_deg >= 0.0 && law.friction_angle_deg < 90.0, "friction_angle_deg",
          "in [0, 90)", law.friction_angle_deg);
  require(std::isfinite(law.cohesion) && law.cohesion >= 0.0, "cohesion", "finite and >= 0 (Pa)",
          law.cohesion);
  require(std::isfinite(law.tensile_strength) && law.tensile_strength >= 0.0, "tensile_strength",
          "finite and >= 0 (Pa)", law.tensile_strength);
  require(std::isfinite(law.gap_tolerance) && law.gap_tolerance >= 0.0, "gap_tolerance", "finite and >= 0 (m)",
          law.gap_tolerance);
}

ContactKinematics3d contact_kinematics(const ContactSide3d& cp, const ContactSide3d& tp,
                                       const kernel::Point3& normal, double area) {
  assert(cp.dof == 0 || cp.dof == rigid_dof3d || cp.dof == dof3d);
  assert(tp.dof == 0 || tp.dof == rigid_dof3d || tp.dof == dof3d);
  assert(area >= 0.0);
  const auto t_of = [](const ContactSide3d& side) -> Eigen::Matrix3Xd {
    const kernel::Point3 offset{side.point.x - side.centroid.x, side.point.y - side.centroid.y,
                                side.point.z - side.centroid.z};
    return displacement_matrix(offset).leftCols(side.dof);
  };
  ContactKinematics3d kin;
  kin.t_i = t_of(cp);
  kin.t_j = t_of(tp);
  kin.normal = vec(normal);
  kin.gap = (vec(tp.point) - vec(cp.point)).dot(kin.normal);
  kin.area = area;
  return kin;
}

void add_contact_terms(const ContactKinematics3d& kin, const ContactState3d& state,
                       const ContactLaw3d& law, ContactBlocks3d out) {
  assert(out.k_ii.rows() == kin.t_i.cols() && out.k_jj.rows() == kin.t_j.cols());
  if (state.mode == ContactMode::open) return;
  const Vector3d& n = kin.normal;
  add_spring(kin, n, kin.gap - state.offset, law.kn, out);  // eq. 22-24
  if (state.mode == ContactMode::locked) {   // eq. 25-29, P = t1 t1ᵀ + t2 t2ᵀ
    const auto [t1, t2] = tangent_basis(n);
    add_spring(kin, t1, t1.dot(state.shear), law.kt, out);
    add_spring(kin, t2, t2.dot(state.shear), law.kt, out);
    return;
  }
  const Vector3d v = unit_or(tangential(state.sliding_direction, n), Vector3d::Zero());
  const double f = friction_limit(law, state.normal_force, kin.area);  // eq. 30
  out.f_i += pulled_back(kin.t_i, f * v);                              // eq. 32
  out.f_j -= pulled_back(kin.t_j, f * v);
}

Eigen::Vector3d relative_motion(const ContactKinematics3d& kin, const Eigen::Ref<const Eigen::VectorXd>& d_i,
                                const Eigen::Ref<const Eigen::VectorXd>& d_j) {
  Vector3d out = Vector3d::Zero();
  if (kin.t_j.cols() > 0) out += kin.t_j * d_j;
  if (kin.t_i.cols() > 0) out -= kin.t_i * d_i;
  return out;
}

void add_dashpots(const ContactKinematics3d& kin, const ContactState3d& state, double normal, double tangential,
                  ContactBlocks3d out) {
  if (state.mode == ContactMode::open) return;
  if (normal > 0.0) add_spring(kin, kin.normal, 0.0, normal, out);
  if (tangential > 0.0 && state.mode == ContactMode::locked) {
    const auto [t1, t2] = tangent_basis(kin.normal);
    add_spring(kin, t1, 0.0, tangential, out);
    add_spring(kin, t2, 0.0, tangential, out);
  }
}

double dashpot_work(const ContactKinematics3d& kin, const ContactState3d& state, double normal, double tangential,
                    const Eigen::Vector3d& relative) {
  if (state.mode == ContactMode::open) return 0.0;
  const double along = kin.normal.dot(relative);
  double work = normal * along * along;
  if (state.mode == ContactMode::locked) work += tangential * (relative - along * kin.normal).squaredNorm();
  return work;
}

ContactUpdate3d evaluate_contact(const ContactKinematics3d& kin, const ContactState3d& state,
                                 const ContactLaw3d& law,
                                 const Eigen::Ref<const Eigen::VectorXd>& d_i,
                                 const Eigen::Ref<const Eigen::VectorXd>& d_j) {
  assert(d_i.size() == kin.t_i.cols() && d_j.size() == kin.t_j.cols());
  const Vector3d& n = kin.normal;
  const Vector3d relative = relative_motion(kin, d_i, d_j);
  ContactUpdate3d out;
  out.gap = kin.gap + n.dot(relative);  // eq. 21
  const bool was_closed = state.mode != ContactMode::open;
  const bool closed =
      was_closed ? law.kn * (out.gap - state.offset - law.gap_tolerance) <= law.tensile_strength * kin.area
                 : out.gap < state.offset - law.gap_tolerance;
  if (!closed) {
    out.sliding_direction = unit_or(tangential(relative, n), state.sliding_direction);
    return out;
  }
  out.normal_force = -law.kn * (out.gap - state.offset);
  if (!was_closed) {
    out.mode = ContactMode::locked;
    out.shear = tangential(state.shear, n);
    out.sliding_direction = unit_or(tangential(relative, n), state.sliding_direction);
    return out;
  }
  const Vector3d trial = tangential(state.shear + relative, n);
  judge_tangential(law, kin.area, trial, out);
  out.sliding_direction = unit_or(trial, state.sliding_direction);
  return out;
}

void next_iteration(ContactState3d& state, const ContactUpdate3d& update) {
  state.mode = update.mode;
  state.normal_force = update.normal_force;
  state.sliding_direction = update.sliding_direction;
}

void commit_step(ContactState3d& state, const ContactUpdate3d& update) {
  next_iteration(state, update);
  state.shear = update.shear;
  if (update.mode == ContactMode::open) state.offset = std::min(0.0, update.gap);
}

double spring_energy(const ContactLaw3d& law, ContactMode mode, double offset, double gap,
                     const Eigen::Vector3d& shear) {
  if (mode == ContactMode::open) return 0.0;
  const double stretch = gap - offset;
  return 0.5 * law.kn * stretch * stretch + 0.5 * law.kt * shear.squaredNorm();
}

namespace {

// Eq. 43: the fraction of the step at which a contact open at its start (d0 >= 0) and penetrating
// at its end (d1 < 0) closes, under a linear relative motion; nullopt when it does not cross.
std::optional<double> crossing_fraction(const Vector3d& p_cp, const Vector3d& p_tp, const Vector3d& normal,
                                        const Vector3d& relative) {
  const double d0 = (p_tp - p_cp).dot(normal);  // eq. 20
  const double d1 = d0 + normal.dot(relative);  // eq. 21
  if (!(d0 >= 0.0 && d1 < 0.0)) return std::nullopt;
  return d0 / (d0 - d1);
}

}  // namespace

std::optional<RevisedContact3d> revise_vertex_face(const kernel::Point3& point_cp,
                                                   const kernel::Point3& point_tp,
                                                   const Eigen::Vector3d& normal,
                                                   kernel::BlockRole vertex,
                                                   const Eigen::Vector3d& relative) {
  const Vector3d p_cp = vec(point_cp), p_tp = vec(point_tp);
  const std::optional<double> t = crossing_fraction(p_cp, p_tp, normal, relative);
  if (!t) return std::nullopt;
  RevisedContact3d out;
  out.fraction = *t;
  const Vector3d moved = out.fraction * relative;  // eq. 41-42, the motion up to the crossing
  out.point_cp = vertex == kernel::BlockRole::cp ? point_cp : point(p_tp + moved);
  out.point_tp = vertex == kernel::BlockRole::tp ? point_tp : point(p_cp - moved);
  out.shear = tangential(vec(out.point_tp) - vec(out.point_cp), normal);
  return out;
}

std::optional<RevisedContact3d> revise_edge_edge(const kernel::Point3& point_cp, const kernel::Point3& point_tp,
                                                 const Eigen::Vector3d& normal, const Eigen::Vector3d& e_cp,
                                                 const Eigen::Vector3d& e_tp, const Eigen::Vector3d& relative) {
  const Vector3d p_cp = vec(point_cp), p_tp = vec(point_tp);
  const std::optional<double> t = crossing_fraction(p_cp, p_tp, normal, relative);
  if (!t) return std::nullopt;
  // Eq. 45: P Δr = a e_cp + b e_tp, by the normal equations of the two edges' directions in the
  // plane.
  const Vector3d u = tangential(e_cp, normal), w = tangential(e_tp, normal), s = tangential(relative, normal);
  const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w);
  const double det = uu * ww - uw * uw;
  if (!(det > 0.0)) return std::nullopt;
  const double a = (ww * u.dot(s) - uw * w.dot(s)) / det;
  const double b = (uu * w.dot(s) - uw * u.dot(s)) / det;
  RevisedContact3d out;
  out.fraction = *t;
  out.point_cp = point(p_cp + out.fraction * a * u);  // eq. 46
  out.point_tp = point(p_tp - out.fraction * b * w);
  out.shear = tangential(vec(out.point_tp) - vec(out.point_cp), normal);
  return out;
}

}  // namespace rockcontact::dynamics::detail
