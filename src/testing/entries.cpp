// The test entries (testing.hpp) on the host: each checks what it can and runs on the
// executor its options resolve to.
#include "testing/testing.hpp"

#include <algorithm>
#include <cmath>

#include "exec/dispatch.hpp"
#include "testing/backend.hpp"

namespace gpugeom::testing {

void triangulate_from(const double* xy, std::int64_t n, const std::int32_t* start,
                      std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                      const Delaunay2dOptions& opt, del2d::Output& out, Delaunay2dStats& stats) {
  del2d::check_count(n);
  const Backend b = resolve_backend(opt.backend, opt.device);
  GG_TABLE(b, del2d, testing_entries)
      .triangulate_from(xy, n, start, nstart, twin, hint, opt, out, stats);
}

del2d::digital::Sketch digital_sketch(const double* xy, std::int64_t n, std::int64_t side,
                                      const RunOptions& run, bool keep_colour) {
  del2d::digital::Sketch s;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (std::int64_t i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      lo[d] = std::min(lo[d], xy[2 * i + d]), hi[d] = std::max(hi[d], xy[2 * i + d]);
  del2d::digital::set_frame(s, lo, hi, side);
  const Backend b = resolve_backend(run.backend, run.device);
  GG_TABLE(b, del2d, testing_entries).digital_sketch_dual(xy, n, run, keep_colour, s);
  return s;
}

del2d::digital::Start shift_sketch(const double* xy, std::int64_t n,
                                   const del2d::digital::Sketch& s, const RunOptions& run) {
  del2d::digital::Start out;
  if (!s.exact) {
    out.reason = "the grid points are not exact doubles";
    return out;
  }
  if (s.triangles.empty()) {
    out.reason = "the sketch has no triangle";
    return out;
  }
  const Backend b = resolve_backend(run.backend, run.device);
  GG_TABLE(b, del2d, testing_entries).digital_shift(xy, n, s, run, out);
  return out;
}

}  // namespace gpugeom::testing
