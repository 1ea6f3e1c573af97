// The Voronoi diagram dual to a 2D Delaunay triangulation (host code: linear in the size of
// the triangulation, a small fraction of the triangulation's own time).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "gpugeom/delaunay2d.hpp"

namespace gpugeom {

namespace {

void check_sizes(std::int64_t n, const Triangulation2d& tri) {
  if (tri.triangles.size() != std::size_t(3 * tri.triangle_count) ||
      tri.neighbors.size() != tri.triangles.size())
    throw Error(ErrorCode::InvalidArgument,
                "the triangulation's triangles or neighbours are not in its result (were they "
                "written into the caller's arrays, Delaunay2dOptions::into?): the Voronoi "
                "diagram needs them there");
  if (std::int64_t(tri.duplicate_of.size()) != n || tri.neighbors.size() != tri.triangles.size())
    throw Error(ErrorCode::InvalidArgument,
                "the triangulation does not belong to these " + std::to_string(n) + " points");
}

// One incident corner (triangle, local index) per vertex; on the hull the most clockwise one,
// so that walking counter-clockwise from it visits the whole star.
std::vector<std::int64_t> star_starts(std::int64_t n, const Triangulation2d& tri) {
  std::vector<std::int64_t> start(std::size_t(n), -1);
  const std::int64_t nt = std::int64_t(tri.num_triangles());
  for (std::int64_t c = 0; c < 3 * nt; ++c) {
    const std::int32_t v = tri.triangles[c];
    const std::int64_t t = c / 3;
    const int k = int(c % 3);
    const bool cw_open = tri.neighbors[3 * t + (k + 2) % 3] < 0;
    if (start[v] < 0 || cw_open) start[v] = c;
  }
  return start;
}

// Triangles around vertex tri[c] counter-clockwise from corner c, and whether the star is open
// (the vertex on the hull).
template <class F>
bool walk_star(const Triangulation2d& tri, std::int64_t c, F visit) {
  const std::int32_t v = tri.triangles[c];
  std::int64_t t = c / 3;
  int k = int(c % 3);
  const std::int64_t first = t;
  for (;;) {
    visit(t, k);
    const std::int32_t nx = tri.neighbors[3 * t + (k + 1) % 3];
    if (nx < 0) return true;
    if (nx == first) return false;
    t = nx;
    k = tri.triangles[3 * t] == v ? 0 : tri.triangles[3 * t + 1] == v ? 1 : 2;
  }
}

}  // namespace

Voronoi2d voronoi2d(const double* xy, std::int64_t n, const Triangulation2d& tri) {
  check_sizes(n, tri);
  Voronoi2d v;
  const std::int64_t nt = std::int64_t(tri.num_triangles());
  v.vertices.resize(std::size_t(2 * nt));
  for (std::int64_t t = 0; t < nt; ++t) {
    const double* a = xy + 2 * tri.triangles[3 * t];
    const double* b = xy + 2 * tri.triangles[3 * t + 1];
    const double* c = xy + 2 * tri.triangles[3 * t + 2];
    // relative to a, which keeps the rounding to the triangle's own scale
    const double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
    const double d = 2 * (bx * cy - by * cx);
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    v.vertices[2 * t] = a[0] + (cy * b2 - by * c2) / d;
    v.vertices[2 * t + 1] = a[1] + (bx * c2 - cx * b2) / d;
  }
  // ridges: each Delaunay edge once (from the triangle with the smaller index, or the hull)
  for (std::int64_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t o = tri.neighbors[3 * t + k];
      if (o >= 0 && o < t) continue;
      const std::int32_t u = tri.triangles[3 * t + (k + 1) % 3];
      const std::int32_t w = tri.triangles[3 * t + (k + 2) % 3];
      v.ridge_points.push_back(u);
      v.ridge_points.push_back(w);
      v.ridge_vertices.push_back(std::int32_t(t));
      v.ridge_vertices.push_back(o);
      double dx = 0, dy = 0;
      if (o < 0) {  // outward normal of the hull edge u->w (the triangle lies to its left)
        const double ex = xy[2 * w] - xy[2 * u], ey = xy[2 * w + 1] - xy[2 * u + 1];
        const double len = std::hypot(ex, ey);
        dx = ey / len;
        dy = -ex / len;
      }
      v.ridge_directions.push_back(dx);
      v.ridge_directions.push_back(dy);
    }
  // cells
  const auto start = star_starts(n, tri);
  v.cell_offsets.assign(std::size_t(n + 1), 0);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int32_t src = tri.duplicate_of[i] >= 0 ? tri.duplicate_of[i] : std::int32_t(i);
    const std::int64_t c = start[src];
    if (c < 0)
      throw Error(ErrorCode::InvalidArgument,
                  "point " + std::to_string(src) + " is not a vertex of the triangulation");
    const std::size_t at = v.cell_vertices.size();
    const bool open =
        walk_star(tri, c, [&](std::int64_t t, int) { v.cell_vertices.push_back(std::int32_t(t)); });
    if (open) v.cell_vertices.insert(v.cell_vertices.begin() + std::ptrdiff_t(at), -1);
    v.cell_offsets[i + 1] = std::int64_t(v.cell_vertices.size());
  }
  return v;
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
