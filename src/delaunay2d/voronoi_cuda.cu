// The Voronoi diagram of a triangulation in executor memory, compiled for the CUDA executor.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <thrust/functional.h>

#include "base/clock.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "delaunay2d/voronoi_core.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/scratch_lease.hpp"
#include "gpugeom/removed.hpp"
#include "mesh/union_find.hpp"
#include "mesh/vertex_classes.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::del2d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "delaunay2d/impl/voronoi.inl"
void voronoi(const double* xy, std::int64_t n, const std::int32_t* tri, const std::int32_t* nb,
             const std::int32_t* dup, std::int64_t nt, const RunOptions& run,
             DeviceVoronoiOutput& out, Stats& stats, Voronoi2d* host) {
  voronoi_impl(xy, n, tri, nb, dup, nt, run, out, stats, host);
}
// The host entry that computes both structures (voronoi2d(xy, n, opt)): the points cross the bus
// once, the triangulation and the diagram are made on the device, and only the results come back
// (through the executor's staged copies into the host vectors).
void voronoi_from_host(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Voronoi2d& v,
                       Triangulation2d* tri, Stats& stats) {
  const auto t0 = std::chrono::steady_clock::now();
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  auto up = ex.template alloc<double>(std::size_t(2 * n));
  ex.from_host(xy, 2 * n, up.data());
  stats.phase_ms.push_back({"upload", ms_since(t0)});
  Delaunay2dOptions o = opt;
  o.into = {};
  DeviceOutput d;
  triangulate_device(up.data(), n, o, d, stats);
  DeviceVoronoiOutput unused;
  voronoi_impl(up.data(), n, d.triangles.get(), d.neighbors.get(),
               d.num_duplicates ? d.duplicate_of.get() : nullptr, d.num_triangles, opt, unused,
               stats, &v);
  if (!tri) return;
  const auto t1 = std::chrono::steady_clock::now();
  const OutBuffer<std::int32_t> none{};
  deliver::to_host(ex, d.triangles.get(), 3 * d.num_triangles, none, tri->triangles);
  deliver::to_host(ex, d.neighbors.get(), 3 * d.num_triangles, none, tri->neighbors);
  deliver::to_host(ex, d.duplicate_of.get(), n, none, tri->duplicate_of);
  tri->num_triangles = d.num_triangles;
  tri->num_duplicates = d.num_duplicates;
  stats.phase_ms.push_back({"copy_triangulation", ms_since(t1)});
}
}  // namespace gpugeom::del2d::cuda_impl
