#pragma once
// The exact volume of a HalfspacePolyhedron, unrounded, for tests that assert exact volume
// conservation under cutting, and the Exact volume's lazy stage, for tests that hold it to the
// exact one (3d/src/halfspace_polyhedron.cpp).

#include <optional>
#include <string>

#include "rockcontact/kernel/3d/halfspace_polyhedron.hpp"

namespace rockcontact::kernel::detail {

// The lazy stage of the Exact volume (halfspace_polyhedron.cpp): the exact volume's formula in
// DoubleDouble with a running error bound; the double nearest to the exact volume when the
// bound settles it, nullopt when it does not (Exact then rounds the exact rational volume).
std::optional<double> lazily_rounded_volume(const HalfspacePolyhedron& p);

// The exact rational volume as "p/q" in lowest terms ("p" when q = 1), GMP's notation.
std::string exact_volume_string(const HalfspacePolyhedron& p);

}  // namespace rockcontact::kernel::detail
