#pragma once
// Contact constraints of two polyhedral blocks: the generalized contact model of seed 001 §2,
// as the list of point-pair constraints the implicit 3D DDA will assemble (§3, §4.2).
//
// Every contact is one of the four first-entrance types of §2 (Figure 1): vertex-face,
// crossing edge-edge, vertex-edge, vertex-vertex; edge-face and face-face contacts are not a
// type of their own but decompose into these (the corners of the contact polygon). A
// constraint carries two contact points, one per block (§2.1), the unit normal of its contact
// plane (§2.2) pointing from cp towards tp, the gap (point_tp - point_cp) . normal (metres,
// negative = penetration; a penalty spring pushes tp by kn max(0, -gap) normal), an orthonormal
// tangent basis of the plane (§2.3) and the ids of the two features, so the open-close
// iteration can follow a contact from step to step (§4.2, §4.3).
//
// Method, for two convex polyhedra X and Y (applied with X = cp, Y = tp and with X = tp, Y = cp
// for the vertex contacts):
//   1. Each vertex v of X is located against Y with exact predicates:
//      * v strictly inside Y (below every face plane): a penetrating vertex; its face is the
//        shortest exit (§2.2.1, eq. 4), the face of Y whose plane v is least deep below, its
//        depth h_f / |n_f| compared exactly (ties: the lowest face index). Vertex-face. A
//        vertex inside by no more than S_tie (below) under some faces is on the boundary but for
//        rounding: it is located as touching, by the tests below with those faces' heights 0.
//      * otherwise the closest point p of Y to v (p = v when v is on Y's boundary) lies in the
//        relative interior of exactly one feature of Y, found by exact Voronoi-region tests
//        (vertex w: (v - w).(u - w) <= 0 for every neighbour u of w; edge [a, b]:
//        0 < (v - a).(b - a) < |b - a|^2 and v beyond, on or within S_tie inside the edge's
//        line in both adjacent faces; face f: v on or above f's plane and strictly inside all
//        of f's edge lines). v is a contact when |v - p| <= tolerance, compared exactly as a
//        square (for tolerance 0: exactly when v lies on Y's boundary). The feature gives the type: face -> vertex-face
//        (normal: the face's), edge -> vertex-edge (p = the projection of v on the edge, §2.1
//        method (a)), vertex -> vertex-vertex (p = the vertex, §2.1).
//   2. Each pair of non-parallel edges e = [a, b] of X and g = [c, d] of Y whose closest points
//      p_e, p_g (§2.1, eq. 2-3) are interior to both edges (0 < s, t < 1, exact), at an angle
//      above cone_flush_sine (nearer to parallel, the crossing's place is the rounding's), is a
//      crossing edge-edge contact when the plane through e with normal n = (b - a) x (d - c)
//      supports X (both faces of X at e on one side, a face within cone_flush_sine of the plane
//      counting as in it), the parallel plane through g supports Y on the other side, the gap
//      between the planes is <= tolerance, and, for a negative gap, e meets the interior of Y
//      and g the interior of X (exact): the edges cut into the other block, not
//      only cross in projection (never for a touching pair, whose interiors are disjoint).
//      Asking p_e in Y and p_g in X instead would miss crossings where a block's wedge leans
//      sideways: the edges interpenetrate next to the closest points, not at them. The normal
//      is n oriented away from X.
//   3. Vertex-edge and vertex-vertex contacts have no unique plane (§2.2). The shortest-exit
//      rule (§2.2.1) chooses one among candidate planes neighbouring the contact: the faces of
//      Y at the edge (or at the vertex w), the faces of X at v, and the planes spanned by an
//      edge of X at v and the edge g (or an edge of Y at w), more than cone_flush_sine from
//      parallel (nearer, their plane is the rounding's: two keel edges of a wedge slid 10⁻⁵ m
//      along the keel spanned a plane whose normal was 0/0). A candidate passes
//      the no-overlap check when, oriented from X to Y, the edges of X leaving v point to its
//      non-positive side and Y's tangent cone at p (its edges leaving w; or +-g and the edges
//      of g's two faces) points to its non-negative side (exact signs of triple products; for
//      a vertex touching Y or within S_round of it, a generator within cone_flush_sine of the
//      plane counts as in it). Its separation distance (eq. 4) is (p - v) . n / |n|; the
//      candidate with the largest wins by more than S_tie (estimated in double, whose error is
//      far below S_tie). Ties, which are the rule at an exact touch (every candidate through p
//      gives 0, or a few ulps where the faces are coplanar but for rounding), go to the first in
//      the order: faces of Y, faces of X, edge pairs, each by increasing index; so a vertex on
//      an edge of a face it rests on takes that face's normal. If no candidate passes (a
//      separated pair within tolerance whose tangent cones overlap) the normal is the unit of
//      p - v, the line of the two contact points. Every passing candidate is kept in
//      candidates, the "vector list for potential contact normal directions" of §4.2,
//      for the open-close iteration to re-run the rule with updated points (§4.3).
//   4. Overlapping parts: the minimum translation. When two convex parts overlap (exact verdict,
//      asked only when a contact above penetrates or is unseparated, below), their penetration
//      (penetration.hpp: depth delta, normal n from cp towards tp) bounds every contact: no
//      point of the overlap is deeper along n than delta, and the pair comes apart by delta n.
//      So (a) a constraint deeper than delta (+ penetration_slack of the pair's size,
//      tolerances.hpp) is dropped: an edge-edge crossing whose plane the blocks cannot come
//      apart along at that depth (two cubes overlapping 1 mm face-on with an offset cross edges
//      0.5 m and 0.7 m "deep" across the overlap's other sides); (b) a touching vertex with no
//      plane separating the two blocks' tangent cones (an edge of its block leaving it into the
//      other: the blocks overlap around it, as every corner of two equal cubes overlapping
//      face-on does) takes the plane of the minimum translation: a vertex v of cp the plane of
//      tp's lowest points along n, gap = min over tp of w.n - v.n; a vertex w of tp the plane
//      of cp's highest, gap = w.n - max over cp of v.n; both in [-delta, 0] (a corner of cp on a
//      corner of tp is one contact, not two: step 5);
//      (c) when nothing holds the pair then (every contact dropped or none found), the corners
//      of the overlap of cp's and tp's support features along n, projected on the plane, each
//      with gap -delta. An unseparated vertex of a pair that only touches (its separating plane
//      is an internal face) gives no constraint. The depth and these constructions are in
//      double in a frame at cp's first vertex under every policy (the verdicts stay exact).
//   5. One constraint per position: parts of one block that share an edge or a face plane give
//      the same contact once per part (a vertex on the edge two parts share), and a corner both
//      blocks have (cut from one region) gives it from each block's vertex; constraints with the
//      same normal at the same position are one (merge_coincident, below). So the §6.1 wedge
//      has seed 001 Table 4's six: a plane each at its two front corners, both planes at the
//      crest and at the daylight point on the line of intersection.
//   Duplicates: each type has its own feature pair, and no contact is found twice: edge-edge
//   needs interior points of both edges (a crossing at a vertex is that vertex's contact), a
//   vertex-vertex contact found from both blocks is kept once (from cp's vertex), and an
//   edge-face or face-face contact yields only the corners of the contact polygon: a cube
//   resting inside a larger face gives its four bottom corners as vertex-face and nothing else
//   (its bottom edges do not cross the face's edges; their collinear neighbours are parallel).
//   Parallel (collinear) edge pairs never give an edge-edge contact; their overlap's endpoints
//   are vertices, located by step 1.
//
// Non-convex blocks (§2.2.2): a block is a union of convex parts, and constraints come from
// every pair of a part of cp and a part of tp, each feature id naming its part. A face of a
// part is *internal* when another part of the same block has a face in the same plane with the
// opposite outward normal (its vertices within face_planarity_tolerance times the block's size
// of the plane, decided exactly, since the parts of a cut block meet only to the rounding of
// their implicit vertices; the other part on the face's outer side, exact; and the two faces
// overlapping, the centroid of one strictly inside the other, so that coplanar faces meeting
// only along an edge, such as the two faces of a step or the joint face a wedge rests on beside
// its base's concave edge, stay outer faces); an internal face carries no vertex-face contact and
// is no candidate plane. It is a shortest exit of a penetrating vertex only when it continues an
// outer face of another part (the same plane, the same outward normal): a vertex pushed past the
// block's concave edge there leaves by that plane (a wedge's crest sunk into the keel part below
// its two joints, whose joint faces are internal, leaves by a joint). A vertex inside a part with
// no exit face gives no constraint. Parts are assumed to meet along whole faces (a conforming
// decomposition); a face only partly covered by its neighbour is treated as internal as a whole.
// The multiple-plane rule of §2.2.2 follows from the decomposition itself: a vertex in a concave
// edge or corner of a block touches each convex part meeting there, and each part pair gives one
// constraint with that part's plane (chosen by shortest exit among the part's candidates), so a
// concave angle is split into its convex sub-angles, one plane each, as in Figures 4 and 5.
// Known limits: two identical blocks overlap with no minimum translation that is unique: they
// get the penetration plane of one of the tied directions (penetration.hpp's tie rule). An
// edge where two parts meet
// flush (inside a flat face of the union) still counts as an edge of each part, so a face
// resting across it gets extra corner constraints there, and a vertex resting on it one
// constraint per part (each with the right normal and gap: more stiffness, not a wrong force).
//
// For the implicit DDA (seed 001 §3-§5): a constraint is what §4.2 stores per contact. Its
// normal spring acts on gap = (point_tp - point_cp) . normal, linear in the two blocks'
// displacements through the points (T_i(x) of eq. 11) with the normal fixed over the step (§3.1);
// (type, cp_feature, tp_feature) identifies the contact across steps, to inherit its mode
// (§2.4 method 2); the features and points are what the revision of §5.1 (eq. 41-45) needs
// (the vertex and face of a vertex-face, the two edges of an edge-edge); `plane` and
// `candidates` let the open-close iteration redo the shortest exit with updated points (§4.3).
//
// Coincidence: blocks moved along the faces they rest on (a wedge sliding down its joints), or
// cut from one region, meet only to the rounding of their coordinates, which exact decisions
// see. S_tie = same_contact_tolerance and S_round = coincidence_tolerance times the pair's
// extent, and cone_flush_sine (tolerances.hpp), are where such decisions take coincidence for
// what it was meant to be; gaps stay exact.
//
// Robustness: every decision above (the location of a vertex, interior parameters, supporting
// sides, the tolerance, the no-overlap check) is the exact sign of a polynomial of input
// coordinates and the tolerances, under Filtered, Exact and Checked
// (triple products through predicates.hpp's static filter, the other formulas, of degree 2 to
// 8, through interval arithmetic; then CGAL::Mpzf); a touch reports gap exactly 0 and equal
// contact points. Constructions follow the decisions: under Float and Filtered in double after
// translating the pair to a local origin (a vertex of cp), so their error is a few ulps of the
// pair's size, not of its distance from the origin; under Exact in exact rationals (square
// roots for unit normals and distances in 256-bit MPFR), rounded once. Contact points that are
// input vertices are returned exactly as given.
// Float decides in double too, as the naive baseline.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "rockcontact/kernel/3d/convex_polyhedron.hpp"
#include "rockcontact/kernel/3d/point3.hpp"
#include "rockcontact/kernel/core/number_policy.hpp"

namespace rockcontact::kernel {

enum class ConstraintType { vertex_face, edge_edge, vertex_edge, vertex_vertex };

// A vertex, edge or face of one convex part of a block: index into the part's vertices(),
// edges() or faces(); part = the part's position in the block's list (0 for a convex block).
struct Feature {
  enum class Kind : std::uint8_t { vertex, edge, face };
  Kind kind = Kind::vertex;
  std::uint32_t index = 0;
  std::uint32_t part = 0;
  friend bool operator==(const Feature&, const Feature&) = default;
};

enum class BlockRole : std::uint8_t { cp, tp };

// Where a contact plane comes from: the plane of a face of cp or of tp, the plane through an
// edge of each block parallel to the other (edge_pair), for a vertex-edge or vertex-vertex
// contact without a passing candidate the line of the two contact points (contact_line), or,
// in a pair of parts that overlap, the plane of their minimum translation (penetration,
// step 4 of the header).
// Indices are into faces() or edges() of the parts named by cp_feature.part and tp_feature.part.
struct PlaneSource {
  enum class Kind : std::uint8_t { cp_face, tp_face, edge_pair, contact_line, penetration };
  Kind kind = Kind::cp_face;
  std::uint32_t cp_index = 0;  // cp's face (cp_face) or edge (edge_pair); 0 otherwise
  std::uint32_t tp_index = 0;  // tp's face (tp_face) or edge (edge_pair); 0 otherwise
  friend bool operator==(const PlaneSource&, const PlaneSource&) = default;
};

// A candidate plane of the shortest-exit rule that passed the no-overlap check.
struct CandidatePlane {
  Point3 normal;  // unit, from cp towards tp
  PlaneSource source;
};

struct ContactConstraint {
  ConstraintType type = ConstraintType::vertex_face;
  Feature cp_feature;  // cp's vertex, edge or face in contact
  Feature tp_feature;
  // The block whose vertex (edge, for edge-edge: cp by convention) enters the other: the owner
  // of the vertex of a vertex-face or vertex-edge contact; of a vertex-vertex contact, the
  // block whose vertex was located (cp, unless only tp's vertex is within tolerance).
  BlockRole entering = BlockRole::cp;
  Point3 point_cp;  // contact point on cp, metres
  Point3 point_tp;  // contact point on tp, metres
  Point3 normal;    // unit normal of the contact plane, from cp towards tp
  PlaneSource plane;  // what it is the plane of (for vertex-edge, vertex-vertex: the shortest exit)
  double gap = 0.0; // (point_tp - point_cp) . normal, metres; negative = penetration
  Point3 tangent1;  // unit, normal x tangent1 = tangent2: a right-handed basis (t1, t2, n)
  Point3 tangent2;
  // Vertex-edge and vertex-vertex only: every candidate plane that passed the no-overlap check,
  // the chosen one included, in the tie-break order; empty for the other types.
  std::vector<CandidatePlane> candidates;
};

// The constraints of two convex blocks closer than `tolerance` (metres, >= 0), touching or
// overlapping: vertex contacts of cp's vertices, then tp's, then crossing edge pairs by cp edge
// and tp edge index. Empty for a pair farther apart than the tolerance. Throws
// std::invalid_argument for a negative or non-finite tolerance.
template <NumberPolicy Policy>
std::vector<ContactConstraint> contact_constraints(const ConvexPolyhedron& cp, const ConvexPolyhedron& tp,
                                                   double tolerance = 0.0);

// Non-convex blocks as unions of convex parts (the header explains internal faces and the
// multiple-plane rule): the constraints of every part pair, by cp part then tp part.
template <NumberPolicy Policy>
std::vector<ContactConstraint> contact_constraints(std::span<const ConvexPolyhedron> cp_parts,
                                                   std::span<const ConvexPolyhedron> tp_parts,
                                                   double tolerance = 0.0);

// One constraint per contact position and plane (step 5 of the header): of the constraints
// whose normals agree within same_contact_tolerance (tolerances.hpp) and whose midpoints agree
// across the plane within `near` (metres) and along it within the deeper gap plus `near`, the
// first is kept, unless another is deeper by more than `near`. contact_constraints applies it
// with near = same_contact_tolerance times the pair's extent; a caller that carries contacts
// across steps (the engine's contact memory) applies it again, its own first, with the distance
// the blocks may have slid apart since the contact formed.
void merge_coincident(std::vector<ContactConstraint>& constraints, double near);

// The unit sliding direction of tp's contact point relative to cp's on the contact plane
// (§2.3): the tangential part of `relative` = motion of tp's point minus motion of cp's point,
//   v_t = relative - (relative . n) n,   direction = v_t / |v_t|,
// with relative = the initial velocities (eq. 6), the displacements of the previous time step
// (eq. 7) or of the previous open-close iteration (eq. 8). nullopt when |v_t| <= tolerance
// (m/s or m): the caller then tries the next source, as §2.3 uses eq. 7 when eq. 6 is below a
// tolerance. `normal` must be unit.
std::optional<Point3> sliding_direction(const Point3& normal, const Point3& relative, double tolerance = 0.0);

}  // namespace rockcontact::kernel
