// The distance transform compiled for the CUDA executor.
#include <chrono>
#include <cuda/atomic>
#include <cstdlib>
#include <functional>
#include <cmath>
#include <string>
#include <type_traits>

#include "base/clock.hpp"
#include "edt/edt_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/grid_input.hpp"

namespace gpugeom::edt::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#define GG_EDT_TILES "edt/impl/cuda_tiles.inl"
#define GG_EDT_PASSES "edt/impl/cuda_passes.inl"
#include "edt/impl/packings.inl"
}  // namespace gpugeom::edt::cuda_impl
