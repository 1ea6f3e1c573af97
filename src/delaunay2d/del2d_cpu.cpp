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

namespace gpugeom::del2d {
Output assemble_blocks(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                       const BlocksFn& blocks) {
  Output out;
  out.stats.backend = Backend::Cpu;
  cpu_impl::assemble_impl(xy, n, opt, blocks, out);
  return out;
}
}  // namespace gpugeom::del2d
