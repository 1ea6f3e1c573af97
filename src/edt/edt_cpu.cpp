// The distance transform compiled for the CPU executor.
#include <chrono>
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
#include "edt/impl/run.inl"
void run(const Request& req, Output& out, Stats& stats) { run_impl(req, out, stats); }
}  // namespace gpugeom::edt::cpu_impl
