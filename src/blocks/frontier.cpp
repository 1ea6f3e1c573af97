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
#include <cstdint>
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
  Shape(const CellGrid& g, int dim) {
    for (int j = 0; j < dim; ++j) n[j] = g.counts[j];
    total = n[0] * n[1] * n[2];
  }
  std::int64_t at(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return (i * n[1] + j) * n[2] + k;
  }
  // calls f(neighbour) for each bin sharing a side, an edge or a corner with bin b
  template <class F>
  void around(std::int64_t b, F&& f) const {
    const std::int64_t k = b % n[2], j = (b / n[2]) % n[1], i = b / (n[1] * n[2]);
    for (std::int64_t a = std::max<std::int64_t>(i - 1, 0); a <= std::min(i + 1, n[0] - 1); ++a)
      for (std::int64_t c = std::max<std::int64_t>(j - 1, 0); c <= std::min(j + 1, n[1] - 1); ++c)
        for (std::int64_t e = std::max<std::int64_t>(k - 1, 0); e <= std::min(k + 1, n[2] - 1); ++e)
          if (a != i || c != j || e != k) f(at(a, c, e));
  }
};

// Per empty bin its component of empty bins (sides, edges and corners connect), numbered in
// the order of their lowest bin; -1 for an occupied bin. One sweep with a stack: the labels do
// not depend on anything but the counts.
std::vector<std::int32_t> label_empty(const std::int32_t* counts, const Shape& s,
                                      std::int32_t* components) {
  std::vector<std::int32_t> label(std::size_t(s.total), -1);
  std::vector<std::int64_t> stack;
  std::int32_t next = 0;
  for (std::int64_t b = 0; b < s.total; ++b) {
    if (counts[b] != 0 || label[std::size_t(b)] >= 0) continue;
    label[std::size_t(b)] = next;
    stack.push_back(b);
    while (!stack.empty()) {
      const std::int64_t c = stack.back();
      stack.pop_back();
      s.around(c, [&](std::int64_t e) {
        if (counts[e] == 0 && label[std::size_t(e)] < 0) {
          label[std::size_t(e)] = next;
          stack.push_back(e);
        }
      });
    }
    ++next;
  }
  *components = next;
  return label;
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
  // The occupied bins with an empty bin round them, increasing (in parallel: 10^6 bins and
  // more at 10^7 points), then per such bin the components of those empty bins (CSR; only these
  // bins are looked at per block).
  auto near_empty = [&](std::int64_t b) {
    if (counts[b] == 0) return false;
    bool any = false;
    s.around(b, [&](std::int64_t e) { any = any || counts[e] == 0; });
    return any;
  };
  std::vector<std::int64_t> beside;
  blocks_detail::ordered_compact(
      s.total, near_empty, [&](std::int64_t total) { beside.resize(std::size_t(total)); },
      [&](std::int64_t b, std::int64_t r) { beside[std::size_t(r)] = b; });
  std::vector<std::int64_t> start{0};
  std::vector<std::int32_t> comps;
  for (const std::int64_t b : beside) {
    const std::size_t first = comps.size();
    s.around(b, [&](std::int64_t e) {
      const std::int32_t l = label[std::size_t(e)];
      if (l >= 0 && std::find(comps.begin() + std::ptrdiff_t(first), comps.end(), l) == comps.end())
        comps.push_back(l);
    });
    start.push_back(std::int64_t(comps.size()));
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
      auto interior = [&](std::int64_t b) {
        const std::int64_t k = b % s.n[2], j = (b / s.n[2]) % s.n[1], i = b / (s.n[1] * s.n[2]);
        const std::int64_t at[3] = {i, j, k};
        for (int a = 0; a < dim; ++a)
          if (at[a] <= first[a] || at[a] >= last[a]) return false;
        return true;
      };
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
        auto near = [&](std::int64_t b) {
          const std::int64_t at[3] = {b / (s.n[1] * s.n[2]), (b / s.n[2]) % s.n[1], b % s.n[2]};
          for (int a = 0; a < dim; ++a)
            if (at[a] < near_lo[a] || at[a] > near_hi[a]) return false;
          return true;
        };
        std::size_t kept = 0;
        held = 0;
        for (const std::int64_t b : mine)
          if (near(b)) mine[kept++] = b, held += counts[b];
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
