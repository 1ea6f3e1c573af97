/// @file
/// Exact 2D Delaunay triangulation (batch insertion with parallel flipping, thesis 5.3 applied
/// to 2D) and the Voronoi diagram derived from it.
///
/// Exactness: every decision is an exact predicate with simulation of simplicity, so
/// cocircular and collinear subsets get one consistent answer; the triangulation returned is a
/// Delaunay triangulation of the distinct input points, every distinct point is a vertex, and
/// no triangle is degenerate (collinear points on the hull become hull vertices).
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"
#include "gpugeom/changes.hpp"
#include "gpugeom/removed.hpp"

namespace gpugeom {

/// Arrays the caller provides for the results (OutBuffer, common.hpp; SciPy's `out=` pattern):
/// host memory for delaunay2d, device memory for delaunay2d_device (host memory where it runs on
/// the CPU executor). triangles and neighbors must hold at least 3 times the triangle count, which
/// depends on the result (3 * delaunay2d_max_triangles(n) always suffices); duplicate_of at least
/// n. They are checked once the count is known and before anything is written (Error(
/// InvalidArgument) naming the array and both lengths). An output written into a caller's array
/// is empty (null) in the result; num_triangles says how much of it was written.
struct Triangulation2dBuffers {
  OutBuffer<std::int32_t> triangles, neighbors, duplicate_of;
};

/// How delaunay2d and delaunay2d_device run (RunOptions), the method and the caller's output
/// arrays.
struct Delaunay2dOptions : RunOptions {
  Triangulation2dBuffers into;  ///< optional
  /// The method (common.hpp): the result does not depend on it. Method::Digital runs from host
  /// points (delaunay2d; delaunay2d_device refuses it).
  Method method = Method::Incremental;
  /// Method::Digital: the grid's size: the pixel is the least power of two with which the
  /// points' bounding box spans at most `grid` pixels (between grid / 2 and grid); 0 chooses it
  /// from the point count. 4 to 46338.
  std::int64_t grid = 0;
};

/// The most triangles a triangulation of n points has (2n - 5, for n >= 3): sizes `into` ahead.
std::int64_t delaunay2d_max_triangles(std::int64_t n);

/// Statistics of a 2D Delaunay triangulation: RunStats (phases "prepare", "insert" (with its
/// flips; "insert/<step>" under RunOptions::profile), "finish" and "copies"; Method::Digital adds
/// "digital_*" (grid, pba, debris, dual, adjacency, hull_fill, shift_*) and "start";
/// DynamicDelaunay2d's updates their own and "total") and the counters, 0 where their step did
/// not run.
struct Delaunay2dStats : RunStats {
  /// The points given, those distinct, and those equal to an earlier one.
  std::int64_t points = 0, distinct_points = 0, duplicates = 0;
  /// Insertion batches, flip rounds (with a non-empty work list; of them those shorter than a
  /// full round: small_flip_rounds, and those run in one team of threads, without a launch per
  /// step: team_flip_rounds) and flips.
  std::int64_t batches = 0, flip_rounds = 0, small_flip_rounds = 0, team_flip_rounds = 0, flips = 0;
  /// Work-list entries, and of them those the floating-point filter left to the exact
  /// predicates.
  std::int64_t work_list_entries = 0, exact_predicates = 0;
  /// Further exact passes past the exact list's capacity; relocations within a batch for a full
  /// flip log; flip rounds run in parts past the first.
  std::int64_t exact_rest_passes = 0, log_relocations = 0, split_flip_rounds = 0;
  /// The CPU executor's own schedule: points inserted one by one (each by its cavity), and of
  /// them those a thread left to the end because their cavity reached another thread's part of
  /// the curve (0 where the batches ran).
  std::int64_t cavity_insertions = 0, deferred_points = 0;
  /// Triangles left flat on the hull and peeled (points on one line at the boundary).
  std::int64_t flat_triangles = 0;
  /// The start's point location by walks: steps, scans, and the longest walk.
  std::int64_t start_walk_steps = 0, start_walk_scans = 0, start_walk_longest = 0;
  /// Method::Digital: the grid's width and height, the points with a pixel of their own (sites)
  /// and those the sketch missed, the debris pixels and candidates removed, pinched corners, the
  /// sketch's hull triangles, and whether it was not a disk.
  std::int64_t grid_width = 0, grid_height = 0, sites = 0, sketch_missing = 0, debris_pixels = 0,
               debris_candidates = 0, pinched_corners = 0, hull_triangles = 0, sketch_not_disk = 0;
  /// Method::Digital: the start triangulation's repair (vertices shifted, bad inner and boundary
  /// triangles, shift and delete rounds) and its size.
  std::int64_t shifted = 0, bad_inner = 0, bad_boundary = 0, shift_rounds = 0, delete_rounds = 0,
               start_vertices = 0, start_triangles = 0;
  /// Method::Digital: 1 where the sketch could not be used and the incremental method ran on
  /// the same preparation.
  std::int64_t digital_fallback = 0;
  /// DynamicDelaunay2d: points inserted; points removed, the holes' vertices and triangles, and
  /// whether the removal made the triangulation afresh; a move's rounds, the vertices it took
  /// out and put back, and whether it made the triangulation afresh.
  std::int64_t inserted_points = 0, removed_points = 0, hole_vertices = 0, hole_triangles = 0,
               remove_rebuilt = 0, move_rounds = 0, move_taken_out = 0, move_reinserted = 0,
               move_rebuilt = 0;
  /// delaunay{2,3}d_devices (multi_gpu.hpp): the blocks, those that took a second round, and
  /// the local points of their last rounds (all blocks together).
  std::int64_t blocks = 0, blocks_second_round = 0, block_local_points = 0;
  /// delaunay2d_furthest: the furthest-site triangulation's vertices (the hull's).
  std::int64_t furthest_site_vertices = 0;

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// The result of delaunay2d: triangles, neighbours and duplicates, in host memory.
struct Triangulation2d {
  /// Counter-clockwise triangles, 3 input-point indices each, in one order that depends on the
  /// points alone: each triangle starts at its vertex first on the points' space-filling curve,
  /// and the triangles follow their first two vertices in that order. So both executors, any
  /// thread count, either method and DynamicDelaunay2d give the same arrays.
  HostVector<std::int32_t> triangles;
  /// neighbors[3*i + k]: the triangle opposite vertex k of triangle i, -1 on the hull (SciPy's
  /// convention).
  HostVector<std::int32_t> neighbors;
  /// One entry per input point: -1 when the point is a vertex, else the index of the earlier
  /// point with the same coordinates, which is the one used.
  HostVector<std::int32_t> duplicate_of;
  std::int64_t num_duplicates = 0;
  Delaunay2dStats stats;
  /// Triangles written (also where they went into the caller's arrays, Delaunay2dOptions::into).
  std::int64_t num_triangles = 0;
};

/// xy: n points, x and y interleaved. Throws Error(InvalidInput) for NaN/Inf or coordinates
/// outside the exactly representable range, more than 2^29 - 2 points (536 870 910);
/// Error(OutOfMemory) before any launch where the device cannot hold the work (168 B a point at
/// least: 5·10^8 points on an 80 GB GPU); Error(DegenerateInput) for fewer than 3 distinct
/// points or all points on one line.
Triangulation2d delaunay2d(const double* xy, std::int64_t n, const Delaunay2dOptions& opt = {});
/// The same for a vector of points.
Triangulation2d delaunay2d(const std::vector<Point2>& pts, const Delaunay2dOptions& opt = {});

/// The same triangulation with the points already on the GPU and the result left there: device_xy
/// is device memory holding n points, x and y interleaved, on opt.device. The work runs on
/// opt.stream (see RunOptions), so the points must be ready in that stream's order (work on the
/// legacy default stream always is); the call returns once the result is ready, and waits for
/// nothing else on the device. The arrays are device memory of the call's resource
/// (RunOptions::memory), freed when the last copy of their pointer goes (they can be wrapped
/// without copying, e.g. by CuPy), or the caller's (opt.into). With opt.backend == Backend::Cpu the
/// CPU executor runs it on host memory (the same result); otherwise CUDA runs it, whatever
/// GPUGEOM_BACKEND says.
struct DeviceTriangulation2d {
  std::int64_t num_points = 0, num_triangles = 0, num_duplicates = 0;
  std::shared_ptr<std::int32_t> triangles;     ///< 3 * num_triangles, as Triangulation2d's
  std::shared_ptr<std::int32_t> neighbors;     ///< 3 * num_triangles
  std::shared_ptr<std::int32_t> duplicate_of;  ///< num_points
  Backend backend = Backend::Cuda;             ///< where the arrays are: Cuda = device memory
  Delaunay2dStats stats;
};
/// Throws Error(Unsupported) where no CUDA device can be used (and the CPU was not asked for), and
/// as delaunay2d otherwise.
DeviceTriangulation2d delaunay2d_device(const double* device_xy, std::int64_t n,
                                        const Delaunay2dOptions& opt = {});

/// A 2D Delaunay triangulation that follows its points (issue 47): kept on the executor between
/// calls, it takes new points and is brought up to date from where it was, not rebuilt. After any
/// sequence of calls it is exactly the triangulation delaunay2d gives for all the points so far:
/// the same arrays of triangles and neighbours,
/// degenerate input included, as the symbolic perturbation depends on the points alone
/// (docs/design-notes.md). Points keep the indices they were given: the first call's are
/// 0 .. n - 1, each insert's follow on. A point equal to an earlier one (given before or in the
/// same call) is not a vertex; duplicate_of names the earliest, as delaunay2d's does.
///
/// The state lives where the executor runs: device memory of opt.device on CUDA (the device is
/// fixed at construction; the work runs on opt.stream, which must outlive the object), host
/// memory on the CPU executor; both give the same arrays. Calls on one object must not overlap;
/// separate objects are independent. A call that throws leaves the object as it was. Today an
/// insertion still sorts all points again (the one global step left; the triangulation itself is
/// only repaired where the new points fall): docs/performance.md has what it costs.
class DynamicDelaunay2d {
 public:
  /// Triangulates n host points (x and y interleaved) on the executor opt picks. Throws as
  /// delaunay2d; Error(Unsupported) for Method::Digital or opt.into (results are read with
  /// triangulation()).
  DynamicDelaunay2d(const double* xy, std::int64_t n, const Delaunay2dOptions& opt = {});
  /// The same from points in executor memory (device memory, as delaunay2d_device takes them;
  /// host memory with opt.backend == Backend::Cpu).
  static DynamicDelaunay2d from_device(const double* device_xy, std::int64_t n,
                                       const Delaunay2dOptions& opt = {});
  DynamicDelaunay2d(DynamicDelaunay2d&&) noexcept;
  DynamicDelaunay2d& operator=(DynamicDelaunay2d&&) noexcept;
  ~DynamicDelaunay2d();

  /// Adds n points (host memory; insert_device: executor memory, as from_device), numbered
  /// num_points() on, and brings the triangulation up to date. Throws as delaunay2d for bad
  /// coordinates or too many points in all; the object is then unchanged.
  void insert(const double* xy, std::int64_t n);
  /// As insert, with the points in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void insert_device(const double* device_xy, std::int64_t n);
  /// New coordinates for every point (n == num_points(); host memory, or executor memory for
  /// move_device), and the triangulation brought up to date from the kept one: the vertices of
  /// triangles that turned over (checked exactly) are taken out, their holes filled at the new
  /// places, the rest flipped until Delaunay and those vertices inserted again (Delaunay2dStats'
  /// move_rounds, move_taken_out, move_reinserted). Where that would take out more than an
  /// eighth of the points, or where points came to coincide or to part, the triangulation is
  /// made afresh (Delaunay2dStats::move_rebuilt). Any displacement gives the right
  /// triangulation; only the time depends on how far the points moved. Throws as insert, and
  /// Error(InvalidArgument) for another count; the object is then unchanged.
  void move(const double* xy, std::int64_t n);
  /// As move, with the coordinates in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void move_device(const double* device_xy, std::int64_t n);
  /// Removes the points with the given indices (count of them, each once, none removed before;
  /// host memory, or executor memory for remove_device) and brings the triangulation up to
  /// date. A removed point is no vertex but keeps its index: duplicate_of reads kRemovedPoint
  /// there (an equal point given before or after is a vertex in its place). The holes are filled
  /// with the triangles of the triangulation of their own vertices that fit in them (the
  /// triangles of the kept one without a removed vertex stay); where that cannot be done (too few
  /// such vertices, all in one line) the points left are triangulated afresh
  /// (Delaunay2dStats::remove_rebuilt). Throws Error(InvalidArgument) for a bad index list, and as
  /// the constructor where the points left have no triangulation; the object is then unchanged.
  void remove(const std::int32_t* indices, std::int64_t count);
  /// As remove, with the indices in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void remove_device(const std::int32_t* device_indices, std::int64_t count);

  std::int64_t num_points() const;  ///< every index given so far, removed ones included
  /// Points removed so far.
  std::int64_t num_removed() const;
  /// Triangles of the current triangulation.
  std::int64_t num_triangles() const;
  /// Points equal to an earlier point (not vertices).
  std::int64_t num_duplicates() const;
  Backend backend() const;  ///< the executor holding the state
  /// Copies of the current triangulation: host arrays as delaunay2d returns them, or new arrays
  /// in executor memory as delaunay2d_device returns them (freed when their last pointer goes).
  Triangulation2d triangulation() const;
  /// The current triangulation in executor memory (copies of the kept arrays).
  DeviceTriangulation2d device_triangulation() const;
  /// Which triangles the last update (insert, move or remove) changed (changes.hpp): per triangle
  /// of the current results its index in the results before that update, or -1 where it is new, and
  /// the indices of those that went. Off by default: with track_changes(true), each update keeps
  /// the state it replaces until the next one (a second copy of the state, in the executor's
  /// memory); track_changes(false) frees it. changes() / device_changes() (executor memory, as
  /// device_triangulation's) throw Error(InvalidArgument) where no update ran with
  /// tracking on.
  void track_changes(bool on = true);
  /// Since track_changes: the triangles that were removed and those added, in host memory.
  SimplexChanges changes() const;
  /// As changes, in executor memory.
  DeviceSimplexChanges device_changes() const;
  /// Phases and counters of the last call that changed the points.
  const Delaunay2dStats& stats() const;

 private:
  struct Impl;
  explicit DynamicDelaunay2d(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Where voronoi2d and voronoi2d_device write the diagram, when given: the caller's arrays (host
/// memory for voronoi2d, device memory for voronoi2d_device; host memory where it runs on the
/// CPU executor), each at least as long as the result's array of that name: vertices 2
/// num_vertices, ridge_points, ridge_vertices and ridge_directions 2 num_ridges, cell_offsets
/// num_points + 1, cell_vertices num_cell_vertices, simplex_vertex the triangulation's
/// num_triangles. They are checked once the counts are known and before anything is written
/// (Error(InvalidArgument) naming the array and both lengths). An output written into a caller's
/// array is empty (null) in the result; the counts say how much of it was written.
struct Voronoi2dBuffers {
  OutBuffer<double> vertices;
  OutBuffer<std::int32_t> ridge_points, ridge_vertices;
  OutBuffer<double> ridge_directions;
  OutBuffer<std::int64_t> cell_offsets;
  OutBuffer<std::int32_t> cell_vertices, simplex_vertex;
};

/// How voronoi2d (from a triangulation) and voronoi2d_device run: the executor (RunOptions) and
/// where the arrays go.
struct Voronoi2dOptions : RunOptions {
  Voronoi2dBuffers into;  ///< optional
};

/// The Voronoi diagram dual to a Delaunay triangulation, in SciPy's `Voronoi` conventions.
/// Its vertices are the circumcentres of the triangles, one per circle: triangles whose points lie
/// on one circle exactly (the exact in-circle test) share a vertex, so no ridge has length zero
/// (as SciPy's: a 3x3 grid has 4 vertices). They are numbered in the order of their first
/// triangles.
struct Voronoi2d {
  std::int64_t num_points = 0, num_vertices = 0, num_ridges = 0, num_cell_vertices = 0;
  HostVector<double> vertices;  ///< circumcentres, x and y interleaved
  /// Ridges: the pair of input points each ridge separates, and its two Voronoi vertices
  /// (-1 for a ridge that goes to infinity).
  HostVector<std::int32_t> ridge_points;
  HostVector<std::int32_t> ridge_vertices;
  /// Cells: for each input point, its Voronoi vertices in counter-clockwise order; an unbounded
  /// cell starts with -1 (its two unbounded ridges leave from its first and last vertex).
  /// Duplicate points share the cell of the point they duplicate.
  HostVector<std::int64_t> cell_offsets;  ///< n + 1 offsets into cell_vertices
  HostVector<std::int32_t> cell_vertices;
  /// For an unbounded ridge, the outward direction (unit vector) of its ray, else (0, 0).
  HostVector<double> ridge_directions;
  /// Per triangle of the triangulation, its Voronoi vertex.
  HostVector<std::int32_t> simplex_vertex;
  /// Phase "voronoi" ("upload" before it where a host triangulation went up to CUDA; the
  /// one-call entry's phases are in its stats argument).
  RunStats stats;
};
/// The Voronoi diagram of the n points xy (x and y interleaved) from their triangulation tri
/// (delaunay2d's result for the same points, its arrays in the result), computed on the executor
/// opt picks: on the CPU executor from the caller's arrays where they are; on CUDA the points and
/// the triangulation go up once and only the diagram comes back (or goes into opt.into). The
/// arrays are the same on both. Throws Error(InvalidArgument) when tri does not belong to these
/// points or an array of opt.into is too short.
Voronoi2d voronoi2d(const double* xy, std::int64_t n, const Triangulation2d& tri,
                    const Voronoi2dOptions& opt = {});
/// The triangulation of host points and its Voronoi diagram in one call, both made on the
/// executor opt picks: on CUDA the points cross the bus once and only the results come back.
/// tri, when given, receives the triangulation (as delaunay2d returns it; opt.into is not used);
/// stats, when given, the phases and counters of both. A composition of two capabilities: for
/// the diagram in the caller's arrays, run delaunay2d (or delaunay2d_device) and voronoi2d (or
/// voronoi2d_device) with Voronoi2dOptions::into. Throws as delaunay2d.
Voronoi2d voronoi2d(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                    Triangulation2d* tri = nullptr, Delaunay2dStats* stats = nullptr);

/// The result of voronoi2d_device: arrays in device memory (host memory on the CPU executor).
struct DeviceVoronoi2d {
  std::int64_t num_points = 0, num_vertices = 0, num_ridges = 0, num_cell_vertices = 0;
  std::shared_ptr<double> vertices;              ///< 2 * num_vertices
  std::shared_ptr<std::int32_t> ridge_points;    ///< 2 * num_ridges
  std::shared_ptr<std::int32_t> ridge_vertices;  ///< 2 * num_ridges
  std::shared_ptr<double> ridge_directions;      ///< 2 * num_ridges
  std::shared_ptr<std::int64_t> cell_offsets;    ///< num_points + 1
  std::shared_ptr<std::int32_t> cell_vertices;   ///< num_cell_vertices
  std::shared_ptr<std::int32_t> simplex_vertex;  ///< tri.num_triangles
  Backend backend = Backend::Cuda;               ///< where the arrays are: Cuda = device memory
  RunStats stats;                                ///< phase "voronoi"
};
/// The same diagram for a triangulation left on the device (delaunay2d_device), computed there:
/// device_xy its n points (device memory; host memory where tri.backend is Backend::Cpu), on
/// opt.stream of opt.device; the arrays as Voronoi2d's, in device memory of the call's resource
/// (RunOptions::memory) (freed when the last copy of their pointer goes), or in the caller's
/// (opt.into). The executor is tri's (tri.backend): opt.backend is not read. Throws
/// Error(InvalidArgument) when tri's arrays went into the caller's arrays (into) or do not belong
/// to these points, or an array of opt.into is too short.
DeviceVoronoi2d voronoi2d_device(const double* device_xy, std::int64_t n,
                                 const DeviceTriangulation2d& tri,
                                 const Voronoi2dOptions& opt = {});

/// The furthest-site Delaunay triangulation (issue 49; SciPy's furthest_site=True): of the
/// extreme points of the hull, counter-clockwise triangles whose circumcircles each hold every
/// point (inside or on), decided by the exact in-circle test; points on one circle get one of the
/// valid triangulations, the same on every run. neighbors as delaunay2d's (-1 on the hull);
/// duplicate_of: -1 for a vertex, a copy's twin where that is a vertex, kRemovedPoint for the
/// other points (inside the hull: no vertex and no furthest-site cell; voronoi2d(xy, n, r) then
/// gives the furthest-site Voronoi diagram, whose rays point into the hull). Runs delaunay2d
/// with opt for the hull, the rest on the calling thread (O(h log h) expected for h hull
/// vertices). Throws as delaunay2d; Error(DegenerateInput) for fewer than 3 extreme points.
Triangulation2d furthest_site_delaunay2d(const double* xy, std::int64_t n,
                                         const Delaunay2dOptions& opt = {});

/// The extreme points of a 2D triangulation's point set in counter-clockwise order, read from its
/// boundary (neighbors -1): points on a hull edge between its ends are left out (exact
/// orientation), as only extreme points are hull vertices. triangles / neighbors: 3 per triangle,
/// counter-clockwise, as delaunay2d returns them. Throws Error(InvalidArgument) when the boundary
/// is not one cycle.
HostVector<std::int32_t> convex_hull2d_vertices(const double* xy, std::int64_t n,
                                                const std::int32_t* triangles,
                                                const std::int32_t* neighbors,
                                                std::int64_t num_triangles);

/// Voronoi cells clipped to a box [xmin, xmax] x [ymin, ymax] that contains every input point:
/// each cell as a closed counter-clockwise polygon (x, y interleaved).
struct ClippedCells {
  HostVector<std::int64_t> offsets;  ///< n + 1 offsets (in points) into xy
  HostVector<double> xy;
};
/// Every point's Voronoi cell clipped to the box [x0, x1] x [y0, y1], as polygons.
ClippedCells clip_voronoi_cells(const double* xy, std::int64_t n, const Triangulation2d& tri,
                                const Voronoi2d& vor, double xmin, double ymin, double xmax,
                                double ymax);

}  // namespace gpugeom
