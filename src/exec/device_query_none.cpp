// Device query for builds without CUDA: there is never a device to use.
#include "gpugeom/common.hpp"

namespace gpugeom {
bool built_with_cuda() {
  return false;
}
DeviceInfo query_device() {
  DeviceInfo d;
  d.reason = "this build of gpugeom was compiled without CUDA (GPUGEOM_CUDA=OFF or no nvcc)";
  return d;
}
}  // namespace gpugeom
