// 2D Delaunay triangulation compiled for the CUDA executor (exec/dispatch.hpp).
#include <cooperative_groups.h>
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "delaunay2d/impl/unit.hpp"

namespace gpugeom::del2d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "delaunay2d/impl/unit.inl"
#include "delaunay2d/impl/entries.inl"
#include "delaunay2d/impl/assemble.inl"
}  // namespace gpugeom::del2d::cuda_impl
