// 3D Delaunay tetrahedralisation compiled for the CUDA executor (exec/dispatch.hpp).
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "delaunay3d/impl/unit.hpp"

namespace gpugeom::del3d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "delaunay3d/impl/unit.inl"
#include "delaunay3d/impl/entries.inl"
#include "delaunay3d/impl/assemble.inl"
}  // namespace gpugeom::del3d::cuda_impl
