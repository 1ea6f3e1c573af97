// Drawings of 2D triangulations and Voronoi cells for a person to look at (SVG or PNG).
#pragma once
#include <string>
#include <vector>

#include "gpugeom/delaunay2d.hpp"

namespace gpugeom::cli {

// Bounding box of xy (x, y interleaved) grown by frac of its size on each side:
// {xmin, ymin, xmax, ymax}.
std::vector<double> grown_box(const HostVector<double>& xy, double frac);

// Triangles in grey, points in black, clipped Voronoi cells (optional) in red. The format
// follows the extension: .svg or .png (1600 pixels on the longer side).
void draw_triangulation(const std::string& path, const HostVector<double>& xy,
                        const Triangulation2d& tri, const ClippedCells* cells);

}  // namespace gpugeom::cli
