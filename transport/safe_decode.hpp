#pragma once
/// @file
/// Decoding a datagram without trusting it. lcm-gen's decoders size every
/// array from the length fields in the data *before* checking that the data
/// holds that many elements, so a 100-byte datagram claiming 400 000 joints
/// and 6 000 chain stages makes them allocate 10 GB (found by
/// fuzz/message_fuzzer.cpp). safeDecode gives each decode an allocation
/// budget proportional to the datagram: an honest message needs about as
/// many bytes as it carries; one that asks for more is undecodable.

#include <cstddef>
#include <exception>

namespace lagrange::transport {

/// While alive, operator new on this thread fails (std::bad_alloc) once the
/// allocations made under it exceed `bytes` in total.
class AllocationBudget {
 public:
  explicit AllocationBudget(std::size_t bytes);
  ~AllocationBudget();
  AllocationBudget(const AllocationBudget&) = delete;
  AllocationBudget& operator=(const AllocationBudget&) = delete;

 private:
  long long previous_;
};

/// Bytes of allocation a datagram of `size` bytes may cause when decoded.
inline std::size_t decodeBudget(std::size_t size) { return 64 * size + 4096; }

/// Decodes exactly `size` bytes as Msg; false -- never a throw, never an
/// allocation out of proportion -- if they are not one whole Msg.
template <class Msg>
bool safeDecode(const void* data, std::size_t size, Msg& out) {
  try {
    const AllocationBudget budget(decodeBudget(size));
    return out.decode(data, 0, static_cast<int>(size)) == static_cast<int>(size);
  } catch (const std::exception&) {  // std::bad_alloc over budget; length_error for a negative count
    return false;
  }
}

}  // namespace lagrange::transport
