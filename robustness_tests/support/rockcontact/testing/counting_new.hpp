#pragma once
// Counts heap allocations: replaces the global operator new and delete with ones that count
// every allocation in rockcontact::testing::heap_allocations. Include it in exactly one
// translation unit of a test executable (replacement functions cannot be inline); read the
// counter before and after the code under test. libstdc++'s array and nothrow forms call these
// two.

#include <atomic>
#include <cstdlib>
#include <new>

namespace rockcontact::testing {
inline std::atomic<long> heap_allocations{0};
}  // namespace rockcontact::testing

// GCC cannot see that these replacements pair malloc with free on purpose.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  rockcontact::testing::heap_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
