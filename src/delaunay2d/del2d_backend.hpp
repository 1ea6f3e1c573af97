// What the public 2D Delaunay entry gets back from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "exec/dynamic_state.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::del2d {

struct Output {
  HostVector<std::int32_t> triangles;     // 3 per triangle, input indices, counter-clockwise
  HostVector<std::int32_t> neighbors;     // 3 per triangle, -1 on the hull
  HostVector<std::int32_t> duplicate_of;  // n entries
  std::int64_t num_duplicates = 0;
  std::int64_t num_triangles = 0;
};

// The result of the device entry: the library's arrays (executor memory; null where the caller's
// arrays, opt.into, took the output).
struct DeviceOutput {
  std::shared_ptr<std::int32_t> triangles, neighbors, duplicate_of;
  std::int64_t num_triangles = 0, num_duplicates = 0;
};

// The Voronoi diagram of the device entry, in the executor's memory.
struct DeviceVoronoiOutput {
  std::shared_ptr<double> vertices, ridge_directions;
  std::shared_ptr<std::int32_t> ridge_points, ridge_vertices, cell_vertices, simplex_vertex;
  std::shared_ptr<std::int64_t> cell_offsets;
  std::int64_t num_vertices = 0, num_ridges = 0, num_cell_vertices = 0;
};

// triangulate: xy holds n points on the host; triangulate_device: n points in the executor's
// memory. Both validate the coordinates on the executor (throw Error) and honour opt.into.
// triangulate_from: the same from a start (the digital method's sketch, issue 20): nstart
// counter-clockwise triangles of input indices (3 each, host memory) that cover the convex hull
// of their vertices, each directed edge once; the other points are inserted into it and the
// whole is flipped until Delaunay by the same batches and rounds. twin (host, 3 nstart, or
// null: found by sorting the edges): per half-edge 3t + k (vertex k to k + 1) its reverse, -1 on
// the hull. hint (host, n entries, or null): for each point not in the start, a start vertex near
// it where its walk begins (-1: anywhere). The result equals triangulate's. Refuses counts no
// triangulation can be made of (Error, as the public entries say).
// triangulate_digital: Method::Digital from host points (digital/digital.hpp says what it
// reports); the points go to the executor once and every phase's arrays stay there.
void check_count(std::int64_t n);
// Tests: the first triangle slot's number (clamped so that the last slot is 2^30 - 1), so that
// small inputs run through the top of the wide slot encoding. Not thread-safe; 0 restores.
void set_slot_base_for_testing(std::int64_t base);
std::int64_t slot_base_for_testing();
// Tests: the flip rounds' capacities, in place of those sized from the point count (0 keeps
// that one): points one batch inserts, flip-log records, exact-list entries. Small values
// send small inputs through the paths large inputs take past each capacity. Not thread-safe.
struct Capacities {
  std::int64_t batch_points = 0, log_records = 0, exact_entries = 0;
};
void set_capacities_for_testing(const Capacities& c);
Capacities capacities_for_testing();

// DynamicDelaunay2d's state on one executor (impl/dynamic.inl).
using Kept = detail::KeptState<Output, DeviceOutput>;

namespace cpu_impl {
std::unique_ptr<Kept> make_kept(const RunOptions& run);
void triangulate(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Output& out,
                 Stats& stats);
void triangulate_digital(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                         Output& out, Stats& stats);
void triangulate_from(const double* xy, std::int64_t n, const std::int32_t* start,
                      std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                      const Delaunay2dOptions& opt, Output& out, Stats& stats);
void triangulate_device(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                        DeviceOutput& out, Stats& stats);
// The Voronoi diagram of nt triangles (tri, nb; dup may be null: no duplicates) of n points xy,
// all in the executor's memory; into `host` where given (the host entry), else left in `out`.
void voronoi(const double* xy, std::int64_t n, const std::int32_t* tri, const std::int32_t* nb,
             const std::int32_t* dup, std::int64_t nt, const RunOptions& run,
             DeviceVoronoiOutput& out, Stats& stats, Voronoi2d* host = nullptr);
}  // namespace cpu_impl
namespace cuda_impl {
std::unique_ptr<Kept> make_kept(const RunOptions& run);
void triangulate(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Output& out,
                 Stats& stats);
void triangulate_digital(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                         Output& out, Stats& stats);
void triangulate_from(const double* xy, std::int64_t n, const std::int32_t* start,
                      std::int64_t nstart, const std::int32_t* twin, const std::int32_t* hint,
                      const Delaunay2dOptions& opt, Output& out, Stats& stats);
void triangulate_device(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                        DeviceOutput& out, Stats& stats);
void voronoi(const double* xy, std::int64_t n, const std::int32_t* tri, const std::int32_t* nb,
             const std::int32_t* dup, std::int64_t nt, const RunOptions& run,
             DeviceVoronoiOutput& out, Stats& stats, Voronoi2d* host = nullptr);
void voronoi_from_host(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Voronoi2d& v,
                       Triangulation2d* tri, Stats& stats);
}  // namespace cuda_impl

}  // namespace gpugeom::del2d
