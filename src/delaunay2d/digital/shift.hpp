// The digital method's shifting phase (issue 20, thesis 4.3.3, Algs. 4.4 and 4.5; internal):
// the sketch is a valid triangulation of its sites at their grid points; this moves each site to
// its own coordinates where that keeps the triangulation valid (a "good case": its fan stays
// counter-clockwise and, on the boundary, the boundary stays convex), in index order, and
// deletes the others ("bad cases", which become missing points): an inner vertex's hole is
// re-triangulated by ear clipping, a boundary vertex's by the convex chain its neighbours leave
// (the pockets between it and them filled). Every test is an exact orientation; the grid points
// are exact doubles (sketch.hpp), so the triangulation is valid at every step.
//
// The result is checked as a whole before it is used (every triangle counter-clockwise, the
// boundary one convex cycle turning once, V - E + F = 1): a triangulation covering the convex
// hull of its vertices, the start the 2D Triangulator takes (del2d_backend.hpp,
// triangulate_from). Where that check fails the caller uses the incremental method (the same
// result; the tests require it never to happen).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "delaunay2d/digital/sketch.hpp"

namespace gpugeom::del2d::digital {

struct Start {
  std::vector<std::int32_t> triangles;  // counter-clockwise at the points' own coordinates
  // Per point not in the start: a start vertex near it (its pixel's site, or a neighbour it had
  // when it was deleted), where the insertion's walk begins (thesis 4.3.4); -1: none found.
  std::vector<std::int32_t> hint;
  std::vector<std::int32_t> twin;  // per half-edge of triangles (sketch.hpp's convention)
  std::int64_t vertices = 0;       // points the triangles use
  std::int64_t shifted = 0;        // sites moved to their coordinates (good cases)
  std::int64_t bad_inner = 0, bad_boundary = 0;  // sites deleted (bad cases)
  std::int64_t filled = 0;                       // triangles added where a boundary vertex went
  bool valid = false;                            // false: not a start (reason says why)
  std::string reason;
};

// xy: the n points the sketch was made of.
Start shift_sketch(const double* xy, std::int64_t n, const Sketch& s);

}  // namespace gpugeom::del2d::digital
