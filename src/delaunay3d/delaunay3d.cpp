// Public entry of the 3D Delaunay module: checks sizes and picks the backend.
#include "gpugeom/delaunay3d.hpp"

#include <string>

#include "base/method_grid.hpp"
#include "base/point_count.hpp"
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
  detail::check_point_count(n, 4, kMaxPoints,
                            "per 3D triangulation (the 2^30 - 1 tetrahedra its 32-bit neighbour "
                            "encoding addresses)",
                            "a 3D Delaunay triangulation needs 4 points not on one plane");
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
  return detail::run_host_entry(GG_PICK(del3d), xyz, n, opt);
}

DeviceTriangulation3d delaunay3d_device(const double* device_xyz, std::int64_t n,
                                        const Delaunay3dOptions& opt) {
  check_count(n);
  check_method(opt);
  return detail::run_device_entry(GG_PICK(del3d), device_xyz, n, opt, "delaunay3d_device");
}

Triangulation3d delaunay3d(const std::vector<Point3>& pts, const Delaunay3dOptions& opt) {
  return delaunay3d(pts.empty() ? nullptr : &pts.data()->x, std::int64_t(pts.size()), opt);
}

}  // namespace gpugeom
