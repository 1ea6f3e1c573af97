// Relaxed device-scope atomics for both executors (cuda::atomic_ref compiles for the host
// too), and the list append the GPU needs to stay fast. Shared by every module whose kernels
// vote, count or collect work lists.
#pragma once
#include <cstdint>
#include <cuda/atomic>
#ifdef __CUDACC__
#include <cooperative_groups.h>
#include <cooperative_groups/reduce.h>
#endif

#include "base/hd.hpp"

namespace gpugeom {

template <class T>
GG_INLINE T atomic_add(T* p, T v) {
  cuda::atomic_ref<T, cuda::thread_scope_device> r(*p);
  return r.fetch_add(v, cuda::memory_order_relaxed);
}
// Minimum / maximum that skip the atomic when a plain read shows it cannot win: many threads
// aim at few addresses (millions of points choosing among a handful of early simplices), and
// same-address atomics serialise.
template <class T>
GG_INLINE void atomic_min(T* p, T v) {
  cuda::atomic_ref<T, cuda::thread_scope_device> r(*p);
  if (r.load(cuda::memory_order_relaxed) > v) r.fetch_min(v, cuda::memory_order_relaxed);
}
template <class T>
GG_INLINE void atomic_max(T* p, T v) {
  cuda::atomic_ref<T, cuda::thread_scope_device> r(*p);
  if (r.load(cuda::memory_order_relaxed) < v) r.fetch_max(v, cuda::memory_order_relaxed);
}
// The same where most threads of a warp aim at one of a few addresses: converged threads with
// the same address first agree on their maximum, and one of them does the atomic (millions of
// points choosing among the first dozen facets would otherwise queue at those addresses).
template <class T>
GG_INLINE void atomic_max_grouped(T* p, T v) {
#ifdef __CUDA_ARCH__
  namespace cg = cooperative_groups;
  const cg::coalesced_group g = cg::coalesced_threads();
  const auto same = cg::labeled_partition(g, reinterpret_cast<unsigned long long>(p));
  const T m = cg::reduce(same, v, cg::greater<T>());
  if (same.thread_rank() == 0) atomic_max(p, m);
#else
  atomic_max(p, v);
#endif
}
// Sets bits: the marks many threads may set in one word (a block's border: per point, the blocks
// it goes to), the same whatever their order.
template <class T>
GG_INLINE void atomic_or(T* p, T v) {
  cuda::atomic_ref<T, cuda::thread_scope_device> r(*p);
  if ((r.load(cuda::memory_order_relaxed) & v) != v) r.fetch_or(v, cuda::memory_order_relaxed);
}
// A plain read of a word other threads may be writing (their writes atomic too).
template <class T>
GG_INLINE T atomic_load(const T* p) {
  cuda::atomic_ref<T, cuda::thread_scope_device> r(*const_cast<T*>(p));
  return r.load(cuda::memory_order_relaxed);
}
template <class T>
GG_INLINE T atomic_exchange(T* p, T v) {
  cuda::atomic_ref<T, cuda::thread_scope_device> r(*p);
  return r.exchange(v, cuda::memory_order_relaxed);
}
// A slot in a list whose length is *counter: on the GPU one atomic per group of converged
// threads (a single counter bumped by every thread of a large kernel serialises them all).
GG_INLINE std::int64_t append_slot(std::int64_t* counter) {
#ifdef __CUDA_ARCH__
  namespace cg = cooperative_groups;
  const cg::coalesced_group g = cg::coalesced_threads();
  unsigned long long base = 0;
  if (g.thread_rank() == 0)
    base = atomicAdd(reinterpret_cast<unsigned long long*>(counter), (unsigned long long)g.size());
  return std::int64_t(g.shfl(base, 0)) + g.thread_rank();
#else
  return atomic_add(counter, std::int64_t(1));
#endif
}

}  // namespace gpugeom
