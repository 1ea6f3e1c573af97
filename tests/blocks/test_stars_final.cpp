// stars_final (include/gpugeom/blocks.hpp) against a brute force over every point: a block's
// stars are final exactly when no tested simplex's closed circumball holds a point the block
// lacks (outside its region and strips, not held). The scan of the bins must find every such
// point; the brute force asks every point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/predicates.hpp"

namespace {
using namespace gpugeom;
using I64 = HostVector<std::int64_t>;

struct Scene {
  int dim;
  std::vector<double> all;
  BlockBoxes boxes;
  std::vector<double> strip_lo, strip_hi;  // one strip along the low side of axis 0
};

Scene make(int dim, std::int64_t n, unsigned seed) {
  Scene s{dim, {}, {}, {}, {}};
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  s.all.resize(std::size_t(n * dim));
  for (auto& x : s.all) x = u(rng);
  for (int j = 0; j < dim; ++j) {
    s.boxes.region_lo[j] = 0.3;
    s.boxes.region_hi[j] = 0.7;
    s.boxes.bounds_lo[j] = 1.0, s.boxes.bounds_hi[j] = 0.0;
  }
  for (std::int64_t i = 0; i < n; ++i)
    for (int j = 0; j < dim; ++j) {
      s.boxes.bounds_lo[j] = std::min(s.boxes.bounds_lo[j], s.all[std::size_t(i * dim + j)]);
      s.boxes.bounds_hi[j] = std::max(s.boxes.bounds_hi[j], s.all[std::size_t(i * dim + j)]);
    }
  s.boxes.scale = 1.0;
  for (int j = 0; j < dim; ++j) {
    s.strip_lo.push_back(s.boxes.bounds_lo[j]);
    s.strip_hi.push_back(j == 0 ? s.boxes.bounds_lo[j] + 0.05 : s.boxes.bounds_hi[j]);
  }
  return s;
}

bool in_box(const double* x, const double* lo, const double* hi, int dim) {
  for (int j = 0; j < dim; ++j)
    if (x[j] < lo[j] || x[j] > hi[j]) return false;
  return true;
}

bool in_ball(int dim, const double* const* v, const double* x) {
  if (dim == 2)
    return incircle({v[0][0], v[0][1]}, {v[1][0], v[1][1]}, {v[2][0], v[2][1]}, {x[0], x[1]}) >= 0;
  return insphere({v[0][0], v[0][1], v[0][2]}, {v[1][0], v[1][1], v[1][2]},
                  {v[2][0], v[2][1], v[2][2]}, {v[3][0], v[3][1], v[3][2]},
                  {x[0], x[1], x[2]}) >= 0;
}

// The block holds the points in its region and strip and `held`: triangulated, tested by
// stars_final (simplices with test[i]) and by asking every point; returns the verdict.
bool check(const Scene& s, const I64& held, bool strip, const std::string& what) {
  const int dim = s.dim, d1 = dim + 1;
  const std::int64_t n = std::int64_t(s.all.size()) / dim;
  auto boxed = [&](std::int64_t i) {
    const double* x = s.all.data() + i * dim;
    return in_box(x, s.boxes.region_lo, s.boxes.region_hi, dim) ||
           (strip && in_box(x, s.strip_lo.data(), s.strip_hi.data(), dim));
  };
  I64 local;
  for (std::int64_t i = 0; i < n; ++i)
    if (boxed(i) || std::binary_search(held.begin(), held.end(), i)) local.push_back(i);
  std::vector<double> pts;
  for (auto i : local)
    for (int j = 0; j < dim; ++j) pts.push_back(s.all[std::size_t(i * dim + j)]);
  HostVector<std::int32_t> simp;
  std::int64_t m;
  const std::int64_t nl = std::int64_t(local.size());
  if (dim == 2) {
    Delaunay2dOptions o;
    o.backend = Backend::Cpu;
    auto t = delaunay2d(pts.data(), nl, o);
    simp = t.triangles, m = t.num_triangles;
  } else {
    Delaunay3dOptions o;
    o.backend = Backend::Cpu;
    auto t = delaunay3d(pts.data(), nl, o);
    simp = t.tetrahedra, m = t.num_tetrahedra;
  }
  // the tested simplices: every other one, so that the untested are skipped too
  HostVector<std::uint8_t> test(static_cast<std::size_t>(m));
  for (std::int64_t i = 0; i < m; ++i) test[std::size_t(i)] = i % 2 == 0;
  CellGrid bins;
  for (int j = 0; j < dim; ++j) {
    bins.counts[j] = 9;
    bins.lo[j] = s.boxes.bounds_lo[j];
    bins.width[j] = (s.boxes.bounds_hi[j] - s.boxes.bounds_lo[j]) / 9.0;
  }
  const CellSplit index = split_by_cell(s.all.data(), dim, n, bins);
  const bool got = stars_final(pts.data(), dim, simp.data(), m, test.data(), s.boxes, s.all.data(),
                               bins, index.order.data(), index.cuts.data(), held.data(),
                               std::int64_t(held.size()), strip ? s.strip_lo.data() : nullptr,
                               strip ? s.strip_hi.data() : nullptr, strip ? 1 : 0);
  bool want = true;
  for (std::int64_t i = 0; i < m && want; ++i) {
    if (!test[std::size_t(i)]) continue;
    const double* v[4];
    for (int k = 0; k < d1; ++k)
      v[k] = pts.data() + std::int64_t(simp[std::size_t(i * d1 + k)]) * dim;
    for (std::int64_t p = 0; p < n && want; ++p)
      if (!boxed(p) && !std::binary_search(held.begin(), held.end(), p) &&
          in_ball(dim, v, s.all.data() + p * dim))
        want = false;
  }
  EXPECT_EQ(got, want) << what;
  return want;
}

// Held: the points outside the region within `w` of it (a ghost layer of width w).
I64 ghost(const Scene& s, double w) {
  I64 out;
  const std::int64_t n = std::int64_t(s.all.size()) / s.dim;
  double lo[3], hi[3];
  for (int j = 0; j < s.dim; ++j)
    lo[j] = s.boxes.region_lo[j] - w, hi[j] = s.boxes.region_hi[j] + w;
  for (std::int64_t i = 0; i < n; ++i) {
    const double* x = s.all.data() + i * s.dim;
    if (in_box(x, lo, hi, s.dim) && !in_box(x, s.boxes.region_lo, s.boxes.region_hi, s.dim))
      out.push_back(i);
  }
  return out;
}

TEST(StarsFinal, AgreesWithEveryPoint) {
  int finals = 0, not_finals = 0;
  for (int dim : {2, 3})
    for (unsigned seed : {1u, 2u}) {
      const Scene s = make(dim, dim == 2 ? 3000 : 1500, seed);
      const std::int64_t n = std::int64_t(s.all.size()) / dim;
      I64 every;
      for (std::int64_t i = 0; i < n; ++i) every.push_back(i);
      for (double w : {0.0, 0.02, 0.1, 0.3})
        for (bool strip : {false, true}) {
          const std::string what = std::to_string(dim) + "D seed " + std::to_string(seed) +
                                   " ghost " + std::to_string(w) + (strip ? " strip" : "");
          (check(s, ghost(s, w), strip, what) ? finals : not_finals) += 1;
        }
      EXPECT_TRUE(check(s, every, false, "every point held"));
      // every ghost point but one held, near the region: the one missing point must be found
      I64 g = ghost(s, 0.3);
      g.erase(g.begin() + std::ptrdiff_t(g.size() / 2));
      (check(s, g, false, std::to_string(dim) + "D one ghost point missing") ? finals
                                                                             : not_finals) += 1;
    }
  // both verdicts were reached, so neither side of the comparison is idle
  EXPECT_GT(finals, 0);
  EXPECT_GT(not_finals, 0);
}

}  // namespace
