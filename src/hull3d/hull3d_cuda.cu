// 3D convex hull compiled for the CUDA executor.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "base/clock.hpp"
#include "exec/atomics.hpp"
#include "exec/cuda_exec.cuh"
#include "hull3d/hull3d_backend.hpp"
#include "exec/scratch_slots.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/compact.hpp"
#include "mesh/decision.hpp"
#include "mesh/flip_fix.hpp"
#include "mesh/first_tetrahedron.hpp"
#include "mesh/prepare.hpp"
#include "mesh/priority.hpp"
#include "mesh/work_list.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::hull3d::cuda_impl {
using Exec = CudaExec;
#include "hull3d/impl/geometry.inl"
#include "hull3d/impl/prepare.inl"
#include "hull3d/impl/surface.inl"
#include "hull3d/impl/construct.inl"
#include "hull3d/impl/flipflop.inl"
#include "hull3d/impl/hull.inl"
void compute(const double* xyz, std::int64_t n, const RunOptions& run, Output& out, Stats& stats) {
  compute_impl(xyz, n, run, out, stats);
}
void compute_device(const double* xyz, std::int64_t n, const RunOptions& run, DeviceOutput& out,
                    Stats& stats) {
  Exec ex(run);
  Result R = hull_core(ex, xyz, n, stats);
  ex.sync();  // the buffers were allocated stream-ordered; cudaFree later is not
  out.num_facets = R.facets.count;
  out.num_vertices = R.num_vertices;
  out.triangles = R.facets.simplices.hand_over();
  out.neighbors = R.facets.neighbors.hand_over();
  out.vertices = R.vertices.hand_over();
}
}  // namespace gpugeom::hull3d::cuda_impl
