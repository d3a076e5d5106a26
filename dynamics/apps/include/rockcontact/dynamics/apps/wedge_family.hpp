#pragma once
// A family of rock wedges around seed 001 §6.1's, each with its independent reference: Hoek &
// Bray's limit equilibrium (wedge_limit_equilibrium.hpp) for the factor of safety, and for a
// wedge that cannot stand (FS < 1) its slide along the line of intersection. The 3D DDA is right
// on wedges when it is right on the family, not on the one example (DESIGN.md, "Families, not
// instances").
//
// The slope is the example's (examples/scenes3d/wedge.json): the box region
// [-20, 20] x [0, 30] x [-25, 0] m, axes x East, y North, z Up, with the free face y = 0 facing
// South and the horizontal top z = 0. Two joint planes through a crest point on the top cut it;
// the piece above both is the wedge, a tetrahedron with corners
//   crest     on both joints and the top,
//   on_a      on joint A, the top and the free face (on_b likewise),
//   daylight  on both joints and the free face, where the line of intersection leaves the slope.
// From the crest, these are the ends of the three edges of the cone {above A, above B, below the
// top}: the line of intersection i (pointing down it) and the traces t_A, t_B of the joints on
// the top (t_A along A's strike, on B's upper side), each stopped at the face y = 0.
//
// generate_wedge draws one case from its own std::mt19937_64 (a uniform number in [0, 1) is the
// top 53 bits of a raw output times 2^-53, so the draws are the same under every standard
// library), repeating until a draw is accepted:
//   1. dips uniform in [35, 70] degrees and dip directions uniform in [0, 360), each rounded to
//      0.1 degree (readable, and exact in a scene file);
//   2. accepted when Hoek & Bray give WedgeMode::wedge with both reactions N_A, N_B at least
//      0.1 of the weight (both planes carry it), the line of intersection plunges 20 to 50
//      degrees with its trend within 60 degrees of South (it daylights in the free face), the
//      strikes are at least 30 degrees apart, and t_A, t_B, i all leave the free face at 15
//      degrees or more (the corners on the face are not far along it);
//   3. the size: a length L uniform in [5, 10] m is the longest side of the wedge's bounding
//      box. The crest goes behind the face at the distance that makes it so, at the x that
//      centres the box on x = 0, rounded to the mm: the wedge lies 15 m or more inside the
//      region's other faces, whatever its shape (its volume varies with the shape, from about
//      1 to 100 m³).
// The accepted fraction is about 9 % (so about 11 draws a case). Deciding the tests in step 2
// takes sin and cos, which libraries may round differently in the last ulp: a draw within an
// ulp of a threshold could be decided differently on another platform, nothing else can.
//
// wedge_scene builds the example's scene for a case on the path a user takes: the cut document
// (wedge_cut_document, the input of `rockcontact cut`: the box and one plane of each joint set,
// spacing 1000 m, offset n · crest) is cut by cut3d_blocks, the piece above both joints becomes
// the movable "wedge" (group "rock") and the other pieces the convex parts of the one fixed,
// non-convex "base" (group "slope"), as in wedge.json; the document (wedge_scene_document) is
// read by parse_scene3d. Material as the example's (2600 kg/m³, E = 10 GPa, ν = 0.25), the
// penalty law with kt = kn / 10 and the cases' friction angle on the default law and on the
// "slope"-"rock" interface, no cohesion, gravity 9.81 m/s² down.
//
// The slide reference. With both planes in contact and the same friction angle φ on both, the
// net force along the line of intersection is W sin ψ_i − tan φ (N_A + N_B) = W sin ψ_i (1 − FS),
// so a wedge released from rest with FS < 1 moves along i by ½ g sin ψ_i (1 − FS) t²
// (wedge_slide_acceleration gives g sin ψ_i (1 − FS)); one with FS >= 1 stays.

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "rockcontact/dynamics/apps/wedge_limit_equilibrium.hpp"
#include "rockcontact/dynamics/io/scene3d.hpp"
#include "rockcontact/kernel/3d/point3.hpp"

namespace rockcontact::dynamics {

// The slope's region, m (the example's).
inline constexpr kernel::Point3 wedge_family_region_min{-20.0, 0.0, -25.0};
inline constexpr kernel::Point3 wedge_family_region_max{20.0, 30.0, 0.0};
// The scenes' gravity, m/s², along −z, and the rock's density, kg/m³ (the example's).
inline constexpr double wedge_family_gravity = 9.81;
inline constexpr double wedge_family_density = 2600.0;

struct WedgeCase {
  WedgeJoint a;             // the joints: dip, dip direction, the family's friction angle, no
  WedgeJoint b;             // cohesion, area 0 (Hoek & Bray's friction-only form)
  std::uint64_t seed = 0;   // the case's own seed: generate_wedge(seed, φ) draws it again
  kernel::Point3 crest;     // m, on the top (z = 0): both joint planes pass through it
  friend bool operator==(const WedgeCase&, const WedgeCase&) = default;
};

// The corners of a case's wedge (header), m.
struct WedgeCorners {
  kernel::Point3 crest;     // joints A and B, top
  kernel::Point3 on_a;      // joint A, top, free face
  kernel::Point3 on_b;      // joint B, top, free face
  kernel::Point3 daylight;  // joints A and B, free face
};

// The case of seed `case_seed` with friction angle `friction_angle_deg` (degrees, in [0, 90))
// on both joints (header). Throws std::invalid_argument naming "friction_angle_deg" for an
// angle out of range.
WedgeCase generate_wedge(std::uint64_t case_seed, double friction_angle_deg);

// `count` cases from `seed`: case k is generate_wedge(s_k, φ), s_k one step of splitmix64 from
// seed + k · 0x9E3779B97F4A7C15, so the first cases of a longer family are the shorter one's,
// and the geometry does not depend on φ (the same seed gives the same wedges at every φ).
std::vector<WedgeCase> generate_wedges(std::uint64_t seed, std::size_t count, double friction_angle_deg);

// The corners from the crest along the cone's edges (header).
WedgeCorners wedge_corners(const WedgeCase& c);

// m³: the tetrahedron of wedge_corners.
double wedge_volume(const WedgeCase& c);

// m/s²: g sin ψ_i (1 − FS) for a wedge in WedgeMode::wedge with FS < 1, 0 for one with FS >= 1
// (it stays); the slide along `reference.intersection` from rest is ½ of it times t². Valid for
// the same friction angle on both joints and no cohesion (as generated). Throws
// std::invalid_argument for another mode: the wedge would leave a plane.
double wedge_slide_acceleration(const WedgeLimitEquilibrium& reference, double g);

// s: how long a slide from rest may be compared with ½ a t² (a = wedge_slide_acceleration):
// `at_most`, or for a fast slide 0.8 of the time the wedge's centroid takes to reach the free
// face (y = 0), or 0.8 of the time it takes to slide to where it could no longer do so without
// turning (wedge_sliding_support below; 0 when it cannot from the start). The reference takes
// the joints as unbounded; the slope's end there, and a wedge whose centroid has slid past the
// free face's edge is no longer carried behind it and tips over the edge (the 1.9 m³ wedge of
// the family at φ = 20° reaches it in 0.55 s); before that, the faces it rests on shrink towards
// the crest and may no longer hold its moments. `at_most` for a wedge that stays (a = 0).
// Throws what wedge_slide_acceleration and wedge_sliding_support throw.
double wedge_slide_time(const WedgeCase& c, const WedgeLimitEquilibrium& reference, double g, double at_most = 1.0);

// Whether the slide reference holds for a rigid wedge: Hoek & Bray balance forces only. A wedge
// sliding along i without turning needs, besides the reactions N_A, N_B, a distribution of them
// over its contact faces that also balances the moments about its centroid. With the normal
// forces at the corners of its faces (any pressure over a face is such a distribution) and the
// friction tan φ of each opposing the motion along i, the unknowns are six corner forces against
// five equations (force across i, moments): a line of solutions.
struct WedgeSlidingSupport {
  // The largest, over that line, of the smallest corner force, a fraction of the weight:
  // > 0 when the wedge can slide on both joints without turning, < 0 when it must turn.
  double margin = 0.0;
  double reaction_a = 0.0;  // Σ of the corner forces on joint A, of the weight (= Hoek & Bray's)
  double reaction_b = 0.0;  // on joint B
};

// The support of the case's wedge after it has slid `slid` m (>= 0) down i: its faces on the
// joints are those of wedge_corners moved by slid · i, less what has passed the free face (the
// joints end at y = 0). Valid for the same friction angle on both joints (as generated). Throws
// std::invalid_argument for slid < 0 or unequal friction angles, std::logic_error when the
// equations are degenerate (not a generated case).
WedgeSlidingSupport wedge_sliding_support(const WedgeCase& c, double slid);

struct WedgeSceneParams {
  double kn = 1.0e10;       // N/m per constraint, finite > 0; kt = kn / 10
  double dt = 1.0e-4;       // s, the scene's time.dt, finite > 0
  double duration = 1.0;    // s, the scene's time.duration (`rockcontact run`), finite > 0
  std::size_t every = 100;  // record every `every` steps, >= 1
};

inline WedgeSceneParams default_wedge_scene_params() { return {}; }

// The cut document of a case: {"dimension": 3, "region": {"box", "material": "rock", "group":
// "slope", "id_prefix": "slope", "min_block_volume": 0}, "joint_sets": [A, B]} (cut3d.hpp).
nlohmann::ordered_json wedge_cut_document(const WedgeCase& c);

// The scene document of a case (header): blocks "base" (fixed, convex parts) and "wedge".
// Throws std::invalid_argument when the joints' friction angles differ (one interface carries
// both), or when the cut leaves no piece above both joints (a case not generated here); what
// cut3d_blocks throws.
nlohmann::ordered_json wedge_scene_document(const WedgeCase& c, const WedgeSceneParams& params);

// parse_scene3d of wedge_scene_document, named "wedge case <seed>".
Scene3d wedge_scene(const WedgeCase& c, const WedgeSceneParams& params = default_wedge_scene_params());

}  // namespace rockcontact::dynamics
