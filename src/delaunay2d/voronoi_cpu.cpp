// The Voronoi diagram of a triangulation in executor memory, compiled for the CPU executor.
#include "delaunay2d/impl/voronoi_unit.hpp"
#include "exec/cpu_exec.hpp"

namespace gpugeom::del2d::cpu_impl {
using Exec = CpuExec;
#include "delaunay2d/impl/voronoi.inl"
#include "delaunay2d/impl/voronoi_entries.inl"
}  // namespace gpugeom::del2d::cpu_impl
