// Points to the blocks of gpugeom.dask's grid, and points in boxes (include/gpugeom/
// blocks.hpp): one pass each, where NumPy made a temporary array per axis and comparison and
// sorted the cells (an argsort of 10^7 int64 cells took 0.7 s).
#include <cmath>
#include <string>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

void points_in_boxes(const double* points, int dim, std::int64_t n, const double* lo,
                     const double* hi, std::int64_t k, std::uint8_t* inside, int threads) {
  blocks_detail::ThreadScope scope(threads);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const double* x = points + p * dim;
    std::uint8_t in = 0;
    for (std::int64_t b = 0; b < k && !in; ++b) {
      bool all = true;
      for (int j = 0; j < dim; ++j) all = all && x[j] >= lo[b * dim + j] && x[j] <= hi[b * dim + j];
      in = all ? 1 : 0;
    }
    inside[p] = in;
  }
}

CellSplit split_by_cell(const double* points, int dim, std::int64_t n, const CellGrid& grid,
                        int threads) {
  blocks_detail::check_dim(dim, "split_by_cell");
  blocks_detail::ThreadScope scope(threads);
  CellSplit out;
  out.cell.resize(std::size_t(n));
  std::int64_t cells = 1;
  for (int j = 0; j < dim; ++j) cells *= grid.counts[j];
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    std::int64_t c = 0;
    for (int j = 0; j < dim; ++j) {
      std::int64_t i = 0;
      if (grid.width[j] > 0) {
        // as gpugeom.dask's Grid.cell_of: the same two roundings, then clamped
        const double f = std::floor((points[p * dim + j] - grid.lo[j]) / grid.width[j]);
        i = f < 0 ? 0 : (f > double(grid.counts[j] - 1) ? grid.counts[j] - 1 : std::int64_t(f));
      }
      c = c * grid.counts[j] + i;
    }
    out.cell[std::size_t(p)] = c;
  }
  // a counting sort, stable: on one thread (the scatter keeps the points' order in a cell)
  out.cuts.assign(std::size_t(cells + 1), 0);
  for (std::int64_t p = 0; p < n; ++p) ++out.cuts[std::size_t(out.cell[std::size_t(p)] + 1)];
  for (std::int64_t c = 0; c < cells; ++c) out.cuts[std::size_t(c + 1)] += out.cuts[std::size_t(c)];
  out.order.resize(std::size_t(n));
  HostVector<std::int64_t> next(out.cuts.begin(), out.cuts.end() - 1);
  for (std::int64_t p = 0; p < n; ++p)
    out.order[std::size_t(next[std::size_t(out.cell[std::size_t(p)])]++)] = p;
  return out;
}

}  // namespace gpugeom
