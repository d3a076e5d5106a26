#pragma once
// What the run outputs share (scene_output.cpp, scene3d_output.cpp, scene_cdem_output.cpp):
// numbers that read back exactly, CSV fields, XML text, the heads of VTK XML pieces, frame
// numbers, the output directory, JSON documents, the ParaView collection (.pvd) of a run's
// frames and the frame of an SVG picture. Internal to the io module.

#include <cstddef>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <ostream>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rockcontact/dynamics/equilibrium.hpp"

namespace rockcontact::dynamics::output_text {

// Shortest text that reads back as the same double ("0.1", "1e-05", "-3.25").
std::string number(double value);

// Pixel coordinates of an SVG: two decimals are far below what a viewer shows.
std::string pixel(double value);

// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text);

// `text` with & < > " ' replaced by their XML entities.
std::string xml_escape(const std::string& text);

// The head of a VTK XML PolyData file up to its one Piece's opening tag.
void open_piece(std::ostream& out, std::size_t points, std::size_t verts, std::size_t polys);

// The head of a VTK XML UnstructuredGrid file up to its one Piece's opening tag.
void open_grid_piece(std::ostream& out, std::size_t points, std::size_t cells);

// The opening of a piece's Points: a Float64 DataArray of 3 components, one point a line follows.
void open_points(std::ostream& out);

// The number of decimal digits of `value` (1 for 0).
std::size_t decimal_digits(std::size_t value);

// The width of the frame numbers of a run of `steps` steps recorded at t = 0, every `every`
// steps and at the last step: the last frame number's digits, at least 4.
std::size_t frame_digits(std::size_t steps, std::size_t every);

// `index` zero-padded to `digits` digits ("0007"); a wider number is written whole.
std::string frame_index(std::size_t index, std::size_t digits);

// Creates the directory `dir` (and its parents) if missing; throws OutputError when it cannot.
void create_directory(const std::filesystem::path& dir);

// `document` indented by 2 spaces, written through an AtomicFile (summary.json).
void write_json(const std::filesystem::path& file, const nlohmann::ordered_json& document);

// Every engine's "initial_equilibrium" of summary.json: null when no block started resting on
// a support, else {blocks, iterations, ratio, converged, seconds, unsettled [ids]}.
nlohmann::ordered_json equilibrium_json(const Equilibrium& e);

// The last keys of every summary.json: "blocks" (the ids of `blocks`, each with an `id`, in
// scene order), "tracked" (`tracked`) and "frames" (`frames`).
template <class BlockSpecs>
void add_blocks_and_frames(nlohmann::ordered_json& summary, const BlockSpecs& blocks,
                           const std::vector<std::string>& tracked, std::size_t frames) {
  nlohmann::ordered_json ids = nlohmann::ordered_json::array();
  for (const auto& b : blocks) ids.push_back(b.id);
  summary["blocks"] = std::move(ids);
  summary["tracked"] = tracked;
  summary["frames"] = frames;
}

// A ParaView collection of (time in s, file name relative to the .pvd) frames, written through
// an AtomicFile; throws OutputError when it cannot be written.
void write_pvd(const std::filesystem::path& file,
               std::span<const std::pair<double, std::string>> frames);

// The extent of what a picture shows, m; non-finite points are left out.
struct Extent {
  double xmin = std::numeric_limits<double>::infinity();
  double xmax = -std::numeric_limits<double>::infinity();
  double ymin = std::numeric_limits<double>::infinity();
  double ymax = -std::numeric_limits<double>::infinity();

  void add(double x, double y);
};

// A plane picture: `extent` (m, y up) fitted to `width_px` pixels with a margin of 5 % of its
// larger side; an empty, flat or non-finite extent becomes the unit square.
class SvgCanvas {
 public:
  explicit SvgCanvas(Extent extent, double width_px = 800.0);

  // "px,py": the pixel coordinates of the point (x, y) in m.
  std::string point(double x, double y) const;

  // The <svg> element's opening with the picture's size, its title "t = <time> s" and a white
  // background.
  void open(std::ostream& out, double time) const;

 private:
  Extent extent_;
  double margin_, scale_, width_px_, height_px_;
};

}  // namespace rockcontact::dynamics::output_text
