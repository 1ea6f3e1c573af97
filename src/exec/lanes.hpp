// Lanes: the threads that run one work item together (Exec::for_each_lanes). On the GPU they are
// a warp, for items whose work is a long loop one thread would run alone while the rest of the
// launch has finished (a star of thousands of triangles among stars of thirty); on the CPU
// executor an item is one thread's, so its Lanes are a single lane. Code written against Lanes
// runs both ways and gives the same result: every collective below is called by all lanes of
// the group together, with the same trip counts (loops stride by size over a shared bound).
#pragma once
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom {

// One lane (the CPU executor's, and a thread's own work item on the GPU).
struct SoloLanes {
  static constexpr int rank = 0, size = 1;
  GG_INLINE void sync() const {}
  GG_INLINE std::uint32_t ballot(bool b) const { return b ? 1u : 0u; }
  GG_INLINE bool any(bool b) const { return b; }
  // Set lanes of mask below this one, and in all.
  GG_INLINE int below(std::uint32_t) const { return 0; }
  GG_INLINE static int count(std::uint32_t mask) { return int(mask & 1u); }
  // The sum of the v of lower lanes; *total the sum of all.
  GG_INLINE int exclusive_scan(int v, int* total) const {
    *total = v;
    return 0;
  }
  // Lane 0's v, to every lane.
  template <class T>
  GG_INLINE T broadcast(T v) const {
    return v;
  }
};

}  // namespace gpugeom
