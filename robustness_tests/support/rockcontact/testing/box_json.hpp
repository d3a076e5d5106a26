#pragma once
// The axis-aligned box [lo, hi] as the {"vertices", "faces"} of a 3D scene or pair document,
// faces counter-clockwise seen from outside: for tests that write 3D documents.

#include <array>
#include <nlohmann/json.hpp>

namespace rockcontact::testing {

inline nlohmann::json box_json(std::array<double, 3> lo, std::array<double, 3> hi) {
  return {{"vertices",
           {{lo[0], lo[1], lo[2]},
            {hi[0], lo[1], lo[2]},
            {hi[0], hi[1], lo[2]},
            {lo[0], hi[1], lo[2]},
            {lo[0], lo[1], hi[2]},
            {hi[0], lo[1], hi[2]},
            {hi[0], hi[1], hi[2]},
            {lo[0], hi[1], hi[2]}}},
          {"faces", {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}}};
}

}  // namespace rockcontact::testing
