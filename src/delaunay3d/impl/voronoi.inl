// The Voronoi diagram of 3D points, dual to their Delaunay tetrahedralisation (issue 49),
// computed on the executor from the tetrahedralisation's arrays (as Triangulation3d has them:
// 4 vertices and 4 neighbours per tetrahedron, -1 across the hull). Included inside
// gpugeom::del3d::{cpu,cuda}_impl.
//
// - Vertices: one per sphere. Tetrahedra across a face whose five points lie on one sphere
//   exactly (the exact in-sphere test, no perturbation) share a circumcentre; the classes of
//   tetrahedra joined that way are the vertices (mesh/vertex_classes.hpp), each the
//   circumcentre of its smallest tetrahedron.
// - Ridges: one per edge (u, w) of the Delaunay subdivision: the ring of tetrahedra round the
//   edge, read as classes (consecutive tetrahedra of one class are one vertex), must have at
//   least three vertices (a closed ring), or at least two besides the vertex at infinity (a
//   ring open at the hull), or one whose two hull faces are not in one plane. Otherwise the edge
//   only cuts a cospherical cell (or a flat stretch of hull) into tetrahedra, and its "ridge"
//   would have no area. Each ridge is found from the smallest tetrahedron round its edge, and
//   lists its vertices in cyclic order; an open one starts with -1.
// - Regions: per point, the classes of its tetrahedra in increasing order, -1 first for a
//   point on the hull; a duplicate has its twin's region, a removed point (kept
//   triangulations) an empty one.

// The edges of a tetrahedron, by local vertex pairs.
GG_HD inline void vor3_edge(int e, int& i, int& j) {
  constexpr int a[6] = {0, 0, 0, 1, 1, 2}, b[6] = {1, 2, 3, 2, 3, 3};
  i = a[e], j = b[e];
}
GG_HD inline int vor3_local(const std::int32_t* tet, std::int64_t t, std::int32_t v) {
  for (int k = 0; k < 4; ++k)
    if (tet[4 * t + k] == v) return k;
  return -1;
}
// The vertex of tetrahedron t that is none of a, b, c.
GG_HD inline std::int32_t vor3_fourth(const std::int32_t* tet, std::int64_t t, std::int32_t a,
                                      std::int32_t b, std::int32_t c) {
  for (int k = 0; k < 4; ++k) {
    const std::int32_t v = tet[4 * t + k];
    if (v != a && v != b && v != c) return v;
  }
  return -1;
}

// A walk round the edge (u, w): at tetrahedron t, leaving across the face opposite its vertex x
// (the face holds u, w and t's fourth vertex y). step() moves on; at the hull it stays and
// reports false. The walk back is the same state with x and y swapped.
struct EdgeWalk {
  std::int64_t t;
  std::int32_t u, w, x;
  GG_HD std::int32_t other(const std::int32_t* tet) const { return vor3_fourth(tet, t, u, w, x); }
  GG_HD bool step(const std::int32_t* tet, const std::int32_t* nb) {
    const std::int32_t n = nb[4 * t + vor3_local(tet, t, x)];
    if (n < 0) return false;
    const std::int32_t y = other(tet);
    t = n;
    x = y;  // (n holds u, w, y and its own fourth vertex; it is left across the face without y)
    return true;
  }
};

// Ring of edge e of tetrahedron t: whether t is its smallest tetrahedron (so the ridge is
// found once), whether it is closed, and where its open ring starts (the hull end that the walk
// back from reaches every tetrahedron round the edge). closed and start are only set for the
// smallest tetrahedron: the others stop at the first smaller one they meet.
struct Ring {
  bool owner = true, closed = true;
  EdgeWalk start;
};
GG_HD inline Ring vor3_ring(const std::int32_t* tet, const std::int32_t* nb, std::int64_t t, int e,
                            std::int64_t limit) {
  int i, j;
  vor3_edge(e, i, j);
  Ring R;
  const std::int32_t u = tet[4 * t + i], w = tet[4 * t + j];
  int k = 0;
  while (k == i || k == j) ++k;
  EdgeWalk a{t, u, w, tet[4 * t + k]};
  for (std::int64_t s = 0; s < limit; ++s) {
    if (!a.step(tet, nb)) {
      R.closed = false;
      break;
    }
    if (a.t == t) break;
    if (a.t < t) {  // (not the smallest: another tetrahedron finds the ridge; stop here)
      R.owner = false;
      return R;
    }
  }
  if (R.closed) {
    R.start = EdgeWalk{t, u, w, tet[4 * t + k]};
    return R;
  }
  // open: the other way round to the other hull end, from where the walk back passes them all
  EdgeWalk b{t, u, w, vor3_fourth(tet, t, u, w, tet[4 * t + k])};
  for (std::int64_t s = 0; s < limit && b.step(tet, nb); ++s)
    if (b.t < t) {
      R.owner = false;
      return R;
    }
  R.start = EdgeWalk{b.t, u, w, b.other(tet)};
  return R;
}

// Visits the classes round a ring from its start (the open ring's whole length, or the closed
// ring once round); returns the walk's last state (for an open ring, at the other hull end).
template <class F>
GG_HD EdgeWalk vor3_walk(const std::int32_t* tet, const std::int32_t* nb, const Ring& R,
                         std::int64_t limit, F visit) {
  EdgeWalk a = R.start;
  const std::int64_t t0 = a.t;
  for (std::int64_t s = 0; s < limit; ++s) {
    visit(a.t);
    const EdgeWalk before = a;
    if (!a.step(tet, nb)) return before;
    if (a.t == t0) return before;
  }
  return a;
}

// The circumcentre of tetrahedron t: c = r + (|b|^2 (c x d) + |c|^2 (d x b) + |d|^2 (b x c)) /
// (2 b.(c x d)), with b, c, d the other corners taken from the reference corner r. The
// reference is an end of the shortest edge: taken from a corner far from two near ones, the
// edges to those round to parallel vectors and the formula to 0/0 (corners 10^40 away from
// others 10^-30 apart); from the shortest edge every difference keeps its digits. The
// differences are scaled by a power of two (exact) so that their squares and products neither
// overflow nor underflow. Every operation rounded on its own (no contraction into FMA), so both
// executors give the same bits.
GG_HD inline void circumcentre3(const double* xyz, const std::int32_t* tet, std::int64_t t,
                                double* out) {
  using exact::add_rn;
  using exact::mul_rn;
  using exact::sub_rn;
  const double* q[4];
  for (int k = 0; k < 4; ++k) q[k] = xyz + 3 * std::int64_t(tet[4 * t + k]);
  auto dot = [&](const double* x, const double* y) {
    return add_rn(add_rn(mul_rn(x[0], y[0]), mul_rn(x[1], y[1])), mul_rn(x[2], y[2]));
  };
  // the reference corner: an end of the shortest edge (largest coordinate difference)
  int ref = 0;
  double best = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      double len = 0;
      for (int d = 0; d < 3; ++d) len = fmax(len, fabs(sub_rn(q[j][d], q[i][d])));
      if ((i == 0 && j == 1) || len < best) best = len, ref = i;
    }
  const double* a = q[ref];
  double far = 0;
  for (int j = 0; j < 4; ++j)
    for (int d = 0; d < 3; ++d) far = fmax(far, fabs(sub_rn(q[j][d], a[d])));
  // the three others, in the tetrahedron's cyclic order from the reference (keeps the sign)
  const int o0 = (ref + 1) % 4, o1 = (ref + 2) % 4, o2 = (ref + 3) % 4;
  const double* others[3] = {q[o0], q[o1], q[o2]};
  const int ex = far > 0 ? ilogb(far) : 0;
  double e[3][3];
  for (int k = 0; k < 3; ++k)
    for (int d = 0; d < 3; ++d) e[k][d] = ldexp(sub_rn(others[k][d], a[d]), -ex);
  auto cross = [&](const double* x, const double* y, double* z) {
    z[0] = sub_rn(mul_rn(x[1], y[2]), mul_rn(x[2], y[1]));
    z[1] = sub_rn(mul_rn(x[2], y[0]), mul_rn(x[0], y[2]));
    z[2] = sub_rn(mul_rn(x[0], y[1]), mul_rn(x[1], y[0]));
  };
  double cd[3], db[3], bc[3];
  cross(e[1], e[2], cd);
  cross(e[2], e[0], db);
  cross(e[0], e[1], bc);
  const double l0 = dot(e[0], e[0]), l1 = dot(e[1], e[1]), l2 = dot(e[2], e[2]);
  // (the determinant in twice the precision: a nearly flat tetrahedron's rounds to 0 otherwise)
  mesh::Sum2 det;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    det.add_product(e[0][i], e[1][j], e[2][k]);
    det.add_product(-e[0][i], e[1][k], e[2][j]);
  }
  const double den = 2 * det.value();
  for (int d = 0; d < 3; ++d) {
    mesh::Sum2 num;
    num.add_product(l0, cd[d]);
    num.add_product(l1, db[d]);
    num.add_product(l2, bc[d]);
    out[d] = add_rn(a[d], ldexp(num.value() / den, ex));
  }
}

// The Voronoi vertices: classes of tetrahedra joined across exactly cospherical faces
// (mesh::number_classes: per tetrahedron its class, per class its first tetrahedron).
inline mesh::Classes<Exec> vor3_classes(Exec& ex, const double* xyz, const std::int32_t* tet,
                                        const std::int32_t* nb, std::int64_t nt,
                                        const ScratchLease& lease) {
  using I32 = std::int32_t;
  using I64 = std::int64_t;
  auto d_parent = ex.template alloc<I32>(std::size_t(nt));
  I32* parent = d_parent.data();
  ex.for_each_index(
      nt, GG_LAMBDA(I64 t) { parent[t] = I32(t); });
  auto d_cnt = ex.template alloc<I64>(1);
  I64* cnt = d_cnt.data();
  ex.fill(cnt, 1, I64(0));
  ex.for_each_index(
      4 * nt, GG_LAMBDA(I64 c) {
        const I64 t = c / 4;
        const I32 o = nb[c];
        if (o <= t) return;  // (each face once, from its smaller tetrahedron; hull faces have none)
        const int j = vor3_local(nb, o, I32(t));  // (o's face towards t)
        const double* p[5];
        for (int k = 0; k < 4; ++k) p[k] = xyz + 3 * I64(tet[4 * t + k]);
        p[4] = xyz + 3 * I64(tet[4 * I64(o) + j]);
        int r = pred::insphere_fast(p[0], p[1], p[2], p[3], p[4]);
        if (r == 0) {
          double* s = lease.acquire(std::uint32_t(t) * 2654435761u + std::uint32_t(o));
          r = pred::insphere(p[0], p[1], p[2], p[3], p[4], s);
          lease.release(s);
        }
        if (r != 0) return;
        mesh::uf_unite(parent, I32(t), o);
        atomic_add(cnt, I64(1));
      });
  I64 joined = 0;
  ex.to_host(cnt, 1, &joined);
  return mesh::number_classes(ex, parent, nt, joined);
}

// Per (tetrahedron, edge) c < 6 nt, the exclusive scan (into len, 6 nt + 1 entries) of the
// length of its ridge's vertex list: 0 where the edge has no ridge or another tetrahedron of its
// ring finds it; vid: each tetrahedron's class (vor3_classes).
inline void vor3_ridge_lengths(Exec& ex, const double* xyz, const std::int32_t* tet,
                               const std::int32_t* nb, std::int64_t nt, const std::int32_t* vid,
                               const ScratchLease& lease, std::int64_t* len) {
  using I64 = std::int64_t;
  ex.exclusive_scan_of(
      6 * nt + 1,
      GG_LAMBDA(I64 c)->I64 {
        if (c >= 6 * nt) return 0;
        const Ring R = vor3_ring(tet, nb, c / 6, int(c % 6), nt);
        if (!R.owner) return 0;
        mesh::ClassRun run{};
        const EdgeWalk end = vor3_walk(tet, nb, R, nt, [&](I64 t) { run.step(vid[t]); });
        const I64 m = run.length(R.closed);
        if (R.closed) return m >= 3 ? m : 0;
        if (m >= 2) return m + 1;
        // one finite vertex: a ridge unless the two hull faces at the ring's ends are in one plane
        const EdgeWalk& s = R.start;
        const double* a = xyz + 3 * I64(s.u);
        const double* b = xyz + 3 * I64(s.w);
        const double* y0 = xyz + 3 * I64(s.x);  // (the start's hull face holds u, w and x)
        const double* y1 = xyz + 3 * I64(end.other(tet));
        int o = pred::orient3d_fast(a, b, y0, y1);
        if (o == 0) {
          double* sc = lease.acquire(std::uint32_t(c) * 2654435761u);
          o = pred::orient3d(a, b, y0, y1, sc);
          lease.release(sc);
        }
        return o != 0 ? 2 : 0;
      },
      len);
}

inline void voronoi3d_impl(const double* xyz, std::int64_t n, const std::int32_t* tet,
                           const std::int32_t* nb, const std::int32_t* dup, std::int64_t nt,
                           const Voronoi3dOptions& run, DeviceVoronoi3d& out, Voronoi3dStats& st,
                           Voronoi3d* host, const ::gpugeom::detail::ExecContext* outer) {
  const auto t0 = std::chrono::steady_clock::now();
  Exec ex(run, outer);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  using I32 = std::int32_t;
  using I64 = std::int64_t;
  LeasePool<Exec> pool(ex, std::clamp<std::int64_t>(ex.concurrency(), 64, 1024),
                       pred::kInsphereScratch);
  const ScratchLease lease = pool.view;
  auto V = vor3_classes(ex, xyz, tet, nb, nt, lease);
  const I32* vid = V.of.data();
  const I32* first = V.first.data();
  const I64 nv = V.count;
  auto vx = ex.template alloc<double>(std::size_t(3 * nv));
  double* v = vx.data();
  ex.for_each_index(
      nv, GG_LAMBDA(I64 j) { circumcentre3(xyz, tet, first[j], v + 3 * j); });
  st.voronoi_vertices = nv;
  // Ridges: per (tetrahedron, edge), where its ridge's vertex list starts (vor3_ridge_lengths).
  auto d_len = ex.template alloc<I64>(std::size_t(6 * nt + 1));
  I64* len = d_len.data();
  vor3_ridge_lengths(ex, xyz, tet, nb, nt, vid, lease, len);
  // ... ridge numbers: a second scan over the same flags (a ridge has a list of 2 or more)
  auto d_rank = ex.template alloc<I64>(std::size_t(6 * nt + 1));
  I64* rank = d_rank.data();
  ex.exclusive_scan_of(
      6 * nt + 1, GG_LAMBDA(I64 c)->I64 { return c < 6 * nt && len[c + 1] != len[c]; }, rank);
  I64 nr = 0, nrv = 0;
  ex.to_host(rank + 6 * nt, 1, &nr);
  ex.to_host(len + 6 * nt, 1, &nrv);
  auto rpb = ex.template alloc<I32>(std::size_t(2 * nr));
  auto rob = ex.template alloc<I64>(std::size_t(nr + 1));
  auto rvb = ex.template alloc<I32>(std::size_t(nrv));
  I32* rp = rpb.data();
  I64* ro = rob.data();
  I32* rv = rvb.data();
  ex.fill(ro + nr, 1, nrv);
  ex.for_each_index(
      6 * nt, GG_LAMBDA(I64 c) {
        if (len[c + 1] == len[c]) return;
        const I64 r = rank[c];
        const Ring R = vor3_ring(tet, nb, c / 6, int(c % 6), nt);
        rp[2 * r] = R.start.u, rp[2 * r + 1] = R.start.w;
        ro[r] = len[c];
        I32* o = rv + len[c];
        const I64 m = len[c + 1] - len[c];
        I64 at = 0;
        if (!R.closed) o[at++] = -1;
        mesh::ClassRun run{};
        vor3_walk(tet, nb, R, nt, [&](I64 t) {
          if (run.step(vid[t]) && at < m) o[at++] = vid[t];
        });
      });
  st.voronoi_ridges = nr;
  // Regions: the (point, class) pairs of every corner, sorted, once each.
  auto d_keys = ex.template alloc<std::uint64_t>(std::size_t(4 * nt));
  std::uint64_t* keys = d_keys.data();
  ex.for_each_index(
      4 * nt, GG_LAMBDA(I64 c) {
        keys[c] = (std::uint64_t(std::uint32_t(tet[c])) << 32) | std::uint32_t(vid[c / 4]);
      });
  ex.sort(keys, 4 * nt);
  auto d_urank = ex.template alloc<I64>(std::size_t(4 * nt + 1));
  I64* urank = d_urank.data();
  ex.exclusive_scan_of(
      4 * nt + 1,
      GG_LAMBDA(I64 j)->I64 { return j < 4 * nt && (j == 0 || keys[j] != keys[j - 1]); }, urank);
  I64 nu = 0;
  ex.to_host(urank + 4 * nt, 1, &nu);
  auto d_uniq = ex.template alloc<std::uint64_t>(std::size_t(nu));
  std::uint64_t* uniq = d_uniq.data();
  ex.for_each_index(
      4 * nt, GG_LAMBDA(I64 j) {
        if (urank[j + 1] != urank[j]) uniq[urank[j]] = keys[j];
      });
  // per point: where its pairs start and end, and whether it is on the hull
  auto d_from = ex.template alloc<I64>(std::size_t(2 * n));
  I64* from = d_from.data();
  I64* to = from + n;
  auto d_hull = ex.template alloc<std::int8_t>(std::size_t(n));
  std::int8_t* on_hull = d_hull.data();
  ex.fill(from, 2 * n, I64(0));
  ex.fill(on_hull, n, std::int8_t(0));
  ex.for_each_index(
      nu, GG_LAMBDA(I64 j) {
        const I64 p = I64(uniq[j] >> 32);
        if (j == 0 || I64(uniq[j - 1] >> 32) != p) from[p] = j;
        if (j == nu - 1 || I64(uniq[j + 1] >> 32) != p) to[p] = j + 1;
      });
  ex.for_each_index(
      4 * nt, GG_LAMBDA(I64 c) {
        if (nb[c] >= 0) return;  // (a hull face: the three vertices other than corner c)
        const I64 t = c / 4;
        for (int k = 0; k < 4; ++k)
          if (4 * t + k != c) on_hull[tet[4 * t + k]] = 1;
      });
  const mesh::CellSource src_of{dup};
  auto offb = ex.template alloc<I64>(std::size_t(n + 1));
  I64* off = offb.data();
  ex.exclusive_scan_of(
      n + 1,
      GG_LAMBDA(I64 i)->I64 {
        if (i >= n || src_of.removed(i)) return 0;
        const I64 p = src_of(i);
        return to[p] - from[p] + on_hull[p];
      },
      off);
  I64 ncv = 0;
  ex.to_host(off + n, 1, &ncv);
  auto cvb = ex.template alloc<I32>(std::size_t(ncv));
  I32* cv = cvb.data();
  ex.for_each_index(
      n, GG_LAMBDA(I64 i) {
        if (src_of.removed(i)) return;
        const I64 p = src_of(i);
        I32* o = cv + off[i];
        if (on_hull[p]) *o++ = -1;
        for (I64 j = from[p]; j < to[p]; ++j) *o++ = I32(uniq[j] & 0xffffffffu);
      });
  auto missing = ex.template alloc<I64>(1);
  ex.transform_reduce_into(
      n, GG_LAMBDA(I64 i)->I64 { return !src_of.removed(i) && off[i + 1] == off[i] ? 1 : 0; },
      I64(0), thrust::plus<I64>(), missing.data());
  I64 nmiss = 0;
  ex.to_host(missing.data(), 1, &nmiss);
  if (nmiss)
    throw Error(ErrorCode::InvalidArgument,
                std::to_string(nmiss) +
                    " point(s) are not vertices of the tetrahedralisation: it does not belong to "
                    "these points");
  // The caller's arrays, checked before anything is written to them.
  const Voronoi3dBuffers& into = run.into;
  deliver::check(into.vertices, 3 * nv, "vertices");
  deliver::check(into.ridge_points, 2 * nr, "ridge_points");
  deliver::check(into.ridge_offsets, nr + 1, "ridge_offsets");
  deliver::check(into.ridge_vertices, nrv, "ridge_vertices");
  deliver::check(into.region_offsets, n + 1, "region_offsets");
  deliver::check(into.region_vertices, ncv, "region_vertices");
  deliver::check(into.simplex_vertex, nt, "simplex_vertex");
  if (host) {  // the host entry: into its HostVectors (on the CPU executor a parallel copy)
    deliver::to_host(ex, v, 3 * nv, into.vertices, host->vertices);
    deliver::to_host(ex, rp, 2 * nr, into.ridge_points, host->ridge_points);
    deliver::to_host(ex, ro, nr + 1, into.ridge_offsets, host->ridge_offsets);
    deliver::to_host(ex, rv, nrv, into.ridge_vertices, host->ridge_vertices);
    deliver::to_host(ex, off, n + 1, into.region_offsets, host->region_offsets);
    deliver::to_host(ex, cv, ncv, into.region_vertices, host->region_vertices);
    deliver::to_host(ex, vid, nt, into.simplex_vertex, host->simplex_vertex);
    host->num_points = n;
    host->num_vertices = nv;
    host->num_ridges = nr;
    host->num_ridge_vertices = nrv;
    host->num_region_vertices = ncv;
    st.phase_ms.push_back({"voronoi", ms_since(t0)});
    return;
  }
  auto p_v = deliver::place(ex, vx, 3 * nv, into.vertices);
  auto p_rp = deliver::place(ex, rpb, 2 * nr, into.ridge_points);
  auto p_ro = deliver::place(ex, rob, nr + 1, into.ridge_offsets);
  auto p_rv = deliver::place(ex, rvb, nrv, into.ridge_vertices);
  auto p_off = deliver::place(ex, offb, n + 1, into.region_offsets);
  auto p_cv = deliver::place(ex, cvb, ncv, into.region_vertices);
  auto p_sv = deliver::place(ex, V.of, nt, into.simplex_vertex);
  ex.sync();  // the caller may read them now (and free them on any stream)
  out.num_vertices = nv;
  out.num_ridges = nr;
  out.num_ridge_vertices = nrv;
  out.num_region_vertices = ncv;
  out.vertices = p_v.own();
  out.ridge_points = p_rp.own();
  out.ridge_offsets = p_ro.own();
  out.ridge_vertices = p_rv.own();
  out.region_offsets = p_off.own();
  out.region_vertices = p_cv.own();
  out.simplex_vertex = p_sv.own();
  st.phase_ms.push_back({"voronoi", ms_since(t0)});
}
