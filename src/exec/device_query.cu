// What the CUDA runtime says about the device; compiled only when the build has CUDA.
#include <cuda_runtime.h>

#include "gpugeom/common.hpp"

namespace gpugeom {

bool built_with_cuda() {
  return true;
}

DeviceInfo query_device() {
  DeviceInfo d;
  int n = 0;
  cudaError_t e = cudaGetDeviceCount(&n);
  if (e != cudaSuccess || n == 0) {
    d.reason = e != cudaSuccess
                   ? std::string("no usable CUDA driver/device (") + cudaGetErrorString(e) + ")"
                   : std::string("no CUDA device found");
    cudaGetLastError();  // clear the sticky-free error so later calls start clean
    return d;
  }
  int dev = 0;
  cudaDeviceProp p{};
  if ((e = cudaGetDeviceProperties(&p, dev)) != cudaSuccess) {
    d.reason = std::string("cannot read device properties: ") + cudaGetErrorString(e);
    return d;
  }
  d.name = p.name;
  d.compute_major = p.major;
  d.compute_minor = p.minor;
  d.multiprocessors = p.multiProcessorCount;
  d.total_memory = p.totalGlobalMem;
  std::size_t fr = 0, tot = 0;
  if (cudaMemGetInfo(&fr, &tot) == cudaSuccess) d.free_memory = fr;
  if (p.major < 7) {
    d.reason = "compute capability " + std::to_string(p.major) + "." + std::to_string(p.minor) +
               " is older than this build supports (7.0+)";
    return d;
  }
  d.available = true;
  return d;
}

}  // namespace gpugeom
