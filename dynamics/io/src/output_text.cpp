#include "output_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

#include "rockcontact/dynamics/io/atomic_file.hpp"

namespace rockcontact::dynamics::output_text {

std::string number(double value) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), end);
}

std::string pixel(double value) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                       std::chars_format::fixed, 2);
  return std::string(buffer.data(), end);
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string xml_escape(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&apos;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

void open_piece(std::ostream& out, std::size_t points, std::size_t verts, std::size_t polys) {
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << points << "\" NumberOfVerts=\"" << verts
      << "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" << polys << "\">\n";
}

void open_grid_piece(std::ostream& out, std::size_t points, std::size_t cells) {
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << points << "\" NumberOfCells=\"" << cells << "\">\n";
}

void open_points(std::ostream& out) {
  out << "      <Points>\n"
      << "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
}

std::size_t decimal_digits(std::size_t value) {
  std::size_t digits = 1;
  while (value >= 10) value /= 10, ++digits;
  return digits;
}

std::size_t frame_digits(std::size_t steps, std::size_t every) {
  const std::size_t last_frame = steps / every + (steps % every == 0 ? 0 : 1);
  return std::max<std::size_t>(4, decimal_digits(last_frame));
}

std::string frame_index(std::size_t index, std::size_t digits) {
  std::string text = std::to_string(index);
  text.insert(0, digits - std::min(digits, text.size()), '0');
  return text;
}

void create_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError("cannot create the directory " + dir.string() + ": " + ec.message());
}

void write_json(const std::filesystem::path& file, const nlohmann::ordered_json& document) {
  AtomicFile output(file);
  output.stream() << document.dump(2) << '\n';
  output.commit();
}

void write_pvd(const std::filesystem::path& file,
               std::span<const std::pair<double, std::string>> frames) {
  AtomicFile pvd(file);
  std::ostream& out = pvd.stream();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const auto& [time, name] : frames) {
    out << "    <DataSet timestep=\"" << number(time) << "\" group=\"\" part=\"0\" file=\"" << name
        << "\"/>\n";
  }
  out << "  </Collection>\n</VTKFile>\n";
  pvd.commit();
}

void Extent::add(double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  xmin = std::min(xmin, x), xmax = std::max(xmax, x);
  ymin = std::min(ymin, y), ymax = std::max(ymax, y);
}

SvgCanvas::SvgCanvas(Extent extent, double width_px) : extent_(extent), width_px_(width_px) {
  Extent& e = extent_;
  if (!(e.xmin < e.xmax && e.ymin < e.ymax && std::isfinite(e.xmax - e.xmin) &&
        std::isfinite(e.ymax - e.ymin))) {
    e = {0.0, 1.0, 0.0, 1.0};  // nothing finite to show
  }
  margin_ = 0.05 * std::max(e.xmax - e.xmin, e.ymax - e.ymin);
  scale_ = width_px_ / (e.xmax - e.xmin + 2.0 * margin_);
  height_px_ = (e.ymax - e.ymin + 2.0 * margin_) * scale_;
}

std::string SvgCanvas::point(double x, double y) const {
  return pixel((x - extent_.xmin + margin_) * scale_) + ',' +
         pixel((extent_.ymax + margin_ - y) * scale_);
}

void SvgCanvas::open(std::ostream& out, double time) const {
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << pixel(width_px_)
      << "\" height=\"" << pixel(height_px_) << "\" viewBox=\"0 0 " << pixel(width_px_) << ' '
      << pixel(height_px_) << "\">\n"
      << "  <title>t = " << number(time) << " s</title>\n"
      << "  <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
}

nlohmann::ordered_json equilibrium_json(const Equilibrium& e) {
  if (!e.ran) return nullptr;
  return {{"blocks", e.blocks},   {"iterations", e.iterations}, {"ratio", e.ratio},
          {"converged", e.converged}, {"seconds", e.seconds},     {"unsettled", e.unsettled}};
}

}  // namespace rockcontact::dynamics::output_text
