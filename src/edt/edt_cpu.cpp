// The distance transform compiled for the CPU executor.
#include <chrono>
#include <cuda/atomic>
#include <cstdlib>
#include <functional>
#include <cmath>
#include <string>
#include <type_traits>

#include "base/clock.hpp"
#include "edt/edt_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/cpu_exec.hpp"
#include "exec/peak.hpp"
#include "exec/grid_input.hpp"

namespace gpugeom::edt::cpu_impl {
using Exec = CpuExec;
using std::sqrt;
#define GG_EDT_TILES "edt/impl/cpu_tiles.inl"
#define GG_EDT_PASSES "edt/impl/cpu_passes.inl"
#include "edt/impl/packings.inl"
}  // namespace gpugeom::edt::cpu_impl
