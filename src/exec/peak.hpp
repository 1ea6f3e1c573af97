// The device memory a call needs: measured for its Stats, and checked before it starts
// (internal; issue 23).
// Declared right after a module's executor, it resets the call's high-water mark and, when the
// call ends (returns or throws), records the call's peak use in RunStats::device_peak_bytes.
// An executor run inside another call (exec/exec_context.hpp) leaves the mark to that call,
// whose peak then includes its own: it records the peak so far. Nothing on the CPU executor.
#pragma once
#include <cstdint>
#include <string>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {

template <class Exec>
class DevicePeak {
 public:
  DevicePeak(Exec& ex, RunStats& st) : ex_(ex), st_(st) {
    if constexpr (Exec::backend == Backend::Cuda)
      if (!ex_.nested()) ex_.reset_peak();
  }
  ~DevicePeak() {
    if constexpr (Exec::backend == Backend::Cuda) {
      try {
        st_.device_peak_bytes = std::int64_t(ex_.peak_bytes());
      } catch (...) {  // (a statistic: never a reason to fail, nor to throw from a destructor)
      }
    }
  }
  DevicePeak(const DevicePeak&) = delete;
  DevicePeak& operator=(const DevicePeak&) = delete;

 private:
  Exec& ex_;
  RunStats& st_;
};

// The least device memory a problem needs, in bytes, checked before any launch on the CUDA
// executor; what names the problem in the refusal.
template <class Exec>
void require_device_bytes(Exec& ex, std::uint64_t bytes, const std::string& what) {
  if constexpr (Exec::backend == Backend::Cuda) ex.require_memory(bytes, what);
}

// The least device memory a problem of `count` elements needs, `per` bytes each (a lower bound:
// docs/performance.md has the measured peaks), checked before any launch on the CUDA executor.
template <class Exec>
void require_device_memory(Exec& ex, std::int64_t count, double per, const char* problem,
                           const char* unit) {
  if constexpr (Exec::backend == Backend::Cuda)
    ex.require_memory(std::uint64_t(double(count) * per),
                      std::string(problem) + " of " + std::to_string(count) + " " + unit);
}

}  // namespace gpugeom::detail
