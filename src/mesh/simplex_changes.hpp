// Which simplices an update changed (internal; the triangulations that follow their points,
// issue 47): the simplices of the result before an update matched to those after it by their
// vertex sets. A simplex is the same where its vertices are (its orientation and the order of
// its vertices in the arrays do not matter, nor its neighbours).
//
// Matching: each simplex's sorted vertices hashed to 64 bits; the old ones sorted by hash; each
// new one searches its hash among them and compares the vertex sets exactly along the run of
// equal hashes (so a collision costs a comparison, never a wrong match).
#pragma once
#include <thrust/functional.h>

#include <cstdint>

#include "base/hd.hpp"
#include "gpugeom/changes.hpp"
#include "mesh/compact.hpp"
#include "mesh/hole_refill.hpp"

namespace gpugeom::mesh {

namespace changes_detail {

template <int K>
GG_HD void sorted_vertices(const std::int32_t* v, std::int32_t* s) {
  for (int k = 0; k < K; ++k) s[k] = v[k];
  for (int i = 1; i < K; ++i)
    for (int j = i; j > 0 && s[j - 1] > s[j]; --j) {
      const std::int32_t t = s[j];
      s[j] = s[j - 1];
      s[j - 1] = t;
    }
}

template <int K>
GG_HD std::uint64_t set_key(const std::int32_t* v) {
  std::int32_t s[K];
  sorted_vertices<K>(v, s);
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (int k = 0; k < K; ++k) h = refill_detail::mix(h ^ std::uint32_t(s[k]));
  return h;
}

template <int K>
GG_HD bool same_set(const std::int32_t* a, const std::int32_t* b) {
  std::int32_t x[K], y[K];
  sorted_vertices<K>(a, x);
  sorted_vertices<K>(b, y);
  for (int k = 0; k < K; ++k)
    if (x[k] != y[k]) return false;
  return true;
}

}  // namespace changes_detail

// prev: per new simplex, the index of the same simplex among the old ones, -1 where it is new;
// removed: the old simplices that are gone, increasing.
template <class Exec>
struct SimplexMatch {
  typename Exec::template Buffer<std::int32_t> prev, removed;
  std::int64_t num_new = 0, num_removed = 0;
};

// old: na simplices of K vertices each; now: nb. [synchronises]
template <int K, class Exec>
SimplexMatch<Exec> match_simplices(Exec& ex, const std::int32_t* old, std::int64_t na,
                                   const std::int32_t* now, std::int64_t nb) {
  using changes_detail::same_set;
  using changes_detail::set_key;
  SimplexMatch<Exec> M;
  auto d_key = ex.template alloc<std::uint64_t>(std::size_t(na));
  auto d_id = ex.template alloc<std::int32_t>(std::size_t(na));
  auto d_kept = ex.template alloc<std::int8_t>(std::size_t(na));
  std::uint64_t* key = d_key.data();
  std::int32_t* id = d_id.data();
  std::int8_t* kept = d_kept.data();
  ex.for_each_index(
      na, GG_LAMBDA(std::int64_t i) {
        key[i] = set_key<K>(old + K * i);
        id[i] = std::int32_t(i);
        kept[i] = 0;
      });
  ex.sort_by_key(key, id, na);
  M.prev = ex.template alloc<std::int32_t>(std::size_t(nb));
  std::int32_t* prev = M.prev.data();
  ex.for_each_index(
      nb, GG_LAMBDA(std::int64_t j) {
        const std::int32_t* v = now + K * j;
        const std::uint64_t h = set_key<K>(v);
        std::int64_t lo = 0, hi = na;  // the first old key >= h
        while (lo < hi) {
          const std::int64_t mid = lo + (hi - lo) / 2;
          if (key[mid] < h)
            lo = mid + 1;
          else
            hi = mid;
        }
        std::int32_t found = -1;
        for (std::int64_t p = lo; p < na && key[p] == h && found < 0; ++p)
          if (same_set<K>(old + K * std::int64_t(id[p]), v)) found = id[p];
        prev[j] = found;
        if (found >= 0) kept[found] = 1;  // (a simplex appears once in each result)
      });
  M.removed = ex.template alloc<std::int32_t>(std::size_t(na));
  M.num_removed = ex.compact_indices(
      na, GG_LAMBDA(std::int64_t i) { return kept[i] == 0; }, M.removed.data());
  M.num_new = nb - (na - M.num_removed);
  return M;
}

// The changes from the results `before` (na simplices of K vertices) to `now` (nb), as the
// public structs: host vectors, or executor arrays handed over (ready when this returns).
template <int K, class Exec>
void host_changes(Exec& ex, const std::int32_t* before, std::int64_t na, const std::int32_t* now,
                  std::int64_t nb, SimplexChanges& out) {
  auto M = match_simplices<K>(ex, before, na, now, nb);
  out.num_simplices = nb;
  out.num_previous = na;
  out.num_new = M.num_new;
  out.num_removed = M.num_removed;
  out.previous_index.resize(std::size_t(nb));
  out.removed.resize(std::size_t(M.num_removed));
  ex.to_host(M.prev.data(), nb, out.previous_index.data());
  ex.to_host(M.removed.data(), M.num_removed, out.removed.data());
}
template <int K, class Exec>
void device_changes(Exec& ex, const std::int32_t* before, std::int64_t na, const std::int32_t* now,
                    std::int64_t nb, DeviceSimplexChanges& out) {
  auto M = match_simplices<K>(ex, before, na, now, nb);
  ex.sync();  // (the caller may read them, and free them on any stream)
  out.num_simplices = nb;
  out.num_previous = na;
  out.num_new = M.num_new;
  out.num_removed = M.num_removed;
  out.previous_index = M.prev.hand_over();
  out.removed = M.removed.hand_over();
}
// The same for compacted results.
template <int K, class Exec>
void host_changes(Exec& ex, const Compacted<Exec>& before, const Compacted<Exec>& now,
                  SimplexChanges& out) {
  host_changes<K>(ex, before.simplices.data(), before.count, now.simplices.data(), now.count, out);
}
template <int K, class Exec>
void device_changes(Exec& ex, const Compacted<Exec>& before, const Compacted<Exec>& now,
                    DeviceSimplexChanges& out) {
  device_changes<K>(ex, before.simplices.data(), before.count, now.simplices.data(), now.count,
                    out);
}

}  // namespace gpugeom::mesh
