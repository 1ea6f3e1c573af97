// The output step of every mesh module: the live simplices renumbered in slot order, each with
// its K vertices (as the caller names them, e.g. input indices) and its K neighbours among the
// live ones (-1 across a face whose neighbour is not live: delaunay2d's infinite triangles).
//
// Slots are never reused inside a computation, so the store holds dead slots (hull3d's removed
// facets) and slots outside the output (delaunay2d's triangles at the infinity point); a scan
// over liveness gives each live slot its rank, and the rank steps where a slot is live, so a
// neighbour's liveness needs no second test.
#pragma once
#include <cstddef>
#include <cstdint>

#include "base/hd.hpp"
#include "mesh/adjacency.hpp"

namespace gpugeom::mesh {

// One simplex as the store hands it to the output: vertices and neighbour slots (decoded by
// the store, which knows its encoding's reading: adjacency.hpp).
template <int K>
struct SimplexRecord {
  std::int32_t v[K];
  std::int32_t n[K];
};

template <class Exec>
struct Compacted {
  typename Exec::template Buffer<std::int32_t> simplices, neighbors;  // K per simplex
  std::int64_t count = 0;
};

namespace compact_detail {
template <class Store>
struct Liveness {
  Store s;
  std::int64_t used;
  GG_HD std::int32_t operator()(std::int64_t t) const { return t < used && s.live(t) ? 1 : 0; }
};
template <int K, class Store>
struct Emit {
  Store s;
  const std::int32_t* rank;  // used + 1 entries
  std::int32_t* simplices;
  std::int32_t* neighbors;
  GG_HD void operator()(std::int64_t t) const {
    const std::int64_t r = rank[t];
    if (rank[t + 1] == r) return;  // not live
    const SimplexRecord<K> x = s.get(t);
    for (int k = 0; k < K; ++k) {
      simplices[K * r + k] = x.v[k];
      const std::int32_t nb = x.n[k];  // (-1: none)
      const std::int32_t rn = nb >= 0 ? rank[nb] : -1;
      neighbors[K * r + k] = nb >= 0 && rank[nb + 1] != rn ? rn : -1;
    }
  }
};
}  // namespace compact_detail

// Store: GG_HD bool live(t); GG_HD SimplexRecord<K> get(t) (output vertex names, neighbour
// slots, -1 for none). used: the slots handed out. [synchronises] (reads the count)
template <int K, class Exec, class Store>
Compacted<Exec> compact_live(Exec& ex, std::int64_t used, const Store& store) {
  auto rank = ex.template alloc<std::int32_t>(std::size_t(used) + 1);
  std::int32_t* rk = rank.data();
  ex.exclusive_scan_of(used + 1, compact_detail::Liveness<Store>{store, used}, rk);
  Compacted<Exec> c;
  std::int32_t count = 0;
  ex.to_host(rk + used, 1, &count);
  c.count = count;
  c.simplices = ex.template alloc<std::int32_t>(std::size_t(K) * std::size_t(count));
  c.neighbors = ex.template alloc<std::int32_t>(std::size_t(K) * std::size_t(count));
  ex.for_each_index(
      used, compact_detail::Emit<K, Store>{store, rk, c.simplices.data(), c.neighbors.data()});
  return c;
}

}  // namespace gpugeom::mesh
