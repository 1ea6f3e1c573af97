// Random site grids of many shapes and densities, and a brute-force reference transform.
#pragma once
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "gpugeom/edt.hpp"
#include "edt/edt_backend.hpp"
#include "../common/tuning.hpp"
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

// The library's knobs (RunOptions::tuning) for raster-index packing (edt::LinearLayout) of every
// grid, and for column packing (edt::ColumnLayout) of every slice-by-slice request.
inline std::shared_ptr<const gpugeom::detail::Tuning> linear_packing() {
  return gg_test::tuning([](gpugeom::detail::Tuning& t) { t.edt.linear_packing = true; });
}
inline std::shared_ptr<const gpugeom::detail::Tuning> column_packing() {
  return gg_test::tuning([](gpugeom::detail::Tuning& t) { t.edt.column_packing = true; });
}

// The slices (z values) of a whole-volume result, as the slice-by-slice mode returns them.
inline gpugeom::EdtResult slices_of(const gpugeom::EdtResult& whole,
                                    const std::vector<std::int64_t>& slices) {
  gpugeom::EdtResult r;
  r.shape = whole.shape;
  r.shape[0] = std::int64_t(slices.size());
  const std::int64_t n = whole.count(), plane = n / whole.shape[0], m = r.count();
  auto take = [&](const auto& from, auto& to, int arrays) {
    if (from.empty()) return;
    to.resize(std::size_t(arrays * m));
    for (int a = 0; a < arrays; ++a)
      for (std::size_t k = 0; k < slices.size(); ++k)
        for (std::int64_t i = 0; i < plane; ++i)
          to[std::size_t(a * m + std::int64_t(k) * plane + i)] =
              from[std::size_t(a * n + slices[k] * plane + i)];
  };
  take(whole.sqdist_int, r.sqdist_int, 1);
  take(whole.sqdist_real, r.sqdist_real, 1);
  take(whole.distance32, r.distance32, 1);
  take(whole.distance64, r.distance64, 1);
  take(whole.features, r.features, int(whole.shape.size()));
  take(whole.labels, r.labels, 1);
  return r;
}

// Indices [first, first + count) along axis 0 of a u8 grid as a grid of their own, with the
// bounds EdtOptions::slab needs: per column, the last site before the slab and the first after.
struct Slab {
  gpugeom::io::Grid grid;
  gpugeom::EdtSlab bounds;
};
inline Slab slab_of(const gpugeom::io::Grid& g, std::int64_t first, std::int64_t count,
                    gpugeom::SiteRule rule) {
  Slab s;
  const std::int64_t plane = g.count() / g.shape[0];
  s.grid.shape = g.shape;
  s.grid.shape[0] = count;
  s.grid.type = g.type;
  s.grid.data.assign(g.data.begin() + first * plane, g.data.begin() + (first + count) * plane);
  s.bounds.extent = g.shape[0];
  s.bounds.first = first;
  s.bounds.before.assign(std::size_t(plane), -1);
  s.bounds.after.assign(std::size_t(plane), -1);
  auto site = [&](std::int64_t z, std::int64_t c) {
    return (g.data[std::size_t(z * plane + c)] != 0) == (rule == gpugeom::SiteRule::NonZero);
  };
  for (std::int64_t c = 0; c < plane; ++c) {
    for (std::int64_t z = first - 1; z >= 0 && s.bounds.before[std::size_t(c)] < 0; --z)
      if (site(z, c)) s.bounds.before[std::size_t(c)] = z;
    for (std::int64_t z = first + count; z < g.shape[0] && s.bounds.after[std::size_t(c)] < 0; ++z)
      if (site(z, c)) s.bounds.after[std::size_t(c)] = z;
  }
  return s;
}

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
    std::int64_t c[8], s[8];
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

// A volume of more than 2^32 voxels (65536 x 257 x 263, C order) known by a few hundred listed
// sites, and slices to compute by the slice-by-slice mode: the first and last slices, slices
// among clusters of sites, and slices with exact ties between sites of different columns on
// either side (the site below lies in the later column: the tie goes to it, first in raster
// order, only if z is compared before the column). The list repeats a site (its label is its
// first index) that slices meet both above and below.
struct TallVolume {
  std::vector<std::int64_t> shape{65536, 257, 263};
  std::vector<std::int64_t> sites;  // (z, y, x) per site
  std::vector<std::int64_t> slices;
};
inline TallVolume tall_volume(unsigned seed) {
  TallVolume t;
  std::mt19937 r(seed);
  auto site = [&](std::int64_t z, std::int64_t y, std::int64_t x) {
    t.sites.push_back(z);
    t.sites.push_back(y);
    t.sites.push_back(x);
  };
  site(30, 5, 5);  // repeated last: slice 0 meets it above, slice 39 below
  for (std::int64_t centre : {0, 40, 32767, 40000, 65535})
    for (int k = 0; k < 50; ++k) {
      const std::int64_t z = centre + std::int64_t(r() % 81) - 40;
      site(std::min<std::int64_t>(65535, std::max<std::int64_t>(0, z)), r() % 257, r() % 263);
    }
  for (std::int64_t z0 : {20000, 50000}) {  // ties at (z0, 100, 108): 9 + 1 from both sites
    site(z0 - 3, 100, 109);
    site(z0 + 3, 100, 107);
    t.slices.push_back(z0);
  }
  site(30, 5, 5);
  for (std::int64_t z : {0, 1, 39, 40, 32767, 32768, 40000, 65535}) t.slices.push_back(z);
  return t;
}

// The slice mode's exact outputs by brute force: for each voxel of the slices (in order), the
// weighted squared distance to its nearest site (w: integer weights, sampling^2), the site's
// coordinates (ties: first in raster order) and label (its first index in the list).
struct SliceReference {
  std::vector<std::int64_t> sq;
  std::vector<std::int64_t> coords;  // 3 per voxel (z, y, x)
  std::vector<std::int32_t> label;
};
inline SliceReference slice_reference(const TallVolume& t, const std::int64_t w[3]) {
  const std::int64_t ny = t.shape[1], nx = t.shape[2], plane = ny * nx;
  const std::int64_t ns = std::int64_t(t.sites.size()) / 3;
  SliceReference ref;
  const std::size_t n = t.slices.size() * std::size_t(plane);
  ref.sq.resize(n);
  ref.coords.resize(3 * n);
  ref.label.resize(n);
  for (std::size_t k = 0; k < t.slices.size(); ++k)
    for (std::int64_t p = 0; p < plane; ++p) {
      const std::int64_t c[3] = {t.slices[k], p / nx, p % nx};
      std::int64_t best = -1, raster = 0, at = 0;
      for (std::int64_t j = 0; j < ns; ++j) {
        const std::int64_t* s = &t.sites[std::size_t(3 * j)];
        std::int64_t d = 0;
        for (int a = 0; a < 3; ++a) d += w[a] * (s[a] - c[a]) * (s[a] - c[a]);
        const std::int64_t ri = (s[0] * ny + s[1]) * nx + s[2];
        if (best < 0 || d < best || (d == best && ri < raster)) best = d, raster = ri, at = j;
      }
      const std::size_t i = k * std::size_t(plane) + std::size_t(p);
      ref.sq[i] = best;
      for (int a = 0; a < 3; ++a) ref.coords[3 * i + a] = t.sites[std::size_t(3 * at + a)];
      ref.label[i] = std::int32_t(at);
    }
  return ref;
}

inline gpugeom::EdtOptions all_outputs(gpugeom::Backend b = gpugeom::Backend::Cpu) {
  using namespace gpugeom;
  EdtOptions o;
  o.backend = b;
  o.squared = true;
  o.distance = 64;
  o.features = true;
  o.labels = true;
  return o;
}

// Every output of the transform of g against the brute-force reference: the nearest site (its
// features and label, ties to the first in raster order), squared and plain distances.
inline void expect_exact(const gpugeom::io::Grid& g, const gpugeom::EdtOptions& o,
                         const std::string& what) {
  using namespace gpugeom;
  const auto ref = brute_force(g, o.sampling);
  const auto r = distance_transform(g, SiteRule::NonZero, o);
  const std::int64_t n = g.count();
  const int nd = int(g.shape.size());
  ASSERT_EQ(r.labels.size(), std::size_t(n)) << what;
  // labels are raster ranks of the sites
  std::vector<std::int64_t> rank(n, -1);
  for (std::int64_t i = 0, k = 0; i < n; ++i)
    if (g.data[i]) rank[i] = k++;
  for (std::int64_t i = 0; i < n; ++i) {
    std::int64_t f = 0;
    for (int j = 0; j < nd; ++j) f = f * g.shape[j] + r.features[std::size_t(j) * n + i];
    ASSERT_EQ(f, ref.nearest[i]) << what << " voxel " << i << ": wrong nearest site (tie rule?)";
    ASSERT_EQ(r.labels[i], rank[ref.nearest[i]]) << what << " voxel " << i;
    if (o.sampling.empty()) {
      ASSERT_EQ(mpq_class((long)r.sqdist_int[i]), ref.sq[i]) << what << " voxel " << i;
    } else {
      ASSERT_NEAR(r.sqdist_real[i], ref.sq[i].get_d(), 1e-12 * (1 + ref.sq[i].get_d())) << what;
    }
    ASSERT_NEAR(r.distance64[i], std::sqrt(ref.sq[i].get_d()), 1e-12 * (1 + r.distance64[i]))
        << what;
  }
}

}  // namespace gg_edt
