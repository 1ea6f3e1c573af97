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

namespace gpugeom::del3d {
Output assemble_blocks(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                       const BlocksFn& blocks) {
  Output out;
  out.stats.backend = Backend::Cpu;
  cpu_impl::assemble_impl(xyz, n, opt, blocks, out);
  return out;
}
}  // namespace gpugeom::del3d
