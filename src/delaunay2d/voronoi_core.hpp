// The pieces of the Voronoi diagram of a 2D triangulation (internal), one element at a time, so
// that the host's loop (voronoi2d) and the executor's kernels (voronoi2d_device) compute the
// same doubles in the same order. Arrays as Triangulation2d has them: tri and nb, 3 per triangle.
#pragma once
#include <cmath>
#include <cstdint>

#include "base/hd.hpp"
#include "mesh/sum2.hpp"
#include "predicates/expansion.hpp"

namespace gpugeom::del2d::vor {

// The circumcentre of triangle t: c = r + (|b|^2 c_perp - |c|^2 b_perp) / (2 b x c), with b, c
// the other corners taken from the reference corner r, an end of the shortest edge (taken from a
// corner far from two near ones, the edges to those round to parallel vectors and the formula to
// 0/0: corners 10^40 away from others 10^-30 apart). The differences are scaled by a power of two
// (exact) so that their squares and products neither overflow nor underflow. Every operation
// rounded on its own (the device would otherwise fuse products into sums), so that both executors
// give the same bits.
GG_HD inline void circumcentre(const double* xy, const std::int32_t* tri, std::int64_t t,
                               double* out) {
  using exact::add_rn;
  using exact::mul_rn;
  using exact::sub_rn;
  const double* q[3];
  for (int k = 0; k < 3; ++k) q[k] = xy + 2 * std::int64_t(tri[3 * t + k]);
  int ref = 0;
  double best = 0;
  for (int i = 0; i < 3; ++i) {  // (edge i: corners i and i + 1)
    const int j = (i + 1) % 3;
    const double len = fmax(fabs(sub_rn(q[j][0], q[i][0])), fabs(sub_rn(q[j][1], q[i][1])));
    if (i == 0 || len < best) best = len, ref = i;
  }
  const double* a = q[ref];
  const double* b0 = q[(ref + 1) % 3];  // (counter-clockwise from the reference: keeps the sign)
  const double* c0 = q[(ref + 2) % 3];
  double far = 0;
  for (int d = 0; d < 2; ++d)
    far = fmax(far, fmax(fabs(sub_rn(b0[d], a[d])), fabs(sub_rn(c0[d], a[d]))));
  const int ex = far > 0 ? ilogb(far) : 0;
  const double bx = ldexp(sub_rn(b0[0], a[0]), -ex), by = ldexp(sub_rn(b0[1], a[1]), -ex);
  const double cx = ldexp(sub_rn(c0[0], a[0]), -ex), cy = ldexp(sub_rn(c0[1], a[1]), -ex);
  // (the determinant in twice the precision: a nearly flat triangle's rounds to 0 otherwise)
  mesh::Sum2 det, nx, ny;
  det.add_product(bx, cy);
  det.add_product(-by, cx);
  const double d = 2 * det.value();
  const double b2 = add_rn(mul_rn(bx, bx), mul_rn(by, by));
  const double c2 = add_rn(mul_rn(cx, cx), mul_rn(cy, cy));
  nx.add_product(cy, b2);
  nx.add_product(-by, c2);
  ny.add_product(bx, c2);
  ny.add_product(-cx, b2);
  out[0] = add_rn(a[0], ldexp(nx.value() / d, ex));
  out[1] = add_rn(a[1], ldexp(ny.value() / d, ex));
}

// Each Delaunay edge is one ridge, taken from the triangle with the smaller index (or the hull).
GG_HD inline bool has_ridge(const std::int32_t* nb, std::int64_t t, int k) {
  const std::int32_t o = nb[3 * t + k];
  return !(o >= 0 && o < t);
}

// The ridge across edge k of triangle t: the two points it separates, its two Voronoi vertices
// (-1: it goes to infinity) and, for an unbounded ridge, the outward unit normal of the hull
// edge u->w (the triangle lies to its left), else (0, 0).
GG_HD inline void ridge(const double* xy, const std::int32_t* tri, const std::int32_t* nb,
                        std::int64_t t, int k, std::int32_t* points, std::int32_t* vertices,
                        double* direction) {
  const std::int32_t o = nb[3 * t + k];
  const std::int32_t u = tri[3 * t + (k + 1) % 3], w = tri[3 * t + (k + 2) % 3];
  points[0] = u;
  points[1] = w;
  vertices[0] = std::int32_t(t);
  vertices[1] = o;
  double dx = 0, dy = 0;
  if (o < 0) {
    const double ex = exact::sub_rn(xy[2 * std::int64_t(w)], xy[2 * std::int64_t(u)]);
    const double ey = exact::sub_rn(xy[2 * std::int64_t(w) + 1], xy[2 * std::int64_t(u) + 1]);
    // (sqrt and division are correctly rounded on host and device)
    const double len = sqrt(exact::add_rn(exact::mul_rn(ex, ex), exact::mul_rn(ey, ey)));
    dx = ey / len;
    dy = -ex / len;
  }
  direction[0] = dx;
  direction[1] = dy;
}

// Where a vertex's cell walk starts: one incident corner, on the hull the most clockwise one
// (so that walking counter-clockwise from it visits the whole star). Every corner c of the
// vertex offers a key; the largest wins: the last corner whose clockwise side is open, else the
// first corner. start_corner decodes it (-1: no corner offered, not a vertex).
constexpr std::int64_t kOpenKey = std::int64_t(1) << 40;
GG_HD inline std::int64_t start_key(const std::int32_t* nb, std::int64_t c) {
  const std::int64_t t = c / 3;
  const int k = int(c % 3);
  return nb[3 * t + (k + 2) % 3] < 0 ? kOpenKey + c : kOpenKey - 1 - c;
}
GG_HD inline std::int64_t start_corner(std::int64_t key) {
  return key < 0 ? -1 : key >= kOpenKey ? key - kOpenKey : kOpenKey - 1 - key;
}

// Triangles around vertex tri[c] counter-clockwise from corner c (visit(t, k) each, k the
// vertex's corner in t), and whether
// the star is open (the vertex on the hull). At most `limit` steps (the triangle count): arrays
// that are not a triangulation end the walk instead of looping.
template <class F>
GG_HD bool walk_star(const std::int32_t* tri, const std::int32_t* nb, std::int64_t c,
                     std::int64_t limit, F visit) {
  const std::int32_t v = tri[c];
  std::int64_t t = c / 3;
  int k = int(c % 3);
  const std::int64_t first = t;
  for (std::int64_t step = 0; step < limit; ++step) {
    visit(t, k);
    const std::int32_t nx = nb[3 * t + (k + 1) % 3];
    if (nx < 0) return true;
    if (nx == first) return false;
    t = nx;
    k = tri[3 * t] == v ? 0 : tri[3 * t + 1] == v ? 1 : 2;
  }
  return false;
}

}  // namespace gpugeom::del2d::vor
