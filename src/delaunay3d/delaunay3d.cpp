// Public entry of the 3D Delaunay module: checks sizes and picks the backend.
#include "gpugeom/delaunay3d.hpp"

#include <string>

#include "delaunay3d/del3d_backend.hpp"

namespace gpugeom {

namespace {
// Up to about 7.5 tetrahedra per point with the dead and infinite slots must stay below the
// 2^29 slots the neighbour encoding addresses.
constexpr std::int64_t kMaxPoints = std::int64_t(1) << 26;

void check_count(std::int64_t n) {
  if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
  if (n > kMaxPoints)
    throw Error(ErrorCode::InvalidInput, "too many points (" + std::to_string(n) + "): at most " +
                                             std::to_string(kMaxPoints) +
                                             " per 3D triangulation in this version");
  if (n < 4)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 4 points (" + std::to_string(n) +
                    "): a 3D Delaunay triangulation needs 4 points not on one plane");
}
}  // namespace

Triangulation3d delaunay3d(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt) {
  check_count(n);
  Triangulation3d r;
  const Backend b = resolve_backend(opt.backend, opt.device);
  r.stats.backend = b;
  del3d::Output out;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda)
    del3d::cuda_impl::triangulate(xyz, n, opt, out, r.stats);
  else
    del3d::cpu_impl::triangulate(xyz, n, opt, out, r.stats);
#else
  del3d::cpu_impl::triangulate(xyz, n, opt, out, r.stats);
#endif
  r.tetrahedra = std::move(out.tetrahedra);
  r.neighbors = std::move(out.neighbors);
  r.duplicate_of = std::move(out.duplicate_of);
  r.num_duplicates = out.num_duplicates;
  r.hull_facets = std::move(out.hull_facets);
  r.vertex_to_simplex = std::move(out.vertex_to_simplex);
  return r;
}

DeviceTriangulation3d delaunay3d_device(const double* device_xyz, std::int64_t n,
                                        const RunOptions& run) {
  check_count(n);
  DeviceTriangulation3d r;
  r.stats.backend = resolve_backend(Backend::Cuda, run.device);  // throws where there is none
  r.num_points = n;
#ifdef GPUGEOM_HAVE_CUDA
  del3d::DeviceOutput out;
  del3d::cuda_impl::triangulate_device(device_xyz, n, run, out, r.stats);
  r.num_tetrahedra = out.num_tetrahedra;
  r.num_duplicates = out.num_duplicates;
  r.tetrahedra = std::move(out.tetrahedra);
  r.neighbors = std::move(out.neighbors);
  r.duplicate_of = std::move(out.duplicate_of);
#else
  (void)device_xyz;
  (void)run;
#endif
  return r;
}

Triangulation3d delaunay3d(const std::vector<Point3>& pts, const Delaunay3dOptions& opt) {
  return delaunay3d(pts.empty() ? nullptr : &pts.data()->x, std::int64_t(pts.size()), opt);
}

}  // namespace gpugeom
