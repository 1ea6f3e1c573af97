// gpugeom_testing (issue 48): the library's phases entered one by one, for its tests only. Only
// the tests link this target; the product library has no entry point that exists for them (its
// knobs for tests are detail::Tuning, carried in the options: exec/tuning.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include "delaunay2d/del2d_backend.hpp"
#include "delaunay2d/digital/shift.hpp"
#include "delaunay2d/digital/sketch.hpp"
#include "gpugeom/delaunay3d.hpp"

namespace gpugeom::testing {

// 2D Delaunay from a start: nstart counter-clockwise triangles of input indices (3 each, host
// memory) that cover the convex hull of their vertices, each directed edge once; the other
// points are inserted into it and the whole is flipped until Delaunay by the same batches and
// rounds (what the digital method does with its sketch). twin (host, 3 nstart, or null: found by
// sorting the edges): per half-edge 3t + k (vertex k to k + 1) its reverse, -1 on the hull. hint
// (host, n entries, or null): for each point not in the start, a start vertex near it where its
// walk begins (-1: anywhere). The result equals delaunay2d's. Runs on opt's executor.
void triangulate_from(const double* xy, std::int64_t n, const std::int32_t* start,
                      std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                      const Delaunay2dOptions& opt, del2d::Output& out, Delaunay2dStats& stats);

// The digital sketch (delaunay2d/digital/sketch.hpp) of host points, on run's executor. side:
// the grid's largest extent (4..46338): the pixel size is the least power of two with which the
// points' bounding box spans at most side pixels (between side / 2 and side), and the grid is
// trimmed to the box (two pixels more at most: the origin rounded down, the last pixel).
// keep_colour: also bring the whole colouring to the host.
del2d::digital::Sketch digital_sketch(const double* xy, std::int64_t n, std::int64_t side,
                                      const RunOptions& run, bool keep_colour = false);

// The shifting phase (delaunay2d/digital/shift.hpp) of a sketch of the n points xy, on run's
// executor.
del2d::digital::Start shift_sketch(const double* xy, std::int64_t n,
                                   const del2d::digital::Sketch& s, const RunOptions& run);

// The 3D digital method's stars on the CPU executor, after creation (splay 0), after splaying
// (1), or after splaying by the tetrahedra's rounds and the proof alone (2). pts: the distinct
// points in curve order (3 each); star v is tri[3 start[v], 3 start[v + 1]) (link triangles, 3
// point indices each; index pts.size() / 3 is the infinity point), its vertex table
// table_vertex / table_hash [table_start[v], table_start[v + 1]) (the link vertices, each with
// its ring's hash). built is false where the method fell back. first_requests > 0 sizes the
// splaying's request buffer (so that requests overflow it); request_spills counts the checks run
// again for those.
struct Stars {
  bool built = false;
  std::vector<double> pts;
  std::vector<std::int64_t> start;
  std::vector<std::int32_t> tri;
  std::vector<std::int64_t> table_start;
  std::vector<std::int32_t> table_vertex;
  std::vector<std::uint32_t> table_hash;
  std::int64_t request_spills = 0;
};
void digital_stars(const double* xyz, std::int64_t n, std::int64_t grid, int splay, Stars& out,
                   std::int64_t first_requests = 0);

}  // namespace gpugeom::testing
