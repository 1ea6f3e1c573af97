// The 2D hull candidates of a piece of gpugeom.dask's input (include/gpugeom/blocks.hpp): where
// the blocks run on the host, a 2D ConvexHull would triangulate the whole piece, and the same
// filter in NumPy made a temporary array per edge and operation (0.4 s for 2·10^6 points).
#include <omp.h>

#include <cmath>
#include <limits>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "blocks/hull_rules.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

HostVector<std::int64_t> hull_candidates2d(const double* points, std::int64_t n, int threads) {
  HostVector<std::int64_t> out;
  auto everything = [&] {
    out.resize(std::size_t(n));
    for (std::int64_t i = 0; i < n; ++i) out[std::size_t(i)] = i;
    return out;
  };
  if (n < 4) return everything();
  // the extreme point in each of 8 directions, counter-clockwise (the first where several tie):
  // per thread over a static range, then joined in thread order, so that the choice is the
  // serial scan's on any thread count
  blocks_detail::ThreadScope scope(threads);
  const blocks_detail::Directions8 dir;
  const int teams = omp_get_max_threads();
  std::vector<double> tops(std::size_t(teams) * 8, -std::numeric_limits<double>::infinity());
  std::vector<std::int64_t> bests(std::size_t(teams) * 8, 0);
#pragma omp parallel num_threads(teams)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const std::int64_t lo = n * t / nt, hi = n * (t + 1) / nt;
    double* top = tops.data() + 8 * t;
    std::int64_t* best = bests.data() + 8 * t;
    for (std::int64_t i = lo; i < hi; ++i)
      for (int k = 0; k < 8; ++k) {
        const double h = points[2 * i] * dir.x[k] + points[2 * i + 1] * dir.y[k];
        if (h > top[k]) top[k] = h, best[k] = i;
      }
  }
  std::int64_t best[8];
  for (int k = 0; k < 8; ++k) {
    double top = -std::numeric_limits<double>::infinity();
    best[k] = 0;
    for (int t = 0; t < teams; ++t)
      if (tops[std::size_t(8 * t + k)] > top)
        top = tops[std::size_t(8 * t + k)], best[k] = bests[std::size_t(8 * t + k)];
  }
  const std::vector<std::int64_t> poly = blocks_detail::octagon(best);
  if (poly.empty()) return everything();
  std::vector<double> corners;
  for (std::int64_t v : poly)
    corners.push_back(points[2 * v]), corners.push_back(points[2 * v + 1]);
  const int m = int(poly.size());
  HostVector<std::uint8_t> keep(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    keep[std::size_t(i)] =
        blocks_detail::strictly_inside(points[2 * i], points[2 * i + 1], corners.data(), m) ? 0 : 1;
  blocks_detail::ordered_compact(
      n, [&](std::int64_t i) { return keep[std::size_t(i)] != 0; },
      [&](std::int64_t total) { out.resize(std::size_t(total)); },
      [&](std::int64_t i, std::int64_t r) { out[std::size_t(r)] = i; });
  return out;
}

}  // namespace gpugeom
