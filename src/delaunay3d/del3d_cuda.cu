// 3D Delaunay tetrahedralisation compiled for the CUDA executor.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "base/clock.hpp"
#include "delaunay3d/del3d_backend.hpp"
#include "delaunay3d/tet.hpp"
#include "edt/edt_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/scratch_lease.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/compact.hpp"
#include "mesh/hole_refill.hpp"
#include "mesh/simplex_changes.hpp"
#include "mesh/kept_points.hpp"
#include "mesh/first_tetrahedron.hpp"
#include "mesh/flip_fix.hpp"
#include "mesh/history.hpp"
#include "mesh/prepare.hpp"
#include "mesh/priority.hpp"
#include "mesh/work_list.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::del3d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "delaunay3d/impl/geometry.inl"
#include "delaunay3d/impl/link.inl"
#include "edt/impl/point_voronoi.inl"
#include "delaunay3d/digital/impl/working_sets.inl"
#include "delaunay3d/impl/stars.inl"
#include "delaunay3d/impl/repair.inl"
#include "delaunay3d/digital/impl/pipeline.inl"
#include "delaunay3d/impl/triangulate.inl"
#include "delaunay3d/impl/dynamic.inl"
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
