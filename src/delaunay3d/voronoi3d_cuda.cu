// The 3D Voronoi diagram of a tetrahedralisation in executor memory, and the Voronoi cells
// (issue 49), compiled for the CUDA executor (exec/dispatch.hpp).
#include "delaunay3d/impl/voronoi_unit.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"

namespace gpugeom::del3d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "delaunay3d/impl/voronoi.inl"
#include "delaunay3d/impl/cells_kernels.inl"
#include "delaunay3d/impl/cells.inl"
#include "delaunay3d/impl/voronoi_entries.inl"
}  // namespace gpugeom::del3d::cuda_impl
