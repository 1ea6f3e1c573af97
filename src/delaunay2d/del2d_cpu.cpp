// 2D Delaunay triangulation compiled for the CPU executor.
#include "exec/cpu_exec.hpp"
#include "delaunay2d/impl/unit.hpp"

namespace gpugeom::del2d::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
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
  return std::make_unique<KeptOn>(run);
}
}  // namespace gpugeom::del2d::cpu_impl
