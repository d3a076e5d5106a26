#pragma once
// Point2 and Vector2: plain pairs of doubles. Coordinates are metres unless a caller says
// otherwise. The exact policy treats each double as the exact rational it denotes.

namespace rockcontact::kernel {

struct Point2 {
  double x = 0.0;
  double y = 0.0;
  friend bool operator==(const Point2&, const Point2&) = default;
};

struct Vector2 {
  double x = 0.0;
  double y = 0.0;
  friend bool operator==(const Vector2&, const Vector2&) = default;
};

}  // namespace rockcontact::kernel
