// The digital 2D Delaunay method's entry (digital.hpp).
#include "delaunay2d/digital/digital.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "exec/dispatch.hpp"

namespace gpugeom::del2d::digital {

std::int64_t auto_side(const double lo[2], const double hi[2], std::int64_t n) {
  // About 4 pixels a point over the points' bounding box: the thesis found larger grids faster
  // (fewer missing points and flips) until the diagram's own cost dominates. The pixel size is
  // the power of two nearest that (sketch.hpp), and the side returned fits the box with it.
  const double wx = hi[0] - lo[0], wy = hi[1] - lo[1], longer = std::max(wx, wy);
  if (!(longer > 0) || !std::isfinite(longer)) return 64;
  // The shorter side counts at least a 64th of the longer (thin inputs: a strip of pixels).
  const double area = longer * std::max(std::min(wx, wy), longer / 64);
  const double h = std::sqrt(area / (4.0 * double(std::max<std::int64_t>(n, 1))));
  const double h2 = std::exp2(std::round(std::log2(h)));
  const double side = std::ceil(longer / h2);
  return std::int64_t(std::clamp(side, 64.0, 16384.0));
}

std::int64_t auto_side(const double* xy, std::int64_t n) {
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (std::int64_t i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      lo[d] = std::min(lo[d], xy[2 * i + d]), hi[d] = std::max(hi[d], xy[2 * i + d]);
  return auto_side(lo, hi, n);
}

void triangulate(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Backend b,
                 Output& out, Delaunay2dStats& st) {
  if (opt.grid != 0 && (opt.grid < 4 || opt.grid > 46338))
    throw Error(ErrorCode::InvalidArgument,
                "grid: the digital method's grid side must be 4..46338 (or 0: chosen from the "
                "point count), got " +
                    std::to_string(opt.grid));
  GG_ENTRIES(b, del2d).digital(xy, n, opt, out, st);
}

}  // namespace gpugeom::del2d::digital
