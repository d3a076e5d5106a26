#include "rockcontact/kernel/2d/moments.hpp"

namespace rockcontact::kernel {

// Green's theorem per edge (x_i, y_i) -> (x_{i+1}, y_{i+1}) with w = x_i y_{i+1} - x_{i+1} y_i:
//   S   = Σ w / 2
//   Sx  = Σ w (x_i + x_{i+1}) / 6,            Sy  = Σ w (y_i + y_{i+1}) / 6
//   Sxx = Σ w (x_i² + x_i x_{i+1} + x_{i+1}²) / 12,  Syy likewise in y
//   Sxy = Σ w (2 x_i y_i + x_i y_{i+1} + x_{i+1} y_i + 2 x_{i+1} y_{i+1}) / 24
// evaluated relative to o = the first vertex, then shifted: with local moments s*,
//   Sx = s_x + ox S,  Sxx = s_xx + 2 ox s_x + ox² S,  Sxy = s_xy + ox s_y + oy s_x + ox oy S.
PolygonMoments compute_moments(std::span<const Point2> v) {
  const Point2 o = v[0];
  double S = 0, Sx = 0, Sy = 0, Sxx = 0, Syy = 0, Sxy = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Point2& p = v[i];
    const Point2& q = v[i + 1 == v.size() ? 0 : i + 1];
    const double x0 = p.x - o.x, y0 = p.y - o.y, x1 = q.x - o.x, y1 = q.y - o.y;
    const double w = x0 * y1 - x1 * y0;
    S += w;
    Sx += w * (x0 + x1);
    Sy += w * (y0 + y1);
    Sxx += w * (x0 * x0 + x0 * x1 + x1 * x1);
    Syy += w * (y0 * y0 + y0 * y1 + y1 * y1);
    Sxy += w * (2 * x0 * y0 + x0 * y1 + x1 * y0 + 2 * x1 * y1);
  }
  S /= 2, Sx /= 6, Sy /= 6, Sxx /= 12, Syy /= 12, Sxy /= 24;
  PolygonMoments m;
  m.S = S;
  m.Sx = Sx + o.x * S;
  m.Sy = Sy + o.y * S;
  m.Sxx = Sxx + 2 * o.x * Sx + o.x * o.x * S;
  m.Syy = Syy + 2 * o.y * Sy + o.y * o.y * S;
  m.Sxy = Sxy + o.x * Sy + o.y * Sx + o.x * o.y * S;
  return m;
}

}  // namespace rockcontact::kernel
