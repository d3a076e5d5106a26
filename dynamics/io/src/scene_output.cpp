#include "rockcontact/dynamics/io/scene_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "output_text.hpp"
#include "run_clock.hpp"
#include "rockcontact/dynamics/io/checkpoint.hpp"

namespace rockcontact::dynamics {

namespace {

using nlohmann::ordered_json;
namespace fs = std::filesystem;
using output_text::csv_field;
using output_text::number;
using output_text::open_piece;
using output_text::open_points;
using output_text::write_pvd;
using output_text::xml_escape;

void write_vtp(const fs::path& file, std::span<const BlockState> blocks) {
  std::size_t points = 0;
  for (const BlockState& b : blocks) points += b.vertices.size();
  AtomicFile output(file);
  std::ostream& out = output.stream();
  open_piece(out, points, 0, blocks.size());
  open_points(out);
  for (const BlockState& b : blocks) {
    for (const kernel::Point2& p : b.vertices) {
      out << "          " << number(p.x) << ' ' << number(p.y) << " 0\n";
    }
  }
  out << "        </DataArray>\n      </Points>\n      <Polys>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  std::size_t next = 0;
  for (const BlockState& b : blocks) {
    out << "         ";
    for (std::size_t i = 0; i < b.vertices.size(); ++i) out << ' ' << next++;
    out << '\n';
  }
  out << "        </DataArray>\n"
      << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n         ";
  std::size_t offset = 0;
  for (const BlockState& b : blocks) out << ' ' << (offset += b.vertices.size());
  out << "\n        </DataArray>\n      </Polys>\n"
      << "      <CellData Scalars=\"block\" Vectors=\"velocity\">\n"
      << "        <DataArray type=\"Int32\" Name=\"block\" format=\"ascii\">\n         ";
  for (std::size_t i = 0; i < blocks.size(); ++i) out << ' ' << i;
  out << "\n        </DataArray>\n"
      << "        <DataArray type=\"UInt8\" Name=\"fixed\" format=\"ascii\">\n         ";
  for (const BlockState& b : blocks) out << ' ' << (b.fixed ? 1 : 0);
  out << "\n        </DataArray>\n"
      << "        <DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  for (const BlockState& b : blocks) {
    out << "          " << number(b.velocity[0]) << ' ' << number(b.velocity[1]) << " 0\n";
  }
  out << "        </DataArray>\n"
      << "        <DataArray type=\"Float64\" Name=\"omega\" format=\"ascii\">\n         ";
  for (const BlockState& b : blocks) out << ' ' << number(b.velocity[2]);
  out << "\n        </DataArray>\n"
      << "        <DataArray type=\"Float64\" Name=\"stress\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  for (const BlockState& b : blocks) {
    out << "          " << number(b.stress[0]) << ' ' << number(b.stress[1]) << ' '
        << number(b.stress[2]) << '\n';
  }
  out << "        </DataArray>\n      </CellData>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  output.commit();
}

// One contact row of contacts.csv and contacts_NNNN.vtp.
struct ContactRow {
  std::string a, b;
  double x, y, nx, ny, fn, ft;
  int state;  // 0 stick, 1 slide, 2 open
};

constexpr const char* state_names[] = {"stick", "slide", "open"};

void write_contact_vtp(const fs::path& file, std::span<const ContactRow> rows) {
  AtomicFile output(file);
  std::ostream& out = output.stream();
  open_piece(out, rows.size(), rows.size(), 0);
  open_points(out);
  for (const ContactRow& r : rows) out << "          " << number(r.x) << ' ' << number(r.y) << " 0\n";
  out << "        </DataArray>\n      </Points>\n      <Verts>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n         ";
  for (std::size_t k = 0; k < rows.size(); ++k) out << ' ' << k;
  out << "\n        </DataArray>\n"
      << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n         ";
  for (std::size_t k = 0; k < rows.size(); ++k) out << ' ' << k + 1;
  out << "\n        </DataArray>\n      </Verts>\n"
      << "      <PointData Scalars=\"fn\" Vectors=\"normal\">\n"
      << "        <DataArray type=\"Float64\" Name=\"normal\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  for (const ContactRow& r : rows) out << "          " << number(r.nx) << ' ' << number(r.ny) << " 0\n";
  out << "        </DataArray>\n";
  for (const auto& [name, member] : {std::pair{"fn", &ContactRow::fn}, std::pair{"ft", &ContactRow::ft}}) {
    out << "        <DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n         ";
    for (const ContactRow& r : rows) out << ' ' << number(r.*member);
    out << "\n        </DataArray>\n";
  }
  out << "        <DataArray type=\"Int32\" Name=\"state\" format=\"ascii\">\n         ";
  for (const ContactRow& r : rows) out << ' ' << r.state;
  out << "\n        </DataArray>\n      </PointData>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  output.commit();
}

// A ParaView collection of the files of `frames`.
bool all_finite(std::span<const kernel::Point2> polygon) {
  return std::all_of(polygon.begin(), polygon.end(),
                     [](const auto& p) { return std::isfinite(p.x) && std::isfinite(p.y); });
}

// The blocks at `time` filled, over the movable blocks at `start_time` as dashed outlines
// (`start`: each block's vertices then, in the same order; empty: none), with both times
// written in the corner.
void write_svg(const fs::path& file, std::span<const BlockState> blocks,
               std::span<const std::vector<kernel::Point2>> start, double start_time,
               std::span<const std::string> tracked, double time) {
  output_text::Extent extent;
  for (const BlockState& b : blocks) {
    for (const kernel::Point2& p : b.vertices) extent.add(p.x, p.y);
  }
  for (const auto& polygon : start) {
    for (const kernel::Point2& p : polygon) extent.add(p.x, p.y);
  }
  const output_text::SvgCanvas canvas(extent);
  AtomicFile output(file);
  std::ostream& out = output.stream();
  canvas.open(out, time);
  const auto points = [&](std::span<const kernel::Point2> polygon) {
    std::string text;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      text += (i == 0 ? "" : " ") + canvas.point(polygon[i].x, polygon[i].y);
    }
    return text;
  };
  for (const BlockState& b : blocks) {
    if (!all_finite(b.vertices)) continue;
    const bool is_tracked = std::find(tracked.begin(), tracked.end(), b.id) != tracked.end();
    const char* style = b.fixed      ? "fill=\"#bdbdbd\" stroke=\"#616161\" stroke-width=\"1\""
                        : is_tracked ? "fill=\"#f28e2b\" stroke=\"#7f3b08\" stroke-width=\"2\""
                                     : "fill=\"#9ecae1\" stroke=\"#2171b5\" stroke-width=\"1\"";
    out << "  <polygon " << style << " points=\"" << points(b.vertices) << "\"><title>"
        << xml_escape(b.id) << "</title></polygon>\n";
  }
  for (std::size_t i = 0; i < start.size() && i < blocks.size(); ++i) {
    if (blocks[i].fixed || !all_finite(start[i])) continue;
    out << "  <polygon fill=\"none\" stroke=\"#525252\" stroke-width=\"1\" "
           "stroke-dasharray=\"4 3\" points=\""
        << points(start[i]) << "\"><title>" << xml_escape(blocks[i].id) << " at t = "
        << number(start_time) << " s</title></polygon>\n";
  }
  out << "  <text x=\"8\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\">t = "
      << number(time) << " s; dashed: t = " << number(start_time) << " s</text>\n"
      << "</svg>\n";
  output.commit();
}

// The energy terms by name, in the order of summary.json and energies.csv.
std::array<std::pair<const char*, double>, 7> energy_terms(const Energies& e) {
  return {{{"kinetic", e.kinetic},
           {"gravitational", e.gravitational},
           {"strain", e.strain},
           {"contact", e.contact},
           {"friction_dissipated", e.friction_dissipated},
           {"damping_dissipated", e.damping_dissipated},
           {"total", e.total()}}};
}

ordered_json energies_json(const Energies& e) {
  ordered_json out;
  for (const auto& [name, value] : energy_terms(e)) out[name] = value;
  return out;
}

}  // namespace

SceneRecorder::SceneRecorder(const Scene& scene, fs::path dir)
    : dir_(std::move(dir)), track_(scene.track) {
  frame_digits_ = output_text::frame_digits(step_count(scene), scene.every);
  output_text::create_directory(dir_);
  tracks_.emplace(dir_ / "tracks.csv");
  tracks_->stream() << "t,block,x,y,rotation,vx,vy,omega\n";
  energies_.emplace(dir_ / "energies.csv");
  energies_->stream() << 't';
  for (const auto& term : energy_terms(Energies{})) energies_->stream() << ',' << term.first;
  energies_->stream() << '\n';
  contacts_.emplace(dir_ / "contacts.csv");
  contacts_->stream() << "t,block_a,block_b,x,y,nx,ny,fn,ft,state\n";
}

void SceneRecorder::record(double time, std::span<const BlockState> blocks,
                           std::span<const ContactState> contacts, const Energies& energies) {
  for (const std::string& id : track_) {
    const auto it =
        std::find_if(blocks.begin(), blocks.end(), [&](const BlockState& b) { return b.id == id; });
    if (it == blocks.end()) continue;
    tracks_->stream() << number(time) << ',' << csv_field(id) << ',' << number(it->centroid.x) << ','
            << number(it->centroid.y) << ',' << number(it->rotation) << ','
            << number(it->velocity[0]) << ',' << number(it->velocity[1]) << ','
            << number(it->velocity[2]) << '\n';
  }
  if (!tracks_->stream()) throw OutputError("cannot write " + tracks_->target().string());
  energies_->stream() << number(time);
  for (const auto& term : energy_terms(energies)) energies_->stream() << ',' << number(term.second);
  energies_->stream() << '\n';
  if (!energies_->stream()) throw OutputError("cannot write " + energies_->target().string());
  std::vector<ContactRow> rows;
  std::map<std::array<std::size_t, 4>, Open> now;
  for (const ContactState& c : contacts) {
    const double size = std::hypot(c.normal_force.x, c.normal_force.y);
    const double nx = c.normal_force.x / size, ny = c.normal_force.y / size;
    const double fx = c.normal_force.x + c.friction_force.x + c.damping_force.x;
    const double fy = c.normal_force.y + c.friction_force.y + c.damping_force.y;
    ContactRow& r = rows.emplace_back(ContactRow{blocks[c.cp].id, blocks[c.tp].id, c.point.x,
                                                 c.point.y, nx, ny, fx * nx + fy * ny,
                                                 -fx * ny + fy * nx, c.sliding ? 1 : 0});
    now[{c.cp, c.tp, c.cp_part, c.tp_part}] = {r.a, r.b, r.x, r.y, r.nx, r.ny};
  }
  for (const auto& [key, gone] : last_contacts_) {
    if (!now.contains(key)) rows.push_back({gone.a, gone.b, gone.x, gone.y, gone.nx, gone.ny, 0.0, 0.0, 2});
  }
  last_contacts_ = std::move(now);
  for (const ContactRow& r : rows) {
    contacts_->stream() << number(time) << ',' << csv_field(r.a) << ',' << csv_field(r.b) << ','
                        << number(r.x) << ',' << number(r.y) << ',' << number(r.nx) << ','
                        << number(r.ny) << ',' << number(r.fn) << ',' << number(r.ft) << ','
                        << state_names[r.state] << '\n';
  }
  if (!contacts_->stream()) throw OutputError("cannot write " + contacts_->target().string());
  const std::string index = output_text::frame_index(frames_.size(), frame_digits_);
  write_vtp(dir_ / ("frame_" + index + ".vtp"), blocks);
  if (frames_.empty()) {
    for (const BlockState& b : blocks) start_.push_back(b.vertices);
  }
  write_contact_vtp(dir_ / ("contacts_" + index + ".vtp"), rows);
  frames_.push_back({time, index});
}

void SceneRecorder::finish(std::span<const BlockState> blocks, const ordered_json& summary) {
  tracks_->commit();
  energies_->commit();
  contacts_->commit();
  for (const auto& [prefix, collection] : {std::pair{"frame_", "frames.pvd"},
                                             std::pair{"contacts_", "contacts.pvd"}}) {
    std::vector<std::pair<double, std::string>> files;
    for (const Frame& f : frames_) files.emplace_back(f.time, prefix + f.index + ".vtp");
    write_pvd(dir_ / collection, files);
  }
  write_svg(dir_ / "final.svg", blocks, start_, frames_.empty() ? 0.0 : frames_.front().time,
            track_, frames_.empty() ? 0.0 : frames_.back().time);
  output_text::write_json(dir_ / "summary.json", summary);
}

ordered_json run_summary(const Scene& scene, const RunReport& report) {
  ordered_json out;
  out["scene"] = scene.source;
  out["description"] = scene.description;
  out["status"] = report.status;
  if (!report.error.empty()) out["error"] = report.error;
  out["steps"] = report.steps;
  out["time"] = report.time;
  out["dt"] = scene.params.dt;
  out["critical_time_step"] = std::isfinite(report.critical_time_step)
                                  ? ordered_json(report.critical_time_step)
                                  : ordered_json(nullptr);
  out["critical_time_step_source"] = report.critical_time_step_source;
  out["H"] = scene.law.normal.H;
  out["H_rule"] = to_string(scene.h_rule);
  if (!report.restarted_from.empty()) {
    out["restart"] = {{"file", report.restarted_from.string()},
                      {"steps", report.restart_steps},
                      {"time", static_cast<double>(report.restart_steps) * scene.params.dt}};
  }
  out["wall_seconds"] = report.simulation_seconds + report.output_seconds;
  out["simulation_seconds"] = report.simulation_seconds;
  out["output_seconds"] = report.output_seconds;
  out["energy"] = {{"start", energies_json(report.initial)}, {"end", energies_json(report.final)}};
  out["predicates"] = {{"calls", report.predicates.total_calls()},
                       {"fallbacks", report.predicates.total_fallbacks()}};
  out["max_penetration"] = report.max_penetration;
  out["initial_equilibrium"] = output_text::equilibrium_json(report.equilibrium);
  if (scene.params.analysis == Analysis::static_equilibrium) {
    ordered_json history = ordered_json::array();
    for (const auto& [step, ratio] : report.balance) history.push_back({step, ratio});
    out["static"] = {{"tolerance", scene.static_tolerance},
                     {"converged", report.converged},
                     {"iterations", report.steps},
                     {"ratio", report.balance.empty() ? 0.0 : report.balance.back().second},
                     {"history", std::move(history)}};
  }
  output_text::add_blocks_and_frames(out, scene.blocks, scene.track, report.frames);
  return out;
}

RunReport run_scene(const Scene& scene, const RunOptions& options) {
  RunClock clock;
  RunReport report;
  if (options.checkpoint_every > 0 && options.out_dir.empty()) {
    throw std::invalid_argument("run_scene: checkpoints need an output directory");
  }
  std::optional<Checkpoint> resume;
  if (!options.restart.empty()) {
    resume = read_checkpoint(options.restart, scene);
    report.restarted_from = options.restart;
    report.restart_steps = resume->engine.steps;
  }
  Dda2d simulation = resume ? Dda2d(scene.blocks, scene.law, scene.params, resume->engine)
                            : Dda2d(scene.blocks, scene.law, scene.params);
  report.equilibrium = simulation.initial_equilibrium();
  std::optional<SceneRecorder> recorder;
  const bool static_analysis = scene.params.analysis == Analysis::static_equilibrium;
  const auto record = [&] {
    if (static_analysis) report.balance.emplace_back(simulation.steps(), simulation.balance_ratio());
    if (!recorder) return;
    clock.output([&] {
      recorder->record(simulation.time(), simulation.blocks(), simulation.contacts(),
                       simulation.energies());
    });
  };
  // Fills the report from the simulation as it stands and completes the files.
  const auto conclude = [&] {
    report.steps = simulation.steps();
    report.time = simulation.time();
    report.final = simulation.energies();
    report.max_penetration = simulation.max_penetration();
    report.critical_time_step = simulation.critical_time_step();
    report.critical_time_step_source = simulation.critical_time_step_source();
    report.predicates = simulation.predicate_counters();
    report.simulation_seconds = clock.simulation_seconds();
    report.output_seconds = clock.output_seconds();
    if (!recorder) return;
    report.frames = recorder->frames();
    clock.output([&] { recorder->finish(simulation.blocks(), run_summary(scene, report)); });
    report.output_seconds = clock.output_seconds();  // the summary's, and writing it
  };

  if (!options.out_dir.empty()) clock.output([&] { recorder.emplace(scene, options.out_dir); });
  report.initial = resume ? resume->initial : simulation.energies();
  record();
  if (options.observer) options.observer(simulation);
  const std::size_t total = step_count(scene);
  try {
    for (std::size_t s = simulation.steps() + 1; s <= total; ++s) {
      simulation.step();
      if (options.checkpoint_every > 0 && s % options.checkpoint_every == 0) {
        clock.output([&] {
          write_checkpoint(options.out_dir / "checkpoint.json", scene,
                           {scene.digest, report.initial, simulation.snapshot()});
        });
      }
      if (options.observer) options.observer(simulation);
      report.converged = static_analysis && simulation.balance_ratio() < scene.static_tolerance;
      if (s % scene.every == 0 || s == total || report.converged) record();
      if (options.progress) options.progress(s, total);
      if (report.converged) break;
    }
  } catch (const StabilityError& e) {
    report.status = "stopped";
    report.error = e.what();
  }
  conclude();
  return report;
}

}  // namespace rockcontact::dynamics
