#include "rockcontact/dynamics/io/scene_cdem_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "output_text.hpp"
#include "run_clock.hpp"
#include "rockcontact/dynamics/io/atomic_file.hpp"

namespace rockcontact::dynamics {

namespace {

using nlohmann::ordered_json;
namespace fs = std::filesystem;
using output_text::csv_field;
using output_text::number;
using output_text::xml_escape;

constexpr std::string_view tracks_header = "t,block,x,y,rotation,vx,vy,omega";
constexpr std::string_view events_header = "t,event,block_a,block_b";
constexpr std::uint8_t vtk_triangle = 5;

std::string_view law_name(CdemLaw law) {
  switch (law) {
    case CdemLaw::two_scale:
      return "two-scale";
    case CdemLaw::penalty:
      return "penalty";
  }
  return "?";
}

std::string_view event_name(CdemEvent::Kind kind) {
  switch (kind) {
    case CdemEvent::Kind::touch:
      return "touch";
    case CdemEvent::Kind::separate:
      return "separate";
  }
  return "?";
}

// The von Mises stress of an element's plane stress (xx, yy, xy), Pa: sigma_zz is
// nu (sigma_xx + sigma_yy) in plane strain (the elastic out-of-plane stress) and 0 in plane
// stress.
double von_mises(const std::array<double, 3>& s, CdemPlane plane, double poisson_ratio) {
  const double zz = plane == CdemPlane::strain ? poisson_ratio * (s[0] + s[1]) : 0.0;
  const double a = s[0] - s[1], b = s[1] - zz, c = zz - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * s[2] * s[2]);
}

// One DataArray of a piece: `name`, `components` values a line, `lines` given by `write_line`.
template <class WriteLine>
void data_array(std::ostream& out, std::string_view type, std::string_view name,
                std::size_t components, std::size_t lines, WriteLine&& write_line) {
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name
      << "\" NumberOfComponents=\"" << components << "\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < lines; ++k) {
    out << "         ";
    write_line(k);
    out << '\n';
  }
  out << "        </DataArray>\n";
}

// Every block's mesh as one grid (header): points, triangle cells, point and cell data.
void write_frame(const fs::path& file, const Cdem& simulation, CdemPlane plane) {
  std::vector<CdemMeshView> meshes;
  std::vector<std::size_t> first_node{0}, cell_block;  // node offset of each block; cell's block
  std::vector<std::array<std::size_t, 3>> cells;
  for (std::size_t i = 0; i < simulation.block_count(); ++i) {
    const CdemMeshView& mesh = meshes.emplace_back(simulation.mesh(i));
    for (const auto& t : *mesh.triangles) {
      const std::size_t o = first_node.back();
      cells.push_back({o + t[0], o + t[1], o + t[2]});
      cell_block.push_back(i);
    }
    first_node.push_back(first_node.back() + mesh.nodes->size());
  }
  const std::size_t points = first_node.back();
  AtomicFile output(file);
  std::ostream& out = output.stream();
  output_text::open_grid_piece(out, points, cells.size());
  output_text::open_points(out);
  for (const CdemMeshView& mesh : meshes) {
    for (const kernel::Point2& p : *mesh.nodes)
      out << "          " << number(p.x) << ' ' << number(p.y) << " 0\n";
  }
  out << "        </DataArray>\n      </Points>\n      <Cells>\n";
  data_array(out, "Int64", "connectivity", 1, cells.size(), [&](std::size_t c) {
    out << ' ' << cells[c][0] << ' ' << cells[c][1] << ' ' << cells[c][2];
  });
  data_array(out, "Int64", "offsets", 1, cells.size(),
             [&](std::size_t c) { out << ' ' << 3 * (c + 1); });
  data_array(out, "UInt8", "types", 1, cells.size(),
             [&](std::size_t) { out << ' ' << static_cast<int>(vtk_triangle); });
  out << "      </Cells>\n      <PointData Vectors=\"velocity\">\n";
  std::vector<const std::array<double, 2>*> velocity;
  for (const CdemMeshView& mesh : meshes) {
    for (const auto& v : *mesh.velocities) velocity.push_back(&v);
  }
  data_array(out, "Float64", "velocity", 3, points, [&](std::size_t k) {
    out << ' ' << number((*velocity[k])[0]) << ' ' << number((*velocity[k])[1]) << " 0";
  });
  out << "      </PointData>\n      <CellData Scalars=\"block\">\n";
  data_array(out, "Int32", "block", 1, cells.size(),
             [&](std::size_t c) { out << ' ' << cell_block[c]; });
  std::vector<const std::array<double, 3>*> stress;
  for (const CdemMeshView& mesh : meshes) {
    for (const auto& s : *mesh.stresses) stress.push_back(&s);
  }
  data_array(out, "Float64", "stress", 3, cells.size(), [&](std::size_t c) {
    for (const double s : *stress[c]) out << ' ' << number(s);
  });
  data_array(out, "Float64", "von_mises", 1, cells.size(), [&](std::size_t c) {
    const double nu = simulation.block(cell_block[c]).material.poisson_ratio;
    out << ' ' << number(von_mises(*stress[c], plane, nu));
  });
  out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  output.commit();
}

// The edges of a mesh that belong to one triangle only: its outline (the block's boundary).
std::vector<std::array<std::uint32_t, 2>> boundary_edges(const CdemMeshView& mesh) {
  std::map<std::array<std::uint32_t, 2>, int> count;
  for (const auto& t : *mesh.triangles) {
    for (std::size_t k = 0; k < 3; ++k)
      ++count[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  }
  std::vector<std::array<std::uint32_t, 2>> edges;
  for (const auto& [edge, n] : count) {
    if (n == 1) edges.push_back(edge);
  }
  return edges;
}

// The final meshes (header): one group per block, its elements filled, its outline over them.
void write_svg(const fs::path& file, const Cdem& simulation, std::span<const std::string> tracked) {
  output_text::Extent extent;
  for (std::size_t i = 0; i < simulation.block_count(); ++i) {
    for (const kernel::Point2& p : *simulation.mesh(i).nodes) extent.add(p.x, p.y);
  }
  const output_text::SvgCanvas canvas(extent);
  AtomicFile output(file);
  std::ostream& out = output.stream();
  canvas.open(out, simulation.time());
  for (std::size_t i = 0; i < simulation.block_count(); ++i) {
    const CdemBlockSpec& b = simulation.block(i);
    const CdemMeshView mesh = simulation.mesh(i);
    const std::vector<kernel::Point2>& nodes = *mesh.nodes;
    const auto finite = [&](std::uint32_t n) {
      return std::isfinite(nodes[n].x) && std::isfinite(nodes[n].y);
    };
    const bool is_tracked = std::find(tracked.begin(), tracked.end(), b.id) != tracked.end();
    const char* style = b.fixed      ? "fill=\"#bdbdbd\" stroke=\"#616161\""
                        : is_tracked ? "fill=\"#f28e2b\" stroke=\"#7f3b08\""
                                     : "fill=\"#9ecae1\" stroke=\"#2171b5\"";
    out << "  <g " << style << " stroke-linejoin=\"round\"><title>" << xml_escape(b.id)
        << "</title>\n";
    for (const auto& t : *mesh.triangles) {
      if (!finite(t[0]) || !finite(t[1]) || !finite(t[2])) continue;
      out << "    <polygon stroke-width=\"0.3\" points=\"";
      for (std::size_t k = 0; k < 3; ++k)
        out << (k == 0 ? "" : " ") << canvas.point(nodes[t[k]].x, nodes[t[k]].y);
      out << "\"/>\n";
    }
    std::string outline;
    for (const auto& [m, n] : boundary_edges(mesh)) {
      if (!finite(m) || !finite(n)) continue;
      outline += (outline.empty() ? "M" : " M") + canvas.point(nodes[m].x, nodes[m].y) + " L" +
                 canvas.point(nodes[n].x, nodes[n].y);
    }
    out << "    <path fill=\"none\" stroke-width=\"1.5\" d=\"" << outline << "\"/>\n  </g>\n";
  }
  out << "  <text x=\"8\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\">t = "
      << number(simulation.time()) << " s</text>\n"
      << "</svg>\n";
  output.commit();
}

ordered_json energies_json(const CdemEnergies& e) {
  return {{"kinetic", e.kinetic},
          {"strain", e.strain},
          {"gravitational", e.gravitational},
          {"contact", e.contact},
          {"onset_loss", e.onset_loss},
          {"friction", e.friction},
          {"damping", e.damping},
          {"tie_work", e.tie_work},
          {"total", e.total()}};
}

// Writes the files of the header into one directory (created if missing).
class SceneCdemRecorder {
 public:
  SceneCdemRecorder(const SceneCdem& scene, fs::path dir)
      : dir_(std::move(dir)),
        track_(scene.track),
        plane_(scene.params.plane),
        frame_digits_(output_text::frame_digits(step_count(scene), scene.every)) {
    for (const std::string& id : track_) {
      const auto b = std::find_if(scene.blocks.begin(), scene.blocks.end(),
                                  [&](const CdemBlockSpec& s) { return s.id == id; });
      tracked_.push_back(static_cast<std::size_t>(b - scene.blocks.begin()));
    }
    output_text::create_directory(dir_);
    tracks_.emplace(dir_ / "tracks.csv");
    tracks_->stream() << tracks_header << '\n';
  }

  void record(const Cdem& simulation) {
    const std::string t = number(simulation.time());
    std::ostream& out = tracks_->stream();
    for (std::size_t k = 0; k < tracked_.size(); ++k) {
      const CdemBlockState b = simulation.block_state(tracked_[k]);
      out << t << ',' << csv_field(track_[k]) << ',' << number(b.centre[0]) << ','
          << number(b.centre[1]) << ',' << number(b.rotation) << ',' << number(b.velocity[0])
          << ',' << number(b.velocity[1]) << ',' << number(b.omega) << '\n';
    }
    if (!out) throw OutputError("cannot write " + tracks_->target().string());
    const std::string name =
        "frame_" + output_text::frame_index(frames_.size(), frame_digits_) + ".vtu";
    write_frame(dir_ / name, simulation, plane_);
    frames_.emplace_back(simulation.time(), name);
  }

  void finish(const Cdem& simulation, const ordered_json& summary) {
    tracks_->commit();
    AtomicFile events(dir_ / "events.csv");
    events.stream() << events_header << '\n';
    for (const CdemEvent& e : simulation.events()) {
      events.stream() << number(e.t) << ',' << event_name(e.kind) << ','
                      << csv_field(simulation.block(e.block_a).id) << ','
                      << csv_field(simulation.block(e.block_b).id) << '\n';
    }
    events.commit();
    output_text::write_pvd(dir_ / "frames.pvd", frames_);
    write_svg(dir_ / "final.svg", simulation, track_);
    output_text::write_json(dir_ / "summary.json", summary);
  }

  std::size_t frames() const noexcept { return frames_.size(); }

 private:
  fs::path dir_;
  std::vector<std::string> track_;
  std::vector<std::size_t> tracked_;  // the block index of each id of track_
  CdemPlane plane_;
  std::size_t frame_digits_;
  std::optional<AtomicFile> tracks_;
  std::vector<std::pair<double, std::string>> frames_;  // (time, file name)
};

}  // namespace

ordered_json run_cdem_summary(const SceneCdem& scene, const RunCdemReport& report) {
  ordered_json out;
  out["scene"] = scene.source;
  out["description"] = scene.description;
  out["dimension"] = 2;
  out["solver"] = "cdem";
  out["law"] = law_name(scene.params.contact.law);
  out["status"] = report.status;
  if (!report.error.empty()) out["error"] = report.error;
  out["steps"] = report.steps;
  out["time"] = report.time;
  out["dt"] = scene.params.dt;
  out["critical_dt"] =
      std::isfinite(report.critical_dt) ? ordered_json(report.critical_dt) : ordered_json(nullptr);
  out["wall_seconds"] = report.simulation_seconds + report.output_seconds;
  out["simulation_seconds"] = report.simulation_seconds;
  out["output_seconds"] = report.output_seconds;
  out["elements"] = report.elements;
  out["nodes"] = report.nodes;
  out["energy"] = {{"start", energies_json(report.initial)}, {"end", energies_json(report.final)}};
  out["momentum"] = {{"start", report.momentum_initial}, {"end", report.momentum_final}};
  out["clone_nodes"] = {{"formed", report.counters.clone_nodes_formed},
                        {"separated", report.counters.clone_nodes_separated}};
  out["touches"] = report.counters.touches;
  out["subdivided_elements"] = report.counters.subdivided_elements;
  out["events"] = report.events;
  output_text::add_blocks_and_frames(out, scene.blocks, scene.track, report.frames);
  return out;
}

RunCdemReport run_scene_cdem(const SceneCdem& scene, const RunCdemOptions& options) {
  RunClock clock;
  RunCdemReport report;
  Cdem simulation(scene.blocks, scene.params);
  report.elements = simulation.element_count();
  report.nodes = simulation.node_count();
  report.critical_dt = simulation.critical_dt();
  std::optional<SceneCdemRecorder> recorder;
  if (!options.out_dir.empty()) clock.output([&] { recorder.emplace(scene, options.out_dir); });
  const auto record = [&] {
    if (recorder) clock.output([&] { recorder->record(simulation); });
  };
  report.initial = simulation.energies();
  report.momentum_initial = simulation.momentum();
  record();
  const std::size_t total = step_count(scene);
  try {
    for (std::size_t s = 1; s <= total; ++s) {
      simulation.step();
      if (s % scene.every == 0 || s == total) record();
      if (options.progress) options.progress(s, total);
    }
  } catch (const CdemStabilityError& e) {
    report.status = "stopped";
    report.error = e.what();
    if (simulation.steps() % scene.every != 0) record();  // the last state, unless just recorded
  }
  report.steps = simulation.steps();
  report.time = simulation.time();
  report.final = simulation.energies();
  report.momentum_final = simulation.momentum();
  report.counters = simulation.counters();
  report.events = simulation.events().size();
  report.simulation_seconds = clock.simulation_seconds();
  report.output_seconds = clock.output_seconds();
  if (!recorder) return report;
  report.frames = recorder->frames();
  clock.output([&] { recorder->finish(simulation, run_cdem_summary(scene, report)); });
  report.output_seconds = clock.output_seconds();  // the summary's, and writing it
  return report;
}

}  // namespace rockcontact::dynamics
