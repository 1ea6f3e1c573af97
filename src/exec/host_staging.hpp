// Large copies between pageable host memory and the device through pinned staging buffers
// (internal; CUDA builds only). A pageable cudaMemcpy moves about 3 GB/s on the H100 host;
// chunks through two pinned buffers, with the host-side copies spread over the cores and
// overlapped with the next chunk's transfer, move about an order of magnitude faster.
#pragma once
#include <cstddef>

#include <cuda_runtime.h>

namespace gpugeom::staging {

// Below this size a plain copy costs less than the pipeline. (From about 256 KB up the pageable
// path's rate, 3-8 GB/s, costs more than a transfer into pinned memory and a host copy: a hull's
// 5 MB of result arrays came back in 0.6 ms through it.)
constexpr std::size_t kMinBytes = std::size_t(256) << 10;

// Both wait for the copy to finish. Work queued on stream s before the call is ordered before
// the copy.
void to_host(void* host, const void* device, std::size_t bytes, cudaStream_t s);
void from_host(void* device, const void* host, std::size_t bytes, cudaStream_t s);

// Small reads (counters, one element): through a pinned mailbox, since a copy into pageable
// memory takes the driver's slow path. Waits for the copy.
constexpr std::size_t kMailBytes = 4096;
void small_to_host(void* host, const void* device, std::size_t bytes, cudaStream_t s);

}  // namespace gpugeom::staging
