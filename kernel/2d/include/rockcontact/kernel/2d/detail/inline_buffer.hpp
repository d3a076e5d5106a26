#pragma once
// InlineBuffer<T, N>: scratch storage for a workspace that must not allocate in the common case.
// Up to N elements live in an array inside the object; a request for more is served by a heap
// vector, grown to the largest request seen and reused after that.

#include <array>
#include <cstddef>
#include <vector>

namespace rockcontact::kernel::detail {

template <class T, std::size_t N>
class InlineBuffer {
 public:
  static constexpr std::size_t inline_capacity = N;

  // Room for `count` elements: the inline array when count <= N, else the heap vector. The
  // caller initialises what it reads; a pointer from an earlier call may be invalidated.
  T* storage(std::size_t count) {
    if (count <= N) return inline_.data();
    if (heap_.size() < count) heap_.resize(count);
    return heap_.data();
  }

 private:
  std::array<T, N> inline_{};
  std::vector<T> heap_;
};

}  // namespace rockcontact::kernel::detail
