// What the public 3D Delaunay entry gets back from a backend (internal).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "exec/dynamic_state.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"
#include "gpugeom/delaunay3d.hpp"

namespace gpugeom::del3d {

using ProgressFn = std::function<void(const Delaunay3dProgress&)>;

struct Output {
  HostVector<std::int32_t> tetrahedra;    // 4 per tetrahedron, input indices, positive
  HostVector<std::int32_t> neighbors;     // 4 per tetrahedron, -1 on the hull
  HostVector<std::int32_t> duplicate_of;  // n entries
  std::int64_t num_duplicates = 0;
  HostVector<std::int32_t> hull_facets;        // 3 per hull facet, outward, input indices
  HostVector<std::int32_t> vertex_to_simplex;  // n entries (a copy takes its original's)
  std::int64_t num_tetrahedra = 0, num_hull_facets = 0;
};

// The result of the device entry: the library's arrays (executor memory; null where the caller's
// arrays, opt.into, took the output).
struct DeviceOutput {
  std::shared_ptr<std::int32_t> tetrahedra, neighbors, duplicate_of, vertex_to_simplex, hull_facets;
  std::int64_t num_tetrahedra = 0, num_duplicates = 0, num_hull_facets = 0;
};

// triangulate: xyz holds n points on the host; triangulate_device: n points in the executor's
// memory. Both validate the coordinates on the executor (throw Error) and honour opt.into.
// Refuses counts no tetrahedralisation can be made of, or past the store's reach (Error).
void check_count(std::int64_t n);
// The backends' outputs as the public results.
Triangulation3d to_public(Output&& out);
DeviceTriangulation3d to_public(DeviceOutput&& out, std::int64_t n, Backend b);

// DynamicDelaunay3d's state on one executor (impl/dynamic.inl).
using Kept = detail::KeptState<Output, DeviceOutput>;

namespace cpu_impl {
std::unique_ptr<Kept> make_kept(const Delaunay3dOptions& opt);
void triangulate(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt, Output& out,
                 Stats& stats);
void triangulate_device(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                        DeviceOutput& out, Stats& stats);
}  // namespace cpu_impl
namespace cuda_impl {
std::unique_ptr<Kept> make_kept(const Delaunay3dOptions& opt);
void triangulate(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt, Output& out,
                 Stats& stats);
void triangulate_device(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                        DeviceOutput& out, Stats& stats);
}  // namespace cuda_impl

}  // namespace gpugeom::del3d
