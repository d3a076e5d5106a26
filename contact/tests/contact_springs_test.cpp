#define BOOST_TEST_MODULE contact_contact_springs
#include <boost/test/unit_test.hpp>

// The linear model of a contact line (contact_springs.hpp), which the 2D pre-solve's Newton
// iterations use, against closed forms worked out in the comments:
//   - contact_line of a block pressed into a wider one: the normal, the stretch, the gaps;
//   - closed_part: where a linear gap is negative, as fractions of the line;
//   - gauss_springs: two springs whose force and moment are those of the penalty pressure
//     2 kn / H (-g) over the closed part (the two-point Gauss rule is exact for them: the
//     force integrand is linear, the moment's quadratic);
//   - part_force_change: 2 kn / H times the integral of |g| over the parts' difference.
// Tolerances: the inputs are short decimals and each result a handful of operations, so 1e-12
// relative (or 1e-18 m absolute on gaps of order 1e-3 m) covers the roundings with a margin,
// far below the differences the cases are built to show.

#include <algorithm>
#include <cmath>

#include "rockcontact/contact/potential2d/contact_springs.hpp"

namespace {

using rockcontact::contact::closed_part;
using rockcontact::contact::contact_line;
using rockcontact::contact::ContactLine;
using rockcontact::contact::gauss_springs;
using rockcontact::contact::Interval;
using rockcontact::contact::part_force_change;
using rockcontact::kernel::ConvexPolygon;
using rockcontact::kernel::Point2;

// A line of length 2 m along x from (0, 0), normal +y, with gap g0 at x = 0 and g1 at x = 2.
ContactLine line_with(double g0, double g1) { return {{0.0, 0.0}, {2.0, 0.0}, {0.0, 1.0}, g0, g1}; }

BOOST_AUTO_TEST_CASE(the_line_of_a_block_pressed_into_a_wider_one_is_their_common_stretch) {
  // a = [0.25, 0.75] x [0.999, 2] pressed 1 mm into b = [0, 1] x [0, 1]. Both faces' axes
  // separate by -0.001 m; either way the normal points from b towards a, (0, 1), the line is
  // a's bottom edge over b's top (0.5 m long, from x = 0.25 to 0.75) and its gaps are -0.001.
  const ConvexPolygon b = ConvexPolygon::make("b", {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}});
  const ConvexPolygon a = ConvexPolygon::make("a", {{0.25, 0.999}, {0.75, 0.999}, {0.75, 2.0}, {0.25, 2.0}});
  const auto line = contact_line(a, b, 0.01);
  BOOST_REQUIRE(line.has_value());
  BOOST_TEST(std::abs(line->normal.x) < 1e-12);
  BOOST_TEST(line->normal.y == 1.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(line->gap_from == -0.001, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(line->gap_to == -0.001, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(std::min(line->from.x, line->to.x) == 0.25, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(std::max(line->from.x, line->to.x) == 0.75, boost::test_tools::tolerance(1e-12));
  // 2 cm apart it is still a line within a reach of 0.05 m, with gaps +0.02; not within 0.01.
  const ConvexPolygon above = ConvexPolygon::make("above", {{0.25, 1.02}, {0.75, 1.02}, {0.75, 2.0}, {0.25, 2.0}});
  const auto apart = contact_line(above, b, 0.05);
  BOOST_REQUIRE(apart.has_value());
  BOOST_TEST(apart->gap_from == 0.02, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(!contact_line(above, b, 0.01).has_value());
}

BOOST_AUTO_TEST_CASE(the_closed_part_is_where_the_gap_is_negative) {
  // g from -1e-3 to +3e-3: zero at t = 1/4.
  const Interval part = closed_part(line_with(-1e-3, 3e-3));
  BOOST_TEST(part.first == 0.0);
  BOOST_TEST(part.last == 0.25, boost::test_tools::tolerance(1e-12));
  // Moved apart by 2e-3 at the left end and together by 4e-3 at the right: g from 1e-3 to
  // -1e-3, closed from t = 1/2 to 1.
  const Interval moved = closed_part(line_with(-1e-3, 3e-3), 2e-3, -4e-3);
  BOOST_TEST(moved.first == 0.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(moved.last == 1.0);
  BOOST_TEST(closed_part(line_with(1e-3, 2e-3)).empty());
  const Interval whole = closed_part(line_with(-1e-3, -2e-3));
  BOOST_TEST((whole.first == 0.0 && whole.last == 1.0));
}

BOOST_AUTO_TEST_CASE(two_gauss_springs_carry_the_force_and_moment_of_the_pressure) {
  // g from -1e-3 at x = 0 to +3e-3 at x = 2: closed on x in [0, 0.5], where -g = 1e-3 - 2e-3 x.
  // Pressure 2 kn / H (-g) (kn = 2e9 Pa, H = 0.5 m: 8e9 per metre):
  //   force  = 8e9 ∫_0^0.5 (1e-3 - 2e-3 x) dx = 8e9 (5e-4 - 2.5e-4) = 2e6 N/m,
  //   moment about x = 0: 8e9 ∫_0^0.5 x (1e-3 - 2e-3 x) dx = 8e9 (1.25e-4 - 8.3333e-5)
  //          = 8e9 / 24000 = 333333.33 N.
  const ContactLine line = line_with(-1e-3, 3e-3);
  const auto springs = gauss_springs(line, closed_part(line), 2e9, 0.5);
  double force = 0.0, moment = 0.0;
  for (const auto& s : springs) {
    force += s.k * -s.gap;
    moment += s.k * -s.gap * s.at.x;
    BOOST_TEST(s.at.y == 0.0);
  }
  BOOST_TEST(force == 2e6, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(moment == 8e9 / 24000.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(a_part_change_is_measured_by_the_force_it_moves) {
  const double kn = 2e9, H = 0.5;  // 2 kn / H = 8e9 Pa/m; the line is 2 m long
  const ContactLine line = line_with(-1e-3, 3e-3);  // g(t) = -1e-3 + 4e-3 t, zero at t = 1/4
  // The same part: nothing changes.
  BOOST_TEST(part_force_change(line, {0.0, 0.25}, {0.0, 0.25}, kn, H) == 0.0);
  // Its end moved from 0.25 to 0.2: ∫_0.2^0.25 |g| dt = ½ (2e-4) (0.05) = 5e-6, times 2 m and
  // 8e9: 8e4 N/m. The force of the part [0, 0.2] is indeed 8e9 * 2 * ∫_0^0.2 (1e-3 - 4e-3 t)
  // dt = 8e9 * 2 * 1.2e-4 = 1.92e6 against 2e6 for [0, 0.25].
  BOOST_TEST(part_force_change(line, {0.0, 0.25}, {0.0, 0.2}, kn, H) == 8e4,
             boost::test_tools::tolerance(1e-12));
  // Moved past the zero, to 0.3: the gap there is positive, and the bound counts it as well:
  // ∫_0.25^0.3 |g| = ½ (2e-4)(0.05) = 5e-6 -> 8e4.
  BOOST_TEST(part_force_change(line, {0.0, 0.25}, {0.0, 0.3}, kn, H) == 8e4,
             boost::test_tools::tolerance(1e-12));
  // Across the zero, from [0.2, 0.25] to [0.25, 0.3]: disjoint, both count: 8e4 + 8e4.
  BOOST_TEST(part_force_change(line, {0.2, 0.25}, {0.25, 0.3}, kn, H) == 1.6e5,
             boost::test_tools::tolerance(1e-12));
  // Opened: the whole closed part's force, 2e6.
  BOOST_TEST(part_force_change(line, {0.0, 0.25}, {}, kn, H) == 2e6, boost::test_tools::tolerance(1e-12));
  // With the ends moved by the approach: gaps 1e-3 and -1e-3 (g = 1e-3 - 2e-3 t, zero at 1/2);
  // closing [0.5, 1] from [0.6, 1]: ∫_0.5^0.6 |g| = ½ (2e-4)(0.1) = 1e-5 -> 1.6e5.
  BOOST_TEST(part_force_change(line, {0.6, 1.0}, {0.5, 1.0}, kn, H, 2e-3, -4e-3) == 1.6e5,
             boost::test_tools::tolerance(1e-12));
}

}  // namespace
