// naive_clipper: the contact kernel people write first, as an example of a kernel to check with
// `rockcontact pairs --compare` (README.md beside this file).
//
//   naive_clipper IN.json OUT.json      (OUT.json "-": stdout)
//
// Reads a `pairs` input document (only "pairs" [{id, cp, tp}] is used) and writes the `pairs`
// output schema with the fields it computes: {"results": [{"id", "status", "ip", "area"}],
// "stats": {"pairs", "seconds"}}; no force, no contact point.
//
// Everything is plain double with no tolerance:
//   * IP: Sutherland-Hodgman, tp clipped by the closed half-plane left of each edge of cp
//     (cross product >= 0 is inside), an edge crossing cut at the parameter s_p / (s_p - s_q)
//     of the two side values;
//   * area: the shoelace formula on the clipped polygon;
//   * status: "overlap" when the clipped polygon has at least 3 vertices and a positive area;
//     otherwise "touch" when anything is left of it (points on cp's boundary survive the closed
//     test: a shared vertex, an edge lying on an edge) and "separate" when nothing is.
// The polygons are taken as given (cp is assumed counter-clockwise and convex, not checked).

#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "naive_clip.hpp"

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

struct Point {
  double x;
  double y;
};
using Polygon = std::vector<Point>;

double shoelace_area(const Polygon& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point& p = polygon[i];
    const Point& q = polygon[(i + 1) % polygon.size()];
    twice += p.x * q.y - q.x * p.y;
  }
  return 0.5 * twice;
}

Polygon read_polygon(const json& value) {
  Polygon polygon;
  for (const json& v : value) polygon.push_back({v.at(0).get<double>(), v.at(1).get<double>()});
  return polygon;
}

ordered_json pair_result(const json& pair) {
  const Polygon cp = read_polygon(pair.at("cp")), tp = read_polygon(pair.at("tp"));
  Polygon clipped, scratch;
  naive::clip_polygon<Point>(cp, tp, clipped, scratch);
  const double area = shoelace_area(clipped);
  const bool overlap = clipped.size() >= 3 && area > 0.0;
  ordered_json ip = ordered_json::array();
  if (overlap) {
    for (const Point& p : clipped) ip.push_back({p.x, p.y});
  }
  ordered_json result;
  result["id"] = pair.at("id");
  result["status"] = overlap ? "overlap" : clipped.empty() ? "separate" : "touch";
  result["ip"] = std::move(ip);
  result["area"] = overlap ? area : 0.0;
  return result;
}

// The output document, one result per line.
std::string run(const json& input) {
  const auto start = std::chrono::steady_clock::now();
  std::string results;
  for (const json& pair : input.at("pairs")) {
    results += (results.empty() ? "\n  " : ",\n  ") + pair_result(pair).dump();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const ordered_json stats = {{"pairs", input.at("pairs").size()}, {"seconds", seconds}};
  return "{\"results\": [" + results + "\n ],\n \"stats\": " + stats.dump() + "}\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: naive_clipper IN.json OUT.json   (OUT.json '-' for stdout)\n";
    return 2;
  }
  const std::string in_name = argv[1], out_name = argv[2];
  try {
    std::ifstream in(in_name);
    if (!in) throw std::runtime_error("cannot open " + in_name);
    const std::string text = run(json::parse(in));
    if (out_name == "-") {
      std::cout << text;
      return 0;
    }
    std::ofstream out(out_name);
    if (!(out << text)) throw std::runtime_error("cannot write " + out_name);
    out.close();
    if (!out) throw std::runtime_error("cannot write " + out_name);
  } catch (const std::exception& e) {
    std::cerr << "naive_clipper: " << in_name << ": " << e.what() << '\n';
    return 2;
  }
  return 0;
}
