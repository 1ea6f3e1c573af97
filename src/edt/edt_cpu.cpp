// The distance transform compiled for the CPU executor.
#include <chrono>
#include <cuda/atomic>
#include <cstdlib>
#include <functional>
#include <cmath>
#include <string>
#include <type_traits>

#include "edt/edt_backend.hpp"
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
#include "edt/impl/run.inl"
void run(const Request& req, Output& out, Stats& stats) {
  run_impl(req, out, stats);
}
}  // namespace gpugeom::edt::cpu_impl
