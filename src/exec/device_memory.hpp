// One call's device memory (CUDA builds only): the resource the caller chose (RunOptions::memory)
// or the library's pool, and what the call holds from it. Every DeviceBuffer of the call, and
// every device result it hands over, keeps this alive by a shared pointer, so the resource
// outlives whatever was taken from it; the counts give the call's own peak (Stats'
// device_peak_bytes), which a shared pool's high-water mark cannot (other calls use it too).
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <cuda_runtime.h>

#include "gpugeom/common.hpp"
#include "gpugeom/memory.hpp"

namespace gpugeom::detail {

class CallMemory {
 public:
  // Every block is aligned for any element type and for CUB's temporaries.
  static constexpr std::size_t kAlignment = 256;

  CallMemory(std::shared_ptr<DeviceMemoryResource> r, int device)
      : r_(r ? std::move(r) : library_memory_resource()), device_(device) {}

  // Stream-ordered; throws Error(OutOfMemory) whatever the resource threw.
  void* allocate(std::size_t bytes, cudaStream_t s) {
    void* p = nullptr;
    try {
      p = r_->allocate(bytes, kAlignment, s);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      refused(bytes, e.what());
    } catch (...) {
      refused(bytes, "an unknown exception");
    }
    if (!p) refused(bytes, "a null pointer");
    const std::int64_t now = live_.fetch_add(std::int64_t(bytes)) + std::int64_t(bytes);
    std::int64_t high = high_.load(std::memory_order_relaxed);
    while (now > high && !high_.compare_exchange_weak(high, now)) {
    }
    return p;
  }
  void deallocate(void* p, std::size_t bytes, cudaStream_t s) noexcept {
    r_->deallocate(p, bytes, kAlignment, s);
    live_.fetch_sub(std::int64_t(bytes));
  }

  DeviceMemoryResource& resource() const { return *r_; }
  bool is_library_pool() const { return r_ == library_memory_resource(); }
  int device() const { return device_; }
  // The most this call held at once since the last reset_peak (its device results included).
  std::int64_t peak() const { return high_.load(); }
  void reset_peak() { high_.store(live_.load()); }

 private:
  [[noreturn]] static void refused(std::size_t bytes, const std::string& why) {
    throw Error(ErrorCode::OutOfMemory,
                "the device memory resource given in RunOptions::memory refused " +
                    std::to_string(bytes) + " bytes (" + why +
                    "): the problem does not fit in what it can hand out: use a smaller input, "
                    "free memory the program holds, or the CPU backend (--backend cpu)");
  }
  std::shared_ptr<DeviceMemoryResource> r_;
  int device_;
  std::atomic<std::int64_t> live_{0}, high_{0};
};

}  // namespace gpugeom::detail
