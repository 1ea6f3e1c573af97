// The 2D test entries (testing.hpp) compiled for the CPU executor: the module's algorithm (its
// own unit.inl, as the library compiles it) and the entries (impl/del2d.inl).
#include "exec/cpu_exec.hpp"
#include "delaunay2d/impl/unit.hpp"
#include "testing/backend.hpp"

namespace gpugeom::del2d::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "delaunay2d/impl/unit.inl"
#include "testing/impl/del2d.inl"
}  // namespace gpugeom::del2d::cpu_impl
