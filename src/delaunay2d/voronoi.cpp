// The Voronoi diagram dual to a 2D Delaunay triangulation (host code: linear in the size of
// the triangulation, a small fraction of the triangulation's own time).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "delaunay2d/del2d_backend.hpp"
#include "delaunay2d/voronoi_core.hpp"
#include "exec/device_voronoi.hpp"
#include "exec/dispatch.hpp"
#include "gpugeom/delaunay2d.hpp"

namespace gpugeom {

namespace {

void check_sizes(std::int64_t n, const Triangulation2d& tri) {
  if (tri.triangles.size() != std::size_t(3 * tri.num_triangles) ||
      tri.neighbors.size() != tri.triangles.size())
    throw Error(ErrorCode::InvalidArgument,
                "the triangulation's triangles or neighbours are not in its result (were they "
                "written into the caller's arrays, Delaunay2dOptions::into?): the Voronoi "
                "diagram needs them there");
  if (std::int64_t(tri.duplicate_of.size()) != n || tri.neighbors.size() != tri.triangles.size())
    throw Error(ErrorCode::InvalidArgument,
                "the triangulation does not belong to these " + std::to_string(n) + " points");
}

// One incident corner per vertex (vor::start_key: on the hull the most clockwise one), -1 for a
// point that is not a vertex.
std::vector<std::int64_t> star_starts(std::int64_t n, const Triangulation2d& tri) {
  std::vector<std::int64_t> key(std::size_t(n), -1);
  const std::int64_t nt = tri.num_triangles;
  for (std::int64_t c = 0; c < 3 * nt; ++c) {
    std::int64_t& k = key[std::size_t(tri.triangles[c])];
    k = std::max(k, del2d::vor::start_key(tri.neighbors.data(), c));
  }
  for (auto& k : key) k = del2d::vor::start_corner(k);
  return key;
}

// Triangles around vertex tri[c] counter-clockwise from corner c, and whether the star is open.
template <class F>
bool walk_star(const Triangulation2d& tri, std::int64_t c, F visit) {
  return del2d::vor::walk_star(tri.triangles.data(), tri.neighbors.data(), c, tri.num_triangles,
                               visit);
}

}  // namespace

// The host entry: the executor's algorithm over the caller's arrays (the CPU executor), or over
// their one upload; the same arrays on both, bit for bit.
Voronoi2d voronoi2d(const double* xy, std::int64_t n, const Triangulation2d& tri,
                    const Voronoi2dOptions& opt) {
  check_sizes(n, tri);
  const Backend b = resolve_backend(opt.backend, opt.device);
  Voronoi2d v;
  v.stats.backend = b;
  GG_TABLE(b, del2d, voronoi_entries)
      .of_host(xy, n, tri.triangles.data(), tri.neighbors.data(),
               tri.duplicate_of.data(),  // (copies; removed points: empty cells)
               tri.num_triangles, opt, v);
  return v;
}

Voronoi2d voronoi2d(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                    Triangulation2d* tri, Delaunay2dStats* stats) {
  const Backend b = resolve_backend(opt.backend, opt.device);
  Delaunay2dStats local;
  Delaunay2dStats& st = stats ? *stats : local;
  st.backend = b;
  const auto& on = GG_TABLE(b, del2d, voronoi_entries);
  if (on.from_host && opt.method == Method::Incremental) {
    del2d::check_count(n);
    Voronoi2d v;
    v.stats.backend = b;
    on.from_host(xy, n, opt, v, tri, st);
    return v;
  }
  Delaunay2dOptions o = opt;
  o.into = {};
  Triangulation2d t = delaunay2d(xy, n, o);
  Voronoi2d v = voronoi2d(xy, n, t, options_from<Voronoi2dOptions>(opt));
  st = t.stats;
  if (tri) *tri = std::move(t);
  return v;
}

DeviceVoronoi2d voronoi2d_device(const double* device_xy, std::int64_t n,
                                 const DeviceTriangulation2d& tri, const Voronoi2dOptions& opt) {
  return detail::run_device_voronoi<DeviceVoronoi2d>(
      GG_TABLE(tri.backend, del2d, voronoi_entries), device_xy, n, tri, tri.triangles.get(),
      tri.num_triangles, opt, "triangulation", "triangles", "Delaunay2dOptions");
}

ClippedCells clip_voronoi_cells(const double* xy, std::int64_t n, const Triangulation2d& tri,
                                const Voronoi2d& vor, double xmin, double ymin, double xmax,
                                double ymax) {
  check_sizes(n, tri);
  if (std::int64_t(vor.cell_offsets.size()) != n + 1)
    throw Error(ErrorCode::InvalidArgument, "the Voronoi diagram does not belong to these points");
  if (!(xmin < xmax && ymin < ymax)) throw Error(ErrorCode::InvalidArgument, "empty clip box");
  ClippedCells out;
  out.offsets.assign(std::size_t(n + 1), 0);
  const auto start = star_starts(n, tri);
  std::vector<double> poly, next;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int32_t src = tri.duplicate_of[i] >= 0 ? tri.duplicate_of[i] : std::int32_t(i);
    const double px = xy[2 * src], py = xy[2 * src + 1];
    // The cell is the intersection of the half-planes nearer p than each Delaunay neighbour q:
    // clip the box by their bisectors (no rays or far points needed for unbounded cells).
    poly = {xmin, ymin, xmax, ymin, xmax, ymax, xmin, ymax};
    if (start[src] < 0)
      throw Error(ErrorCode::InvalidArgument,
                  "point " + std::to_string(src) + " is not a vertex of the triangulation");
    walk_star(tri, start[src], [&](std::int64_t t, int k) {
      for (int side = 1; side <= 2; ++side) {
        const std::int32_t q = tri.triangles[3 * t + (k + side) % 3];
        const double qx = xy[2 * q], qy = xy[2 * q + 1];
        // keep x with (q - p) . (x - (p + q) / 2) <= 0
        const double nx = qx - px, ny = qy - py, mx = 0.5 * (px + qx), my = 0.5 * (py + qy);
        next.clear();
        const std::size_t np = poly.size() / 2;
        for (std::size_t j = 0; j < np; ++j) {
          const double ax = poly[2 * j], ay = poly[2 * j + 1];
          const double bx = poly[2 * ((j + 1) % np)], by = poly[2 * ((j + 1) % np) + 1];
          const double fa = nx * (ax - mx) + ny * (ay - my);
          const double fb = nx * (bx - mx) + ny * (by - my);
          if (fa <= 0) next.insert(next.end(), {ax, ay});
          if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
            const double s = fa / (fa - fb);
            next.insert(next.end(), {ax + s * (bx - ax), ay + s * (by - ay)});
          }
        }
        poly.swap(next);
      }
    });
    out.xy.insert(out.xy.end(), poly.begin(), poly.end());
    out.offsets[i + 1] = std::int64_t(out.xy.size() / 2);
  }
  return out;
}

}  // namespace gpugeom
