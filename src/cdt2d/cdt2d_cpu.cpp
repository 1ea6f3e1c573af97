// 2D constrained Delaunay triangulation compiled for the CPU executor (exec/dispatch.hpp).
#include "cdt2d/impl/unit.hpp"
#include "exec/cpu_exec.hpp"

namespace gpugeom::cdt::cpu_impl {
using Exec = CpuExec;
namespace dt_impl = ::gpugeom::del2d::cpu_impl;
#include "cdt2d/impl/segment_check.inl"
#include "cdt2d/impl/recover.inl"
#include "cdt2d/impl/domain.inl"
#include "cdt2d/impl/triangulate.inl"
const Entries entries{&triangulate_impl, &triangulate_device_impl};
}  // namespace gpugeom::cdt::cpu_impl
