// The 3D Voronoi diagram of a tetrahedralisation in executor memory (issue 49), compiled for the
// CUDA executor.
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
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
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

namespace gpugeom::del3d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "delaunay3d/impl/voronoi.inl"
#include "delaunay3d/impl/cells_kernels.inl"
#include "delaunay3d/impl/cells.inl"
void voronoi(const double* xyz, std::int64_t n, const std::int32_t* tet, const std::int32_t* nb,
             const std::int32_t* dup, std::int64_t nt, const RunOptions& run, DeviceVoronoi3d& out,
             Stats& stats, Voronoi3d* host) {
  voronoi3d_impl(xyz, n, tet, nb, dup, nt, run, out, stats, host);
}
// The host entry that computes both structures (voronoi3d(xyz, n, opt)): the points cross the bus
// once, the tetrahedralisation and the diagram are made on the device, and only the results come
// back (through the executor's staged copies into the host vectors).
void voronoi_from_host(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                       Voronoi3d& v, Triangulation3d* tri) {
  const auto t0 = std::chrono::steady_clock::now();
  Exec ex(opt);
  auto up = ex.template alloc<double>(std::size_t(3 * n));
  ex.from_host(xyz, 3 * n, up.data());
  v.stats.phase_ms.push_back({"upload", ms_since(t0)});
  Delaunay3dOptions o = opt;
  o.into = {};
  o.backend = Backend::Cuda;
  const DeviceTriangulation3d d = delaunay3d_device(up.data(), n, o);
  DeviceVoronoi3d unused;
  voronoi3d_impl(up.data(), n, d.tetrahedra.get(), d.neighbors.get(),
                 d.num_duplicates ? d.duplicate_of.get() : nullptr, d.num_tetrahedra, opt, unused,
                 v.stats, &v);
  if (!tri) return;
  const auto t1 = std::chrono::steady_clock::now();
  const OutBuffer<std::int32_t> none{};
  deliver::to_host(ex, d.tetrahedra.get(), 4 * d.num_tetrahedra, none, tri->tetrahedra);
  deliver::to_host(ex, d.neighbors.get(), 4 * d.num_tetrahedra, none, tri->neighbors);
  deliver::to_host(ex, d.duplicate_of.get(), n, none, tri->duplicate_of);
  deliver::to_host(ex, d.vertex_to_simplex.get(), n, none, tri->vertex_to_simplex);
  deliver::to_host(ex, d.hull_facets.get(), 3 * d.num_hull_facets, none, tri->hull_facets);
  tri->num_tetrahedra = d.num_tetrahedra;
  tri->num_hull_facets = d.num_hull_facets;
  tri->num_duplicates = d.num_duplicates;
  tri->stats = d.stats;
  tri->stats.phase_ms.push_back({"copy_tetrahedralisation", ms_since(t1)});
}
void cells(const double* xyz, std::int64_t n, bool on_host, const VoronoiCellsOptions& opt,
           DeviceVoronoiCells* dev, VoronoiCells* host) {
  voronoi_cells_impl(xyz, n, on_host, opt, Backend::Cuda, dev, host);
}
}  // namespace gpugeom::del3d::cuda_impl
