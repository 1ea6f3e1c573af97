// Shared by the CPU and CUDA tests of delaunay{2,3}d_devices (include/gpugeom/multi_gpu.hpp):
// the blocks' result must be a single call's, array for array, on every distribution, on
// degenerate sets and across 1 to 8 blocks.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/generate.hpp"
#include "gpugeom/multi_gpu.hpp"

namespace gg_devices {
using namespace gpugeom;

// Clusters: `k` tight Gaussian blobs at random centres, with a sparse background.
template <class P, int D>
std::vector<P> clusters(std::int64_t n, int k, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, 0.01);
  std::vector<std::array<double, 3>> c(static_cast<std::size_t>(k));
  for (auto& x : c)
    for (auto& v : x) v = u(rng);
  std::vector<P> out;
  for (std::int64_t i = 0; i < n; ++i) {
    double x[3];
    if (i % 10 == 0) {
      for (auto& v : x) v = u(rng);
    } else {
      const auto& m = c[std::size_t(i) % c.size()];
      for (int j = 0; j < 3; ++j) x[j] = m[std::size_t(j)] + g(rng);
    }
    if constexpr (D == 2)
      out.push_back({x[0], x[1]});
    else
      out.push_back({x[0], x[1], x[2]});
  }
  return out;
}

template <class P>
struct Input {
  std::string name;
  std::vector<P> pts;
};

inline std::vector<Input<Point3>> inputs3d(std::int64_t n) {
  std::vector<Input<Point3>> out;
  for (const auto& d : distributions3d())
    if (d != "two_lines") out.push_back({d, generate3d(d, n, 11)});
  out.push_back({"clusters", clusters<Point3, 3>(n, 7, 5)});
  Input<Point3> grid{"integer_grid", {}};  // cospherical everywhere, turned off the axes
  const int k = int(std::cbrt(double(n)));
  for (int x = 0; x < k; ++x)
    for (int y = 0; y < k; ++y)
      for (int z = 0; z < k; ++z) grid.pts.push_back({x + 0.5 * y, y - 0.25 * z, double(z)});
  out.push_back(grid);
  Input<Point3> copies{"copies", generate3d("uniform", n / 3, 4)};
  const auto c = copies.pts;
  copies.pts.insert(copies.pts.end(), c.begin(), c.end());
  std::shuffle(copies.pts.begin(), copies.pts.end(), std::mt19937_64(3));
  out.push_back(copies);
  return out;
}

inline std::vector<Input<Point2>> inputs2d(std::int64_t n) {
  std::vector<Input<Point2>> out;
  for (const auto& d : distributions2d())
    if (d != "two_segments") out.push_back({d, generate2d(d, n, 11)});
  out.push_back({"clusters", clusters<Point2, 2>(n, 5, 5)});
  Input<Point2> grid{"integer_grid", {}};
  const int k = int(std::sqrt(double(n)));
  for (int x = 0; x < k; ++x)
    for (int y = 0; y < k; ++y) grid.pts.push_back({x + 0.5 * y, double(y)});
  out.push_back(grid);
  Input<Point2> copies{"copies", generate2d("uniform", n / 3, 4)};
  const auto c = copies.pts;
  copies.pts.insert(copies.pts.end(), c.begin(), c.end());
  std::shuffle(copies.pts.begin(), copies.pts.end(), std::mt19937_64(3));
  out.push_back(copies);
  return out;
}

inline void expect_same(const Triangulation3d& got, const Triangulation3d& want,
                        const std::string& what) {
  EXPECT_EQ(got.num_tetrahedra, want.num_tetrahedra) << what;
  EXPECT_TRUE(got.tetrahedra == want.tetrahedra) << what;
  EXPECT_TRUE(got.neighbors == want.neighbors) << what;
  EXPECT_TRUE(got.duplicate_of == want.duplicate_of) << what;
  EXPECT_EQ(got.num_duplicates, want.num_duplicates) << what;
  EXPECT_TRUE(got.vertex_to_simplex == want.vertex_to_simplex) << what;
  EXPECT_TRUE(got.hull_facets == want.hull_facets) << what;
  EXPECT_EQ(got.num_hull_facets, want.num_hull_facets) << what;
}

inline void expect_same(const Triangulation2d& got, const Triangulation2d& want,
                        const std::string& what) {
  EXPECT_EQ(got.num_triangles, want.num_triangles) << what;
  EXPECT_TRUE(got.triangles == want.triangles) << what;
  EXPECT_TRUE(got.neighbors == want.neighbors) << what;
  EXPECT_TRUE(got.duplicate_of == want.duplicate_of) << what;
  EXPECT_EQ(got.num_duplicates, want.num_duplicates) << what;
}

// The inputs on a convex surface (blocks/convex_sample.hpp), which go to the single call on the
// first device whatever the devices listed.
inline bool on_convex_surface(const std::string& name) {
  return name == "sphere" || name == "thin_sphere" || name == "circle";
}

// Every input across 1, 2, 3 and 8 blocks (devices: `device` named that often) against one
// call on `backend`; returns the blocks that took a second round, over all runs.
template <class P, class Opt, class Single, class Devices>
std::int64_t check_all(const std::vector<Input<P>>& inputs, Backend backend, int device,
                       Single single, Devices devices) {
  std::int64_t second = 0;
  for (const auto& in : inputs) {
    Opt o;
    o.backend = backend;
    const double* p = &in.pts.data()->x;
    const std::int64_t n = std::int64_t(in.pts.size());
    const auto want = single(p, n, o);
    for (int k : {1, 2, 3, 8}) {
      const auto got = devices(p, n, std::vector<int>(std::size_t(k), device), o);
      expect_same(got, want, in.name + " in " + std::to_string(k) + " blocks");
      EXPECT_EQ(got.stats.blocks, on_convex_surface(in.name) ? 1 : k) << in.name;
      second += got.stats.blocks_second_round;
    }
  }
  return second;
}

}  // namespace gg_devices
