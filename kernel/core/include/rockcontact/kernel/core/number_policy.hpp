#pragma once
// Number policies: the same algorithm code runs under each (a template parameter).
//
//   Float     plain double everywhere: what most DEM codes do. Predicates may answer wrongly
//             on near-degenerate input; kept as the baseline and for differential testing.
//   Filtered  predicates in double with a proven error bound, re-evaluated exactly (GMP
//             rationals) only when the sign is uncertain; constructions in double whose
//             combinatorics follow the exact predicates, crossing points certified to 2^-40 of
//             their edge or else rounded from the exact crossing (crossing_point.hpp). The
//             default.
//   Exact     predicates and constructions in GMP rationals (square roots of edge lengths,
//             needed only by the potential, at 256 bits); results rounded to double once, at
//             the end. The reference.

#include <concepts>
#include <optional>
#include <string_view>

namespace rockcontact::kernel {

enum class PolicyKind { float_, filtered, exact };

struct Float {
  static constexpr PolicyKind kind = PolicyKind::float_;
  static constexpr std::string_view name = "float";
};
struct Filtered {
  static constexpr PolicyKind kind = PolicyKind::filtered;
  static constexpr std::string_view name = "filtered";
};
struct Exact {
  static constexpr PolicyKind kind = PolicyKind::exact;
  static constexpr std::string_view name = "exact";
};

template <class P>
concept NumberPolicy = std::same_as<P, Float> || std::same_as<P, Filtered> || std::same_as<P, Exact>;

constexpr std::string_view to_string(PolicyKind kind) {
  switch (kind) {
    case PolicyKind::float_: return Float::name;
    case PolicyKind::filtered: return Filtered::name;
    case PolicyKind::exact: return Exact::name;
  }
  return "?";
}

constexpr std::optional<PolicyKind> parse_policy(std::string_view text) {
  if (text == Float::name) return PolicyKind::float_;
  if (text == Filtered::name) return PolicyKind::filtered;
  if (text == Exact::name) return PolicyKind::exact;
  return std::nullopt;
}

// Calls f(Policy{}) with the policy named at run time; one switch for every dispatching caller.
template <class F>
decltype(auto) with_policy(PolicyKind kind, F&& f) {
  switch (kind) {
    case PolicyKind::float_: return f(Float{});
    case PolicyKind::exact: return f(Exact{});
    case PolicyKind::filtered: break;
  }
  return f(Filtered{});
}

}  // namespace rockcontact::kernel
