// The CUDA executor's Lloyd iterations equal the CPU executor's exactly: sites, masses and
// energies, on 2D and 3D densities large enough for many bands and many chunks per column.
#include <gtest/gtest.h>

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
