// 2D Delaunay triangulation compiled for the CUDA executor.
#include <cooperative_groups.h>
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "delaunay2d/impl/unit.hpp"

namespace gpugeom::del2d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "delaunay2d/impl/unit.inl"
void triangulate_digital(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                         Output& out, Stats& stats) {
  triangulate_digital_impl(xy, n, opt, out, stats);
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
}  // namespace gpugeom::del2d::cuda_impl
