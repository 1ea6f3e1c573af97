// 2D constrained Delaunay triangulation compiled for the CUDA executor.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>
#include <climits>
#include <thrust/functional.h>

#include "base/clock.hpp"
#include "cdt2d/cavity.hpp"
#include "cdt2d/cdt2d_backend.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "exec/atomics.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "exec/deliver.hpp"
#include "exec/prefault.hpp"
#include "exec/scratch_slots.hpp"
#include "locate/walk.hpp"
#include "mesh/union_find.hpp"

namespace gpugeom::cdt::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace dt_impl = ::gpugeom::del2d::cuda_impl;
#include "cdt2d/impl/segment_check.inl"
#include "cdt2d/impl/recover.inl"
#include "cdt2d/impl/domain.inl"
#include "cdt2d/impl/triangulate.inl"
void triangulate(const double* xy, std::int64_t n, const std::int32_t* segments, std::int64_t nseg,
                 const Cdt2dOptions& opt, ConstrainedTriangulation2d& r, RecoveryCounts& rc) {
  triangulate_impl(xy, n, segments, nseg, opt, r, rc);
}
void triangulate_device(const double* xy, std::int64_t n, const std::int32_t* segments,
                        std::int64_t nseg, const Cdt2dOptions& opt, DeviceResult& d, Stats& st,
                        RecoveryCounts& rc) {
  triangulate_device_impl(xy, n, segments, nseg, opt, d, st, rc);
}
}  // namespace gpugeom::cdt::cuda_impl
