// 3D Delaunay tetrahedralisation compiled for the CPU executor.
#include "exec/cpu_exec.hpp"
#include "delaunay3d/impl/unit.hpp"

namespace gpugeom::del3d::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "delaunay3d/impl/unit.inl"
std::unique_ptr<Kept> make_kept(const Delaunay3dOptions& opt) {
  return std::make_unique<KeptOn>(opt);
}
void triangulate(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt, Output& out,
                 Stats& stats) {
  triangulate_impl(xyz, n, opt, out, stats);
}
void triangulate_device(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                        DeviceOutput& out, Stats& stats) {
  triangulate_device_impl(xyz, n, opt, out, stats);
}
}  // namespace gpugeom::del3d::cpu_impl
