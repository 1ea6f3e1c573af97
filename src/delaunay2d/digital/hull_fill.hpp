// The digital sketch made a triangulation of the convex hull of its vertices (issue 20, thesis
// 4.3.2's boundary step; internal). The dual of a diagram truncated by its grid is a disk whose
// boundary need not be convex; each pocket between the boundary and the hull of the boundary's
// vertices is a simple polygon, triangulated by ear clipping. The flips that follow make the
// result Delaunay, so any triangulation of a pocket will do. Integer grid coordinates: every
// orientation is exact.
#pragma once
#include <cstdint>
#include <vector>

namespace gpugeom::del2d::digital {

// x, y: each point's grid coordinates (the points the triangles name); triangles: a disk of
// counter-clockwise triangles, each directed edge once. Appends the pockets' triangles and
// returns how many; throws Error(Internal) where the boundary is not one simple cycle.
std::int64_t fill_to_hull(const std::vector<std::int64_t>& x, const std::vector<std::int64_t>& y,
                          std::vector<std::int32_t>& triangles);

}  // namespace gpugeom::del2d::digital
