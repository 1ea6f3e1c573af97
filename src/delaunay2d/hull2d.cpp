// The convex hull of a 2D triangulation's points from its boundary (include/gpugeom/
// delaunay2d.hpp): the boundary edges chained counter-clockwise, then the points that lie on a
// hull edge between its ends dropped by exact orientation, so only extreme points remain (the
// triangulation keeps such points as vertices: every distinct point is one).
#include <string>
#include <vector>

#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/predicates.hpp"

namespace gpugeom {

HostVector<std::int32_t> convex_hull2d_vertices(const double* xy, std::int64_t n,
                                                const std::int32_t* triangles,
                                                const std::int32_t* neighbors,
                                                std::int64_t num_triangles) {
  auto bad = [](const std::string& what) {
    throw Error(ErrorCode::InvalidArgument, "convex_hull2d_vertices: " + what);
  };
  // next[a] = b for each boundary edge a -> b with the interior on its left.
  std::vector<std::int32_t> next(std::size_t(n), -1);
  std::int32_t start = -1;
  std::int64_t edges = 0;
  for (std::int64_t t = 0; t < num_triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      if (neighbors[3 * t + k] >= 0) continue;
      const std::int32_t a = triangles[3 * t + (k + 1) % 3], b = triangles[3 * t + (k + 2) % 3];
      if (a < 0 || a >= n || b < 0 || b >= n) bad("a triangle refers to a missing point");
      if (next[std::size_t(a)] >= 0) bad("the boundary is not one convex cycle");
      next[std::size_t(a)] = b;
      start = a;
      ++edges;
    }
  if (start < 0) bad("the triangulation has no boundary");
  std::vector<std::int32_t> cycle;
  cycle.reserve(std::size_t(edges));
  std::int32_t v = start;
  do {
    cycle.push_back(v);
    v = next[std::size_t(v)];
    if (v < 0 || std::int64_t(cycle.size()) > edges) bad("the boundary is not one convex cycle");
  } while (v != start);
  if (std::int64_t(cycle.size()) != edges) bad("the boundary is not one convex cycle");
  auto pt = [&](std::int32_t i) { return Point2{xy[2 * i], xy[2 * i + 1]}; };
  HostVector<std::int32_t> out;
  const std::size_t h = cycle.size();
  for (std::size_t i = 0; i < h; ++i) {
    const std::int32_t a = cycle[(i + h - 1) % h], b = cycle[i], c = cycle[(i + 1) % h];
    if (orient2d(pt(a), pt(b), pt(c)) != 0) out.push_back(b);  // (collinear: not extreme)
  }
  return out;
}

}  // namespace gpugeom
