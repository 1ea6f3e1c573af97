// Reads of one GPU's memory by kernels on another, for as long as the object lives: the several
// devices' blocks gather their points on their own devices from the first device, where the
// points were prepared and split (blocks/delaunay_devices.cpp). Host code may hold one (no CUDA
// types here; a build without CUDA has only the same device to read).
#pragma once
#include <memory>

namespace gpugeom::detail {

class PeerReads {
 public:
  // reader, owner: device ordinals. Peer access is turned on where the GPUs have it (and off
  // again when the object goes, unless it was on before).
  PeerReads(int reader, int owner);
  ~PeerReads();
  PeerReads(PeerReads&&) noexcept;
  PeerReads(const PeerReads&) = delete;
  PeerReads& operator=(const PeerReads&) = delete;
  PeerReads& operator=(PeerReads&&) = delete;
  // Whether kernels on `reader` may read `owner`'s memory (always on the same device).
  bool readable() const { return readable_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool readable_ = false;
};

}  // namespace gpugeom::detail
