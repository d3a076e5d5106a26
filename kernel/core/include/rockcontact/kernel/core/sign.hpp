#pragma once
// The answer of a predicate: a sign, never a double to compare.

namespace rockcontact::kernel {

enum class Sign : int { negative = -1, zero = 0, positive = 1 };

template <class T>
constexpr Sign sign_of(const T& value) {
  if (value > 0) return Sign::positive;
  if (value < 0) return Sign::negative;
  return Sign::zero;
}

constexpr Sign operator-(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }
constexpr Sign operator*(Sign a, Sign b) {
  return static_cast<Sign>(static_cast<int>(a) * static_cast<int>(b));
}

}  // namespace rockcontact::kernel
