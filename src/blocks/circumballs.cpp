// The bulk finality test of a distributed-Delaunay block (include/gpugeom/blocks.hpp). It is the
// first test of gpugeom.dask's final_simplices (python/gpugeom/dask/_ghost.py: _circumcentres
// and _ball_misses) with the same centre, the same rounding bound and the same slabs, one
// simplex at a time: almost every simplex of a block passes here, and only the few that do not
// go on to the Python tests along the hull.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/circumball.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

namespace {

using blocks_detail::circumball;

// The boxes where points outside the region may lie: per axis and side with room, the part of
// the bounds beyond the region's face.
struct Slabs {
  int count = 0;
  double lo[6][3], hi[6][3];
};

Slabs slabs_of(const BlockBoxes& b, int dim) {
  Slabs s;
  for (int k = 0; k < dim; ++k)
    for (int side = 0; side < 2; ++side) {
      const bool room =
          side == 0 ? b.region_lo[k] > b.bounds_lo[k] : b.region_hi[k] < b.bounds_hi[k];
      if (!room) continue;
      for (int j = 0; j < dim; ++j) {
        s.lo[s.count][j] = b.bounds_lo[j];
        s.hi[s.count][j] = b.bounds_hi[j];
      }
      if (side == 0)
        s.hi[s.count][k] = b.region_lo[k];
      else
        s.lo[s.count][k] = b.region_hi[k];
      ++s.count;
    }
  return s;
}

template <int D, class I>
void run(const double* pts, const I* simplices, const std::int64_t* rows, std::int64_t count,
         const BlockBoxes& boxes, std::uint8_t* inside) {
  const Slabs slabs = slabs_of(boxes, D);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    const I* v = simplices + (rows ? rows[i] : i) * (D + 1);
    double c[D], reach;
    bool ok = circumball<D>(pts, v, c, &reach, boxes.scale);
    for (int s = 0; ok && s < slabs.count; ++s) {
      double g2 = 0;
      for (int k = 0; k < D; ++k) {
        const double gap = std::max(std::max(slabs.lo[s][k] - c[k], c[k] - slabs.hi[s][k]), 0.0);
        g2 += gap * gap;
      }
      ok = std::sqrt(g2) > reach;
    }
    inside[i] = ok ? 1 : 0;
  }
}

template <class I>
void inside_region(const double* points, int dim, const I* simplices, const std::int64_t* rows,
                   std::int64_t count, const BlockBoxes& boxes, std::uint8_t* inside, int threads) {
  blocks_detail::check_dim(dim, "circumballs_inside_region");
  if (count <= 0) return;
  blocks_detail::ThreadScope scope(threads);
  if (dim == 2)
    run<2>(points, simplices, rows, count, boxes, inside);
  else
    run<3>(points, simplices, rows, count, boxes, inside);
}

}  // namespace

void circumballs_inside_region(const double* points, int dim, const std::int64_t* simplices,
                               const std::int64_t* rows, std::int64_t count,
                               const BlockBoxes& boxes, std::uint8_t* inside, int threads) {
  inside_region(points, dim, simplices, rows, count, boxes, inside, threads);
}
void circumballs_inside_region(const double* points, int dim, const std::int32_t* simplices,
                               const std::int64_t* rows, std::int64_t count,
                               const BlockBoxes& boxes, std::uint8_t* inside, int threads) {
  inside_region(points, dim, simplices, rows, count, boxes, inside, threads);
}

}  // namespace gpugeom
