#pragma once
// Reading back what `rockcontact run` writes, for the tests of the run outputs (2D, 3D, CDEM):
// text, CSV rows under an exact header, XML (VTK frames, SVG), the numbers of a VTK DataArray,
// the entries of a ParaView collection. A file that is missing or malformed fails the test.

#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <boost/test/unit_test.hpp>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace rockcontact::testing {

// A fresh (removed, not created) directory `test`/`name` under the working directory.
inline std::filesystem::path fresh_dir(const std::string& test, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::current_path() / test / name;
  std::filesystem::remove_all(dir);
  return dir;
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  BOOST_TEST_REQUIRE(in.good(), "cannot open " << file.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, separator);) parts.push_back(part);
  return parts;
}

// The rows of a CSV file after its header, which must be `header`; each row split at commas
// (the ids of the tests hold none) and required to have the header's number of columns.
inline std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& file,
                                                      const std::string& header) {
  const std::vector<std::string> lines = split(read_text(file), '\n');
  BOOST_TEST_REQUIRE(!lines.empty());
  BOOST_TEST(lines[0] == header);
  const std::size_t columns = split(header, ',').size();
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    rows.push_back(split(lines[i], ','));
    BOOST_TEST_REQUIRE(rows.back().size() == columns);
  }
  return rows;
}

// Parses an XML file (throws on malformed XML, which fails the test case).
inline boost::property_tree::ptree read_xml(const std::filesystem::path& file) {
  boost::property_tree::ptree tree;
  boost::property_tree::read_xml(file.string(), tree);
  return tree;
}

// The numbers of a VTK DataArray's text.
inline std::vector<double> numbers(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  return values;
}

// The DataArray called `name` under `parent` (Points, Polys, Cells, PointData or CellData).
inline const boost::property_tree::ptree& data_array(const boost::property_tree::ptree& parent,
                                                     const std::string& name) {
  for (const auto& [tag, child] : parent) {
    if (tag == "DataArray" && child.get<std::string>("<xmlattr>.Name", "") == name) return child;
  }
  BOOST_FAIL("no DataArray " << name);
  return parent;
}

// The (timestep, file) entries of a ParaView collection (.pvd), in order.
inline std::vector<std::pair<double, std::string>> pvd_entries(const std::filesystem::path& file) {
  const boost::property_tree::ptree tree = read_xml(file);
  BOOST_TEST(tree.get<std::string>("VTKFile.<xmlattr>.type") == "Collection");
  std::vector<std::pair<double, std::string>> entries;
  for (const auto& [tag, child] : tree.get_child("VTKFile.Collection")) {
    if (tag != "DataSet") continue;
    entries.emplace_back(child.get<double>("<xmlattr>.timestep"),
                         child.get<std::string>("<xmlattr>.file"));
  }
  return entries;
}

}  // namespace rockcontact::testing
