#pragma once
// The potential contact of two faces as a distributed spring along their contact line: the
// tangent an implicit solve (the engines' initial equilibrium, dynamics/common/equilibrium.hpp)
// needs of a force that seed 000 only ever evaluates.
//
// Two faces overlapping by a thin sliver whose thickness t(s) varies linearly along the
// contact line get, by eq. 11 (phi_CP = kn t / H on the face of TP inside CP and likewise on the
// other face), a normal pressure 2 kn t(s) / H: a distributed spring of 2 kn / H per unit length
// acting where t > 0, that is where the signed gap g(s) = -t(s) is negative. Over an interval
// where it acts, the integral of that linear pressure and its first moment are exact at the two
// Gauss points: two point springs of kn l / H each, l the interval's length, at
// ±l / (2√3) from its centre, each compressed by -g there. Where the gap opens along the line
// (a block rocking on its neighbour), the interval shrinks to the part that still overlaps: a
// vertex pressed into a face has a short interval that grows with the depth (its force grows
// with the depth squared), and a face lifted off at one end keeps the stiffness of the part
// that touches. That is the whole of a Newton step's contact model: where the interval lies
// is the open-close decision of the step.
//
// These springs only steer the solve: its convergence is judged on the forces of eq. 11, so a
// rounding in the line (double constructions here) costs iterations, never accuracy.

#include <array>
#include <optional>

#include "rockcontact/kernel/2d/convex_polygon.hpp"
#include "rockcontact/kernel/2d/point.hpp"

namespace rockcontact::contact {

// A segment of contact between two parts a and b, with the signed gap of b's nearest face
// at its two ends (linear in between).
struct ContactLine {
  kernel::Point2 from, to;  // on the face of the part the axis belongs to, m
  kernel::Vector2 normal;   // unit, from b towards a: the way a moves to come apart
  double gap_from = 0.0;    // m (< 0: they overlap there)
  double gap_to = 0.0;
};

// The contact line of two convex polygons apart by at most `reach` (m), else empty. The axis
// is the separating axis of largest signed distance (an edge normal of either polygon; negative
// when they overlap: minus their minimum translation distance); the line is the stretch of that
// edge facing the other polygon's most opposed edge, with that edge's gaps at the stretch's
// ends. Empty also when the stretch is a point apart or in touch (two corners that meet, as at
// the junction of four blocks of a jointed mass: no force, and no normal to push along).
std::optional<ContactLine> contact_line(const kernel::ConvexPolygon& a, const kernel::ConvexPolygon& b,
                                        double reach);

// The part of the line where the gap, each end's moved by the given approach (m, positive
// apart), is negative: as fractions [first, last] of the way from `from` to `to`, empty
// (first >= last) when none is.
struct Interval {
  double first = 0.0, last = 0.0;
  bool empty() const { return !(first < last); }
};
Interval closed_part(const ContactLine& line, double moved_from = 0.0, double moved_to = 0.0);

// The two Gauss points of `part` of the line (header): where they are, the gap there, and the
// stiffness of each, kn l / H (kn in Pa, H in m, l the part's length in m): N/m per metre of
// thickness.
struct GaussSpring {
  kernel::Point2 at;
  double gap = 0.0;
  double k = 0.0;
};
std::array<GaussSpring, 2> gauss_springs(const ContactLine& line, Interval part, double kn, double H);

// How much the springs' normal force (N per metre of thickness) can change when the closed part
// goes from `a` to `b`, the gaps of the line's ends moved by the given approach (m): 2 kn / H
// (the two springs of a part sum to 2 kn / H times the integral of the gap over it) times the
// integral of |gap| over the stretch in one part and not the other. Its moment about any point
// of the line changes by at most this times the line's length. An open-close iteration that
// compares parts by this, not by how far their ends moved, stops with the forces it solved
// for: a part end that moves a fraction s along a line of length L whose gap changes by Δg
// along it, from where the gap is zero, changes the force by kn / H Δg s² L: at kn = 2 GPa,
// H = L = 1 m and s = 0.05, ~15 N for a tilt of 3 µm.
double part_force_change(const ContactLine& line, Interval a, Interval b, double kn, double H,
                         double moved_from = 0.0, double moved_to = 0.0);

}  // namespace rockcontact::contact
