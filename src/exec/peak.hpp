// The device memory a call needed, for its Stats (internal; issue 23's memory per element).
// Declared right after a module's executor, it resets the device pool's high-water mark and,
// when the call ends (returns or throws), records the pool's peak use in the counter
// "device_peak_bytes". Nothing on the CPU executor.
#pragma once
#include <cstdint>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {

template <class Exec>
class DevicePeak {
 public:
  DevicePeak(Exec& ex, Stats& st) : ex_(ex), st_(st) {
    if constexpr (Exec::backend == Backend::Cuda) ex_.reset_peak();
  }
  ~DevicePeak() {
    if constexpr (Exec::backend == Backend::Cuda) {
      try {
        st_.counters["device_peak_bytes"] = ex_.peak_bytes();
      } catch (...) {  // (a statistic: never a reason to fail, nor to throw from a destructor)
      }
    }
  }
  DevicePeak(const DevicePeak&) = delete;
  DevicePeak& operator=(const DevicePeak&) = delete;

 private:
  Exec& ex_;
  Stats& st_;
};

}  // namespace gpugeom::detail
