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

// The same in one order that depends on the triangles alone (K = 3). The store names each
// triangle's vertices for the order too (order_names(t, w): delaunay2d's curve positions, so
// that the order follows the curve, as the slots of either executor roughly do, and the output
// is read and written nearly in sequence): each triangle is turned so that its vertex first in
// that order comes first (its orientation kept), and the triangles are sorted by their first
// two vertices. A directed edge lies in one triangle, so the order is total. Two schedules that
// build the same triangulation (the executors', a kept one's updates and a fresh call) then
// give the same arrays, whatever slots their histories left. It costs a sort of the live
// triangles' keys (docs/performance.md: the canonical order). names_below: every order name is
// smaller (sizes the keys: fewer radix passes).
namespace compact_detail {
GG_HD inline int smallest_first(const std::int32_t* v) {
  return v[0] < v[1] ? (v[0] < v[2] ? 0 : 2) : (v[1] < v[2] ? 1 : 2);
}
template <class Store>
struct SortKey {
  Store s;
  const std::int32_t* slot;  // the live slots
  std::uint64_t* keys;
  int shift;
  GG_HD void operator()(std::int64_t i) const {
    std::int32_t w[3];
    s.order_names(slot[i], w);
    const int r = smallest_first(w);
    keys[i] = (std::uint64_t(std::uint32_t(w[r])) << shift) |
              std::uint64_t(std::uint32_t(w[(r + 1) % 3]));
  }
};
struct PlaceOf {
  const std::int32_t* slot;  // in output order
  std::int32_t* place;       // per slot: its position, -1 where not live
  GG_HD void operator()(std::int64_t i) const { place[slot[i]] = std::int32_t(i); }
};
template <class Store>
struct EmitSorted {
  Store s;
  const std::int32_t* slot;
  const std::int32_t* place;
  std::int32_t* simplices;
  std::int32_t* neighbors;
  GG_HD void operator()(std::int64_t i) const {
    const SimplexRecord<3> x = s.get(slot[i]);
    std::int32_t w[3];
    s.order_names(slot[i], w);
    const int r = smallest_first(w);
    for (int k = 0; k < 3; ++k) {
      const int j = (r + k) % 3;
      simplices[3 * i + k] = x.v[j];
      neighbors[3 * i + k] = x.n[j] >= 0 ? place[x.n[j]] : -1;
    }
  }
};
}  // namespace compact_detail

template <class Exec, class Store>
Compacted<Exec> compact_live_sorted(Exec& ex, std::int64_t used, const Store& store,
                                    std::int64_t names_below) {
  auto live = ex.template alloc<std::int32_t>(std::size_t(used));
  std::int32_t* slot = live.data();
  const std::int64_t count =
      ex.compact_indices(used, compact_detail::Liveness<Store>{store, used}, slot);
  int shift = 1;
  while ((std::int64_t(1) << shift) < names_below) ++shift;
  {
    auto keys = ex.template alloc<std::uint64_t>(std::size_t(count));
    ex.for_each_index(count, compact_detail::SortKey<Store>{store, slot, keys.data(), shift});
    ex.sort_by_key(keys.data(), slot, count, 2 * shift);
  }
  auto where = ex.template alloc<std::int32_t>(std::size_t(used));
  ex.fill(where.data(), used, std::int32_t(-1));
  ex.for_each_index(count, compact_detail::PlaceOf{slot, where.data()});
  Compacted<Exec> c;
  c.count = count;
  c.simplices = ex.template alloc<std::int32_t>(3 * std::size_t(count));
  c.neighbors = ex.template alloc<std::int32_t>(3 * std::size_t(count));
  ex.for_each_index(count, compact_detail::EmitSorted<Store>{
                               store, slot, where.data(), c.simplices.data(), c.neighbors.data()});
  return c;
}

}  // namespace gpugeom::mesh
