#include "transport/safe_decode.hpp"

#include <cstdlib>
#include <new>

namespace {
// Bytes the current decode may still allocate; negative: no budget (the
// normal case, outside safeDecode).
thread_local long long t_remaining = -1;

void* allocate(std::size_t n) {
  if (t_remaining >= 0) {
    if (static_cast<long long>(n) > t_remaining) throw std::bad_alloc();
    t_remaining -= static_cast<long long>(n);
  }
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
}  // namespace

namespace lagrange::transport {
AllocationBudget::AllocationBudget(std::size_t bytes) : previous_(t_remaining) {
  t_remaining = static_cast<long long>(bytes);
}
AllocationBudget::~AllocationBudget() { t_remaining = previous_; }
}  // namespace lagrange::transport

// The program's operator new and delete: malloc and free, with the budget.
// (Replacing them is standard C++; this object is linked into every process
// because safeDecode needs AllocationBudget from it.)
void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
