// Public entry of the 3D Delaunay module: checks sizes and picks the backend.
#include "gpugeom/delaunay3d.hpp"

#include <string>

#include "base/method_grid.hpp"
#include "delaunay3d/del3d_backend.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/tuning.hpp"

namespace gpugeom {

namespace del3d {
// About 7.3 slots a point (tetrahedra with the dead and infinite ones; 7.5 with a margin) must
// stay below the 2^30 - 1 slots the neighbour encoding addresses (delaunay3d/tet.hpp).
constexpr std::int64_t kMaxPoints = ((std::int64_t(1) << 30) - 1) * 2 / 15;

void check_count(std::int64_t n) {
  if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
  if (n > kMaxPoints)
    throw Error(ErrorCode::InvalidInput, "too many points (" + std::to_string(n) + "): at most " +
                                             std::to_string(kMaxPoints) +
                                             " per 3D triangulation (the 2^30 - 1 "
                                             "tetrahedra its 32-bit neighbour encoding "
                                             "addresses)");
  if (n < 4)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 4 points (" + std::to_string(n) +
                    "): a 3D Delaunay triangulation needs 4 points not on one plane");
}

}  // namespace del3d

namespace {
using del3d::check_count;
void check_method(const Delaunay3dOptions& opt) {
  detail::check_method_grid(opt.method, opt.grid, 16, 1024, "the digital method's grid side");
  if (opt.method == Method::Digital && detail::tuning_of(opt).del3d.max_flip_rounds >= 0)
    throw Error(ErrorCode::InvalidArgument,
                "the max_flip_rounds knob is the incremental method's; Method::Digital has "
                "no flip rounds");
}
}  // namespace

Triangulation3d delaunay3d(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt) {
  check_count(n);
  check_method(opt);
  const Backend b = resolve_backend(opt.backend, opt.device);
  Triangulation3d r;
  r.stats.backend = b;
  GG_ENTRIES(b, del3d).triangulate(xyz, n, opt, r, r.stats);
  return r;
}

DeviceTriangulation3d delaunay3d_device(const double* device_xyz, std::int64_t n,
                                        const Delaunay3dOptions& opt) {
  check_count(n);
  check_method(opt);
  const Backend b = device_entry_backend(opt.backend, opt.device, "delaunay3d_device");
  DeviceTriangulation3d r;
  r.backend = r.stats.backend = b;
  r.num_points = n;
  GG_ENTRIES(b, del3d).triangulate_device(device_xyz, n, opt, r, r.stats);
  return r;
}

Triangulation3d delaunay3d(const std::vector<Point3>& pts, const Delaunay3dOptions& opt) {
  return delaunay3d(pts.empty() ? nullptr : &pts.data()->x, std::int64_t(pts.size()), opt);
}

}  // namespace gpugeom
