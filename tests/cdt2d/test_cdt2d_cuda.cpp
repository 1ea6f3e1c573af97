// The constrained Delaunay triangulation with the Delaunay step on the CUDA executor: the same
// arrays as the CPU executor's, every result passing the exact checker.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "../common/device_arrays.hpp"
#include "cdt2d_cases.hpp"
#include "gpugeom/delaunay2d.hpp"

using namespace gpugeom;

namespace {
struct Both {
  ConstrainedTriangulation2d cpu, gpu;
};
// g triangulated with options o on the CPU executor, then on CUDA; the arrays must agree.
Both on_both(const gg_cdt::Pslg& g, Cdt2dOptions o) {
  const std::int64_t n = std::int64_t(g.xy.size() / 2), m = std::int64_t(g.segs.size() / 2);
  Both b;
  o.backend = Backend::Cpu;
  b.cpu = cdt2d(g.xy.data(), n, g.segs.data(), m, o);
  o.backend = Backend::Cuda;
  b.gpu = cdt2d(g.xy.data(), n, g.segs.data(), m, o);
  EXPECT_EQ(b.gpu.triangles, b.cpu.triangles) << g.name;
  EXPECT_EQ(b.gpu.neighbors, b.cpu.neighbors) << g.name;
  EXPECT_EQ(b.gpu.segment_of, b.cpu.segment_of) << g.name;
  return b;
}
}  // namespace

TEST(CudaCdt2d, SameAsCpu) {
  std::vector<gg_cdt::Pslg> cases{gg_cdt::grid_pslg(16), gg_cdt::thin_polygon(200),
                                  gg_cdt::circle_pslg(256, 3)};
  for (unsigned seed : {1u, 2u}) cases.push_back(gg_cdt::random_pslg(100000, 30000, seed));
  for (unsigned seed : {3u, 4u}) cases.push_back(gg_cdt::random_pslg(20000, 3000, seed, 1));
  cases.push_back(gg_cdt::contour_pslg(40, 5000, 100000, 5));
  if (!std::getenv("GG_UNDER_SANITIZER"))  // (10^6 points under the sanitizer: slow)
    cases.push_back(gg_cdt::coastline_pslg(1000000, 6));
  for (const auto& g : cases) {
    const std::int64_t m = std::int64_t(g.segs.size() / 2);
    const auto gpu = on_both(g, Cdt2dOptions{}).gpu;
    gg_cdt::expect_cdt(g, gpu);
    EXPECT_EQ(gpu.stats.backend, Backend::Cuda) << g.name;
    std::printf(
        "%s: %lld triangles, %lld segments (%lld recovered, %lld cavity triangles, %lld rounds)",
        g.name.c_str(), (long long)gpu.num_triangles, (long long)m,
        (long long)gpu.stats.segments_recovered, (long long)gpu.stats.cavity_triangles,
        (long long)gpu.stats.recovery_rounds);
    for (const auto& ph : gpu.stats.phase_ms)
      std::printf(", %s %.1f ms", ph.first.c_str(), ph.second);
    std::printf("\n");
  }
}

// Crossings::Split on the CUDA executor: the same new points and arrays as the CPU executor's.
TEST(CudaCdt2d, SplitSameAsCpu) {
  for (unsigned seed : {5u, 6u}) {
    const auto g = gg_cdt::crossing_pslg(20000, 400, seed);
    Cdt2dOptions o;
    o.crossings = Cdt2dOptions::Crossings::Split;
    const auto [cpu, gpu] = on_both(g, o);
    gg_cdt::expect_split_cdt(g, gpu);
    EXPECT_EQ(gpu.new_points, cpu.new_points) << g.name;
    std::printf("%s: %lld crossings split, %lld segments cut\n", g.name.c_str(),
                (long long)gpu.stats.crossings, (long long)gpu.stats.segments_split);
  }
}

// Holes, the outside and regions on the CUDA executor: the same kept triangles, neighbours,
// marks and attributes as the CPU executor's (contour rings: the outside of the outermost
// removed, a hole between two rings, regions in others).
TEST(CudaCdt2d, DomainSameAsCpu) {
  const auto g = gg_cdt::contour_pslg(12, 3000, 50000, 7);
  Cdt2dOptions o;
  o.domain = Cdt2dOptions::Domain::Enclosed;
  o.holes = {{0.0, 0.33}};
  o.regions = {{0.0, 0.6, 2.0}, {0.0, 0.05, 5.0}, {0.5, 0.5, 7.0}};
  const auto [cpu, gpu] = on_both(g, o);
  EXPECT_GT(gpu.removed_triangles, 0);
  EXPECT_EQ(gpu.removed_triangles, cpu.removed_triangles);
  EXPECT_EQ(gpu.attribute, cpu.attribute);
  std::printf("contour domain: %lld kept, %lld removed, phases:", (long long)gpu.num_triangles,
              (long long)gpu.removed_triangles);
  for (const auto& ph : gpu.stats.phase_ms) std::printf(" %s %.1f ms", ph.first.c_str(), ph.second);
  std::printf("\n");
}

// The device entry on CUDA: points and segments in device memory, the result left there; the
// same arrays as the host entry's.
TEST(CudaCdt2d, DeviceEntry) {
  const auto g = gg_cdt::random_pslg(200000, 60000, 9);
  const std::int64_t n = std::int64_t(g.xy.size() / 2), m = std::int64_t(g.segs.size() / 2);
  Cdt2dOptions o;
  o.backend = Backend::Cuda;
  o.domain = Cdt2dOptions::Domain::Enclosed;
  const auto h = cdt2d(g.xy.data(), n, g.segs.data(), m, o);
  const gg_test::DeviceCopy dxy(g.xy), dsegs(g.segs);
  const auto d = cdt2d_device(static_cast<const double*>(dxy.data()), n,
                              static_cast<const std::int32_t*>(dsegs.data()), m, o);
  ASSERT_EQ(d.num_triangles, h.num_triangles);
  EXPECT_EQ(d.backend, Backend::Cuda);
  EXPECT_EQ(gg_test::from_device(d.triangles, 3 * d.num_triangles), h.triangles);
  EXPECT_EQ(gg_test::from_device(d.neighbors, 3 * d.num_triangles), h.neighbors);
  EXPECT_EQ(gg_test::from_device(d.segment_of, 3 * d.num_triangles), h.segment_of);
  EXPECT_EQ(gg_test::from_device(d.duplicate_of, n), h.duplicate_of);
  EXPECT_EQ(d.removed_triangles, h.removed_triangles);
  std::vector<std::int32_t> bad = g.segs;
  bad[11] = -1;
  const gg_test::DeviceCopy dbad(bad);
  EXPECT_THROW(cdt2d_device(static_cast<const double*>(dxy.data()), n,
                            static_cast<const std::int32_t*>(dbad.data()), m, o),
               Error);
}

// Into the caller's device arrays (Cdt2dOptions::into) from the device entry, and into host
// arrays from the host entry, on CUDA: the same arrays as the library's.
TEST(CudaCdt2d, IntoCallersArrays) {
  const auto g = gg_cdt::random_pslg(20000, 3000, 7);
  const std::int64_t n = std::int64_t(g.xy.size() / 2), m = std::int64_t(g.segs.size() / 2);
  Cdt2dOptions o;
  o.backend = Backend::Cuda;
  const auto ref = cdt2d(g.xy.data(), n, g.segs.data(), m, o);
  const std::int64_t nt = ref.num_triangles, cap = 3 * delaunay2d_max_triangles(n);
  std::vector<std::int32_t> ht(std::size_t(cap), 7), hs(std::size_t(cap), 7);
  auto mine = o;
  mine.into.triangles = {ht.data(), cap};
  mine.into.segment_of = {hs.data(), cap};
  const auto h = cdt2d(g.xy.data(), n, g.segs.data(), m, mine);
  EXPECT_TRUE(h.triangles.empty() && h.segment_of.empty());
  EXPECT_EQ(h.neighbors, ref.neighbors);
  ASSERT_EQ(h.num_triangles, nt);
  EXPECT_EQ(std::vector<std::int32_t>(ht.begin(), ht.begin() + 3 * nt), ref.triangles);
  EXPECT_EQ(std::vector<std::int32_t>(hs.begin(), hs.begin() + 3 * nt), ref.segment_of);

  const gg_test::DeviceCopy dxy(g.xy), dsegs(g.segs);
  std::int32_t *t = nullptr, *d = nullptr;
  ASSERT_EQ(cudaMalloc(&t, cap * 4), cudaSuccess);
  ASSERT_EQ(cudaMalloc(&d, n * 4), cudaSuccess);
  auto dev = o;
  dev.into.triangles = {t, cap};
  dev.into.duplicate_of = {d, n};
  const auto r =
      cdt2d_device(dxy.doubles(), n, static_cast<const std::int32_t*>(dsegs.data()), m, dev);
  EXPECT_FALSE(r.triangles || r.duplicate_of);
  ASSERT_TRUE(r.neighbors && r.segment_of);
  ASSERT_EQ(r.num_triangles, nt);
  std::vector<std::int32_t> t2(static_cast<std::size_t>(3 * nt)), d2(static_cast<std::size_t>(n));
  ASSERT_EQ(cudaMemcpy(t2.data(), t, t2.size() * 4, cudaMemcpyDeviceToHost), cudaSuccess);
  ASSERT_EQ(cudaMemcpy(d2.data(), d, d2.size() * 4, cudaMemcpyDeviceToHost), cudaSuccess);
  EXPECT_EQ(t2, ref.triangles);
  EXPECT_EQ(d2, ref.duplicate_of);
  EXPECT_EQ(gg_test::from_device(r.segment_of, 3 * nt), ref.segment_of);
  cudaFree(t);
  cudaFree(d);
}
