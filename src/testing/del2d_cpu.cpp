// The 2D test entries (testing.hpp) compiled for the CPU executor: the module's algorithm (its
// own unit.inl, as the library compiles it) and the entries' wrappers (impl/del2d.inl).
#include "exec/cpu_exec.hpp"
#include "delaunay2d/impl/unit.hpp"
#include "testing/backend.hpp"

namespace gpugeom::del2d::cpu_impl {
using Exec = CpuExec;
namespace edt_impl = gpugeom::edt::cpu_impl;
#include "delaunay2d/impl/unit.inl"
#include "testing/impl/del2d.inl"
}  // namespace gpugeom::del2d::cpu_impl

namespace gpugeom::testing::cpu_impl {
namespace del2d_impl = del2d::cpu_impl;
#define GG_TESTING_DEFINE
#include "testing/impl/entries.inl"
#undef GG_TESTING_DEFINE
}  // namespace gpugeom::testing::cpu_impl
