// The digital sketch of a 2D Delaunay triangulation (issue 20, thesis 4.3 Phases 1a and 1b;
// internal): the points mapped to a grid, the digital Voronoi diagram by PBA (the EDT module's,
// on the executor asked for), its debris recoloured so that every cell is path-connected to its
// site (Alg. 4.3: the result equals the standard flooding algorithm's, Alg. 4.2), and its dual:
// a triangle for each grid corner where three colours meet, two where four do, completed to the
// convex hull of its vertices. Points sharing a
// pixel with an earlier point are missing points (inserted by a later phase).
//
// The order ≺ of (pixel, site) pairs everywhere: squared distance, then the site's raster
// index (y * width + x), then the pixel's raster index (PBA breaks ties between sites the same
// way, so its labels and the flooding agree wherever a cell is connected).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "gpugeom/common.hpp"

namespace gpugeom::del2d::digital {

struct Sketch {
  // The grid: width x height pixels; grid point (gx, gy) stands for (ox + gx h, oy + gy h), h a
  // power of two and ox, oy multiples of it, so that these are exact doubles wherever `exact`
  // (the shifting phase compares them with the points' own coordinates, shift.hpp).
  std::int64_t width = 0, height = 0;
  double ox = 0, oy = 0, h = 1;
  bool exact = false;
  std::vector<std::int32_t> pixel;     // per point: its pixel's raster index (y * width + x)
  std::vector<std::int32_t> missing;   // points whose pixel an earlier point took
  std::vector<std::int32_t> site_of;   // per point: the site of its pixel (itself for a site)
  std::vector<std::int32_t> colour;    // per pixel: the point whose cell holds it (keep_colour)
  std::int64_t debris = 0;             // pixels recoloured
  std::int64_t debris_candidates = 0;  // pixels whose descent missed their site (tested further)
  std::int64_t pinched = 0;            // corners a cell crosses diagonally (no triangle)
  std::int64_t hull_triangles = 0;     // added between the dual's boundary and its convex hull
  std::int64_t not_disk = 0;  // 1: the dual's boundary passes a vertex twice (no triangles kept)
  // Dual triangles as point indices, counter-clockwise in the grid (the corner's cells in
  // counter-clockwise order), then those filling the pockets up to the convex hull of their
  // vertices (hull_fill.hpp): a triangulation of that hull.
  std::vector<std::int32_t> triangles;
  // Per half-edge 3t + k (from vertex k of triangle t to vertex k + 1): its reverse, -1 on the
  // boundary.
  std::vector<std::int32_t> twin;
  // Milliseconds of each step: "grid" (mapping), "pba", "debris", "dual", "adjacency",
  // "hull_fill".
  std::vector<std::pair<std::string, double>> phase_ms;
};

// The frame (width, height, ox, oy, h, exact) for points in the box [lo, hi] and a grid of
// `side` (4..46338; else Error(InvalidArgument)).
void set_frame(Sketch& s, const double lo[2], const double hi[2], std::int64_t side);

}  // namespace gpugeom::del2d::digital
