// Weighted Lloyd iteration compiled for the CPU executor (exec/dispatch.hpp).
#include "cvd/impl/unit.hpp"
#include "exec/cpu_exec.hpp"

namespace gpugeom::cvd::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "cvd/impl/density.inl"
#include "cvd/impl/lloyd.inl"
const Entries entries{&lloyd_impl};
}  // namespace gpugeom::cvd::cpu_impl
