// The test entries' work on each executor (testing.hpp says what each does; exec/dispatch.hpp).
#pragma once
#include "exec/dispatch.hpp"
#include "testing/testing.hpp"

namespace gpugeom::testing {
// One executor's entries: impl/del2d.inl fills them as del2d's `testing_entries`, in each
// executor's unit (del2d_cpu.cpp, del2d_cuda.cu); GG_TABLE(b, del2d, testing_entries) picks them.
struct Entries {
  void (*triangulate_from)(const double* xy, std::int64_t n, const std::int32_t* start,
                           std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                           const Delaunay2dOptions& opt, del2d::Output& out,
                           Delaunay2dStats& stats);
  // s holds the frame (width, height, ox, oy, h); fills pixel, missing, site_of, debris,
  // pinched, triangles and twins (the dual and the hull fill), colour where keep_colour, and
  // phase times.
  void (*digital_sketch_dual)(const double* xy, std::int64_t n, const RunOptions& run,
                              bool keep_colour, del2d::digital::Sketch& s);
  // The rounds: fills out's triangles, twins, hints, counts and the check's verdict.
  void (*digital_shift)(const double* xy, std::int64_t n, const del2d::digital::Sketch& s,
                        const RunOptions& run, del2d::digital::Start& out);
};
}  // namespace gpugeom::testing

namespace gpugeom::del2d {
GG_DECLARE_TABLE(testing::Entries, testing_entries)
}  // namespace gpugeom::del2d
