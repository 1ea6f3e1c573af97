// 2D Delaunay triangulation compiled for the CPU executor (exec/dispatch.hpp).
#include "exec/cpu_exec.hpp"
#include "delaunay2d/impl/unit.hpp"

namespace gpugeom::del2d::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "delaunay2d/impl/unit.inl"
#include "delaunay2d/impl/entries.inl"
#include "delaunay2d/impl/assemble.inl"
}  // namespace gpugeom::del2d::cpu_impl
