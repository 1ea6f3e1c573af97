// Densities and a brute-force Lloyd step for the CVD tests.
#pragma once
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "gpugeom/cvd.hpp"
#include "gpugeom/io.hpp"

namespace gg_cvd {

// A uint16 density (C order shape) whose maximum is 65535, so that the library's 16-bit
// quantisation keeps every value as it is. zero_frac of the pixels are 0 (below 0: uniform).
inline gpugeom::io::Grid random_density(const std::vector<std::int64_t>& shape, double zero_frac,
                                        unsigned seed) {
  gpugeom::io::Grid g;
  g.shape = shape;
  g.type = gpugeom::io::ScalarType::U16;
  std::mt19937 r(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<std::uint16_t> v(std::size_t(g.count()));
  // zero_frac < 0: a uniform density (every value 65535), the unweighted diagram.
  for (auto& x : v)
    x = zero_frac < 0 ? 65535 : U(r) < zero_frac ? 0 : std::uint16_t(1 + r() % 65535);
  v[r() % v.size()] = 65535;
  g.data.resize(v.size() * 2);
  std::memcpy(g.data.data(), v.data(), g.data.size());
  return g;
}

// Sites (geometric x, y[, z] order) at random grid points where the density is positive.
inline std::vector<double> random_sites(const gpugeom::io::Grid& g, int count, unsigned seed) {
  const int nd = int(g.shape.size());
  std::mt19937 r(seed);
  std::vector<double> s;
  while (int(s.size()) < count * nd) {
    const std::int64_t i = std::int64_t(r() % std::uint64_t(g.count()));
    if (g.value(i) == 0) continue;
    std::int64_t rest = i;
    double c[3];
    for (int a = 0; a < nd; ++a)
      c[a] = double(rest % g.shape[nd - 1 - a]), rest /= g.shape[nd - 1 - a];
    for (int a = 0; a < nd; ++a) s.push_back(c[a]);
  }
  return s;
}

struct Step {
  std::vector<double> sites;        // after the step
  std::vector<double> mass;         // of the cells before it (0 for a repeated site), density units
  double energy = 0;                // of the diagram before it, density units
  std::vector<std::int32_t> owner;  // per grid point (raster order), the site index
};

// One Lloyd step as the library defines it, by brute force: every point goes to its nearest
// site (ties: the site first in raster order, then the lowest index); each site moves to the
// grid point nearest its weighted centroid (ties upward) when strictly nearer than it is.
inline Step brute_step(const gpugeom::io::Grid& g, const std::vector<double>& sites) {
  const int nd = int(g.shape.size());
  const std::int64_t n = g.count(), ns = std::int64_t(sites.size()) / nd;
  std::int64_t ext[3] = {1, 1, 1};  // geometric axis extents
  for (int a = 0; a < nd; ++a) ext[a] = g.shape[nd - 1 - a];
  auto raster = [&](const std::int64_t* c) { return c[0] + ext[0] * (c[1] + ext[1] * c[2]); };
  std::vector<std::int64_t> sp(std::size_t(ns) * 3, 0);
  for (std::int64_t j = 0; j < ns; ++j)
    for (int a = 0; a < nd; ++a) sp[j * 3 + a] = std::int64_t(sites[j * nd + a]);
  Step st;
  st.owner.resize(std::size_t(n));
  std::vector<unsigned __int128> m(ns, 0), M(std::size_t(ns) * 3, 0);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t c[3] = {i % ext[0], (i / ext[0]) % ext[1], i / (ext[0] * ext[1])};
    std::int64_t best = -1, bd = 0;
    for (std::int64_t j = 0; j < ns; ++j) {
      std::int64_t d = 0;
      for (int a = 0; a < nd; ++a) d += (sp[j * 3 + a] - c[a]) * (sp[j * 3 + a] - c[a]);
      if (best < 0 || d < bd || (d == bd && raster(&sp[j * 3]) < raster(&sp[best * 3])))
        best = j, bd = d;
    }
    const std::uint64_t w = std::uint64_t(g.value(i));
    st.owner[i] = std::int32_t(best);
    st.energy += double(w) * double(bd);
    m[best] += w;
    for (int a = 0; a < nd; ++a) M[best * 3 + a] += w * std::uint64_t(c[a]);
  }
  st.sites = sites;
  st.mass.resize(std::size_t(ns));
  for (std::int64_t j = 0; j < ns; ++j) {
    st.mass[j] = double(m[j]);
    if (m[j] == 0) continue;
    __int128 dn = 0, dp = 0;
    std::int64_t r[3];
    for (int a = 0; a < nd; ++a) {
      r[a] = std::int64_t((2 * M[j * 3 + a] + m[j]) / (2 * m[j]));
      const __int128 en = __int128(m[j]) * r[a] - __int128(M[j * 3 + a]);
      const __int128 ep = __int128(m[j]) * sp[j * 3 + a] - __int128(M[j * 3 + a]);
      dn += en * en;
      dp += ep * ep;
    }
    if (dn < dp)
      for (int a = 0; a < nd; ++a) st.sites[j * nd + a] = double(r[a]);
  }
  return st;
}

}  // namespace gg_cvd
