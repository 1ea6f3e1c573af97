// 3D Delaunay tetrahedralisation compiled for the CPU executor (exec/dispatch.hpp).
#include "exec/cpu_exec.hpp"
#include "delaunay3d/impl/unit.hpp"

namespace gpugeom::del3d::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "delaunay3d/impl/unit.inl"
#include "delaunay3d/impl/entries.inl"
#include "delaunay3d/impl/assemble.inl"
}  // namespace gpugeom::del3d::cpu_impl
