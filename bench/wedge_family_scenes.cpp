// Writes the scenes of a wedge family (dynamics/apps/wedge_family.hpp) and their references, for
// bench/wedge_family.py to run through `rockcontact safety-factor` and `rockcontact run`:
//   DIR/case_K.json      the scene (wedge_scene_document), K = 0, 1, ...
//   DIR/case_K_cut.json  its cut document (`rockcontact cut` makes the scene's blocks from it)
//   DIR/cases.json       per case: the files, the case seed, the joints, the crest, the wedge's
//                        volume, and Hoek & Bray's factor of safety, mode, reactions (fractions
//                        of the weight), line of intersection (unit, down it), plunge, trend and
//                        slide acceleration g sin ψ_i (1 − FS) (0 when FS >= 1), m/s²
//
//   wedge_family_scenes --seed 1 --count 10 --phi 40 --kn 1e10 --dt 1e-4 --out DIR

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "rockcontact/dynamics/apps/wedge_family.hpp"

namespace dyn = rockcontact::dynamics;
using nlohmann::ordered_json;

namespace {

void write(const std::filesystem::path& file, const ordered_json& document) {
  std::ofstream out(file);
  out << document.dump(1) << '\n';
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

ordered_json joint_json(const dyn::WedgeJoint& j) {
  return {{"dip_deg", j.dip_deg}, {"dip_direction_deg", j.dip_direction_deg}, {"friction_angle_deg", j.friction_angle_deg}};
}

ordered_json reference_json(const dyn::WedgeCase& c) {
  const double volume = dyn::wedge_volume(c);
  const double weight = dyn::wedge_family_density * dyn::wedge_family_gravity * volume;  // N
  const dyn::WedgeLimitEquilibrium r = dyn::wedge_factor_of_safety(c.a, c.b, weight);
  return {{"volume_m3", volume},
          {"factor_of_safety", r.factor_of_safety},
          {"mode", std::string(dyn::to_string(r.mode))},
          {"reaction_a_of_weight", r.normal_reaction_a / weight},
          {"reaction_b_of_weight", r.normal_reaction_b / weight},
          {"intersection", {r.intersection.x, r.intersection.y, r.intersection.z}},
          {"plunge_deg", r.plunge_deg},
          {"trend_deg", r.trend_deg},
          {"slide_acceleration_m_s2", dyn::wedge_slide_acceleration(r, dyn::wedge_family_gravity)},
          {"slide_time_s", dyn::wedge_slide_time(c, r, dyn::wedge_family_gravity)},
          // The smallest corner force, of the weight, at the start of a slide without turning.
          {"sliding_support_of_weight", dyn::wedge_sliding_support(c, 0.0).margin}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Write the scenes of a wedge family and their Hoek & Bray references"};
  std::uint64_t seed = 1;
  std::size_t count = 10;
  double phi = 40.0;
  dyn::WedgeSceneParams params = dyn::default_wedge_scene_params();
  std::string dir;
  app.add_option("--seed", seed, "The family's seed")->capture_default_str();
  app.add_option("--count", count, "Number of wedges")->capture_default_str();
  app.add_option("--phi", phi, "Friction angle on both joints, degrees")->capture_default_str();
  app.add_option("--kn", params.kn, "Normal penalty, N/m (kt = kn / 10)")->capture_default_str();
  app.add_option("--dt", params.dt, "Time step, s")->capture_default_str();
  app.add_option("--duration", params.duration, "Duration of `rockcontact run`, s")->capture_default_str();
  app.add_option("--every", params.every, "Record every N steps")->capture_default_str();
  app.add_option("--out", dir, "Output directory")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    std::filesystem::create_directories(dir);
    ordered_json index = ordered_json::array();
    const auto cases = dyn::generate_wedges(seed, count, phi);
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const dyn::WedgeCase& c = cases[k];
      const std::string name = "case_" + std::to_string(k);
      write(std::filesystem::path(dir) / (name + ".json"), dyn::wedge_scene_document(c, params));
      write(std::filesystem::path(dir) / (name + "_cut.json"), dyn::wedge_cut_document(c));
      index.push_back({{"scene", name + ".json"},
                       {"cut", name + "_cut.json"},
                       {"seed", c.seed},
                       {"joint_a", joint_json(c.a)},
                       {"joint_b", joint_json(c.b)},
                       {"crest", {c.crest.x, c.crest.y, c.crest.z}},
                       {"reference", reference_json(c)}});
    }
    write(std::filesystem::path(dir) / "cases.json", index);
  } catch (const std::exception& e) {
    std::cerr << "wedge_family_scenes: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
