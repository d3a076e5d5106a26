#include "rockcontact/dynamics/apps/pairs_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>

namespace rockcontact::dynamics {

namespace {

using nlohmann::ordered_json;

// %.6g of a number; nlohmann keeps a non-finite double as a number in memory.
std::string number(const ordered_json& value) {
  if (!value.is_number()) return value.dump();
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value.get<double>());
  return text;
}

std::string vector_text(const ordered_json& xy) {
  if (!xy.is_array() || xy.size() != 2) return "-";
  return "(" + number(xy[0]) + ", " + number(xy[1]) + ")";
}

std::string magnitude(const ordered_json& xy) {
  if (!xy.is_array() || xy.size() != 2 || !xy[0].is_number() || !xy[1].is_number()) return "-";
  return number(std::hypot(xy[0].get<double>(), xy[1].get<double>()));
}

std::string padded(std::string text, std::size_t width) {
  if (text.size() < width) text.append(width - text.size(), ' ');
  return text;
}

// The width of the id column: the longest id and two spaces.
std::size_t id_column_width(const ordered_json& results) {
  std::size_t width = 2;
  for (const auto& r : results) width = std::max(width, r.at("id").get_ref<const std::string&>().size());
  return width + 2;
}

void write_table(std::ostream& out, const ordered_json& results) {
  const std::size_t id_width = id_column_width(results);
  out << padded("id", id_width) << padded("status", 10) << padded("area [m^2]", 14)
      << padded("|force| [N/m]", 15) << padded("force [N/m]", 28) << padded("point [m]", 28)
      << "fallbacks\n";
  for (const auto& r : results) {
    const std::string& status = r.at("status").get_ref<const std::string&>();
    out << padded(r.at("id").get<std::string>(), id_width) << padded(status, 10);
    if (status == "error") {
      out << r.at("error").get<std::string>() << '\n';
      continue;
    }
    out << padded(number(r.at("area")), 14) << padded(magnitude(r.at("force")), 15)
        << padded(vector_text(r.at("force")), 28) << padded(vector_text(r.at("point")), 28)
        << r.at("fallbacks").get<std::uint64_t>() << '\n';
  }
}

// 3D: volume, distance or penetration depth, contact-set dimension, constraints and the
// largest penalty force among them.
void write_table3(std::ostream& out, const ordered_json& results) {
  const std::size_t id_width = id_column_width(results);
  out << padded("id", id_width) << padded("status", 10) << padded("volume [m^3]", 14)
      << padded("distance [m]", 14) << padded("depth [m]", 14) << padded("set", 5)
      << padded("constraints", 13) << padded("max |force| [N]", 17) << "fallbacks\n";
  for (const auto& r : results) {
    const std::string& status = r.at("status").get_ref<const std::string&>();
    out << padded(r.at("id").get<std::string>(), id_width) << padded(status, 10);
    if (status == "error") {
      out << r.at("error").get<std::string>() << '\n';
      continue;
    }
    const ordered_json& penetration = r.at("penetration");
    const ordered_json& set = r.at("contact_set");
    double largest = 0.0;
    for (const auto& c : r.at("constraints")) {
      const auto& f = c.at("force");
      largest = std::max(largest, std::hypot(f[0].get<double>(), f[1].get<double>(), f[2].get<double>()));
    }
    out << padded(number(r.at("volume")), 14)
        << padded(r.at("distance").is_null() ? "-" : number(r.at("distance")), 14)
        << padded(penetration.is_null() ? "-" : number(penetration.at("depth")), 14)
        << padded(set.is_null() ? "-" : std::to_string(set.at("dimension").get<int>()) + "D", 5)
        << padded(std::to_string(r.at("constraints").size()), 13) << padded(number(largest), 17)
        << r.at("fallbacks").get<std::uint64_t>() << '\n';
  }
}

void write_totals(std::ostream& out, const ordered_json& results, const ordered_json& stats) {
  std::map<std::string, std::size_t> by_status;
  for (const auto& r : results) ++by_status[r.at("status").get<std::string>()];
  const auto pairs = stats.at("pairs").get<std::uint64_t>();
  const auto predicates = stats.at("predicates").get<std::uint64_t>();
  const auto fallbacks = stats.at("fallbacks").get<std::uint64_t>();
  const double seconds = stats.at("seconds").get<double>();

  out << "pairs: " << pairs << " (";
  const char* separator = "";
  for (const char* status : {"overlap", "touch", "separate", "error"}) {
    out << separator << status << ' ' << by_status[status];
    separator = ", ";
  }
  char rate[32] = "-";
  if (predicates > 0) {
    std::snprintf(rate, sizeof rate, "%.3g %%",
                  100.0 * static_cast<double>(fallbacks) / static_cast<double>(predicates));
  }
  out << ")\npredicates: " << predicates << ", exact fallbacks: " << fallbacks << " (" << rate
      << " of predicates)\n";
  char time[96];
  if (pairs > 0) {
    std::snprintf(time, sizeof time, "time: %.3g s, %.0f ns per pair", seconds,
                  1e9 * seconds / static_cast<double>(pairs));
  } else {
    std::snprintf(time, sizeof time, "time: %.3g s", seconds);
  }
  out << time << '\n';
}

}  // namespace

void write_pairs_summary(std::ostream& out, const ordered_json& document) {
  out << "policy " << document.at("policy").get<std::string>();
  if (document.contains("demarcation")) {
    out << ", demarcation " << document.at("demarcation").get<std::string>() << "\n\n";
    write_table(out, document.at("results"));
  } else {
    out << ", 3D\n\n";
    write_table3(out, document.at("results"));
  }
  out << '\n';
  write_totals(out, document.at("results"), document.at("stats"));
}

}  // namespace rockcontact::dynamics
