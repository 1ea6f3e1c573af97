// The output step of every mesh module: the live simplices renumbered in slot order, each with
// its K vertices (as the caller names them, e.g. input indices) and its K neighbours among the
// live ones (-1 across a face whose neighbour is not live: delaunay2d's infinite triangles).
//
// Slots are never reused inside a computation, so the store holds dead slots (hull3d's removed
// facets) and slots outside the output (delaunay2d's triangles at the infinity point); a scan
// over liveness gives each live slot its rank, and the rank steps where a slot is live, so a
// neighbour's liveness needs no second test.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include <cuda/atomic>

#include "base/hd.hpp"
#include "gpugeom/common.hpp"
#include "exec/atomics.hpp"
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
  // Where compact_live_sorted was asked for it: per order name, the last simplex naming it (-1:
  // none). 3D's vertex map, made here where the names are at hand and near one another: from the
  // output's vertices (input indices, in no order) every entry was a cache miss.
  typename Exec::template Buffer<std::int32_t> last;
  // Where compact_live_sorted's `into` placed the arrays instead (null: the buffers hold them).
  std::int32_t* placed_simplices = nullptr;
  std::int32_t* placed_neighbors = nullptr;
  const std::int32_t* simplices_data() const {
    return placed_simplices ? placed_simplices : simplices.data();
  }
  const std::int32_t* neighbors_data() const {
    return placed_neighbors ? placed_neighbors : neighbors.data();
  }
};

// Where compact_live_sorted writes: into(count) returns arrays of K·count entries in executor
// memory for the simplices and the neighbours (the host result's own, on the CPU executor: no
// copy), or nulls for new buffers of the executor's (OwnArrays).
struct OwnArrays {
  std::pair<std::int32_t*, std::int32_t*> operator()(std::int64_t) const { return {}; }
};
// The host result's own arrays (Vec: a HostVector), on the CPU executor where the caller gave
// none: the output is written there (the executor's memory is the host's), with no second
// array and no copy (at 10^6 3D points 215 MB, 0.3-0.6 s on the 2-core machine, most of it
// faulting fresh pages in). The caller's arrays are written only after every length is
// checked, so they take the copy; so does everything on the GPU.
template <int K, class Exec, class Vec>
struct IntoResult {
  bool caller_gave;
  Vec& simplices;
  Vec& neighbors;
  std::pair<std::int32_t*, std::int32_t*> operator()(std::int64_t count) const {
    if (Exec::backend != Backend::Cpu || caller_gave) return {};
    simplices.resize(std::size_t(K * count));
    neighbors.resize(std::size_t(K * count));
    return {simplices.data(), neighbors.data()};
  }
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

// The same in one order that depends on the simplices alone (K = 3: triangles, K = 4:
// tetrahedra). The store names each simplex's vertices for the order too (order_names(t, w):
// the modules' curve positions, so that the order follows the curve, as the slots of either
// executor roughly do, and the output is read and written nearly in sequence). Each simplex is
// turned so that its vertex first in that order comes first, with its orientation kept (a
// rotation of a triangle; for a tetrahedron an even permutation, which also brings the least
// of the other three second), and the simplices are sorted by their first two vertices, then
// (K = 4) their third. A directed edge lies in one triangle, an oriented face in one
// tetrahedron, so the order is total. Two schedules that build the same triangulation (the
// executors', a kept one's updates and a fresh call) then give the same arrays, whatever slots
// their histories left. It costs a sort of the live simplices' keys (docs/performance.md: one
// output order). The store also hints its record of a slot soon read (prefetch(t): the host's
// prefetch, nothing on the device). names_below: every order name is smaller (sizes the keys: fewer
// radix passes).
namespace compact_detail {
// The canonical turn of a simplex named w: perm[k] is the local vertex that goes k-th.
template <int K>
GG_HD inline void canonical_turn(const std::int32_t* w, int* perm) {
  int r = 0;
  for (int k = 1; k < K; ++k)
    if (w[k] < w[r]) r = k;
  if constexpr (K == 3) {
    for (int k = 0; k < 3; ++k) perm[k] = (r + k) % 3;
  } else {
    // r first by a double swap (even): (0 1 2 3), (1 0 3 2), (2 3 0 1), (3 2 1 0); then the other
    // three turned (an even cycle) so that their least comes second.
    const int rest[3] = {r ^ 1, r ^ 2, r ^ 3};  // (r ^ 1, r ^ 2, r ^ 3 is that double swap's tail)
    int j = 0;
    for (int i = 1; i < 3; ++i)
      if (w[rest[i]] < w[rest[j]]) j = i;
    perm[0] = r;
    for (int i = 0; i < 3; ++i) perm[1 + i] = rest[(j + i) % 3];
  }
}
template <int K, class Store>
struct SortKey {
  Store s;
  const std::int32_t* slot;  // the live slots
  std::uint64_t* keys;
  std::uint64_t* third;  // K = 4: the third name above the slot (SortRuns reads no record)
  int shift;
  GG_HD void operator()(std::int64_t i) const {
    std::int32_t w[K];
    int p[K];
    s.order_names(slot[i], w);
    canonical_turn<K>(w, p);
    keys[i] =
        (std::uint64_t(std::uint32_t(w[p[0]])) << shift) | std::uint64_t(std::uint32_t(w[p[1]]));
    if constexpr (K == 4)
      third[i] = (std::uint64_t(std::uint32_t(w[p[2]])) << 32) | std::uint32_t(slot[i]);
  }
};
// K = 4: the simplices whose first two names are equal (those around one edge whose ends come
// first in both: a few) sorted by their third, each run by the thread at its start, and the
// slots taken out in that order.
struct SortRuns {
  const std::uint64_t* keys;  // sorted
  std::uint64_t* third;       // sorted with them
  std::int32_t* slot;
  std::int64_t count;
  GG_HD void operator()(std::int64_t i) const {
    if (i > 0 && keys[i - 1] == keys[i]) return;
    std::int64_t end = i + 1;
    while (end < count && keys[end] == keys[i]) ++end;
    for (std::int64_t a = i + 1; a < end; ++a) {  // (insertion sort: runs are short)
      const std::uint64_t x = third[a];
      std::int64_t b = a;
      for (; b > i && (third[b - 1] >> 32) > (x >> 32); --b) third[b] = third[b - 1];
      third[b] = x;
    }
    for (std::int64_t a = i; a < end; ++a) slot[a] = std::int32_t(std::uint32_t(third[a]));
  }
};
// How far ahead the CPU executor's gathering passes ask for what they will read (prefetch on
// the host; nothing on the device): CountInBucket's counters (a locked add waits for its miss: 65 %
// of that pass), PlaceOf's and EmitSorted's records through slot[], whose order follows the
// output, not the store (58 % of EmitSorted on one thread, 10^6 3D points, was that load).
constexpr std::int64_t kAhead = 16;
// The CPU executor's way to the same order (BucketSlots): the live simplices counted by their
// first name (buckets), placed in their bucket, and each bucket (a few: 6.7 tetrahedra or 2
// triangles a vertex, on average) sorted by the rest. No radix passes over 16-byte pairs, and
// a third of the temporary memory; the order within a bucket before its sort depends on the
// threads, after it on the names alone (they are distinct within a bucket: see above).
// Two passes over the slots: the first counts each bucket's simplices and gives each its rank
// among them (CountInBucket), the second places them at their bucket's start plus their rank
// (PlaceInBucket). (The second pass bumped the counters again, as the first; a locked add per
// simplex twice was most of the output's sorting on one thread.)
// The least of slot t's order names: its bucket (negative for a dead slot's).
template <int K, class Store>
GG_HD inline std::int32_t least_name(const Store& s, std::int64_t t) {
  std::int32_t w[K];
  s.order_names(t, w);
  std::int32_t least = w[0];
  for (int k = 1; k < K; ++k) least = w[k] < least ? w[k] : least;
  return least;
}
template <int K, class Store>
struct CountInBucket {
  Store s;
  std::int32_t* count;  // per first name
  std::int32_t* rank;   // per slot: its rank in its bucket
  std::int64_t used;
  GG_HD void operator()(std::int64_t t) const {
    std::int32_t w[K];
    if (t + kAhead < used) {  // (the counter the slot kAhead on will bump: see kAhead)
      const std::int32_t least = least_name<K>(s, t + kAhead);
      if (least >= 0) prefetch_on_host<true>(count + least);
    }
    if (!s.live(t)) return;
    int p[K];
    s.order_names(t, w);
    canonical_turn<K>(w, p);
    cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> c(count[w[p[0]]]);
    rank[t] = c.fetch_add(1, cuda::memory_order_relaxed);
  }
};
template <int K, class Store>
struct PlaceInBucket {
  Store s;
  const std::int32_t* begin;  // per first name: where its bucket starts
  const std::int32_t* rank;   // per slot: its rank in its bucket (CountInBucket)
  std::int32_t* slot;         // per entry
  std::uint64_t* rest;        // per entry: the second name above the third (K = 4), or the second
  std::int64_t used;
  GG_HD void operator()(std::int64_t t) const {
#ifndef __CUDA_ARCH__
    if (t + kAhead < used && s.live(t + kAhead)) {  // (the entry the slot kAhead on will write)
      const std::int32_t at = begin[least_name<K>(s, t + kAhead)] + rank[t + kAhead];
      prefetch_on_host<true>(slot + at);
      prefetch_on_host<true>(rest + at);
    }
#endif
    if (!s.live(t)) return;
    std::int32_t w[K];
    int p[K];
    s.order_names(t, w);
    canonical_turn<K>(w, p);
    const std::int32_t at = begin[w[p[0]]] + rank[t];
    slot[at] = std::int32_t(t);
    const std::uint64_t second = std::uint32_t(w[p[1]]);
    rest[at] = K == 4 ? (second << 32) | std::uint32_t(w[p[2]]) : second;
  }
};
// (Buckets are small, but not always: the fan around one end of a segment over the points of
// another holds a bucket of thousands, which the insertion sort made quadratic; those go by
// std::sort. SortBucket runs on the host only: live_by_buckets is the CPU executor's.)
constexpr std::int32_t kInsertionSortMost = 32;
struct SortBucket {
  const std::int32_t* begin;  // per first name, and one past the last
  std::int32_t* slot;
  std::uint64_t* rest;
  GG_HD void operator()(std::int64_t a) const {
    const std::int32_t lo = begin[a], hi = begin[a + 1];
#ifndef __CUDA_ARCH__
    if (hi - lo > kInsertionSortMost) {
      std::vector<std::pair<std::uint64_t, std::int32_t>> b;
      b.reserve(std::size_t(hi - lo));
      for (std::int32_t i = lo; i < hi; ++i) b.push_back({rest[i], slot[i]});
      std::sort(b.begin(), b.end());
      for (std::int32_t i = lo; i < hi; ++i)
        rest[i] = b[std::size_t(i - lo)].first, slot[i] = b[std::size_t(i - lo)].second;
      return;
    }
#endif
    for (std::int32_t i = lo + 1; i < hi; ++i) {  // (insertion sort: buckets are small)
      const std::uint64_t x = rest[i];
      const std::int32_t y = slot[i];
      std::int32_t j = i;
      for (; j > lo && rest[j - 1] > x; --j) rest[j] = rest[j - 1], slot[j] = slot[j - 1];
      rest[j] = x, slot[j] = y;
    }
  }
};
struct PlaceOf {
  const std::int32_t* slot;  // in output order
  std::int32_t* place;       // per slot: its position, -1 where not live
  std::int64_t count;
  GG_HD void operator()(std::int64_t i) const {
    if (i + kAhead < count) prefetch_on_host<true>(place + slot[i + kAhead]);
    place[slot[i]] = std::int32_t(i);
  }
};
// Downwards (i from count - 1), so that `last` takes few atomics: a thread's first write of a
// name is its greatest there, and the later ones see a greater value with a plain read (upwards
// every entry would be an atomic). The record kAhead on is asked for, and the neighbours' places
// of the one kAhead / 2 on, whose record is then in the cache (the places, by slot, were most of
// this pass's misses at 10^7 points).
template <int K, class Store>
struct EmitSorted {
  Store s;
  const std::int32_t* slot;
  const std::int32_t* place;
  std::int32_t* simplices;
  std::int32_t* neighbors;
  std::int32_t* last;  // per order name: the greatest place naming it, or null (not asked for)
  std::int64_t count;
  GG_HD void operator()(std::int64_t j) const {
    const std::int64_t i = count - 1 - j;
#ifndef __CUDA_ARCH__
    if (i >= kAhead) s.prefetch(slot[i - kAhead]);
    if (i >= kAhead / 2) {
      const SimplexRecord<K> y = s.get(slot[i - kAhead / 2]);
      for (int k = 0; k < K; ++k)
        if (y.n[k] >= 0) prefetch_on_host(place + y.n[k]);
    }
#endif
    const SimplexRecord<K> x = s.get(slot[i]);
    std::int32_t w[K];
    int p[K];
    s.order_names(slot[i], w);
    canonical_turn<K>(w, p);
    for (int k = 0; k < K; ++k) {
      const int j = p[k];
      simplices[K * i + k] = x.v[j];
      neighbors[K * i + k] = x.n[j] >= 0 ? place[x.n[j]] : -1;
    }
    if (last)
      for (int k = 0; k < K; ++k) atomic_max(last + w[k], std::int32_t(i));
  }
};
}  // namespace compact_detail

// The live slots in the output order, by buckets (the CPU executor's way): returns how many.
// rank: used entries of scratch.
template <int K, class Exec, class Store>
std::int64_t live_by_buckets(Exec& ex, std::int64_t used, const Store& store, std::int64_t names,
                             std::int32_t* rank,
                             typename Exec::template Buffer<std::int32_t>& live) {
  auto count = ex.template alloc<std::int32_t>(std::size_t(names) + 1);
  auto begin = ex.template alloc<std::int32_t>(std::size_t(names) + 1);
  std::int32_t* b = begin.data();
  ex.fill(count.data(), names + 1, std::int32_t(0));
  ex.for_each_index(used, compact_detail::CountInBucket<K, Store>{store, count.data(), rank, used});
  ex.exclusive_scan(count.data(), b, names + 1);
  std::int32_t total = 0;
  ex.to_host(b + names, 1, &total);
  live = ex.template alloc<std::int32_t>(std::size_t(total));
  auto rest = ex.template alloc<std::uint64_t>(std::size_t(total));
  ex.for_each_index(used, compact_detail::PlaceInBucket<K, Store>{store, b, rank, live.data(),
                                                                  rest.data(), used});
  ex.for_each_index(names, compact_detail::SortBucket{b, live.data(), rest.data()});
  return total;
}

// with_last: also each order name's last simplex (Compacted::last).
template <int K, class Exec, class Store, class Into = OwnArrays>
Compacted<Exec> compact_live_sorted(Exec& ex, std::int64_t used, const Store& store,
                                    std::int64_t names_below, Into into = {},
                                    bool with_last = false) {
  static_assert(K == 3 || K == 4, "triangles or tetrahedra");
  typename Exec::template Buffer<std::int32_t> live, where;  // (where: per slot, its place)
  std::int64_t count = 0;
  if constexpr (Exec::backend == Backend::Cpu) {
    where = ex.template alloc<std::int32_t>(std::size_t(used));  // (the buckets' ranks first)
    count = live_by_buckets<K>(ex, used, store, names_below, where.data(), live);
  } else {
    live = ex.template alloc<std::int32_t>(std::size_t(used));
    count = ex.compact_indices(used, compact_detail::Liveness<Store>{store, used}, live.data());
    int shift = 1;
    while ((std::int64_t(1) << shift) < names_below) ++shift;
    std::int32_t* slot = live.data();
    auto keys = ex.template alloc<std::uint64_t>(std::size_t(count));
    if constexpr (K == 3) {
      ex.for_each_index(
          count, compact_detail::SortKey<K, Store>{store, slot, keys.data(), nullptr, shift});
      ex.sort_by_key(keys.data(), slot, count, 2 * shift);
    } else {
      auto third = ex.template alloc<std::uint64_t>(std::size_t(count));
      ex.for_each_index(
          count, compact_detail::SortKey<K, Store>{store, slot, keys.data(), third.data(), shift});
      ex.sort_by_key(keys.data(), third.data(), count, 2 * shift);
      ex.for_each_index(count, compact_detail::SortRuns{keys.data(), third.data(), slot, count});
    }
  }
  // (on the GPU after the sort's keys are freed, so that it does not raise the peak beside them)
  if constexpr (Exec::backend != Backend::Cpu)
    where = ex.template alloc<std::int32_t>(std::size_t(used));
  const std::int32_t* slot = live.data();
  ex.fill(where.data(), used, std::int32_t(-1));
  ex.for_each_index(count, compact_detail::PlaceOf{slot, where.data(), count});
  Compacted<Exec> c;
  c.count = count;
  std::tie(c.placed_simplices, c.placed_neighbors) = into(count);
  if (!c.placed_simplices) {
    c.simplices = ex.template alloc<std::int32_t>(std::size_t(K) * std::size_t(count));
    c.neighbors = ex.template alloc<std::int32_t>(std::size_t(K) * std::size_t(count));
  }
  std::int32_t* sp = c.placed_simplices ? c.placed_simplices : c.simplices.data();
  std::int32_t* np = c.placed_simplices ? c.placed_neighbors : c.neighbors.data();
  if (with_last) {
    c.last = ex.template alloc<std::int32_t>(std::size_t(names_below));
    ex.fill(c.last.data(), names_below, std::int32_t(-1));
  }
  ex.for_each_index(count, compact_detail::EmitSorted<K, Store>{store, slot, where.data(), sp, np,
                                                                c.last.data(), count});
  return c;
}

}  // namespace gpugeom::mesh
