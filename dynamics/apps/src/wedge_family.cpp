#include "rockcontact/dynamics/apps/wedge_family.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "rockcontact/dynamics/io/cut3d.hpp"
#include "rockcontact/kernel/3d/block_cutting.hpp"

namespace rockcontact::dynamics {
namespace {

using kernel::Point3;

// The acceptance of generate_wedge (header, step 2), degrees unless said.
constexpr double dip_min = 35.0, dip_max = 70.0;
constexpr double plunge_min = 20.0, plunge_max = 50.0;
constexpr double trend_from_south_max = 60.0;
constexpr double strike_angle_min = 30.0;
constexpr double face_angle_min = 15.0;  // of t_A, t_B, i with the free face
constexpr double reaction_min = 0.1;     // N_A / W and N_B / W, dimensionless
constexpr double size_min = 5.0, size_max = 10.0;  // m, the bounding box's longest side
// Draws before giving up: at the ~9 % acceptance the chance of reaching it is below 1e-400.
constexpr int max_draws = 10'000;

constexpr double radians_per_degree = std::numbers::pi / 180.0;
constexpr double joint_spacing = 1000.0;  // m: one plane of each set meets the region

double dot(const Point3& u, const Point3& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
Point3 minus(const Point3& u, const Point3& v) { return {u.x - v.x, u.y - v.y, u.z - v.z}; }
Point3 along(const Point3& p, const Point3& d, double t) { return {p.x + t * d.x, p.y + t * d.y, p.z + t * d.z}; }
double determinant(const Point3& u, const Point3& v, const Point3& w) {
  return u.x * (v.y * w.z - v.z * w.y) - u.y * (v.x * w.z - v.z * w.x) + u.z * (v.x * w.y - v.y * w.x);
}

// A uniform number in [lo, hi) from the engine's raw output, the same under every library.
double uniform(std::mt19937_64& engine, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(engine() >> 11) * 0x1.0p-53;
}

double tenths(double deg) { return std::round(deg * 10.0) / 10.0; }

std::uint64_t splitmix64(std::uint64_t state) {
  std::uint64_t z = state + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// The trace of the plane of normal n on the top (its strike), unit, on the upper side of the
// plane of normal other.
Point3 trace(const Point3& n, const Point3& other) {
  const double length = std::hypot(n.x, n.y);
  Point3 t{n.y / length, -n.x / length, 0.0};
  if (dot(t, other) < 0) t = {-t.x, -t.y, 0.0};
  return t;
}

struct Edges {  // the cone's edges from the crest (header)
  Point3 a, b, line;
};

Edges cone_edges(const WedgeLimitEquilibrium& r) {
  return {trace(r.normal_a, r.normal_b), trace(r.normal_b, r.normal_a), r.intersection};
}

// Step 2 of generate_wedge.
bool accepted(const WedgeLimitEquilibrium& r) {
  if (r.mode != WedgeMode::wedge || r.normal_reaction_a < reaction_min || r.normal_reaction_b < reaction_min) return false;
  if (r.plunge_deg < plunge_min || r.plunge_deg > plunge_max) return false;
  if (std::abs(r.trend_deg - 180.0) > trend_from_south_max) return false;
  const Edges e = cone_edges(r);
  if (std::acos(std::min(1.0, std::abs(dot(e.a, e.b)))) < strike_angle_min * radians_per_degree) return false;
  const double face_sine = std::sin(face_angle_min * radians_per_degree);
  return -e.a.y >= face_sine && -e.b.y >= face_sine && -e.line.y >= face_sine;
}

// The corners for a crest `crest`, each edge stopped at y = 0.
WedgeCorners corners_from(const Point3& crest, const Edges& e) {
  return {crest, along(crest, e.a, crest.y / -e.a.y), along(crest, e.b, crest.y / -e.b.y),
          along(crest, e.line, crest.y / -e.line.y)};
}

// Step 3 of generate_wedge: the crest for a wedge of bounding-box side `size`.
Point3 place_crest(const Edges& e, double size) {
  const WedgeCorners unit = corners_from({0.0, 1.0, 0.0}, e);
  const double x_min = std::min({unit.crest.x, unit.on_a.x, unit.on_b.x, unit.daylight.x});
  const double x_max = std::max({unit.crest.x, unit.on_a.x, unit.on_b.x, unit.daylight.x});
  const double scale = size / std::max({x_max - x_min, 1.0, -unit.daylight.z});
  const auto mm = [](double m) { return std::round(m * 1000.0) / 1000.0; };
  return {mm(-scale * 0.5 * (x_min + x_max)), mm(scale), 0.0};
}

kernel::JointSet3 joint_set(const WedgeJoint& joint, const Point3& crest) {
  kernel::JointSet3 set{joint.dip_deg, joint.dip_direction_deg, joint_spacing, 0.0};
  set.offset = dot(kernel::joint_normal(set), crest);
  return set;
}

nlohmann::ordered_json joint_set_json(const kernel::JointSet3& set) {
  return {{"dip_deg", set.dip_deg}, {"dip_direction_deg", set.dip_direction_deg}, {"spacing", set.spacing},
          {"offset", set.offset}};
}

// The cut's blocks split into the wedge (the piece whose vertex mean is above both joints: each
// piece lies on one side of each plane) and the base's parts, as {"vertices", "faces"}.
std::pair<nlohmann::ordered_json, nlohmann::ordered_json> split_pieces(const WedgeCase& c,
                                                                      const nlohmann::ordered_json& cut) {
  const kernel::JointSet3 sets[2] = {joint_set(c.a, c.crest), joint_set(c.b, c.crest)};
  nlohmann::ordered_json wedge, base = nlohmann::ordered_json::array();
  for (const auto& block : cut.at("blocks")) {
    const auto& vertices = block.at("vertices");
    Point3 mean;
    const double share = 1.0 / static_cast<double>(vertices.size());
    for (const auto& v : vertices) mean = along(mean, {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}, share);
    const bool above = dot(kernel::joint_normal(sets[0]), mean) > sets[0].offset &&
                       dot(kernel::joint_normal(sets[1]), mean) > sets[1].offset;
    nlohmann::ordered_json solid = {{"vertices", vertices}, {"faces", block.at("faces")}};
    if (above) {
      wedge = std::move(solid);
    } else {
      base.push_back(std::move(solid));
    }
  }
  if (wedge.is_null()) {
    throw std::invalid_argument("wedge case " + std::to_string(c.seed) +
                                ": the joints cut no piece above both of them from the region");
  }
  return {std::move(wedge), std::move(base)};
}

}  // namespace

WedgeCase generate_wedge(std::uint64_t case_seed, double friction_angle_deg) {
  if (!(friction_angle_deg >= 0 && friction_angle_deg < 90)) {
    throw std::invalid_argument("friction_angle_deg: expected degrees in [0, 90), got " +
                                std::to_string(friction_angle_deg));
  }
  std::mt19937_64 engine(case_seed);
  for (int draw = 0; draw < max_draws; ++draw) {
    WedgeCase c;
    c.seed = case_seed;
    c.a = {tenths(uniform(engine, dip_min, dip_max)), 0.0, friction_angle_deg, 0.0, 0.0};
    c.b = {tenths(uniform(engine, dip_min, dip_max)), 0.0, friction_angle_deg, 0.0, 0.0};
    c.a.dip_direction_deg = std::fmod(tenths(uniform(engine, 0.0, 360.0)), 360.0);
    c.b.dip_direction_deg = std::fmod(tenths(uniform(engine, 0.0, 360.0)), 360.0);
    const double size = uniform(engine, size_min, size_max);
    WedgeLimitEquilibrium r;
    try {
      r = wedge_factor_of_safety(c.a, c.b, 1.0);
    } catch (const std::invalid_argument&) {
      continue;  // parallel joints or a horizontal line of intersection: no wedge
    }
    if (!accepted(r)) continue;
    c.crest = place_crest(cone_edges(r), size);
    return c;
  }
  throw std::logic_error("generate_wedge: no wedge accepted in " + std::to_string(max_draws) + " draws");
}

std::vector<WedgeCase> generate_wedges(std::uint64_t seed, std::size_t count, double friction_angle_deg) {
  std::vector<WedgeCase> cases;
  cases.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    cases.push_back(generate_wedge(splitmix64(seed + k * 0x9E3779B97F4A7C15ULL), friction_angle_deg));
  }
  return cases;
}

WedgeCorners wedge_corners(const WedgeCase& c) {
  return corners_from(c.crest, cone_edges(wedge_factor_of_safety(c.a, c.b, 1.0)));
}

double wedge_volume(const WedgeCase& c) {
  const WedgeCorners k = wedge_corners(c);
  return std::abs(determinant(minus(k.on_a, k.crest), minus(k.on_b, k.crest), minus(k.daylight, k.crest))) / 6.0;
}

double wedge_slide_acceleration(const WedgeLimitEquilibrium& reference, double g) {
  if (reference.mode != WedgeMode::wedge) {
    throw std::invalid_argument("reference.mode: expected wedge (both planes in contact), got " +
                                std::string(to_string(reference.mode)));
  }
  if (reference.factor_of_safety >= 1.0) return 0.0;
  return g * std::sin(reference.plunge_deg * radians_per_degree) * (1.0 - reference.factor_of_safety);
}

double wedge_slide_time(const WedgeCase& c, const WedgeLimitEquilibrium& reference, double g, double at_most) {
  const double a = wedge_slide_acceleration(reference, g);
  const WedgeCorners k = wedge_corners(c);
  const double centroid_y = (k.crest.y + k.on_a.y + k.on_b.y + k.daylight.y) / 4.0;
  const double to_face = centroid_y / std::abs(reference.intersection.y);  // along the line, m
  if (a <= 0.0) return at_most;
  // The slide at which the wedge would have to turn (wedge_sliding_support): the first of 64
  // samples up to the face with no support left, narrowed by bisection to 10^-6 of the way.
  double turns = to_face;
  const auto supported = [&](double slid) { return wedge_sliding_support(c, slid).margin > 0.0; };
  if (!supported(0.0)) return 0.0;
  constexpr int samples = 64;
  for (int j = 1; j <= samples; ++j) {
    const double slid = to_face * j / samples;
    if (supported(slid)) continue;
    double lo = to_face * (j - 1) / samples, hi = slid;
    while (hi - lo > 1e-6 * to_face) (supported(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
    turns = lo;
    break;
  }
  return std::min(at_most, 0.8 * std::sqrt(2.0 * turns / a));
}

namespace {

Eigen::Vector3d vec(const Point3& p) { return {p.x, p.y, p.z}; }

// The part of the polygon `corners` with y >= 0 (behind the free face). Corners within
// `tolerance` of the face count as on it: the wedge's corners on the face are there but for
// rounding, and a crossing next to one would be a second copy of it.
std::vector<Eigen::Vector3d> behind_free_face(const std::vector<Eigen::Vector3d>& corners, double tolerance) {
  std::vector<Eigen::Vector3d> out;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const Eigen::Vector3d& p = corners[k];
    const Eigen::Vector3d& q = corners[(k + 1) % corners.size()];
    if (p.y() >= -tolerance) out.push_back(p);
    if ((p.y() > tolerance && q.y() < -tolerance) || (p.y() < -tolerance && q.y() > tolerance)) {
      out.push_back(p + (q - p) * (p.y() / (p.y() - q.y())));
    }
  }
  return out;
}

}  // namespace

WedgeSlidingSupport wedge_sliding_support(const WedgeCase& c, double slid) {
  if (!(slid >= 0.0)) throw std::invalid_argument("slid: expected >= 0 (m), got " + std::to_string(slid));
  if (c.a.friction_angle_deg != c.b.friction_angle_deg) {
    throw std::invalid_argument("wedge case " + std::to_string(c.seed) + ": expected the same friction angle on both joints");
  }
  const WedgeLimitEquilibrium r = wedge_factor_of_safety(c.a, c.b, 1.0);
  const WedgeCorners k = wedge_corners(c);
  const Eigen::Vector3d i = vec(r.intersection);
  const Eigen::Vector3d shift = slid * i;
  const Eigen::Vector3d centroid = (vec(k.crest) + vec(k.on_a) + vec(k.on_b) + vec(k.daylight)) / 4.0 + shift;
  const double mu = std::tan(c.a.friction_angle_deg * radians_per_degree);
  // Across i: two unit vectors normal to it.
  const Eigen::Vector3d e1 = i.cross(Eigen::Vector3d::UnitZ()).normalized(), e2 = i.cross(e1);
  // Per corner, the force of a unit normal reaction there and its moment about the centroid.
  std::vector<Eigen::Matrix<double, 6, 1>> columns;
  std::vector<bool> on_a;
  const auto face = [&](const Point3& other, const Point3& normal, bool a) {
    const std::vector<Eigen::Vector3d> corners{vec(k.crest) + shift, vec(other) + shift, vec(k.daylight) + shift};
    const Eigen::Vector3d force = vec(normal) - mu * i;
    for (const Eigen::Vector3d& p : behind_free_face(corners, 1e-9 * (corners[0] - corners[2]).norm())) {
      Eigen::Matrix<double, 6, 1> column;
      column << force, (p - centroid).cross(force);
      columns.push_back(column);
      on_a.push_back(a);
    }
  };
  face(k.on_a, r.normal_a, true);
  face(k.on_b, r.normal_b, false);
  const auto n = static_cast<Eigen::Index>(columns.size());
  Eigen::MatrixXd equations(5, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto& column = columns[static_cast<std::size_t>(j)];
    equations.col(j) << e1.dot(column.head<3>()), e2.dot(column.head<3>()), column.tail<3>();
  }
  // The weight, 1 along -z, balanced across i; no moment about the centroid.
  Eigen::VectorXd load(5);
  load << e1.z(), e2.z(), 0.0, 0.0, 0.0;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(equations);
  const Eigen::MatrixXd line = lu.kernel();
  if (lu.rank() != 5 || line.cols() != 1) {
    throw std::logic_error("wedge case " + std::to_string(c.seed) + ": the support equations are degenerate");
  }
  const Eigen::VectorXd base = lu.solve(load);
  const Eigen::VectorXd z = line.col(0);
  // max over λ of min_j (base_j + λ z_j): concave and piecewise linear, largest where two of the
  // lines cross. Bounded: the balance across i fixes each joint's sum (the joints' normals are
  // independent there), so along the line each joint's z_j sum to 0 and some fall as others rise.
  double best = -std::numeric_limits<double>::infinity(), best_lambda = 0.0;
  for (Eigen::Index p = 0; p < n; ++p) {
    for (Eigen::Index q = p + 1; q < n; ++q) {
      if (z(p) == z(q)) continue;
      const double lambda = (base(q) - base(p)) / (z(p) - z(q));
      const double smallest = (base + lambda * z).minCoeff();
      if (smallest > best) best = smallest, best_lambda = lambda;
    }
  }
  const Eigen::VectorXd forces = base + best_lambda * z;
  WedgeSlidingSupport out;
  out.margin = best;
  for (Eigen::Index j = 0; j < n; ++j) (on_a[static_cast<std::size_t>(j)] ? out.reaction_a : out.reaction_b) += forces(j);
  return out;
}

nlohmann::ordered_json wedge_cut_document(const WedgeCase& c) {
  const Point3 lo = wedge_family_region_min, hi = wedge_family_region_max;
  return {{"dimension", 3},
          {"region",
           {{"box", {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}}},
            {"material", "rock"},
            {"group", "slope"},
            {"id_prefix", "slope"},
            // The wedge is the block under study, 1 to 100 m³ beside a 30 000 m³ region: "auto"
            // would merge the smaller ones into the base.
            {"min_block_volume", 0}}},
          {"joint_sets", {joint_set_json(joint_set(c.a, c.crest)), joint_set_json(joint_set(c.b, c.crest))}}};
}

nlohmann::ordered_json wedge_scene_document(const WedgeCase& c, const WedgeSceneParams& params) {
  if (c.a.friction_angle_deg != c.b.friction_angle_deg) {
    throw std::invalid_argument("wedge case " + std::to_string(c.seed) +
                                ": expected the same friction angle on both joints (one interface carries them)");
  }
  const std::string name = "wedge case " + std::to_string(c.seed);
  const Cut3Input input = parse_cut3(nlohmann::json(wedge_cut_document(c)), name);
  const nlohmann::ordered_json cut = cut3d_blocks(input, cut3d(input));
  auto [wedge, base] = split_pieces(c, cut);
  const double phi = c.a.friction_angle_deg;
  nlohmann::ordered_json base_block = {{"id", "base"}, {"group", "slope"}, {"material", "rock"}, {"fixed", true},
                                       {"parts", std::move(base)}};
  nlohmann::ordered_json wedge_block = {{"id", "wedge"}, {"group", "rock"}, {"material", "rock"},
                                        {"vertices", std::move(wedge.at("vertices"))},
                                        {"faces", std::move(wedge.at("faces"))}};
  return {{"dimension", 3},
          {"description", name + " (dynamics/apps/wedge_family.hpp)"},
          {"time", {{"dt", params.dt}, {"duration", params.duration}}},
          {"gravity", {0.0, 0.0, -wedge_family_gravity}},
          {"materials", {{"rock", {{"density", wedge_family_density}, {"youngs_modulus", 1.0e10}, {"poisson_ratio", 0.25}}}}},
          {"contact",
           {{"law", "penalty"}, {"kn", params.kn}, {"kt", params.kn / 10.0}, {"friction_angle_deg", phi},
            {"cohesion", 0.0}, {"tensile_strength", 0.0}, {"policy", "filtered"}}},
          {"interfaces", {{{"between", {"slope", "rock"}}, {"friction_angle_deg", phi}}}},
          {"blocks", {std::move(base_block), std::move(wedge_block)}},
          {"output", {{"track", {"wedge"}}, {"every", params.every}}}};
}

Scene3d wedge_scene(const WedgeCase& c, const WedgeSceneParams& params) {
  return parse_scene3d(nlohmann::json(wedge_scene_document(c, params)), "wedge case " + std::to_string(c.seed));
}

}  // namespace rockcontact::dynamics
