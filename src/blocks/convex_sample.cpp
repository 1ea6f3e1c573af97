// The sample's share of extreme points (convex_sample.hpp), from the library's own hulls on the
// CPU executor, as gpugeom.ConvexHull makes them for gpugeom.dask's side of the rule: in 2D the
// boundary of the sample's triangulation (convex_hull2d_vertices: points on a hull edge between
// its ends are not extreme), in 3D convex_hull3d.
#include "blocks/convex_sample.hpp"

#include <cmath>
#include <vector>

#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/hull3d.hpp"

namespace gpugeom::blocks_detail {

bool on_convex_surface(const double* pts, int dim, std::int64_t m) {
  const std::int64_t stride = convex_sample_stride(m);
  const std::int64_t s = (m + stride - 1) / stride;
  if (s < dim + 2) return false;  // (too few to tell: the split handles them)
  std::vector<double> p(static_cast<std::size_t>(dim * s));
  for (std::int64_t i = 0; i < s; ++i)
    for (int j = 0; j < dim; ++j) {
      const double x = pts[dim * i * stride + j];
      // (a NaN or an infinity says no: the call that follows refuses such input with its error)
      if (!std::isfinite(x)) return false;
      p[std::size_t(dim * i + j)] = x;
    }
  std::int64_t extreme = 0;
  try {
    if (dim == 2) {
      Delaunay2dOptions o;
      o.backend = Backend::Cpu;
      o.threads = 1;  // (4096 points: a team of threads costs more than it saves)
      const Triangulation2d t = delaunay2d(p.data(), s, o);
      extreme = std::int64_t(convex_hull2d_vertices(p.data(), s, t.triangles.data(),
                                                    t.neighbors.data(), t.num_triangles)
                                 .size());
    } else {
      Hull3dOptions o;
      o.backend = Backend::Cpu;
      o.threads = 1;  // (4096 points: a team of threads costs more than it saves)
      extreme = convex_hull3d(p.data(), s, o).num_vertices;
    }
  } catch (const Error& e) {
    // (flat, or coordinates the hulls do not take: the call that follows says which)
    if (e.code() != ErrorCode::DegenerateInput && e.code() != ErrorCode::InvalidInput) throw;
    return false;
  }
  return 2 * extreme >= s;
}

}  // namespace gpugeom::blocks_detail
