// The digital 2D Delaunay method's entry (digital.hpp).
#include "delaunay2d/digital/digital.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "delaunay2d/digital/shift.hpp"
#include "delaunay2d/digital/sketch.hpp"
#include "exec/dispatch.hpp"

namespace gpugeom::del2d::digital {

std::int64_t auto_side(const double* xy, std::int64_t n) {
  // About 4 pixels a point over the points' bounding box: the thesis found larger grids faster
  // (fewer missing points and flips) until the diagram's own cost dominates. The pixel size is
  // the power of two nearest that (sketch.hpp), and the side returned fits the box with it.
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (std::int64_t i = 0; i < n; ++i) {
    x0 = std::min(x0, xy[2 * i]), x1 = std::max(x1, xy[2 * i]);
    y0 = std::min(y0, xy[2 * i + 1]), y1 = std::max(y1, xy[2 * i + 1]);
  }
  const double wx = x1 - x0, wy = y1 - y0, longer = std::max(wx, wy);
  if (!(longer > 0) || !std::isfinite(longer)) return 64;
  // The shorter side counts at least a 64th of the longer (thin inputs: a strip of pixels).
  const double area = longer * std::max(std::min(wx, wy), longer / 64);
  const double h = std::sqrt(area / (4.0 * double(std::max<std::int64_t>(n, 1))));
  const double h2 = std::exp2(std::round(std::log2(h)));
  const double side = std::ceil(longer / h2);
  return std::int64_t(std::clamp(side, 64.0, 16384.0));
}

void triangulate(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Backend b,
                 Output& out, Stats& st) {
  if (opt.grid != 0 && (opt.grid < 4 || opt.grid > 46338))
    throw Error(ErrorCode::InvalidArgument,
                "grid: the digital method's grid side must be 4..46338 (or 0: chosen from the "
                "point count), got " +
                    std::to_string(opt.grid));
  // Coordinates the incremental method refuses are refused by it (the same errors).
  bool finite = true;
  for (std::int64_t i = 0; i < 2 * n && finite; ++i) finite = std::isfinite(xy[i]);
  auto incremental = [&] {
    st.counters["digital_fallback"] = 1;
    GG_ON_EXECUTOR(b, del2d, triangulate, xy, n, opt, out, st);
  };
  if (!finite) return incremental();
  const std::int64_t side = opt.grid ? opt.grid : auto_side(xy, n);
  RunOptions run = opt;
  run.backend = b;
  Sketch s = digital_sketch(xy, n, side, run);
  for (const auto& [name, ms] : s.phase_ms) st.phase_ms.push_back({"digital_" + name, ms});
  st.counters["grid_width"] = s.width;
  st.counters["grid_height"] = s.height;
  st.counters["sites"] = n - std::int64_t(s.missing.size());
  st.counters["sketch_missing"] = std::int64_t(s.missing.size());
  st.counters["debris_pixels"] = s.debris;
  st.counters["pinched_corners"] = s.pinched;
  st.counters["hull_triangles"] = s.hull_triangles;
  const Start start = shift_sketch(xy, n, s, run);
  for (const auto& [name, ms] : start.phase_ms) st.phase_ms.push_back({"digital_" + name, ms});
  st.counters["shifted"] = start.shifted;
  st.counters["bad_inner"] = start.bad_inner;
  st.counters["bad_boundary"] = start.bad_boundary;
  st.counters["shift_rounds"] = start.shift_rounds;
  st.counters["delete_rounds"] = start.delete_rounds;
  st.counters["start_vertices"] = start.vertices;
  st.counters["start_triangles"] = std::int64_t(start.triangles.size() / 3);
  if (!start.valid) return incremental();
  st.counters["digital_fallback"] = 0;
  s = Sketch{};  // (the grid's memory back before the Triangulator's)
  GG_ON_EXECUTOR(b, del2d, triangulate_from, xy, n, start.triangles.data(),
                 std::int64_t(start.triangles.size() / 3), start.twin.data(), start.hint.data(),
                 opt, out, st);
}

}  // namespace gpugeom::del2d::digital
