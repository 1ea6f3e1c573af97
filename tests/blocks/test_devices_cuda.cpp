// delaunay{2,3}d_devices with the blocks on the GPU (the device listed several times): a
// single GPU call's arrays.
#include "devices_cases.hpp"

namespace gg_devices {
namespace {

TEST(DelaunayDevicesCuda, Blocks3dEqualOneCall) {
  check_all<Point3, Delaunay3dOptions>(
      inputs3d(20000), Backend::Cuda, 0,
      [](const double* p, std::int64_t n, const Delaunay3dOptions& o) {
        return delaunay3d(p, n, o);
      },
      [](const double* p, std::int64_t n, const std::vector<int>& d, const Delaunay3dOptions& o) {
        return delaunay3d_devices(p, n, d, o);
      });
}

TEST(DelaunayDevicesCuda, Blocks2dEqualOneCall) {
  check_all<Point2, Delaunay2dOptions>(
      inputs2d(50000), Backend::Cuda, 0,
      [](const double* p, std::int64_t n, const Delaunay2dOptions& o) {
        return delaunay2d(p, n, o);
      },
      [](const double* p, std::int64_t n, const std::vector<int>& d, const Delaunay2dOptions& o) {
        return delaunay2d_devices(p, n, d, o);
      });
}

}  // namespace
}  // namespace gg_devices
