// Input checks and the first tetrahedron (thesis 6.4), on the executor; included inside
// gpugeom::hull3d::{cpu,cuda}_impl after geometry.inl.

// A point and its index, ordered lexicographically by (x, y, z) then index; `key` holds a
// distance for the farthest-point reductions.
struct Cand {
  double x, y, z, key;
  std::int32_t i;
};
GG_HD inline bool lex_less(const Cand& a, const Cand& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  if (a.z != b.z) return a.z < b.z;
  return a.i < b.i;
}
struct MinLex {
  GG_HD Cand operator()(const Cand& a, const Cand& b) const { return lex_less(a, b) ? a : b; }
};
struct MaxLex {  // largest coordinates, then the smaller index
  GG_HD Cand operator()(const Cand& a, const Cand& b) const {
    if (a.x != b.x || a.y != b.y || a.z != b.z) return lex_less(a, b) ? b : a;
    return a.i < b.i ? a : b;
  }
};
struct Farthest {
  GG_HD Cand operator()(const Cand& a, const Cand& b) const {
    if (a.key != b.key) return a.key > b.key ? a : b;
    return a.i < b.i ? a : b;
  }
};
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

// Can the exact predicates take every coordinate of point q? (No NaN, Inf, or magnitudes out of
// range.)
GG_HD inline bool exact_ok(const double* q) {
  return pred::in_exact_range(q[0]) && pred::in_exact_range(q[1]) && pred::in_exact_range(q[2]);
}

// The input check and both lexicographic extremes in one pass: the count of points the exact
// predicates cannot take, and the smallest and largest point (meaningful once the count is 0).
struct Scan0 {
  Cand lo, hi;
  std::int64_t bad;
};
struct Scan0Op {
  GG_HD Scan0 operator()(const Scan0& a, const Scan0& b) const {
    return Scan0{MinLex{}(a.lo, b.lo), MaxLex{}(a.hi, b.hi), a.bad + b.bad};
  }
};
inline void throw_bad(std::int64_t bad) {
  throw Error(ErrorCode::InvalidInput,
              std::to_string(bad) +
                  " point(s) have a coordinate that is NaN, infinite or outside the exactly "
                  "representable range (magnitude 1.8e-43 .. 1.5e54, or 0)");
}

// The reduction of f over the points; init is the identity for each op (validated points are
// finite, so the infinities lose every comparison).
template <class F, class Op>
Cand reduce_cand(Exec& ex, std::int64_t n, F f, Op op, double start = 0) {
  auto out = ex.template alloc<Cand>(1);
  const Cand init{start, start, start, -1, std::numeric_limits<std::int32_t>::max()};
  ex.transform_reduce_into(n, f, init, op, out.data());
  Cand h;
  ex.to_host(out.data(), 1, &h);
  return h;
}

// The first tetrahedron (after the input check: Error(InvalidInput) for points the exact
// predicates cannot take): the lexicographically smallest and largest points, the point
// farthest from their line, the point farthest from the plane of the three (by the rounded
// measure; the choice is then checked exactly, with an exact scan when the rounded one was
// degenerate). Throws Error(DegenerateInput) naming the case when there is none.
struct Tetra {
  std::int32_t v[4];
  double s[3];
};
inline Tetra first_tetrahedron(Exec& ex, const double* p, std::int64_t n) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::int32_t none = std::numeric_limits<std::int32_t>::max();
  auto ext = ex.template alloc<Scan0>(1);
  ex.transform_reduce_into(
      n,
      GG_LAMBDA(std::int64_t i)->Scan0 {
        const double* q = p + 3 * i;
        const Cand c{q[0], q[1], q[2], 0.0, std::int32_t(i)};
        return Scan0{c, c, exact_ok(q) ? 0 : 1};
      },
      Scan0{Cand{inf, inf, inf, -1, none}, Cand{-inf, -inf, -inf, -1, none}, 0}, Scan0Op{},
      ext.data());
  Scan0 x;
  ex.to_host(ext.data(), 1, &x);
  if (x.bad) throw_bad(x.bad);
  const Cand lo = x.lo, hi = x.hi;
  const double A[3] = {lo.x, lo.y, lo.z}, B[3] = {hi.x, hi.y, hi.z};
  if (same_point(A, B))
    throw Error(ErrorCode::DegenerateInput, "all " + std::to_string(n) +
                                                " points coincide: a convex hull needs 4 points "
                                                "not on one plane");
  const std::int32_t ia = lo.i, ib = hi.i;
  const double ax = A[0], ay = A[1], az = A[2], ux = B[0] - A[0], uy = B[1] - A[1],
               uz = B[2] - A[2];
  Cand c = reduce_cand(
      ex, n,
      GG_LAMBDA(std::int64_t i)->Cand {
        // Rounded operations one by one (no FMA contraction, which nvcc would apply and g++
        // here does not): both executors then pick the same point.
        using pred::add_rn, pred::mul_rn, pred::sub_rn;
        const double* q = p + 3 * i;
        const double wx = sub_rn(q[0], ax), wy = sub_rn(q[1], ay), wz = sub_rn(q[2], az);
        const double cx = sub_rn(mul_rn(uy, wz), mul_rn(uz, wy)),
                     cy = sub_rn(mul_rn(uz, wx), mul_rn(ux, wz)),
                     cz = sub_rn(mul_rn(ux, wy), mul_rn(uy, wx));
        const double len2 = add_rn(add_rn(mul_rn(cx, cx), mul_rn(cy, cy)), mul_rn(cz, cz));
        return Cand{q[0], q[1], q[2], len2, std::int32_t(i)};
      },
      Farthest{});
  double C[3] = {c.x, c.y, c.z};  // (the reduction carries the point along)
  if (collinear3(A, B, C)) {      // rounding hid a tiny offset, or the input is on one line
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
      throw Error(ErrorCode::DegenerateInput,
                  "all " + std::to_string(n) +
                      " points lie on one line: a convex hull needs 4 points not on one plane");
    c.i = any;
    ex.to_host(p + 3 * std::int64_t(c.i), 3, C);
  }
  const std::int32_t ic = c.i;
  Cand d = reduce_cand(
      ex, n,
      GG_LAMBDA(std::int64_t i)->Cand {
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
        return Cand{q[0], q[1], q[2], det < 0 ? -det : det, std::int32_t(i)};
      },
      Farthest{});
  double D[3] = {d.x, d.y, d.z};
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
                    "all " + std::to_string(n) +
                        " points lie on one plane (or there are fewer than 4 distinct points): "
                        "a convex hull in 3D needs 4 points not on one plane");
      d.i = any;
      ex.to_host(p + 3 * std::int64_t(d.i), 3, D);
    }
  }
  Tetra t;
  t.v[0] = ia, t.v[1] = ib, t.v[2] = ic, t.v[3] = d.i;
  double s[pred::kOrient3dScratch];
  if (pred::orient3d(A, B, C, D, s) > 0) std::swap(t.v[1], t.v[2]);  // make d lie below abc
  for (int k = 0; k < 3; ++k) t.s[k] = (A[k] + B[k] + C[k] + D[k]) / 4;
  return t;
}
