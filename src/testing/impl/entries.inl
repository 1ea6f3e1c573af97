// The test entries' work on one executor (testing.hpp says what each does), declared inside
// testing::cpu_impl and testing::cuda_impl (backend.hpp) and defined there by the executor's own
// unit (del2d_cpu.cpp, del2d_cuda.cu) with GG_TESTING_DEFINE set, where `del2d_impl` names the
// module's namespace for that executor.
#ifndef GG_TESTING_DEFINE
void triangulate_from(const double* xy, std::int64_t n, const std::int32_t* start,
                      std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                      const Delaunay2dOptions& opt, del2d::Output& out, Stats& stats);
// s holds the frame (width, height, ox, oy, h); fills pixel, missing, site_of, debris, pinched,
// triangles and twins (the dual and the hull fill), colour where keep_colour, and phase times.
void digital_sketch_dual(const double* xy, std::int64_t n, const RunOptions& run, bool keep_colour,
                         del2d::digital::Sketch& s);
// The rounds: fills out's triangles, twins, hints, counts and the check's verdict.
void digital_shift(const double* xy, std::int64_t n, const del2d::digital::Sketch& s,
                   const RunOptions& run, del2d::digital::Start& out);
#else
void triangulate_from(const double* xy, std::int64_t n, const std::int32_t* start,
                      std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                      const Delaunay2dOptions& opt, del2d::Output& out, Stats& stats) {
  del2d_impl::triangulate_from_impl(xy, n, start, nstart, twin, hint, opt, out, stats);
}
void digital_sketch_dual(const double* xy, std::int64_t n, const RunOptions& run, bool keep_colour,
                         del2d::digital::Sketch& s) {
  del2d_impl::digital_sketch_dual_impl(xy, n, run, keep_colour, s);
}
void digital_shift(const double* xy, std::int64_t n, const del2d::digital::Sketch& s,
                   const RunOptions& run, del2d::digital::Start& out) {
  del2d_impl::digital_shift_impl(xy, n, s, run, out);
}
#endif
