// libFuzzer target: the scene reader (dynamics/scene.hpp), parsing and validation only; no
// simulation runs.
//
// The bytes are the scene file. read_scene_file either returns a Scene or throws InputError
// with a message "<file>: <path>: <problem>"; any other exception, a crash, a sanitizer report
// or a hang (libFuzzer's -timeout) is a failure. An accepted scene must hold what the format
// promises: dt, duration and H finite and > 0, one material name per block, the generated
// blocks inside the block list, tracked ids among the blocks, and every block a valid polygon
// (ConvexPolygon::make, or kernel::convex_partition for a non-convex one). The cheap functions
// a run starts with are called too: step_count, mean_edge_length, generated_blocks_json.
//
// Work bound. The reader does real geometry: it cuts regions by joint sets (CGAL
// arrangements), partitions non-convex blocks (O(n^4)) and, for H = "inscribed", solves every
// triple of edges of every block (O(n^4)). The library bounds each cut (kernel/block_cutting.hpp:
// at most 10^6 trace lines, 10^6 pieces and 10^7 potential crossings), so absurd spacings fail
// fast; but a cut just inside those bounds still takes minutes, far beyond libFuzzer's
// -timeout, and is not a bug. So before calling the reader this target estimates each region's
// cut from the raw JSON, as the library does: per set, the trace lines across the region's
// extent along the set's normal plus three (the library adds one on each side; one more for
// rounding), the pieces along the disc the library lays them on, the crossings summed over
// pairs of sets with different dips. Then
//   * every region within max_trace_lines, max_trace_pieces and max_crossings: the reader runs;
//   * the first region beyond that is beyond twice a library bound, the regions before it
//     within ours: the reader runs and must reject the scene (InputError), which it does
//     before cutting anything big. This is the "spacing 1e-9 m in a 1 km region" case: an error,
//     not a hang;
//   * otherwise the document is skipped (no verdict).
// Documents holding a polygon of more than max_polygon_vertices vertices are skipped too, and
// documents the estimate cannot read (a missing or non-numeric field) go to the reader
// unchanged: it rejects them before cutting anything.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "json_target.hpp"
#include "rockcontact/dynamics/io/scene.hpp"
#include "rockcontact/kernel/2d/block_cutting.hpp"
#include "rockcontact/kernel/2d/convex_polygon.hpp"

namespace {

namespace rd = rockcontact::dynamics;
namespace rk = rockcontact::kernel;
namespace rf = rockcontact::fuzz;
using nlohmann::json;
constexpr const char* target = "fuzz_scene_json";

constexpr double max_trace_lines = 256;
constexpr double max_trace_pieces = 2048;
constexpr double max_crossings = 4096;
constexpr std::size_t max_polygon_vertices = 24;

constexpr double pi = 3.141592653589793;

std::optional<double> number(const json& object, const char* key) {
  if (!object.is_object() || !object.contains(key) || !object.at(key).is_number()) return std::nullopt;
  return object.at(key).get<double>();
}

// A region's vertices, or nullopt when they are not an array of numeric pairs (the reader
// rejects those before cutting).
std::optional<std::vector<rk::Point2>> region_vertices(const json& region) {
  if (!region.is_object() || !region.contains("vertices") || !region.at("vertices").is_array()) {
    return std::nullopt;
  }
  std::vector<rk::Point2> out;
  for (const json& v : region.at("vertices")) {
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) return std::nullopt;
    out.push_back({v[0].get<double>(), v[1].get<double>()});
  }
  return out;
}

// max - min of (dx, dy) . v over the vertices.
double extent(const std::vector<rk::Point2>& vertices, double dx, double dy) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const rk::Point2& v : vertices) {
    lo = std::min(lo, dx * v.x + dy * v.y);
    hi = std::max(hi, dx * v.x + dy * v.y);
  }
  return hi - lo;
}

struct CutWork {
  double lines = 0.0;
  double pieces = 0.0;
  double crossings = 0.0;
};

// The work of cutting `vertices` by the readable sets of `sets`. The library lays the pieces of
// a non-persistent set along a disc 6.25 % wider than the bounding box's circumscribed circle.
CutWork cut_work(const json& sets, const std::vector<rk::Point2>& vertices) {
  CutWork work;
  const double disc = 1.0625 * std::hypot(extent(vertices, 1.0, 0.0), extent(vertices, 0.0, 1.0));
  std::vector<std::pair<double, double>> dip_and_lines;
  for (const json& set : sets) {
    const std::optional<double> dip = number(set, "dip_deg"), spacing = number(set, "spacing");
    if (!dip || !spacing || !(*spacing > 0.0)) continue;
    const double angle = *dip * pi / 180.0, c = std::cos(angle), s = std::sin(angle);
    const double lines = extent(vertices, -s, c) / *spacing + 3.0;
    const std::optional<double> length = number(set, "length");
    const double period = length.value_or(0.0) + number(set, "gap").value_or(0.0);
    work.pieces += length ? lines * (disc / period + 3.0) : lines;
    for (const auto& [other_dip, other_lines] : dip_and_lines) {
      if (other_dip != *dip) work.crossings += lines * other_lines;
    }
    work.lines += lines;
    dip_and_lines.emplace_back(*dip, lines);
  }
  return work;
}

bool within(const CutWork& w, double lines, double pieces, double crossings) {
  // Written so that NaN (an infinite extent over an infinite spacing) is never within.
  return w.lines <= lines && w.pieces <= pieces && w.crossings <= crossings;
}

bool polygon_too_large(const json& object) {
  return object.is_object() && object.contains("vertices") && object.at("vertices").is_array() &&
         object.at("vertices").size() > max_polygon_vertices;
}

enum class Verdict { run, must_reject, skip };

// Which of the three cases described at the top the document falls in.
Verdict classify(const std::uint8_t* data, std::size_t size) {
  const json document = json::parse(data, data + size, nullptr, false);
  if (document.is_discarded() || !document.is_object()) return Verdict::run;
  if (document.contains("blocks") && document.at("blocks").is_array()) {
    for (const json& block : document.at("blocks")) {
      if (polygon_too_large(block)) return Verdict::skip;
    }
  }
  if (!document.contains("region")) return Verdict::run;
  const json& region = document.at("region");
  const json single = json::array({region});
  const json& regions = region.is_array() ? region : single;
  const json no_sets = json::array();
  const json& sets =
      document.contains("joint_sets") && document.at("joint_sets").is_array() ? document.at("joint_sets") : no_sets;
  for (const json& r : regions) {
    if (polygon_too_large(r)) return Verdict::skip;
  }
  CutWork total;
  for (const json& r : regions) {
    const std::optional<std::vector<rk::Point2>> vertices = region_vertices(r);
    if (!vertices) continue;
    const CutWork work = cut_work(sets, *vertices);
    total.lines += work.lines;
    total.pieces += work.pieces;
    total.crossings += work.crossings;
    if (within(total, max_trace_lines, max_trace_pieces, max_crossings)) continue;
    const bool library_rejects =
        !within(work, 2.0 * static_cast<double>(rk::max_cut_trace_lines),
                2.0 * static_cast<double>(rk::max_cut_trace_pieces), 2.0 * rk::max_cut_trace_crossings);
    return library_rejects ? Verdict::must_reject : Verdict::skip;
  }
  return Verdict::run;
}

bool positive_finite(double value) { return std::isfinite(value) && value > 0.0; }

void check_block(const rd::BlockSpec& block) {
  try {
    rk::ConvexPolygon::make(block.id, block.vertices);
  } catch (const rk::InvalidPolygon& e) {
    if (e.reason() != rk::InvalidPolygon::Reason::not_convex) {
      rf::fail(target, "accepted an invalid block: " + std::string(e.what()));
    }
    try {
      rk::convex_partition(block.vertices);
    } catch (const rk::InvalidCut& cut) {
      rf::fail(target, "accepted a non-convex block that is not simple: " + std::string(cut.what()));
    }
  }
}

void check_accepted(const rd::Scene& scene) {
  if (!positive_finite(scene.params.dt) || !positive_finite(scene.duration)) {
    rf::fail(target, "accepted a scene with dt or duration not finite and > 0");
  }
  if (!positive_finite(scene.law.normal.H) || !positive_finite(scene.law.normal.kn)) {
    rf::fail(target, "accepted a scene whose kn or resolved H is not finite and > 0 (H = " +
                         std::to_string(scene.law.normal.H) + ")");
  }
  if (scene.material_names.size() != scene.blocks.size() ||
      scene.generated_first + scene.generated_count > scene.blocks.size()) {
    rf::fail(target, "accepted a scene whose block bookkeeping is inconsistent");
  }
  for (const std::string& id : scene.track) {
    const bool known = std::any_of(scene.blocks.begin(), scene.blocks.end(),
                                   [&](const rd::BlockSpec& b) { return b.id == id; });
    if (!known) rf::fail(target, "accepted a scene tracking an unknown block");
  }
  for (const rd::BlockSpec& block : scene.blocks) check_block(block);
  rd::step_count(scene);
  rd::mean_edge_length(scene.blocks);
  rd::generated_blocks_json(scene).dump(2);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static rf::ScratchFile scratch("fuzz_scene_json");
  const Verdict verdict = classify(data, size);
  if (verdict == Verdict::skip) return 0;
  const std::filesystem::path& file = scratch.write({data, size});
  try {
    const rd::Scene scene = rd::read_scene_file(file);
    if (verdict == Verdict::must_reject) {
      rf::fail(target, "accepted a scene whose cut is beyond the library's work bounds");
    }
    check_accepted(scene);
  } catch (const rd::InputError& e) {
    rf::check_input_error(target, e, file);
  } catch (const std::exception& e) {
    rf::fail(target, std::string("an exception other than InputError: ") + e.what());
  }
  return 0;
}
