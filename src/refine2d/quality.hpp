// The geometry of Delaunay refinement (internal; host and device code): triangle quality, the
// new points (circumcentres, off-centres, subsegment splits) and the exact encroachment test.
//
// Every rounding operation of a new point goes through exact::*_rn, which nvcc never fuses into
// an FMA (host code is compiled with -ffp-contract=off; division and square root round
// correctly on both), so both executors compute the same doubles and the same mesh.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

#include "base/hd.hpp"
#include "predicates/expansion.hpp"

namespace gpugeom::refine {

using exact::add_rn;
using exact::mul_rn;
using exact::sub_rn;

// Is the angle apb obtuse (p strictly inside the circle with diameter ab)? The sign of
// (a - p) . (b - p), exact: a floating-point filter, then the expansion of the four products.
GG_HD inline bool obtuse(const double* a, const double* b, const double* p) {
  const double ax = sub_rn(a[0], p[0]), ay = sub_rn(a[1], p[1]);
  const double bx = sub_rn(b[0], p[0]), by = sub_rn(b[1], p[1]);
  const double xx = mul_rn(ax, bx), yy = mul_rn(ay, by);
  const double dot = add_rn(xx, yy);
  const double perm = add_rn(std::fabs(xx), std::fabs(yy));
  // Each difference and product rounds once (relative 2^-53), the sum once more: 8 units of
  // 2^-53 of the permanent bound the error, away from underflow.
  const double bound = mul_rn(perm, 8.0 * 0x1p-53);
  if (perm > 1e-280 && perm < 1e290 && (dot > bound || -dot > bound)) return dot < 0;
  double e[4][2];
  int len[4];
  const double d[4][2] = {{a[0], p[0]}, {b[0], p[0]}, {a[1], p[1]}, {b[1], p[1]}};
  for (int k = 0; k < 4; ++k) {
    double hi, lo;
    exact::two_diff(d[k][0], d[k][1], hi, lo);
    len[k] = 0;
    if (lo != 0.0) e[k][len[k]++] = lo;
    if (hi != 0.0) e[k][len[k]++] = hi;
  }
  double px[8], py[8], t1[4], t2[8], sum[16];
  const int lx = exact::expansion_product(len[0], e[0], len[1], e[1], px, t1, t2);
  const int ly = exact::expansion_product(len[2], e[2], len[3], e[3], py, t1, t2);
  const int ls = exact::expansion_sum(lx, px, ly, py, sum);
  return exact::expansion_sign(ls, sum) < 0;
}

// Does p encroach upon the subsegment ab? Triangle's rule (Shewchuk's diametral lens): the angle
// apb is obtuse (p strictly inside the circle with diameter ab: the sign of (a - p) . (b - p),
// exact) and at least 180 degrees less twice the angle bound: dot^2 >= lens * |a - p|^2 |b - p|^2
// with lens = cos^2(2 bound) (1 without an angle bound: only a straight angle; 0 for the whole
// diametral circle). The lens keeps vertices that cannot make a bad triangle from splitting a
// subsegment; the comparison is in doubles, which only moves where points go, never what the
// triangulation of them is.
GG_HD inline bool encroaches(const double* a, const double* b, const double* p, double lens) {
  if (!obtuse(a, b, p)) return false;
  if (lens <= 0) return true;
  const double ax = sub_rn(a[0], p[0]), ay = sub_rn(a[1], p[1]);
  const double bx = sub_rn(b[0], p[0]), by = sub_rn(b[1], p[1]);
  const double dot = add_rn(mul_rn(ax, bx), mul_rn(ay, by));
  const double la = add_rn(mul_rn(ax, ax), mul_rn(ay, ay));
  const double lb = add_rn(mul_rn(bx, bx), mul_rn(by, by));
  return mul_rn(dot, dot) >= mul_rn(mul_rn(lens, la), lb);
}

// The squared edge lengths (l[k]: the edge opposite vertex k), twice the signed area, and the
// shortest edge (ties to the lower k, so the choice is a function of the triangle's order).
struct TriangleShape {
  double l[3];
  double area2;
  int shortest;
};
GG_HD inline TriangleShape shape_of(const double* p0, const double* p1, const double* p2) {
  const double* p[3] = {p0, p1, p2};
  TriangleShape s;
  for (int k = 0; k < 3; ++k) {
    const double* u = p[(k + 1) % 3];
    const double* v = p[(k + 2) % 3];
    const double dx = sub_rn(v[0], u[0]), dy = sub_rn(v[1], u[1]);
    s.l[k] = add_rn(mul_rn(dx, dx), mul_rn(dy, dy));
  }
  const double ux = sub_rn(p1[0], p0[0]), uy = sub_rn(p1[1], p0[1]);
  const double vx = sub_rn(p2[0], p0[0]), vy = sub_rn(p2[1], p0[1]);
  s.area2 = sub_rn(mul_rn(ux, vy), mul_rn(uy, vx));
  s.shortest = 0;
  for (int k = 1; k < 3; ++k)
    if (s.l[k] < s.l[s.shortest]) s.shortest = k;
  return s;
}
// Is the smallest angle below the bound (sin2: the square of its sine)? The smallest angle lies
// between the two longer edges, whose lengths and sine give twice the area: it is below the
// bound exactly when area2^2 < sin2 * la * lb (bounds up to 90 degrees).
GG_HD inline bool skinny(const TriangleShape& s, double sin2) {
  const int k = s.shortest;
  return mul_rn(s.area2, s.area2) < mul_rn(mul_rn(sin2, s.l[(k + 1) % 3]), s.l[(k + 2) % 3]);
}
// Ranks bad triangles, the worst first: the ratio area2^2 / (la * lb) (the squared sine of the
// smallest angle), as float bits, which order like the floats for non-negative values.
GG_HD inline std::uint32_t badness_rank(const TriangleShape& s) {
  const int k = s.shortest;
  const double r = mul_rn(s.area2, s.area2) / mul_rn(s.l[(k + 1) % 3], s.l[(k + 2) % 3]);
  const float f = float(r);
  std::uint32_t u;
  memcpy(&u, &f, sizeof u);
  return u;
}

// The circumcentre of p0 p1 p2 (counter-clockwise, not flat), from p0.
GG_HD inline void circumcentre(const double* p0, const double* p1, const double* p2, double* c) {
  const double ux = sub_rn(p1[0], p0[0]), uy = sub_rn(p1[1], p0[1]);
  const double vx = sub_rn(p2[0], p0[0]), vy = sub_rn(p2[1], p0[1]);
  const double lu = add_rn(mul_rn(ux, ux), mul_rn(uy, uy));
  const double lv = add_rn(mul_rn(vx, vx), mul_rn(vy, vy));
  const double d = mul_rn(2.0, sub_rn(mul_rn(ux, vy), mul_rn(uy, vx)));
  const double cx = sub_rn(mul_rn(vy, lu), mul_rn(uy, lv)) / d;
  const double cy = sub_rn(mul_rn(ux, lv), mul_rn(vx, lu)) / d;
  c[0] = add_rn(p0[0], cx);
  c[1] = add_rn(p0[1], cy);
}

// Ungor's off-centre for a triangle whose smallest angle is below the bound: on the bisector of
// the shortest edge (from a to b, the triangle's other vertex to its left), at the height from
// the edge's midpoint a little below where the edge subtends the bound (cot_half, about
// cot(bound / 2) / 2, times the edge's length), unless the circumcentre c is nearer; the result
// in o.
GG_HD inline void off_centre(const double* a, const double* b, const double* c, double cot_half,
                             double* o) {
  const double mx = mul_rn(0.5, add_rn(a[0], b[0])), my = mul_rn(0.5, add_rn(a[1], b[1]));
  const double ex = sub_rn(b[0], a[0]), ey = sub_rn(b[1], a[1]);
  // The inward normal (left of a->b), as long as the edge: its length times cot_half is the height.
  const double hx = mul_rn(-ey, cot_half), hy = mul_rn(ex, cot_half);
  const double dcx = sub_rn(c[0], mx), dcy = sub_rn(c[1], my);
  const double dc = add_rn(mul_rn(dcx, dcx), mul_rn(dcy, dcy));
  const double dh = add_rn(mul_rn(hx, hx), mul_rn(hy, hy));
  if (dh >= dc) {
    o[0] = c[0], o[1] = c[1];
  } else {
    o[0] = add_rn(mx, hx), o[1] = add_rn(my, hy);
  }
}

// Where a subsegment a-b is split: its midpoint, or, when exactly one end is a corner (an input
// vertex where segments meet), the point at the power of two from that end nearest to half the
// length (within a third and two thirds of it), so that splits around a corner lie on concentric
// circles and never cut a small input angle ever smaller (Ruppert's concentric shells).
GG_HD inline void split_point(const double* a, const double* b, bool corner_a, bool corner_b,
                              double* m) {
  const double ex = sub_rn(b[0], a[0]), ey = sub_rn(b[1], a[1]);
  if (corner_a == corner_b) {
    m[0] = mul_rn(0.5, add_rn(a[0], b[0]));
    m[1] = mul_rn(0.5, add_rn(a[1], b[1]));
    return;
  }
  const double len = std::sqrt(add_rn(mul_rn(ex, ex), mul_rn(ey, ey)));
  double d = 1.0;
  while (d > mul_rn(len, 2.0 / 3.0)) d = mul_rn(d, 0.5);
  while (d < mul_rn(len, 1.0 / 3.0)) d = mul_rn(d, 2.0);
  const double f = corner_a ? d / len : sub_rn(1.0, d / len);
  m[0] = add_rn(a[0], mul_rn(ex, f));
  m[1] = add_rn(a[1], mul_rn(ey, f));
}

// Bilinear sample of an area grid at (x, y), clamped to the grid.
GG_HD inline double grid_sample(const double* v, std::int64_t rows, std::int64_t cols, double x0,
                                double y0, double x1, double y1, double x, double y) {
  auto coord = [](double t, double lo, double hi, std::int64_t n, std::int64_t& i, double& f) {
    double u = n > 1 ? mul_rn(sub_rn(t, lo) / sub_rn(hi, lo), double(n - 1)) : 0.0;
    u = u < 0 ? 0 : (u > double(n - 1) ? double(n - 1) : u);
    i = std::int64_t(u);
    if (i >= n - 1) i = n > 1 ? n - 2 : 0;
    f = n > 1 ? sub_rn(u, double(i)) : 0.0;
  };
  std::int64_t c, r;
  double fx, fy;
  coord(x, x0, x1, cols, c, fx);
  coord(y, y0, y1, rows, r, fy);
  const std::int64_t c1 = cols > 1 ? c + 1 : c, r1 = rows > 1 ? r + 1 : r;
  const double top = add_rn(mul_rn(v[r * cols + c], sub_rn(1.0, fx)), mul_rn(v[r * cols + c1], fx));
  const double bot =
      add_rn(mul_rn(v[r1 * cols + c], sub_rn(1.0, fx)), mul_rn(v[r1 * cols + c1], fx));
  return add_rn(mul_rn(top, sub_rn(1.0, fy)), mul_rn(bot, fy));
}

}  // namespace gpugeom::refine
