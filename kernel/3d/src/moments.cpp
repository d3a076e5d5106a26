#include "rockcontact/kernel/3d/moments.hpp"

#include <array>
#include <cstddef>

namespace rockcontact::kernel {
namespace {

using Vec = std::array<double, 3>;

Vec local(const Point3& p, const Point3& o) { return {p.x - o.x, p.y - o.y, p.z - o.z}; }

// Sums, in the local frame, of D, D s_i and D (a_i a_j + b_i b_j + c_i c_j + s_i s_j) over
// the tetrahedra (moments.hpp); divided by 6, 24 and 120 once at the end.
struct LocalSums {
  double d = 0.0;
  Vec first{};
  std::array<double, 6> second{};  // xx yy zz xy yz zx
};

constexpr std::array<std::array<int, 2>, 6> pairs{{{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}}};

void add_tetrahedron(const Vec& a, const Vec& b, const Vec& c, LocalSums& sums) {
  const double d = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0]);
  const Vec s{a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]};
  sums.d += d;
  for (int i = 0; i < 3; ++i) sums.first[i] += d * s[i];
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const int i = pairs[k][0], j = pairs[k][1];
    sums.second[k] += d * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
  }
}

}  // namespace

Moments3 moments_about(const ConvexPolyhedron& block, const Point3& o) {
  LocalSums sums;
  for (const ConvexPolyhedron::Face& face : block.faces()) {
    const Vec a = local(block[face[0]], o);
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      add_tetrahedron(a, local(block[face[k]], o), local(block[face[k + 1]], o), sums);
    }
  }
  Moments3 r;
  r.volume = sums.d / 6;
  r.first = {sums.first[0] / 24, sums.first[1] / 24, sums.first[2] / 24};
  r.xx = sums.second[0] / 120, r.yy = sums.second[1] / 120, r.zz = sums.second[2] / 120;
  r.xy = sums.second[3] / 120, r.yz = sums.second[4] / 120, r.zx = sums.second[5] / 120;
  return r;
}

Moments3 moments(const ConvexPolyhedron& block) {
  const Point3 o = block[0];
  const Moments3 local_moments = moments_about(block, o);
  const double v = local_moments.volume;
  const Vec m{local_moments.first.x, local_moments.first.y, local_moments.first.z};
  const std::array<double, 6> mm{local_moments.xx, local_moments.yy, local_moments.zz,
                                 local_moments.xy, local_moments.yz, local_moments.zx};

  // Parallel-axis shift back to the global frame.
  const Vec oo{o.x, o.y, o.z};
  Moments3 r;
  r.volume = v;
  r.first = {m[0] + oo[0] * v, m[1] + oo[1] * v, m[2] + oo[2] * v};
  std::array<double, 6> g{};
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const int i = pairs[k][0], j = pairs[k][1];
    g[k] = mm[k] + oo[i] * m[j] + oo[j] * m[i] + oo[i] * oo[j] * v;
  }
  r.xx = g[0], r.yy = g[1], r.zz = g[2], r.xy = g[3], r.yz = g[4], r.zx = g[5];
  return r;
}

}  // namespace rockcontact::kernel
