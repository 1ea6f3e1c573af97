// The CUDA executor's Lloyd iterations equal the CPU executor's exactly: sites, masses and
// energies, on 2D and 3D densities large enough for many bands and many chunks per column.
#include <cuda_runtime.h>
#include <gtest/gtest.h>

#include "../common/device_arrays.hpp"

#include "cvd_cases.hpp"

using namespace gpugeom;

TEST(CudaCvd, SameAsCpu) {
  struct Case {
    std::vector<std::int64_t> shape;
    double zero_frac;
    std::int64_t sites;
    int supersample;
  };
  const std::vector<Case> cases{{{700, 500}, 0.0, 2000, 1},  {{333, 1025}, 0.4, 50, 1},
                                {{256, 256}, 0.1, 20000, 1}, {{120, 90}, 0.2, 500, 3},
                                {{64, 70, 90}, 0.0, 700, 1}, {{40, 33, 130}, 0.5, 60, 1},
                                {{1, 3000}, 0.0, 40, 1}};
  unsigned seed = 1;
  for (const auto& c : cases) {
    const io::Grid g = gg_cvd::random_density(c.shape, c.zero_frac, seed++);
    CvdOptions o;
    o.num_sites = c.sites;
    o.supersample = c.supersample;
    o.max_iterations = 12;
    o.move_tolerance = 0;
    o.seed = seed;
    o.backend = Backend::Cpu;
    const auto cpu = centroidal_voronoi(g, o);
    o.backend = Backend::Cuda;
    const auto gpu = centroidal_voronoi(g, o);
    SCOPED_TRACE("case " + std::to_string(seed - 1));
    EXPECT_EQ(gpu.sites, cpu.sites);
    EXPECT_EQ(gpu.mass, cpu.mass);
    EXPECT_EQ(gpu.iterations, cpu.iterations);
    ASSERT_EQ(gpu.energy.size(), cpu.energy.size());
    for (std::size_t i = 0; i < cpu.energy.size(); ++i)  // summed in another order: rounding
      EXPECT_NEAR(gpu.energy[i], cpu.energy[i], 1e-12 * cpu.energy[i]);
    for (std::size_t i = 1; i < gpu.energy.size(); ++i)
      EXPECT_LE(gpu.energy[i], gpu.energy[i - 1] * (1 + 1e-15));
  }
}

// A small case against the brute-force step, on the device itself.
TEST(CudaCvd, StepEqualsBruteForce) {
  const io::Grid g = gg_cvd::random_density({45, 61}, 0.3, 77);
  std::vector<double> sites = gg_cvd::random_sites(g, 90, 78);
  for (int it = 0; it < 3; ++it) {
    const auto ref = gg_cvd::brute_step(g, sites);
    CvdOptions o;
    o.backend = Backend::Cuda;
    o.initial_sites = sites;
    o.max_iterations = 1;
    o.move_tolerance = 0;
    const auto r = centroidal_voronoi(g, o);
    ASSERT_EQ(r.sites, ref.sites);
    ASSERT_EQ(r.mass, ref.mass);
    ASSERT_EQ(r.energy[0], ref.energy);
    sites = ref.sites;
  }
}

// The density in device memory (float32, on a caller's non-blocking stream), the sites left
// there: the same diagram as the host entry's.
TEST(CudaCvd, DeviceEntrySameAsHost) {
  const io::Grid g16 = gg_cvd::random_density({300, 420}, 0.2, 4);
  const std::int64_t n = g16.count();
  std::vector<float> f(static_cast<std::size_t>(n));
  for (std::int64_t i = 0; i < n; ++i) f[i] = float(g16.value(i));
  CvdOptions o;
  o.num_sites = 3000;
  o.max_iterations = 10;
  o.move_tolerance = 0;
  o.backend = Backend::Cuda;
  const auto ref = centroidal_voronoi(g16, o);
  const gg_test::Stream s;  // (outlives the result below)
  float* df = nullptr;
  ASSERT_EQ(cudaMallocAsync(reinterpret_cast<void**>(&df), n * sizeof(float), s), cudaSuccess);
  ASSERT_EQ(cudaMemcpyAsync(df, f.data(), n * sizeof(float), cudaMemcpyHostToDevice, s),
            cudaSuccess);
  GridView v;
  v.data = df;
  v.type = io::ScalarType::F32;
  v.shape = g16.shape;
  o.stream = s;  // the copy above is ordered before the call's work on s
  const auto r = centroidal_voronoi_device(v, o);
  EXPECT_EQ(r.backend, Backend::Cuda);
  ASSERT_EQ(r.num_sites, ref.num_sites);
  std::vector<double> sites(std::size_t(2 * r.num_sites)), mass(std::size_t(r.num_sites));
  ASSERT_EQ(cudaMemcpy(sites.data(), r.sites.get(), sites.size() * 8, cudaMemcpyDeviceToHost),
            cudaSuccess);
  ASSERT_EQ(cudaMemcpy(mass.data(), r.mass.get(), mass.size() * 8, cudaMemcpyDeviceToHost),
            cudaSuccess);
  EXPECT_EQ(sites, std::vector<double>(ref.sites.begin(), ref.sites.end()));
  EXPECT_EQ(mass, std::vector<double>(ref.mass.begin(), ref.mass.end()));
  EXPECT_EQ(r.energy, ref.energy);
  cudaFreeAsync(df, s);
}
