// The Voronoi diagram of a triangulation in executor memory, compiled for the CPU executor.
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
#include "exec/cpu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/scratch_lease.hpp"
#include "gpugeom/removed.hpp"
#include "mesh/union_find.hpp"
#include "mesh/vertex_classes.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::del2d::cpu_impl {
using Exec = CpuExec;
#include "delaunay2d/impl/voronoi.inl"
void voronoi(const double* xy, std::int64_t n, const std::int32_t* tri, const std::int32_t* nb,
             const std::int32_t* dup, std::int64_t nt, const RunOptions& run,
             DeviceVoronoiOutput& out, Stats& stats, Voronoi2d* host) {
  voronoi_impl(xy, n, tri, nb, dup, nt, run, out, stats, host);
}
}  // namespace gpugeom::del2d::cpu_impl
