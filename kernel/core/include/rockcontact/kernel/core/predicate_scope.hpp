#pragma once
// PredicateScope: one rounding-mode scope for a batch of predicates, such as a pair's verdict
// and clip.
//
// The interval stage of a staged predicate (detail/staged_sign.hpp) needs the FPU to round
// upward. Outside any scope, each interval evaluation switches the rounding mode and restores
// it. Inside a PredicateScope the first interval evaluation switches it and leaves it so; the
// outermost scope restores it when it ends (also on an exception). A pair whose predicates fall
// back several times (an exact touch along a whole edge) then pays one switch, and a pair that
// never falls back pays none.
//
// Contract: between a scope's start and end, code evaluates predicates only. After the switch
// double arithmetic rounds upward; the double filters' error bounds hold under any rounding
// mode (they are derived for eps = 2^-52, the relative error of one operation under directed
// rounding), but a construction in double would not round to nearest. Scopes nest.

namespace rockcontact::kernel {

namespace detail {
struct PredicateScopeState {
  int depth = 0;          // open scopes on this thread
  bool switched = false;  // an interval stage inside them switched to upward rounding
};
inline thread_local PredicateScopeState predicate_scope_state;

// Restores the rounding mode saved by the interval stage that switched it (core/src).
void restore_rounding_mode() noexcept;
}  // namespace detail

class PredicateScope {
 public:
  PredicateScope() noexcept { ++detail::predicate_scope_state.depth; }
  ~PredicateScope() {
    detail::PredicateScopeState& state = detail::predicate_scope_state;
    if (--state.depth == 0 && state.switched) {
      state.switched = false;
      detail::restore_rounding_mode();
    }
  }
  PredicateScope(const PredicateScope&) = delete;
  PredicateScope& operator=(const PredicateScope&) = delete;
};

}  // namespace rockcontact::kernel
