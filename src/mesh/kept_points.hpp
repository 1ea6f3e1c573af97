// What the kept triangulations (DynamicDelaunay2d and DynamicDelaunay3d, issue 47) share about
// their points (internal): where the walks of new points start, and whether a move changed
// which points coincide.
#pragma once
#include <thrust/functional.h>

#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom::mesh {

// Where the walks of points new to a kept triangulation start: each new point takes the old
// vertex before it on the curve order of the prepared points (the first old vertex for new
// points before every old one). The curve order keeps neighbours in space near each other, so
// the walk from that vertex's simplex is short.
// orig: the m prepared (distinct, curve-ordered) points' input indices; the old points are those
// with input index below n_old, all of them vertices of the kept triangulation. hint: n entries
// (input indices): a new point's start vertex (an input index), -1 for the rest. [synchronises]
template <class Exec>
void curve_hints(Exec& ex, const std::int32_t* orig, std::int64_t m, std::int64_t n,
                 std::int64_t n_old, std::int32_t* hint) {
  const std::int32_t old = std::int32_t(n_old);
  auto d_rank = ex.template alloc<std::int64_t>(std::size_t(m + 1));
  auto d_olds = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int64_t* rank = d_rank.data();
  std::int32_t* olds = d_olds.data();
  ex.exclusive_scan_of(
      m + 1, GG_LAMBDA(std::int64_t j)->std::int64_t { return j < m && orig[j] < old; }, rank);
  ex.compact_indices(
      m, GG_LAMBDA(std::int64_t j) { return orig[j] < old; }, olds);
  ex.fill(hint, n, std::int32_t(-1));
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t j) {
        if (orig[j] < old) return;
        const std::int64_t r = rank[j];
        hint[orig[j]] = orig[olds[r > 0 ? r - 1 : 0]];
      });
}

// How many entries of two duplicate maps (n entries each; null: no duplicate) differ.
// [synchronises]
template <class Exec>
std::int64_t dup_changes(Exec& ex, const std::int32_t* a, const std::int32_t* b, std::int64_t n) {
  auto cnt = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      n, GG_LAMBDA(std::int64_t i)->std::int64_t { return (a ? a[i] : -1) != (b ? b[i] : -1); },
      std::int64_t(0), thrust::plus<std::int64_t>(), cnt.data());
  std::int64_t c = 0;
  ex.to_host(cnt.data(), 1, &c);
  return c;
}

}  // namespace gpugeom::mesh
