// Host wall-clock helpers for the per-phase timings in the Stats structs.
#pragma once
#include <chrono>

namespace gpugeom {

using Clock = std::chrono::steady_clock;

inline double ms_between(Clock::time_point t0, Clock::time_point t1) {
  return std::chrono::duration<double, std::milli>(t1 - t0).count();
}
inline double ms_since(Clock::time_point t0) {
  return ms_between(t0, Clock::now());
}
// Milliseconds on the steady clock's own scale, for instants compared across calls.
inline double now_ms() {
  return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
}

}  // namespace gpugeom
