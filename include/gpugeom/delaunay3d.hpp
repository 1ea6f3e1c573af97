/// @file
/// Exact 3D Delaunay tetrahedralisation (thesis 5.3: batch insertion with parallel 2-3 / 3-2
/// flipping on the executor, then adaptive star splaying where flipping got stuck).
///
/// Exactness: every decision is an exact predicate with simulation of simplicity, so cospherical
/// and coplanar subsets get one consistent answer; the result is a Delaunay tetrahedralisation
/// of the distinct input points (every empty-sphere test is exact), every distinct point is a
/// vertex, and every tetrahedron has positive volume (the flat tetrahedra the perturbation may
/// put on the hull, over points exactly in a hull facet's plane, are removed, so such a facet's
/// plane may be covered by several hull facets). The perturbation depends on each point's
/// coordinates alone (lifts in decreasing lexicographic order, as CGAL's symbolic perturbation,
/// so the tetrahedra equal CGAL's on cospherical input): the result depends on the point set
/// only, and a tetrahedron stays when points join whose spheres it does not contain.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"
#include "gpugeom/changes.hpp"
#include "gpugeom/removed.hpp"

namespace gpugeom {

/// Where a run is (see Delaunay3dOptions::progress).
struct Delaunay3dProgress {
  const char* phase = "";  ///< "insert_flip" (after each batch), "splay", "output" (as they begin)
  std::int64_t inserted = 0;  ///< distinct points in the tetrahedralisation so far
  std::int64_t total = 0;     ///< distinct points
  std::int64_t batch = 0;     ///< insertion batches so far
};

/// Arrays the caller provides for the results (OutBuffer, common.hpp; SciPy's `out=` pattern):
/// host memory for delaunay3d, device memory for delaunay3d_device (host memory where it runs on
/// the CPU executor). tetrahedra and neighbors must hold at least 4 times the tetrahedron count,
/// hull_facets at least 3 times the hull facet count (both depend on the result, and no bound
/// linear in n exists in 3D: give what you expect and be told what was needed),
/// duplicate_of and vertex_to_simplex at least n. They are checked once the counts are known and
/// before anything is written (Error(InvalidArgument) naming the array and both lengths). An
/// output written into a caller's array is empty (null) in the result.
struct Triangulation3dBuffers {
  OutBuffer<std::int32_t> tetrahedra, neighbors, duplicate_of, vertex_to_simplex, hull_facets;
};

/// How delaunay3d and delaunay3d_device run (RunOptions), the method, progress and the caller's
/// output arrays.
struct Delaunay3dOptions : RunOptions {
  Triangulation3dBuffers into;  ///< optional
  /// Called on the calling thread after each insertion batch and as phase 2 and the output
  /// begin (a few dozen calls). An exception it throws ends the run and reaches the caller
  /// (a way to cancel), with nothing leaked.
  std::function<void(const Delaunay3dProgress&)> progress;
  /// The method (common.hpp): the result does not depend on it. Method::Digital is the thesis'
  /// DigiDel3D (4.5.2): a digital Voronoi diagram of the points on a grid (3D PBA), a working
  /// set of neighbours for every point from the grid corners where its cell meets others (read
  /// as a perturbed grid), a convex star for every point from its working set (beneath-beyond),
  /// then star splaying until every star agrees with its neighbours' (Shewchuk), all on the
  /// executor. Adds phases "digital_*" (grid, pba, working_sets, stars, splay, tetrahedra; the
  /// splay's parts as "digital_splay.check", ".sort", ".take") and the digital counters of
  /// Delaunay3dStats (digital_fallback 1 where stars grew too large to splay on the executor,
  /// as on the hull planes of integer grids: the incremental method then ran).
  Method method = Method::Incremental;
  /// Method::Digital: the grid's side along the points' longest extent (16..1024; 0 chooses
  /// it from the point count, about 32 grid cells a point, and doubles it once where more than
  /// a tenth of the points share a cell: Delaunay3dStats::digital_grid_refined).
  std::int64_t grid = 0;
};

/// Statistics of a 3D Delaunay tetrahedralisation: RunStats (phases "prepare", "insert_flip",
/// "find_failed", "splay" (phase 2, star splaying on the executor), "drop_flats", "output";
/// Method::Digital's "digital_*"; DynamicDelaunay3d's updates their own and "total") and the
/// counters, 0 where their step did not run. Every array, and phase 1's counters, are the same
/// run after run, on any thread count and on both executors.
struct Delaunay3dStats : RunStats {
  /// The points given, those distinct, and those equal to an earlier one.
  std::int64_t points = 0, distinct_points = 0, duplicates = 0;
  /// Phase 1: insertion batches, flip rounds, 2-3 and 3-2 flips, and the tests that found a
  /// face not flippable.
  std::int64_t batches = 0, flip_rounds = 0, flips23 = 0, flips32 = 0, unflippable_tests = 0;
  /// The CPU executor's own schedule: points inserted one by one (each by its cavity), and of
  /// them those a thread left to the end because their walk or cavity reached another thread's
  /// part of the curve (0 where the batches ran; phase 2 then has nothing to repair).
  std::int64_t cavity_insertions = 0, deferred_points = 0;
  /// Faces found not locally Delaunay after phase 1, and their vertices (phase 2's stars).
  std::int64_t failed_faces = 0, failed_vertices = 0;
  /// Phase 2 (star splaying): stars built and changed, insertions into stars, rounds, and the
  /// tetrahedra it removed and added.
  std::int64_t stars_built = 0, stars_changed = 0, star_insertions = 0, splay_rounds = 0,
               splay_removed = 0, splay_added = 0;
  /// Flat tetrahedra removed from the hull.
  std::int64_t flat_tetrahedra = 0;
  /// Phase 1's arrays at their largest, in bytes, and the tetrahedron store's slots used and
  /// allocated.
  std::int64_t device_bytes_phase1 = 0, slots_used = 0, slots_capacity = 0;
  /// Phase 1's sizing: halts for room, the longest flip list, the most flip records in an
  /// epoch, the most free slots, the most splits in a batch, the lists', log's and ring's
  /// capacities, chunks of rounds launched, team launches, and batches whose short flip list
  /// went on in the next batch's rounds.
  std::int64_t halts = 0, max_list = 0, max_epoch_records = 0, max_free_slots = 0, max_splits = 0,
               list_capacity = 0, log_capacity = 0, ring_capacity = 0, round_chunks = 0,
               team_launches = 0, carried_batches = 0;
  /// Times in microseconds: phase 1's choosing and splitting, flip rounds as kernels and in one
  /// block; phase 2's building stars, splaying rounds, checks, patch and takes.
  std::int64_t us_choose_split = 0, us_rounds_wide = 0, us_rounds_team = 0, us_splay_build = 0,
               us_splay_rounds = 0, us_splay_check = 0, us_splay_patch = 0, us_splay_take = 0;
  /// The start's point location by walks: steps, scans, and the longest walk.
  std::int64_t start_walk_steps = 0, start_walk_scans = 0, start_walk_longest = 0;
  /// Method::Digital: the grid's side (and 1 where it was doubled because more than a tenth of
  /// the points shared a cell), points on the grid's box, the points with a cell of their own
  /// (sites) and those the sketch missed.
  std::int64_t digital_grid = 0, digital_grid_refined = 0, digital_points_on_box = 0, sites = 0,
               sketch_missing = 0;
  /// Method::Digital: the working sets' neighbour pairs, their points, and the sets augmented.
  std::int64_t digital_working_pairs = 0, digital_working_set_points = 0,
               digital_working_sets_augmented = 0;
  /// Method::Digital: the stars' slots made at first and in all, passes that gave new runs to
  /// stars that outgrew theirs, insertions and requests, splaying rounds (and rounds by
  /// vertex), and checks run again for requests past the round's buffer.
  std::int64_t digital_star_slots_created = 0, digital_star_slots = 0, digital_star_growths = 0,
               digital_star_insertions = 0, digital_star_requests = 0, digital_splay_rounds = 0,
               digital_splay_vertex_rounds = 0, digital_splay_request_spills = 0;
  /// Method::Digital: 1 where stars grew too large to splay on the executor (as on the hull
  /// planes of integer grids): the incremental method then ran, and its phases follow.
  std::int64_t digital_fallback = 0;
  /// DynamicDelaunay3d: points inserted; points removed, the holes' vertices and tetrahedra,
  /// and whether the removal made the tetrahedralisation afresh; a move's rounds, the vertices
  /// it took out and put back, the times its store grew, and whether it made the
  /// tetrahedralisation afresh.
  std::int64_t inserted_points = 0, removed_points = 0, hole_vertices = 0, hole_tetrahedra = 0,
               remove_rebuilt = 0, move_rounds = 0, move_taken_out = 0, move_reinserted = 0,
               move_grown = 0, move_rebuilt = 0;
  /// delaunay{2,3}d_devices (multi_gpu.hpp): the blocks, those that took a second round, and
  /// the local points of their last rounds (all blocks together).
  std::int64_t blocks = 0, blocks_second_round = 0, block_local_points = 0;

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// The result of delaunay3d: tetrahedra, neighbours, duplicates and hull facets, in host memory.
struct Triangulation3d {
  /// Positively oriented tetrahedra (orient3d > 0), 4 input-point indices each. The incremental
  /// method gives them in one order, whatever schedule built them (the GPU's batches, the CPU
  /// executor's insertions one by one, any thread count): each starts at its vertex first on
  /// the points' space-filling curve, the least of the other three second (an even permutation,
  /// so the orientation is kept), and the tetrahedra follow their first three vertices in that
  /// curve order. (Method::Digital and DynamicDelaunay3d give the same tetrahedra in orders of
  /// their own.)
  HostVector<std::int32_t> tetrahedra;
  /// neighbors[4*i + k]: the tetrahedron opposite vertex k of tetrahedron i, -1 on the hull
  /// (SciPy's convention).
  HostVector<std::int32_t> neighbors;
  /// One entry per input point: -1 when the point is a vertex, else the index of the earlier
  /// point with the same coordinates, which is the one used.
  HostVector<std::int32_t> duplicate_of;
  std::int64_t num_duplicates = 0;
  /// The hull facets: 3 input indices each, counter-clockwise seen from outside.
  HostVector<std::int32_t> hull_facets;
  /// One entry per input point: a tetrahedron having it as a vertex (a duplicate: that of the
  /// point it duplicates).
  HostVector<std::int32_t> vertex_to_simplex;
  Delaunay3dStats stats;
  /// Tetrahedra and hull facets written (also where they went into the caller's arrays).
  std::int64_t num_tetrahedra = 0, num_hull_facets = 0;
};

/// xyz: n points, x, y and z interleaved. Throws Error(InvalidInput) for NaN/Inf or coordinates
/// outside the exactly representable range, or more than 1.4·10^8 points (the store's 32-bit
/// neighbour encoding addresses 2^30 - 1 tetrahedra, about 7.3 a point with the dead and
/// infinite ones); Error(OutOfMemory), before any launch, where the device's free memory is
/// below what the points certainly need (the bytes needed and free in the message);
/// Error(DegenerateInput)
/// naming the case for fewer than 4 distinct points or all points on one line or one plane.
Triangulation3d delaunay3d(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt = {});
/// The same for a vector of points.
Triangulation3d delaunay3d(const std::vector<Point3>& pts, const Delaunay3dOptions& opt = {});

/// The result of delaunay3d_device: arrays in device memory (host memory on the CPU executor).
struct DeviceTriangulation3d {
  std::int64_t num_points = 0, num_tetrahedra = 0, num_duplicates = 0, num_hull_facets = 0;
  std::shared_ptr<std::int32_t> tetrahedra;         ///< 4 * num_tetrahedra, as Triangulation3d's
  std::shared_ptr<std::int32_t> neighbors;          ///< 4 * num_tetrahedra
  std::shared_ptr<std::int32_t> duplicate_of;       ///< num_points
  std::shared_ptr<std::int32_t> vertex_to_simplex;  ///< num_points
  std::shared_ptr<std::int32_t> hull_facets;        ///< 3 * num_hull_facets
  Backend backend = Backend::Cuda;  ///< where the arrays are: Cuda = device memory, Cpu = host
  Delaunay3dStats stats;
};
/// The same tetrahedralisation with the points already on the GPU and the result left there:
/// device_xyz is device memory holding n points, x, y and z interleaved, on opt.device. The work
/// runs on opt.stream (see RunOptions), so the points must be ready in that stream's order; the
/// call returns once the result is ready; both phases run on the device. The arrays are the
/// device memory of the call's resource (RunOptions::memory), freed when the last copy of their
/// pointer goes (they can be wrapped without copying, e.g. by CuPy), or the caller's (opt.into).
/// With opt.backend == Backend::Cpu the CPU executor runs it on host memory (the same result);
/// otherwise CUDA runs it, whatever GPUGEOM_BACKEND says. Throws Error(Unsupported) where no CUDA
/// device can be used (and the CPU was not asked for), and as delaunay3d otherwise.
DeviceTriangulation3d delaunay3d_device(const double* device_xyz, std::int64_t n,
                                        const Delaunay3dOptions& opt = {});

/// A 3D Delaunay tetrahedralisation that follows its points (issue 47): kept on the executor
/// between calls, it takes new points and is brought up to date from where it was, not rebuilt.
/// After any sequence of calls it is exactly the tetrahedralisation delaunay3d gives for all the
/// points so far: the same tetrahedra with the same neighbours and hull facets (their order in
/// the arrays may differ), degenerate input included, as the symbolic perturbation depends on the
/// points alone (docs/design-notes.md). Points keep the indices they were given: the first
/// call's are 0 .. n - 1, each insert's follow on. A point equal to an earlier one (given before
/// or in the same call) is not a vertex; duplicate_of names the earliest, as delaunay3d's does.
///
/// The state lives where the executor runs: device memory of opt.device on CUDA (the device is
/// fixed at construction; the work runs on opt.stream, which must outlive the object), host
/// memory on the CPU executor. Calls on one object must not overlap; separate objects are
/// independent. A call that throws leaves the object as it was (a moved-from object may only be
/// assigned or destroyed). Today an insertion still sorts all points again (the one global step
/// left; the tetrahedralisation itself is only repaired where the new points fall):
/// docs/performance.md has what it costs.
class DynamicDelaunay3d {
 public:
  /// Tetrahedralises n host points (x, y and z interleaved) on the executor opt picks. Throws as
  /// delaunay3d; Error(Unsupported) for Method::Digital or opt.into (results are read with
  /// tetrahedralisation()). opt.progress is called during every later insertion too.
  DynamicDelaunay3d(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt = {});
  /// The same from points in executor memory (device memory, as delaunay3d_device takes them;
  /// host memory with opt.backend == Backend::Cpu).
  static DynamicDelaunay3d from_device(const double* device_xyz, std::int64_t n,
                                       const Delaunay3dOptions& opt = {});
  DynamicDelaunay3d(DynamicDelaunay3d&&) noexcept;
  DynamicDelaunay3d& operator=(DynamicDelaunay3d&&) noexcept;
  ~DynamicDelaunay3d();

  /// Adds n points (host memory; insert_device: executor memory, as from_device), numbered
  /// num_points() on, and brings the tetrahedralisation up to date. Throws as delaunay3d for bad
  /// coordinates or too many points in all; the object is then unchanged.
  void insert(const double* xyz, std::int64_t n);
  /// As insert, with the points in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void insert_device(const double* device_xyz, std::int64_t n);
  /// New coordinates for every point (n == num_points(); host memory, or executor memory for
  /// move_device), and the tetrahedralisation brought up to date from the kept one: the vertices
  /// of tetrahedra that turned over (checked exactly) are taken out, their holes filled at the
  /// new places, the rest flipped (phase 1's rounds) and star-splayed until Delaunay, and those
  /// vertices inserted again (Delaunay3dStats' move_rounds, move_taken_out,
  /// move_reinserted). Where that would take out more than an eighth of the points, or where
  /// points came to coincide or to part, it is made afresh (Delaunay3dStats::move_rebuilt). Any
  /// displacement gives the right tetrahedralisation; only the time depends on how far the
  /// points moved. Throws as insert, and Error(InvalidArgument) for another count; the object is
  /// then unchanged.
  void move(const double* xyz, std::int64_t n);
  /// As move, with the coordinates in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void move_device(const double* device_xyz, std::int64_t n);
  /// Removes the points with the given indices (count of them, each once, none removed before;
  /// host memory, or executor memory for remove_device) and brings the tetrahedralisation up to
  /// date. A removed point is no vertex but keeps its index: duplicate_of reads kRemovedPoint
  /// there (an equal point given before or after is a vertex in its place). The holes are filled
  /// with the tetrahedra of the tetrahedralisation of their own vertices that fit in them (the
  /// tetrahedra of the kept one without a removed vertex stay); where that cannot be done (too few
  /// such vertices, all in one plane) the points left are tetrahedralised afresh
  /// (Delaunay3dStats::remove_rebuilt). vertex_to_simplex is -1 at removed points. Throws
  /// Error(InvalidArgument) for a bad index list, and as the constructor where the points left have
  /// no tetrahedralisation; the object is then unchanged.
  void remove(const std::int32_t* indices, std::int64_t count);
  /// As remove, with the indices in executor memory (device memory on CUDA, host memory with
  /// Backend::Cpu).
  void remove_device(const std::int32_t* device_indices, std::int64_t count);

  std::int64_t num_points() const;  ///< every index given so far, removed ones included
  /// Points removed so far.
  std::int64_t num_removed() const;
  /// Tetrahedra of the current tetrahedralisation.
  std::int64_t num_tetrahedra() const;
  /// Points equal to an earlier point (not vertices).
  std::int64_t num_duplicates() const;
  Backend backend() const;  ///< the executor holding the state
  /// Copies of the current tetrahedralisation: host arrays as delaunay3d returns them, or new
  /// arrays in executor memory as delaunay3d_device returns them.
  Triangulation3d tetrahedralisation() const;
  /// The current tetrahedralisation in executor memory (copies of the kept arrays).
  DeviceTriangulation3d device_tetrahedralisation() const;
  /// Which tetrahedra the last update (insert, move or remove) changed (changes.hpp): per
  /// tetrahedra of the current results its index in the results before that update, or -1 where it
  /// is new, and the indices of those that went. Off by default: with track_changes(true), each
  /// update keeps the state it replaces until the next one (a second copy of the state, in the
  /// executor's memory); track_changes(false) frees it. changes() / device_changes() (executor
  /// memory, as device_tetrahedralisation's) throw Error(InvalidArgument) where no update ran with
  /// tracking on.
  void track_changes(bool on = true);
  /// Since track_changes: the tetrahedra that were removed and those added, in host memory.
  SimplexChanges changes() const;
  /// As changes, in executor memory.
  DeviceSimplexChanges device_changes() const;
  /// Phases and counters of the last call that changed the points.
  const Delaunay3dStats& stats() const;

 private:
  struct Impl;
  explicit DynamicDelaunay3d(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace gpugeom
