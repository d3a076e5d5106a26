#pragma once
// The byte format of fuzz_pair_kernel's inputs, decoded by the target and encoded by
// fuzz_corpus (the seed corpus from the pair generators). One header so the two cannot drift.
//
//   byte 0        flags: bits 0-1 coordinate encoding (below); bit 2 build the polygons with
//                 robustness::convex_hull instead of ConvexPolygon::make; bit 3 make with
//                 VertexOrder::normalise; bit 4 paper demarcation instead of exact
//   byte 1, 2     vertex counts of cp and tp, each taken modulo max_vertices + 1 (so 0, 1, 2
//                 and other invalid counts occur)
//   [dyadic only] byte 3 scale exponent e = byte - 128 (the int16 step is 2^e), then an
//                 8-byte raw double added to every coordinate (far-from-origin placement)
//   coordinates   x0 y0 x1 y1 ... of cp, then of tp, each in the chosen encoding:
//     raw      8 bytes, the IEEE bit pattern (little-endian): NaN, infinities, subnormals,
//              huge and tiny values all occur;
//     small    1 byte, a signed integer in [-128, 127]: exact collinearity, repeated vertices
//              and touching pairs are frequent;
//     dyadic   2 bytes, a signed integer k: offset + k 2^e (one rounding when offset != 0);
//     tagged   1 tag byte per coordinate: tag < 0xf0 is the small integer tag - 0x78, a tag
//              >= 0xf0 is followed by a raw double: mostly lattice points, now and then a
//              special value.
// Missing bytes decode as zero, so every input decodes to something.

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::fuzz {

using kernel::Point2;

enum class Encoding : std::uint8_t { raw = 0, small = 1, dyadic = 2, tagged = 3 };

inline constexpr std::uint8_t flag_hull = 1u << 2;
inline constexpr std::uint8_t flag_normalise = 1u << 3;
inline constexpr std::uint8_t flag_paper = 1u << 4;
inline constexpr std::size_t max_vertices = 24;
inline constexpr std::uint8_t tag_raw = 0xf0;
inline constexpr int tag_zero = 0x78;

struct PairInput {
  Encoding encoding = Encoding::raw;
  bool hull = false;
  bool normalise = false;
  bool paper_demarcation = false;
  std::vector<Point2> cp;
  std::vector<Point2> tp;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  std::uint8_t byte() { return pos_ < bytes_.size() ? bytes_[pos_++] : 0; }
  bool done() const { return pos_ >= bytes_.size(); }

  double raw() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= std::uint64_t{byte()} << (8 * i);
    return std::bit_cast<double>(bits);
  }

  std::int16_t int16() {
    const auto low = static_cast<std::uint16_t>(byte());
    const auto high = static_cast<std::uint16_t>(byte());
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(low | (high << 8)));
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

inline PairInput decode_pair(std::span<const std::uint8_t> bytes) {
  ByteReader in(bytes);
  PairInput out;
  const std::uint8_t flags = in.byte();
  out.encoding = static_cast<Encoding>(flags & 3u);
  out.hull = (flags & flag_hull) != 0;
  out.normalise = (flags & flag_normalise) != 0;
  out.paper_demarcation = (flags & flag_paper) != 0;
  const std::size_t n_cp = in.byte() % (max_vertices + 1);
  const std::size_t n_tp = in.byte() % (max_vertices + 1);
  int exponent = 0;
  double offset = 0.0;
  if (out.encoding == Encoding::dyadic) {
    exponent = static_cast<int>(in.byte()) - 128;
    offset = in.raw();
  }
  const auto coordinate = [&]() -> double {
    switch (out.encoding) {
      case Encoding::raw: return in.raw();
      case Encoding::small: return static_cast<std::int8_t>(in.byte());
      case Encoding::dyadic: return offset + std::ldexp(static_cast<double>(in.int16()), exponent);
      case Encoding::tagged: break;
    }
    const std::uint8_t tag = in.byte();
    return tag >= tag_raw ? in.raw() : static_cast<double>(int{tag} - tag_zero);
  };
  for (auto [polygon, count] : {std::pair{&out.cp, n_cp}, std::pair{&out.tp, n_tp}}) {
    polygon->reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double x = coordinate();
      const double y = coordinate();
      polygon->push_back({x, y});
    }
  }
  return out;
}

// The raw encoding of a pair, made with ConvexPolygon::make (the generators' polygons are
// valid as they stand); vertex counts above max_vertices are a caller error.
inline std::vector<std::uint8_t> encode_raw_pair(std::span<const Point2> cp, std::span<const Point2> tp,
                                                 std::uint8_t extra_flags = 0) {
  std::vector<std::uint8_t> out{static_cast<std::uint8_t>(static_cast<std::uint8_t>(Encoding::raw) | extra_flags),
                                static_cast<std::uint8_t>(cp.size()), static_cast<std::uint8_t>(tp.size())};
  for (const auto polygon : {cp, tp}) {
    for (const Point2& p : polygon) {
      for (const double c : {p.x, p.y}) {
        const auto bits = std::bit_cast<std::uint64_t>(c);
        for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(bits >> (8 * i)));
      }
    }
  }
  return out;
}

}  // namespace rockcontact::fuzz
