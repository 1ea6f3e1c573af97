// Public entry of the 3D convex hull module: checks sizes, picks the backend, mends the planes the
// executor could not give in double.
#include "gpugeom/hull3d.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

#include "exec/deliver.hpp"
#include "exec/dispatch.hpp"
#include "base/method_grid.hpp"
#include "base/point_count.hpp"
#include "base/stats_fields.hpp"
#include "hull3d/hull3d_backend.hpp"

namespace gpugeom {

namespace {
// Points are int32 indices and index n names the kernel point. The facets have a limit of their
// own (hull3d::kMaxFacetSlots: 2^28 extreme points), checked as the hull grows.
constexpr std::int64_t kMaxPoints = std::int64_t(INT32_MAX) - 1;

}  // namespace

// The counters' names as strings, each its field's own (base/stats_fields.hpp).
// clang-format off
#define GG_HULL3D_COUNTERS(X)                                                                   \
  X(duplicates) X(passes) X(insert_rounds) X(facet_store_grown) X(flip_rounds) X(flips22)       \
  X(flips31) X(labelled_nonextreme) X(exact_predicates) X(first_pass_vertices)                  \
  X(nonextreme_vertices_dropped) X(digital_grid) X(digital_render) X(sketch_points)             \
  X(sketch_facets) X(depth_kept) X(hull_input) X(digital_fallback) X(hull_candidates)           \
  X(outside_points) X(removed_vertices) X(cavity_insertions) X(deferred_points)
// clang-format on
GG_COUNTER_MAP(Hull3dStats, GG_HULL3D_COUNTERS);
#undef GG_HULL3D_COUNTERS

namespace hull3d {
void check_count(std::int64_t n) {
  detail::check_point_count(n, 4, kMaxPoints, "per hull",
                            "a convex hull in 3D needs 4 points not on one plane");
}

// A tenth of the slots of a hull on every point (2n), and at least 2^16: uniform balls and
// cubes keep a few thousand facets of 10^8 points; points on a sphere grow the store by
// doubling, a few copies of its used part. forced > 0 (Tuning::Hull3d) takes its place.
std::int64_t first_facet_slots(std::int64_t n, std::int64_t forced) {
  const std::int64_t want =
      forced > 0 ? forced : std::max<std::int64_t>(std::int64_t(1) << 16, n / 5);
  return std::max<std::int64_t>(8, std::min({want, 2 * n, kMaxFacetSlots}));
}

// The executor gives each facet's unit outward normal and offset from (b - a) x (c - a) in
// double (PlaneOf in impl/hull.inl). Where the differences lose a point entirely (coordinates of
// very different magnitudes, e.g. a facet with one huge and two tiny vertices, whose rounded
// normal is zero) it leaves NaN, and the normal is summed again here as a x b + b x c + c x a
// in long double.
void redo_planes(const double* p, const std::int32_t* t, std::int64_t nf, double* eq) {
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!std::isnan(eq[4 * f])) continue;
    const double *a = p + 3 * std::int64_t(t[3 * f]), *b = p + 3 * std::int64_t(t[3 * f + 1]),
                 *c = p + 3 * std::int64_t(t[3 * f + 2]);
    long double w[3] = {0, 0, 0};
    auto cross = [&w](const double* x, const double* y) {
      w[0] += (long double)x[1] * y[2] - (long double)x[2] * y[1];
      w[1] += (long double)x[2] * y[0] - (long double)x[0] * y[2];
      w[2] += (long double)x[0] * y[1] - (long double)x[1] * y[0];
    };
    cross(a, b);
    cross(b, c);
    cross(c, a);
    const long double wl = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int d = 0; d < 3; ++d) eq[4 * f + d] = wl > 0 ? double(w[d] / wl) : 0.0;
    eq[4 * f + 3] = -(eq[4 * f] * a[0] + eq[4 * f + 1] * a[1] + eq[4 * f + 2] * a[2]);
  }
}
}  // namespace hull3d

namespace {
void check_method(const Hull3dOptions& opt) {
  detail::check_method_grid(opt.method, opt.grid, 16, 8192, "the digital hull's grid side");
}
}  // namespace

std::int64_t convex_hull3d_max_facets(std::int64_t n) {
  return n < 4 ? 0 : 2 * n - 4;
}

ConvexHull3d convex_hull3d(const double* xyz, std::int64_t n, const Hull3dOptions& opt) {
  hull3d::check_count(n);
  check_method(opt);
  return detail::run_host_entry(GG_PICK(hull3d), xyz, n, opt);
}

ConvexHull3d convex_hull3d(const std::vector<Point3>& pts, const Hull3dOptions& opt) {
  return convex_hull3d(pts.empty() ? nullptr : &pts.data()->x, std::int64_t(pts.size()), opt);
}

DeviceHull3d convex_hull3d_device(const double* device_xyz, std::int64_t n,
                                  const Hull3dOptions& opt) {
  hull3d::check_count(n);
  check_method(opt);
  return detail::run_device_entry(GG_PICK(hull3d), device_xyz, n, opt, "convex_hull3d_device");
}

}  // namespace gpugeom
