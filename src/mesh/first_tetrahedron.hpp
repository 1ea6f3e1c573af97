// The first tetrahedron of a 3D mesh module (thesis 6.4), on the executor: hull3d's
// construction and delaunay3d's extended triangulation both start from it.
//
// The lexicographically smallest and largest points, the point farthest from their line, the
// point farthest from the plane of the three (by a rounded measure with every operation rounded
// on its own, so both executors pick the same points; the choice is then checked exactly, with
// an exact scan when the rounded one was degenerate). Throws Error(DegenerateInput) naming the
// case when there is none, and Error(InvalidInput) for coordinates the exact predicates cannot
// take.
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "base/hd.hpp"
#include "gpugeom/common.hpp"
#include "mesh/prepare.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::mesh {

struct MinIndex {
  GG_HD std::int32_t operator()(std::int32_t a, std::int32_t b) const { return a < b ? a : b; }
};

GG_HD inline bool collinear3(const double* a, const double* b, const double* c) {
  double s[pred::kOrient2dScratch];
  for (int i = 0; i < 3; ++i) {  // collinear iff every coordinate-plane projection is
    const int x = i, y = (i + 1) % 3;
    const double pa[2] = {a[x], a[y]}, pb[2] = {b[x], b[y]}, pc[2] = {c[x], c[y]};
    if (pred::orient2d(pa, pb, pc, s) != 0) return false;
  }
  return true;
}
GG_HD inline bool same_point(const double* a, const double* b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

// bad: the coordinates the exact predicates cannot take (mesh::bounds counts coordinates).
inline void throw_bad_coordinates(std::int64_t bad) {
  throw Error(ErrorCode::InvalidInput,
              std::to_string(bad) +
                  " point coordinate(s) are NaN, infinite or outside the range the exact "
                  "predicates support (0 or magnitude in [1.8e-43, 1.5e54]); remove or rescale "
                  "those points");
}

struct Tetra {
  std::int32_t v[4];
  double s[3];
};
// A point strictly inside the tetrahedron V (exactly): its centroid almost always. In a very
// thin one (coordinates of very different magnitudes: one vertex at 1e40, three at 1e-31) the
// rounded centroid can fall outside, and then the cones from it over the faces, which the
// triangulations use to locate points beyond the hull, overlap and leave gaps; so weighted means
// with some vertices made ever lighter (weights 1 : 2^j) are tried until one is inside. The
// centroid where none is (not seen).
inline void kernel_of(const double* const V[4], double s[3]) {
  double sc[pred::kOrient3dScratch];
  const int o = pred::orient3d(V[0], V[1], V[2], V[3], sc);
  auto inside = [&](const double* c) {
    for (int k = 0; k < 4; ++k) {
      const double* W[4] = {V[0], V[1], V[2], V[3]};
      W[k] = c;
      if (pred::orient3d(W[0], W[1], W[2], W[3], sc) != o) return false;
    }
    return true;
  };
  for (int k = 0; k < 3; ++k) s[k] = (V[0][k] + V[1][k] + V[2][k] + V[3][k]) / 4;
  if (inside(s)) return;
  for (int light = 1; light < 15; ++light)  // the set of light vertices, as bits
    for (int j = 1; j < 1000; j += 3) {
      const int nl = __builtin_popcount(unsigned(light));
      const double w = std::ldexp(1.0, j);  // the heavy ones' weight, the light ones' 1
      const double tot = nl + (4 - nl) * w;
      const double a = 1.0 / tot, b = w / tot;  // (no overflow)
      double c[3];
      bool exact_range = true;
      for (int k = 0; k < 3; ++k) {
        double l = 0, h = 0;
        for (int i = 0; i < 4; ++i) (light >> i & 1 ? l : h) += V[i][k];
        c[k] = a * l + b * h;
        exact_range = exact_range && pred::in_exact_range(c[k]);
      }
      if (exact_range && inside(c)) {
        for (int k = 0; k < 3; ++k) s[k] = c[k];
        return;
      }
    }
}

// v: positively oriented when `positive` (delaunay3d), else negatively (hull3d: the fourth point
// lies below the first three); s: the centroid. n_input: the caller's point count, for the
// messages (p holds n distinct points of them); what: the structure asked for ("a convex
// hull").
template <class Exec>
Tetra first_tetrahedron(Exec& ex, const double* p, std::int64_t n, std::int64_t n_input,
                        const char* what, bool positive) {
  using C3 = Cand<3>;
  const Extremes<3> x = extremes<3>(ex, p, n);
  if (x.bad) throw_bad_coordinates(x.bad);
  const C3 lo = x.lo, hi = x.hi;
  const double A[3] = {lo.x[0], lo.x[1], lo.x[2]}, B[3] = {hi.x[0], hi.x[1], hi.x[2]};
  if (same_point(A, B))  // (one distinct point)
    throw Error(ErrorCode::DegenerateInput, "all " + std::to_string(n_input) +
                                                " points coincide: " + what +
                                                " needs 4 points not on one plane");
  const std::int32_t ia = lo.i, ib = hi.i;
  const double ax = A[0], ay = A[1], az = A[2], ux = B[0] - A[0], uy = B[1] - A[1],
               uz = B[2] - A[2];
  C3 c = reduce_cand<3>(
      ex, n,
      GG_LAMBDA(std::int64_t i)->C3 {
        // Rounded operations one by one (no FMA contraction, which nvcc would apply and g++
        // here does not): both executors then pick the same point.
        using pred::add_rn, pred::mul_rn, pred::sub_rn;
        const double* q = p + 3 * i;
        const double wx = sub_rn(q[0], ax), wy = sub_rn(q[1], ay), wz = sub_rn(q[2], az);
        const double cx = sub_rn(mul_rn(uy, wz), mul_rn(uz, wy)),
                     cy = sub_rn(mul_rn(uz, wx), mul_rn(ux, wz)),
                     cz = sub_rn(mul_rn(ux, wy), mul_rn(uy, wx));
        const double len2 = add_rn(add_rn(mul_rn(cx, cx), mul_rn(cy, cy)), mul_rn(cz, cz));
        return cand_of<3>(p, i, len2);
      },
      Farthest<3>{});
  double C[3] = {c.x[0], c.x[1], c.x[2]};  // (the reduction carries the point along)
  if (collinear3(A, B, C)) {  // rounding hid a tiny offset, or the input is on one line
    auto out = ex.template alloc<std::int32_t>(1);
    ex.transform_reduce_into(
        n,
        GG_LAMBDA(std::int64_t i)->std::int32_t {
          return collinear3(p + 3 * std::int64_t(ia), p + 3 * std::int64_t(ib), p + 3 * i)
                     ? std::numeric_limits<std::int32_t>::max()
                     : std::int32_t(i);
        },
        std::numeric_limits<std::int32_t>::max(), MinIndex{}, out.data());
    std::int32_t any = 0;
    ex.to_host(out.data(), 1, &any);
    if (any == std::numeric_limits<std::int32_t>::max())
      throw Error(ErrorCode::DegenerateInput, "all " + std::to_string(n_input) +
                                                  " points lie on one line: " + what +
                                                  " needs 4 points not on one plane");
    c.i = any;
    ex.to_host(p + 3 * std::int64_t(c.i), 3, C);
  }
  const std::int32_t ic = c.i;
  C3 d = reduce_cand<3>(
      ex, n,
      GG_LAMBDA(std::int64_t i)->C3 {
        const double *pa = p + 3 * std::int64_t(ia), *pb = p + 3 * std::int64_t(ib),
                     *pc = p + 3 * std::int64_t(ic), *q = p + 3 * i;
        using pred::add_rn, pred::mul_rn, pred::sub_rn;  // no FMA: as above
        double u[3], v[3], w[3];
        for (int k = 0; k < 3; ++k)
          u[k] = sub_rn(pb[k], pa[k]), v[k] = sub_rn(pc[k], pa[k]), w[k] = sub_rn(q[k], pa[k]);
        const double det =
            add_rn(add_rn(mul_rn(w[0], sub_rn(mul_rn(u[1], v[2]), mul_rn(u[2], v[1]))),
                          mul_rn(w[1], sub_rn(mul_rn(u[2], v[0]), mul_rn(u[0], v[2])))),
                   mul_rn(w[2], sub_rn(mul_rn(u[0], v[1]), mul_rn(u[1], v[0]))));
        return cand_of<3>(p, i, det < 0 ? -det : det);
      },
      Farthest<3>{});
  double D[3] = {d.x[0], d.x[1], d.x[2]};
  {
    double s[pred::kOrient3dScratch];
    if (pred::orient3d(A, B, C, D, s) == 0) {
      auto out = ex.template alloc<std::int32_t>(1);
      ex.transform_reduce_into(
          n,
          GG_LAMBDA(std::int64_t i)->std::int32_t {
            const double *pa = p + 3 * std::int64_t(ia), *pb = p + 3 * std::int64_t(ib),
                         *pc = p + 3 * std::int64_t(ic), *q = p + 3 * i;
            if (pred::orient3d_fast(pa, pb, pc, q) != 0) return std::int32_t(i);
            double sc[pred::kOrient3dScratch];  // only inputs this degenerate come here
            return pred::orient3d_exact(pa, pb, pc, q, sc) != 0
                       ? std::int32_t(i)
                       : std::numeric_limits<std::int32_t>::max();
          },
          std::numeric_limits<std::int32_t>::max(), MinIndex{}, out.data());
      std::int32_t any = 0;
      ex.to_host(out.data(), 1, &any);
      if (any == std::numeric_limits<std::int32_t>::max())
        throw Error(ErrorCode::DegenerateInput,
                    "all " + std::to_string(n_input) +
                        " points lie on one plane (or there are fewer than 4 distinct points): " +
                        what + " needs 4 points not on one plane");
      d.i = any;
      ex.to_host(p + 3 * std::int64_t(d.i), 3, D);
    }
  }
  Tetra t;
  t.v[0] = ia, t.v[1] = ib, t.v[2] = ic, t.v[3] = d.i;
  double s[pred::kOrient3dScratch];
  if ((pred::orient3d(A, B, C, D, s) > 0) != positive) std::swap(t.v[1], t.v[2]);
  const double* V[4] = {A, B, C, D};
  kernel_of(V, t.s);
  return t;
}

}  // namespace gpugeom::mesh
