// Public entry of the 3D Delaunay module: checks sizes and picks the backend.
#include "gpugeom/delaunay3d.hpp"

#include <string>

#include "base/method_grid.hpp"
#include "base/point_count.hpp"
#include "base/stats_fields.hpp"
#include "delaunay3d/del3d_backend.hpp"
#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "exec/tuning.hpp"

namespace gpugeom {

// clang-format off
#define GG_DELAUNAY3D_COUNTERS(X)                                                                 \
  X(points) X(distinct_points) X(duplicates) X(batches) X(flip_rounds) X(flips23) X(flips32)     \
  X(cavity_insertions) X(deferred_points) X(unflippable_tests) X(failed_faces) X(failed_vertices) X(stars_built) X(stars_changed)        \
  X(star_insertions) X(splay_rounds) X(splay_removed) X(splay_added) X(flat_tetrahedra)          \
  X(device_bytes_phase1) X(slots_used) X(slots_capacity) X(halts) X(max_list)                    \
  X(max_epoch_records) X(max_free_slots) X(max_splits) X(list_capacity) X(log_capacity)          \
  X(ring_capacity) X(round_chunks) X(team_launches) X(carried_batches) X(us_choose_split)        \
  X(us_rounds_wide) X(us_rounds_team) X(us_splay_build) X(us_splay_rounds) X(us_splay_check)     \
  X(us_splay_patch) X(us_splay_take) X(start_walk_steps) X(start_walk_scans)                     \
  X(start_walk_longest) X(digital_grid) X(digital_grid_refined) X(digital_points_on_box)         \
  X(sites) X(sketch_missing) X(digital_working_pairs) X(digital_working_set_points)              \
  X(digital_working_sets_augmented) X(digital_star_slots_created) X(digital_star_slots)          \
  X(digital_star_growths) X(digital_star_insertions) X(digital_star_requests)                    \
  X(digital_splay_rounds) X(digital_splay_vertex_rounds) X(digital_splay_request_spills)         \
  X(digital_fallback) X(inserted_points) X(removed_points) X(hole_vertices) X(hole_tetrahedra)   \
  X(remove_rebuilt) X(move_rounds) X(move_taken_out) X(move_reinserted) X(move_grown)            \
  X(move_rebuilt) X(blocks) X(blocks_second_round) X(block_local_points)
// clang-format on
GG_COUNTER_MAP(Delaunay3dStats, GG_DELAUNAY3D_COUNTERS);
#undef GG_DELAUNAY3D_COUNTERS

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
