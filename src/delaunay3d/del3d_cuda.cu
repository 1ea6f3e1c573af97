// 3D Delaunay tetrahedralisation compiled for the CUDA executor.
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "delaunay3d/impl/unit.hpp"

namespace gpugeom::del3d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "delaunay3d/impl/unit.inl"
std::unique_ptr<Kept> make_kept(const Delaunay3dOptions& opt) {
  Delaunay3dOptions o = opt;
  o.device = cuda_device::resolve(opt);  // (kept: later calls run on this device, whatever the
                                         // calling thread's current one is then)
  return std::make_unique<KeptOn>(o);
}
void triangulate(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt, Output& out,
                 Stats& stats) {
  triangulate_impl(xyz, n, opt, out, stats);
}
void triangulate_device(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                        DeviceOutput& out, Stats& stats) {
  triangulate_device_impl(xyz, n, opt, out, stats);
}
}  // namespace gpugeom::del3d::cuda_impl
