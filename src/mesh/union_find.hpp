// Connected components by lock-free union-find (internal; host and device code): every thread
// may unite any two elements at once. Roots only ever move to a smaller index (a root hooks
// under the other only by a compare-and-swap on itself), so the structure stays a forest and
// each component ends with its smallest element as root, whatever the order of the unions.
#pragma once
#include <cstdint>
#include <cuda/atomic>

#include "base/hd.hpp"

namespace gpugeom::mesh {

GG_INLINE std::int32_t uf_find(std::int32_t* parent, std::int32_t x) {
  for (;;) {
    cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> px(parent[x]);
    const std::int32_t p = px.load(cuda::memory_order_relaxed);
    if (p == x) return x;
    cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> pp(parent[p]);
    const std::int32_t g = pp.load(cuda::memory_order_relaxed);
    if (g != p) {  // path halving (either outcome of the swap is a valid forest)
      std::int32_t expect = p;
      px.compare_exchange_strong(expect, g, cuda::memory_order_relaxed);
    }
    x = p;
  }
}

GG_INLINE void uf_unite(std::int32_t* parent, std::int32_t a, std::int32_t b) {
  for (;;) {
    a = uf_find(parent, a), b = uf_find(parent, b);
    if (a == b) return;
    if (a < b) {
      const std::int32_t t = a;
      a = b, b = t;
    }
    cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> pa(parent[a]);
    std::int32_t expect = a;  // a still a root: hook it under the smaller root b
    if (pa.compare_exchange_strong(expect, b, cuda::memory_order_relaxed)) return;
  }
}

}  // namespace gpugeom::mesh
