// Device query for builds without CUDA: there is never a device to use.
#include <utility>

#include "gpugeom/common.hpp"
#include "gpugeom/memory.hpp"
#include "exec/peer_reads.hpp"

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

namespace detail {
// (no devices: only "the same device" is readable, and no block runs on one)
struct PeerReads::Impl {};
PeerReads::PeerReads(int reader, int owner) : readable_(reader >= 0 && reader == owner) {}
PeerReads::~PeerReads() = default;
PeerReads::PeerReads(PeerReads&& o) noexcept : impl_(std::move(o.impl_)), readable_(o.readable_) {
  o.readable_ = false;
}
}  // namespace detail
}  // namespace gpugeom
