// Per-device state the CUDA executor needs and the library owns (CUDA builds only): which device
// a call runs on, the library's own stream-ordered memory pool on each device (the default
// memory resource, gpugeom/memory.hpp), the memory check before a large call. Nothing here
// changes process-wide CUDA state (the device's default pool, the current device of a thread
// beyond the call that set it).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include <cuda_runtime.h>

#include "gpugeom/common.hpp"
#include "exec/device_memory.hpp"

namespace gpugeom::cuda_device {

// The device a call with these options runs on: run.device when set (checked to exist and be
// usable by this build), else the stream's device, else the calling thread's current device.
// Throws Error(InvalidArgument) for a device that does not exist, Error(Unsupported) for one
// this build has no code for.
int resolve(const RunOptions& run);

// The library's memory pool on `device`, created on first use. Freed blocks stay in it for the
// next call (as CuPy's pool keeps them): by default a pool returns them to the driver at every
// synchronisation, and the next large allocation then maps fresh pages (about 1 ms per 512 MB).
cudaMemPool_t pool(int device);
// Returns the pool's unused blocks to the driver (after an allocation failed, or on request).
void trim(int device);

// Sets the calling thread's current device for a scope, restoring the previous one after.
class Scope {
 public:
  explicit Scope(int device);
  ~Scope();
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

 private:
  int prev_ = -1;
  bool changed_ = false;
};

// Direct reads by `device` of `peer`'s memory (cudaDeviceEnablePeerAccess) for the scope's life,
// where the hardware has them and they were not on already; turned off again at the end, so the
// process's state is as it was. Copies on device's streams from the peer's memory then go over
// the link instead of through the host. Nothing where device is peer or either is negative.
// Keep it until the copies that use it have run.
class PeerScope {
 public:
  PeerScope(int device, int peer);
  ~PeerScope();
  PeerScope(PeerScope&& o) noexcept : device_(o.device_), peer_(o.peer_), enabled_(o.enabled_) {
    o.enabled_ = false;
  }
  PeerScope(const PeerScope&) = delete;
  PeerScope& operator=(const PeerScope&) = delete;
  PeerScope& operator=(PeerScope&&) = delete;

 private:
  int device_ = -1, peer_ = -1;
  bool enabled_ = false;
};

// The message of an allocation failure: the bytes wanted and those free on the device.
[[noreturn]] void throw_out_of_memory(std::size_t bytes, const char* what);

// Refuses, before any launch, a problem whose least memory exceeds what the device has left
// (free memory plus what the call's resource holds unused): Error(OutOfMemory) naming the
// problem, the bytes needed and the bytes free. `bytes` is a lower bound (the arrays a run
// certainly holds at once, docs/performance.md's bytes per element), so a refusal is certain; a
// problem that passes may still run out later (the typed error of the allocation that fails).
// With the library's pool, a problem larger than the driver's free memory first hands the
// pool's unused blocks back (after the call's own stream has run its queued frees).
void require_memory(detail::CallMemory& mem, cudaStream_t s, std::uint64_t bytes,
                    const std::string& what);
// What the device has left for a call: free memory plus what its resource holds unused.
std::uint64_t available_memory(const detail::CallMemory& mem);

}  // namespace gpugeom::cuda_device
