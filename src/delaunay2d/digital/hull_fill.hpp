// The digital sketch made a triangulation of the convex hull of its vertices (issue 20, thesis
// 4.3.2's boundary step; internal). The dual of a diagram truncated by its grid is a disk whose
// boundary need not be convex; each pocket between the boundary and the hull of the boundary's
// vertices is a simple polygon, triangulated by ear clipping. The flips that follow make the
// result Delaunay, so any triangulation of a pocket will do. Integer grid coordinates: every
// orientation is exact. Only the boundary is read (it comes from the executor, compacted:
// about the square root of the sketch's size), and only the new triangles are returned.
#pragma once
#include <cstdint>
#include <vector>

namespace gpugeom::del2d::digital {

// A boundary half-edge of a disk of counter-clockwise triangles: its id e (3t + k), from vertex
// a to vertex b, with (x, y) a's coordinates.
struct RimEdge {
  std::int32_t e, a, b;
  double x, y;
};

struct HullFill {
  // false where the boundary is not one simple cycle (the dual is no disk: on coarse grids with
  // few sites, a vertex can be passed twice); then nothing is filled.
  bool disk = true;
  std::vector<std::int32_t> triangles;  // the pockets' triangles, counter-clockwise
  // Per new half-edge (id 3 (first + j) + k for new triangle j): its twin, a rim half-edge's id
  // or another new one's; -1 on the hull.
  std::vector<std::int32_t> twin;
};

// rim: the disk's boundary half-edges (grid coordinates, integers below 2^31); first: the
// disk's triangle count.
HullFill fill_to_hull(const std::vector<RimEdge>& rim, std::int64_t first);

}  // namespace gpugeom::del2d::digital
