// The digital 2D Delaunay method (issue 20, thesis 4.3; Delaunay2dOptions::method = Digital):
// the sketch (sketch.hpp: grid, PBA, debris, dual, hull), the shifting phase (shift.hpp), then
// the 2D Triangulator from that start (impl/triangulate.inl, run_from_start): the points the
// sketch lost are inserted by its batches (Alg. 4.6) and everything flipped by its rounds
// (Phase 3b). The result equals the incremental method's.
#pragma once
#include <cstdint>

#include "delaunay2d/del2d_backend.hpp"

namespace gpugeom::del2d::digital {

// The grid's longer side chosen from the point count and their bounding box
// (Delaunay2dOptions::grid = 0): about 4 pixels a point, at most 16384. The box [lo, hi], or
// the points' own.
std::int64_t auto_side(const double lo[2], const double hi[2], std::int64_t n);
std::int64_t auto_side(const double* xy, std::int64_t n);

// The public host entry's work for Method::Digital on executor b (del2d_backend.hpp,
// triangulate_digital, after the grid side is checked). Stats: the sketch's and the
// shift's phases, then the Triangulator's; the digital counters (Delaunay2dStats), and
// digital_fallback 1 where the sketch could not be used and the incremental method ran instead
// (points whose grid points are not exact doubles, fewer than 3 sites).
void triangulate(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Backend b,
                 Output& out, Delaunay2dStats& st);

}  // namespace gpugeom::del2d::digital
