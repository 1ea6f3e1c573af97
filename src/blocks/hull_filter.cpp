// The 2D hull candidates of a piece of gpugeom.dask's input (include/gpugeom/blocks.hpp): where
// the blocks run on the host, a 2D ConvexHull would triangulate the whole piece, and the same
// filter in NumPy made a temporary array per edge and operation (0.4 s for 2·10^6 points).
#include <omp.h>

#include <cmath>
#include <limits>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

namespace {

// Shewchuk's bound on the rounding of a 2D orientation computed in doubles, relative to the sum
// of its two products' magnitudes (ccwerrboundA; epsilon is half an ulp of 1).
constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;
constexpr double kOrientBound = (3.0 + 16.0 * kEps) * kEps;

}  // namespace

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
  const double pi = std::acos(-1.0);
  double cx[8], cy[8];
  for (int k = 0; k < 8; ++k) cx[k] = std::cos(2 * pi * k / 8), cy[k] = std::sin(2 * pi * k / 8);
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
        const double h = points[2 * i] * cx[k] + points[2 * i + 1] * cy[k];
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
  std::vector<std::int64_t> poly;
  for (int k = 0; k < 8; ++k)
    if (poly.empty() || poly.back() != best[k]) poly.push_back(best[k]);
  if (poly.size() > 1 && poly.front() == poly.back()) poly.pop_back();
  if (poly.size() < 3) return everything();
  HostVector<std::uint8_t> keep(static_cast<std::size_t>(n));
  const int m = int(poly.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const double x = points[2 * i], y = points[2 * i + 1];
    bool inside = true;
    for (int e = 0; e < m && inside; ++e) {
      const double* a = points + 2 * poly[std::size_t(e)];
      const double* b = points + 2 * poly[std::size_t((e + 1) % m)];
      const double left = (a[0] - x) * (b[1] - y), right = (a[1] - y) * (b[0] - x);
      inside = left - right > kOrientBound * (std::fabs(left) + std::fabs(right));
    }
    keep[std::size_t(i)] = inside ? 0 : 1;
  }
  blocks_detail::ordered_compact(
      n, [&](std::int64_t i) { return keep[std::size_t(i)] != 0; },
      [&](std::int64_t total) { out.resize(std::size_t(total)); },
      [&](std::int64_t i, std::int64_t r) { out[std::size_t(r)] = i; });
  return out;
}

}  // namespace gpugeom
