// 3D convex hull compiled for the CUDA executor (exec/dispatch.hpp).
#include "hull3d/impl/unit.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"

namespace gpugeom::hull3d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "hull3d/impl/unit.inl"
#include "hull3d/impl/entries.inl"
}  // namespace gpugeom::hull3d::cuda_impl
