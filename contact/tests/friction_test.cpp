#define BOOST_TEST_MODULE contact_friction
#include <boost/test/unit_test.hpp>

// Coulomb friction of a pair against hand-computed cases: the paper's stick/slide law (seed 000
// eq. 24-26, §3.2.6) and the elastoplastic law (friction.hpp), side by side where they differ.
// Every expected number below is worked out in the comment next to it. The inputs are chosen so
// that the arithmetic is a handful of correctly rounded operations on short decimals; the
// tolerance 1e-12 relative covers those roundings (each is 2^-53 ~ 1.1e-16 relative) with a
// wide margin and is far below any difference between the branches being tested (>= 1 %).

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "rockcontact/contact/friction/law.hpp"

namespace {

using rockcontact::contact::advance_friction;
using rockcontact::contact::commit_friction;
using rockcontact::contact::evaluate_friction;
using rockcontact::contact::FrictionLaw;
using rockcontact::contact::FrictionModel;
using rockcontact::contact::FrictionResult;
using rockcontact::contact::FrictionState;
using rockcontact::contact::Vector2;

constexpr double tolerance = 1e-12;

bool close(double a, double b, double scale) { return std::fabs(a - b) <= tolerance * scale; }

bool close(Vector2 a, Vector2 b, double scale) {
  return close(a.x, b.x, scale) && close(a.y, b.y, scale);
}

// kt = 1e7 N/m, phi = 30 deg: with |f_n| = 100 N/m the limit is 100 tan 30° = 57.735... N/m.
FrictionLaw law30() { return {1.0e7, 30.0, 0.0, FrictionModel::paper}; }
FrictionLaw elastoplastic30() { return {1.0e7, 30.0}; }
const double limit30 = 100.0 * std::tan(std::numbers::pi / 6.0);

// One step of a loading history under the normal (0, 100): the increment of CP relative to TP
// applied before the evaluation (m), and what the evaluation must find.
struct HistoryRow {
  double increment;
  double force;  // friction force x on CP, N/m
  bool sliding;
  double dissipated = 0.0;  // J/m
};

// Runs the rows through advance -> evaluate -> commit, as the integrator calls them.
void check_history(const FrictionLaw& law, const std::vector<HistoryRow>& rows) {
  FrictionState state;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    advance_friction(state, {rows[k].increment, 0.0}, law);
    const FrictionResult r = evaluate_friction(state, {0.0, 100.0}, law);
    BOOST_TEST_CONTEXT("row " << k) {
      BOOST_TEST(r.sliding == rows[k].sliding);
      BOOST_TEST(close(r.force, {rows[k].force, 0.0}, limit30));
      BOOST_TEST(close(r.dissipated, rows[k].dissipated, 1e-4));
    }
    commit_friction(state, r);
  }
}

}  // namespace

// Normal (0, 100): d = (1e-6, 2e-6) splits into d_nor = (0, 2e-6) and d_tan = (1e-6, 0);
// kt |d_tan| = 10 < 57.7, so the pair sticks with f = -kt d_tan = (-10, 0).
BOOST_AUTO_TEST_CASE(stick_below_the_limit) {
  const FrictionState state{{1e-6, 2e-6}, false, {}};
  const FrictionResult r = evaluate_friction(state, {0.0, 100.0}, law30());
  BOOST_TEST(!r.sliding);
  BOOST_TEST(close(r.force, {-10.0, 0.0}, 10.0));
  BOOST_TEST(close(r.tangential, {1e-6, 0.0}, 1e-6));
}

// Normal (30, 40): |f_n| = 50, n = (0.6, 0.8), tangent t = (0.8, -0.6). d = 2e-5 t + 1e-5 n =
// (2.2e-5, -0.4e-5), so d_tan = 2e-5 t and kt |d_tan| = 200. With phi = 20 deg the limit is
// 50 tan 20° = 18.2 < 200: slide at the limit against s = t, f = -18.2 (0.8, -0.6).
BOOST_AUTO_TEST_CASE(slide_at_the_limit_along_d_tan) {
  const FrictionState state{{2.2e-5, -0.4e-5}, false, {}};
  const FrictionResult r = evaluate_friction(state, {30.0, 40.0}, {1.0e7, 20.0, 0.0, FrictionModel::paper});
  const double limit = 50.0 * std::tan(20.0 * std::numbers::pi / 180.0);
  BOOST_TEST(r.sliding);
  BOOST_TEST(close(r.force, {-0.8 * limit, 0.6 * limit}, limit));
  BOOST_TEST(close(std::hypot(r.force.x, r.force.y), limit, limit));
  BOOST_TEST(close(r.tangential, {1.6e-5, -1.2e-5}, 2e-5));
}

// The normal part of d never produces friction: d along n gives d_tan = 0, no force, stick.
BOOST_AUTO_TEST_CASE(normal_displacement_gives_no_friction) {
  const FrictionState state{{0.6e-3, 0.8e-3}, false, {}};
  const FrictionResult r = evaluate_friction(state, {30.0, 40.0}, law30());
  BOOST_TEST(!r.sliding);
  BOOST_TEST(close(r.force, {0.0, 0.0}, 1e4 * 1e-3));  // kt |d| = 1e4 sets the scale
}

// Eq. 26, first case: the pair slid last step with f = (-57.7, 0) (moving towards +x), and d
// was reset to that step's increment (1e-7, 0). kt |d_tan| = 1 alone would stick (eq. 25), but
// f_prev . d_tan < 0 (same direction), so it keeps sliding at the full limit.
BOOST_AUTO_TEST_CASE(sliding_continues_while_the_motion_keeps_its_direction) {
  const FrictionState state{{1e-7, 0.0}, true, {-limit30, 0.0}};
  const FrictionResult r = evaluate_friction(state, {0.0, 100.0}, law30());
  BOOST_TEST(r.sliding);
  BOOST_TEST(close(r.force, {-limit30, 0.0}, limit30));
}

// Eq. 26, second case: the motion reversed (d_tan = (-1e-7, 0), f_prev . d_tan > 0). Eq. 25
// decides again: kt |d_tan| = 1 < 57.7, stick with f = -kt d_tan = (1, 0).
BOOST_AUTO_TEST_CASE(reversal_sticks_below_the_limit) {
  const FrictionState state{{-1e-7, 0.0}, true, {-limit30, 0.0}};
  const FrictionResult r = evaluate_friction(state, {0.0, 100.0}, law30());
  BOOST_TEST(!r.sliding);
  BOOST_TEST(close(r.force, {1.0, 0.0}, 1.0));
}

// A reversal larger than limit / kt in one step: kt |d_tan| = 100 >= 57.7, so it slides the new
// way at the limit (the paper's uncapped -kt d_tan would give 100 > 57.7).
BOOST_AUTO_TEST_CASE(large_reversal_slides_the_other_way_at_the_limit) {
  const FrictionState state{{-1e-5, 0.0}, true, {-limit30, 0.0}};
  const FrictionResult r = evaluate_friction(state, {0.0, 100.0}, law30());
  BOOST_TEST(r.sliding);
  BOOST_TEST(close(r.force, {limit30, 0.0}, limit30));
}

// §3.2.6: after a stick evaluation d accumulates, after a sliding one it restarts from Δd.
BOOST_AUTO_TEST_CASE(update_accumulates_after_stick_and_resets_after_sliding) {
  FrictionState stick{{1e-6, 2e-6}, false, {}};
  advance_friction(stick, {0.5e-6, -1e-6}, law30());
  BOOST_TEST(close(stick.displacement, {1.5e-6, 1e-6}, 1e-6));
  FrictionState slide{{1e-6, 2e-6}, true, {-1.0, 0.0}};
  advance_friction(slide, {0.5e-6, -1e-6}, law30());
  BOOST_TEST(close(slide.displacement, {0.5e-6, -1e-6}, 1e-6));
}

// No sliding direction and no normal force. d = 0: zero force, stick. |f_n| = 0: the limit is
// zero, so any tangential d slides with a zero force (free sliding).
BOOST_AUTO_TEST_CASE(degenerate_inputs) {
  const FrictionResult at_rest = evaluate_friction({}, {0.0, 100.0}, law30());
  BOOST_TEST(!at_rest.sliding);
  BOOST_TEST((at_rest.force == Vector2{0.0, 0.0}));
  const FrictionResult free = evaluate_friction({{1e-6, 0.0}, false, {}}, {0.0, 0.0}, law30());
  BOOST_TEST(free.sliding);
  BOOST_TEST(close(free.force, {0.0, 0.0}, 1.0));
  const FrictionResult frictionless = evaluate_friction({{1e-6, 0.0}, false, {}}, {0.0, 100.0},
                                                        {1.0e7, 0.0, 0.0, FrictionModel::paper});
  BOOST_TEST(frictionless.sliding);
  BOOST_TEST((frictionless.force == Vector2{-0.0, 0.0} || frictionless.force == Vector2{0.0, 0.0}));
}

// A loading-unloading history through evaluate -> commit -> advance, as the integrator calls
// them, under the paper's law. Normal (0, 100), phi = 30 deg (limit 57.7 N/m), kt = 1e7 N/m. Increments of CP
// relative to TP, and the force found at the start of each step:
//   d = 0                  -> 0         stick
//   +2e-6: d = 2e-6        -> -20       stick (20 < 57.7)
//   +2e-6: d = 4e-6        -> -40       stick
//   +2e-6: d = 6e-6        -> -57.7     slide (60 >= 57.7)
//   +2e-6: d = 2e-6 (reset)-> -57.7     slide (eq. 26: same direction, although 20 < 57.7)
//   -1e-6: d = -1e-6       -> +10       stick (reversal, eq. 25)
//   -1e-6: d = -2e-6       -> +20       stick (accumulates again)
BOOST_AUTO_TEST_CASE(loading_sliding_and_reversal_history) {
  check_history(law30(), {{0.0, 0.0, false},
                          {2e-6, -20.0, false},
                          {2e-6, -40.0, false},
                          {2e-6, -limit30, true},
                          {2e-6, -limit30, true},
                          {-1e-6, 10.0, false},
                          {-1e-6, 20.0, false}});
}

BOOST_AUTO_TEST_CASE(bad_laws_are_rejected_by_field) {
  using rockcontact::contact::check_friction_law;
  BOOST_CHECK_NO_THROW(check_friction_law({1.0e7, 0.0}));
  const auto message_names = [](const FrictionLaw& law, const char* field) {
    try {
      check_friction_law(law);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what()).find(field) != std::string::npos;
    }
    return false;
  };
  BOOST_TEST(message_names({0.0, 10.0}, "kt"));
  BOOST_TEST(message_names({std::nan(""), 10.0}, "kt"));
  BOOST_TEST(message_names({1.0e7, 90.0}, "friction_angle_deg"));
  BOOST_TEST(message_names({1.0e7, -1.0}, "friction_angle_deg"));
  BOOST_TEST(message_names({1.0e7, std::nan("")}, "friction_angle_deg"));
  BOOST_TEST(message_names({1.0e7, 10.0, -1.0}, "cohesion"));
  BOOST_TEST(message_names({1.0e7, 10.0, HUGE_VAL}, "cohesion"));
  BOOST_TEST(!rockcontact::contact::parse_friction_model("coulomb").has_value());
  BOOST_TEST((rockcontact::contact::parse_friction_model("paper") == FrictionModel::paper));
  BOOST_TEST((rockcontact::contact::parse_friction_model("elastoplastic") == FrictionModel::elastoplastic));
}

// ---- elastoplastic ------------------------------------------------------------------------
// Normal (0, 100) on CP: n = (0, 1), the tangent t = (-n_y, n_x) = (-1, 0). CP moving +x relative
// to TP by Δ stretches the spring to s = Δd . t = -Δ, and f_t = -kt s t = (-kt Δ, 0) opposes it.

// The same history as the paper's above. Up to the first slip they agree; the slip keeps the
// stretch at the cap limit / kt = 5.7735e-6 m (paper: resets to the increment), so the reversal
// of 1e-6 m unloads the spring from the cap: f = -kt (5.7735e-6 - 1e-6) = -47.735 N/m, still
// resisting the downhill direction (paper: +10, the spring restarted from zero). The first slip,
// from the kept stretch 4e-6 m to a trial 6e-6 m, dissipates ½ kt (4e-6 + cap)(6e-6 - cap) =
// 1.1069e-5 J/m; the next, sliding on, limit × the plastic slip 2e-6 m = 1.1547e-4 J/m.
BOOST_AUTO_TEST_CASE(elastoplastic_history_keeps_the_stretch_through_a_slip) {
  const double cap = limit30 / 1.0e7;
  check_history(elastoplastic30(), {{0.0, 0.0, false},
                                    {2e-6, -20.0, false},
                                    {2e-6, -40.0, false},
                                    {2e-6, -limit30, true, 0.5e7 * (4e-6 + cap) * (6e-6 - cap)},
                                    {2e-6, -limit30, true, limit30 * 2e-6},
                                    {-1e-6, -1.0e7 * (cap - 1e-6), false},
                                    {-1e-6, -1.0e7 * (cap - 2e-6), false}});
  // A sliding record accumulates: no reset.
  FrictionState sliding{{1e-6, 0.0}, true, {-10.0, 0.0}, {0.0, 1.0}};
  advance_friction(sliding, {0.5e-6, 0.0}, elastoplastic30());
  BOOST_TEST(close(sliding.displacement, {1.5e-6, 0.0}, 1e-6));
}

// The stretch turns with the contact frame. Built under n = (0, 1) as s = 3e-6 m along
// t = (-1, 0) (the vector (-3e-6, 0)); the normal turns to (1, 0), t' = (0, 1): the stretch is
// s t' = (0, 3e-6) and f = (0, -30) N/m, the same magnitude. (Projecting the old vector on the
// new tangent would have lost it all: (-3e-6, 0) . (0, 1) = 0.) Increments along the normal
// leave it unchanged.
BOOST_AUTO_TEST_CASE(elastoplastic_stretch_turns_with_the_normal) {
  const FrictionState built{{-3e-6, 0.0}, false, {30.0, 0.0}, {0.0, 1.0}};
  const FrictionResult r = evaluate_friction(built, {100.0, 0.0}, elastoplastic30());
  BOOST_TEST(!r.sliding);
  BOOST_TEST(close(r.force, {0.0, -30.0}, 30.0));
  BOOST_TEST(close(r.next.normal, {1.0, 0.0}, 1.0));
  FrictionState pushed = built;
  advance_friction(pushed, {0.0, 7e-6}, elastoplastic30());  // along the old normal
  const FrictionResult same = evaluate_friction(pushed, {0.0, 100.0}, elastoplastic30());
  BOOST_TEST(close(same.force, {30.0, 0.0}, 30.0));
}

// Cohesion: phi = 0, c = 1e4 Pa on L = 0.01 m gives the limit c L = 100 N/m whatever the normal
// force. A stretch of 5e-6 m (kt s = 50) sticks; 2e-5 m (200) slides at 100 N/m, keeping the
// stretch at 1e-5 m.
BOOST_AUTO_TEST_CASE(elastoplastic_cohesion_adds_c_times_the_contact_length) {
  const FrictionLaw cohesive{1.0e7, 0.0, 1.0e4};
  FrictionState state;
  advance_friction(state, {5e-6, 0.0}, cohesive);
  const FrictionResult stick = evaluate_friction(state, {0.0, 1.0}, cohesive, 0.01);
  BOOST_TEST(!stick.sliding);
  BOOST_TEST(close(stick.force, {-50.0, 0.0}, 100.0));
  commit_friction(state, stick);
  advance_friction(state, {1.5e-5, 0.0}, cohesive);
  const FrictionResult slide = evaluate_friction(state, {0.0, 1.0}, cohesive, 0.01);
  BOOST_TEST(slide.sliding);
  BOOST_TEST(close(slide.force, {-100.0, 0.0}, 100.0));
  BOOST_TEST(close(slide.tangential, {1e-5, 0.0}, 1e-5));
}
