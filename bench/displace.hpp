// The moved points of issue 47's benchmarks (gpugeom_bench_dynamic and the CGAL anchor take the
// same ones): every point moved by a normal step of f times the mean spacing in each coordinate
// (hashed per point and coordinate, so every run and program draws the same steps), and the
// fixed random choice of points to remove.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "bench_csv.hpp"

namespace gpugeom::bench {

// The mean spacing of points P (dim coordinates each): (bounding box volume / n)^(1 / dim).
template <int dim, class P>
double mean_spacing(const std::vector<P>& p) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const auto& x : p)
    for (int d = 0; d < dim; ++d) {
      const double c = (&x.x)[d];
      lo[d] = std::min(lo[d], c), hi[d] = std::max(hi[d], c);
    }
  double volume = 1;
  for (int d = 0; d < dim; ++d) volume *= hi[d] - lo[d];
  return std::pow(volume / double(p.size()), 1.0 / dim);
}

template <int dim, class P>
std::vector<P> displaced(const std::vector<P>& p, double f) {
  const double step = f * mean_spacing<dim>(p);
  std::vector<P> q = p;
  for (std::size_t i = 0; i < q.size(); ++i)
    for (int d = 0; d < dim; ++d) {
      const std::uint64_t s = std::uint64_t(2 * d + 1);
      const double u1 = (double(hash64(i, s) >> 11) + 0.5) / 9007199254740992.0;
      const double u2 = double(hash64(i, s + 1) >> 11) / 9007199254740992.0;
      (&q[i].x)[d] += step * std::sqrt(-2 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    }
  return q;
}

// k of n indices, a fixed random choice.
inline std::vector<std::int32_t> removal_choice(std::int64_t n, std::int64_t k) {
  std::vector<std::int32_t> idx(static_cast<std::size_t>(n));
  for (std::int64_t i = 0; i < n; ++i) idx[std::size_t(i)] = std::int32_t(i);
  std::mt19937_64 rng(11);
  std::shuffle(idx.begin(), idx.end(), rng);
  idx.resize(std::size_t(k));
  return idx;
}

}  // namespace gpugeom::bench
