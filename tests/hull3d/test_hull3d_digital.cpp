// The digital 3D convex hull (issue 20, thesis 4.4) on the CPU executor: the same facets and
// vertices as the incremental method on every distribution and degenerate input, on coarse and
// automatic grids (a coarse grid's sketch misses most hull vertices, so the depth test must
// find them all); the depth test discards points (it is not a pass-through); errors.
#include <cmath>
#include <random>
#include <string>

#include "hull3d_cases.hpp"

using namespace gpugeom;

using gg_hull3d::cpu;

TEST(DigitalHull3d, SameHullAsIncrementalOnDistributions) {
  std::int64_t fallbacks = 0, cases = 0;
  for (const auto& c : gg_hull3d::distribution_cases({4, 5, 10, 100, 1000, 20000}, 11))
    for (std::int64_t grid : {0, 16}) {
      const auto h = gg_hull3d::expect_digital_same(c, cpu(), grid);
      fallbacks += h.stats.digital_fallback;
      ++cases;
    }
  std::cout << "digital hull over " << cases << " cases: " << fallbacks << " fall backs\n";
  EXPECT_LT(fallbacks, cases / 4);
}

TEST(DigitalHull3d, SameHullAsIncrementalOnDegenerateInput) {
  for (const auto& c : gg_hull3d::degenerate_cases())
    for (std::int64_t grid : {0, 16, 64}) gg_hull3d::expect_digital_same(c, cpu(), grid);
}

// Shapes a grid frames badly: a slab 10^-7 thick, a thin bar far from the origin, two clusters
// far apart (the grid between them empty), a coarse lattice with many copies; grids of odd and
// automatic sides.
TEST(DigitalHull3d, SameHullOnShapesAGridFramesBadly) {
  for (int kind = 0; kind < 4; ++kind)
    for (int n : {9, 60, 2000}) {
      std::mt19937_64 r(std::uint64_t(100 * kind + n));
      std::uniform_real_distribution<double> U(-1, 1);
      gg_hull3d::Case c{"shape" + std::to_string(kind) + "/" + std::to_string(n), {}};
      for (int i = 0; i < n; ++i) {
        double x = U(r), y = U(r), z = U(r);
        if (kind == 0) z *= 1e-7;
        if (kind == 1) x = 1e6 + 1e-3 * x;
        if (kind == 2 && i % 2) x += 1000;
        if (kind == 3)
          x = std::round(4 * x) / 4, y = std::round(4 * y) / 4, z = std::round(4 * z) / 4;
        c.pts.push_back({x, y, z});
      }
      for (std::int64_t grid : {0, 16, 17}) gg_hull3d::expect_digital_same(c, cpu(), grid);
    }
}

// On a ball most points are deep inside the sketch's hull: the depth test drops them, and the
// last hull is computed from a small part of the input. On a sphere every point is a vertex:
// all are kept.
TEST(DigitalHull3d, DepthTestDropsInteriorPointsAndKeepsExtremeOnes) {
  const gg_hull3d::Case ball{"ball", generate3d("ball", 100000, 3)};
  const auto b = gg_hull3d::expect_digital_same(ball, cpu(), 0);
  EXPECT_EQ(b.stats.digital_fallback, 0);
  EXPECT_LT(b.stats.hull_input, 100000 / 5);
  EXPECT_GT(b.stats.sketch_points, 0);
  const gg_hull3d::Case sphere{"sphere", generate3d("sphere", 20000, 4)};
  const auto s = gg_hull3d::expect_digital_same(sphere, cpu(), 0);
  EXPECT_EQ(s.stats.hull_input, 20000);
  // A coarse grid: few sketch points, so most vertices come from the depth test.
  const auto c = gg_hull3d::expect_digital_same(sphere, cpu(), 16);
  EXPECT_GT(c.stats.depth_kept, c.stats.sketch_points);
}

TEST(DigitalHull3d, DeviceEntryOnTheCpuExecutor) {
  auto p = generate3d("ball", 5000, 8);
  for (int k = 0; k < 20; ++k) p.push_back(p[std::size_t(17 * k)]);  // copies
  auto o = cpu();
  o.method = Method::Digital;
  const auto ref = convex_hull3d(p, o);
  const auto dv = convex_hull3d_device(&p.data()->x, std::int64_t(p.size()), o);
  ASSERT_EQ(dv.num_facets, ref.num_facets);
  const std::vector<std::int32_t> tri(dv.triangles.get(), dv.triangles.get() + 3 * dv.num_facets);
  EXPECT_EQ(tri, std::vector<std::int32_t>(ref.triangles.begin(), ref.triangles.end()));
}

TEST(DigitalHull3d, Errors) {
  const auto p = generate3d("ball", 100, 1);
  auto o = cpu();
  o.method = Method::Digital;
  for (std::int64_t g : {-1, 8, 15, 8193}) {
    o.grid = g;
    try {
      convex_hull3d(p, o);
      ADD_FAILURE() << "grid " << g << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
      EXPECT_NE(std::string(e.what()).find("grid"), std::string::npos);
    }
  }
  o.method = Method::Incremental;
  o.grid = 64;
  EXPECT_THROW(convex_hull3d(p, o), Error);
  // Input the incremental method refuses is refused with the same error.
  o.method = Method::Digital;
  o.grid = 0;
  std::vector<Point3> flat;
  for (int i = 0; i < 50; ++i) flat.push_back({double(i % 7), double(i / 7), 0});
  try {
    convex_hull3d(flat, o);
    ADD_FAILURE() << "coplanar points accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::DegenerateInput);
  }
  flat[3].x = std::nan("");
  EXPECT_THROW(convex_hull3d(flat, o), Error);
}
