// delaunay{2,3}d_devices on the CPU executor (every entry a block): a single call's arrays.
#include "devices_cases.hpp"

namespace gg_devices {
namespace {

Triangulation3d single3(const double* p, std::int64_t n, const Delaunay3dOptions& o) {
  return delaunay3d(p, n, o);
}
Triangulation3d blocks3(const double* p, std::int64_t n, const std::vector<int>& d,
                        const Delaunay3dOptions& o) {
  return delaunay3d_devices(p, n, d, o);
}
Triangulation2d single2(const double* p, std::int64_t n, const Delaunay2dOptions& o) {
  return delaunay2d(p, n, o);
}
Triangulation2d blocks2(const double* p, std::int64_t n, const std::vector<int>& d,
                        const Delaunay2dOptions& o) {
  return delaunay2d_devices(p, n, d, o);
}

TEST(DelaunayDevices, Blocks3dEqualOneCall) {
  const auto second =
      check_all<Point3, Delaunay3dOptions>(inputs3d(6000), Backend::Cpu, 0, single3, blocks3);
  RecordProperty("second_rounds", int(second));
}

TEST(DelaunayDevices, Blocks2dEqualOneCall) {
  const auto second =
      check_all<Point2, Delaunay2dOptions>(inputs2d(20000), Backend::Cpu, 0, single2, blocks2);
  RecordProperty("second_rounds", int(second));
}

}  // namespace
}  // namespace gg_devices
