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
void triangulate_from(const double* xy, std::int64_t n, const std::int32_t* start,
                      std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                      const Delaunay2dOptions& opt, del2d::Output& out, Stats& stats) {
  del2d::cpu_impl::triangulate_from_impl(xy, n, start, nstart, twin, hint, opt, out, stats);
}
void digital_sketch_dual(const double* xy, std::int64_t n, const RunOptions& run, bool keep_colour,
                         del2d::digital::Sketch& s) {
  del2d::cpu_impl::digital_sketch_dual_impl(xy, n, run, keep_colour, s);
}
void digital_shift(const double* xy, std::int64_t n, const del2d::digital::Sketch& s,
                   const RunOptions& run, del2d::digital::Start& out) {
  del2d::cpu_impl::digital_shift_impl(xy, n, s, run, out);
}
}  // namespace gpugeom::testing::cpu_impl
