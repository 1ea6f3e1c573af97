// The Voronoi diagram of 3D points from their Delaunay tetrahedralisation (issue 49): the entries
// check what they are given and run the executor's algorithm (impl/voronoi.inl).
#include <cstdint>
#include <string>
#include <utility>

#include "base/stats_fields.hpp"
#include "delaunay3d/del3d_backend.hpp"
#include "delaunay3d/voronoi3d_backend.hpp"
#include "exec/device_voronoi.hpp"
#include "exec/dispatch.hpp"
#include "gpugeom/voronoi3d.hpp"

namespace gpugeom {

#define GG_VORONOI3D_COUNTERS(X) X(voronoi_vertices) X(voronoi_ridges)
GG_COUNTER_MAP(Voronoi3dStats, GG_VORONOI3D_COUNTERS);
#undef GG_VORONOI3D_COUNTERS

// The host entry: the executor's algorithm over the caller's arrays (the CPU executor), or over
// their one upload; the same arrays on both, bit for bit.
Voronoi3d voronoi3d(const double* xyz, std::int64_t n, const Triangulation3d& tri,
                    const Voronoi3dOptions& opt) {
  const std::int64_t nt = tri.num_tetrahedra;
  if (tri.tetrahedra.size() != std::size_t(4 * nt) || tri.neighbors.size() != std::size_t(4 * nt))
    throw Error(ErrorCode::InvalidArgument,
                "the tetrahedralisation's tetrahedra or neighbours are not in its result (were "
                "they written into the caller's arrays, Delaunay3dOptions::into?): the Voronoi "
                "diagram needs them there");
  if (std::int64_t(tri.duplicate_of.size()) != n)
    throw Error(ErrorCode::InvalidArgument,
                "the tetrahedralisation does not belong to these " + std::to_string(n) + " points");
  const Backend b = resolve_backend(opt.backend, opt.device);
  Voronoi3d v;
  v.stats.backend = b;
  GG_TABLE(b, del3d, voronoi_entries)
      .of_host(xyz, n, tri.tetrahedra.data(), tri.neighbors.data(), tri.duplicate_of.data(), nt,
               opt, v);
  return v;
}

Voronoi3d voronoi3d(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                    Triangulation3d* tri) {
  const Backend b = resolve_backend(opt.backend, opt.device);
  const auto& on = GG_TABLE(b, del3d, voronoi_entries);
  if (on.from_host && opt.method == Method::Incremental) {
    del3d::check_count(n);
    Voronoi3d v;
    v.stats.backend = b;
    on.from_host(xyz, n, opt, v, tri);
    return v;
  }
  Delaunay3dOptions o = opt;
  o.into = {};
  Triangulation3d t = delaunay3d(xyz, n, o);
  Voronoi3d v = voronoi3d(xyz, n, t, options_from<Voronoi3dOptions>(opt));
  if (tri) *tri = std::move(t);
  return v;
}

DeviceVoronoi3d voronoi3d_device(const double* device_xyz, std::int64_t n,
                                 const DeviceTriangulation3d& tri, const Voronoi3dOptions& opt) {
  return detail::run_device_voronoi<DeviceVoronoi3d>(
      GG_TABLE(tri.backend, del3d, voronoi_entries), device_xyz, n, tri, tri.tetrahedra.get(),
      tri.num_tetrahedra, opt, "tetrahedralisation", "tetrahedra", "Delaunay3dOptions");
}

}  // namespace gpugeom
