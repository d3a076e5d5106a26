#include "output_text.hpp"

#include <array>
#include <charconv>
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

}  // namespace rockcontact::dynamics::output_text
