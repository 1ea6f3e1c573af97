// The 3D Voronoi diagram of a tetrahedralisation in executor memory (issue 49), compiled for the
// CPU executor.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <string>
#include <type_traits>
#include <thrust/functional.h>

#include "base/clock.hpp"
#include "delaunay3d/convex_cell.hpp"
#include "delaunay3d/voronoi3d_backend.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/cpu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/scratch_lease.hpp"
#include "gpugeom/removed.hpp"
#include "gpugeom/voronoi_cells.hpp"
#include "mesh/sum2.hpp"
#include "mesh/union_find.hpp"
#include "mesh/vertex_classes.hpp"
#include "predicates/expansion.hpp"
#include "predicates/predicates.hpp"
#include "spatial/hilbert.hpp"

namespace gpugeom::del3d::cpu_impl {
using Exec = CpuExec;
#include "delaunay3d/impl/voronoi.inl"
#include "delaunay3d/impl/cells_kernels.inl"
#include "delaunay3d/impl/cells.inl"
void voronoi(const double* xyz, std::int64_t n, const std::int32_t* tet, const std::int32_t* nb,
             const std::int32_t* dup, std::int64_t nt, const RunOptions& run, DeviceVoronoi3d& out,
             Stats& stats, Voronoi3d* host) {
  voronoi3d_impl(xyz, n, tet, nb, dup, nt, run, out, stats, host);
}
void cells(const double* xyz, std::int64_t n, bool on_host, const VoronoiCellsOptions& opt,
           DeviceVoronoiCells* dev, VoronoiCells* host) {
  voronoi_cells_impl(xyz, n, on_host, opt, Backend::Cpu, dev, host);
}
}  // namespace gpugeom::del3d::cpu_impl
