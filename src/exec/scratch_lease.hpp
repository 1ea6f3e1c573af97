// Exact scratch on demand: a pool of scratch slots that threads borrow for one exact predicate.
//
// The split passes (scratch_slots.hpp, split_pass.hpp) run the exact stage as a pass of its own
// over the items the filter left open. Some decisions cannot be cut out that way without
// splitting a walk in the middle: delaunay3d's point relocation follows a chain of flips, each
// step an orientation test that may need the exact stage, and its flip classification needs
// several tests in a row. There a thread that finds the filter undecided borrows a slot from
// a pool: it takes the first free slot from a position spread by its hint (compare-and-swap on
// the slot's flag), runs the predicate, and gives the slot back. A holder never waits for
// anything while it holds a slot, so every waiting thread gets one eventually (on the GPU the
// independent thread scheduling of sm_70+ lets lanes of one warp spin while another lane
// holds a slot). The pool is sized so that waiting is rare: the filter decides almost every
// test on inputs in general position, and on degenerate inputs the integer and translated
// tiers answer in a few hundred nanoseconds.
#pragma once
#include <cstdint>
#include <cuda/atomic>

#include "base/hd.hpp"

namespace gpugeom {

struct ScratchLease {
  double* base = nullptr;
  std::int32_t* busy = nullptr;  // one flag per slot, 0 free
  std::int32_t slots = 0;
  std::int64_t doubles = 0;  // per slot

  GG_HD double* acquire(std::uint32_t hint) const {
    std::int32_t i = std::int32_t(hint % std::uint32_t(slots));
    for (;;) {
      cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> f(busy[i]);
      std::int32_t expect = 0;
      if (f.load(cuda::memory_order_relaxed) == 0 &&
          f.compare_exchange_strong(expect, 1, cuda::memory_order_acquire))
        return base + std::int64_t(i) * doubles;
      i = i + 1 == slots ? 0 : i + 1;
    }
  }
  GG_HD void release(const double* s) const {
    const std::int64_t i = (s - base) / doubles;
    cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> f(busy[i]);
    f.store(0, cuda::memory_order_release);
  }
};

// The pool's memory on an executor.
template <class Exec>
struct LeasePool {
  typename Exec::template Buffer<double> scratch;
  typename Exec::template Buffer<std::int32_t> busy;
  ScratchLease view;
  LeasePool() = default;
  LeasePool(Exec& ex, std::int64_t slots, std::int64_t doubles) {
    scratch = ex.template alloc<double>(std::size_t(slots * doubles));
    busy = ex.template alloc<std::int32_t>(std::size_t(slots));
    ex.fill(busy.data(), slots, std::int32_t(0));
    view = ScratchLease{scratch.data(), busy.data(), std::int32_t(slots), doubles};
  }
};

}  // namespace gpugeom
