// A 3D Delaunay tetrahedralisation kept on the executor between calls (DynamicDelaunay3d, issue
// 47). Included inside gpugeom::del3d::{cpu,cuda}_impl after triangulate.inl.
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
                              bool on_device, bool replace, Stats& st) {
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
inline Prepared prepare_kept(Exec& ex, const KeptArrays& R, std::int64_t n, Stats& st) {
  if (!R.nremoved) return prepare_points(ex, R.xyz.data(), n, true, st);
  const auto L = mesh::gather_live<3>(ex, R.xyz.data(), n, R.gone.data());
  Prepared P = prepare_points(ex, L.p.data(), L.count, true, st);
  mesh::SortedPoints<Exec>& S = P.S;
  S.dup =
      mesh::to_input_indices(ex, L, S.orig.data(), S.m, S.duplicates ? S.dup.data() : nullptr, n);
  st.counters["points"] = n;
  st.counters["removed_points"] = R.nremoved;
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
                          const std::int32_t* new_dup, const Delaunay3dOptions& opt, Stats& st,
                          std::int8_t* mark = nullptr) {
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
  st.counters["hole_vertices"] = nv;
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
    Stats sd;
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
  st.counters["hole_tetrahedra"] = f.inside;
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

// Before a move's fill: the staying tetrahedra whose face with the hole will likely not be one of
// D's (a vertex that stays, of a neighbour of the hole tetrahedron across that face, lies inside
// their sphere at the new places, so the face is not locally Delaunay among the hole's vertices;
// the hole tetrahedron's own apex is always taken out, so it cannot tell) join the hole now, their
// vertices flagged in `out`, rather than after a fill that lacks the face: each fill is a whole
// pipeline on D. A prediction only: a face the fill still lacks grows the hole as before
// (refill_holes' mark). Returns how many points it flagged. [synchronises]
// Its scratch, made once for a move's passes.
struct GrowScratch {
  LeasePool<Exec> pool;  // exact in-sphere tests (larger than the flatness tests')
  typename Exec::template Buffer<std::int8_t> grow;  // n
  GrowScratch(Exec& ex, std::int64_t n)
      : pool(ex, std::clamp<std::int64_t>(ex.concurrency(), 64, 1024), pred::kInsphereScratch),
        grow(ex.template alloc<std::int8_t>(std::size_t(n))) {}
};
inline std::int64_t grow_predicted(Exec& ex, GrowScratch& scratch, const Tet* tet,
                                   std::int64_t used, const double* xyz, std::int64_t n,
                                   std::int8_t* out) {
  Geo g{};
  g.p = xyz;
  g.m = std::int32_t(n);
  g.lease = scratch.pool.view;
  std::int8_t* grow = scratch.grow.data();
  ex.fill(grow, n, std::int8_t(0));
  ex.for_each_index(
      used, GG_LAMBDA(std::int64_t t) {
        const Tet T = tet[t];
        if (T.v[0] == -1) return;    // dead
        for (int k = 0; k < 4; ++k)  // finite and staying
          if (T.v[k] == Triangulator::kKeptInfinity || out[T.v[k]]) return;
        for (int k = 0; k < 4; ++k) {
          if (T.n[k] == kNoNeighbour) continue;
          // (the hole tetrahedron across face k: its apex is taken out, the face's vertices are
          // not; the vertices of its neighbours that stay are the hole vertices nearest the face)
          const Tet H = tet[simplex_of(T.n[k])];
          const int back = loc_of(T.n[k]);
          if (H.v[back] < 0 || !out[H.v[back]]) continue;  // (not a hole tetrahedron)
          auto inside = [&](const Tet& N) {
            for (int j = 0; j < 4; ++j) {
              const std::int32_t w = N.v[j];
              if (w < 0 || out[w] || w == T.v[0] || w == T.v[1] || w == T.v[2] || w == T.v[3])
                continue;
              if (in_sphere_ext(g, T.v, w)) return true;
            }
            return false;
          };
          for (int i = 0; i < 4; ++i) {
            if (i == back || H.n[i] == kNoNeighbour) continue;
            if (inside(tet[simplex_of(H.n[i])])) {
              for (int q = 0; q < 4; ++q) grow[T.v[q]] = 1;
              return;
            }
          }
        }
      });
  // (only staying vertices were flagged: out is read, not written, above)
  const std::int64_t more = mesh::count_flags(ex, grow, n);
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        if (grow[i]) out[i] = 1;
      });
  return more;
}

// A move's start (issue 47): the kept store with the points at their new places. Where a
// tetrahedron turns over there (or a hull face no longer faces away from the kernel point), its
// vertices are taken out, to be inserted again at their new places as new points: the holes they
// leave in the kept store are filled at the new places by the tetrahedra of D, the Delaunay
// tetrahedralisation of the hole's other vertices there, that fit in them (refill_3d, as a
// removal). D's tetrahedra are positive at the new places by construction; where a face of the
// hole is not one of D's (the kept tetrahedra around the hole are not Delaunay at the new
// places), the staying tetrahedron across it is taken into the hole too and D is made again.
// The filled store is then tested like the kept one (the kernel point placed in it again). A
// few rounds settle it; beyond kMoveRounds, or where more than an eighth of the points would go
// (a large displacement is no cheaper to repair), the caller builds afresh.
constexpr int kMoveRounds = 8;
struct MovedStart3d {
  typename Exec::template Buffer<Tet> tet;  // the refilled store (empty: the kept one)
  std::int64_t used = 0;
  typename Exec::template Buffer<std::int8_t> out;  // n: 1 where taken out
  std::int64_t nout = 0;
  double kernel[3] = {0, 0, 0};  // inside the start's hull at the new places
  bool ok = false;
};
inline MovedStart3d moved_start(Exec& ex, const KeptArrays& K, const double* xyz, std::int64_t n,
                                const Delaunay3dOptions& opt, Stats& st) {
  MovedStart3d M;
  M.out = ex.template alloc<std::int8_t>(std::size_t(n));
  ex.fill(M.out.data(), n, std::int8_t(0));
  Refill3d f;
  const Tet* cur = K.tet.data();
  std::int64_t used = K.used;
  bool grown = false;  // the last fill lacked boundary faces: its hole grew, fill again
  std::optional<GrowScratch> scratch;
  for (int round = 0; round < kMoveRounds; ++round) {
    st.counters["move_rounds"] = round + 1;
    if (!grown) {
      const MoveTest t = test_moved(ex, cur, used, xyz, n, M.out.data());
      if (!t.placed) return M;
      if (t.bad == 0) {
        M.ok = t.holding == 1;  // (else the store wraps round s)
        for (int k = 0; k < 3; ++k) M.kernel[k] = t.s[k];
        M.tet = std::move(f.tet);
        M.used = used;
        return M;
      }
    }
    // (counted before the growth too: growing only adds, and a move that takes out too many
    // points is given up before the growth's passes)
    M.nout = mesh::count_flags(ex, M.out.data(), n);
    if (!grown && M.nout <= n / 8) {  // (until none is predicted: a grown hole has new faces)
      if (!scratch) scratch.emplace(ex, n);
      for (int g = 0; g < 4; ++g) {
        const std::int64_t more = grow_predicted(ex, *scratch, cur, used, xyz, n, M.out.data());
        st.counters["move_grown"] += more;
        M.nout += more;
        if (!more) break;
      }
    }
    st.counters["move_taken_out"] = M.nout;
    if (M.nout > n / 8) return M;
    const auto t0 = Clock::now();
    f = refill_3d(ex, K, M.out.data(), xyz, K.dup_map(), opt, st, M.out.data());
    st.phase_ms.push_back({"move_refill", ms_since(t0)});
    grown = !f.ok && f.unmatched > 0;
    if (!f.ok && !grown) return M;
    if (f.ok) cur = f.tet.data(), used = f.used;
  }
  return M;
}

// The state for the n points in R.xyz (the kept points with more appended, or all of them
// moved), built beside K: K is not touched, so a call that throws leaves it as it was. Insert:
// the new points go into the kept store. Move: the kept store with the vertices of turned-over
// tetrahedra taken out (moved_start) is repaired by phase 2 (star splaying) over every face,
// and those vertices go back in as new points; where that cannot be done, the points are
// tetrahedralised afresh (counter "move_rebuilt").
inline KeptArrays kept_update(Exec& ex, const KeptArrays& K, KeptArrays R, std::int64_t n,
                              Update how, const Delaunay3dOptions& opt, Stats& st) {
  Prepared P = prepare_kept(ex, R, n, st);
  mesh::SortedPoints<Exec>& S = P.S;
  const std::int32_t* dup_map = S.duplicates || R.nremoved ? S.dup.data() : nullptr;
  mesh::Tetra first = P.first;
  bool fresh = !K.n;
  // the store phase 1 starts from, and the slots phase 2 tests (null: all)
  const Tet* start = K.tet.data();
  std::int64_t start_used = K.used;
  Refill3d filled;
  if (how == Update::Remove) {
    const auto t1 = Clock::now();
    auto d_now = mesh::removed_now(ex, R.gone.data(), K.gone_map(), n);
    filled = refill_3d(ex, K, d_now.data(), R.xyz.data(), dup_map, opt, st);
    st.phase_ms.push_back({"refill", ms_since(t1)});
    fresh = !filled.ok;
    st.counters["remove_rebuilt"] = fresh;
    start = filled.tet.data(), start_used = filled.used;
  }
  MovedStart3d moved;
  if (!fresh && how == Update::Move) {
    const auto t1 = Clock::now();
    const bool same_points =
        S.duplicates == K.ndup && mesh::dup_changes(ex, K.dup_map(), dup_map, n) == 0;
    if (same_points) moved = moved_start(ex, K, R.xyz.data(), n, opt, st);
    fresh = !moved.ok;
    st.counters["move_rebuilt"] = fresh;
    st.phase_ms.push_back({"move_start", ms_since(t1)});
    if (moved.tet.size()) start = moved.tet.data(), start_used = moved.used;
  }
  // The kernel point must lie inside the start's hull: the first build's is inside every later
  // one while points are only added; after a removal the new first tetrahedron's is, after a
  // move the one moved_start placed.
  if (!fresh && how == Update::Insert)
    for (int k = 0; k < 3; ++k) first.s[k] = K.kernel[k];
  if (!fresh && how == Update::Move)
    for (int k = 0; k < 3; ++k) first.s[k] = moved.kernel[k];
  auto t0 = Clock::now();
  Triangulator T(ex, S.pts.data(), std::int32_t(S.m), first, ex.tuning().del3d.max_flip_rounds,
                 opt.progress, st);
  if (fresh) {
    T.run();
    st.phase_ms.push_back({"insert_flip", ms_since(t0)});
    repair_phase(ex, T, S.m, opt.progress, st);
  } else {
    if (how == Update::Insert) st.counters["inserted_points"] = S.m - (K.n - K.ndup - K.nremoved);
    // input index -> prepared index; each new point's walk start (prepared indices; a move's
    // points taken out go back in as new points)
    const bool walks = how == Update::Insert || (how == Update::Move && moved.nout);
    auto d_inv = ex.template alloc<std::int32_t>(std::size_t(n));
    auto d_hint = ex.template alloc<std::int32_t>(walks ? std::size_t(n) : 0);
    auto d_near = ex.template alloc<std::int32_t>(walks ? std::size_t(S.m) : 0);
    std::int32_t* inv = d_inv.data();
    std::int32_t* hint = d_hint.data();
    std::int32_t* near = d_near.data();
    const std::int32_t* orig = S.orig.data();
    ex.for_each_index(
        S.m, GG_LAMBDA(std::int64_t j) { inv[orig[j]] = std::int32_t(j); });
    if (how == Update::Insert)
      mesh::curve_hints(ex, orig, S.m, n, mesh::BelowIndex{std::int32_t(K.n)}, hint);
    if (how == Update::Move && moved.nout) {
      st.counters["move_reinserted"] = moved.nout;
      mesh::curve_hints(ex, orig, S.m, n, mesh::NotFlagged{moved.out.data()}, hint);
    }
    if (walks)
      ex.for_each_index(
          S.m, GG_LAMBDA(std::int64_t j) {
            const std::int32_t h = hint[orig[j]];
            near[j] = h >= 0 ? inv[h] : -1;
          });
    T.start_from(start, start_used, inv, walks ? near : nullptr);
    if (how == Update::Move) T.flip_start();
    st.phase_ms.push_back({"start", ms_since(t0)});
    T.insert_all();
    st.phase_ms.push_back({"insert_flip", ms_since(t0)});
    // Only the slots the insertions rewrote (or the refill wrote, and their neighbours) can hold
    // faces that are not locally Delaunay (all of them may, where the points moved).
    typename Exec::template Buffer<std::int8_t> d_touched;
    if (how == Update::Insert) d_touched = touched_slots(ex, T, K, inv);
    if (how == Update::Remove) d_touched = refilled_slots(ex, T, filled);
    repair_phase(ex, T, S.m, opt.progress, st, how == Update::Move ? nullptr : d_touched.data());
  }
  t0 = Clock::now();
  T.report();
  R.n = n;
  R.ndup = S.duplicates;
  if (dup_map) R.dup = std::move(S.dup);
  for (int k = 0; k < 3; ++k) R.kernel[k] = first.s[k];
  R.used = T.counters().used;
  R.tet = keep_store(ex, T, S.orig.data());
  {
    LeasePool<Exec> pool = flat_test_pool(ex);
    const KeptTets s{R.tet.data(), R.xyz.data(), pool.view};
    auto cnt = ex.template alloc<std::int64_t>(1);
    ex.transform_reduce_into(
        R.used, GG_LAMBDA(std::int64_t t)->std::int64_t { return s.live(t); }, std::int64_t(0),
        thrust::plus<std::int64_t>(), cnt.data());
    ex.to_host(cnt.data(), 1, &R.nout);
  }
  st.phase_ms.push_back({"keep", ms_since(t0)});
  return R;
}

class KeptOn final : public Kept {
 public:
  explicit KeptOn(const Delaunay3dOptions& opt) : opt_(opt) {}
  void insert(const double* xyz, std::int64_t n, bool on_device, Stats& st) override {
    if (n == 0 && K_.n) return;
    Exec ex(opt_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    ::gpugeom::detail::require_device_memory(ex, K_.n + n, kLeastBytesPerPoint,
                                             "a 3D Delaunay tetrahedralisation", "points");
    KeptArrays R = with_points(ex, K_, xyz, n, on_device, false, st);
    before_.commit(K_, kept_update(ex, K_, std::move(R), K_.n + n, Update::Insert, opt_, st));
  }
  void move(const double* xyz, bool on_device, Stats& st) override {
    Exec ex(opt_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    ::gpugeom::detail::require_device_memory(ex, K_.n, kLeastBytesPerPoint,
                                             "a 3D Delaunay tetrahedralisation", "points");
    KeptArrays R = with_points(ex, K_, xyz, K_.n, on_device, true, st);
    before_.commit(K_, kept_update(ex, K_, std::move(R), K_.n, Update::Move, opt_, st));
  }
  void remove(const std::int32_t* idx, std::int64_t count, bool on_device, Stats& st) override {
    if (count == 0) return;
    Exec ex(opt_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    typename Exec::template Buffer<std::int32_t> up;
    if (!on_device) {
      up = ex.template alloc<std::int32_t>(std::size_t(count));
      ex.from_host(idx, count, up.data());
      idx = up.data();
    }
    auto gone = mesh::removal_flags(ex, K_.gone_map(), K_.n, idx, count);
    KeptArrays R = with_points(ex, K_, nullptr, 0, false, false, st);
    R.gone = std::move(gone);
    R.nremoved = K_.nremoved + count;
    before_.commit(K_, kept_update(ex, K_, std::move(R), K_.n, Update::Remove, opt_, st));
  }
  std::int64_t points() const override { return K_.n; }
  std::int64_t removed() const override { return K_.nremoved; }
  std::int64_t simplices() const override { return K_.nout; }
  std::int64_t duplicates() const override { return K_.ndup; }
  // The results: tetrahedra and neighbours, the vertex map and the hull facets.
  struct Results {
    mesh::Compacted<Exec> f;
    Extras E;
  };
  static mesh::Compacted<Exec> compacted(Exec& ex, const KeptArrays& A) {
    LeasePool<Exec> pool = flat_test_pool(ex);
    return mesh::compact_live<4>(ex, A.used, KeptTets{A.tet.data(), A.xyz.data(), pool.view});
  }
  Results results(Exec& ex) const {
    Results r;
    r.f = compacted(ex, K_);
    r.E = extras(ex, K_.dup_map(), r.f, K_.n);
    return r;
  }
  void track_changes(bool on) override { before_.set(on); }
  bool has_changes() const override { return before_.held; }
  void host_changes(SimplexChanges& out) const override {
    Exec ex(opt_);
    mesh::host_changes<4>(ex, compacted(ex, before_.arrays), compacted(ex, K_), out);
  }
  void device_changes(DeviceSimplexChanges& out) const override {
    Exec ex(opt_);
    mesh::device_changes<4>(ex, compacted(ex, before_.arrays), compacted(ex, K_), out);
  }
  void host_copy(Output& out) const override {
    Exec ex(opt_);
    Results r = results(ex);
    mesh::Compacted<Exec>& f = r.f;
    const std::int64_t nh = r.E.num_hull_facets;
    out.num_tetrahedra = f.count;
    out.num_duplicates = K_.ndup;
    out.num_hull_facets = nh;
    auto put = [&](const std::int32_t* src, std::int64_t count, HostVector<std::int32_t>& dst) {
      dst.resize(std::size_t(count));
      ex.to_host(src, count, dst.data());
    };
    put(f.simplices.data(), 4 * f.count, out.tetrahedra);
    put(f.neighbors.data(), 4 * f.count, out.neighbors);
    put(r.E.vertex_to_simplex.data(), K_.n, out.vertex_to_simplex);
    put(r.E.hull_facets.data(), 3 * nh, out.hull_facets);
    out.duplicate_of.resize(std::size_t(K_.n));
    if (K_.dup_map())
      ex.to_host(K_.dup.data(), K_.n, out.duplicate_of.data());
    else
      ex.fill_host(out.duplicate_of.data(), K_.n, std::int32_t(-1));
  }
  void device_copy(DeviceOutput& out) const override {
    Exec ex(opt_);
    Results r = results(ex);
    auto dup = ex.template alloc<std::int32_t>(std::size_t(K_.n));
    if (K_.dup_map())
      ex.copy(K_.dup.data(), K_.n, dup.data());
    else
      ex.fill(dup.data(), K_.n, std::int32_t(-1));
    ex.sync();  // (the caller may read them, and free them on any stream)
    out.num_tetrahedra = r.f.count;
    out.num_duplicates = K_.ndup;
    out.num_hull_facets = r.E.num_hull_facets;
    out.tetrahedra = r.f.simplices.hand_over();
    out.neighbors = r.f.neighbors.hand_over();
    out.duplicate_of = dup.hand_over();
    out.vertex_to_simplex = r.E.vertex_to_simplex.hand_over();
    out.hull_facets = r.E.hull_facets.hand_over();
  }

  Delaunay3dOptions opt_;
  KeptArrays K_;
  ::gpugeom::detail::Before<KeptArrays> before_;
};
