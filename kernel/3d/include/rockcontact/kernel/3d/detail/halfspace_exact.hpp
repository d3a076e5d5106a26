#pragma once
// The exact volume of a HalfspacePolyhedron, unrounded, for tests that assert exact volume
// conservation under cutting (3d/src/halfspace_polyhedron.cpp).

#include <string>

#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"

namespace rockcontact::kernel::detail {

// The exact rational volume as "p/q" in lowest terms ("p" when q = 1), GMP's notation.
std::string exact_volume_string(const HalfspacePolyhedron& p);

}  // namespace rockcontact::kernel::detail
