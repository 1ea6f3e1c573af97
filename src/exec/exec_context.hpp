// What a running executor shares with another capability it calls (internal): the device, the
// stream and the call's memory. Executors cannot cross from one unit to another
// (exec/dispatch.hpp says why), so a capability that runs another on its own executor (the CDT
// its Delaunay triangulation, the Voronoi diagrams and cells their tetrahedralisation) passes
// this plain host struct through the other's entry, which builds its executor from it: both then
// run on one stream, and one count of the call's memory (Stats' device_peak_bytes) sees both.
#pragma once
#include <memory>

namespace gpugeom::detail {

class CallMemory;  // exec/device_memory.hpp (CUDA builds)

struct ExecContext {
  int device = -1;
  void* stream = nullptr;              // the CUDA stream (cudaStream_t)
  std::shared_ptr<CallMemory> memory;  // null on the CPU executor
};

}  // namespace gpugeom::detail
