// Voronoi cells of 3D points in a box (issue 49): the entries check the box and run the
// executor's algorithm (impl/cells.inl).
#include <cmath>
#include <cstdint>
#include <string>

#include "base/stats_fields.hpp"
#include "delaunay3d/del3d_backend.hpp"
#include "delaunay3d/voronoi3d_backend.hpp"
#include "exec/dispatch.hpp"
#include "gpugeom/voronoi_cells.hpp"

namespace gpugeom {
namespace {

void check_box(const VoronoiCellsOptions& opt, std::int64_t n) {
  if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
  static const char* axis = "xyz";
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(opt.lo[d]) || !std::isfinite(opt.hi[d]) || !(opt.lo[d] < opt.hi[d]))
      throw Error(ErrorCode::InvalidArgument,
                  std::string("the box's ") + axis[d] + " range [" + std::to_string(opt.lo[d]) +
                      ", " + std::to_string(opt.hi[d]) +
                      "] is empty or not finite: VoronoiCellsOptions::lo must be below hi");
}

}  // namespace

// clang-format off
#define GG_CELLS_COUNTERS(X) X(images) X(attempts) X(faces) X(cells_cut) X(cell_overflows)
// clang-format on
GG_COUNTER_MAP(VoronoiCellsStats, GG_CELLS_COUNTERS);
#undef GG_CELLS_COUNTERS

VoronoiCells voronoi_cells(const double* xyz, std::int64_t n, const VoronoiCellsOptions& opt) {
  check_box(opt, n);
  VoronoiCells c;
  const Backend b = resolve_backend(opt.backend, opt.device);
  c.stats.backend = b;
  GG_TABLE(b, del3d, voronoi_entries).cells(xyz, n, true, opt, nullptr, &c);
  return c;
}

DeviceVoronoiCells voronoi_cells_device(const double* device_xyz, std::int64_t n,
                                        const VoronoiCellsOptions& opt) {
  check_box(opt, n);
  DeviceVoronoiCells c;
  const Backend b = resolve_backend(opt.backend, opt.device);
  c.backend = c.stats.backend = b;
  GG_TABLE(b, del3d, voronoi_entries).cells(device_xyz, n, false, opt, &c, nullptr);
  return c;
}

}  // namespace gpugeom
