// Exact 3D convex hull (thesis 5.2: star-shaped construction, then Flip-Flop).
//
// Exactness: every decision is an exact predicate with simulation of simplicity, and the
// vertices returned are exactly the extreme points: a point inside a hull face or on a hull
// edge is not a vertex, and of several copies of an extreme point exactly one is: the first in
// input order. Coplanar extreme points of a face are triangulated; no facet is degenerate. The
// points are processed along a Hilbert curve, and the perturbation follows that order, so the
// result (which diagonals cut a flat face, the facet order) depends on the point set only, not
// on the order of the input, and is the same on every executor and every run.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

struct Hull3dOptions : RunOptions {};

struct ConvexHull3d {
  // Facets: 3 input-point indices each, counter-clockwise seen from outside.
  HostVector<std::int32_t> triangles;
  // neighbors[3*i + k]: the facet across the edge opposite vertex k of facet i (the surface is
  // closed: never -1).
  HostVector<std::int32_t> neighbors;
  // The extreme points, as sorted input indices.
  HostVector<std::int32_t> vertices;
  // Plane of each facet as in Qhull / SciPy's `equations`: unit outward normal (a, b, c) and
  // offset d, with a x + b y + c z + d <= 0 for every input point up to rounding (the planes
  // are computed in floating point; the hull itself is exact).
  HostVector<double> equations;
  // Stats: phases "upload" (CUDA), "sort" (validation, curve order, copies merged),
  // "prepare", "construct", "flip", "extreme_test", "input_indices", "host_arrays",
  // "copy_back" (CUDA), "planes"; counters "duplicates", "insert_rounds", "flip_rounds",
  // "flips22", "flips31", "labelled_nonextreme", "exact_predicates", "first_pass_vertices",
  // "nonextreme_vertices_dropped", "passes" (2 when the extreme points needed a hull of their
  // own).
  Stats stats;
  std::size_t num_facets() const { return triangles.size() / 3; }
};

// xyz: n points, x, y and z interleaved. Throws Error(InvalidInput) for NaN/Inf or coordinates
// outside the exactly representable range, or more than 2^28 - 8 points;
// Error(DegenerateInput) naming the case when all points coincide, lie on one line or on one
// plane (which includes fewer than 4 distinct points).
ConvexHull3d convex_hull3d(const double* xyz, std::int64_t n, const Hull3dOptions& opt = {});
ConvexHull3d convex_hull3d(const std::vector<Point3>& pts, const Hull3dOptions& opt = {});

// The same hull with the points already on the GPU and the result left there (CUDA builds):
// device_xyz is device memory holding n points on run's device, ready in run.stream's order (see
// RunOptions; work on the legacy default stream always is). The arrays are device memory freed when
// the last copy of their pointer goes. Throws Error(Unsupported) where the build or the machine has
// no CUDA device.
struct DeviceHull3d {
  std::int64_t num_points = 0, num_facets = 0, num_vertices = 0;
  std::shared_ptr<std::int32_t> triangles;  // 3 * num_facets, as ConvexHull3d's
  std::shared_ptr<std::int32_t> neighbors;  // 3 * num_facets
  std::shared_ptr<std::int32_t> vertices;   // num_vertices
  Stats stats;
};
DeviceHull3d convex_hull3d_device(const double* device_xyz, std::int64_t n,
                                  const RunOptions& run = {});

}  // namespace gpugeom
