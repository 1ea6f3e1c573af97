// Weighted Lloyd iteration compiled for the CUDA executor.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <unordered_set>
#include <cuda/atomic>
#include <cstdint>
#include <thrust/functional.h>
#include <vector>

#include "base/clock.hpp"
#include "cvd/cvd_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/grid_input.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "exec/peak.hpp"

namespace gpugeom::cvd::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "cvd/impl/density.inl"
#include "cvd/impl/lloyd.inl"
void lloyd(const Request& rq, Output& out, Stats& stats) {
  lloyd_impl(rq, out, stats);
}
}  // namespace gpugeom::cvd::cuda_impl
