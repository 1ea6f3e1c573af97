// 2D Delaunay triangulation compiled for the CUDA executor.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
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
#include <unordered_map>
#include <thrust/functional.h>
#include <vector>

#include "delaunay2d/del2d_backend.hpp"
#include "delaunay2d/digital/convex_turn.hpp"
#include "delaunay2d/digital/digital.hpp"
#include "delaunay2d/digital/ear_clip.hpp"
#include "delaunay2d/digital/hull_fill.hpp"
#include "delaunay2d/digital/shift.hpp"
#include "delaunay2d/digital/sketch_backend.hpp"
#include "edt/edt_backend.hpp"
#include "edt/edt_device.hpp"
#include "base/clock.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/prefault.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/scratch_slots.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/compact.hpp"
#include "mesh/hole_refill.hpp"
#include "mesh/simplex_changes.hpp"
#include "mesh/kept_points.hpp"
#include "mesh/decision.hpp"
#include "mesh/flip_fix.hpp"
#include "mesh/half_edges.hpp"
#include "mesh/history.hpp"
#include "mesh/prepare.hpp"
#include "mesh/priority.hpp"
#include "mesh/work_list.hpp"
#include "predicates/predicates.hpp"
#include "spatial/hilbert.hpp"

namespace gpugeom::del2d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "delaunay2d/impl/geometry.inl"
#include "delaunay2d/impl/prepare.inl"
#include "delaunay2d/impl/mesh.inl"
#include "delaunay2d/impl/triangulate.inl"
#include "delaunay2d/impl/dynamic.inl"
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "edt/impl/point_voronoi.inl"
#include "delaunay2d/digital/impl/sketch.inl"
#include "delaunay2d/digital/impl/shift.inl"
#include "delaunay2d/digital/impl/pipeline.inl"
void triangulate_digital(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                         Output& out, Stats& stats) {
  triangulate_digital_impl(xy, n, opt, out, stats);
}
void digital_shift(const double* xy, std::int64_t n, const digital::Sketch& s,
                   const RunOptions& run, digital::Start& out) {
  digital_shift_impl(xy, n, s, run, out);
}
void digital_sketch_dual(const double* xy, std::int64_t n, const RunOptions& run, bool keep_colour,
                         digital::Sketch& s) {
  digital_sketch_dual_impl(xy, n, run, keep_colour, s);
}
void triangulate(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Output& out,
                 Stats& stats) {
  triangulate_impl(xy, n, opt, out, stats);
}
void triangulate_device(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                        DeviceOutput& out, Stats& stats) {
  triangulate_device_impl(xy, n, opt, out, stats);
}
std::unique_ptr<Kept> make_kept(const RunOptions& run) {
  RunOptions r = run;
  r.device = cuda_device::resolve(run);  // (kept: later calls run on this device, whatever the
                                         // calling thread's current one is then)
  return std::make_unique<KeptOn>(r);
}
void triangulate_from(const double* xy, std::int64_t n, const std::int32_t* start,
                      std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                      const Delaunay2dOptions& opt, Output& out, Stats& stats) {
  triangulate_from_impl(xy, n, start, nstart, twin, hint, opt, out, stats);
}
}  // namespace gpugeom::del2d::cuda_impl
