// Predicates on the extended triangulation (thesis 6.4), included inside
// gpugeom::del2d::{cpu,cuda}_impl.
//
// The points are the m distinct input points in curve order; vertex index m is the infinity
// point. In orientation tests it stands for the kernel point s (inside the first triangle, and
// so inside every later hull) with the sign reversed, which makes the boundary of the
// triangulation star-shaped from s and splits the outside into the cones from s over the
// boundary edges: an outside point lies in exactly one infinite triangle. In the Delaunay test
// an infinite triangle (a, b, inf) has the open half-plane left of a->b as its circle, the
// limit of the circles through a and b. s takes index m (which orders it only after an input
// point it equals: the perturbation follows coordinates), so every test is perturbed
// consistently and never ties.

using pred::kIncircleScratch;
using pred::kOrient2dScratch;

struct Geo {
  const double* p;  // 2 per point
  double s[2];      // kernel point
  std::int32_t m;   // number of points = index of the infinity vertex
  GG_INLINE const double* at(std::int32_t i) const { return i == m ? s : p + 2 * std::int64_t(i); }
};

// A tie of the filter, by the perturbation: out of line (rare; with its scratch inlined, the
// whole test stayed a call, a tenth of the CPU executor's insertion time, most of it walks).
GG_COLD int orient_tie(const double* pa, std::int32_t a, const double* pb, std::int32_t b,
                       const double* pc, std::int32_t c) {
  double scratch[kOrient2dScratch];
  return pred::orient2d_sos(pa, a, pb, b, pc, c, scratch);
}
// Orientation with the infinity vertex standing for s, sign reversed; q is finite.
GG_ALWAYS_INLINE int orient_ext(const Geo& g, std::int32_t a, std::int32_t b, std::int32_t c) {
  const int flip = (a == g.m || b == g.m || c == g.m) ? -1 : 1;
  const double *pa = g.at(a), *pb = g.at(b), *pc = g.at(c);
  int r = pred::orient2d_fast(pa, pb, pc);
  if (!r) r = orient_tie(pa, a, pb, b, pc, c);
  return flip * r;
}

// Is q inside triangle t (vertices v)? Exactly one triangle of the extended triangulation
// contains each point not yet inserted.
GG_HD inline bool inside_ext(const Geo& g, const std::int32_t* v, std::int32_t q) {
  return orient_ext(g, v[0], v[1], q) > 0 && orient_ext(g, v[1], v[2], q) > 0 &&
         orient_ext(g, v[2], v[0], q) > 0;
}

// Edge-legality decision for triangle v and the vertex d opposite its edge across from v[k]:
// +1 illegal (flip), -1 legal, 0 the filter cannot tell (the exact pass decides).
GG_HD inline int illegal_fast(const Geo& g, const std::int32_t* v, std::int32_t d) {
  if (d == g.m) return -1;  // the infinity vertex is outside every circle
  int gi = v[0] == g.m ? 0 : v[1] == g.m ? 1 : v[2] == g.m ? 2 : -1;
  if (gi >= 0) {  // half-plane left of the finite edge
    const std::int32_t a = v[(gi + 1) % 3], b = v[(gi + 2) % 3];
    return pred::orient2d_fast(g.at(a), g.at(b), g.at(d));
  }
  return pred::incircle_fast(g.at(v[0]), g.at(v[1]), g.at(v[2]), g.at(d));
}
GG_HD inline int illegal_exact(const Geo& g, const std::int32_t* v, std::int32_t d,
                               double* scratch) {
  int gi = v[0] == g.m ? 0 : v[1] == g.m ? 1 : v[2] == g.m ? 2 : -1;
  if (gi >= 0) {
    const std::int32_t a = v[(gi + 1) % 3], b = v[(gi + 2) % 3];
    return pred::orient2d_sos(g.at(a), a, g.at(b), b, g.at(d), d, scratch);
  }
  return pred::incircle_sos(g.at(v[0]), v[0], g.at(v[1]), v[1], g.at(v[2]), v[2], g.at(d), d,
                            scratch);
}

// Order-preserving map of a float to 32 bits (NaN sorts last).
GG_INLINE std::uint32_t ordered_bits(float f) {
  if (f != f) return 0xFFFFFFFFu;
  std::uint32_t u;
  memcpy(&u, &f, 4);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

// Which point a triangle takes in the next batch: the one nearest its circumcentre (thesis
// 5.3.3); for an infinite triangle, whose circumcentre is at infinity beyond its edge, the one
// farthest beyond the edge. Where that measure cannot separate the points (nearly flat
// triangles, points on the line of a hull edge) the one nearest the middle of the triangle or
// edge: taking the nearest to an end would cost one batch per point on collinear input.
// Smaller is better; the choice only steers the work, never the result.
// (Every product and sum rounded on its own, as on the CPU: nvcc would otherwise contract to
// FMA, and the two executors would choose differently on near-ties.)
GG_HD inline std::uint32_t choice_key(const Geo& g, const std::int32_t* v, std::int32_t q) {
  using pred::add_rn;
  using pred::mul_rn;
  using pred::sub_rn;
  const double* pq = g.at(q);
  int gi = v[0] == g.m ? 0 : v[1] == g.m ? 1 : v[2] == g.m ? 2 : -1;
  if (gi >= 0) {
    const double *a = g.at(v[(gi + 1) % 3]), *b = g.at(v[(gi + 2) % 3]);
    const double ex = sub_rn(b[0], a[0]), ey = sub_rn(b[1], a[1]);
    const double o = sub_rn(mul_rn(ex, sub_rn(pq[1], a[1])), mul_rn(ey, sub_rn(pq[0], a[0])));
    const double e2 = add_rn(mul_rn(ex, ex), mul_rn(ey, ey));  // o = |ab| * distance beyond
    if (o > mul_rn(1e-6, e2)) return ordered_bits(float(-o / e2));
    const double mx = sub_rn(pq[0], mul_rn(0.5, add_rn(a[0], b[0])));
    const double my = sub_rn(pq[1], mul_rn(0.5, add_rn(a[1], b[1])));
    return ordered_bits(float(add_rn(mul_rn(mx, mx), mul_rn(my, my)) / e2));
  }
  const double *a = g.at(v[0]), *b = g.at(v[1]), *c = g.at(v[2]);
  const double bx = sub_rn(b[0], a[0]), by = sub_rn(b[1], a[1]);
  const double cx = sub_rn(c[0], a[0]), cy = sub_rn(c[1], a[1]);
  const double d = mul_rn(2.0, sub_rn(mul_rn(bx, cy), mul_rn(by, cx)));
  const double b2 = add_rn(mul_rn(bx, bx), mul_rn(by, by));
  const double c2 = add_rn(mul_rn(cx, cx), mul_rn(cy, cy));
  const double qx = sub_rn(pq[0], a[0]), qy = sub_rn(pq[1], a[1]);
  if (!(mul_rn(d, d) > mul_rn(mul_rn(1e-12, b2), c2))) {  // sliver: far circumcentre, use the
    const double mx = sub_rn(qx, add_rn(bx, cx) / 3);     // centroid
    const double my = sub_rn(qy, add_rn(by, cy) / 3);
    return ordered_bits(float(add_rn(mul_rn(mx, mx), mul_rn(my, my))));
  }
  const double ux = sub_rn(mul_rn(cy, b2), mul_rn(by, c2)) / d;
  const double uy = sub_rn(mul_rn(bx, c2), mul_rn(cx, b2)) / d;
  const double dx = sub_rn(qx, ux), dy = sub_rn(qy, uy);
  return ordered_bits(float(add_rn(mul_rn(dx, dx), mul_rn(dy, dy))));
}
