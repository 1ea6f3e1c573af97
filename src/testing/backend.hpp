// The test entries' work on each executor (testing.hpp says what each does; exec/dispatch.hpp).
#pragma once
#include "testing/testing.hpp"

namespace gpugeom::testing {
// One executor's entries, filled by each executor's unit (del2d_cpu.cpp, del2d_cuda.cu) from
// impl/del2d.inl.
struct Entries {
  void (*triangulate_from)(const double* xy, std::int64_t n, const std::int32_t* start,
                           std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                           const Delaunay2dOptions& opt, del2d::Output& out, Stats& stats);
  // s holds the frame (width, height, ox, oy, h); fills pixel, missing, site_of, debris,
  // pinched, triangles and twins (the dual and the hull fill), colour where keep_colour, and
  // phase times.
  void (*digital_sketch_dual)(const double* xy, std::int64_t n, const RunOptions& run,
                              bool keep_colour, del2d::digital::Sketch& s);
  // The rounds: fills out's triangles, twins, hints, counts and the check's verdict.
  void (*digital_shift)(const double* xy, std::int64_t n, const del2d::digital::Sketch& s,
                        const RunOptions& run, del2d::digital::Start& out);
};
namespace cpu_impl {
extern const Entries entries;
}
namespace cuda_impl {
extern const Entries entries;
}
}  // namespace gpugeom::testing
