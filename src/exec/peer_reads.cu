// exec/peer_reads.hpp on CUDA: cuda_device::PeerScope (peer access on for the object's life where
// this call turned it on) after the driver says the reader can reach the owner at all.
#include "exec/peer_reads.hpp"

#include <utility>

#include "exec/cuda_check.cuh"
#include "exec/cuda_device.hpp"

namespace gpugeom::detail {

struct PeerReads::Impl {
  cuda_device::PeerScope scope;
};

PeerReads::PeerReads(int reader, int owner) {
  if (reader < 0 || owner < 0) return;
  if (reader == owner) {
    readable_ = true;
    return;
  }
  int can = 0;
  GG_CUDA_CHECK(cudaDeviceCanAccessPeer(&can, reader, owner));
  if (!can) return;
  impl_ = std::make_unique<Impl>(Impl{cuda_device::PeerScope(reader, owner)});
  readable_ = true;
}
PeerReads::~PeerReads() = default;
PeerReads::PeerReads(PeerReads&& o) noexcept
    : impl_(std::move(o.impl_)), readable_(std::exchange(o.readable_, false)) {}

}  // namespace gpugeom::detail
