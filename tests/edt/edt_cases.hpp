// Random site grids of many shapes and densities, and a brute-force reference transform.
#pragma once
#include <gmpxx.h>

#include <cstdint>
#include <random>
#include <vector>

#include "gpugeom/edt.hpp"
#include "edt/edt_backend.hpp"
#include "gpugeom/io.hpp"

namespace gg_edt {

inline gpugeom::io::Grid random_grid(const std::vector<std::int64_t>& shape, double density,
                                     unsigned seed) {
  gpugeom::io::Grid g;
  g.shape = shape;
  g.type = gpugeom::io::ScalarType::U8;
  std::mt19937 r(seed);
  std::uniform_real_distribution<double> U(0, 1);
  g.data.resize(std::size_t(g.count()));
  for (auto& v : g.data) v = U(r) < density;
  if (std::count(g.data.begin(), g.data.end(), 1) == 0) g.data[r() % g.data.size()] = 1;
  return g;
}

// Raster-index packing (edt::LinearLayout) for every grid while alive (the library's test
// switch).
struct LinearPacking {
  LinearPacking() { gpugeom::edt::set_linear_packing_for_testing(true); }
  ~LinearPacking() { gpugeom::edt::set_linear_packing_for_testing(false); }
  LinearPacking(const LinearPacking&) = delete;
  LinearPacking& operator=(const LinearPacking&) = delete;
};

struct Reference {
  std::vector<mpq_class> sq;  // exact weighted squared distance
  std::vector<std::int64_t>
      nearest;  // voxel (raster index) of the nearest site, first in raster order
};

// O(voxels * sites), exact with rationals: for small grids only.
inline Reference brute_force(const gpugeom::io::Grid& g, const std::vector<double>& sampling) {
  const int nd = int(g.shape.size());
  const std::int64_t n = g.count();
  std::vector<std::int64_t> sites;
  for (std::int64_t i = 0; i < n; ++i)
    if (g.data[i]) sites.push_back(i);
  std::vector<mpq_class> w(nd, 1);
  for (int j = 0; j < int(sampling.size()); ++j)
    w[j] = mpq_class(sampling[j]) * mpq_class(sampling[j]);
  auto coords = [&](std::int64_t i, std::int64_t* c) {
    for (int j = nd - 1; j >= 0; --j) c[j] = i % g.shape[j], i /= g.shape[j];
  };
  Reference ref;
  ref.sq.resize(n);
  ref.nearest.resize(n);
  const bool iso = sampling.empty();
  for (std::int64_t i = 0; i < n; ++i) {
    std::int64_t c[3], s[3];
    coords(i, c);
    if (iso) {  // integers are exact and much faster than rationals
      std::int64_t best = -1, at = 0;
      for (std::int64_t site : sites) {
        coords(site, s);
        std::int64_t d = 0;
        for (int j = 0; j < nd; ++j) d += (s[j] - c[j]) * (s[j] - c[j]);
        if (best < 0 || d < best) best = d, at = site;
      }
      ref.sq[i] = mpq_class((long)best);
      ref.nearest[i] = at;
      continue;
    }
    bool first = true;
    for (std::int64_t site : sites) {  // increasing raster order: strict < keeps the first
      coords(site, s);
      mpq_class d = 0;
      for (int j = 0; j < nd; ++j) d += w[j] * mpq_class((long)((s[j] - c[j]) * (s[j] - c[j])));
      if (first || d < ref.sq[i]) ref.sq[i] = d, ref.nearest[i] = site, first = false;
    }
  }
  return ref;
}

}  // namespace gg_edt
