// The digital method's shifting phase (issue 20, thesis 4.3.3, Algs. 4.4 and 4.5; internal):
// the sketch is a valid triangulation of its sites at their grid points; this moves each site to
// its own coordinates where that keeps the triangulation valid (a "good case": its fan stays
// counter-clockwise and, on the boundary, the boundary stays convex), in rounds of a fixed
// scattered order (impl/shift.inl), and
// deletes the others ("bad cases", which become missing points): an inner vertex's hole is
// re-triangulated by ear clipping, a boundary vertex's by the convex chain its neighbours leave
// (the pockets between it and them filled). Every test is an exact orientation; the grid points
// are exact doubles (sketch.hpp), so the triangulation is valid at every step.
//
// The result is checked as a whole before it is used (every triangle counter-clockwise, the
// boundary one convex cycle turning once, V - E + F = 1): a triangulation covering the convex
// hull of its vertices, the start the 2D Triangulator takes (impl/triangulate.inl,
// run_from_start). Where that check fails the caller uses the incremental method (the same
// result; the tests require it never to happen).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "delaunay2d/digital/hull_fill.hpp"
#include "delaunay2d/digital/sketch.hpp"

namespace gpugeom::del2d::digital {

struct Start {
  std::vector<std::int32_t> triangles;  // counter-clockwise at the points' own coordinates
  std::vector<std::int32_t> twin;       // per half-edge of triangles (sketch.hpp's convention)
  // Per point not in the start: a start vertex near it (its pixel's site, or a neighbour it had
  // when it was deleted), where the insertion's walk begins (thesis 4.3.4); -1: none found.
  std::vector<std::int32_t> hint;
  std::int64_t triangle_count = 0;               // (also where the arrays stay on the executor)
  std::int64_t vertices = 0;                     // points the triangles use
  std::int64_t shifted = 0;                      // sites moved to their coordinates (good cases)
  std::int64_t bad_inner = 0, bad_boundary = 0;  // sites deleted (bad cases)
  std::int64_t shift_rounds = 0, delete_rounds = 0;
  std::int64_t not_ccw = 0;  // triangles left not counter-clockwise (the check refuses them)
  bool valid = false;        // false: not a start (reason says why)
  std::string reason;
  std::vector<std::pair<std::string, double>> phase_ms;
};

// The start's whole check from its boundary half-edges (coordinates: the points' own) and s's
// counts (triangle_count, vertices, not_ccw): empty where it is a start, else the reason.
std::string check_start(const std::vector<RimEdge>& rim, const Start& s);

}  // namespace gpugeom::del2d::digital
