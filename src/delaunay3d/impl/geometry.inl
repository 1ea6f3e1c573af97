// Predicates on the extended tetrahedralisation (thesis 6.4 in 3D), included inside
// gpugeom::del3d::{cpu,cuda,host}_impl.
//
// The points are the m distinct input points in curve order; vertex index m is the infinity
// point. In orientation tests it stands for the kernel point s (inside the first tetrahedron,
// and so inside every later hull) with the sign reversed: the boundary stays star-shaped from
// s, and the outside is split into the cones from s over the boundary triangles, so an
// outside point lies in exactly one infinite tetrahedron. In the Delaunay test an infinite
// tetrahedron (a, b, c, inf) has as its sphere the open half-space beyond its finite face (the
// limit of the spheres through a, b, c), i.e. a point q is inside when the tetrahedron with q
// in place of the infinity point is positively oriented. s takes index m and is perturbed by its
// coordinates like any point, so every test is perturbed consistently and never ties. Where the
// filter cannot tell, whole-number points (grids) are decided in integers, and anything else
// runs the exact stages on scratch borrowed from the pool (exec/scratch_lease.hpp), which
// threads may have to wait for.

struct Geo {
  const double* p;  // 3 per point
  double s[3];      // kernel point
  std::int32_t m;   // number of points = index of the infinity vertex
  ScratchLease lease;
  GG_INLINE const double* at(std::int32_t i) const { return i == m ? s : p + 3 * std::int64_t(i); }
};

GG_INLINE std::uint32_t lease_hint(std::int32_t a, std::int32_t b) {
  return std::uint32_t(a) * 2654435761u ^ std::uint32_t(b) * 40503u;
}

// The tiers past the floating-point filters (integers, double-word, SoS, the exact stages on
// leased scratch), out of line: rare on most inputs, and inlined into every kernel that tests
// they held those kernels at 240-255 registers and 1.5-2 KB of stack (8 warps a
// multiprocessor for the flip rounds' test). Each repeats its filter, which is cheap beside it.
GG_COLD int orient_rest(const double* pa, std::int32_t a, const double* pb, std::int32_t b,
                        const double* pc, std::int32_t c, const double* pd, std::int32_t d,
                        ScratchLease lease) {
  int r = pred::orient3d_sos_quick(pa, a, pb, b, pc, c, pd, d);
  if (r == pred::kUndecided) {
    double* s = lease.acquire(lease_hint(a, d));
    r = pred::orient3d_sos(pa, a, pb, b, pc, c, pd, d, s);
    lease.release(s);
  }
  return r;
}
GG_COLD int in_sphere_rest(const double* a, std::int32_t ia, const double* b, std::int32_t ib,
                           const double* c, std::int32_t ic, const double* d, std::int32_t id,
                           const double* e, std::int32_t q, ScratchLease lease) {
  int r = pred::insphere_sos_quick(a, ia, b, ib, c, ic, d, id, e, q);
  if (r == pred::kUndecided) {
    double* s = lease.acquire(lease_hint(ia, q));
    r = pred::insphere_sos(a, ia, b, ib, c, ic, d, id, e, q, s);
    lease.release(s);
  }
  return r;
}

// Orientation with the infinity vertex standing for s, sign reversed (at most one of the four
// is the infinity vertex).
GG_HD inline int orient_ext(const Geo& g, std::int32_t a, std::int32_t b, std::int32_t c,
                            std::int32_t d) {
  const int flip = (a == g.m || b == g.m || c == g.m || d == g.m) ? -1 : 1;
  const double *pa = g.at(a), *pb = g.at(b), *pc = g.at(c), *pd = g.at(d);
  if (const int r = pred::orient3d_fast(pa, pb, pc, pd)) return flip * r;
  return flip * orient_rest(pa, a, pb, b, pc, c, pd, d, g.lease);
}

// The tetrahedron v with its vertex k replaced by q.
GG_INLINE int orient_with(const Geo& g, const std::int32_t* v, int k, std::int32_t q) {
  std::int32_t w[4] = {v[0], v[1], v[2], v[3]};
  w[k] = q;
  return orient_ext(g, w[0], w[1], w[2], w[3]);
}

// Is q strictly inside the (positively oriented) tetrahedron v?
GG_HD inline bool inside_ext(const Geo& g, const std::int32_t* v, std::int32_t q) {
  for (int k = 0; k < 4; ++k)
    if (orient_with(g, v, k, q) <= 0) return false;
  return true;
}

// Is q inside the sphere of the positively oriented tetrahedron v (see above for infinite
// ones)? The infinity point is inside no sphere.
GG_HD inline bool in_sphere_ext(const Geo& g, const std::int32_t* v, std::int32_t q) {
  if (q == g.m) return false;
  for (int k = 0; k < 4; ++k)
    if (v[k] == g.m) return orient_with(g, v, k, q) > 0;
  const double *a = g.at(v[0]), *b = g.at(v[1]), *c = g.at(v[2]), *d = g.at(v[3]), *e = g.at(q);
  // (the semi-static bound first: the cavities' tests are most of the CPU's time, and it
  // decides nearly all of them; in_sphere_rest starts with the permanent's sharper bound)
  if (const int r = pred::insphere_semistatic(a, b, c, d, e)) return r > 0;
  return in_sphere_rest(a, v[0], b, v[1], c, v[2], d, v[3], e, q, g.lease) > 0;
}

// Is the finite tetrahedron v flat: its four points exactly on one plane (the perturbation
// orders them; such layers lie over hull facets' planes, and the output leaves them out)? An
// infinite tetrahedron is not.
GG_HD inline bool flat_ext(const Geo& g, const std::int32_t* v) {
  for (int k = 0; k < 4; ++k)
    if (v[k] == g.m) return false;
  const double *a = g.at(v[0]), *b = g.at(v[1]), *c = g.at(v[2]), *d = g.at(v[3]);
  if (pred::orient3d_fast(a, b, c, d) != 0) return false;
  int o;
  if (!exact::orient3d_int(a, b, c, d, o)) {
    double* s = g.lease.acquire(lease_hint(v[0], v[3]));
    o = pred::orient3d(a, b, c, d, s);
    g.lease.release(s);
  }
  return o == 0;
}

// Faces of a tetrahedron (v0, v1, v2, v3): the face opposite vertex k, listed so that it is
// oriented outward (the tetrahedron lies on its negative side); the tetrahedron (v_k, face)
// is then positively oriented.
GG_INLINE int face_vertex(int k, int i) {
  // {1,2,3}, {0,3,2}, {0,1,3}, {0,2,1}: four bits per entry, row k from bit 12 k
  constexpr std::uint64_t kFaces =
      0x123ull | (0x032ull << 12) | (0x013ull << 24) | (0x021ull << 36);
  return int((kFaces >> (12 * k + 4 * (2 - i))) & 0xFu);
}

// The local index of the vertex of v not among the face (a, b, c), or -1 when v does not have
// that face.
GG_INLINE int opposite_of_face(const std::int32_t* v, std::int32_t a, std::int32_t b,
                               std::int32_t c) {
  int found = 0, other = -1;
  for (int k = 0; k < 4; ++k) {
    if (v[k] == a || v[k] == b || v[k] == c)
      ++found;
    else
      other = k;
  }
  return found == 3 ? other : -1;
}

// Order-preserving map of a float to 32 bits (NaN sorts last).
GG_INLINE std::uint32_t ordered_bits(float f) {
  if (f != f) return 0xFFFFFFFFu;
  std::uint32_t u;
  memcpy(&u, &f, 4);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

// Which point a tetrahedron takes in the next batch: the one nearest its circumcentre (thesis
// 5.3.3); for an infinite tetrahedron, whose circumcentre is at infinity beyond its face, the
// one farthest beyond the face, or where that cannot separate the points (points in the
// face's plane) the one nearest the face's centroid; for slivers the one nearest the centroid.
// Smaller is better; the choice only steers the work, never the result. (Every operation
// rounded on its own, so that both executors choose the same points.)
GG_HD inline std::uint32_t choice_key(const Geo& g, const std::int32_t* v, std::int32_t q) {
  using pred::add_rn;
  using pred::mul_rn;
  using pred::sub_rn;
  const double* pq = g.at(q);
  auto dot = [](const double* x, const double* y) {
    return add_rn(add_rn(mul_rn(x[0], y[0]), mul_rn(x[1], y[1])), mul_rn(x[2], y[2]));
  };
  auto cross = [](const double* x, const double* y, double* z) {
    z[0] = sub_rn(mul_rn(x[1], y[2]), mul_rn(x[2], y[1]));
    z[1] = sub_rn(mul_rn(x[2], y[0]), mul_rn(x[0], y[2]));
    z[2] = sub_rn(mul_rn(x[0], y[1]), mul_rn(x[1], y[0]));
  };
  int gi = -1;
  for (int k = 0; k < 4; ++k)
    if (v[k] == g.m) gi = k;
  if (gi >= 0) {
    const double* a = g.at(v[face_vertex(gi, 0)]);
    const double* b = g.at(v[face_vertex(gi, 1)]);
    const double* c = g.at(v[face_vertex(gi, 2)]);
    double u[3], w[3], nrm[3], d[3], mid[3];
    for (int i = 0; i < 3; ++i) {
      u[i] = sub_rn(b[i], a[i]);
      w[i] = sub_rn(c[i], a[i]);
      d[i] = sub_rn(pq[i], a[i]);
    }
    // The face is listed outward from this tetrahedron, so (b - a) x (c - a) points back into
    // the hull; its reverse points to the infinite side, where the points are. (Taking the
    // face's own normal here once chose the point nearest the face: the hull then grew by a
    // sliver per batch, and uniform 10^5 took 75 batches and 2 300 flip rounds instead of 10
    // and 190.)
    cross(w, u, nrm);
    const double n2 = dot(nrm, nrm), o = dot(nrm, d);
    if (o > 0 && mul_rn(o, o) > mul_rn(1e-12, mul_rn(n2, dot(d, d))))
      return ordered_bits(float(-o / n2));
    for (int i = 0; i < 3; ++i) mid[i] = sub_rn(pq[i], add_rn(add_rn(a[i], b[i]), c[i]) / 3);
    return ordered_bits(float(dot(mid, mid)));
  }
  const double *a = g.at(v[0]), *b = g.at(v[1]), *c = g.at(v[2]), *d = g.at(v[3]);
  double u[3], w[3], x[3], qa[3], uw[3], wx[3], xu[3];
  for (int i = 0; i < 3; ++i) {
    u[i] = sub_rn(b[i], a[i]);
    w[i] = sub_rn(c[i], a[i]);
    x[i] = sub_rn(d[i], a[i]);
    qa[i] = sub_rn(pq[i], a[i]);
  }
  cross(w, x, wx);
  cross(x, u, xu);
  cross(u, w, uw);
  const double det = mul_rn(2.0, dot(u, wx));
  const double u2 = dot(u, u), w2 = dot(w, w), x2 = dot(x, x);
  const double scale = mul_rn(mul_rn(u2, w2), x2);
  double cc[3];
  if (!(mul_rn(det, det) > mul_rn(1e-12, scale))) {  // sliver: use the centroid
    for (int i = 0; i < 3; ++i) cc[i] = add_rn(add_rn(u[i], w[i]), x[i]) / 4;
  } else {
    for (int i = 0; i < 3; ++i)
      cc[i] = add_rn(add_rn(mul_rn(u2, wx[i]), mul_rn(w2, xu[i])), mul_rn(x2, uw[i])) / det;
  }
  double dd[3];
  for (int i = 0; i < 3; ++i) dd[i] = sub_rn(qa[i], cc[i]);
  return ordered_bits(float(dot(dd, dd)));
}
