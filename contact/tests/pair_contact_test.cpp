#define BOOST_TEST_MODULE contact_pair_contact
#include <boost/test/unit_test.hpp>

#include "rockcontact/testing/contact2d.hpp"
#include "rockcontact/testing/counting_new.hpp"

// The host-facing pair API (pair_contact.hpp) against independent references:
//   (a) the closed form "corner" of potential_contact_test.cpp (CP = [0,2]×[0,1],
//       TP = [1.25,4]×[0.25,2]: f = kn/H (-1/2, -7/16), pg = (369/226, 557/904), area 9/16),
//       given as local rectangles with poses, then with both poses turned by an angle; the
//       contact length is half the IP's perimeter, 1.5;
//   (b) the penetration depth by hand (boxes: the smaller axis overlap) and against the
//       entrance block's stored boundary distance, a separate computation;
//   (c) the independent contact2d reference data, through plain arrays;
//   (d) no allocation in steady state (operator new and GMP's allocator counted);
//   (e) distinct evaluators on distinct threads give the serial results bit for bit;
//   (f) bad input: odd arrays, non-finite poses, invalid polygons named "a"/"b", bad params;
//       the evaluator stays usable after a refusal.

#include <gmp.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "rockcontact/contact/embed/pair_contact.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/entrance_block.hpp"

// The allocation counter for (d): rockcontact/testing/counting_new.hpp.
using rockcontact::testing::heap_allocations;

namespace {

using rockcontact::PairContact;
using rockcontact::PairContactParams;
using rockcontact::PairEvaluator;
using rockcontact::PairStatus;
using rockcontact::Pose2;
using rockcontact::kernel::ConvexPolygon;
using rockcontact::kernel::Point2;
using rockcontact::kernel::PolicyKind;

PairContactParams params(PolicyKind policy, double kn = 1.0e7, double H = 1.0) {
  PairContactParams p = rockcontact::default_pair_contact_params();
  p.kn = kn;
  p.H = H;
  p.policy = policy;
  return p;
}

// A w × h rectangle centred on the local origin, CCW, interleaved.
std::vector<double> rectangle(double w, double h) {
  return {-w / 2, -h / 2, w / 2, -h / 2, w / 2, h / 2, -w / 2, h / 2};
}

Pose2 turned(const Pose2& pose, double angle) {  // the pose rotated about the world origin
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * pose.x - s * pose.y, s * pose.x + c * pose.y, pose.theta + angle};
}

// The "corner" case as the host sees it: CP = [0,2]×[0,1] centred at (1, 0.5), TP =
// [1.25,4]×[0.25,2] centred at (2.625, 1.125); all dyadic, so the poses place them exactly.
const std::vector<double> corner_a = rectangle(2.0, 1.0);
const std::vector<double> corner_b = rectangle(2.75, 1.75);
const Pose2 corner_a_pose{1.0, 0.5, 0.0};
const Pose2 corner_b_pose{2.625, 1.125, 0.0};

}  // namespace

// (a) Under every policy the posed rectangles give the closed form; the constructions are
// double sums of dyadic inputs (Filtered, Float) or exact (Exact), so 1e-12 relative covers
// the few roundings of the integration.
BOOST_AUTO_TEST_CASE(closed_form_through_poses) {
  const double kn = 2.0e7, H = 0.5, scale = kn / H;
  for (const PolicyKind policy : {PolicyKind::float_, PolicyKind::filtered, PolicyKind::exact}) {
    PairEvaluator contact(params(policy, kn, H));
    const PairContact c = contact.evaluate(corner_a, corner_a_pose, corner_b, corner_b_pose);
    BOOST_TEST_INFO(rockcontact::kernel::to_string(policy));
    BOOST_TEST((c.status == PairStatus::overlap));
    BOOST_TEST(c.area == 9.0 / 16.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(c.force[0] / scale == -0.5, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(c.force[1] / scale == -7.0 / 16.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST_REQUIRE(c.has_point);
    BOOST_TEST(c.point[0] == 369.0 / 226.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(c.point[1] == 557.0 / 904.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(c.penetration == 0.75, boost::test_tools::tolerance(1e-12));
    // The IP [1.25, 2] × [0.25, 1] has perimeter 3: L = 1.5.
    BOOST_TEST(c.length == 1.5, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(contact.intersection_polygon().size() == 4u);
  }
}

// Turning both poses by the same angle turns force and point with them. The rotated vertices
// are rounded (cos and sin are), which moves each by ~1e-16 m; the force and point are
// Lipschitz in the vertices with constants of order kn/H and 1 on this well-conditioned pair,
// so 1e-12 of their size bounds the change with a wide margin.
BOOST_AUTO_TEST_CASE(rotation_of_both_poses) {
  const double scale = 1.0e7;
  PairEvaluator contact(params(PolicyKind::filtered));
  for (const double angle : {0.3, std::numbers::pi / 2, 2.5, -1.0}) {
    const PairContact c = contact.evaluate(corner_a, turned(corner_a_pose, angle), corner_b,
                                           turned(corner_b_pose, angle));
    const double cs = std::cos(angle), sn = std::sin(angle);
    const double fx = -0.5 * scale, fy = -7.0 / 16.0 * scale;
    const double px = 369.0 / 226.0, py = 557.0 / 904.0;
    BOOST_TEST_INFO("angle " << angle);
    BOOST_TEST_REQUIRE((c.status == PairStatus::overlap && c.has_point));
    BOOST_TEST(std::hypot(c.force[0] - (cs * fx - sn * fy), c.force[1] - (sn * fx + cs * fy)) <=
               1e-12 * std::hypot(fx, fy));
    BOOST_TEST(std::hypot(c.point[0] - (cs * px - sn * py), c.point[1] - (sn * px + cs * py)) <=
               1e-12 * 4.0);
    BOOST_TEST(c.area == 9.0 / 16.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(c.penetration == 0.75, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(c.length == 1.5, boost::test_tools::tolerance(1e-12));
  }
}

// (b) Separate and touching blocks: no force, no point, zero area, penetration and length.
BOOST_AUTO_TEST_CASE(separate_and_touch) {
  PairEvaluator contact(params(PolicyKind::filtered));
  const std::vector<double> unit = rectangle(1.0, 1.0);
  const PairContact touch = contact.evaluate(unit, {0.5, 0.5, 0.0}, unit, {1.5, 0.75, 0.0});
  BOOST_TEST((touch.status == PairStatus::touch));
  const PairContact apart = contact.evaluate(unit, {0.5, 0.5, 0.0}, unit, {1.5 + 1e-9, 0.5, 0.0});
  BOOST_TEST((apart.status == PairStatus::separate));
  for (const PairContact& c : {touch, apart}) {
    BOOST_TEST(!c.has_point);
    BOOST_TEST(c.force[0] == 0.0);
    BOOST_TEST(c.force[1] == 0.0);
    BOOST_TEST(c.area == 0.0);
    BOOST_TEST(c.penetration == 0.0);
    BOOST_TEST(c.length == 0.0);
  }
  BOOST_TEST(contact.intersection_polygon().empty());
}

namespace {

struct ReferencePair {
  std::string id;
  std::vector<double> cp, tp;  // interleaved x, y, as a host passes them
  nlohmann::json expected;
};

std::vector<double> interleaved(const std::vector<Point2>& points) {
  std::vector<double> xy;
  for (const Point2& p : points) xy.insert(xy.end(), {p.x, p.y});
  return xy;
}

// The contact2d reference pairs (robustness_tests/data/contact2d: an independent exact
// computation), with kn and H.
struct ReferenceData {
  double kn = 0.0, H = 0.0;
  std::vector<ReferencePair> pairs;
};

const ReferenceData& reference_data() {
  static const ReferenceData data = [] {
    const rockcontact::testing::Contact2dData& raw = rockcontact::testing::contact2d_data();
    ReferenceData d{raw.kn, raw.H, {}};
    for (const auto& pair : raw.pairs) {
      d.pairs.push_back({pair.id, interleaved(pair.cp), interleaved(pair.tp), pair.expected});
    }
    return d;
  }();
  return data;
}

}  // namespace

// (c) Every reference pair through plain arrays and the identity pose, under Filtered and
// Exact: status exactly; area, force and point within 1e-9 of the pair's size (the reference
// data's own stated accuracy for rounded results; see its README).
BOOST_AUTO_TEST_CASE(contact2d_reference_through_arrays) {
  const ReferenceData& data = reference_data();
  BOOST_TEST_REQUIRE(!data.pairs.empty());
  for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
    PairEvaluator contact(params(policy, data.kn, data.H));
    for (const ReferencePair& ref : data.pairs) {
      const nlohmann::json& e = ref.expected;
      const double size = e.at("size").get<double>();
      const PairContact c = contact.evaluate(ref.cp, {}, ref.tp, {});
      const char* status[] = {"separate", "touch", "overlap"};
      BOOST_TEST_INFO(ref.id << " " << rockcontact::kernel::to_string(policy));
      BOOST_TEST(status[static_cast<int>(c.status)] == e.at("status").get<std::string>());
      BOOST_TEST_INFO(ref.id);
      BOOST_TEST(std::fabs(c.area - e.at("area").get<double>()) <= 1e-9 * size * size);
      const double fx = e.at("force").at(0).get<double>(), fy = e.at("force").at(1).get<double>();
      const double ftol =
          1e-9 * std::max(std::hypot(fx, fy), 1e-6 * data.kn / data.H * size * size);
      BOOST_TEST_INFO(ref.id);
      BOOST_TEST(std::hypot(c.force[0] - fx, c.force[1] - fy) <= ftol);
      BOOST_TEST_INFO(ref.id);
      BOOST_TEST(c.has_point == !e.at("point").is_null());
      if (c.has_point && !e.at("point").is_null()) {
        BOOST_TEST_INFO(ref.id);
        BOOST_TEST(std::hypot(c.point[0] - e.at("point").at(0).get<double>(),
                              c.point[1] - e.at("point").at(1).get<double>()) <= 1e-9 * size);
      }
    }
  }
}

// (b) The penetration depth equals the entrance block's boundary distance (computed there from
// the stored vertices of E, here edge by edge during the merge): bit for bit under Exact, which
// rounds the same exact value once; within 1e-12 of the pair's size under Filtered, where each
// side rounds its own differences.
BOOST_AUTO_TEST_CASE(penetration_is_the_entrance_block_distance) {
  namespace rk = rockcontact::kernel;
  const ReferenceData& data = reference_data();
  PairEvaluator exact(params(PolicyKind::exact, data.kn, data.H));
  PairEvaluator filtered(params(PolicyKind::filtered, data.kn, data.H));
  int overlaps = 0;
  for (const ReferencePair& ref : data.pairs) {
    const auto polygon = [](const std::string& name, const std::vector<double>& xy) {
      std::vector<Point2> v;
      for (std::size_t k = 0; k < xy.size(); k += 2) v.push_back({xy[k], xy[k + 1]});
      return ConvexPolygon::make(name, v);
    };
    const ConvexPolygon a = polygon("a", ref.cp), b = polygon("b", ref.tp);
    const rk::EntranceBlock e = rk::compute_entrance_block<rk::Exact>(a, b);
    const PairContact x = exact.evaluate(ref.cp, {}, ref.tp, {});
    const PairContact f = filtered.evaluate(ref.cp, {}, ref.tp, {});
    const double expected = e.status == rk::Overlap::overlap ? e.distance : 0.0;
    BOOST_TEST_INFO(ref.id);
    BOOST_TEST(x.penetration == expected);
    BOOST_TEST_INFO(ref.id);
    BOOST_TEST(std::fabs(f.penetration - expected) <= 1e-12 * ref.expected.at("size").get<double>());
    overlaps += e.status == rk::Overlap::overlap;
  }
  BOOST_TEST(overlaps > 0);
}

namespace {

std::atomic<long> gmp_allocations{0};

void* counting_gmp_alloc(std::size_t size) {
  gmp_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size);
}
void* counting_gmp_realloc(void* p, std::size_t, std::size_t size) {
  gmp_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::realloc(p, size);
}
void gmp_free(void* p, std::size_t) { std::free(p); }

}  // namespace

// (d) Once an evaluator has seen the pairs, evaluating them again allocates nothing: no
// operator new, and no GMP allocation either on pairs whose predicates never fell back. The
// batch is the reference data (3 to 10 vertices, every status) plus posed and rotated pairs.
BOOST_AUTO_TEST_CASE(no_allocation_in_steady_state) {
  const ReferenceData& data = reference_data();
  PairEvaluator contact(params(PolicyKind::filtered, data.kn, data.H));
  std::vector<const ReferencePair*> batch;
  for (const ReferencePair& ref : data.pairs) {  // warm-up, and keep pairs without fallbacks
    if (contact.evaluate(ref.cp, {}, ref.tp, {}).fallbacks == 0) batch.push_back(&ref);
  }
  // Turned by different angles: rotated copies of parallel edges stay nearly parallel, which
  // costs an exact fallback, as the reference pairs that were left out do.
  const Pose2 a_pose = turned(corner_a_pose, 0.3), b_pose = turned(corner_b_pose, 0.5);
  BOOST_TEST_REQUIRE(contact.evaluate(corner_a, a_pose, corner_b, b_pose).fallbacks == 0u);
  BOOST_TEST_MESSAGE(batch.size() << " of " << data.pairs.size() << " reference pairs without fallback");
  BOOST_TEST_REQUIRE(batch.size() > data.pairs.size() / 2);

  mp_set_memory_functions(counting_gmp_alloc, counting_gmp_realloc, gmp_free);
  const long heap_before = heap_allocations.load();
  double checksum = 0.0;
  for (int round = 0; round < 3; ++round) {
    for (const ReferencePair* ref : batch) checksum += contact.evaluate(ref->cp, {}, ref->tp, {}).area;
    checksum += contact.evaluate(corner_a, a_pose, corner_b, b_pose).force[0];
  }
  const long heap = heap_allocations.load() - heap_before;
  mp_set_memory_functions(nullptr, nullptr, nullptr);  // back to GMP's defaults
  BOOST_TEST(std::isfinite(checksum));
  BOOST_TEST(heap == 0);
  BOOST_TEST(gmp_allocations.load() == 0);
}

// (e) Four threads, each with its own evaluator, over the whole reference set under Filtered
// and Exact: the results are the serial ones bit for bit (no shared mutable state).
BOOST_AUTO_TEST_CASE(distinct_evaluators_on_threads) {
  const ReferenceData& data = reference_data();
  for (const PolicyKind policy : {PolicyKind::filtered, PolicyKind::exact}) {
    const auto run_all = [&] {
      PairEvaluator contact(params(policy, data.kn, data.H));
      std::vector<double> out;
      for (const ReferencePair& ref : data.pairs) {
        const PairContact c = contact.evaluate(ref.cp, {}, ref.tp, {});
        out.insert(out.end(), {static_cast<double>(c.status), c.force[0], c.force[1], c.point[0],
                               c.point[1], c.area, c.penetration});
      }
      return out;
    };
    const std::vector<double> serial = run_all();
    std::vector<std::vector<double>> parallel(4);
    std::vector<std::thread> threads;
    for (auto& result : parallel) threads.emplace_back([&result, &run_all] { result = run_all(); });
    for (auto& t : threads) t.join();
    for (const auto& result : parallel) BOOST_TEST((result == serial));
  }
}

// (f) Refusals name the polygon and say what was expected; the evaluator keeps working.
BOOST_AUTO_TEST_CASE(bad_input) {
  using rockcontact::kernel::InvalidPolygon;
  PairEvaluator contact(params(PolicyKind::filtered));
  const std::vector<double> unit = rectangle(1.0, 1.0);
  const std::vector<double> odd = {0, 0, 1, 0, 1};
  const std::vector<double> clockwise = {0, 0, 0, 1, 1, 1, 1, 0};
  const std::vector<double> collinear = {0, 0, 1, 0, 2, 0, 1, 1};
  const auto message = [&](const std::vector<double>& a, const Pose2& pa, const std::vector<double>& b) {
    try {
      contact.evaluate(a, pa, b, {});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  BOOST_TEST(message(odd, {}, unit).find("polygon a: 5 coordinates") != std::string::npos);
  BOOST_TEST(message(unit, {}, odd).find("polygon b: 5 coordinates") != std::string::npos);
  BOOST_TEST(message(unit, {NAN, 0.0, 0.0}, unit).find("polygon a: the pose") != std::string::npos);
  BOOST_TEST(message(unit, {0.0, 0.0, INFINITY}, unit).find("must be finite") != std::string::npos);
  BOOST_TEST(message(clockwise, {}, unit).find("polygon a: vertices are clockwise") != std::string::npos);
  BOOST_TEST(message(unit, {}, collinear).find("polygon b, vertex 1: is collinear") != std::string::npos);
  BOOST_CHECK_THROW(contact.evaluate(unit, {}, std::vector<double>{0, 0, 1, 0}, {}), InvalidPolygon);
  BOOST_CHECK_THROW(contact.evaluate(unit, {}, std::vector<double>{0, 0, NAN, 0, 1, 1}, {}),
                    InvalidPolygon);

  const PairContact c = contact.evaluate(corner_a, corner_a_pose, corner_b, corner_b_pose);
  BOOST_TEST(c.area == 9.0 / 16.0, boost::test_tools::tolerance(1e-12));

  for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    BOOST_CHECK_THROW(PairEvaluator(params(PolicyKind::filtered, bad, 1.0)), std::invalid_argument);
    BOOST_CHECK_THROW(PairEvaluator(params(PolicyKind::filtered, 1.0e7, bad)), std::invalid_argument);
  }
}
