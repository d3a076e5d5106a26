#include "rockcontact/kernel/core/detail/staged_sign.hpp"

#include <cstdio>
#include <string>

#include "rockcontact/kernel/core/policy_disagreement.hpp"

namespace rockcontact::kernel::detail {

namespace {

const char* name_of(PredicateKind kind) {
  switch (kind) {
    case PredicateKind::cross: return "cross_sign";
    case PredicateKind::crossing_side: return "crossing_side";
    case PredicateKind::crossing_point: return "crossing_point";
    case PredicateKind::triple: return "triple_sign";
    case PredicateKind::plane_side: return "plane_side";
    case PredicateKind::count: break;
  }
  return "?";
}

}  // namespace

void throw_disagreement(PredicateKind kind, std::span<const double> input, Sign staged, Sign exact) {
  std::string text = std::string("Checked policy: ") + name_of(kind) + " staged sign " +
                     std::to_string(static_cast<int>(staged)) + " but exact sign " +
                     std::to_string(static_cast<int>(exact)) + " on input [";
  char buffer[32];
  for (std::size_t i = 0; i < input.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%s%a", i == 0 ? "" : ", ", input[i]);
    text += buffer;
  }
  throw PolicyDisagreement(text + "]");
}

}  // namespace rockcontact::kernel::detail
