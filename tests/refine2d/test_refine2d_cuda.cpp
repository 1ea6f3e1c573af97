// Delaunay refinement on the CUDA executor: the same points, triangles and marks as the CPU
// executor's (the rounds' choices are functions of the exact triangulation and of arithmetic
// that rounds alike on both), every mesh passing the exact checker with its bounds; the device
// entry; larger meshes timed (printed, never asserted).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "../common/device_arrays.hpp"
#include "refine2d_cases.hpp"

using namespace gpugeom;
using gg_refine::Domain;

namespace {
RefinedMesh2d on_both(const Domain& d, Refine2dOptions o) {
  o.backend = Backend::Cpu;
  const auto cpu = gg_refine::refine(d, o);
  o.backend = Backend::Cuda;
  const auto gpu = gg_refine::refine(d, o);
  EXPECT_EQ(gpu.points, cpu.points) << d.g.name;
  EXPECT_EQ(gpu.triangles, cpu.triangles) << d.g.name;
  EXPECT_EQ(gpu.neighbors, cpu.neighbors) << d.g.name;
  EXPECT_EQ(gpu.segment_of, cpu.segment_of) << d.g.name;
  EXPECT_EQ(gpu.small_angles, cpu.small_angles) << d.g.name;
  EXPECT_EQ(gpu.stats.backend, Backend::Cuda);
  return gpu;
}
Refine2dOptions options(double angle, double area) {
  Refine2dOptions o;
  o.min_angle = angle;
  o.max_area = area;
  return o;
}
}  // namespace

TEST(CudaRefine2d, SameAsCpu) {
  const std::vector<Domain> domains{gg_refine::square_with_hole(), gg_refine::letter_a(),
                                    gg_refine::small_angles(), gg_refine::coastline(2000),
                                    gg_refine::random_domain(3000, 3)};
  for (const Domain& d : domains)
    for (double angle : {20.0, 30.0}) {
      const auto o = options(angle, d.enclosed ? 2e-4 : 0.0);
      const auto r = on_both(d, o);
      gg_refine::expect_quality(d, r, o);
      std::printf("%s, angle %.1f: %zu triangles, %lld rounds\n", d.g.name.c_str(), angle,
                  r.num_triangles, (long long)r.stats.rounds);
    }
}

TEST(CudaRefine2d, DeviceEntry) {
  const Domain d = gg_refine::letter_a();
  Refine2dOptions o = options(30, 1e-3);
  o.domain = Cdt2dOptions::Domain::Enclosed;
  o.holes = d.holes;
  o.backend = Backend::Cuda;
  const auto host = refine2d(d.g.xy.data(), std::int64_t(d.g.xy.size() / 2), d.g.segs.data(),
                             std::int64_t(d.g.segs.size() / 2), o);
  gg_test::DeviceCopy xy(d.g.xy), segs(d.g.segs);
  const auto dev = refine2d_device(xy.doubles(), std::int64_t(d.g.xy.size() / 2),
                                   static_cast<const std::int32_t*>(segs.data()),
                                   std::int64_t(d.g.segs.size() / 2), o);
  ASSERT_EQ(dev.num_triangles, host.num_triangles);
  ASSERT_EQ(dev.num_points, host.num_points);
  EXPECT_EQ(gg_test::from_device(dev.triangles, 3 * dev.num_triangles),
            std::vector<std::int32_t>(host.triangles.begin(), host.triangles.end()));
  EXPECT_EQ(gg_test::from_device(dev.points, 2 * dev.num_points),
            std::vector<double>(host.points.begin(), host.points.end()));
  EXPECT_EQ(gg_test::from_device(dev.segment_of, 3 * dev.num_triangles),
            std::vector<std::int32_t>(host.segment_of.begin(), host.segment_of.end()));
}

// The caller's arrays (Refine2dOptions::into) on the GPU: host arrays from the host entry,
// device arrays from the device entry, the same values as the library's own.
TEST(CudaRefine2d, IntoCallersArrays) {
  const Domain d = gg_refine::letter_a();
  const std::int64_t n = std::int64_t(d.g.xy.size() / 2), m = std::int64_t(d.g.segs.size() / 2);
  Refine2dOptions o = options(30, 1e-3);
  o.backend = Backend::Cuda;
  const auto ref = refine2d(d.g.xy.data(), n, d.g.segs.data(), m, o);
  const std::int64_t np = ref.num_points, nt = ref.num_triangles,
                     ns = std::int64_t(ref.subsegment_of.size());
  std::vector<double> hp(std::size_t(2 * np));
  std::vector<std::int32_t> hs(std::size_t(2 * ns));
  auto mine = o;
  mine.into.points = {hp.data(), 2 * np};
  mine.into.subsegments = {hs.data(), 2 * ns};
  const auto h = refine2d(d.g.xy.data(), n, d.g.segs.data(), m, mine);
  EXPECT_TRUE(h.points.empty() && h.subsegments.empty());
  EXPECT_EQ(h.triangles, ref.triangles);
  EXPECT_EQ(hp, ref.points);
  EXPECT_EQ(hs, ref.subsegments);

  const gg_test::DeviceCopy dxy(d.g.xy), dsegs(d.g.segs);
  const gg_test::DeviceCopy out_t(std::vector<std::int32_t>(std::size_t(3 * nt + 3), 7));
  const gg_test::DeviceCopy out_p(std::vector<double>(std::size_t(2 * np), 7));
  auto dev = o;
  dev.into.triangles = {static_cast<std::int32_t*>(out_t.data()), 3 * nt + 3};
  dev.into.points = {static_cast<double*>(out_p.data()), 2 * np};
  const auto r =
      refine2d_device(dxy.doubles(), n, static_cast<const std::int32_t*>(dsegs.data()), m, dev);
  EXPECT_FALSE(r.triangles || r.points);
  ASSERT_TRUE(r.neighbors && r.subsegments);
  ASSERT_EQ(r.num_triangles, nt);
  std::vector<std::int32_t> t(std::size_t(3 * nt + 3));
  std::vector<double> p(std::size_t(2 * np));
  ASSERT_EQ(cudaMemcpy(t.data(), out_t.data(), t.size() * 4, cudaMemcpyDeviceToHost), cudaSuccess);
  ASSERT_EQ(cudaMemcpy(p.data(), out_p.data(), p.size() * 8, cudaMemcpyDeviceToHost), cudaSuccess);
  EXPECT_EQ(std::vector<std::int32_t>(t.begin(), t.begin() + 3 * nt), ref.triangles);
  EXPECT_EQ(t[std::size_t(3 * nt)], 7);  // (nothing past the result's length)
  EXPECT_EQ(p, ref.points);
  EXPECT_EQ(gg_test::from_device(r.neighbors, 3 * nt), ref.neighbors);
  EXPECT_EQ(gg_test::from_device(r.subsegments, 2 * ns), ref.subsegments);
}

// Larger meshes: times printed for the notes (the bench measures them properly).
TEST(CudaRefine2d, Larger) {
  for (double area : {1e-5, 1e-6, 1e-7}) {
    const Domain d = gg_refine::square_with_hole();
    auto o = options(30, area);
    o.backend = Backend::Cuda;
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = gg_refine::refine(d, o);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (area >= 1e-5) gg_refine::expect_quality(d, r, o);
    std::printf("square with a hole, area %g: %zu triangles, %lld rounds, %.1f ms\n", area,
                r.num_triangles, (long long)r.stats.rounds, ms);
  }
}
