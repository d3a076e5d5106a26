#pragma once
// The text formats shared by the 2D and 3D run outputs (scene_output.cpp, scene3d_output.cpp):
// numbers that read back exactly, CSV fields, XML text, the head of a VTK XML PolyData piece
// and the ParaView collection (.pvd) of a run's frames. Internal to the io module.

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <span>
#include <string>
#include <utility>

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

// A ParaView collection of (time in s, file name relative to the .pvd) frames, written through
// an AtomicFile; throws OutputError when it cannot be written.
void write_pvd(const std::filesystem::path& file,
               std::span<const std::pair<double, std::string>> frames);

}  // namespace rockcontact::dynamics::output_text
