#define BOOST_TEST_MODULE wedge_limit_equilibrium
#include "rockcontact/dynamics/apps/wedge_limit_equilibrium.hpp"

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/kernel/3d/block_cutting.hpp"

namespace dyn = rockcontact::dynamics;
using rockcontact::kernel::Point3;

namespace {

constexpr double pi = std::numbers::pi;
double rad(double deg) { return deg * pi / 180.0; }
double deg(double rad) { return rad * 180.0 / pi; }

// Seed 001 §6.1: joint 1 dip 50° towards 110°, joint 2 dip 55° towards 240°, φ = 40°, dry,
// no cohesion. The weight is arbitrary for friction only.
const dyn::WedgeJoint paper_joint_1{50.0, 110.0, 40.0, 0.0, 0.0};
const dyn::WedgeJoint paper_joint_2{55.0, 240.0, 40.0, 0.0, 0.0};
constexpr double paper_weight = 1.0e6;  // N

Point3 cross(const Point3& u, const Point3& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}
Point3 combine(double s, const Point3& u, double t, const Point3& v) {
  return {s * u.x + t * v.x, s * u.y + t * v.y, s * u.z + t * v.z};
}
double distance(const Point3& u, const Point3& v) {
  return std::hypot(u.x - v.x, u.y - v.y, u.z - v.z);
}

// The signed difference x − y of two azimuths, degrees, in [−180, 180).
double azimuth_difference(double x, double y) {
  return std::fmod(std::fmod(x - y + 180.0, 360.0) + 360.0, 360.0) - 180.0;
}

// The joint whose upward unit normal is n (n_z > 0), with friction angle φ.
dyn::WedgeJoint joint_with_normal(const Point3& n, double phi_deg) {
  const double direction = deg(std::atan2(n.x, n.y));
  return {deg(std::acos(n.z)), direction < 0 ? direction + 360.0 : direction, phi_deg, 0.0, 0.0};
}

// A wedge given by its cross-section (Hoek & Bray's construction). The line of intersection has
// trend τ and plunge ψ_i. Looking down it, in the section plane spanned by h (horizontal) and u
// (up, the vertical's component across the line), the two planes' traces leave the wedge's
// apex at angles a = β + ξ/2 (plane A) and b = β − ξ/2 (plane B) from h: ξ is the wedge's
// included angle and β the angle of its bisector above the horizontal (β = 90° for a symmetric
// wedge). The wedge is the sector b < t < a, so the reactions on it, normal to the traces and
// pointing into it, are n_A = sin a h − cos a u and n_B = −sin b h + cos b u. They point up (the
// wedge rests on top of both planes) when b < 90° < a.
std::pair<dyn::WedgeJoint, dyn::WedgeJoint> section_wedge(double trend, double plunge, double xi, double beta,
                                                          double phi_a, double phi_b) {
  const Point3 line{std::cos(rad(plunge)) * std::sin(rad(trend)), std::cos(rad(plunge)) * std::cos(rad(trend)),
                    -std::sin(rad(plunge))};
  const Point3 up{std::sin(rad(plunge)) * std::sin(rad(trend)), std::sin(rad(plunge)) * std::cos(rad(trend)),
                  std::cos(rad(plunge))};
  const Point3 across = cross(line, up);
  const double a = rad(beta + xi / 2), b = rad(beta - xi / 2);
  return {joint_with_normal(combine(std::sin(a), across, -std::cos(a), up), phi_a),
          joint_with_normal(combine(-std::sin(b), across, std::cos(b), up), phi_b)};
}

}  // namespace

// The paper's wedge: FS = 2.198 (seed 001 §6.1, eq. 51). The line of intersection against the
// stereonet formula, and eq. 51 rebuilt from spherical trigonometry, neither using vectors.
BOOST_AUTO_TEST_CASE(paper_wedge_has_factor_of_safety_2_198) {
  const auto r = dyn::wedge_factor_of_safety(paper_joint_1, paper_joint_2, paper_weight);
  BOOST_TEST_MESSAGE(std::setprecision(17)
                     << "seed 001 §6.1 wedge: FS = " << r.factor_of_safety << ", line plunge " << r.plunge_deg
                     << "° trend " << r.trend_deg << "°, A = " << r.coefficient_a << ", B = " << r.coefficient_b);
  BOOST_TEST(r.mode == dyn::WedgeMode::wedge);
  // The paper prints 2.198: FS rounded to three decimals, so it lies within half a unit of the
  // last digit.
  BOOST_TEST(std::abs(r.factor_of_safety - 2.198) <= 0.0005);

  // Stereonet formula: the line is the direction α in which both planes have the same apparent
  // dip, tan ψ_A cos(α − α_A) = tan ψ_B cos(α − α_B), so
  //   tan α = (tan ψ_A cos α_A − tan ψ_B cos α_B) / (tan ψ_B sin α_B − tan ψ_A sin α_A),
  // taken in the half-turn where that apparent dip is downward; the plunge is that apparent dip.
  const double ta = std::tan(rad(50)), tb = std::tan(rad(55));
  double trend = deg(std::atan((ta * std::cos(rad(110)) - tb * std::cos(rad(240))) /
                               (tb * std::sin(rad(240)) - ta * std::sin(rad(110)))));
  if (std::cos(rad(trend - 110)) < 0) trend += 180;
  if (trend < 0) trend += 360;
  const double plunge = deg(std::atan(ta * std::cos(rad(trend - 110))));
  BOOST_TEST_MESSAGE(std::setprecision(17) << "stereonet: plunge " << plunge << "° trend " << trend << "°");
  // Both sides compute an angle of O(100) degrees in a few dozen well-conditioned double
  // operations (the planes meet at 80 degrees), so they agree to ~1e-13 degrees; 1e-10 leaves
  // room for libm while any convention error (a swapped axis, a reversed line) is degrees.
  BOOST_TEST(std::abs(r.plunge_deg - plunge) <= 1e-10);
  BOOST_TEST(std::abs(r.trend_deg - trend) <= 1e-10);

  // Eq. 51 from the dips alone: the angle θ between the poles by the spherical law of cosines,
  // cos θ = cos ψ_A cos ψ_B + sin ψ_A sin ψ_B cos(α_A − α_B); A, B as in the header.
  const double cos_theta =
      std::cos(rad(50)) * std::cos(rad(55)) + std::sin(rad(50)) * std::sin(rad(55)) * std::cos(rad(110 - 240));
  const double sin2_theta = 1 - cos_theta * cos_theta;
  const double sin_plunge = std::sin(rad(plunge));
  const double A = (std::cos(rad(50)) - std::cos(rad(55)) * cos_theta) / (sin_plunge * sin2_theta);
  const double B = (std::cos(rad(55)) - std::cos(rad(50)) * cos_theta) / (sin_plunge * sin2_theta);
  const double fs = (A + B) * std::tan(rad(40));
  // A few dozen roundings of O(1) terms, 1 − cos²θ with cos θ = 0.17 losing nothing: 1e-13
  // relative is ~500 units of rounding, still far below a wrong formula.
  BOOST_TEST(std::abs(r.coefficient_a - A) <= 1e-13 * A);
  BOOST_TEST(std::abs(r.coefficient_b - B) <= 1e-13 * B);
  BOOST_TEST(std::abs(r.factor_of_safety - fs) <= 1e-13 * fs);

  // The decomposition of the weight: (0, 0, −W) = D i − N_A n_A − N_B n_B (the planes push the
  // wedge along their upward normals; the shear along the line takes up D).
  const Point3 balance =
      combine(-1.0, combine(r.normal_reaction_a, r.normal_a, r.normal_reaction_b, r.normal_b), r.driving_force,
              r.intersection);
  // Forces of O(1e6 N), each component a sum of three products: 1e-8 N is ~1e-14 relative.
  BOOST_TEST(distance(balance, Point3{0, 0, -paper_weight}) <= 1e-8);
  BOOST_TEST(r.normal_reaction_a > 0);
  BOOST_TEST(r.normal_reaction_b > 0);
}

// The normals follow block cutting's convention, so the DDA's blocks and this reference see the
// same planes. Same formula on both sides: a difference beyond one rounding (2^-53 of a
// component of magnitude <= 1) would be a different convention, which is O(1).
BOOST_AUTO_TEST_CASE(normals_follow_block_cutting_convention) {
  const auto r = dyn::wedge_factor_of_safety(paper_joint_1, paper_joint_2, paper_weight);
  const Point3 n1 = rockcontact::kernel::joint_normal({50.0, 110.0, 1.0, 0.0});
  const Point3 n2 = rockcontact::kernel::joint_normal({55.0, 240.0, 1.0, 0.0});
  BOOST_TEST(distance(r.normal_a, n1) <= 0x1p-52);
  BOOST_TEST(distance(r.normal_b, n2) <= 0x1p-52);
}

// Hoek & Bray's wedge factor. In the section across the line of intersection the weight's
// component W cos ψ_i balances the reactions R_A (sin a, −cos a) and R_B (−sin b, cos b)
// (section_wedge above): horizontally R_A sin a = R_B sin b, vertically
// R_B cos b − R_A cos a = W cos ψ_i, so
//   R_A = W cos ψ_i sin b / sin ξ,   R_B = W cos ψ_i sin a / sin ξ,
//   R_A + R_B = W cos ψ_i (sin a + sin b) / sin ξ = W cos ψ_i sin β / sin(ξ/2),
// and FS = (R_A tan φ_A + R_B tan φ_B) / (W sin ψ_i); with φ_A = φ_B = φ,
//   FS = (sin β / sin(ξ/2)) tan φ / tan ψ_i.
BOOST_AUTO_TEST_CASE(section_wedges_match_the_wedge_factor) {
  struct Case {
    double trend, plunge, xi, beta, phi_a, phi_b;
  };
  const std::vector<Case> cases{
      // symmetric: β = 90°, equal dips, dip directions symmetric about the trend
      {172.5, 28.7, 60, 90, 40, 40},
      {0, 45, 90, 90, 30, 30},
      {300, 20, 120, 90, 35, 35},
      {45, 60, 30, 90, 25, 25},
      {200, 10, 150, 90, 40, 40},
      // tilted (β ≠ 90°) and different friction angles: the general form
      {110, 35, 70, 75, 40, 30},
      {250, 25, 100, 110, 20, 45},
      {30, 50, 40, 100, 38, 22},
  };
  constexpr double weight = 2.5e5;  // N
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT("trend " << c.trend << " plunge " << c.plunge << " xi " << c.xi << " beta " << c.beta) {
      const auto [a_joint, b_joint] = section_wedge(c.trend, c.plunge, c.xi, c.beta, c.phi_a, c.phi_b);
      if (c.beta == 90) {
        // The construction is the symmetric wedge of the brief (acos and atan2 round trips: 1e-12 degrees).
        BOOST_TEST(std::abs(a_joint.dip_deg - b_joint.dip_deg) <= 1e-12);
        BOOST_TEST(std::abs(azimuth_difference(a_joint.dip_direction_deg, c.trend) +
                            azimuth_difference(b_joint.dip_direction_deg, c.trend)) <= 1e-12);
      }
      const auto r = dyn::wedge_factor_of_safety(a_joint, b_joint, weight);
      const double a = rad(c.beta + c.xi / 2), b = rad(c.beta - c.xi / 2);
      const double across = weight * std::cos(rad(c.plunge)) / std::sin(rad(c.xi));
      const double resisting =
          across * std::sin(b) * std::tan(rad(c.phi_a)) + across * std::sin(a) * std::tan(rad(c.phi_b));
      const double fs = resisting / (weight * std::sin(rad(c.plunge)));
      BOOST_TEST_MESSAGE(std::setprecision(17) << "section wedge trend " << c.trend << " plunge " << c.plunge << " xi "
                                               << c.xi << " beta " << c.beta << ": FS " << r.factor_of_safety
                                               << ", closed form " << fs);
      BOOST_TEST(r.mode == dyn::WedgeMode::wedge);
      // The joints went through degrees and acos/atan2 (relative errors of a few 1e-16), and
      // the formula divides by sin²θ sin ψ_i >= 0.04 here (θ = 180° − ξ), so those errors grow
      // at most ~25-fold (measured: <= 2e-15): 1e-12 relative leaves a wide margin and still
      // catches any error in the formula or its signs.
      BOOST_TEST(std::abs(r.factor_of_safety - fs) <= 1e-12 * fs);
      BOOST_TEST(std::abs(r.normal_reaction_a - across * std::sin(b)) <= 1e-12 * weight);
      BOOST_TEST(std::abs(r.normal_reaction_b - across * std::sin(a)) <= 1e-12 * weight);
      BOOST_TEST(std::abs(r.plunge_deg - c.plunge) <= 1e-10);
      BOOST_TEST(std::abs(azimuth_difference(r.trend_deg, c.trend)) <= 1e-10);
      if (c.phi_a == c.phi_b) {
        const double wedge_factor = std::sin(rad(c.beta)) / std::sin(rad(c.xi / 2));
        const double k = wedge_factor * std::tan(rad(c.phi_a)) / std::tan(rad(c.plunge));
        BOOST_TEST(std::abs(r.factor_of_safety - k) <= 1e-12 * k);
      }
    }
  }
}

// When the weight would pull the wedge off plane B (N_B <= 0, Hoek & Bray's contact check), it
// slides on plane A alone, down A's dip: FS = tan φ_A / tan ψ_A, N_A = W cos ψ_A.
BOOST_AUTO_TEST_CASE(wedge_off_plane_b_slides_on_plane_a) {
  const dyn::WedgeJoint a{30.0, 180.0, 40.0, 0.0, 0.0};
  // B dips 80° towards 150°: n_Bz = 0.17 < m n_Az = 0.50, so the wedge solution has N_B < 0.
  const dyn::WedgeJoint b{80.0, 150.0, 25.0, 0.0, 0.0};
  constexpr double weight = 1.0e4;  // N
  const auto r = dyn::wedge_factor_of_safety(a, b, weight);
  BOOST_TEST(r.mode == dyn::WedgeMode::plane_a);
  const double fs = std::tan(rad(40)) / std::tan(rad(30));
  // The same quotient of two tangents, as cos/sin and tan: a few roundings, 1e-14 relative.
  BOOST_TEST(std::abs(r.factor_of_safety - fs) <= 1e-14 * fs);
  BOOST_TEST(std::abs(r.normal_reaction_a - weight * std::cos(rad(30))) <= 1e-14 * weight);
  BOOST_TEST(r.normal_reaction_b == 0.0);
  BOOST_TEST(r.coefficient_b == 0.0);
  BOOST_TEST(distance(r.sliding, Point3{0.0, -std::cos(rad(30)), -std::sin(rad(30))}) <= 1e-15);

  // Swapped, the same wedge slides on plane B.
  const auto s = dyn::wedge_factor_of_safety(b, a, weight);
  BOOST_TEST(s.mode == dyn::WedgeMode::plane_b);
  BOOST_TEST(s.factor_of_safety == r.factor_of_safety);
}

// A wedge whose plane B tends to the vertical plane through A's dip line (dip 90° − ε towards
// 90°, A dipping 30° towards 180°). Then n_B = (cos ε, 0, sin ε), m = sin ε cos ψ_A and
// n_Bz − m n_Az = sin ε sin²ψ_A, so B = sin ε sin ψ_A + O(ε²) while A = 1/tan ψ_A + O(ε²):
//   FS − tan φ / tan ψ_A = ε sin ψ_A tan φ (1 + O(ε)).
// At ε = 0 exactly, N_B = 0 and the wedge slides on plane A alone.
BOOST_AUTO_TEST_CASE(wedge_tends_to_plane_sliding_as_plane_b_turns_vertical) {
  const dyn::WedgeJoint a{30.0, 180.0, 40.0, 0.0, 0.0};
  const double plane = std::tan(rad(40)) / std::tan(rad(30));
  for (const double eps : {10.0, 1.0, 0.1, 0.01, 0.001}) {
    BOOST_TEST_CONTEXT("eps " << eps << " degrees") {
      const auto r = dyn::wedge_factor_of_safety(a, {90.0 - eps, 90.0, 40.0, 0.0, 0.0}, 1.0);
      const double first_order = rad(eps) * std::sin(rad(30)) * std::tan(rad(40));
      const double ratio = (r.factor_of_safety - plane) / first_order;
      BOOST_TEST_MESSAGE(std::setprecision(17) << "eps " << eps << "°: FS " << r.factor_of_safety
                                               << ", (FS - plane) / first order " << ratio);
      BOOST_TEST(r.mode == dyn::WedgeMode::wedge);
      // The O(ε) remainder is ≈ 0.42 ε (radians); bounding it by ε (radians) leaves room, and
      // rounding in FS − plane (~1e-15 against a first-order term >= 7e-6) is negligible.
      BOOST_TEST(std::abs(ratio - 1) <= rad(eps));
    }
  }
  const auto r = dyn::wedge_factor_of_safety(a, {90.0, 90.0, 40.0, 0.0, 0.0}, 1.0);
  BOOST_TEST(r.mode == dyn::WedgeMode::plane_a);
  BOOST_TEST(std::abs(r.factor_of_safety - plane) <= 1e-14 * plane);  // as in the test above
  // Exact sines at 90°: the line is A's dip line to rounding of sin/cos 30°.
  BOOST_TEST(distance(r.intersection, Point3{0.0, -std::cos(rad(30)), -std::sin(rad(30))}) <= 1e-15);
}

// Two vertical planes carry nothing: the wedge falls (lift_off, FS = 0). The line is vertical,
// trend 0 by convention in either order (n_A × n_B is (0, 0, ±1) with signed zeros that would
// make atan2 answer 180).
BOOST_AUTO_TEST_CASE(two_vertical_planes_lift_off) {
  const dyn::WedgeJoint north{90.0, 0.0, 40.0, 0.0, 0.0}, east{90.0, 90.0, 40.0, 0.0, 0.0};
  for (const auto& [a, b] : {std::pair{north, east}, std::pair{east, north}}) {
    const auto r = dyn::wedge_factor_of_safety(a, b, 1.0);
    BOOST_TEST(r.mode == dyn::WedgeMode::lift_off);
    BOOST_TEST(r.factor_of_safety == 0.0);
    BOOST_TEST(r.plunge_deg == 90.0);
    BOOST_TEST(r.trend_deg == 0.0);
    BOOST_TEST(!std::signbit(r.trend_deg));
  }
}

// A rotation about the vertical moves the line's trend and nothing else.
BOOST_AUTO_TEST_CASE(rotating_both_dip_directions_leaves_fs_unchanged) {
  const auto base = dyn::wedge_factor_of_safety(paper_joint_1, paper_joint_2, paper_weight);
  for (const double turn : {0.5, 17.0, 90.0, 180.0, 249.75, 300.0}) {
    BOOST_TEST_CONTEXT("turn " << turn << " degrees") {
      dyn::WedgeJoint a = paper_joint_1, b = paper_joint_2;
      a.dip_direction_deg = std::fmod(a.dip_direction_deg + turn, 360.0);
      b.dip_direction_deg = std::fmod(b.dip_direction_deg + turn, 360.0);
      const auto r = dyn::wedge_factor_of_safety(a, b, paper_weight);
      // Only the sines and cosines of the dip directions change, each by a rounding: the
      // results move by a few 1e-16 relative; 1e-13 says "unchanged" with a wide margin.
      BOOST_TEST(std::abs(r.factor_of_safety - base.factor_of_safety) <= 1e-13 * base.factor_of_safety);
      BOOST_TEST(std::abs(r.normal_reaction_a - base.normal_reaction_a) <= 1e-13 * paper_weight);
      BOOST_TEST(std::abs(r.normal_reaction_b - base.normal_reaction_b) <= 1e-13 * paper_weight);
      BOOST_TEST(std::abs(r.plunge_deg - base.plunge_deg) <= 1e-10);
      BOOST_TEST(std::abs(azimuth_difference(r.trend_deg, base.trend_deg + turn)) <= 1e-10);
    }
  }
}

// Swapping the joints swaps the reactions and leaves everything else to the bit: every
// operation involved is commutative in IEEE arithmetic and n_B × n_A = −(n_A × n_B) exactly
// (the build turns off FMA contraction, -ffp-contract=off).
BOOST_AUTO_TEST_CASE(swapping_the_joints_leaves_fs_unchanged) {
  const std::vector<std::pair<dyn::WedgeJoint, dyn::WedgeJoint>> pairs{
      {paper_joint_1, paper_joint_2},
      {{35.0, 20.0, 30.0, 0.0, 0.0}, {70.0, 300.0, 45.0, 0.0, 0.0}},
      {{62.0, 140.0, 33.0, 2.0e4, 15.0}, {41.0, 205.0, 28.0, 1.0e4, 22.0}},
  };
  for (const auto& [a, b] : pairs) {
    const auto ab = dyn::wedge_factor_of_safety(a, b, paper_weight);
    const auto ba = dyn::wedge_factor_of_safety(b, a, paper_weight);
    BOOST_TEST(ab.factor_of_safety == ba.factor_of_safety);
    BOOST_TEST(ab.normal_reaction_a == ba.normal_reaction_b);
    BOOST_TEST(ab.normal_reaction_b == ba.normal_reaction_a);
    BOOST_TEST(ab.coefficient_a == ba.coefficient_b);
    BOOST_TEST((ab.intersection == ba.intersection));
  }
}

// Friction only, FS depends on the orientations and friction angles alone (eq. 51): to the bit,
// since W enters the reactions and the driving force but not A, B. The reactions scale with W.
BOOST_AUTO_TEST_CASE(friction_only_fs_does_not_depend_on_the_weight) {
  const auto base = dyn::wedge_factor_of_safety(paper_joint_1, paper_joint_2, 1.0);
  for (const double weight : {9.81, 2.7e4, 3.3e9, 1.0e-3}) {
    const auto r = dyn::wedge_factor_of_safety(paper_joint_1, paper_joint_2, weight);
    BOOST_TEST(r.factor_of_safety == base.factor_of_safety);
    // One extra rounding in the product by W: 1e-15 relative.
    BOOST_TEST(std::abs(r.normal_reaction_a - weight * base.normal_reaction_a) <= 1e-15 * r.normal_reaction_a);
    BOOST_TEST(std::abs(r.driving_force - weight * base.driving_force) <= 1e-15 * r.driving_force);
  }
}

// Cohesion adds (c_A S_A + c_B S_B) / (W sin ψ_i), which halves when W doubles.
BOOST_AUTO_TEST_CASE(cohesion_adds_its_force_over_the_driving_force) {
  dyn::WedgeJoint a = paper_joint_1, b = paper_joint_2;
  a.cohesion_pa = 2.0e4;
  a.area = 30.0;
  b.cohesion_pa = 5.0e3;
  b.area = 45.0;
  const auto dry = dyn::wedge_factor_of_safety(paper_joint_1, paper_joint_2, paper_weight);
  for (const double weight : {paper_weight, 2 * paper_weight}) {
    const auto r = dyn::wedge_factor_of_safety(a, b, weight);
    const double cohesive = (2.0e4 * 30.0 + 5.0e3 * 45.0) / (weight * std::sin(rad(dry.plunge_deg)));
    // Sums of O(1) terms with a few roundings each: 1e-13 absolute on FS of order 3.
    BOOST_TEST(std::abs(r.factor_of_safety - dry.factor_of_safety - cohesive) <= 1e-13);
  }
}

// Bad input: std::invalid_argument whose message starts with the field it refuses.
BOOST_AUTO_TEST_CASE(bad_input_names_the_field) {
  const auto expect_refused = [](const dyn::WedgeJoint& a, const dyn::WedgeJoint& b, double weight,
                                 const std::string& field, const std::string& detail) {
    BOOST_TEST_CONTEXT(field << " / " << detail) {
      try {
        dyn::wedge_factor_of_safety(a, b, weight);
        BOOST_ERROR("accepted");
      } catch (const std::invalid_argument& e) {
        const std::string message = e.what();
        BOOST_TEST_MESSAGE(message);
        BOOST_TEST(message.starts_with(field + ": expected"), message);
        BOOST_TEST(message.find(detail) != std::string::npos, message);
      }
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const dyn::WedgeJoint a = paper_joint_1, b = paper_joint_2;
  auto with = [](dyn::WedgeJoint j, double dyn::WedgeJoint::*field, double value) {
    j.*field = value;
    return j;
  };
  expect_refused(with(a, &dyn::WedgeJoint::dip_deg, 95), b, 1, "joint_a.dip_deg", "[0, 90], got 95");
  expect_refused(with(a, &dyn::WedgeJoint::dip_deg, -1), b, 1, "joint_a.dip_deg", "got -1");
  expect_refused(a, with(b, &dyn::WedgeJoint::dip_deg, nan), 1, "joint_b.dip_deg", "got nan");
  expect_refused(a, with(b, &dyn::WedgeJoint::dip_direction_deg, 360), 1, "joint_b.dip_direction_deg", "[0, 360)");
  expect_refused(with(a, &dyn::WedgeJoint::dip_direction_deg, -5), b, 1, "joint_a.dip_direction_deg", "got -5");
  expect_refused(with(a, &dyn::WedgeJoint::friction_angle_deg, 90), b, 1, "joint_a.friction_angle_deg", "[0, 90)");
  expect_refused(a, with(b, &dyn::WedgeJoint::cohesion_pa, -1), 1, "joint_b.cohesion_pa", "Pa >= 0");
  expect_refused(a, with(b, &dyn::WedgeJoint::area, inf), 1, "joint_b.area", "got inf");
  expect_refused(a, b, 0, "weight_n", "N > 0");
  expect_refused(a, b, nan, "weight_n", "got nan");
  // Parallel planes: the same orientation, two horizontal planes (whatever their dip
  // directions), two vertical planes of the same strike facing each other.
  expect_refused(a, a, 1, "joint_a, joint_b", "parallel");
  expect_refused({0, 10, 30, 0, 0}, {0, 200, 30, 0, 0}, 1, "joint_a, joint_b", "parallel");
  expect_refused({90, 90, 30, 0, 0}, {90, 270, 30, 0, 0}, 1, "joint_a, joint_b", "parallel");
  // A line of intersection that does not plunge: planes of the same strike dipping opposite
  // ways meet along a horizontal line; a horizontal plane meets any other along its strike.
  expect_refused({40, 0, 30, 0, 0}, {60, 180, 30, 0, 0}, 1, "joint_a, joint_b", "plunges");
  expect_refused({0, 0, 30, 0, 0}, {45, 123, 30, 0, 0}, 1, "joint_a, joint_b", "plunges");
}
