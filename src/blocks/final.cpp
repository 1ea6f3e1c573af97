// Whether a block's stars are final, tested against every point (include/gpugeom/blocks.hpp:
// stars_final): the test of the multi-device triangulation, which holds all the points in one
// process. gpugeom.dask's blocks see only counts per bin of the points they lack, so their test
// bounds the balls' parts inside the hull by caps (python/gpugeom/dask/_ghost.py); here the
// points themselves are at hand, so a ball is final exactly when no point it holds is missing.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/predicates.hpp"
#include "blocks/circumball.hpp"
#include "blocks/final.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

namespace {

using blocks_detail::in_box;

using blocks_detail::BallParts;
using blocks_detail::cells_along;
using blocks_detail::centre_and_reach;
using blocks_detail::circumball_parts;
using blocks_detail::may_hold;
using blocks_detail::may_meet;

struct AllPoints {
  const double* xyz;
  const CellGrid& bins;
  const std::int64_t* order;
  const std::int64_t* cuts;
  const std::int64_t* held;  // sorted
  std::int64_t nheld;
  const double* extra_lo;  // further boxes the block holds every point of
  const double* extra_hi;
  std::int64_t nextra;
  double margin;
  // The points the scans may visit in all (< 0: no limit), and those visited so far.
  std::int64_t budget;
  std::atomic<std::int64_t>* visits;
  // Whether visiting `count` more points passes the budget (then the test answers "not final").
  bool spent(std::int64_t count) const {
    return budget >= 0 && visits->fetch_add(count, std::memory_order_relaxed) + count > budget;
  }
  // whether the block holds point x by its boxes (the region, then the extra boxes)
  bool boxed(const double* x, const BlockBoxes& b, int dim) const {
    if (in_box(x, b.region_lo, b.region_hi, dim)) return true;
    for (std::int64_t e = 0; e < nextra; ++e)
      if (in_box(x, extra_lo + e * dim, extra_hi + e * dim, dim)) return true;
    return false;
  }
};

// Whether point x lies in the closed circumball of the simplex v (positively oriented):
// exactly, as the ball's rounding bound is no verdict (the flat simplices along the hull have
// centres far outside and bounds that reach deep into the hull).
template <int D>
bool in_closed_ball(const double* const* v, const double* x) {
  if constexpr (D == 2)
    return incircle({v[0][0], v[0][1]}, {v[1][0], v[1][1]}, {v[2][0], v[2][1]}, {x[0], x[1]}) >= 0;
  else
    return insphere({v[0][0], v[0][1], v[0][2]}, {v[1][0], v[1][1], v[1][2]},
                    {v[2][0], v[2][1], v[2][2]}, {v[3][0], v[3][1], v[3][2]},
                    {x[0], x[1], x[2]}) >= 0;
}

// Whether the circumball of simplex v, within the ball (c, r) that bounds it, holds a point of
// `a` the block lacks within the box [lo, hi] (a slab of the bounds beyond its region): the bins
// the bound meets there, row by row, and their points outside the block's boxes, not held, and
// in the ball by the exact predicate. True also where the scans' budget is spent (no verdict:
// the block takes its second round, which needs no test). Along the last axis the bound's chord
// over the row limits the bins scanned, so a ball as large as the box costs its rows, not its bins.
template <int D>
bool holds_missing(const AllPoints& a, const BlockBoxes& b, const double* const* v,
                   const BallParts& ball, const double* c, double r, const double* lo,
                   const double* hi) {
  if (!may_meet<D>(ball, lo, hi, a.margin)) return false;
  const CellGrid& g = a.bins;
  double blo[D], bhi[D];
  for (int j = 0; j < D; ++j) {
    blo[j] = std::max(lo[j], c[j] - r);
    bhi[j] = std::min(hi[j], c[j] + r);
  }
  std::int64_t f[D], l[D];
  for (int j = 0; j < D - 1; ++j)
    if (!cells_along(blo[j], bhi[j], g, j, a.margin, true, &f[j], &l[j])) return false;
  const double r2 = r * r;
  // bin k's span along axis j
  auto span = [&](int j, std::int64_t k, double* s, double* e) {
    *s = g.lo[j] + double(k) * g.width[j];
    *e = g.lo[j] + double(k + 1) * g.width[j];
  };
  // the squared gap from the centre to bin k's slab along axis j (grown by the margin)
  auto gap2 = [&](int j, std::int64_t k) {
    if (!(g.width[j] > 0)) return 0.0;
    const double s = g.lo[j] + double(k) * g.width[j] - a.margin;
    const double e = g.lo[j] + double(k + 1) * g.width[j] + a.margin;
    const double d = std::max(std::max(s - c[j], c[j] - e), 0.0);
    return d * d;
  };
  // (the row's box: its bins' spans along the other axes, blo..bhi along the last)
  // Whether bins [first, last] hold no point: `cuts` are the bins' running counts, in the
  // grid's order, so a run of bins along the last axis, or whole rows, is one subtraction.
  auto none = [&](std::int64_t first, std::int64_t last) {
    return a.cuts[first] == a.cuts[last + 1];
  };
  auto scan = [&](std::int64_t row, double used, double* rlo, double* rhi) {
    const int j = D - 1;
    const std::int64_t base = row * g.counts[j];
    if (none(base, base + g.counts[j] - 1)) return false;
    const double half = std::sqrt(std::max(r2 - used, 0.0));
    std::int64_t s, e;
    if (!cells_along(std::max(blo[j], c[j] - half), std::min(bhi[j], c[j] + half), g, j, a.margin,
                     true, &s, &e))
      return false;
    rlo[j] = blo[j], rhi[j] = bhi[j];
    if (!may_meet<D>(ball, rlo, rhi, a.margin)) return false;
    for (std::int64_t k = s; k <= e; ++k) {
      // on to the next bin with points: the balls of the flat simplices along a curved hull
      // (points in a ball) span mostly empty space, 10^5-10^6 bins each at 10^7 points
      if (none(base + k, base + k)) {
        const std::int64_t* end = a.cuts + base + e + 2;
        const std::int64_t* next = std::upper_bound(a.cuts + base + k + 1, end, a.cuts[base + k]);
        if (next == end) break;
        k = std::int64_t(next - a.cuts) - base - 1;
      }
      span(j, k, &rlo[j], &rhi[j]);
      if (!may_meet<D>(ball, rlo, rhi, a.margin)) continue;
      const std::int64_t bin = base + k;
      if (a.spent(a.cuts[bin + 1] - a.cuts[bin])) return true;
      for (std::int64_t q = a.cuts[bin]; q < a.cuts[bin + 1]; ++q) {
        const std::int64_t p = a.order[q];
        const double* x = a.xyz + p * D;
        if (a.boxed(x, b, D)) continue;
        if (!may_hold<D>(ball, x) || !in_closed_ball<D>(v, x)) continue;
        if (!std::binary_search(a.held, a.held + a.nheld, p)) return true;
      }
    }
    return false;
  };
  double rlo[D], rhi[D];
  for (std::int64_t i = f[0]; i <= l[0]; ++i) {
    const double g0 = gap2(0, i);
    if (g0 > r2) continue;
    span(0, i, &rlo[0], &rhi[0]);
    if constexpr (D == 2) {
      if (scan(i, g0, rlo, rhi)) return true;
    } else {
      const std::int64_t n2 = g.counts[2];
      if (none((i * g.counts[1] + f[1]) * n2, (i * g.counts[1] + l[1] + 1) * n2 - 1)) continue;
      for (std::int64_t k = f[1]; k <= l[1]; ++k) {
        const double g1 = g0 + gap2(1, k);
        if (g1 > r2) continue;
        span(1, k, &rlo[1], &rhi[1]);
        if (scan(i * g.counts[1] + k, g1, rlo, rhi)) return true;
      }
    }
  }
  return false;
}

// The slabs less the extra boxes the block holds every point of: where a box covers a slab
// along every axis but one and reaches past one end of it there, that part is cut off the slab
// (its points would all be skipped as held), and a slab a box covers whole is dropped. The
// strips along the bounds' sides are such boxes: without the cut, the flat simplices along the
// hull, whose balls are huge but whose parts inside the hull are thin lenses within the strips,
// visited every point of a side (at 10^7 points 4.5 s of a block's test on the H200's host).
// The slabs stay closed boxes: a point on a cut is both in the box and in what is left, and is
// skipped as held there.
template <int D>
void cut_held_boxes(blocks_detail::Slabs& slabs, const AllPoints& a) {
  int kept = 0;
  for (int s = 0; s < slabs.count; ++s) {
    double* lo = slabs.lo[s];
    double* hi = slabs.hi[s];
    bool empty = false;
    for (std::int64_t e = 0; e < a.nextra && !empty; ++e) {
      const double* elo = a.extra_lo + e * D;
      const double* ehi = a.extra_hi + e * D;
      int open = -1, count = 0;  // the axes along which box e does not cover the slab
      for (int j = 0; j < D; ++j)
        if (elo[j] > lo[j] || ehi[j] < hi[j]) open = j, ++count;
      if (count == 0) {
        empty = true;
      } else if (count == 1) {
        const int j = open;
        if (elo[j] <= lo[j] && ehi[j] >= lo[j])
          lo[j] = ehi[j];
        else if (ehi[j] >= hi[j] && elo[j] <= hi[j])
          hi[j] = elo[j];
        empty = lo[j] > hi[j];
      }
    }
    if (empty) continue;
    for (int j = 0; j < D; ++j) slabs.lo[kept][j] = lo[j], slabs.hi[kept][j] = hi[j];
    ++kept;
  }
  slabs.count = kept;
}

template <int D, class I>
bool run(const double* pts, const I* simplices, std::int64_t m, const std::uint8_t* test,
         const BlockBoxes& b, const AllPoints& a) {
  blocks_detail::Slabs slabs = blocks_detail::slabs_of(b, D);
  cut_held_boxes<D>(slabs, a);
  std::atomic<bool> ok{true};
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < m; ++i) {
    if (!test[i] || !ok.load(std::memory_order_relaxed)) continue;
    double c[D], r;
    BallParts ball;
    if (!circumball_parts<D>(pts, simplices + i * (D + 1), &ball) ||
        !centre_and_reach<D>(ball, b.scale, c, &r)) {
      ok.store(false, std::memory_order_relaxed);  // a centre not trusted: not a verdict
      continue;
    }
    if (blocks_detail::misses(slabs, c, r, D)) continue;
    const double* v[D + 1];
    for (int k = 0; k <= D; ++k) v[k] = pts + std::int64_t(simplices[i * (D + 1) + k]) * D;
    for (int s = 0; s < slabs.count; ++s)
      if (holds_missing<D>(a, b, v, ball, c, r, slabs.lo[s], slabs.hi[s])) {
        ok.store(false, std::memory_order_relaxed);
        break;
      }
  }
  return ok.load();
}

template <class I>
bool stars_final_impl(const double* points, int dim, const I* simplices, std::int64_t m,
                      const std::uint8_t* test, const BlockBoxes& boxes, const double* all,
                      const CellGrid& bins, const std::int64_t* order, const std::int64_t* cuts,
                      const std::int64_t* held, std::int64_t nheld, const double* extra_lo,
                      const double* extra_hi, std::int64_t nextra, int threads,
                      std::int64_t budget) {
  blocks_detail::check_dim(dim, "stars_final");
  blocks_detail::ThreadScope scope(threads);
  std::atomic<std::int64_t> visits{0};
  const AllPoints a{all,    bins,     order,    cuts,   held,
                    nheld,  extra_lo, extra_hi, nextra, 1e-9 * boxes.scale,
                    budget, &visits};
  return dim == 2 ? run<2>(points, simplices, m, test, boxes, a)
                  : run<3>(points, simplices, m, test, boxes, a);
}

}  // namespace

bool stars_final(const double* points, int dim, const std::int32_t* simplices, std::int64_t m,
                 const std::uint8_t* test, const BlockBoxes& boxes, const double* all,
                 const CellGrid& bins, const std::int64_t* order, const std::int64_t* cuts,
                 const std::int64_t* held, std::int64_t nheld, const double* extra_lo,
                 const double* extra_hi, std::int64_t nextra, int threads) {
  return stars_final_impl(points, dim, simplices, m, test, boxes, all, bins, order, cuts, held,
                          nheld, extra_lo, extra_hi, nextra, threads, -1);
}

bool blocks_detail::stars_final_within(const double* points, int dim, const std::int32_t* simplices,
                                       std::int64_t m, const std::uint8_t* test,
                                       const BlockBoxes& boxes, const double* all,
                                       const CellGrid& bins, const std::int64_t* order,
                                       const std::int64_t* cuts, const std::int64_t* held,
                                       std::int64_t nheld, const double* extra_lo,
                                       const double* extra_hi, std::int64_t nextra, int threads,
                                       std::int64_t budget) {
  return stars_final_impl(points, dim, simplices, m, test, boxes, all, bins, order, cuts, held,
                          nheld, extra_lo, extra_hi, nextra, threads, budget);
}

}  // namespace gpugeom
