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
// triangulate_digital: Method::Digital from host points (digital/digital.hpp says what it
// reports); the points go to the executor once and every phase's arrays stay there. It starts
// from a triangulation (run_from_start in impl/triangulate.inl; src/testing enters that from
// host arrays).
// check_count refuses counts no triangulation can be made of (Error, as the public entries say).
void check_count(std::int64_t n);
// DynamicDelaunay2d's state on one executor (impl/dynamic.inl).
using Kept = detail::KeptState<Output, DeviceOutput>;

namespace cpu_impl {
std::unique_ptr<Kept> make_kept(const RunOptions& run);
void triangulate(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Output& out,
                 Stats& stats);
void triangulate_digital(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                         Output& out, Stats& stats);
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
void triangulate_device(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                        DeviceOutput& out, Stats& stats);
void voronoi(const double* xy, std::int64_t n, const std::int32_t* tri, const std::int32_t* nb,
             const std::int32_t* dup, std::int64_t nt, const RunOptions& run,
             DeviceVoronoiOutput& out, Stats& stats, Voronoi2d* host = nullptr);
void voronoi_from_host(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Voronoi2d& v,
                       Triangulation2d* tri, Stats& stats);
}  // namespace cuda_impl

}  // namespace gpugeom::del2d
