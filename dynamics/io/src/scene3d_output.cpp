#include "rockcontact/dynamics/io/scene3d_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <span>
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
using kernel::Point3;
using output_text::csv_field;
using output_text::number;
using output_text::xml_escape;

constexpr std::string_view tracks_header = "t,block,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz";
constexpr std::string_view contacts_header = "t,block_a,block_b,x,y,z,nx,ny,nz,fn,ft,state";

std::string_view mode_name(ContactMode3d mode) {
  switch (mode) {
    case ContactMode3d::open:
      return "open";
    case ContactMode3d::stick:
      return "stick";
    case ContactMode3d::slide:
      return "slide";
  }
  return "?";
}

// Component k of a block's velocity (vx, vy, vz, wx, wy, wz, ...): a fixed block has none, 0.
double velocity(const Block3dState& b, std::size_t k) {
  return k < b.velocity.size() ? b.velocity[k] : 0.0;
}

// One cell's values in a cell-data list of a .vtp file.
void write_numbers(std::ostream& out, std::span<const double> values) {
  out << "         ";
  for (const double v : values) out << ' ' << number(v);
  out << '\n';
}

// One polygon per face as given of every part of every block (header).
void write_frame(const fs::path& file, std::span<const Block3dState> blocks) {
  std::size_t points = 0, polys = 0;
  for (const Block3dState& b : blocks) {
    for (const kernel::ConvexPolyhedron& p : b.parts)
      points += p.size(), polys += p.input_faces().size();
  }
  AtomicFile output(file);
  std::ostream& out = output.stream();
  output_text::open_piece(out, points, 0, polys);
  output_text::open_points(out);
  for (const Block3dState& b : blocks) {
    for (const kernel::ConvexPolyhedron& p : b.parts) {
      for (const Point3& v : p.vertices())
        out << "          " << number(v.x) << ' ' << number(v.y) << ' ' << number(v.z) << '\n';
    }
  }
  out << "        </DataArray>\n      </Points>\n      <Polys>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  std::size_t first = 0;
  std::vector<std::size_t> offsets;
  for (const Block3dState& b : blocks) {
    for (const kernel::ConvexPolyhedron& p : b.parts) {
      for (const auto& face : p.input_faces()) {
        out << "         ";
        for (const std::uint32_t i : face) out << ' ' << first + i;
        out << '\n';
        offsets.push_back((offsets.empty() ? 0 : offsets.back()) + face.size());
      }
      first += p.size();
    }
  }
  out << "        </DataArray>\n"
      << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n         ";
  for (const std::size_t o : offsets) out << ' ' << o;
  out << "\n        </DataArray>\n      </Polys>\n"
      << "      <CellData Scalars=\"block\" Vectors=\"velocity\">\n";
  // Each face's values: its block's (and part's) repeated over the faces.
  const auto per_face = [&](const char* type, const char* name, std::size_t components,
                            auto&& values) {
    out << "        <DataArray type=\"" << type << "\" Name=\"" << name
        << "\" NumberOfComponents=\"" << components << "\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      for (std::size_t j = 0; j < blocks[i].parts.size(); ++j) {
        const std::vector<double> v = values(blocks[i], i, j);
        for (std::size_t f = 0; f < blocks[i].parts[j].input_faces().size(); ++f)
          write_numbers(out, v);
      }
    }
    out << "        </DataArray>\n";
  };
  per_face("Int32", "block", 1, [](const Block3dState&, std::size_t i, std::size_t) {
    return std::vector<double>{static_cast<double>(i)};
  });
  per_face("Int32", "part", 1, [](const Block3dState&, std::size_t, std::size_t j) {
    return std::vector<double>{static_cast<double>(j)};
  });
  per_face("UInt8", "fixed", 1, [](const Block3dState& b, std::size_t, std::size_t) {
    return std::vector<double>{b.fixed ? 1.0 : 0.0};
  });
  per_face("Float64", "velocity", 3, [](const Block3dState& b, std::size_t, std::size_t) {
    return std::vector<double>{velocity(b, 0), velocity(b, 1), velocity(b, 2)};
  });
  per_face("Float64", "angular_velocity", 3, [](const Block3dState& b, std::size_t, std::size_t) {
    return std::vector<double>{velocity(b, 3), velocity(b, 4), velocity(b, 5)};
  });
  // Block3dState::stress is (xx, yy, zz, yz, zx, xy); ParaView reads xx, yy, zz, xy, yz, xz.
  per_face("Float64", "stress", 6, [](const Block3dState& b, std::size_t, std::size_t) {
    const auto& s = b.stress;
    return std::vector<double>{s[0], s[1], s[2], s[5], s[3], s[4]};
  });
  out << "      </CellData>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  output.commit();
}

double dot(const Point3& a, const Point3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Point3 unit(const Point3& a) {
  const double n = std::sqrt(dot(a, a));
  return {a.x / n, a.y / n, a.z / n};
}

// The SVG's view (header): `toward` points from the scene to the viewer, `right` and `up` span
// the picture.
struct View {
  Point3 toward = unit({0.4, -1.0, 0.5});
  Point3 right = unit(cross({0.0, 0.0, 1.0}, toward));
  Point3 up = cross(toward, right);
};

struct DrawnFace {
  double depth;  // along View::toward at the face's centroid: larger is nearer
  std::vector<std::array<double, 2>> corners;  // picture coordinates, m
  double shade;                                // 0 (dark) to 1
  std::size_t block;
};

// The faces turned towards the viewer, far ones first (painter's order).
std::vector<DrawnFace> visible_faces(std::span<const Block3dState> blocks, const View& view) {
  const Point3 light = unit({0.3, -0.5, 1.0});
  std::vector<DrawnFace> faces;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (const kernel::ConvexPolyhedron& p : blocks[i].parts) {
      for (const auto& face : p.input_faces()) {
        Point3 normal{0.0, 0.0, 0.0}, centre{0.0, 0.0, 0.0};  // Newell's normal, the mean vertex
        DrawnFace drawn{0.0, {}, 0.0, i};
        for (std::size_t k = 0; k < face.size(); ++k) {
          const Point3& a = p[face[k]];
          const Point3& b = p[face[(k + 1) % face.size()]];
          normal = {normal.x + (a.y - b.y) * (a.z + b.z), normal.y + (a.z - b.z) * (a.x + b.x),
                    normal.z + (a.x - b.x) * (a.y + b.y)};
          centre = {centre.x + a.x, centre.y + a.y, centre.z + a.z};
          drawn.corners.push_back({dot(a, view.right), dot(a, view.up)});
        }
        if (!(dot(normal, view.toward) > 0.0)) continue;  // turned away (or degenerate, or NaN)
        normal = unit(normal);
        drawn.depth = dot(centre, view.toward) / static_cast<double>(face.size());
        drawn.shade = 0.55 + 0.45 * std::max(0.0, dot(normal, light));
        faces.push_back(std::move(drawn));
      }
    }
  }
  std::stable_sort(faces.begin(), faces.end(),
                   [](const DrawnFace& a, const DrawnFace& b) { return a.depth < b.depth; });
  return faces;
}

std::string shaded(std::array<int, 3> rgb, double shade) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", static_cast<int>(rgb[0] * shade),
                static_cast<int>(rgb[1] * shade), static_cast<int>(rgb[2] * shade));
  return text;
}

void write_svg(const fs::path& file, std::span<const Block3dState> blocks,
               std::span<const std::string> tracked, double time) {
  const std::vector<DrawnFace> faces = visible_faces(blocks, View{});
  output_text::Extent extent;
  for (const DrawnFace& f : faces) {
    for (const auto& [x, y] : f.corners) extent.add(x, y);
  }
  const output_text::SvgCanvas canvas(extent);
  AtomicFile output(file);
  std::ostream& out = output.stream();
  canvas.open(out, time);
  for (const DrawnFace& f : faces) {
    const Block3dState& b = blocks[f.block];
    const bool is_tracked = std::find(tracked.begin(), tracked.end(), b.id) != tracked.end();
    const std::array<int, 3> rgb = b.fixed      ? std::array{189, 189, 189}
                                   : is_tracked ? std::array{242, 142, 43}
                                                : std::array{158, 202, 225};
    std::string points;
    bool finite = true;
    for (const auto& [x, y] : f.corners) {
      finite = finite && std::isfinite(x) && std::isfinite(y);
      points += (points.empty() ? "" : " ") + canvas.point(x, y);
    }
    if (!finite) continue;
    out << "  <polygon fill=\"" << shaded(rgb, f.shade)
        << "\" stroke=\"#303030\" stroke-width=\"0.5\" "
        << "stroke-linejoin=\"round\" points=\"" << points << "\"><title>" << xml_escape(b.id)
        << "</title></polygon>\n";
  }
  out << "  <text x=\"8\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\">t = " << number(time)
      << " s; view from the South-East, above</text>\n"
      << "</svg>\n";
  output.commit();
}

ordered_json energies_json(const Energies3d& e) {
  return {{"kinetic", e.kinetic},
          {"gravitational", e.gravitational},
          {"strain", e.strain},
          {"contact", e.contact},
          {"friction_dissipated", e.friction_dissipated},
          {"damping_dissipated", e.damping_dissipated},
          {"numerical_dissipated", e.numerical_dissipated},
          {"total", e.total()}};
}

constexpr std::array<const char*, kernel::predicate_kind_count> predicate_names = {
    "cross", "crossing_side", "crossing_point", "triple", "plane_side"};

ordered_json predicates_json(const kernel::PredicateCounters& c) {
  ordered_json by_kind;
  for (std::size_t k = 0; k < kernel::predicate_kind_count; ++k) {
    by_kind[predicate_names[k]] = {{"calls", c.calls[k]},
                                   {"interval_fallbacks", c.interval_fallbacks[k]},
                                   {"fallbacks", c.fallbacks[k]}};
  }
  return {{"calls", c.total_calls()},
          {"interval_fallbacks", c.total_interval_fallbacks()},
          {"fallbacks", c.total_fallbacks()},
          {"by_kind", std::move(by_kind)}};
}

// Writes the files of the header into one directory (created if missing).
class Scene3dRecorder {
 public:
  Scene3dRecorder(const Scene3d& scene, fs::path dir) : dir_(std::move(dir)), track_(scene.track) {
    const double steps = std::ceil(scene.duration / scene.params.dt);
    const std::size_t last_frame = static_cast<std::size_t>(steps) / scene.every + 1;
    frame_digits_ = std::max<std::size_t>(4, output_text::decimal_digits(last_frame));
    output_text::create_directory(dir_);
    tracks_.emplace(dir_ / "tracks.csv");
    tracks_->stream() << tracks_header << '\n';
    contacts_.emplace(dir_ / "contacts.csv");
    contacts_->stream() << contacts_header << '\n';
  }

  void record(const Dda3d& simulation) {
    const std::string t = number(simulation.time());
    const std::vector<Block3dState>& blocks = simulation.blocks();
    for (const std::string& id : track_) {
      const auto b = std::find_if(blocks.begin(), blocks.end(),
                                  [&](const Block3dState& s) { return s.id == id; });
      std::ostream& out = tracks_->stream();
      out << t << ',' << csv_field(id) << ',' << number(b->centroid.x) << ','
          << number(b->centroid.y) << ',' << number(b->centroid.z);
      for (const double r : b->rotation) out << ',' << number(r);
      for (std::size_t k = 0; k < 6; ++k) out << ',' << number(velocity(*b, k));
      out << '\n';
    }
    if (!tracks_->stream()) throw OutputError("cannot write " + tracks_->target().string());
    for (const Contact3dState& c : simulation.contacts()) {
      contacts_->stream() << t << ',' << csv_field(blocks[c.block_a].id) << ','
                          << csv_field(blocks[c.block_b].id) << ',' << number(c.point.x) << ','
                          << number(c.point.y) << ',' << number(c.point.z) << ','
                          << number(c.normal.x) << ',' << number(c.normal.y) << ','
                          << number(c.normal.z) << ',' << number(c.normal_force) << ','
                          << number(c.tangential_force) << ',' << mode_name(c.mode) << '\n';
    }
    if (!contacts_->stream()) throw OutputError("cannot write " + contacts_->target().string());
    const std::string name =
        "frame_" + output_text::frame_index(frames_.size(), frame_digits_) + ".vtp";
    write_frame(dir_ / name, blocks);
    frames_.emplace_back(simulation.time(), name);
  }

  void finish(std::span<const Block3dState> blocks, const ordered_json& summary) {
    tracks_->commit();
    contacts_->commit();
    output_text::write_pvd(dir_ / "frames.pvd", frames_);
    write_svg(dir_ / "final.svg", blocks, track_, frames_.empty() ? 0.0 : frames_.back().first);
    output_text::write_json(dir_ / "summary.json", summary);
  }

  std::size_t frames() const noexcept { return frames_.size(); }

 private:
  fs::path dir_;
  std::vector<std::string> track_;
  std::size_t frame_digits_ = 4;
  std::optional<AtomicFile> tracks_;
  std::optional<AtomicFile> contacts_;
  std::vector<std::pair<double, std::string>> frames_;  // (time, file name)
};

// The most negative gap of the current contact list as a depth (0 when none penetrates).
double penetration(const Dda3d& simulation) {
  double depth = 0.0;
  for (const Contact3dState& c : simulation.contacts()) depth = std::max(depth, -c.gap);
  return depth;
}

}  // namespace

ordered_json run3d_summary(const Scene3d& scene, const Run3dReport& report) {
  ordered_json out;
  out["scene"] = scene.source;
  out["description"] = scene.description;
  out["dimension"] = 3;
  out["status"] = report.status;
  if (!report.error.empty()) out["error"] = report.error;
  out["steps"] = report.steps;
  out["time"] = report.time;
  out["dt"] = scene.params.dt;
  out["max_displacement_ratio"] = scene.params.max_displacement_ratio;
  out["max_rotation_deg"] = scene.params.max_rotation_deg;
  // The penalties the run used, and whether "auto" chose them.
  out["kn"] = scene.law.kn;
  out["kt"] = scene.law.kt;
  out["kn_auto"] = scene.kn_auto;
  out["kt_auto"] = scene.kt_auto;
  out["wall_seconds"] = report.simulation_seconds + report.output_seconds;
  out["simulation_seconds"] = report.simulation_seconds;
  out["output_seconds"] = report.output_seconds;
  out["energy"] = {{"start", energies_json(report.initial)}, {"end", energies_json(report.final)}};
  const double mean = report.steps == 0 ? 0.0
                                        : static_cast<double>(report.open_close_total) /
                                              static_cast<double>(report.steps);
  out["open_close_iterations"] = {{"mean", mean}, {"max", report.open_close_max}};
  out["step_cuts"] = report.step_cuts;
  out["predicates"] = predicates_json(report.predicates);
  out["max_penetration"] = report.max_penetration;
  out["initial_equilibrium"] = output_text::equilibrium_json(report.equilibrium);
  output_text::add_blocks_and_frames(out, scene.blocks, scene.track, report.frames);
  return out;
}

Run3dReport run_scene3d(const Scene3d& scene, const Run3dOptions& options) {
  RunClock clock;
  Run3dReport report;
  Dda3d simulation(scene.blocks, scene.law, scene.params);
  report.equilibrium = simulation.initial_equilibrium();
  std::optional<Scene3dRecorder> recorder;
  if (!options.out_dir.empty()) clock.output([&] { recorder.emplace(scene, options.out_dir); });
  const auto record = [&] {
    if (recorder) clock.output([&] { recorder->record(simulation); });
  };
  report.initial = simulation.energies();
  report.max_penetration = penetration(simulation);
  record();
  // The engine sums its steps into time(); less than a millionth of dt left is that sum's
  // rounding (each addition errs by at most 2^-53 of the time), not time to simulate.
  const double end = scene.duration - 1e-6 * scene.params.dt;
  try {
    while (simulation.time() < end) {
      simulation.step();
      const Step3dStats& last = simulation.last_step();
      report.open_close_total += last.open_close_iterations;
      report.open_close_max = std::max(report.open_close_max, last.open_close_iterations);
      report.max_penetration = std::max(report.max_penetration, penetration(simulation));
      if (simulation.steps() % scene.every == 0 || simulation.time() >= end) record();
      if (options.progress) options.progress(simulation.steps(), simulation.time());
    }
  } catch (const Stability3dError& e) {
    report.status = "stopped";
    report.error = e.what();
    if (simulation.steps() % scene.every != 0) record();  // the last state, unless just recorded
  }
  report.steps = simulation.steps();
  report.time = simulation.time();
  report.final = simulation.energies();
  report.step_cuts = simulation.last_step().cuts;
  report.predicates = simulation.predicate_counters();
  report.simulation_seconds = clock.simulation_seconds();
  report.output_seconds = clock.output_seconds();
  if (!recorder) return report;
  report.frames = recorder->frames();
  recorder->finish(simulation.blocks(), run3d_summary(scene, report));
  return report;
}

}  // namespace rockcontact::dynamics
