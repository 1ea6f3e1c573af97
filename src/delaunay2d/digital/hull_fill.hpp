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
// counter-clockwise triangles with their half-edges' twins (sketch.hpp; -1 on the boundary).
// Appends the pockets' triangles, pairs their half-edges with the boundary's and each other's,
// and returns how many; throws Error(Internal) where the boundary is not one simple cycle. Only
// the boundary is read.
std::int64_t fill_to_hull(const std::vector<std::int64_t>& x, const std::vector<std::int64_t>& y,
                          std::vector<std::int32_t>& triangles, std::vector<std::int32_t>& twin);

// Pairs the half-edges of the triangles from slot `first` on with the unpaired half-edges open
// (reverse direction; ids 3t + k) and with each other (twin -1 where nothing matches).
void pair_new_half_edges(const std::vector<std::int32_t>& triangles,
                         std::vector<std::int32_t>& twin, std::int64_t first,
                         const std::vector<std::int32_t>& open);

}  // namespace gpugeom::del2d::digital
