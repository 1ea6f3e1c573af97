// Weighted Lloyd iteration compiled for the CPU executor.
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
#include "exec/cpu_exec.hpp"
#include "exec/peak.hpp"

namespace gpugeom::cvd::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "cvd/impl/density.inl"
#include "cvd/impl/lloyd.inl"
void lloyd(const Request& rq, Output& out, Stats& stats) {
  lloyd_impl(rq, out, stats);
}
}  // namespace gpugeom::cvd::cpu_impl
