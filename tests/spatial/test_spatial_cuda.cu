// The CUDA Hilbert sort returns exactly the CPU's order (ties keep input order on both).
#include <gtest/gtest.h>

#include "gpugeom/generate.hpp"
#include "gpugeom/spatial.hpp"

using namespace gpugeom;

TEST(CudaSpatial, SameOrderAsCpu) {
  for (const char* d : {"uniform", "grid", "sphere"}) {
    auto p3 = generate3d(d, 1000003, 9);
    EXPECT_EQ(hilbert_order(p3, Backend::Cuda), hilbert_order(p3, Backend::Cpu)) << d;
  }
  auto p2 = generate2d("gaussian", 777777, 4);
  EXPECT_EQ(hilbert_order(p2, Backend::Cuda), hilbert_order(p2, Backend::Cpu));
}
