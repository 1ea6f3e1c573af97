// A 3D Delaunay tetrahedralisation kept on the executor between calls (DynamicDelaunay3d, issue
// 47). Included inside gpugeom::del3d::{cpu,cuda}_impl after triangulate.inl; the moves and the
// update that use these pieces follow in dynamic.inl.
//
// Kept: the input points in input order, the store as phase 2 leaves it (the Delaunay
// tetrahedralisation of the perturbed points with its infinite and flat tetrahedra, vertices as
// input indices, slot numbers and neighbour encoding as they were), the duplicate map and the
// first build's kernel point (inside its first tetrahedron, so inside every later hull). An
// insertion appends the new points, prepares the whole set again (validation, curve order,
// duplicates: one sort, the step that is still global), puts the kept store back in prepared
// indices (Triangulator::start_from), locates each new point by a walk from the old vertex
// before it on the curve, and runs the batches and phase 2 as a fresh build does. The kept
// tetrahedra are Delaunay among the old points, so only the new points' neighbourhoods flip.
// The result is a fresh build's: the perturbation depends on the points alone, and the
// Delaunay tetrahedralisation of perturbed points is unique. The results leave out the
// infinite and the flat tetrahedra, as a fresh build's output step does.

// The kept store as results: finite tetrahedra that are not flat (exactly coplanar vertices),
// -1 across a face to one that is not.
struct KeptTets {
  const Tet* tet;
  const double* xyz;  // input points
  ScratchLease lease;
  GG_HD bool live(std::int64_t t) const {
    const Tet T = tet[t];
    for (int k = 0; k < 4; ++k)  // (dead slots: v[0] = -1)
      if (T.v[k] < 0) return false;
    Geo g{};
    g.p = xyz;
    g.m = -3;  // (no vertex is the infinity point here)
    g.lease = lease;
    return !flat_ext(g, T.v);
  }
  GG_HD mesh::SimplexRecord<4> get(std::int64_t t) const {
    const Tet T = tet[t];
    mesh::SimplexRecord<4> r;
    for (int k = 0; k < 4; ++k)
      r.v[k] = T.v[k], r.n[k] = T.n[k] == kNoNeighbour ? -1 : simplex_of(T.n[k]);
    return r;
  }
};

// Scratch for the exact flatness tests (as many slots as threads may hold at once, as phase 1
// sizes its own).
inline LeasePool<Exec> flat_test_pool(Exec& ex) {
  return LeasePool<Exec>(ex, std::clamp<std::int64_t>(ex.concurrency(), 64, 1024),
                         pred::kOrient3dScratch);
}

struct KeptArrays {
  typename Exec::template Buffer<double> xyz;        // 3 n, input order
  typename Exec::template Buffer<Tet> tet;           // used slots
  typename Exec::template Buffer<std::int32_t> dup;  // n, when ndup or nremoved > 0
  typename Exec::template Buffer<std::int8_t> gone;  // n (1: removed), when nremoved > 0
  std::int64_t n = 0, used = 0, ndup = 0, nremoved = 0;
  std::int64_t nout = 0;  // tetrahedra in the results
  double kernel[3] = {0, 0, 0};
  // The duplicate map (kRemoved at removed points), or null where every point is a vertex.
  const std::int32_t* dup_map() const { return ndup || nremoved ? dup.data() : nullptr; }
  const std::int8_t* gone_map() const { return nremoved ? gone.data() : nullptr; }
};

// The kept store in input indices (the infinity point as kKeptInfinity), from T's store.
inline typename Exec::template Buffer<Tet> keep_store(Exec& ex, Triangulator& T,
                                                      const std::int32_t* orig) {
  const std::int64_t used = T.counters().used;
  auto out = ex.template alloc<Tet>(std::size_t(used));
  Tet* o = out.data();
  const Tet* tet = T.tet_.data();
  const std::int32_t m = T.m_;
  ex.for_each_index(
      used, GG_LAMBDA(std::int64_t t) {
        Tet X = tet[t];
        if (X.v[0] >= 0)
          for (int k = 0; k < 4; ++k)
            X.v[k] = X.v[k] == m ? Triangulator::kKeptInfinity : orig[X.v[k]];
        o[t] = X;
      });
  return out;
}

// Per slot of T's store: 1 where the insertion rewrote it (a slot past the kept ones, or one
// whose tetrahedron or neighbours differ from the kept store's, put in prepared indices with
// inv). The faces between two slots it did not rewrite are locally Delaunay, as they were.
inline typename Exec::template Buffer<std::int8_t> touched_slots(Exec& ex, Triangulator& T,
                                                                 const KeptArrays& K,
                                                                 const std::int32_t* inv) {
  const std::int64_t used = T.counters().used, kept_used = K.used;
  auto out = ex.template alloc<std::int8_t>(std::size_t(used));
  std::int8_t* o = out.data();
  const Tet* tet = T.tet_.data();
  const Tet* kept = K.tet.data();
  const std::int32_t I = T.m_;
  ex.for_each_index(
      used, GG_LAMBDA(std::int64_t t) {
        if (t >= kept_used) {
          o[t] = 1;
          return;
        }
        const Tet a = tet[t], b = kept[t];
        bool same = true;
        for (int k = 0; k < 4; ++k) {
          const std::int32_t v = b.v[0] == -1                            ? b.v[k]
                                 : b.v[k] == Triangulator::kKeptInfinity ? I
                                                                         : inv[b.v[k]];
          same = same && a.v[k] == v && a.n[k] == b.n[k];
        }
        o[t] = !same;
      });
  return out;
}

// A store tested with the points at xyz (n points) for a move: every tetrahedron must be
// positive (infinite ones: cones from a kernel point s; flat ones: ordered by the perturbation),
// and s inside exactly one finite tetrahedron: with every tetrahedron positive, the number of
// them over a point is the same for every point, so a hull that wraps twice round s is caught.
// s is placed inside the first finite tetrahedron that is positive and not flat. The vertices of
// the tetrahedra that are not positive are flagged in `out`. All exact, with the perturbation (s
// as index n: after any point it equals).
struct MoveTest {
  std::int64_t bad = 0;      // tetrahedra not positive
  std::int64_t holding = 0;  // finite tetrahedra holding s
  bool placed = false;       // s placed (a finite tetrahedron positive and not flat)
  double s[3] = {0, 0, 0};
};
inline MoveTest test_moved(Exec& ex, const Tet* tet, std::int64_t used, const double* xyz,
                           std::int64_t n, std::int8_t* out) {
  MoveTest r;
  LeasePool<Exec> pool = flat_test_pool(ex);
  Geo g{};
  g.p = xyz;
  g.m = std::int32_t(n);
  g.lease = pool.view;
  auto cnt = ex.template alloc<std::int64_t>(2);  // bad tetrahedra, finite ones holding s
  auto d_best = ex.template alloc<std::int32_t>(1);
  std::int64_t* c = cnt.data();
  std::int32_t* best = d_best.data();
  ex.fill(c, 2, std::int64_t(0));
  ex.fill(best, 1, std::numeric_limits<std::int32_t>::max());
  ex.for_each_index(  // the finite tetrahedra
      used, GG_LAMBDA(std::int64_t t) {
        const Tet T = tet[t];
        if (T.v[0] == -1) return;  // dead
        for (int k = 0; k < 4; ++k)
          if (T.v[k] == Triangulator::kKeptInfinity) return;
        if (orient_ext(g, T.v[0], T.v[1], T.v[2], T.v[3]) <= 0) {
          for (int k = 0; k < 4; ++k) out[T.v[k]] = 1;
          atomic_add(&c[0], std::int64_t(1));
        } else if (!flat_ext(g, T.v)) {
          atomic_min(&best[0], std::int32_t(t));
        }
      });
  std::int32_t b = 0;
  ex.to_host(best, 1, &b);
  if (b == std::numeric_limits<std::int32_t>::max()) return r;
  Tet B;
  ex.to_host(tet + b, 1, &B);
  double q[4][3];
  for (int k = 0; k < 4; ++k) ex.to_host(xyz + 3 * std::int64_t(B.v[k]), 3, q[k]);
  const double* V[4] = {q[0], q[1], q[2], q[3]};
  mesh::kernel_of(V, r.s);
  r.placed = true;
  for (int k = 0; k < 3; ++k) g.s[k] = r.s[k];
  ex.for_each_index(  // the infinite ones, and which finite ones hold s
      used, GG_LAMBDA(std::int64_t t) {
        const Tet T = tet[t];
        if (T.v[0] == -1) return;
        std::int32_t w[4];
        bool finite = true;
        for (int k = 0; k < 4; ++k) {
          w[k] = T.v[k] == Triangulator::kKeptInfinity ? g.m : T.v[k];
          finite = finite && w[k] != g.m;
        }
        if (!finite) {
          if (orient_ext(g, w[0], w[1], w[2], w[3]) <= 0) {
            for (int k = 0; k < 4; ++k)
              if (w[k] != g.m) out[w[k]] = 1;
            atomic_add(&c[0], std::int64_t(1));
          }
          return;
        }
        bool holds = true;
        for (int k = 0; k < 4 && holds; ++k) {  // (s replaced for vertex k, not as infinity)
          const double* p[4];
          std::int32_t id[4];
          for (int j = 0; j < 4; ++j)
            p[j] = j == k ? g.s : g.p + 3 * std::int64_t(w[j]), id[j] = j == k ? g.m : w[j];
          int o = pred::orient3d_fast(p[0], p[1], p[2], p[3]);
          if (!o) o = orient_rest(p[0], id[0], p[1], id[1], p[2], id[2], p[3], id[3], g.lease);
          holds = o > 0;
        }
        if (holds) atomic_add(&c[1], std::int64_t(1));
      });
  std::int64_t h[2];
  ex.to_host(c, 2, h);
  r.bad = h[0];
  r.holding = h[1];
  return r;
}

// The kept points with `add` more appended (host memory, or executor memory when on_device), or
// all of them replaced (replace: move).
inline KeptArrays with_points(Exec& ex, const KeptArrays& K, const double* xyz, std::int64_t add,
                              bool on_device, bool replace, Delaunay3dStats& st) {
  const auto t0 = Clock::now();
  const std::int64_t keep = replace ? 0 : K.n, n = keep + add;
  KeptArrays R;
  R.xyz = ex.template alloc<double>(std::size_t(3 * n));
  if (keep) ex.copy(K.xyz.data(), 3 * keep, R.xyz.data());
  if (add && on_device)
    ex.copy(xyz, 3 * add, R.xyz.data() + 3 * keep);
  else if (add)
    ex.from_host(xyz, 3 * add, R.xyz.data() + 3 * keep);
  R.gone = mesh::extend_flags(ex, K.gone_map(), K.n, n);
  R.nremoved = K.nremoved;
  st.phase_ms.push_back({"append", ms_since(t0)});
  return R;
}

enum class Update { Insert, Move, Remove };

// prepare_points over the points not removed (R.gone), its indices made input indices again
// and its duplicate map widened to all n (mesh::to_input_indices).
inline Prepared prepare_kept(Exec& ex, const KeptArrays& R, std::int64_t n, Delaunay3dStats& st) {
  if (!R.nremoved) return prepare_points(ex, R.xyz.data(), n, true, st);
  const auto L = mesh::gather_live<3>(ex, R.xyz.data(), n, R.gone.data());
  Prepared P = prepare_points(ex, L.p.data(), L.count, true, st);
  mesh::SortedPoints<Exec>& S = P.S;
  S.dup =
      mesh::to_input_indices(ex, L, S.orig.data(), S.m, S.duplicates ? S.dup.data() : nullptr, n);
  st.points = n;
  st.removed_points = R.nremoved;
  return P;
}

// Removal (issue 47): the kept store with the holes of the removed vertices filled
// (mesh/hole_refill.hpp) from D, the tetrahedralisation of the hole's vertices that stay and of
// the copies that take a removed vertex's place. ok false where that cannot be done here (too
// few or coplanar such vertices, pieces that do not fit): the caller builds afresh.
struct Refill3d {
  typename Exec::template Buffer<Tet> tet;
  typename Exec::template Buffer<std::int8_t> touched;  // per slot: where phase 2 looks
  std::int64_t used = 0;
  std::int64_t unmatched = 0;  // boundary faces D lacks
  bool ok = false;
};

// A store as plain arrays (vertices, neighbours as slot numbers or -1), and back (neighbours
// encoded with the face they meet: the one whose neighbour is this slot).
inline void plain_of(Exec& ex, const Tet* tet, std::int64_t used, std::int32_t* v,
                     std::int32_t* nb) {
  ex.for_each_index(
      used, GG_LAMBDA(std::int64_t t) {
        const Tet T = tet[t];
        for (int k = 0; k < 4; ++k) {
          v[4 * t + k] = T.v[k];
          nb[4 * t + k] = T.n[k] == kNoNeighbour ? -1 : simplex_of(T.n[k]);
        }
      });
}
inline void store_of(Exec& ex, const std::int32_t* v, const std::int32_t* nb, std::int64_t count,
                     Tet* tet) {
  ex.for_each_index(
      count, GG_LAMBDA(std::int64_t t) {
        Tet T;
        for (int k = 0; k < 4; ++k) {
          T.v[k] = v[4 * t + k];
          const std::int32_t o = nb[4 * t + k];
          int back = 0;
          if (o >= 0)
            for (int j = 0; j < 4; ++j)
              if (nb[4 * std::int64_t(o) + j] == std::int32_t(t)) back = j;
          T.n[k] = o < 0 ? kNoNeighbour : enc(o, back);
        }
        tet[t] = T;
      });
}

// now: per point, 1 where it goes now; xyz: the points' places (D is built there); new_dup: the
// duplicate map after (a copy of a point that goes, -1 there, takes its place); mark (or null):
// set at the vertices of the staying tetrahedra across boundary faces D lacks
// (mesh::refill_holes).
inline Refill3d refill_3d(Exec& ex, const KeptArrays& K, const std::int8_t* now, const double* xyz,
                          const std::int32_t* new_dup, const Delaunay3dOptions& opt,
                          Delaunay3dStats& st, std::int8_t* mark = nullptr) {
  Refill3d out;
  const std::int64_t n = K.n;  // (a removal keeps every index)
  auto d_ov = ex.template alloc<std::int32_t>(std::size_t(4 * K.used));
  auto d_on = ex.template alloc<std::int32_t>(std::size_t(4 * K.used));
  plain_of(ex, K.tet.data(), K.used, d_ov.data(), d_on.data());
  auto d_hole = ex.template alloc<std::int8_t>(std::size_t(K.used));
  const std::int64_t nh = mesh::hole_flags<4>(ex, d_ov.data(), K.used, now, d_hole.data());
  if (nh == 0) {  // only points that were no vertices: the store stays
    out.tet = ex.template alloc<Tet>(std::size_t(K.used));
    ex.copy(K.tet.data(), K.used, out.tet.data());
    out.used = K.used;
    out.touched = ex.template alloc<std::int8_t>(std::size_t(K.used));
    ex.fill(out.touched.data(), K.used, std::int8_t(0));
    out.ok = true;
    return out;
  }
  auto d_ids = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* ids = d_ids.data();
  const std::int64_t nv = mesh::hole_vertices<4>(ex, d_ov.data(), K.used, d_hole.data(), now,
                                                 K.dup_map(), new_dup, n, ids);
  st.hole_vertices = nv;
  if (nv < 4) return out;
  // D: the hole vertices' tetrahedralisation, its store in input indices
  auto d_p = ex.template alloc<double>(std::size_t(3 * nv));
  double* p = d_p.data();
  ex.for_each_index(
      nv, GG_LAMBDA(std::int64_t j) {
        for (int d = 0; d < 3; ++d) p[3 * j + d] = xyz[3 * std::int64_t(ids[j]) + d];
      });
  typename Exec::template Buffer<Tet> dstore;
  std::int64_t dused = 0;
  try {
    Delaunay3dStats sd;
    Prepared PD = prepare_points(ex, p, nv, true, sd);
    if (PD.S.duplicates) return out;  // (the hole's vertices are distinct points)
    Triangulator TD(ex, PD.S.pts.data(), std::int32_t(PD.S.m), PD.first,
                    ex.tuning().del3d.max_flip_rounds, opt.progress, sd);
    TD.run();
    repair_phase(ex, TD, PD.S.m, opt.progress, sd);
    dused = TD.counters().used;
    dstore = keep_store(ex, TD, PD.S.orig.data());
  } catch (const Error& e) {
    if (e.code() == ErrorCode::DegenerateInput) return out;  // (coplanar hole vertices)
    throw;
  }
  auto d_dv = ex.template alloc<std::int32_t>(std::size_t(4 * dused));
  auto d_dn = ex.template alloc<std::int32_t>(std::size_t(4 * dused));
  plain_of(ex, dstore.data(), dused, d_dv.data(), d_dn.data());
  std::int32_t* dv = d_dv.data();
  ex.for_each_index(
      4 * dused, GG_LAMBDA(std::int64_t e) {
        const std::int32_t v = dv[e];
        if (v >= 0) dv[e] = ids[v];  // (dead -1 and infinity kKeptInfinity stay)
      });
  auto f = mesh::refill_holes<4>(ex, d_ov.data(), d_on.data(), K.used, d_hole.data(), dv,
                                 d_dn.data(), dused, true, mark);
  st.hole_tetrahedra = f.inside;
  out.unmatched = f.unmatched;
  if (!f.ok) return out;
  out.tet = ex.template alloc<Tet>(std::size_t(f.count));
  store_of(ex, f.v.data(), f.n.data(), f.count, out.tet.data());
  out.used = f.count;
  out.touched = std::move(f.touched);
  out.ok = true;
  return out;
}

// After a removal: the refilled slots and their neighbours, and any slot past the refilled store
// (a point the refill missed would be inserted there: a safety net, not expected).
inline typename Exec::template Buffer<std::int8_t> refilled_slots(Exec& ex, Triangulator& T,
                                                                  const Refill3d& f) {
  const std::int64_t used = T.counters().used, kept = f.used;
  auto out = ex.template alloc<std::int8_t>(std::size_t(used));
  std::int8_t* o = out.data();
  const std::int8_t* t = f.touched.data();
  ex.for_each_index(
      used, GG_LAMBDA(std::int64_t s) { o[s] = s >= kept || t[s]; });
  return out;
}
