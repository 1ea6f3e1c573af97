// Segments that cross each other, split at their intersections, and the input checks the
// constrained and the refining entries share (internal to cdt2d, host code).
//
// Crossing pairs are found through a uniform grid of cells (each segment listed in the cells it
// passes, every pair sharing a cell tested exactly: both pairs of ends strictly on opposite
// sides), plus any pair the caller names (the recovery reports a crossing the grid missed). Each
// crossing adds a vertex at the intersection, rounded to doubles (computed in long double; the
// same rounded point is one vertex for every pair that gives it), unless an input point lies
// there exactly: then both segments already run through an input point, which the recovery
// takes as it is. Each segment becomes the chain of pieces between its ends and the vertices on
// it, in order along it. Pieces can cross where rounding moved a vertex, so the search runs again
// on the pieces, a few times.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "gpugeom/cdt2d.hpp"

namespace gpugeom::cdt {

struct SplitSegments {
  std::vector<double> points;                // the new vertices, x and y (indices n, n+1, ...)
  std::vector<std::int32_t> point_segments;  // per new vertex, the two input segments crossing
  std::vector<std::int32_t> pieces;          // pairs of point indices (the new ones from n)
  std::vector<std::int32_t> piece_segment;   // per piece, its input segment
  std::int64_t split_segments = 0;           // input segments cut in two or more pieces
};

// xy: n points; segs: m pairs (checked indices). extra: pairs of input segments known to cross.
// Returns no pieces when nothing crosses. Throws Error(InvalidInput) naming two segments whose
// pieces still cross after the rounds (never seen: only near-coincident crossings could).
SplitSegments split_crossings(const double* xy, std::int64_t n, const std::int32_t* segs,
                              std::int64_t m,
                              const std::vector<std::pair<std::int32_t, std::int32_t>>& extra);

// The checks the constrained and the refining entries make before any work (counts, the segments'
// pointer, finite hole and region points); the host entries then check the indices
// (check_segment_indices), the device entries check them on the device.
void check_input(std::int64_t n, const std::int32_t* segments, std::int64_t nseg,
                 const Cdt2dDomainOptions& opt);

// Throws Error(InvalidInput) naming the first of the m segments (index pairs, host memory) that
// names a point outside 0..n-1.
void check_segment_indices(const std::int32_t* segs, std::int64_t m, std::int64_t n);

// What a triangulation runs on after split_crossings: the caller's points and segments where
// nothing was split, else the points followed by the new vertices (held here), and the pieces
// (held by the SplitSegments, which must outlive this).
struct SplitInput {
  std::vector<double> joined;
  const double* points = nullptr;
  std::int64_t num_points = 0;
  const std::int32_t* segments = nullptr;
  std::int64_t num_segments = 0;
};
SplitInput split_input(const double* xy, std::int64_t n, const std::int32_t* segs, std::int64_t m,
                       const SplitSegments& sp);

}  // namespace gpugeom::cdt
