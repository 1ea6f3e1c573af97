// The bins beside empty space that a block takes in its first round (include/gpugeom/blocks.hpp:
// empty_frontiers). A block's first round holds its region (its cell grown by the ghost width);
// a simplex whose ball reaches past the region is final only where the ball meets no bin with a
// point the block lacks. Where the points leave empty space (between clusters, round a ball or
// a Gaussian's tail), the Delaunay balls of the points near it span that space and end on the
// points across it, which no ghost layer of a few spacings holds: the block failed its test and
// was triangulated a second time. Those points are the occupied bins next to the empty bins the
// region reaches through empty space; holding them (about 1 % of the points for 64 clusters in
// 2D, docs/performance.md) makes the first round enough. Only a heuristic of what to hold: the
// finality test still decides, and a block that fails takes its second round as before.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

namespace {

// The grid's shape as three axes (a 2D grid has one bin along the third).
struct Shape {
  std::int64_t n[3] = {1, 1, 1}, total = 1;
  int last = 0;  // the axis along which bins follow each other (rows)
  Shape(const CellGrid& g, int dim) : last(dim - 1) {
    for (int j = 0; j < dim; ++j) n[j] = g.counts[j];
    total = n[0] * n[1] * n[2];
  }
  std::int64_t at(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (i * n[1] + j) * n[2] + k;
  }
  // bin b's place along each axis
  void coords(std::int64_t b, std::int64_t x[3]) const {
    x[2] = b % n[2];
    x[1] = (b / n[2]) % n[1];
    x[0] = b / (n[1] * n[2]);
  }
  // whether bin b lies within bins lo..hi along each of the first dim axes
  bool within(std::int64_t b, const std::int64_t* lo, const std::int64_t* hi, int dim) const {
    std::int64_t x[3];
    coords(b, x);
    for (int a = 0; a < dim; ++a)
      if (x[a] < lo[a] || x[a] > hi[a]) return false;
    return true;
  }
  // calls f(b, x) for every bin b, at x, with the rows shared among the threads of the
  // enclosing parallel region (an omp for: the place is worked out once a row, not once a bin)
  template <class F>
  void each(F&& f) const {
    const std::int64_t len = n[last];
#pragma omp for schedule(static)
    for (std::int64_t r = 0; r < total / len; ++r) {
      std::int64_t x[3];
      coords(r * len, x);
      for (std::int64_t t = 0; t < len; ++t) {
        x[last] = t;
        f(r * len + t, x);
      }
    }
  }
  // calls f(neighbour) for each bin sharing a side, an edge or a corner with the bin at x
  template <class F>
  void around(const std::int64_t x[3], F&& f) const {
    const std::int64_t i = x[0], j = x[1], k = x[2];
    for (std::int64_t a = std::max<std::int64_t>(i - 1, 0); a <= std::min(i + 1, n[0] - 1); ++a)
      for (std::int64_t c = std::max<std::int64_t>(j - 1, 0); c <= std::min(j + 1, n[1] - 1); ++c)
        for (std::int64_t e = std::max<std::int64_t>(k - 1, 0); e <= std::min(k + 1, n[2] - 1); ++e)
          if (a != i || c != j || e != k) f(at(a, c, e));
  }
};

// A forest over the empty bins where every link goes from a higher bin to a lower one of the
// same component, so a tree's root is its component's lowest bin whatever order the threads
// link in (parents only fall; a bin that stops being a root never is one again, which is why
// the halving stores below, of an ancestor, are safe without a compare-and-swap).
template <class Index>
class LowestRoots {
 public:
  explicit LowestRoots(std::int64_t n) : up_(new std::atomic<Index>[std::size_t(n)]) {}
  void reset(std::int64_t b) { up_[b].store(Index(b), std::memory_order_relaxed); }
  Index root(Index x) {
    Index q = up_[x].load(std::memory_order_relaxed);
    while (q != x) {
      const Index g = up_[q].load(std::memory_order_relaxed);
      if (g != q) up_[x].store(g, std::memory_order_relaxed);
      x = q;
      q = g;
    }
    return x;
  }
  void join(Index a, Index b) {
    for (;;) {
      a = root(a);
      b = root(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      Index expected = a;  // a may have been linked meanwhile: then look again
      if (up_[a].compare_exchange_weak(expected, b, std::memory_order_relaxed)) return;
    }
  }
  // once every join is done: x's parent its root (halving alone leaves paths of several steps)
  void flatten(Index x) { up_[x].store(root(x), std::memory_order_relaxed); }
  Index parent(std::int64_t b) const { return up_[b].load(std::memory_order_relaxed); }

 private:
  std::unique_ptr<std::atomic<Index>[]> up_;
};

// Per empty bin its component of empty bins (sides, edges and corners connect), numbered in
// the order of their lowest bin; -1 for an occupied bin. In parallel (the sweep with a stack it
// replaced took 45-57 ms of one core for the 1.25·10^6 bins of 2·10^7 Gaussian points, most of
// them empty): each empty bin joins its lower empty neighbours, then the roots (the components'
// lowest bins) are numbered in increasing order, so the labels depend on the counts alone.
template <class Index>
std::vector<std::int32_t> label_with(const std::int32_t* counts, const Shape& s,
                                     std::int32_t* components) {
  std::vector<std::int32_t> label(std::size_t(s.total), -1);
  LowestRoots<Index> f(s.total);
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (std::int64_t b = 0; b < s.total; ++b)
      if (counts[b] == 0) f.reset(b);
    s.each([&](std::int64_t b, const std::int64_t* x) {
      if (counts[b] == 0)
        s.around(x, [&](std::int64_t e) {
          if (e < b && counts[e] == 0) f.join(Index(b), Index(e));
        });
    });
#pragma omp for schedule(static)
    for (std::int64_t b = 0; b < s.total; ++b)
      if (counts[b] == 0) f.flatten(Index(b));
  }
  *components = std::int32_t(blocks_detail::ordered_compact(
      s.total, [&](std::int64_t b) { return counts[b] == 0 && f.parent(b) == Index(b); },
      [](std::int64_t) {},
      [&](std::int64_t b, std::int64_t r) { label[std::size_t(b)] = std::int32_t(r); }));
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < s.total; ++b)
    if (counts[b] == 0 && f.parent(b) != Index(b))
      label[std::size_t(b)] = label[std::size_t(f.parent(b))];
  return label;
}

std::vector<std::int32_t> label_empty(const std::int32_t* counts, const Shape& s,
                                      std::int32_t* components) {
  if (s.total <= std::numeric_limits<std::int32_t>::max())
    return label_with<std::int32_t>(counts, s, components);
  return label_with<std::int64_t>(counts, s, components);
}

// The components of the empty bins round bin b (at most 26, each once) into out; their count.
int components_around(const Shape& s, const std::vector<std::int32_t>& label,
                      const std::int64_t x[3], std::int32_t* out) {
  int m = 0;
  s.around(x, [&](std::int64_t e) {
    const std::int32_t l = label[std::size_t(e)];
    if (l >= 0 && std::find(out, out + m, l) == out + m) out[m++] = l;
  });
  return m;
}

}  // namespace

BlockFrontiers empty_frontiers(const std::int32_t* counts, const CellGrid& bins, int dim,
                               const double* region_lo, const double* region_hi,
                               std::int64_t nblocks, std::int64_t cap, double band, int threads) {
  blocks_detail::check_dim(dim, "empty_frontiers");
  for (int j = 0; j < dim; ++j)
    if (bins.counts[j] < 1)
      throw Error(ErrorCode::InvalidArgument, "empty_frontiers: every axis needs a bin, got " +
                                                  std::to_string(bins.counts[j]) + " along axis " +
                                                  std::to_string(j));
  blocks_detail::ThreadScope scope(threads);
  const Shape s(bins, dim);
  BlockFrontiers out;
  out.grid = bins;
  out.offsets.assign(std::size_t(nblocks) + 1, 0);
  out.points.assign(std::size_t(nblocks), 0);
  // (uniform points at 16 a bin have none: no sweep, no pass over the occupied bins)
  std::int64_t empty = 0;
#pragma omp parallel for schedule(static) reduction(+ : empty)
  for (std::int64_t b = 0; b < s.total; ++b) empty += counts[b] == 0 ? 1 : 0;
  if (empty == 0 || nblocks <= 0) return out;
  std::int32_t ncomp = 0;
  const std::vector<std::int32_t> label = label_empty(counts, s, &ncomp);
  // The occupied bins with an empty bin round them, increasing, and per such bin the
  // components of those empty bins (CSR; only these bins are looked at per block). In parallel:
  // 10^6 bins and more at 10^7 points.
  std::vector<std::uint8_t> around(std::size_t(s.total), 0);
#pragma omp parallel
  s.each([&](std::int64_t b, const std::int64_t* x) {
    std::int32_t l[26];
    if (counts[b] != 0) around[std::size_t(b)] = std::uint8_t(components_around(s, label, x, l));
  });
  std::vector<std::int64_t> beside;
  blocks_detail::ordered_compact(
      s.total, [&](std::int64_t b) { return around[std::size_t(b)] != 0; },
      [&](std::int64_t total) { beside.resize(std::size_t(total)); },
      [&](std::int64_t b, std::int64_t r) { beside[std::size_t(r)] = b; });
  std::vector<std::int64_t> start(beside.size() + 1, 0);
  for (std::size_t q = 0; q < beside.size(); ++q)
    start[q + 1] = start[q] + around[std::size_t(beside[q])];
  std::vector<std::int32_t> comps(std::size_t(start.back()));
#pragma omp parallel for schedule(static)
  for (std::int64_t q = 0; q < std::int64_t(beside.size()); ++q) {
    std::int64_t x[3];
    s.coords(beside[std::size_t(q)], x);
    components_around(s, label, x, comps.data() + start[std::size_t(q)]);
  }
  std::vector<std::vector<std::int64_t>> lists(static_cast<std::size_t>(nblocks));
#pragma omp parallel
  {
    std::vector<std::uint8_t> seed(static_cast<std::size_t>(ncomp));
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t blk = 0; blk < nblocks; ++blk) {
      // the region's bins along each axis; those strictly inside it hold only points the
      // region holds anyway
      std::int64_t first[3] = {0, 0, 0}, last[3] = {0, 0, 0};
      bool any = true;
      for (int j = 0; j < dim; ++j)
        any = any && blocks_detail::cells_along(region_lo[blk * dim + j], region_hi[blk * dim + j],
                                                bins, j, 0.0, false, &first[j], &last[j]);
      if (!any) continue;
      // the components the region reaches: those of its empty bins
      std::fill(seed.begin(), seed.end(), std::uint8_t(0));
      bool reached = false;
      for (std::int64_t i = first[0]; i <= last[0]; ++i)
        for (std::int64_t j = first[1]; j <= last[1]; ++j)
          for (std::int64_t k = first[2]; k <= last[2]; ++k) {
            const std::int32_t l = label[std::size_t(s.at(i, j, k))];
            if (l >= 0) seed[std::size_t(l)] = 1, reached = true;
          }
      if (!reached) continue;
      std::int64_t inner_lo[3], inner_hi[3];
      for (int j = 0; j < dim; ++j) inner_lo[j] = first[j] + 1, inner_hi[j] = last[j] - 1;
      auto interior = [&](std::int64_t b) { return s.within(b, inner_lo, inner_hi, dim); };
      auto& mine = lists[std::size_t(blk)];
      std::int64_t held = 0;
      for (std::size_t q = 0; q < beside.size(); ++q) {
        const std::int64_t b = beside[q];
        bool hit = false;
        for (std::int64_t c = start[q]; c < start[q + 1] && !hit; ++c)
          hit = seed[std::size_t(comps[std::size_t(c)])] != 0;
        if (!hit || interior(b)) continue;
        mine.push_back(b);
        held += counts[b];
      }
      // Past the cap, only the bins within `band` of the region (a ball's surface all round
      // is beside one empty space: each block needs the part near it); past the cap still,
      // none (points on a sphere: every bin is beside empty space), and the block takes its
      // second round where it needs one.
      if (held > cap && band > 0) {
        std::int64_t near_lo[3] = {0, 0, 0}, near_hi[3] = {0, 0, 0};
        for (int j = 0; j < dim; ++j)
          blocks_detail::cells_along(region_lo[blk * dim + j] - band,
                                     region_hi[blk * dim + j] + band, bins, j, 0.0, true,
                                     &near_lo[j], &near_hi[j]);
        std::size_t kept = 0;
        held = 0;
        for (const std::int64_t b : mine)
          if (s.within(b, near_lo, near_hi, dim)) mine[kept++] = b, held += counts[b];
        mine.resize(kept);
      }
      if (held > cap) {
        mine.clear();
        held = 0;
      }
      out.points[std::size_t(blk)] = held;
    }
  }
  for (std::int64_t blk = 0; blk < nblocks; ++blk)
    out.offsets[std::size_t(blk) + 1] =
        out.offsets[std::size_t(blk)] + std::int64_t(lists[std::size_t(blk)].size());
  out.bins.resize(std::size_t(out.offsets[std::size_t(nblocks)]));
  for (std::int64_t blk = 0; blk < nblocks; ++blk)
    std::copy(lists[std::size_t(blk)].begin(), lists[std::size_t(blk)].end(),
              out.bins.begin() + std::ptrdiff_t(out.offsets[std::size_t(blk)]));
  return out;
}

}  // namespace gpugeom
