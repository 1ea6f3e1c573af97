// The distance transform compiled for the CPU executor.
#include <chrono>
#include <cuda/atomic>
#include <cstdlib>
#include <functional>
#include <cmath>
#include <string>
#include <type_traits>

#include "edt/edt_backend.hpp"
#include "edt/edt_device.hpp"
#include "exec/cpu_exec.hpp"

namespace gpugeom::edt::cpu_impl {
using Exec = CpuExec;
using std::sqrt;
#include "edt/impl/pba.inl"
#include "edt/impl/jfa.inl"
// The CPU twin of the GPU's x pass: the general line pass, one thread walking each row.
void x_pass_rows(Exec& ex, const Layout& L, const Metric& M, const PassGeom& g, std::uint32_t* feat,
                 std::uint32_t* scratch, std::int32_t* lo, std::int32_t* hi) {
  line_pass(ex, L, M, g, feat, scratch, lo, hi);
}
// Tiles in on-chip memory are a GPU device: a CPU thread's cache already holds its line.
bool line_pass_tiled(Exec&, const Layout&, const Metric&, int, std::int64_t, std::uint32_t*,
                     std::uint32_t*, const std::uint8_t*) {
  return false;
}
#include "edt/impl/run.inl"
}  // namespace gpugeom::edt::cpu_impl
