#pragma once
// PolicyDisagreement: what the Checked policy throws when a predicate's staged sign (the one
// Filtered and Exact use) differs from its sign evaluated exactly on its own. what() names the
// predicate, both signs and the full input as hexadecimal floats, so the case reproduces
// bit for bit. A disagreement is a bug in a filter's bound, never an input error.

#include <stdexcept>

namespace rockcontact::kernel {

class PolicyDisagreement : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

}  // namespace rockcontact::kernel
