// Input preparation shared by the mesh modules (thesis 6.4), for points in D dimensions:
// validation against the range the exact predicates take, the bounding box, the Hilbert order
// with duplicates merged, and the reductions that pick a first simplex (lexicographic
// extremes, farthest points). Every choice breaks ties by the smaller index, and every
// reduction is exact comparisons of stored doubles, so both executors pick the same points.
#pragma once
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "base/hd.hpp"
#include "predicates/predicates.hpp"
#include "spatial/hilbert.hpp"

namespace gpugeom::mesh {

using u64 = std::uint64_t;

// A point and its index, with a key for the farthest-point reductions.
template <int D>
struct Cand {
  double x[D];
  double key;
  std::int32_t i;
};
template <int D>
GG_HD inline bool lex_less(const Cand<D>& a, const Cand<D>& b) {
  for (int d = 0; d < D; ++d)
    if (a.x[d] != b.x[d]) return a.x[d] < b.x[d];
  return a.i < b.i;
}
template <int D>
struct MinLex {  // the lexicographically smallest point, then the smaller index
  GG_HD Cand<D> operator()(const Cand<D>& a, const Cand<D>& b) const {
    return lex_less(a, b) ? a : b;
  }
};
template <int D>
struct MaxLex {  // the lexicographically largest point, then the smaller index
  GG_HD Cand<D> operator()(const Cand<D>& a, const Cand<D>& b) const {
    for (int d = 0; d < D; ++d)
      if (a.x[d] != b.x[d]) return a.x[d] > b.x[d] ? a : b;
    return a.i < b.i ? a : b;
  }
};
template <int D>
struct Farthest {  // the largest key, then the smaller index
  GG_HD Cand<D> operator()(const Cand<D>& a, const Cand<D>& b) const {
    if (a.key != b.key) return a.key > b.key ? a : b;
    return a.i < b.i ? a : b;
  }
};
template <int D>
GG_HD inline Cand<D> cand_of(const double* p, std::int64_t i, double key = 0) {
  Cand<D> c;
  for (int d = 0; d < D; ++d) c.x[d] = p[D * i + d];
  c.key = key;
  c.i = std::int32_t(i);
  return c;
}
// The identity of every reduction above (validated points are finite: the infinities lose).
template <int D>
GG_HD inline Cand<D> cand_none(double coords) {
  Cand<D> c;
  for (int d = 0; d < D; ++d) c.x[d] = coords;
  c.key = -1;
  c.i = std::numeric_limits<std::int32_t>::max();
  return c;
}

// The reduction of f(i) -> Cand<D> over i < n with op. [synchronises]
template <int D, class Exec, class F, class Op>
Cand<D> reduce_cand(Exec& ex, std::int64_t n, F f, Op op, double start = 0) {
  auto out = ex.template alloc<Cand<D>>(1);
  ex.transform_reduce_into(n, f, cand_none<D>(start), op, out.data());
  Cand<D> h;
  ex.to_host(out.data(), 1, &h);
  return h;
}

// Can the exact predicates take every coordinate of point q?
template <int D>
GG_HD inline bool exact_ok(const double* q) {
  for (int d = 0; d < D; ++d)
    if (!pred::in_exact_range(q[d])) return false;
  return true;
}

// The input check and both lexicographic extremes in one pass: the points the exact
// predicates cannot take, and the smallest and largest point (meaningful once bad is 0).
template <int D>
struct Extremes {
  Cand<D> lo, hi;
  std::int64_t bad;  // points
};
template <int D>
struct ExtremesOp {
  GG_HD Extremes<D> operator()(const Extremes<D>& a, const Extremes<D>& b) const {
    return Extremes<D>{MinLex<D>{}(a.lo, b.lo), MaxLex<D>{}(a.hi, b.hi), a.bad + b.bad};
  }
};
template <int D>
struct ExtremeOf {
  const double* p;
  GG_HD Extremes<D> operator()(std::int64_t i) const {
    const Cand<D> c = cand_of<D>(p, i);
    return Extremes<D>{c, c, exact_ok<D>(p + D * i) ? 0 : 1};
  }
};
// [synchronises]
template <int D, class Exec>
Extremes<D> extremes(Exec& ex, const double* p, std::int64_t n) {
  const double inf = std::numeric_limits<double>::infinity();
  auto out = ex.template alloc<Extremes<D>>(1);
  ex.transform_reduce_into(n, ExtremeOf<D>{p},
                           Extremes<D>{cand_none<D>(inf), cand_none<D>(-inf), 0}, ExtremesOp<D>{},
                           out.data());
  Extremes<D> h;
  ex.to_host(out.data(), 1, &h);
  return h;
}

// The bounding box of the valid coordinates and the count of invalid ones; bounds_in_place
// also turns -0 into +0 (so that equal points have equal bits in every later step).
template <int D>
struct Bounds {
  double lo[D], hi[D];
  std::int64_t bad;  // coordinates
};
template <int D>
struct BoundsOp {
  GG_HD Bounds<D> operator()(const Bounds<D>& a, const Bounds<D>& b) const {
    Bounds<D> r;
    for (int d = 0; d < D; ++d) {
      r.lo[d] = a.lo[d] < b.lo[d] ? a.lo[d] : b.lo[d];
      r.hi[d] = a.hi[d] > b.hi[d] ? a.hi[d] : b.hi[d];
    }
    r.bad = a.bad + b.bad;
    return r;
  }
};
template <int D, bool kInPlace>
struct BoundsOf {
  std::conditional_t<kInPlace, double*, const double*> r;
  GG_HD Bounds<D> operator()(std::int64_t i) const {
    Bounds<D> b;
    b.bad = 0;
    for (int d = 0; d < D; ++d) {
      const double v = r[D * i + d] + 0.0;
      if constexpr (kInPlace) r[D * i + d] = v;
      const bool ok = pred::in_exact_range(v);
      b.bad += ok ? 0 : 1;
      b.lo[d] = ok ? v : 1e308;
      b.hi[d] = ok ? v : -1e308;
    }
    return b;
  }
};
template <int D, class Exec, class Of>
Bounds<D> reduce_bounds(Exec& ex, std::int64_t n, Of of) {
  auto out = ex.template alloc<Bounds<D>>(1);
  Bounds<D> init;
  for (int d = 0; d < D; ++d) init.lo[d] = 1e308, init.hi[d] = -1e308;
  init.bad = 0;
  ex.transform_reduce_into(n, of, init, BoundsOp<D>{}, out.data());
  Bounds<D> h;
  ex.to_host(out.data(), 1, &h);
  return h;
}
// [synchronises]
template <int D, class Exec>
Bounds<D> bounds_in_place(Exec& ex, double* r, std::int64_t n) {
  return reduce_bounds<D>(ex, n, BoundsOf<D, true>{r});
}
// The same, leaving the points as they are (the caller's array). [synchronises]
template <int D, class Exec>
Bounds<D> bounds(Exec& ex, const double* r, std::int64_t n) {
  return reduce_bounds<D>(ex, n, BoundsOf<D, false>{r});
}

// Doubles as unsigned keys with the same order (-0 turned into +0 before).
GG_INLINE u64 ordered_key(double v) {
  u64 u;
  memcpy(&u, &v, 8);
  return (u >> 63) ? ~u : (u | (u64(1) << 63));
}

// The distinct points in Hilbert order: D coordinates each, the input index of each, and for
// every input point the input index of the point it duplicates (-1 for the kept ones: the
// first of each run, which has the smallest input index), when there are duplicates.
template <class Exec>
struct SortedPoints {
  typename Exec::template Buffer<double> pts;
  typename Exec::template Buffer<std::int32_t> orig;
  typename Exec::template Buffer<std::int32_t> dup;  // n entries, only when duplicates > 0
  std::int64_t m = 0;
  std::int64_t duplicates = 0;
};

namespace prepare_detail {
struct Sum {
  GG_HD std::int64_t operator()(std::int64_t a, std::int64_t b) const { return a + b; }
};
struct Max {
  GG_HD std::int64_t operator()(std::int64_t a, std::int64_t b) const { return a > b ? a : b; }
};
// The end of the run of equal keys that begins at i (i itself where none does).
GG_HD inline std::int64_t run_end(const u64* k, std::int64_t n, std::int64_t i) {
  if (i > 0 && k[i] == k[i - 1]) return i;
  std::int64_t e = i + 1;
  while (e < n && k[e] == k[i]) ++e;
  return e;
}
// The runs' order, as the passes in sort_distinct make it: by the coordinates (+0 for -0),
// first to last, then by input index.
template <int D>
GG_HD inline bool before(const double* r, std::int32_t a, std::int32_t b) {
  for (int d = 0; d < D; ++d) {
    const u64 x = ordered_key(r[D * std::int64_t(a) + d] + 0.0),
              y = ordered_key(r[D * std::int64_t(b) + d] + 0.0);
    if (x != y) return x < y;
  }
  return a < b;
}
constexpr std::int64_t kShortRun = 64;  // (runs up to this long are sorted each by one thread)
}  // namespace prepare_detail

// r: n valid points on the executor, box their bounding box. -0 and +0 are one value here
// (keys and comparisons), and the distinct points come out with +0. [synchronises]
template <int D, class Exec>
SortedPoints<Exec> sort_distinct(Exec& ex, const double* r, std::int64_t n, const Bounds<D>& box) {
  spatial::Box sbox;
  for (int d = 0; d < 3; ++d) sbox.lo[d] = sbox.hi[d] = 0;
  for (int d = 0; d < D; ++d) sbox.lo[d] = box.lo[d], sbox.hi[d] = box.hi[d];
  // The results first, sized for n (m <= n is known later): they then take memory of their
  // own, not pieces of the temporaries' freed blocks, which the caller can hand back to the
  // driver whole when its next arrays need the room (at 5·10^8 2D points the pool holds 20 GB
  // of freed sort buffers after this, none larger than 8 GB: the 32 GB triangle store could
  // not be cut from them).
  SortedPoints<Exec> S;
  S.pts = ex.template alloc<double>(std::size_t(D * n));
  S.orig = ex.template alloc<std::int32_t>(std::size_t(n));
  auto keys = ex.template alloc<u64>(std::size_t(n));
  auto order = ex.template alloc<std::int32_t>(std::size_t(n));
  u64* k = keys.data();
  std::int32_t* o = order.data();
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        k[i] = spatial::hilbert_key<D>(r + D * i, sbox);
        o[i] = std::int32_t(i);
      });
  ex.sort_by_key(k, o, n);
  // Distinct points with equal keys (a curve cell holds several points) or duplicates: make
  // equal points adjacent by sorting on (key, coordinates), least significant first (stable
  // sorts keep input order within a run of equal points).
  auto same_key = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      n, GG_LAMBDA(std::int64_t i)->std::int64_t { return i > 0 && k[i] == k[i - 1] ? 1 : 0; },
      std::int64_t(0), prepare_detail::Sum{}, same_key.data());
  std::int64_t nsame = 0;
  ex.to_host(same_key.data(), 1, &nsame);
  const u64* sk = k;  // the keys in the final order
  typename Exec::template Buffer<u64> tmp;
  std::int64_t longest = 0;
  if (nsame) {  // (the longest run of equal keys)
    auto l = ex.template alloc<std::int64_t>(1);
    ex.transform_reduce_into(
        n, GG_LAMBDA(std::int64_t i)->std::int64_t { return prepare_detail::run_end(k, n, i) - i; },
        std::int64_t(0), prepare_detail::Max{}, l.data());
    ex.to_host(l.data(), 1, &longest);
  }
  if (nsame && longest <= prepare_detail::kShortRun) {
    // Short runs (points closer than a curve cell, or duplicates): each sorted by one thread,
    // in the order the passes below give, where those passes sort everything D + 1 times.
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          const std::int64_t e = prepare_detail::run_end(k, n, i);
          for (std::int64_t a = i + 1; a < e; ++a) {  // (insertion sort: short)
            const std::int32_t x = o[a];
            std::int64_t b = a;
            for (; b > i && prepare_detail::before<D>(r, x, o[b - 1]); --b) o[b] = o[b - 1];
            o[b] = x;
          }
        });
  } else if (nsame) {
    tmp = ex.template alloc<u64>(std::size_t(n));
    u64* t = tmp.data();
    sk = t;  // (the last pass leaves the curve keys in t)
    for (int pass = 0; pass <= D; ++pass) {
      ex.for_each_index(
          n, GG_LAMBDA(std::int64_t i) {
            const std::int32_t j = o[i];
            t[i] = pass < D ? ordered_key(r[D * std::int64_t(j) + (D - 1 - pass)] + 0.0)
                            : spatial::hilbert_key<D>(r + D * std::int64_t(j), sbox);
          });
      ex.sort_by_key(t, o, n);
    }
  }
  // Duplicates: a point equal to its predecessor in this order. Equal points have equal keys,
  // so the coordinates (scattered reads) are compared only within runs of equal keys.
  auto is_dup = GG_LAMBDA(std::int64_t i)->bool {
    if (i == 0 || sk[i] != sk[i - 1]) return false;
    const std::int64_t a = o[i], b = o[i - 1];
    for (int d = 0; d < D; ++d)
      if (r[D * a + d] != r[D * b + d]) return false;
    return true;
  };
  auto kept = ex.template alloc<std::int32_t>(std::size_t(n));
  const std::int64_t m = S.m = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return !is_dup(i); }, kept.data());
  S.duplicates = n - m;
  double* pts = S.pts.data();
  std::int32_t* orig = S.orig.data();
  const std::int32_t* kp = kept.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        const std::int32_t j = o[kp[i]];
        orig[i] = j;
        for (int d = 0; d < D; ++d) pts[D * i + d] = r[D * std::int64_t(j) + d] + 0.0;
      });
  // duplicate_of: the kept point of each run (its rank is the number of kept points up to and
  // including the position, minus one).
  if (S.duplicates) {
    auto rank = ex.template alloc<std::int32_t>(std::size_t(n));
    S.dup = ex.template alloc<std::int32_t>(std::size_t(n));
    std::int32_t* rk = rank.data();
    std::int32_t* dp = S.dup.data();
    ex.exclusive_scan_of(
        n, GG_LAMBDA(std::int64_t i)->std::int32_t { return is_dup(i) ? 0 : 1; }, rk);
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) { dp[o[i]] = is_dup(i) ? orig[rk[i] - 1] : -1; });
  }
  return S;
}

}  // namespace gpugeom::mesh
