// The Voronoi diagram of a triangulation in executor memory, compiled for the CUDA executor.
#include "delaunay2d/impl/voronoi_unit.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"

namespace gpugeom::del2d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "delaunay2d/impl/voronoi.inl"
#include "delaunay2d/impl/voronoi_entries.inl"
}  // namespace gpugeom::del2d::cuda_impl
