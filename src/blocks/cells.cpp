// Points to the blocks of gpugeom.dask's grid (include/gpugeom/blocks.hpp): each point to the
// block of its cell and to every other block with a box holding it, in one pass, where NumPy made
// a temporary array per axis and comparison and sorted the cells (an argsort of 10^7 int64 cells
// took 0.7 s), and a second task per pair of blocks selected the ghosts from the owner's points.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

namespace {

using blocks_detail::in_box;

using blocks_detail::cell_of;

// A finer grid of bins over the cells (`sub` bins a cell along each axis that is not flat), each
// with the boxes that may hold one of its points (CSR, each list in increasing box order, so by
// block, as the boxes come): a point tests only its bin's boxes, so away from the boxes' sides
// none (with a list per cell, each point tested every side strip of its row of cells: 88 ns a
// point). A superset: the exact test per point is what counts.
struct BoxBins {
  CellGrid bins;
  HostVector<std::int64_t> start, list;

  BoxBins(const CellGrid& g, int dim, const double* box_lo, const double* box_hi,
          std::int64_t nboxes) {
    std::int64_t cells = 1;
    for (int j = 0; j < dim; ++j) cells *= g.counts[j];
    // 16 (2D) or 8 (3D) bins a cell along each axis, fewer where that passes 2^18 bins
    std::int64_t sub = dim == 2 ? 16 : 8;
    while (sub > 1 && cells * (dim == 2 ? sub * sub : sub * sub * sub) > (std::int64_t(1) << 18))
      sub /= 2;
    std::int64_t total = 1;
    for (int j = 0; j < dim; ++j) {
      const bool flat = !(g.width[j] > 0);
      bins.lo[j] = g.lo[j];
      bins.counts[j] = flat ? 1 : g.counts[j] * sub;
      bins.width[j] = flat ? 0.0 : g.width[j] / double(sub);
      total *= bins.counts[j];
    }
    // each box's range of bins along each axis, grown by a margin far above the rounding of a
    // point's bin and by a bin on each side
    auto range = [&](std::int64_t b, int j, std::int64_t* first, std::int64_t* last) {
      const std::int64_t k = bins.counts[j];
      if (!(bins.width[j] > 0)) {
        *first = 0, *last = 0;
        return;
      }
      const double margin = 1e-9 * (std::abs(g.lo[j]) + double(g.counts[j]) * g.width[j]);
      auto at = [&](double x) {
        const double f = std::floor((x - bins.lo[j]) / bins.width[j]);
        return !(f >= 0) ? std::int64_t(0) : (f > double(k - 1) ? k - 1 : std::int64_t(f));
      };
      *first = at(box_lo[b * dim + j] - margin);
      *last = at(box_hi[b * dim + j] + margin);
    };
    start.assign(std::size_t(total + 1), 0);
    for (int pass = 0; pass < 2; ++pass) {
      HostVector<std::int64_t> next;
      if (pass == 1) {
        for (std::int64_t c = 0; c < total; ++c) start[std::size_t(c + 1)] += start[std::size_t(c)];
        list.resize(std::size_t(start[std::size_t(total)]));
        next.assign(start.begin(), start.end() - 1);
      }
      for (std::int64_t b = 0; b < nboxes; ++b) {
        std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
        bool empty = false;
        for (int j = 0; j < dim; ++j) {
          range(b, j, &lo[j], &hi[j]);
          empty = empty || !(box_lo[b * dim + j] <= box_hi[b * dim + j]);
        }
        if (empty) continue;
        for (std::int64_t i0 = lo[0]; i0 <= hi[0]; ++i0)
          for (std::int64_t i1 = lo[1]; i1 <= hi[1]; ++i1)
            for (std::int64_t i2 = lo[2]; i2 <= hi[2]; ++i2) {
              std::int64_t c = i0 * bins.counts[1] + i1;
              if (dim == 3) c = c * bins.counts[2] + i2;
              if (pass == 0)
                ++start[std::size_t(c + 1)];
              else
                list[std::size_t(next[std::size_t(c)]++)] = b;
            }
      }
    }
  }
};

// BlockFrontiers turned round: per bin of their grid the blocks that take it (CSR, by block).
struct FrontierBins {
  HostVector<std::int64_t> start, blocks;

  FrontierBins(const BlockFrontiers* f, int dim, std::int64_t nblocks) {
    if (!f) return;
    std::int64_t total = 1;
    for (int j = 0; j < dim; ++j) total *= f->grid.counts[j];
    if (std::int64_t(f->offsets.size()) != nblocks + 1 ||
        std::int64_t(f->bins.size()) != f->offsets[std::size_t(nblocks)])
      throw Error(ErrorCode::InvalidArgument,
                  "split_to_blocks: the frontiers are for " +
                      std::to_string(std::int64_t(f->offsets.size()) - 1) +
                      " blocks (or their offsets do not end at their bins' count), the grid has " +
                      std::to_string(nblocks));
    start.assign(std::size_t(total) + 1, 0);
    for (const std::int64_t b : f->bins) {
      if (b < 0 || b >= total)
        throw Error(ErrorCode::InvalidArgument, "split_to_blocks: frontier bin " +
                                                    std::to_string(b) + " outside a grid of " +
                                                    std::to_string(total));
      ++start[std::size_t(b) + 1];
    }
    for (std::int64_t b = 0; b < total; ++b) start[std::size_t(b + 1)] += start[std::size_t(b)];
    blocks.resize(f->bins.size());
    HostVector<std::int64_t> next(start.begin(), start.end() - 1);
    for (std::int64_t blk = 0; blk < nblocks; ++blk)
      for (std::int64_t q = f->offsets[std::size_t(blk)]; q < f->offsets[std::size_t(blk) + 1]; ++q)
        blocks[std::size_t(next[std::size_t(f->bins[std::size_t(q)])]++)] = blk;
  }
};

}  // namespace

PointBounds point_bounds(const double* points, int dim, std::int64_t n, int threads) {
  blocks_detail::check_dim(dim, "point_bounds");
  blocks_detail::ThreadScope scope(threads);
  const double inf = std::numeric_limits<double>::infinity();
  PointBounds out;
  for (int j = 0; j < dim; ++j) out.lo[j] = inf, out.hi[j] = -inf;
  std::int64_t bad = n;
#pragma omp parallel
  {
    double lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf};
    std::int64_t first = n;
#pragma omp for schedule(static) nowait
    for (std::int64_t p = 0; p < n; ++p)
      for (int j = 0; j < dim; ++j) {
        const double x = points[p * dim + j];
        if (!std::isfinite(x)) first = std::min(first, p);
        lo[j] = std::min(lo[j], x);  // (a NaN x leaves lo as it is; the point is bad anyway)
        hi[j] = std::max(hi[j], x);
      }
#pragma omp critical(gpugeom_point_bounds)
    {
      bad = std::min(bad, first);
      for (int j = 0; j < dim; ++j)
        out.lo[j] = std::min(out.lo[j], lo[j]), out.hi[j] = std::max(out.hi[j], hi[j]);
    }
  }
  out.first_bad = bad < n ? bad : -1;
  return out;
}

CellSplit split_to_blocks(const double* points, int dim, std::int64_t n, const CellGrid& grid,
                          const double* box_lo, const double* box_hi, const std::int64_t* box_block,
                          std::int64_t nboxes, const std::uint8_t* wanted, int threads,
                          const BlockFrontiers* frontiers) {
  blocks_detail::check_dim(dim, "split_to_blocks");
  std::int64_t cells = 1;
  for (int j = 0; j < dim; ++j) cells *= grid.counts[j];
  for (std::int64_t b = 0; b < nboxes; ++b)
    if (box_block[b] < 0 || box_block[b] >= cells)
      throw Error(ErrorCode::InvalidArgument, "split_to_blocks: box " + std::to_string(b) +
                                                  " names block " + std::to_string(box_block[b]) +
                                                  " of a grid of " + std::to_string(cells));
  for (std::int64_t b = 1; b < nboxes; ++b)
    if (box_block[b] < box_block[b - 1])
      throw Error(ErrorCode::InvalidArgument, "split_to_blocks: the boxes must come by block");
  blocks_detail::ThreadScope scope(threads);
  const BoxBins bins(grid, dim, box_lo, box_hi, nboxes);
  const FrontierBins fr(frontiers, dim, cells);
  CellSplit out;
  out.cell.resize(std::size_t(n));
  // Each thread takes a contiguous range of points, counts them per block, then writes them at
  // its offsets: every block's points come out in increasing order, on any thread count.
  const int nt = std::max(1, omp_get_max_threads());
  // (each thread zeroes its own row: at 10^7 points in bins of 16 the rows are 80 MB)
  HostVector<std::int64_t> counts(std::size_t(nt) * std::size_t(cells));
  HostVector<std::int64_t> total(std::size_t(cells) + 1);
  // calls f(block) for each block point p goes to: its cell's, then those of the boxes holding
  // it (a block's boxes come together: once one holds p, the block's others are skipped)
  auto visit = [&](std::int64_t p, auto&& f) {
    const double* x = points + p * dim;
    const std::int64_t c = out.cell[std::size_t(p)];
    if (!wanted || wanted[c]) f(c);
    if (nboxes == 0 && !frontiers) return;
    const std::int64_t bin = cell_of(x, bins.bins, dim);
    // whether a box of block blk holds p (the boxes of a bin come by block)
    auto boxed = [&](std::int64_t blk) {
      for (std::int64_t q = bins.start[std::size_t(bin)]; q < bins.start[std::size_t(bin + 1)];
           ++q) {
        const std::int64_t b = bins.list[std::size_t(q)];
        if (box_block[b] == blk && in_box(x, box_lo + b * dim, box_hi + b * dim, dim)) return true;
      }
      return false;
    };
    std::int64_t last = -1;
    for (std::int64_t q = bins.start[std::size_t(bin)]; q < bins.start[std::size_t(bin + 1)]; ++q) {
      const std::int64_t b = bins.list[std::size_t(q)], blk = box_block[b];
      if (blk == last || blk == c || (wanted && !wanted[blk])) continue;
      if (in_box(x, box_lo + b * dim, box_hi + b * dim, dim)) {
        f(blk);
        last = blk;
      }
    }
    if (!frontiers) return;
    const std::int64_t fb = cell_of(x, frontiers->grid, dim);
    for (std::int64_t q = fr.start[std::size_t(fb)]; q < fr.start[std::size_t(fb + 1)]; ++q) {
      const std::int64_t blk = fr.blocks[std::size_t(q)];
      if (blk != c && (!wanted || wanted[blk]) && !boxed(blk)) f(blk);
    }
  };
#pragma omp parallel num_threads(nt)
  {
    // the ranges by the threads the region has (it may get fewer than asked for)
    const int t = omp_get_thread_num(), threads_here = omp_get_num_threads();
    const std::int64_t first = n * t / threads_here, end = n * (t + 1) / threads_here;
    std::int64_t* mine = counts.data() + std::size_t(t) * std::size_t(cells);
    std::fill(mine, mine + cells, std::int64_t(0));
    for (std::int64_t p = first; p < end; ++p) {
      out.cell[std::size_t(p)] = cell_of(points + p * dim, grid, dim);
      visit(p, [&](std::int64_t b) { ++mine[b]; });
    }
#pragma omp barrier
    // offsets: block by block, and within a block thread by thread (in parallel over the blocks:
    // with a bin a block, 10^6 bins of 16 threads each, one thread took 0.1-0.3 s here)
#pragma omp for schedule(static)
    for (std::int64_t b = 0; b < cells; ++b) {
      std::int64_t sum = 0;
      for (int u = 0; u < threads_here; ++u)
        sum += counts[std::size_t(u) * std::size_t(cells) + std::size_t(b)];
      total[std::size_t(b)] = sum;
    }
#pragma omp single
    {
      out.cuts.resize(std::size_t(cells + 1));
      std::int64_t at = 0;
      for (std::int64_t b = 0; b < cells; ++b) {
        out.cuts[std::size_t(b)] = at;
        at += total[std::size_t(b)];
      }
      out.cuts[std::size_t(cells)] = at;
      out.order.resize(std::size_t(at));
    }
#pragma omp for schedule(static)
    for (std::int64_t b = 0; b < cells; ++b) {
      std::int64_t at = out.cuts[std::size_t(b)];
      for (int u = 0; u < threads_here; ++u) {
        std::int64_t& k = counts[std::size_t(u) * std::size_t(cells) + std::size_t(b)];
        const std::int64_t here = k;
        k = at;
        at += here;
      }
    }
    for (std::int64_t p = first; p < end; ++p)
      visit(p, [&](std::int64_t b) { out.order[std::size_t(mine[b]++)] = p; });
  }
  return out;
}

HostVector<std::int32_t> cell_counts(const double* points, int dim, std::int64_t n,
                                     const CellGrid& grid, int threads) {
  blocks_detail::check_dim(dim, "cell_counts");
  std::int64_t cells = 1;
  for (int j = 0; j < dim; ++j) cells *= grid.counts[j];
  if (n > std::int64_t(INT32_MAX) || cells > (std::int64_t(1) << 28))
    throw Error(ErrorCode::InvalidArgument,
                "cell_counts: at most 2^31 - 1 points and 2^28 cells, got " + std::to_string(n) +
                    " and " + std::to_string(cells));
  blocks_detail::ThreadScope scope(threads);
  HostVector<std::int32_t> out;
  out.assign(std::size_t(cells), 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const std::int64_t c = cell_of(points + p * dim, grid, dim);
#pragma omp atomic
    ++out[std::size_t(c)];
  }
  return out;
}

void gather_blocks(const double* points, int dim, CellSplit& split, int threads) {
  blocks_detail::check_dim(dim, "gather_blocks");
  blocks_detail::ThreadScope scope(threads);
  const std::int64_t total = std::int64_t(split.order.size());
  split.points.resize(std::size_t(total) * std::size_t(dim));
  split.cells.resize(std::size_t(total));
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < total; ++k) {
    const std::int64_t p = split.order[std::size_t(k)];
    for (int j = 0; j < dim; ++j) split.points[std::size_t(k * dim + j)] = points[p * dim + j];
    split.cells[std::size_t(k)] = split.cell[std::size_t(p)];
  }
}

CellSplit split_by_cell(const double* points, int dim, std::int64_t n, const CellGrid& grid,
                        int threads) {
  return split_to_blocks(points, dim, n, grid, nullptr, nullptr, nullptr, 0, nullptr, threads);
}

}  // namespace gpugeom
