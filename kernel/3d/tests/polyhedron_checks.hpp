#pragma once
// Validity of a HalfspacePolyhedron for the 3D kernel's tests: the invariants its header
// states, checked combinatorially (closed, consistently oriented 2-manifold of genus 0) and with
// exact signs (each vertex exactly on its faces' planes, on or below every face plane).

#include <boost/test/unit_test.hpp>

#include <cstdint>
#include <map>
#include <set>
#include <utility>

#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"

namespace rockcontact::testing {

inline void check_valid(const kernel::HalfspacePolyhedron& h) {
  namespace rk = rockcontact::kernel;
  if (h.empty()) {
    BOOST_TEST(h.vertices().empty());
    return;
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::set<std::uint32_t> used;
  for (const auto& face : h.faces()) {
    BOOST_TEST(face.loop.size() >= 3u);
    const std::size_t n = face.loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t u = face.loop[i], v = face.loop[(i + 1) % n];
      ++directed[{u, v}];
      used.insert(u);
      // Exactly on the face's own plane, on or below every face plane.
      BOOST_TEST((h.side<rk::Exact>(u, h.planes()[face.plane]) == rk::Sign::zero));
    }
  }
  for (const auto& [edge, count] : directed) {
    BOOST_TEST(count == 1);
    const auto reverse = directed.find({edge.second, edge.first});
    BOOST_TEST((reverse != directed.end() && reverse->second == 1));
  }
  BOOST_TEST(used.size() == h.vertices().size());
  const auto v = static_cast<long>(h.vertices().size()), e = static_cast<long>(directed.size() / 2),
             f = static_cast<long>(h.faces().size());
  BOOST_TEST(v - e + f == 2);  // Euler: a sphere
  for (std::uint32_t x = 0; x < h.vertices().size(); ++x) {
    for (const auto& face : h.faces()) {
      BOOST_TEST((h.side<rk::Exact>(x, h.planes()[face.plane]) != rk::Sign::positive));
    }
  }
}

}  // namespace rockcontact::testing
