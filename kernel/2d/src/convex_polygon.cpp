#include "rockcontact/kernel/2d/convex_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "rockcontact/kernel/core/number_policy.hpp"
#include "rockcontact/kernel/2d/predicates.hpp"

namespace rockcontact::kernel {

InvalidPolygon::InvalidPolygon(std::string polygon, std::ptrdiff_t vertex, Reason reason,
                               const std::string& what)
    : std::invalid_argument(what), polygon_(std::move(polygon)), vertex_(vertex), reason_(reason) {}

namespace {

[[noreturn]] void fail(const std::string& name, std::ptrdiff_t vertex, InvalidPolygon::Reason reason,
                       const std::string& expected) {
  std::ostringstream message;
  message << "polygon " << name;
  if (vertex >= 0) message << ", vertex " << vertex;
  message << ": " << expected;
  throw InvalidPolygon(name, vertex, reason, message.str());
}

void check_finite(const std::string& name, std::span<const Point2> v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y)) {
      fail(name, static_cast<std::ptrdiff_t>(i), InvalidPolygon::Reason::non_finite,
           "coordinates must be finite numbers");
    }
  }
}

// Reports the later index of the first repeated pair (in input order).
void check_distinct(const std::string& name, std::span<const Point2> v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto less = [&](std::size_t a, std::size_t b) {
    return v[a].x != v[b].x ? v[a].x < v[b].x : (v[a].y != v[b].y ? v[a].y < v[b].y : a < b);
  };
  std::sort(order.begin(), order.end(), less);
  std::ptrdiff_t worst = -1;
  std::size_t first = 0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (v[order[k]] == v[order[k - 1]] &&
        (worst < 0 || order[k] < static_cast<std::size_t>(worst))) {
      worst = static_cast<std::ptrdiff_t>(order[k]);
      first = order[k - 1];
    }
  }
  if (worst >= 0) {
    fail(name, worst, InvalidPolygon::Reason::repeated_vertex,
         "repeats vertex " + std::to_string(first) + " (zero-length edge or duplicate vertex)");
  }
}

// For a polygon whose turns are all left: it is convex only if its edge directions wind once,
// i.e. the direction leaves the upper half-circle exactly once (a pentagram leaves it twice).
// Returns the vertex where it leaves a second time, or -1.
std::ptrdiff_t second_wrap_vertex(std::span<const Point2> v) {
  const std::size_t n = v.size();
  int wraps = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool here = upper_half(v[i], v[(i + 1) % n]);
    const bool next = upper_half(v[(i + 1) % n], v[(i + 2) % n]);
    if (here && !next && ++wraps == 2) return static_cast<std::ptrdiff_t>((i + 1) % n);
  }
  return -1;
}

// make()'s checks in one pass without storage, for the common case: at least 3 finite
// vertices, every turn strictly left, winding once. Distinct vertices follow: a repeated
// neighbour makes a zero turn, and a closed polygon that turns left everywhere and winds once
// is simple.
bool is_valid_ccw(std::span<const Point2> v) {
  const std::size_t n = v.size();
  if (n < 3) return false;
  for (const Point2& p : v) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (orientation<Filtered>(v[i == 0 ? n - 1 : i - 1], v[i], v[(i + 1) % n]) != Sign::positive) {
      return false;
    }
  }
  return second_wrap_vertex(v) < 0;
}

}  // namespace

ConvexPolygon ConvexPolygon::make(std::string name, std::vector<Point2> vertices, VertexOrder order) {
  using Reason = InvalidPolygon::Reason;
  const std::size_t n = vertices.size();
  if (n < 3) {
    fail(name, -1, Reason::too_few_vertices,
         "needs at least 3 vertices, got " + std::to_string(n));
  }
  check_finite(name, vertices);
  check_distinct(name, vertices);

  // Turn at every vertex, decided exactly.
  std::vector<Sign> turn(n);
  std::size_t left = 0, right = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& p = vertices[i == 0 ? n - 1 : i - 1];
    const Point2& q = vertices[(i + 1) % n];
    turn[i] = orientation<Filtered>(p, vertices[i], q);
    if (turn[i] == Sign::zero) {
      fail(name, static_cast<std::ptrdiff_t>(i), Reason::collinear,
           "is collinear with its neighbours (a strictly convex polygon is required)");
    }
    (turn[i] == Sign::positive ? left : right) += 1;
  }
  bool reversed = false;
  if (right == n) {
    if (order == VertexOrder::require_ccw) {
      fail(name, -1, Reason::clockwise, "vertices are clockwise; counter-clockwise order is required");
    }
    std::reverse(vertices.begin(), vertices.end());
    reversed = true;
  } else if (right > 0) {
    const Sign minority = left >= right ? Sign::negative : Sign::positive;
    const auto it = std::find(turn.begin(), turn.end(), minority);
    fail(name, it - turn.begin(), Reason::not_convex,
         "turns the other way from its neighbours (the polygon is not convex)");
  }

  const std::ptrdiff_t second_wrap = second_wrap_vertex(vertices);
  if (second_wrap >= 0) {
    const std::ptrdiff_t reported =
        reversed ? static_cast<std::ptrdiff_t>(n) - 1 - second_wrap : second_wrap;
    fail(name, reported, Reason::not_convex,
         "the boundary winds more than once around the interior (self-intersecting polygon)");
  }
  return ConvexPolygon(std::move(name), std::move(vertices), reversed);
}

void ConvexPolygon::assign(std::span<const Point2> vertices, VertexOrder order) {
  if (is_valid_ccw(vertices)) {
    vertices_.assign(vertices.begin(), vertices.end());
    reversed_ = false;
    return;
  }
  *this = make(name_, std::vector<Point2>(vertices.begin(), vertices.end()), order);
}

double inscribed_radius(std::span<const Point2> polygon) {
  // Edge line k in a frame at the first vertex (no digits lost far from the origin): the
  // distance from p to it, positive inside, is c_k - n_k . p with n_k the outward unit normal.
  struct EdgeLine {
    double nx, ny, c;
  };
  const std::size_t n = polygon.size();
  const Point2 origin = polygon[0];
  std::vector<EdgeLine> lines;
  lines.reserve(n);
  double size = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double ax = polygon[k].x - origin.x, ay = polygon[k].y - origin.y;
    const double ex = polygon[(k + 1) % n].x - polygon[k].x;
    const double ey = polygon[(k + 1) % n].y - polygon[k].y;
    const double length = std::hypot(ex, ey);
    const EdgeLine line{ey / length, -ex / length, (ey * ax - ex * ay) / length};
    lines.push_back(line);
    size = std::max(size, std::hypot(ax, ay));
  }
  // A candidate centre may miss a constraint by the rounding of its 3x3 solve: allow 1e-12 of
  // the polygon's size (the solve is well conditioned: distinct unit normals of a strictly
  // convex polygon are never collinear points of the unit circle, so the determinant is not 0).
  const double slack = 1e-12 * size;
  double best = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        const EdgeLine& a = lines[i];
        const EdgeLine& b = lines[j];
        const EdgeLine& c = lines[k];
        // n . p + r = c for the three lines, by Cramer's rule.
        const double det =
            a.nx * (b.ny - c.ny) - a.ny * (b.nx - c.nx) + (b.nx * c.ny - c.nx * b.ny);
        if (det == 0.0) continue;
        const double x =
            (a.c * (b.ny - c.ny) - a.ny * (b.c - c.c) + (b.c * c.ny - c.c * b.ny)) / det;
        const double y =
            (a.nx * (b.c - c.c) - a.c * (b.nx - c.nx) + (b.nx * c.c - c.nx * b.c)) / det;
        const double r = a.c - a.nx * x - a.ny * y;
        if (!(r > best)) continue;
        const bool inside = std::all_of(lines.begin(), lines.end(), [&](const EdgeLine& l) {
          return l.c - l.nx * x - l.ny * y >= r - slack;
        });
        if (inside) best = r;
      }
    }
  }
  return best;
}

}  // namespace rockcontact::kernel
