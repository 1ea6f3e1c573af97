// 2D Delaunay on the CPU executor: the checker on every distribution and degenerate input,
// errors, and the Voronoi diagram.
#include "del2d_cases.hpp"

using namespace gpugeom;
using gg_del2d::expect_valid;

namespace {
Delaunay2dOptions cpu() {
  Delaunay2dOptions o;
  o.backend = Backend::Cpu;
  return o;
}
}  // namespace

TEST(Delaunay2d, Distributions) {
  for (const auto& c : gg_del2d::distribution_cases({3, 4, 10, 100, 1000, 30000}, 11)) {
    SCOPED_TRACE(c.name);
    if (c.name.rfind("two_segments", 0) == 0 && c.pts.size() < 4) continue;
    expect_valid(c.pts, delaunay2d(c.pts, cpu()));
  }
}

TEST(Delaunay2d, Degenerate) {
  for (const auto& c : gg_del2d::degenerate_cases()) {
    SCOPED_TRACE(c.name);
    const auto t = delaunay2d(c.pts, cpu());
    expect_valid(c.pts, t);
  }
}
