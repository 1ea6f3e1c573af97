// Public entry of the 2D Delaunay module: checks sizes, picks the backend, packs the result.
#include "gpugeom/delaunay2d.hpp"

#include <string>

#include "delaunay2d/del2d_backend.hpp"

namespace gpugeom {

namespace {
// Slots of the extended triangulation (2m - 2) times 4 must fit the int32 neighbour encoding.
constexpr std::int64_t kMaxPoints = std::int64_t(1) << 28;

void check_count(std::int64_t n) {
  if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
  if (n > kMaxPoints)
    throw Error(ErrorCode::InvalidInput, "too many points (" + std::to_string(n) + "): at most " +
                                             std::to_string(kMaxPoints) + " per triangulation");
  if (n < 3)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 3 points (" + std::to_string(n) +
                    "): a triangulation needs at least 3 points not on one line");
}
}  // namespace

Triangulation2d delaunay2d(const double* xy, std::int64_t n, const Delaunay2dOptions& opt) {
  check_count(n);
  Triangulation2d r;
  const Backend b = resolve_backend(opt.backend, opt.device);
  r.stats.backend = b;
  del2d::Output out;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda)
    del2d::cuda_impl::triangulate(xy, n, opt, out, r.stats);
  else
    del2d::cpu_impl::triangulate(xy, n, opt, out, r.stats);
#else
  del2d::cpu_impl::triangulate(xy, n, opt, out, r.stats);
#endif
  r.triangles = std::move(out.triangles);
  r.neighbors = std::move(out.neighbors);
  r.duplicate_of = std::move(out.duplicate_of);
  r.num_duplicates = out.num_duplicates;
  return r;
}

DeviceTriangulation2d delaunay2d_device(const double* device_xy, std::int64_t n,
                                        const RunOptions& run) {
  check_count(n);
  DeviceTriangulation2d r;
  r.stats.backend = resolve_backend(Backend::Cuda, run.device);  // throws where there is none
  r.num_points = n;
#ifdef GPUGEOM_HAVE_CUDA
  del2d::DeviceOutput out;
  del2d::cuda_impl::triangulate_device(device_xy, n, run, out, r.stats);
  r.num_triangles = out.num_triangles;
  r.num_duplicates = out.num_duplicates;
  r.triangles = std::move(out.triangles);
  r.neighbors = std::move(out.neighbors);
  r.duplicate_of = std::move(out.duplicate_of);
#else
  (void)device_xy;
  (void)run;
#endif
  return r;
}

Triangulation2d delaunay2d(const std::vector<Point2>& pts, const Delaunay2dOptions& opt) {
  return delaunay2d(pts.empty() ? nullptr : &pts.data()->x, std::int64_t(pts.size()), opt);
}

}  // namespace gpugeom
