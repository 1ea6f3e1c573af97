// Device query for builds without CUDA: there is never a device to use.
#include "gpugeom/common.hpp"
#include "gpugeom/memory.hpp"

namespace gpugeom {
bool built_with_cuda() {
  return false;
}
std::string built_cuda_architectures() {
  return "";
}
DeviceInfo query_device(int) {
  DeviceInfo d;
  d.reason = "this build of gpugeom was compiled without CUDA (GPUGEOM_CUDA=OFF or no nvcc)";
  return d;
}
void release_cached_device_memory() {}
std::shared_ptr<DeviceMemoryResource> library_memory_resource() {
  return nullptr;
}
void prepare_device(int) noexcept {}
}  // namespace gpugeom
