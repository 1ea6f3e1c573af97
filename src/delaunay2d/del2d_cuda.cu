// 2D Delaunay triangulation compiled for the CUDA executor.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <functional>
#include <map>
#include <cooperative_groups.h>
#include <cuda/atomic>
#include <string>
#include <thread>
#include <thrust/functional.h>
#include <vector>

#include "delaunay2d/del2d_backend.hpp"
#include "base/clock.hpp"
#include "exec/atomics.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/scratch_slots.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/compact.hpp"
#include "mesh/decision.hpp"
#include "mesh/flip_fix.hpp"
#include "mesh/history.hpp"
#include "mesh/prepare.hpp"
#include "mesh/priority.hpp"
#include "mesh/work_list.hpp"
#include "predicates/predicates.hpp"
#include "spatial/hilbert.hpp"

namespace gpugeom::del2d::cuda_impl {
using Exec = CudaExec;
#include "delaunay2d/impl/geometry.inl"
#include "delaunay2d/impl/prepare.inl"
#include "delaunay2d/impl/mesh.inl"
#include "delaunay2d/impl/triangulate.inl"
void triangulate(const double* xy, std::int64_t n, const RunOptions& run, Output& out,
                 Stats& stats) {
  triangulate_impl(xy, n, run, out, stats);
}
void triangulate_device(const double* xy, std::int64_t n, const RunOptions& run, DeviceOutput& out,
                        Stats& stats) {
  Exec ex(run);
  triangulate_core(ex, xy, n, true, run.profile, stats,
                   [&](Prepared& P, Triangulator::Finished& f) {
                     if (!P.dup.size()) {  // no duplicates: the map is all -1
                       P.dup = ex.alloc<std::int32_t>(std::size_t(n));
                       ex.fill(P.dup.data(), n, std::int32_t(-1));
                     }
                     ex.sync();  // the buffers were allocated stream-ordered; cudaFree later is not
                     out.num_triangles = f.count;
                     out.num_duplicates = P.duplicates;
                     out.triangles = f.simplices.hand_over();
                     out.neighbors = f.neighbors.hand_over();
                     out.duplicate_of = P.dup.hand_over();
                   });
}
}  // namespace gpugeom::del2d::cuda_impl
