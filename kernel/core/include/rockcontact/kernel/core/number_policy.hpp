#pragma once
// Number policies: the same algorithm code runs under each (a template parameter).
//
//   Float     plain double everywhere: what most DEM codes do. Predicates may answer wrongly
//             on near-degenerate input; kept as the baseline and for differential testing.
//   Filtered  predicates staged: double with a proven error bound, then interval arithmetic,
//             then exact (kernel/core/detail/staged_sign.hpp), so every sign is exact;
//             constructions in double whose combinatorics follow the exact predicates,
//             crossing points certified to 2^-40 of their edge or else rounded from the exact
//             crossing (crossing_point.hpp). The default.
//   Exact     the same exact predicates; constructions in exact rationals (CGAL's
//             Exact_rational; square roots of edge lengths, needed only by the potential, in
//             MPFR at 256 bits); results rounded to double once, at the end. The reference.
//   Checked   Filtered, with every predicate also evaluated exactly on its own and compared:
//             the first disagreement throws PolicyDisagreement with the predicate's full
//             input (CGAL's Kernel_checker idea). For fuzzing and differential runs.

#include <concepts>
#include <optional>
#include <string_view>

namespace rockcontact::kernel {

enum class PolicyKind { float_, filtered, exact, checked };

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
struct Checked {
  static constexpr PolicyKind kind = PolicyKind::checked;
  static constexpr std::string_view name = "checked";
};

template <class P>
concept NumberPolicy = std::same_as<P, Float> || std::same_as<P, Filtered> || std::same_as<P, Exact> ||
                       std::same_as<P, Checked>;

constexpr std::string_view to_string(PolicyKind kind) {
  switch (kind) {
    case PolicyKind::float_: return Float::name;
    case PolicyKind::filtered: return Filtered::name;
    case PolicyKind::exact: return Exact::name;
    case PolicyKind::checked: return Checked::name;
  }
  return "?";
}

constexpr std::optional<PolicyKind> parse_policy(std::string_view text) {
  if (text == Float::name) return PolicyKind::float_;
  if (text == Filtered::name) return PolicyKind::filtered;
  if (text == Exact::name) return PolicyKind::exact;
  if (text == Checked::name) return PolicyKind::checked;
  return std::nullopt;
}

// Expands M(P) for every number policy P: the kernels' explicit instantiations list the
// policies here, once.
#define ROCKCONTACT_FOR_EACH_POLICY(M) M(Float) M(Filtered) M(Exact) M(Checked)

// Calls f(Policy{}) with the policy named at run time; one switch for every dispatching caller.
template <class F>
decltype(auto) with_policy(PolicyKind kind, F&& f) {
  switch (kind) {
    case PolicyKind::float_: return f(Float{});
    case PolicyKind::exact: return f(Exact{});
    case PolicyKind::checked: return f(Checked{});
    case PolicyKind::filtered: break;
  }
  return f(Filtered{});
}

}  // namespace rockcontact::kernel
