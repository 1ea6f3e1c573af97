// 3D convex hull compiled for the CPU executor (exec/dispatch.hpp).
#include "hull3d/impl/unit.hpp"
#include "exec/cpu_exec.hpp"

namespace gpugeom::hull3d::cpu_impl {
using Exec = CpuExec;
#include "hull3d/impl/unit.inl"
#include "hull3d/impl/entries.inl"
}  // namespace gpugeom::hull3d::cpu_impl
