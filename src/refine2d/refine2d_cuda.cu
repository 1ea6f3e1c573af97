// Delaunay refinement compiled for the CUDA executor.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>
#include <thrust/functional.h>

#include "base/clock.hpp"
#include "exec/atomics.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "exec/deliver.hpp"
#include "predicates/predicates.hpp"
#include "refine2d/quality.hpp"
#include "refine2d/refine2d_backend.hpp"

namespace gpugeom::refine::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace cdt_impl = ::gpugeom::cdt::cuda_impl;
#include "cdt2d/impl/segment_check.inl"
#include "refine2d/impl/rounds.inl"
#include "refine2d/impl/kept_mesh.inl"
#include "refine2d/impl/refine.inl"
void refine(const double* xy, std::int64_t n, const std::int32_t* segs, std::int64_t nseg,
            const std::vector<std::int32_t>& final_of_base, const Refine2dOptions& opt,
            RefinedMesh2d& r, cdt::RecoveryCounts& rc, Tally& tally) {
  refine_host(xy, n, segs, nseg, final_of_base, opt, r, rc, tally);
}
void refine_device(const double* xy, std::int64_t n, const std::int32_t* segs, std::int64_t nseg,
                   const Refine2dOptions& opt, DeviceResult& d, cdt::RecoveryCounts& rc,
                   Tally& tally) {
  refine_device_impl(xy, n, segs, nseg, opt, d, rc, tally);
}
}  // namespace gpugeom::refine::cuda_impl
