#pragma once
// The overlap verdict of two convex blocks, in any dimension: their interiors intersect
// (overlap), only their boundaries meet (touch), or they are disjoint (separate).

#include <string_view>

namespace rockcontact::kernel {

enum class Overlap { separate, touch, overlap };

constexpr std::string_view to_string(Overlap o) {
  switch (o) {
    case Overlap::separate: return "separate";
    case Overlap::touch: return "touch";
    case Overlap::overlap: return "overlap";
  }
  return "?";
}

}  // namespace rockcontact::kernel
