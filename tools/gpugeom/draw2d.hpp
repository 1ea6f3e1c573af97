// Drawings of 2D triangulations and Voronoi cells for a person to look at (SVG or PNG).
#pragma once
#include <string>
#include <vector>

#include "gpugeom/delaunay2d.hpp"

namespace gpugeom::cli {

// Bounding box of xy (x, y interleaved) grown by frac of its size on each side:
// {xmin, ymin, xmax, ymax}.
std::vector<double> grown_box(const HostVector<double>& xy, double frac);

// Triangles in grey, points in black, clipped Voronoi cells (optional) in red, and the edges
// whose mark is not negative (marks: 3 per triangle, the edge opposite vertex k; optional:
// the constraints of a constrained triangulation) in blue. The format follows the extension:
// .svg or .png (1600 pixels on the longer side).
void draw_triangulation(const std::string& path, const HostVector<double>& xy,
                        const Triangulation2d& tri, const ClippedCells* cells,
                        const std::int32_t* marks = nullptr);

}  // namespace gpugeom::cli
