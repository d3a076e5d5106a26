#pragma once
// Point3: a plain triple of doubles, metres. Axes: x East, y North, z Up. The exact policies
// treat each double as the exact rational it denotes.

namespace rockcontact::kernel {

struct Point3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  friend bool operator==(const Point3&, const Point3&) = default;
};

}  // namespace rockcontact::kernel
