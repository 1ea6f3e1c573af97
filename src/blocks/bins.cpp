// A block's balls against the bins that hold points it lacks (include/gpugeom/blocks.hpp:
// balls_in_bins): gpugeom.dask's finality test past the region (python/gpugeom/dask/_ghost.py).
// The box round a ball's part past the region met bins in its corners that the ball never
// reaches; between clusters those corners hold the clusters' cores, so a test by boxes failed
// balls no point could break.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

namespace {

template <int D>
void run(const double* centres, const double* reach, const double* lo, const double* hi,
         std::int64_t m, const CellGrid& g, const std::uint8_t* marked, double margin,
         std::uint8_t* meets) {
  // a ball's scan stops at the first marked cell it meets: a ball as big as the box (points on
  // a sphere) costs one cell, not all of them
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t i = 0; i < m; ++i) {
    const double* c = centres + i * D;
    const double r = reach[i];
    bool finite = std::isfinite(r), bad = false;
    for (int j = 0; j < D; ++j) {
      finite = finite && std::isfinite(c[j]);
      bad = bad || std::isnan(lo[i * D + j]) || std::isnan(hi[i * D + j]);
    }
    if (bad) {  // a box not computed: the ball may meet anything (the caller grows the block)
      meets[i] = 1;
      continue;
    }
    std::int64_t first[3] = {0, 0, 0}, last[3] = {0, 0, 0};
    bool some = true;
    for (int j = 0; j < D && some; ++j) {
      double a = lo[i * D + j], b = hi[i * D + j];
      if (finite) a = std::max(a, c[j] - r), b = std::min(b, c[j] + r);
      some = blocks_detail::cells_along(a, b, g, j, margin, false, &first[j], &last[j]);
    }
    std::uint8_t met = 0;
    if (some) {
      const double r2 = finite ? r * r : 0.0;
      std::int64_t k[3] = {0, 0, 0};
      const std::int64_t end2 = D == 3 ? last[2] : 0;
      for (k[0] = first[0]; k[0] <= last[0] && !met; ++k[0])
        for (k[1] = first[1]; k[1] <= last[1] && !met; ++k[1])
          for (k[2] = first[2]; k[2] <= end2 && !met; ++k[2]) {
            std::int64_t bin = k[0] * g.counts[1] + k[1];
            if (D == 3) bin = bin * g.counts[2] + k[2];
            if (!marked[bin]) continue;
            if (finite) {
              double d2 = 0;  // from the centre to the bin's box grown by the margin
              for (int j = 0; j < D; ++j) {
                const double blo = g.lo[j] + double(k[j]) * g.width[j] - margin;
                const double bhi = g.lo[j] + double(k[j] + 1) * g.width[j] + margin;
                const double gap = std::max(std::max(blo - c[j], c[j] - bhi), 0.0);
                d2 += gap * gap;
              }
              if (d2 > r2) continue;
            }
            met = 1;
          }
    }
    meets[i] = met;
  }
}

}  // namespace

HostVector<std::uint8_t> balls_in_bins(const double* centres, const double* reach, const double* lo,
                                       const double* hi, std::int64_t m, int dim,
                                       const CellGrid& grid, const std::uint8_t* marked,
                                       double margin, int threads) {
  blocks_detail::check_dim(dim, "balls_in_bins");
  std::int64_t cells = 1;
  for (int j = 0; j < dim; ++j) cells *= grid.counts[j];
  if (cells > (std::int64_t(1) << 28))
    throw Error(ErrorCode::InvalidArgument,
                "balls_in_bins: at most 2^28 cells, got " + std::to_string(cells));
  blocks_detail::ThreadScope scope(threads);
  HostVector<std::uint8_t> meets(std::size_t(std::max<std::int64_t>(m, 0)));
  if (m > 0) {
    if (dim == 2)
      run<2>(centres, reach, lo, hi, m, grid, marked, margin, meets.data());
    else
      run<3>(centres, reach, lo, hi, m, grid, marked, margin, meets.data());
  }
  return meets;
}

}  // namespace gpugeom
