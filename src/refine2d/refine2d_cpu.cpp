// Delaunay refinement compiled for the CPU executor (exec/dispatch.hpp).
#include "refine2d/impl/unit.hpp"
#include "exec/cpu_exec.hpp"

namespace gpugeom::refine::cpu_impl {
using Exec = CpuExec;
namespace cdt_impl = ::gpugeom::cdt::cpu_impl;
#include "cdt2d/impl/segment_check.inl"
#include "refine2d/impl/rounds.inl"
#include "refine2d/impl/kept_mesh.inl"
#include "refine2d/impl/refine.inl"
const Entries entries{&refine_host, &refine_device_impl};
}  // namespace gpugeom::refine::cpu_impl
