#define BOOST_TEST_MODULE contact_pair_friction
#include <boost/test/unit_test.hpp>

// Friction through the host-facing pair API (pair_friction.hpp) on a block pressed on a face
// with a known normal force and pushed along it by equal increments, as a host would step it.
//
// The pressed block: a 1 m square (polygon a) whose bottom is d = 2^-10 m below the top of a
// 4 m x 1 m base (polygon b). On the 1 m x d intersection polygon the exit distance of a is d
// except within d of its sides, and that of b is the depth below its top, so the normal force
// on a is kn (2 w d - d²) / H (w = 1 m; examples/embed/dem_host.cpp derives it) along +y, and
// the contact length is half the IP's perimeter, L = w + d. With kt = 1e7 N/m² and
// phi = 30° the Coulomb limit is F tan 30° + c L, and the spring holds a stretch of at most
// limit / kt = 1.15 mm (no cohesion): pushes of 2^-13 m (0.122 mm) reach it at the 10th.
//
// Tolerance: the pair API gives the closed-form force to 1e-12 (pair_contact_test); turning the
// scene rounds each vertex by ~1e-16 m against d ~ 1e-3 m, which moves the force by ~1e-13
// relative; the friction law adds a handful of roundings. 1e-10 of each quantity's scale covers
// all of that and is far below the differences being tested (one push is 10 % of the cap).

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "rockcontact/contact/embed/pair_friction.hpp"

namespace {

using rockcontact::PairContact;
using rockcontact::PairEvaluator;
using rockcontact::PairFriction;
using rockcontact::PairFrictionParams;
using rockcontact::PairFrictionState;
using rockcontact::Pose2;
using rockcontact::contact::FrictionModel;

constexpr double tolerance = 1e-10;
constexpr double kn = 1.0e7;            // Pa, with H = 1 m
constexpr double depth = 1.0 / 1024.0;  // d, m
constexpr double push = 1.0 / 8192.0;   // one tangential increment, m
const double normal_force = kn * (2.0 * depth - depth * depth);  // F, N/m
const double tan30 = std::tan(std::numbers::pi / 6.0);

const std::vector<double> block_xy{-0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5, 0.5};
const std::vector<double> base_xy{-2.0, -0.5, 2.0, -0.5, 2.0, 0.5, -2.0, 0.5};

PairFrictionParams params30(double cohesion = 0.0,
                            FrictionModel model = FrictionModel::elastoplastic) {
  PairFrictionParams p = rockcontact::default_pair_friction_params();
  p.kt = 1.0e7;
  p.friction_angle_deg = 30.0;
  p.cohesion = cohesion;
  p.model = model;
  return p;
}

// The pressed block with the whole scene turned by `angle` about the origin; `along` is the
// block's position along the base's top, m, and `lift` raises it (a positive lift beyond d
// separates the pair).
struct PressedBlock {
  double angle = 0.0;
  PairEvaluator contact{[] {
    rockcontact::PairContactParams p = rockcontact::default_pair_contact_params();
    p.kn = kn;
    return p;
  }()};

  // A vector of the unturned scene in the world frame.
  std::array<double, 2> world(double x, double y) const {
    return {std::cos(angle) * x - std::sin(angle) * y, std::sin(angle) * x + std::cos(angle) * y};
  }
  PairContact at(double along, double lift = 0.0) {
    const std::array<double, 2> p = world(along, 1.0 - depth + lift);
    return contact.evaluate(block_xy, {p[0], p[1], angle}, base_xy, {0.0, 0.0, angle});
  }
  // The component of a world vector along the base's top (+x of the unturned scene).
  double tangential(const double (&v)[2]) const {
    return std::cos(angle) * v[0] + std::sin(angle) * v[1];
  }
};

bool close(double actual, double expected, double scale) {
  return std::fabs(actual - expected) <= tolerance * scale;
}

}  // namespace

// The input the friction law reads: the closed-form normal force and L = w + d.
BOOST_AUTO_TEST_CASE(pressed_block_normal_force_and_length) {
  PressedBlock block;
  const PairContact c = block.at(0.0);
  BOOST_TEST_REQUIRE(c.has_point);
  BOOST_TEST(close(c.force[0], 0.0, normal_force));
  BOOST_TEST(close(c.force[1], normal_force, normal_force));
  BOOST_TEST(close(c.length, 1.0 + depth, 1.0));
}

// Elastoplastic: stick with -kt δ until kt δ reaches F tan 30°, then slide at the limit; while
// sliding each push dissipates limit × push; over the history the work done against the
// friction force (trapezoid rule, as friction.hpp counts it) equals the dissipation plus the
// spring's energy ½ limit² / kt. A push back from the cap unloads the spring by kt × push: the
// block does not slide back. In the scene's frame and turned by 0.3 rad.
BOOST_AUTO_TEST_CASE(stick_then_slide_at_the_limit) {
  for (const double angle : {0.0, 0.3}) {
    BOOST_TEST_CONTEXT("angle " << angle) {
      PressedBlock block{angle};
      const PairFrictionParams params = params30();
      const double limit = normal_force * tan30;
      PairFrictionState state;
      const std::array<double, 2> step = block.world(push, 0.0);
      PairFriction f = rockcontact::evaluate_pair_friction(state, block.at(0.0), step, params);
      BOOST_TEST(f.force[0] == 0.0);  // a new contact: the first increment is ignored
      BOOST_TEST(f.force[1] == 0.0);
      BOOST_TEST(!f.sliding);
      double work = 0.0, dissipated = 0.0, previous = 0.0;
      for (int k = 1; k <= 20; ++k) {
        f = rockcontact::evaluate_pair_friction(state, block.at(k * push), step, params);
        const double stretch = k * push;
        const bool slides = params.kt * stretch > limit;
        const double expected = slides ? -limit : -params.kt * stretch;
        BOOST_TEST_CONTEXT("push " << k) {
          BOOST_TEST(f.sliding == slides);
          BOOST_TEST(close(block.tangential(f.force), expected, limit));
          // Perpendicular to the face: the component along the normal is zero.
          BOOST_TEST(close(-std::sin(angle) * f.force[0] + std::cos(angle) * f.force[1], 0.0, limit));
          if (slides && previous == -limit) BOOST_TEST(close(f.dissipated, limit * push, limit * push));
          if (!slides) BOOST_TEST(f.dissipated == 0.0);
        }
        work += 0.5 * (-previous - expected) * push;
        dissipated += f.dissipated;
        previous = expected;
      }
      BOOST_TEST(close(dissipated, work - 0.5 * limit * limit / params.kt, work));
      const std::array<double, 2> back = block.world(-push, 0.0);
      f = rockcontact::evaluate_pair_friction(state, block.at(19 * push), back, params);
      BOOST_TEST(!f.sliding);
      BOOST_TEST(close(block.tangential(f.force), -limit + params.kt * push, limit));
      BOOST_TEST(f.dissipated == 0.0);
    }
  }
}

// The cohesion adds c L to the limit: with c = 5 kPa, 5 kPa × (1 + d) m = 5004.9 N/m more, a
// cap of 1.65 mm, reached at the 14th push.
BOOST_AUTO_TEST_CASE(cohesion_raises_the_limit) {
  PressedBlock block;
  const PairFrictionParams params = params30(5000.0);
  const double limit = normal_force * tan30 + 5000.0 * (1.0 + depth);
  PairFrictionState state;
  const std::array<double, 2> step{push, 0.0};
  rockcontact::evaluate_pair_friction(state, block.at(0.0), step, params);
  for (int k = 1; k <= 20; ++k) {
    const PairFriction f = rockcontact::evaluate_pair_friction(state, block.at(k * push), step, params);
    BOOST_TEST_CONTEXT("push " << k) {
      BOOST_TEST(f.sliding == (k >= 14));
      BOOST_TEST(close(f.force[0], k >= 14 ? -limit : -params.kt * k * push, limit));
    }
  }
}

// Separation resets the state to a new contact and gives no force; pressed again, the pair
// starts unstretched wherever it lands (the increment of that call is ignored).
BOOST_AUTO_TEST_CASE(separation_resets_the_state) {
  PressedBlock block;
  const PairFrictionParams params = params30();
  PairFrictionState state;
  const std::array<double, 2> step{push, 0.0};
  for (int k = 0; k <= 12; ++k) {
    rockcontact::evaluate_pair_friction(state, block.at(k * push), step, params);
  }
  BOOST_TEST_REQUIRE(state.record.sliding);
  const PairContact apart = block.at(0.0, 2.0 * depth);
  BOOST_TEST_REQUIRE(!apart.has_point);
  PairFriction f = rockcontact::evaluate_pair_friction(state, apart, step, params);
  BOOST_TEST(f.force[0] == 0.0);
  BOOST_TEST(f.force[1] == 0.0);
  BOOST_TEST(!f.sliding);
  BOOST_TEST(!state.in_contact);
  BOOST_TEST(state.record.displacement.x == 0.0);
  BOOST_TEST(!state.record.sliding);
  f = rockcontact::evaluate_pair_friction(state, block.at(0.25), {0.5, 0.5}, params);
  BOOST_TEST(f.force[0] == 0.0);
  BOOST_TEST(!f.sliding);
  f = rockcontact::evaluate_pair_friction(state, block.at(0.25 + push), step, params);
  BOOST_TEST(close(f.force[0], -params.kt * push, params.kt * push));
  BOOST_TEST(!f.sliding);
}

// The paper's law (eq. 25-26): the same stick, then the limit; the spring restarts after each
// sliding step (d = Δd) and still slides, as the motion goes on the same way. Each push after a
// sliding step dissipates limit × push; the push that first slides dissipates nothing yet.
BOOST_AUTO_TEST_CASE(paper_law_through_the_pair_api) {
  PressedBlock block;
  const PairFrictionParams params = params30(0.0, FrictionModel::paper);
  const double limit = normal_force * tan30;
  PairFrictionState state;
  const std::array<double, 2> step{push, 0.0};
  rockcontact::evaluate_pair_friction(state, block.at(0.0), step, params);
  for (int k = 1; k <= 15; ++k) {
    const PairFriction f = rockcontact::evaluate_pair_friction(state, block.at(k * push), step, params);
    BOOST_TEST_CONTEXT("push " << k) {
      BOOST_TEST(f.sliding == (k >= 10));
      BOOST_TEST(close(f.force[0], k >= 10 ? -limit : -params.kt * k * push, limit));
      BOOST_TEST(close(f.dissipated, k >= 11 ? limit * push : 0.0, limit * push));
    }
  }
}

// Bad parameters and inputs are refused with a message naming the field, and the state is left
// as it was.
BOOST_AUTO_TEST_CASE(bad_input_names_the_field) {
  PressedBlock block;
  const PairContact c = block.at(0.0);
  PairFrictionState state;
  rockcontact::evaluate_pair_friction(state, c, {0.0, 0.0}, params30());
  rockcontact::evaluate_pair_friction(state, c, {push, 0.0}, params30());
  const PairFrictionState before = state;
  const auto message = [&](const PairFrictionParams& p, std::array<double, 2> increment,
                           const PairContact& pair) -> std::string {
    try {
      rockcontact::evaluate_pair_friction(state, pair, increment, p);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "not refused";
  };
  PairFrictionParams p = params30();
  p.kt = 0.0;
  BOOST_TEST(message(p, {0.0, 0.0}, c).find("kt must be finite and > 0") != std::string::npos);
  p = params30();
  p.friction_angle_deg = 90.0;
  BOOST_TEST(message(p, {0.0, 0.0}, c).find("friction_angle_deg must be in [0, 90)") !=
             std::string::npos);
  p.friction_angle_deg = NAN;
  BOOST_TEST(message(p, {0.0, 0.0}, c).find("friction_angle_deg") != std::string::npos);
  p = params30(-1.0);
  BOOST_TEST(message(p, {0.0, 0.0}, c).find("cohesion must be finite and >= 0") !=
             std::string::npos);
  BOOST_TEST(message(params30(), {INFINITY, 0.0}, c).find("increment must be finite") !=
             std::string::npos);
  PairContact bad = c;
  bad.length = -1.0;
  BOOST_TEST(message(params30(), {0.0, 0.0}, bad).find("length") != std::string::npos);
  BOOST_CHECK_THROW(rockcontact::check_pair_friction_params(params30(-1.0)), std::invalid_argument);
  BOOST_TEST(state.in_contact == before.in_contact);
  BOOST_TEST((state.record.displacement == before.record.displacement));
  BOOST_TEST((state.record.force == before.record.force));
  BOOST_TEST(state.record.force.x == -params30().kt * push,
             boost::test_tools::tolerance(tolerance));
}
