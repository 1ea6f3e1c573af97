// Public entry of the 2D Delaunay module: checks sizes, picks the backend, packs the result.
#include "gpugeom/delaunay2d.hpp"

#include <string>

#include "base/point_count.hpp"
#include "base/stats_fields.hpp"
#include "delaunay2d/del2d_backend.hpp"
#include "delaunay2d/digital/digital.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"

namespace gpugeom {

// clang-format off
#define GG_DELAUNAY2D_COUNTERS(X)                                                                 \
  X(points) X(distinct_points) X(duplicates) X(batches) X(flip_rounds) X(small_flip_rounds)       \
  X(team_flip_rounds) X(flips) X(work_list_entries) X(exact_predicates) X(exact_rest_passes)      \
  X(log_relocations) X(split_flip_rounds) X(flat_triangles) X(start_walk_steps)                   \
  X(start_walk_scans) X(start_walk_longest) X(grid_width) X(grid_height) X(sites)                 \
  X(sketch_missing) X(debris_pixels) X(debris_candidates) X(pinched_corners) X(hull_triangles)    \
  X(sketch_not_disk) X(shifted) X(bad_inner) X(bad_boundary) X(shift_rounds) X(delete_rounds)     \
  X(start_vertices) X(start_triangles) X(digital_fallback) X(inserted_points) X(removed_points)   \
  X(hole_vertices) X(hole_triangles) X(remove_rebuilt) X(move_rounds) X(move_taken_out)           \
  X(move_reinserted) X(move_rebuilt) X(furthest_site_vertices) X(cavity_insertions)           \
  X(deferred_points) X(blocks) X(blocks_second_round) X(block_local_points)
// clang-format on
GG_COUNTER_MAP(Delaunay2dStats, GG_DELAUNAY2D_COUNTERS);
#undef GG_DELAUNAY2D_COUNTERS

namespace del2d {
// Slots of the extended triangulation (2m - 2) must stay below 2^30, the wide neighbour
// encoding's range (mesh/adjacency.hpp); memory comes first on today's GPUs (168 B a point
// at least: 5·10^8 points on 80 GB), and is checked before any launch.
constexpr std::int64_t kMaxPoints = (std::int64_t(1) << 29) - 2;

void check_count(std::int64_t n) {
  detail::check_point_count(n, 3, kMaxPoints, "per triangulation",
                            "a triangulation needs at least 3 points not on one line");
}
}  // namespace del2d
using del2d::check_count;

std::int64_t delaunay2d_max_triangles(std::int64_t n) {
  return n < 3 ? 0 : 2 * n - 5;
}

Triangulation2d delaunay2d(const double* xy, std::int64_t n, const Delaunay2dOptions& opt) {
  check_count(n);
  if (opt.method != Method::Digital) return detail::run_host_entry(GG_PICK(del2d), xy, n, opt);
  Triangulation2d r;
  const Backend b = resolve_backend(opt.backend, opt.device);
  r.stats.backend = b;
  del2d::digital::triangulate(xy, n, opt, b, r, r.stats);
  return r;
}

DeviceTriangulation2d delaunay2d_device(const double* device_xy, std::int64_t n,
                                        const Delaunay2dOptions& opt) {
  check_count(n);
  if (opt.method == Method::Digital)
    throw Error(ErrorCode::Unsupported,
                "delaunay2d_device: Method::Digital runs from host points (call delaunay2d); "
                "the device entry computes Method::Incremental (the same triangulation)");
  return detail::run_device_entry(GG_PICK(del2d), device_xy, n, opt, "delaunay2d_device");
}

Triangulation2d delaunay2d(const std::vector<Point2>& pts, const Delaunay2dOptions& opt) {
  return delaunay2d(pts.empty() ? nullptr : &pts.data()->x, std::int64_t(pts.size()), opt);
}

}  // namespace gpugeom
