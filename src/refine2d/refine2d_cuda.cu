// Delaunay refinement compiled for the CUDA executor (exec/dispatch.hpp).
#include "refine2d/impl/unit.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"

namespace gpugeom::refine::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace cdt_impl = ::gpugeom::cdt::cuda_impl;
#include "cdt2d/impl/segment_check.inl"
#include "refine2d/impl/rounds.inl"
#include "refine2d/impl/kept_mesh.inl"
#include "refine2d/impl/refine.inl"
const Entries entries{&refine_host, &refine_device_impl};
}  // namespace gpugeom::refine::cuda_impl
