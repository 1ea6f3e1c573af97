// Grids of 4 to 8 axes: the CUDA executor returns exactly what the CPU executor returns (every
// output, bit for bit), from host and device entries, with 32- and 64-bit site indices.
#include <gtest/gtest.h>

#include <cuda_runtime.h>

#include <string>
#include <vector>

#include "../common/device_arrays.hpp"
#include "edt_cases.hpp"
#include "exec/cuda_device.hpp"

using namespace gpugeom;
using gg_test::back;

namespace {
EdtOptions every_output_nd(const std::vector<double>& sampling, Backend b) {
  EdtOptions o;
  o.squared = true;
  o.distance = 32;
  o.features = true;
  o.labels = true;
  o.sampling = sampling;
  o.backend = b;
  return o;
}
}  // namespace

TEST(CudaEdtNd, SameAsCpuBitForBit) {
  struct Case {
    std::vector<std::int64_t> shape;
    double density;
    std::vector<double> sampling;
  };
  const std::vector<Case> cases{{{40, 36, 50, 45}, 0.0005, {}},
                                {{33, 20, 17, 64}, 0.05, {}},
                                {{24, 25, 26, 27}, 0.3, {0.5, 1.25, 2.0, 1.0}},
                                {{12, 11, 10, 9, 8}, 0.01, {}},
                                {{6, 5, 7, 4, 6, 5}, 0.02, {1.0, 2.0, 1.0, 0.5, 3.0, 1.0}},
                                {{4, 3, 5, 4, 3, 4, 3, 5}, 0.005, {}},
                                {{1, 30, 1, 40, 1}, 0.01, {}}};
  unsigned seed = 900;
  for (auto& c : cases) {
    const io::Grid g = gg_edt::random_grid(c.shape, c.density, seed++);
    for (bool wide : {false, true}) {
      EdtOptions o = every_output_nd(c.sampling, Backend::Cpu);
      o.wide_indices = wide;
      const auto cpu = distance_transform(g, SiteRule::NonZero, o);
      o.backend = Backend::Cuda;
      const auto gpu = distance_transform(g, SiteRule::NonZero, o);
      EXPECT_EQ(gpu.labels, cpu.labels);
      EXPECT_EQ(gpu.features, cpu.features);
      EXPECT_EQ(gpu.sqdist_int, cpu.sqdist_int);
      EXPECT_EQ(gpu.sqdist_real, cpu.sqdist_real);
      EXPECT_EQ(gpu.distance32, cpu.distance32);
      o.slices = {c.shape[0] - 1, 0, c.shape[0] / 2};
      const auto gs = distance_transform(g, SiteRule::NonZero, o);
      o.backend = Backend::Cpu;
      const auto cs = distance_transform(g, SiteRule::NonZero, o);
      EXPECT_EQ(gs.labels, cs.labels);
      EXPECT_EQ(gs.features, cs.features);
      EXPECT_EQ(gs.distance32, cs.distance32);
      EXPECT_EQ(gs.labels, gg_edt::slices_of(cpu, o.slices).labels);
    }
  }
}

TEST(CudaEdtNd, BruteForceOnSmallGrids) {
  unsigned seed = 950;
  for (auto shape :
       {std::vector<std::int64_t>{5, 6, 7, 8}, std::vector<std::int64_t>{3, 4, 3, 5, 4},
        std::vector<std::int64_t>{2, 3, 2, 2, 3, 2, 2, 3}})
    for (double d : {0.01, 0.2})
      gg_edt::expect_exact(gg_edt::random_grid(shape, d, seed++),
                           gg_edt::all_outputs(Backend::Cuda), "CUDA N-D");
}

TEST(CudaEdtNd, DeviceEntrySameAsHost) {
  const std::vector<std::int64_t> shape{20, 18, 16, 22};
  const io::Grid g = gg_edt::random_grid(shape, 0.02, 77);
  std::vector<float> f(g.data.size());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = g.data[i] ? 0.f : 1.5f;  // zeros are sites
  EdtOptions o = every_output_nd({}, Backend::Cpu);
  const auto ref = distance_transform(g, SiteRule::NonZero, o);
  const std::int64_t n = ref.count(), nd = std::int64_t(shape.size());
  const gg_test::Stream s;  // (outlives the results below)
  float* dg = nullptr;
  GG_CK(cudaMalloc(&dg, f.size() * sizeof(float)));
  GG_CK(cudaMemcpyAsync(dg, f.data(), f.size() * sizeof(float), cudaMemcpyHostToDevice, s));
  GridView v;
  v.data = dg;
  v.type = io::ScalarType::F32;
  v.shape = shape;
  o.backend = Backend::Cuda;
  o.stream = s;
  const auto r = distance_transform_device(v, SiteRule::Zero, o);
  EXPECT_EQ(r.backend, Backend::Cuda);
  EXPECT_EQ(back(r.sqdist_int.get(), n), ref.sqdist_int);
  EXPECT_EQ(back(r.distance32.get(), n), ref.distance32);
  EXPECT_EQ(back(r.features.get(), nd * n), ref.features);
  EXPECT_EQ(back(r.labels.get(), n), ref.labels);
  std::int32_t* df = nullptr;
  GG_CK(cudaMalloc(&df, sizeof(std::int32_t) * n * nd));
  EdtOptions w = o;
  w.into.features = {df, n * nd};
  const auto r2 = distance_transform_device(v, SiteRule::Zero, w);
  EXPECT_FALSE(r2.features);
  EXPECT_EQ(back(df, n * nd), ref.features);
  GG_CK(cudaFree(df));
  GG_CK(cudaFree(dg));
}
