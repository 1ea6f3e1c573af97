/// @file
/// Where the CUDA executor takes its device memory: a stream-ordered memory resource the caller
/// may pass in RunOptions::memory (issue 48), so that one allocator serves a whole process (a
/// PyTorch or CuPy program, an RMM pool) instead of two caching allocators fighting over the
/// device.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>

namespace gpugeom {

/// A stream-ordered allocator of device memory, the interface of CCCL's `cuda::mr` async
/// resources and RMM's `device_memory_resource`, without their headers (so that this one needs
/// no CUDA). The CUDA executor takes every device array of a call through it, the device
/// results it hands back included; the CPU executor never calls it.
///
/// Both members are called with the call's device current, on the host thread that runs the
/// call (deallocate: the thread that drops a device result's last reference), and `stream` is
/// a `cudaStream_t` of that device.
class DeviceMemoryResource {
 public:
  virtual ~DeviceMemoryResource() = default;
  /// `bytes` (> 0) of device memory, aligned to at least `alignment` (a power of two, at most
  /// 256), usable by work queued on `stream` after this returns. Throws on failure: an
  /// Error(OutOfMemory) passes through unchanged, and the library turns any other exception
  /// into one that names the size and the exception's message.
  virtual void* allocate(std::size_t bytes, std::size_t alignment, void* stream) = 0;
  /// Gives back a block `allocate` returned, with the same `bytes` and `alignment`, after all
  /// work queued on `stream` before this call (the block's last uses) is done with it. Must
  /// not throw; it may return before that work ran.
  virtual void deallocate(void* p, std::size_t bytes, std::size_t alignment,
                          void* stream) noexcept = 0;
  /// Bytes this resource holds unused on `device` and hands out without asking the driver
  /// (a caching pool's free blocks), or 0 when it cannot tell. Before a large problem starts,
  /// the library refuses it (Error(OutOfMemory)) only when its least memory exceeds the
  /// device's free memory plus this.
  virtual std::uint64_t cached_bytes(int device) const noexcept {
    (void)device;
    return 0;
  }
};

/// The library's own resource, used where RunOptions::memory is empty: one stream-ordered pool
/// (`cudaMemPool_t`) per device, created on first use, keeping freed blocks for the next call
/// as CuPy's pool does (release_cached_device_memory() hands them back). An allocation that
/// fails hands the pool's unused blocks back to the driver and tries once more. Null in a
/// build without CUDA.
std::shared_ptr<DeviceMemoryResource> library_memory_resource();

}  // namespace gpugeom
