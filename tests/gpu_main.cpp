// main() of the GPU test binaries: exit 77 (CTest "skipped") when no CUDA device is usable, so
// the gpu label never fails for lack of hardware, and says so.
#include <gtest/gtest.h>

#include <cstdio>

#include "gpugeom/common.hpp"

int main(int argc, char** argv) {
  gpugeom::DeviceInfo d = gpugeom::query_device();
  if (!d.available) {
    std::printf("SKIPPED: no usable CUDA device (%s)\n", d.reason.c_str());
    return 77;
  }
  std::printf("GPU: %s, %d SMs, %zu MiB\n", d.name.c_str(), d.multiprocessors,
              d.total_memory >> 20);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
