// The 3D Voronoi diagram of a tetrahedralisation in executor memory, and the Voronoi cells
// (issue 49), compiled for the CPU executor (exec/dispatch.hpp).
#include "delaunay3d/impl/voronoi_unit.hpp"
#include "exec/cpu_exec.hpp"

namespace gpugeom::del3d::cpu_impl {
using Exec = CpuExec;
#include "delaunay3d/impl/voronoi.inl"
#include "delaunay3d/impl/cells_kernels.inl"
#include "delaunay3d/impl/cells.inl"
#include "delaunay3d/impl/voronoi_entries.inl"
}  // namespace gpugeom::del3d::cpu_impl
