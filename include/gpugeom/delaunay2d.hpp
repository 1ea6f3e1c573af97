// Exact 2D Delaunay triangulation (batch insertion with parallel flipping, thesis 5.3 applied
// to 2D) and the Voronoi diagram derived from it.
//
// Exactness: every decision is an exact predicate with simulation of simplicity, so
// cocircular and collinear subsets get one consistent answer; the triangulation returned is a
// Delaunay triangulation of the distinct input points, every distinct point is a vertex, and
// no triangle is degenerate (collinear points on the hull become hull vertices).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

struct Delaunay2dOptions : RunOptions {};

struct Triangulation2d {
  // Counter-clockwise triangles, 3 input-point indices each.
  HostVector<std::int32_t> triangles;
  // neighbors[3*i + k]: the triangle opposite vertex k of triangle i, -1 on the hull (SciPy's
  // convention).
  HostVector<std::int32_t> neighbors;
  // One entry per input point: -1 when the point is a vertex, else the index of the earlier
  // point with the same coordinates, which is the one used.
  HostVector<std::int32_t> duplicate_of;
  std::int64_t num_duplicates = 0;
  // Stats: phases "prepare", "insert" (with its flips), "finish" and "copies"; counters
  // "batches", "flips", "flip_rounds", "exact_predicates", "points", "distinct_points".
  Stats stats;
  std::size_t num_triangles() const { return triangles.size() / 3; }
};

// xy: n points, x and y interleaved. Throws Error(InvalidInput) for NaN/Inf or coordinates
// outside the exactly representable range, more than 2^28 points; Error(DegenerateInput) for
// fewer than 3 distinct points or all points on one line.
Triangulation2d delaunay2d(const double* xy, std::int64_t n, const Delaunay2dOptions& opt = {});
Triangulation2d delaunay2d(const std::vector<Point2>& pts, const Delaunay2dOptions& opt = {});

// The same triangulation with the points already on the GPU and the result left there (CUDA
// builds): device_xy is device memory holding n points, x and y interleaved, on run's device.
// The work runs on run.stream (see RunOptions), so the points must be ready in that stream's
// order (work on the legacy default stream always is); the call returns once the result is
// ready. The arrays are device memory freed when the last copy of their pointer goes; they can
// be wrapped without copying, e.g. by CuPy. run.backend is ignored.
struct DeviceTriangulation2d {
  std::int64_t num_points = 0, num_triangles = 0, num_duplicates = 0;
  std::shared_ptr<std::int32_t> triangles;     // 3 * num_triangles, as Triangulation2d's
  std::shared_ptr<std::int32_t> neighbors;     // 3 * num_triangles
  std::shared_ptr<std::int32_t> duplicate_of;  // num_points
  Stats stats;
};
// Throws Error(Unsupported) where the build or the machine has no CUDA device.
DeviceTriangulation2d delaunay2d_device(const double* device_xy, std::int64_t n,
                                        const RunOptions& run = {});

// The Voronoi diagram dual to a Delaunay triangulation, in SciPy's `Voronoi` conventions.
struct Voronoi2d {
  HostVector<double> vertices;  // circumcentres, x and y interleaved (one per triangle)
  // Ridges: the pair of input points each ridge separates, and its two Voronoi vertices
  // (-1 for a ridge that goes to infinity).
  HostVector<std::int32_t> ridge_points;
  HostVector<std::int32_t> ridge_vertices;
  // Cells: for each input point, its Voronoi vertices in counter-clockwise order; an unbounded
  // cell starts with -1 (its two unbounded ridges leave from its first and last vertex).
  // Duplicate points share the cell of the point they duplicate.
  HostVector<std::int64_t> cell_offsets;  // n + 1 offsets into cell_vertices
  HostVector<std::int32_t> cell_vertices;
  // For an unbounded ridge, the outward direction (unit vector) of its ray, else (0, 0).
  HostVector<double> ridge_directions;
};
Voronoi2d voronoi2d(const double* xy, std::int64_t n, const Triangulation2d& tri);

// Voronoi cells clipped to a box [xmin, xmax] x [ymin, ymax] that contains every input point:
// each cell as a closed counter-clockwise polygon (x, y interleaved).
struct ClippedCells {
  HostVector<std::int64_t> offsets;  // n + 1 offsets (in points) into xy
  HostVector<double> xy;
};
ClippedCells clip_voronoi_cells(const double* xy, std::int64_t n, const Triangulation2d& tri,
                                const Voronoi2d& vor, double xmin, double ymin, double xmax,
                                double ymax);

}  // namespace gpugeom
