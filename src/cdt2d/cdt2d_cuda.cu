// 2D constrained Delaunay triangulation compiled for the CUDA executor (exec/dispatch.hpp).
#include "cdt2d/impl/unit.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"

namespace gpugeom::cdt::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace dt_impl = ::gpugeom::del2d::cuda_impl;
#include "cdt2d/impl/segment_check.inl"
#include "cdt2d/impl/recover.inl"
#include "cdt2d/impl/domain.inl"
#include "cdt2d/impl/triangulate.inl"
const Entries entries{&triangulate_impl, &triangulate_device_impl};
}  // namespace gpugeom::cdt::cuda_impl
