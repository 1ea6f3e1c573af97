// Public entry of the 3D Delaunay module: checks sizes, picks the backend, adds the hull
// facets and the vertex map.
#include "gpugeom/delaunay3d.hpp"

#include <chrono>
#include <string>

#include "base/clock.hpp"
#include "delaunay3d/del3d_backend.hpp"

namespace gpugeom {

namespace {
// Up to about 7.5 tetrahedra per point with the dead and infinite slots must stay below the
// 2^29 slots the neighbour encoding addresses.
constexpr std::int64_t kMaxPoints = std::int64_t(1) << 26;

void check_count(std::int64_t n) {
  if (n < 0) throw Error(ErrorCode::InvalidArgument, "negative point count");
  if (n > kMaxPoints)
    throw Error(ErrorCode::InvalidInput, "too many points (" + std::to_string(n) + "): at most " +
                                             std::to_string(kMaxPoints) +
                                             " per 3D triangulation in this version");
  if (n < 4)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 4 points (" + std::to_string(n) +
                    "): a 3D Delaunay triangulation needs 4 points not on one plane");
}

// Faces opposite each vertex, oriented outward (the tetrahedron on their negative side).
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
}  // namespace

Triangulation3d delaunay3d(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt) {
  check_count(n);
  Triangulation3d r;
  const Backend b = resolve_backend(opt.backend, opt.device);
  r.stats.backend = b;
  del3d::Output out;
#ifdef GPUGEOM_HAVE_CUDA
  if (b == Backend::Cuda)
    del3d::cuda_impl::triangulate(xyz, n, opt, out, r.stats);
  else
    del3d::cpu_impl::triangulate(xyz, n, opt, out, r.stats);
#else
  del3d::cpu_impl::triangulate(xyz, n, opt, out, r.stats);
#endif
  const auto t0 = std::chrono::steady_clock::now();
  r.tetrahedra = std::move(out.tetrahedra);
  r.neighbors = std::move(out.neighbors);
  r.duplicate_of = std::move(out.duplicate_of);
  r.num_duplicates = out.num_duplicates;
  const std::size_t nt = r.num_tetrahedra();
  r.vertex_to_simplex.assign(std::size_t(n), -1);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 4; ++k) {
      r.vertex_to_simplex[std::size_t(r.tetrahedra[4 * t + k])] = std::int32_t(t);
      if (r.neighbors[4 * t + k] < 0)
        for (int i = 0; i < 3; ++i) r.hull_facets.push_back(r.tetrahedra[4 * t + kFace[k][i]]);
    }
  for (std::size_t i = 0; i < std::size_t(n); ++i)
    if (r.duplicate_of[i] >= 0)
      r.vertex_to_simplex[i] = r.vertex_to_simplex[std::size_t(r.duplicate_of[i])];
  r.stats.phase_ms.push_back({"host_arrays", ms_since(t0)});
  return r;
}

Triangulation3d delaunay3d(const std::vector<Point3>& pts, const Delaunay3dOptions& opt) {
  return delaunay3d(pts.empty() ? nullptr : &pts.data()->x, std::int64_t(pts.size()), opt);
}

}  // namespace gpugeom
