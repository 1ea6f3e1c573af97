// The flip history between two point relocations (thesis 5.3.4), for any mesh module that keeps
// points not yet inserted in the simplices that hold them.
//
// Each flip of an epoch writes one record: the slots it rewrote (Sides of them), a payload the
// module uses to decide which of them holds a point (delaunay2d: the new diagonal's two
// vertices), and per side the next record that rewrote that slot. Per slot, FlipHist keeps the
// slot's first record of the epoch and its latest (as record << kSideBits | side, so that the
// next flip of the slot chains onto it with no read of the record). A point then follows its
// slot from the first record on, choosing a side at each.
//
// Records are numbered on from one epoch to the next, from `base`: per-slot entries below base
// are stale, so they need no clearing between epochs; the log array holds the epoch's records
// from base. Near the top of the number range the caller clears the entries and starts at 0.
#pragma once
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom::mesh {

struct alignas(8) FlipHist {
  std::int32_t first, last;
};

template <int Sides, int Payload>
struct FlipLog {
  static constexpr int kSideBits = Sides <= 2 ? 1 : Sides <= 4 ? 2 : 3;
  static constexpr int kStride = 2 * Sides + Payload;  // slots, payload, next per side
  static constexpr int kNext = Sides + Payload;
  static constexpr std::int32_t kNone = -1;

  std::int32_t* rec;  // the epoch's records from base, kStride each
  FlipHist* hist;     // per slot
  std::int32_t base;

  GG_HD std::int32_t* record(std::int32_t r) const {
    return rec + std::int64_t(kStride) * std::int64_t(r - base);
  }
  // The slots' entries, read before the flip's stores (so that the loads are in flight together).
  GG_HD void load(const std::int32_t (&slots)[Sides], FlipHist (&h)[Sides]) const {
    for (int s = 0; s < Sides; ++s) h[s] = hist[slots[s]];
  }
  // Record r of a flip that rewrote `slots` (entries h from load), chained onto each slot's
  // latest record of the epoch.
  GG_HD void append(std::int32_t r, const std::int32_t (&slots)[Sides],
                    const std::int32_t (&payload)[Payload], FlipHist (&h)[Sides]) const {
    std::int32_t* x = record(r);
    for (int s = 0; s < Sides; ++s) x[s] = slots[s], x[kNext + s] = kNone;
    for (int p = 0; p < Payload; ++p) x[Sides + p] = payload[p];
    constexpr std::int32_t mask = (1 << kSideBits) - 1;
    for (int s = 0; s < Sides; ++s) {
      if ((h[s].last >> kSideBits) >= base)
        record(h[s].last >> kSideBits)[kNext + (h[s].last & mask)] = r;
      else
        h[s].first = r;
      h[s].last = (r << kSideBits) + s;
      hist[slots[s]] = h[s];
    }
  }
  // Where a point is after the epoch's flips, starting from slot L: side(payload) picks the
  // side that holds it at each record.
  template <class Side>
  GG_HD std::int32_t follow(std::int32_t L, const Side& side) const {
    for (std::int32_t r = hist[L].first; r >= base;) {
      const std::int32_t* x = record(r);
      const int s = side(x + Sides);
      L = x[s];
      r = x[kNext + s];
    }
    return L;
  }
  // Host side, after a relocation that consumed `logged` records: the next epoch's numbering.
  // Returns true when the numbers would come near the top of their range within `cap` more
  // records: the caller then clears every slot's entry to {-1, -1} (base is 0 again).
  bool next_epoch(std::int64_t logged, std::int64_t cap) {
    if (std::int64_t(base) + logged + 2 * cap >= std::int64_t(INT32_MAX >> kSideBits)) {
      base = 0;
      return true;
    }
    base += std::int32_t(logged);
    return false;
  }
};

}  // namespace gpugeom::mesh
