// Weighted Lloyd iteration compiled for the CUDA executor (exec/dispatch.hpp).
#include "cvd/impl/unit.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"

namespace gpugeom::cvd::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "cvd/impl/density.inl"
#include "cvd/impl/lloyd.inl"
const Entries entries{&lloyd_impl};
}  // namespace gpugeom::cvd::cuda_impl
