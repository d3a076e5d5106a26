#include "fuzz_cases.hpp"

#include <nlohmann/json.hpp>

namespace rockcontact::cli {

namespace {

using nlohmann::ordered_json;

ordered_json polygon_json(const std::vector<kernel::Point2>& vertices) {
  ordered_json out = ordered_json::array();
  for (const kernel::Point2& p : vertices) out.push_back({p.x, p.y});
  return out;
}

}  // namespace

std::optional<std::vector<robustness::Family>> parse_families(std::string_view names) {
  if (names == "all") {
    return std::vector(robustness::all_families.begin(), robustness::all_families.end());
  }
  std::vector<robustness::Family> families;
  while (true) {
    const std::size_t comma = names.find(',');
    const auto family = robustness::parse_family(names.substr(0, comma));
    if (!family) return std::nullopt;
    families.push_back(*family);
    if (comma == std::string_view::npos) return families;
    names.remove_prefix(comma + 1);
  }
}

std::string family_choices() {
  std::string names = "all";
  for (const robustness::Family family : robustness::all_families) {
    names += ", " + std::string(robustness::to_string(family));
  }
  return names;
}

std::string case_id(robustness::Family family, std::uint64_t seed, std::uint64_t index) {
  return std::string(robustness::to_string(family)) + "-s" + std::to_string(seed) + "-i" +
         std::to_string(index);
}

std::uint64_t write_fuzz_cases(std::ostream& out, const FuzzCases& cases) {
  // One pair per line keeps a file of thousands of cases readable and diffable, which dump(2)
  // (one number per line) would not.
  out << "{\"kn\": " << ordered_json(cases.kn).dump() << ", \"H\": " << ordered_json(cases.H).dump()
      << ", \"demarcation\": \"exact\",\n \"pairs\": [";
  std::uint64_t written = 0;
  for (const robustness::Family family : cases.families) {
    for (std::uint64_t i = 0; i < cases.count; ++i) {
      const robustness::PolygonPair pair = robustness::generate_pair(family, cases.seed, i);
      ordered_json item;
      item["id"] = case_id(family, cases.seed, i);
      item["cp"] = polygon_json(pair.cp);
      item["tp"] = polygon_json(pair.tp);
      out << (written == 0 ? "\n  " : ",\n  ") << item.dump();
      ++written;
    }
  }
  out << "\n ]}\n";
  return written;
}

}  // namespace rockcontact::cli
