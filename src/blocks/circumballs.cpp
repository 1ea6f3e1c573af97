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
using blocks_detail::misses;
using blocks_detail::Slabs;
using blocks_detail::slabs_of;

template <int D, class I>
void run(const double* pts, const I* simplices, const std::int64_t* rows, std::int64_t count,
         const BlockBoxes& boxes, std::uint8_t* inside) {
  const Slabs slabs = slabs_of(boxes, D);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    const I* v = simplices + (rows ? rows[i] : i) * (D + 1);
    double c[D], reach;
    const bool ok = circumball<D>(pts, v, c, &reach, boxes.scale);
    inside[i] = ok && misses(slabs, c, reach, D) ? 1 : 0;
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
