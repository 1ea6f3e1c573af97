// Public entry of the 3D convex hull module: checks sizes, picks the backend, adds the planes.
#include "gpugeom/hull3d.hpp"

#include <chrono>
#include <cmath>
#include <string>

#include "hull3d/hull3d_backend.hpp"

namespace gpugeom {

namespace {
// Facet slots (2n) times 4 must fit the int32 neighbour encoding.
constexpr std::int64_t kMaxPoints = (std::int64_t(1) << 28) - 8;

void check_count(std::int64_t n) {
  if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
  if (n > kMaxPoints)
    throw Error(ErrorCode::InvalidInput, "too many points (" + std::to_string(n) + "): at most " +
                                             std::to_string(kMaxPoints) + " per hull");
  if (n < 4)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 4 points (" + std::to_string(n) +
                    "): a convex hull in 3D needs 4 points not on one plane");
}

// Unit outward normal and offset of each facet: (b - a) x (c - a) in double. Where the
// differences lose a point entirely (coordinates of very different magnitudes, e.g. a facet
// with one huge and two tiny vertices, whose rounded normal is zero), the normal is summed
// again as a x b + b x c + c x a in long double.
std::vector<double> plane_equations(const double* p, const std::vector<std::int32_t>& t) {
  std::vector<double> eq(t.size() / 3 * 4);
  const std::int64_t nf = std::int64_t(t.size() / 3);
  // Threads only where the work outweighs waking them (about 35 ns a facet; waking idle cores
  // on a virtual machine has cost milliseconds).
#pragma omp parallel for schedule(static) if (nf > 50000)
  for (std::int64_t f = 0; f < nf; ++f) {
    const double *a = p + 3 * std::int64_t(t[3 * f]), *b = p + 3 * std::int64_t(t[3 * f + 1]),
                 *c = p + 3 * std::int64_t(t[3 * f + 2]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double nrm[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                     u[0] * v[1] - u[1] * v[0]};
    double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    if (!(len > 0) || !std::isfinite(len)) {
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
      for (int d = 0; d < 3; ++d) nrm[d] = wl > 0 ? double(w[d] / wl) : 0.0;
      len = 1;
    }
    for (int d = 0; d < 3; ++d) eq[4 * f + d] = nrm[d] / len;
    eq[4 * f + 3] = -(eq[4 * f] * a[0] + eq[4 * f + 1] * a[1] + eq[4 * f + 2] * a[2]);
  }
  return eq;
}
}  // namespace

ConvexHull3d convex_hull3d(const double* xyz, std::int64_t n, const Hull3dOptions& opt) {
  check_count(n);
  ConvexHull3d r;
  const Backend b = resolve_backend(opt.backend);
  r.stats.backend = b;
  hull3d::Output out;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda)
    hull3d::cuda_impl::compute(xyz, n, out, r.stats);
  else
    hull3d::cpu_impl::compute(xyz, n, out, r.stats);
#else
  hull3d::cpu_impl::compute(xyz, n, out, r.stats);
#endif
  r.triangles = std::move(out.triangles);
  r.neighbors = std::move(out.neighbors);
  r.vertices = std::move(out.vertices);
  const auto t0 = std::chrono::steady_clock::now();
  r.equations = plane_equations(xyz, r.triangles);
  r.stats.phase_ms.emplace_back(
      "planes",
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  return r;
}

ConvexHull3d convex_hull3d(const std::vector<Point3>& pts, const Hull3dOptions& opt) {
  return convex_hull3d(pts.empty() ? nullptr : &pts.data()->x, std::int64_t(pts.size()), opt);
}

DeviceHull3d convex_hull3d_device(const double* device_xyz, std::int64_t n) {
  check_count(n);
  DeviceHull3d r;
  r.stats.backend = resolve_backend(Backend::Cuda);  // throws where there is no device
  r.num_points = n;
#ifdef GPUGEOM_HAVE_CUDA
  hull3d::DeviceOutput out;
  hull3d::cuda_impl::compute_device(device_xyz, n, out, r.stats);
  r.num_facets = out.num_facets;
  r.num_vertices = out.num_vertices;
  r.triangles = std::move(out.triangles);
  r.neighbors = std::move(out.neighbors);
  r.vertices = std::move(out.vertices);
#else
  (void)device_xyz;
#endif
  return r;
}

}  // namespace gpugeom
