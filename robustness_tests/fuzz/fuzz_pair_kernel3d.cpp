// libFuzzer target: the 3D pair queries (pair3d_queries.hpp: every query of the pairs contract) under
// Checked, Filtered and Exact, on convex polyhedra built from the input bytes.
//
// Input format (missing bytes decode as zero, so every input decodes to something):
//   byte 0    bit 0: 0 = points mode, 1 = generated mode; bits 1-2: the coordinate encoding
//             of pair_input.hpp (raw, small, dyadic, tagged) for the points mode
//   points mode:
//     byte 1, 2   point counts of a and b, each modulo 25
//     [dyadic]    byte 3 scale exponent e = byte - 128, then an 8-byte raw double offset
//     coordinates x y z of a's points, then b's, in the chosen encoding
//     Each block is the convex hull of its finite points (robustness::convex_hull3: CGAL's
//     hull with exact predicates, coplanar faces merged); coplanar point sets are skipped.
//   generated mode:
//     byte 1      family (modulo the number of 3D families); bytes 2-9 seed; bytes 10-11 index
//     then groups of 4 bytes, each a perturbation of the generated pair: byte 0 picks the
//     block (bit 7) and the vertex (modulo its size), byte 1 the coordinate (modulo 3), bytes
//     2-3 a signed count k of ulps (std::nextafter |k| times, k clamped to [-256, 256]); both blocks are
//     re-hulled afterwards. Perturbing the exact touching families by a few ulps makes the
//     near-incidences the staged filters find hardest.
// Aborts (with the pair as hexadecimal floats) on:
//   * a PolicyDisagreement under Checked (a staged sign differing from its exact evaluation);
//   * Filtered's or Checked's result differing from Exact's (staged_differences);
//   * a verdict that is not symmetric in the pair under Exact;
//   * any exception from the queries (valid polyhedra must never make them throw).
// Float runs too, for crashes and sanitizer reports only.
//
// Run (clang configuration of robustness_tests/fuzz/CMakeLists.txt):
//   cmake --build build-fuzz --target fuzz_pair_kernel3d
//   build-fuzz/robustness_tests/fuzz/fuzz_pair_kernel3d -max_total_time=60 -max_len=4096 CORPUS_DIR

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pair3d_queries.hpp"
#include "pair_input.hpp"
#include "rockcontact/generators/pair3d_generators.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/core/policy_disagreement.hpp"

namespace {

namespace rb = rockcontact::robustness;
namespace rk = rockcontact::kernel;
using rc_fuzz_reader = rockcontact::fuzz::ByteReader;
using rk::ConvexPolyhedron;
using rk::Point3;

constexpr std::size_t max_points = 24;
constexpr int max_ulps = 256;

struct Blocks {
  std::optional<ConvexPolyhedron> a;
  std::optional<ConvexPolyhedron> b;
};

void print_block(const char* name, const ConvexPolyhedron& p) {
  std::fprintf(stderr, "  %s vertices = [", name);
  for (const Point3& v : p.vertices()) std::fprintf(stderr, "(%a, %a, %a) ", v.x, v.y, v.z);
  std::fprintf(stderr, "]\n");
}

[[noreturn]] void fail(const std::string& what, const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  std::fprintf(stderr, "fuzz_pair_kernel3d: %s\n", what.c_str());
  print_block("a", a);
  print_block("b", b);
  std::abort();
}

std::optional<ConvexPolyhedron> hull(const char* name, const std::vector<Point3>& points) {
  std::vector<Point3> finite;
  for (const Point3& p : points) {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) finite.push_back(p);
  }
  return rb::convex_hull3(name, finite);
}

Blocks points_mode(rc_fuzz_reader& in, std::uint8_t flags) {
  using rockcontact::fuzz::Encoding;
  const auto encoding = static_cast<Encoding>((flags >> 1) & 3u);
  const std::size_t n_a = in.byte() % (max_points + 1);
  const std::size_t n_b = in.byte() % (max_points + 1);
  int exponent = 0;
  double offset = 0.0;
  if (encoding == Encoding::dyadic) {
    exponent = static_cast<int>(in.byte()) - 128;
    offset = in.raw();
  }
  const auto coordinate = [&]() -> double {
    switch (encoding) {
      case Encoding::raw: return in.raw();
      case Encoding::small: return static_cast<std::int8_t>(in.byte());
      case Encoding::dyadic: return offset + std::ldexp(static_cast<double>(in.int16()), exponent);
      case Encoding::tagged: break;
    }
    const std::uint8_t tag = in.byte();
    return tag >= rockcontact::fuzz::tag_raw ? in.raw() : static_cast<double>(int{tag} - rockcontact::fuzz::tag_zero);
  };
  std::vector<Point3> a, b;
  for (auto [points, count] : {std::pair{&a, n_a}, std::pair{&b, n_b}}) {
    for (std::size_t i = 0; i < count; ++i) {
      const double x = coordinate();
      const double y = coordinate();
      const double z = coordinate();
      points->push_back({x, y, z});
    }
  }
  return {hull("a", a), hull("b", b)};
}

Blocks generated_mode(rc_fuzz_reader& in) {
  const rb::Family3d family = rb::all_families3d[in.byte() % rb::all_families3d.size()];
  std::uint64_t seed = 0;
  for (int i = 0; i < 8; ++i) seed |= std::uint64_t{in.byte()} << (8 * i);
  const auto index = static_cast<std::uint64_t>(static_cast<std::uint16_t>(in.int16()));
  const rb::PolyhedronPair pair = rb::generate_pair3d(family, seed, index);
  std::vector<Point3> a(pair.a.vertices().begin(), pair.a.vertices().end());
  std::vector<Point3> b(pair.b.vertices().begin(), pair.b.vertices().end());
  while (!in.done()) {
    const std::uint8_t which = in.byte();
    std::vector<Point3>& block = (which & 0x80u) != 0 ? b : a;
    Point3& v = block[(which & 0x7fu) % block.size()];
    const int axis = in.byte() % 3;
    double* c = axis == 0 ? &v.x : axis == 1 ? &v.y : &v.z;
    const int k = std::clamp<int>(in.int16(), -max_ulps, max_ulps);
    for (int i = 0; i < std::abs(k); ++i) *c = std::nextafter(*c, k > 0 ? INFINITY : -INFINITY);
  }
  return {hull("a", a), hull("b", b)};
}

void check(const ConvexPolyhedron& a, const ConvexPolyhedron& b) {
  rb::Pair3dResult checked, checked_swapped;
  try {
    checked = rb::evaluate_pair3d<rk::Checked>(a, b);
    checked_swapped = rb::evaluate_pair3d<rk::Checked>(b, a);
  } catch (const rk::PolicyDisagreement& e) {
    fail(std::string("Checked: ") + e.what(), a, b);
  }
  const rb::Pair3dResult filtered = rb::evaluate_pair3d<rk::Filtered>(a, b);
  const rb::Pair3dResult exact = rb::evaluate_pair3d<rk::Exact>(a, b);
  const rb::Pair3dResult exact_swapped = rb::evaluate_pair3d<rk::Exact>(b, a);
  const std::string diff = rb::staged_differences(filtered, exact) + rb::staged_differences(checked, exact) +
                           rb::staged_differences(checked_swapped, exact_swapped);
  if (!diff.empty()) fail("staged vs Exact: " + diff, a, b);
  const std::string swap = rb::swap_differences(exact, exact_swapped);
  if (!swap.empty()) fail("Exact: " + swap, a, b);
  static_cast<void>(rb::evaluate_pair3d<rk::Float>(a, b));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rc_fuzz_reader in({data, size});
  const std::uint8_t flags = in.byte();
  Blocks blocks = (flags & 1u) != 0 ? generated_mode(in) : points_mode(in, flags);
  if (!blocks.a || !blocks.b) return 0;
  try {
    check(*blocks.a, *blocks.b);
  } catch (const std::exception& e) {
    fail(std::string("an exception escaped the queries: ") + e.what(), *blocks.a, *blocks.b);
  }
  return 0;
}
