/// @file
/// Exact 3D convex hull (thesis 5.2: star-shaped construction, then Flip-Flop; or thesis 4.4's
/// digital method, Hull3dOptions::method).
///
/// Exactness: every decision is an exact predicate with simulation of simplicity, and the
/// vertices returned are exactly the extreme points: a point inside a hull face or on a hull
/// edge is not a vertex, and of several copies of an extreme point exactly one is: the first in
/// input order. Coplanar extreme points of a face are triangulated; no facet is degenerate. The
/// points are processed along a Hilbert curve, and the perturbation depends on each point's
/// coordinates alone, so the result (which diagonals cut a flat face, the facet order) depends
/// on the point set only, not on the order of the input, and is the same on every executor and
/// every run; a flat face keeps its diagonals when points join that do not change the face.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpugeom/changes.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// Arrays the caller provides for the results (OutBuffer, common.hpp; SciPy's `out=` pattern):
/// host memory for convex_hull3d, device memory for convex_hull3d_device (host memory where it
/// runs on the CPU executor). Their lengths depend on the result: triangles and neighbors at least
/// 3 times the facet count, equations 4 times, vertices at least the vertex count;
/// convex_hull3d_max_facets(n) facets and n vertices always suffice. They are checked once the
/// counts are known and before anything is written (Error(InvalidArgument) naming the array and
/// both lengths). An output written into a caller's array is empty (null) in the result.
struct Hull3dBuffers {
  OutBuffer<std::int32_t> triangles, neighbors, vertices;
  OutBuffer<double> equations;
};

/// How convex_hull3d and convex_hull3d_device run (RunOptions), the method and the caller's output
/// arrays.
struct Hull3dOptions : RunOptions {
  Hull3dBuffers into;  ///< optional
  /// The method (common.hpp): the result does not depend on it. Method::Digital is the thesis'
  /// DigiHull3D (4.4): the points with a cell on the six faces of a grid around them (a slice of
  /// their digital Voronoi diagram on each face) give a first hull; a digital depth test against
  /// it (six depth images, one pixel of tolerance, Lemma 4.10) keeps every point that may lie
  /// outside or on it; the hull of those is the hull. Both entries take it.
  Method method = Method::Incremental;
  /// Method::Digital: the faces' grid side (16..8192; 0 chooses from the point count, at most
  /// 1024); the depth images have half as many pixels a side.
  std::int64_t grid = 0;
};

/// Statistics of a convex hull: RunStats (where it ran, its phases in the order they ran, its
/// device peak) and the counters as fields, 0 where their step did not run. Phases: "upload"
/// (CUDA), "sort" (validation, curve order, copies merged), "prepare", "construct", "flip" (again
/// for a second pass), "extreme_test", "input_indices", "copy_back" (CUDA), "planes";
/// Method::Digital adds "digital_slices", "digital_sketch_hull", "digital_depth_test";
/// DynamicHull3d's updates "kept_indices", "inside_test", "append" and "total".
struct Hull3dStats : RunStats {
  /// Input points that repeat an earlier one's coordinates (merged before the hull).
  std::int64_t duplicates = 0;
  /// Hull passes made: 2 where the first pass's vertices were not all extreme (points inside a
  /// face or an edge) and the extreme points needed a hull of their own; 0 where a DynamicHull3d
  /// update needed no hull.
  std::int64_t passes = 0;
  /// The star-shaped construction's insertion rounds, and the times its facet store grew (the
  /// GPU's schedule: 0 where the CPU executor runs its own, cavity_insertions below).
  std::int64_t insert_rounds = 0, facet_store_grown = 0;
  /// Flip-Flop's rounds, its 2-2 flips and 3-1 removals, and the vertices it labelled not
  /// extreme (the GPU's schedule, as insert_rounds).
  std::int64_t flip_rounds = 0, flips22 = 0, flips31 = 0, labelled_nonextreme = 0;
  /// Tests the floating-point filter left to the exact predicates.
  std::int64_t exact_predicates = 0;
  /// The first pass's vertices, and of them those the exact test found not extreme.
  std::int64_t first_pass_vertices = 0, nonextreme_vertices_dropped = 0;
  /// Method::Digital: the faces' grid side, the depth images' side, the points with a cell on a
  /// face (the sketch) and the facets of their hull, the points the depth test kept besides the
  /// sketch, and the points the hull was computed from (all of them after a fallback).
  std::int64_t digital_grid = 0, digital_render = 0, sketch_points = 0, sketch_facets = 0,
               depth_kept = 0, hull_input = 0;
  /// Method::Digital: 1 where the sketch had no hull and the incremental method ran.
  std::int64_t digital_fallback = 0;
  /// DynamicHull3d: the points the last hull was made from (the old hull's vertices and the new
  /// points outside it), the inserted points outside the old hull, and the removed points that
  /// were vertices.
  std::int64_t hull_candidates = 0, outside_points = 0, removed_vertices = 0;
  /// The CPU executor's own schedule: points inserted one by one (each by its cavity; those
  /// found inside the hull so far are dropped, not counted), and of them those a thread left to
  /// the end because their cavity reached another thread's part of the hull.
  std::int64_t cavity_insertions = 0, deferred_points = 0;

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// The most facets the hull of n points has (2n - 4, for n >= 4): sizes `into` ahead.
std::int64_t convex_hull3d_max_facets(std::int64_t n);

/// The result of convex_hull3d: facets, their neighbours, the hull's vertices and its planes, in
/// host memory.
struct ConvexHull3d {
  /// Facets: 3 input-point indices each, counter-clockwise seen from outside. In one order on
  /// every executor and thread count: along the Hilbert curve of the points, each facet starting
  /// at its vertex first on the curve.
  HostVector<std::int32_t> triangles;
  /// neighbors[3*i + k]: the facet across the edge opposite vertex k of facet i (the surface is
  /// closed: never -1).
  HostVector<std::int32_t> neighbors;
  /// The extreme points, as sorted input indices.
  HostVector<std::int32_t> vertices;
  /// Plane of each facet as in Qhull / SciPy's `equations`: unit outward normal (a, b, c) and
  /// offset d, with a x + b y + c z + d <= 0 for every input point up to rounding (the planes
  /// are computed in floating point; the hull itself is exact).
  HostVector<double> equations;
  Hull3dStats stats;
  /// Facets and extreme points written (also where they went into the caller's arrays).
  std::int64_t num_facets = 0, num_vertices = 0;
};

/// xyz: n points, x, y and z interleaved. Throws Error(InvalidInput) for NaN/Inf or coordinates
/// outside the exactly representable range, more than 2^31 - 2 points, or a hull of more than
/// 2^28 extreme points (the facets' neighbour encoding; found while the hull grows);
/// Error(OutOfMemory) with the bytes needed and free where the GPU's memory runs out;
/// Error(DegenerateInput) naming the case when all points coincide, lie on one line or on one
/// plane (which includes fewer than 4 distinct points).
ConvexHull3d convex_hull3d(const double* xyz, std::int64_t n, const Hull3dOptions& opt = {});
/// The same for a vector of points.
ConvexHull3d convex_hull3d(const std::vector<Point3>& pts, const Hull3dOptions& opt = {});

/// The result of convex_hull3d_device: arrays in device memory (host memory on the CPU executor).
struct DeviceHull3d {
  std::int64_t num_points = 0, num_facets = 0, num_vertices = 0;
  std::shared_ptr<std::int32_t> triangles;  ///< 3 * num_facets, as ConvexHull3d's
  std::shared_ptr<std::int32_t> neighbors;  ///< 3 * num_facets
  std::shared_ptr<std::int32_t> vertices;   ///< num_vertices
  std::shared_ptr<double> equations;        ///< 4 * num_facets
  Backend backend = Backend::Cuda;          ///< where the arrays are: Cuda = device memory
  Hull3dStats stats;
};
/// The same hull with the points already on the GPU and the result left there: device_xyz is
/// device memory holding n points on opt.device, ready in opt.stream's order (see RunOptions; work
/// on the legacy default stream always is); the call returns once the result is ready, and waits
/// for nothing else on the device. The arrays are device memory of the call's resource
/// (RunOptions::memory), freed when the last copy of their pointer goes, or the caller's
/// (opt.into). With opt.backend == Backend::Cpu the CPU executor runs it on host memory (the same
/// result); otherwise CUDA runs it, whatever GPUGEOM_BACKEND says. Throws Error(Unsupported) where
/// no CUDA device can be used (and the CPU was not asked for), and as convex_hull3d otherwise.
DeviceHull3d convex_hull3d_device(const double* device_xyz, std::int64_t n,
                                  const Hull3dOptions& opt = {});

/// A 3D convex hull that follows its points (issue 47): kept on the executor between calls, it
/// takes new points, new coordinates and removals. After any sequence of calls it is exactly the
/// hull convex_hull3d gives for the points there are (removed ones left out): the same facets with
/// the same neighbours and extreme points (the facets' order in the arrays may differ, and with it
/// where each facet starts, so its plane may differ by rounding).
/// Points keep the indices they were given: the first call's are 0 .. n - 1, each insert's follow
/// on; a removed point keeps its index and is never a vertex.
///
/// What each call costs: an insertion makes the hull of the old hull's vertices and those new
/// points not strictly inside the old hull only (a point that is not extreme stays so when points
/// join), so it does not grow with the points inside, and where every new point is inside no hull
/// is made (Hull3dStats::outside_points); a removal that takes no vertex changes nothing, one
/// that does makes the hull of all points left; a move makes the hull of all the moved points.
/// Hull3dStats::hull_candidates says how many points the last hull was made from.
///
/// The state lives where the executor runs: device memory of opt.device on CUDA (fixed at
/// construction; the work runs on opt.stream, which must outlive the object), host memory on the
/// CPU executor. Calls on one object must not overlap; separate objects are independent. A call
/// that throws leaves the object as it was (a moved-from object may only be assigned or
/// destroyed). opt.method is used for every hull made (the result does not depend on it).
class DynamicHull3d {
 public:
  /// The hull of n host points (x, y and z interleaved) on the executor opt picks. Throws as
  /// convex_hull3d; Error(Unsupported) for opt.into (results are read with hull()).
  DynamicHull3d(const double* xyz, std::int64_t n, const Hull3dOptions& opt = {});
  /// The same from points in executor memory (device memory, as convex_hull3d_device takes them;
  /// host memory with opt.backend == Backend::Cpu).
  static DynamicHull3d from_device(const double* device_xyz, std::int64_t n,
                                   const Hull3dOptions& opt = {});
  DynamicHull3d(DynamicHull3d&&) noexcept;
  DynamicHull3d& operator=(DynamicHull3d&&) noexcept;
  ~DynamicHull3d();

  /// Adds n points (host memory; insert_device: executor memory, as from_device), numbered
  /// num_points() on. Throws as convex_hull3d for bad coordinates or too many points in all; the
  /// object is then unchanged.
  void insert(const double* xyz, std::int64_t n);
  /// As insert, with the points in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void insert_device(const double* device_xyz, std::int64_t n);
  /// New coordinates for every point (n == num_points(); host memory, or executor memory for
  /// move_device). Throws as insert, Error(InvalidArgument) for another count, and
  /// Error(DegenerateInput) where the points (removed ones left out) came to lie on one plane;
  /// the object is then unchanged.
  void move(const double* xyz, std::int64_t n);
  /// As move, with the coordinates in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void move_device(const double* device_xyz, std::int64_t n);
  /// Removes the points with the given indices (count of them, each once, none removed before;
  /// host memory, or executor memory for remove_device). Hull3dStats::removed_vertices: how
  /// many of them were vertices. Throws Error(InvalidArgument) for a bad index list and
  /// Error(DegenerateInput) where the points left have no hull (fewer than 4, or all on one
  /// plane); the object is then unchanged.
  void remove(const std::int32_t* indices, std::int64_t count);
  /// As remove, with the indices in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void remove_device(const std::int32_t* device_indices, std::int64_t count);

  std::int64_t num_points() const;  ///< every index given so far, removed ones included
  /// Points removed so far.
  std::int64_t num_removed() const;
  /// Facets of the current hull.
  std::int64_t num_facets() const;
  /// Vertices of the current hull (extreme points).
  std::int64_t num_vertices() const;
  Backend backend() const;  ///< the executor holding the state
  /// Copies of the current hull: host arrays as convex_hull3d returns them, or new arrays in
  /// executor memory as convex_hull3d_device returns them.
  ConvexHull3d hull() const;
  /// The current hull in executor memory (copies of the kept arrays).
  DeviceHull3d device_hull() const;
  /// Which facets the last update (insert, move or remove) changed (changes.hpp), as
  /// DynamicDelaunay3d's: off by default; with track_changes(true) each update keeps the arrays it
  /// replaces until the next one. changes() / device_changes() throw Error(InvalidArgument) where
  /// no update ran with tracking on.
  void track_changes(bool on = true);
  /// Since track_changes: the facets that were removed and those added, in host memory.
  SimplexChanges changes() const;
  /// As changes, in executor memory.
  DeviceSimplexChanges device_changes() const;
  /// Phases and counters of the last call that changed the points.
  const Hull3dStats& stats() const;

 private:
  struct Impl;
  explicit DynamicHull3d(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace gpugeom
