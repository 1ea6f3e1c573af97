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
                  r.num_triangles, (long long)r.stats.counters.at("rounds"));
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
                r.num_triangles, (long long)r.stats.counters.at("rounds"), ms);
  }
}
