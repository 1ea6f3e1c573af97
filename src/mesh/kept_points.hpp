// What the kept triangulations (DynamicDelaunay2d and DynamicDelaunay3d, issue 47) share about
// their points (internal): where the walks of new points start, whether a move changed which
// points coincide, and the points left once some are removed.
#pragma once
#include <thrust/functional.h>

#include <cstdint>
#include <string>

#include "base/hd.hpp"
#include "exec/atomics.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/removed.hpp"

namespace gpugeom::mesh {

// Which points a kept triangulation already holds as vertices, for curve_hints: those with an
// input index below n_old (an insertion: the points appended are new), or those not flagged (a
// move: the flagged ones were taken out to be put back).
struct BelowIndex {
  std::int32_t n_old;
  GG_HD bool operator()(std::int32_t i) const { return i < n_old; }
};
struct NotFlagged {
  const std::int8_t* flag;
  GG_HD bool operator()(std::int32_t i) const { return flag[i] == 0; }
};

// Where the walks of points new to a kept triangulation start: each new point takes the old
// vertex before it on the curve order of the prepared points (the first old vertex for new
// points before every old one). The curve order keeps neighbours in space near each other, so
// the walk from that vertex's simplex is short.
// orig: the m prepared (distinct, curve-ordered) points' input indices; held(i): whether input
// point i is a vertex of the kept triangulation (BelowIndex, NotFlagged). hint: n entries (input
// indices): a new point's start vertex (an input index), -1 for the rest and where no point is
// held. [synchronises]
template <class Exec, class Held>
void curve_hints(Exec& ex, const std::int32_t* orig, std::int64_t m, std::int64_t n, Held held,
                 std::int32_t* hint) {
  auto d_rank = ex.template alloc<std::int64_t>(std::size_t(m + 1));
  auto d_olds = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int64_t* rank = d_rank.data();
  std::int32_t* olds = d_olds.data();
  ex.exclusive_scan_of(
      m + 1, GG_LAMBDA(std::int64_t j)->std::int64_t { return j < m && held(orig[j]); }, rank);
  const std::int64_t nold = ex.compact_indices(
      m, GG_LAMBDA(std::int64_t j) { return held(orig[j]); }, olds);
  ex.fill(hint, n, std::int32_t(-1));
  if (nold == 0) return;
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t j) {
        if (held(orig[j])) return;
        const std::int64_t r = rank[j];
        hint[orig[j]] = orig[olds[r > 0 ? r - 1 : 0]];
      });
}

// How many of n flags are set. [synchronises]
template <class Exec>
std::int64_t count_flags(Exec& ex, const std::int8_t* flag, std::int64_t n) {
  auto cnt = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      n, GG_LAMBDA(std::int64_t i)->std::int64_t { return flag[i] != 0; }, std::int64_t(0),
      thrust::plus<std::int64_t>(), cnt.data());
  std::int64_t c = 0;
  ex.to_host(cnt.data(), 1, &c);
  return c;
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

// A removed point's entry in a kept triangulation's duplicate map (the public kRemovedPoint).
constexpr std::int32_t kRemoved = kRemovedPoint;

// The points not removed, gathered (dimension D, gathered order = input order) with their input
// indices.
template <class Exec>
struct LivePoints {
  typename Exec::template Buffer<double> p;
  typename Exec::template Buffer<std::int32_t> ids;
  std::int64_t count = 0;
};
// L.p made the coordinates (dimension D, from p) of the L.count points L.ids names.
template <int D, class Exec>
void gather(Exec& ex, const double* p, LivePoints<Exec>& L) {
  L.p = ex.template alloc<double>(std::size_t(D * L.count));
  double* q = L.p.data();
  const std::int32_t* ids = L.ids.data();
  ex.for_each_index(
      L.count, GG_LAMBDA(std::int64_t j) {
        for (int d = 0; d < D; ++d) q[D * j + d] = p[D * std::int64_t(ids[j]) + d];
      });
}
// gone: n flags (1: removed). [synchronises]
template <int D, class Exec>
LivePoints<Exec> gather_live(Exec& ex, const double* p, std::int64_t n, const std::int8_t* gone) {
  LivePoints<Exec> L;
  L.ids = ex.template alloc<std::int32_t>(std::size_t(n));
  L.count = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return gone[i] == 0; }, L.ids.data());
  gather<D>(ex, p, L);
  return L;
}

// After the gathered points were prepared: their m distinct points' indices (orig, in place)
// made input indices again, and the duplicate map (L.count entries of gathered indices, or
// null) widened to the n input points, kRemoved at removed ones.
template <class Exec>
typename Exec::template Buffer<std::int32_t> to_input_indices(Exec& ex, const LivePoints<Exec>& L,
                                                              std::int32_t* orig, std::int64_t m,
                                                              const std::int32_t* dup,
                                                              std::int64_t n) {
  const std::int32_t* ids = L.ids.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t j) { orig[j] = ids[orig[j]]; });
  auto wide = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* w = wide.data();
  ex.fill(w, n, kRemoved);
  ex.for_each_index(
      L.count, GG_LAMBDA(std::int64_t j) { w[ids[j]] = dup && dup[j] >= 0 ? ids[dup[j]] : -1; });
  return wide;
}

// Removal flags (or null: none removed) for n_old points carried to n (the new ones not
// removed); an empty buffer where none is.
template <class Exec>
typename Exec::template Buffer<std::int8_t> extend_flags(Exec& ex, const std::int8_t* gone,
                                                         std::int64_t n_old, std::int64_t n) {
  typename Exec::template Buffer<std::int8_t> out;
  if (!gone) return out;
  out = ex.template alloc<std::int8_t>(std::size_t(n));
  ex.copy(gone, n_old, out.data());
  if (n > n_old) ex.fill(out.data() + n_old, n - n_old, std::int8_t(0));
  return out;
}

// The removal flags after removing `count` indices (executor memory) from n points of which
// `gone` (or null: none) are removed already: checked (each in range, each once, not removed
// before), Error(InvalidArgument) naming the fault otherwise. [synchronises]
template <class Exec>
typename Exec::template Buffer<std::int8_t> removal_flags(Exec& ex, const std::int8_t* gone,
                                                          std::int64_t n, const std::int32_t* idx,
                                                          std::int64_t count) {
  auto d_mark = ex.template alloc<std::int32_t>(std::size_t(n));
  auto d_bad = ex.template alloc<std::int64_t>(3);  // out of range, repeated, removed before
  std::int32_t* mark = d_mark.data();
  std::int64_t* bad = d_bad.data();
  ex.fill(mark, n, std::int32_t(0));
  ex.fill(bad, 3, std::int64_t(0));
  ex.for_each_index(
      count, GG_LAMBDA(std::int64_t j) {
        const std::int32_t i = idx[j];
        if (i < 0 || i >= n) {
          atomic_add(&bad[0], std::int64_t(1));
          return;
        }
        if (gone && gone[i]) atomic_add(&bad[2], std::int64_t(1));
        if (atomic_exchange(&mark[i], std::int32_t(1))) atomic_add(&bad[1], std::int64_t(1));
      });
  std::int64_t b[3];
  ex.to_host(bad, 3, b);
  if (b[0])
    throw Error(ErrorCode::InvalidArgument, "remove: " + std::to_string(b[0]) +
                                                " index(es) outside 0 .. " + std::to_string(n - 1) +
                                                " (the points' indices)");
  if (b[1])
    throw Error(ErrorCode::InvalidArgument,
                "remove: " + std::to_string(b[1]) + " index(es) given more than once");
  if (b[2])
    throw Error(ErrorCode::InvalidArgument,
                "remove: " + std::to_string(b[2]) + " point(s) removed before");
  auto out = ex.template alloc<std::int8_t>(std::size_t(n));
  std::int8_t* o = out.data();
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) { o[i] = std::int8_t((gone && gone[i]) || mark[i]); });
  return out;
}

}  // namespace gpugeom::mesh
