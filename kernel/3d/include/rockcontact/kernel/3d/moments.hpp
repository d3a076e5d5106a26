#pragma once
// Volume moments of a convex polyhedron, for the 3D mass matrix (the 3D counterpart of
// 2d/moments.hpp; seed 000 §2 in the plane):
//   volume = ∫ dV,  first = (∫ x dV, ∫ y dV, ∫ z dV),
//   xx = ∫ x² dV, yy = ∫ y² dV, zz = ∫ z² dV, xy = ∫ x y dV, yz = ∫ y z dV, zx = ∫ z x dV.
//
// Method: the divergence theorem turned into a sum over tetrahedra. Every face (CCW from
// outside) is fanned into triangles (f0, fk, fk+1); each triangle and a reference point o make
// a tetrahedron whose signed volume is positive because o is not above any face plane
// (the block is convex and o is one of its vertices); the tetrahedra tile the block. The
// moments of a tetrahedron with a vertex at the origin and the others at a, b, c
// (D = det[a b c] = 6 V, s = a + b + c) are
//   ∫ dV = D / 6,   ∫ x_i dV = D s_i / 24,
//   ∫ x_i x_j dV = D (a_i a_j + b_i b_j + c_i c_j + s_i s_j) / 120,
// the degree-2 case of ∫_T x^α dV = D α! / (|α| + 3)! over the standard simplex mapped by
// [a b c]. They are summed in the local frame of o = the first vertex, so a block 10^6 m from
// the origin loses no digits to cancellation, and shifted back by the parallel-axis relations:
//   first_i = m_i + o_i V,   x_i x_j = m_ij + o_i m_j + o_j m_i + o_i o_j V.
//
// Accuracy: the local sums are computed from differences v - o (one rounding each) with a
// fixed number of operations per tetrahedron, so each local moment has a relative error of a
// few tens of u on the sum of its terms' magnitudes, as for any positive quadrature (the terms
// are all non-negative for the volume; the others are scaled by |v - o| <= the diameter).
// The shift adds a few u of its largest term (o_i o_j V for the second moments at a far
// offset). The central moments (about the centroid) are NOT recovered accurately from the
// global ones at a far offset (xx - first_x² / V cancels); a caller that needs them should
// work in a frame near the block.

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::kernel {

struct Moments3 {
  double volume = 0.0;  // m³, positive
  Point3 first;         // (∫ x dV, ∫ y dV, ∫ z dV), m⁴
  double xx = 0.0;      // ∫ x² dV, m⁵
  double yy = 0.0;      // ∫ y² dV, m⁵
  double zz = 0.0;      // ∫ z² dV, m⁵
  double xy = 0.0;      // ∫ x y dV, m⁵
  double yz = 0.0;      // ∫ y z dV, m⁵
  double zx = 0.0;      // ∫ z x dV, m⁵
  // The centre of mass of a uniform block, m (in the frame of the origin for moments_about).
  Point3 centroid() const { return {first.x / volume, first.y / volume, first.z / volume}; }
};

Moments3 moments(const ConvexPolyhedron& block);

// The same integrals in the frame of `origin`: of x - origin instead of x (first() is then
// ∫ (x - o) dV, the second moments ∫ (x_i - o_i)(x_j - o_j) dV), with the tetrahedra fanned from
// `origin`, so no shift is needed. With `origin` near the block (a vertex, or a vertex of another
// part of the same body) the central moments follow from them without cancellation:
// S_ij = m_ij - m_i m_j / V. Additive over the parts of a body taken about one origin.
Moments3 moments_about(const ConvexPolyhedron& block, const Point3& origin);

}  // namespace rockcontact::kernel
