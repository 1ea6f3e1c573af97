// A 3D Delaunay tetrahedralisation kept on the executor (kept.inl tells how it is kept): the
// moves' predicted holes and starts, and the update of the kept store after an insertion, a
// move or a removal. Included after kept.inl.

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
                                const Delaunay3dOptions& opt, Delaunay3dStats& st) {
  MovedStart3d M;
  M.out = ex.template alloc<std::int8_t>(std::size_t(n));
  ex.fill(M.out.data(), n, std::int8_t(0));
  Refill3d f;
  const Tet* cur = K.tet.data();
  std::int64_t used = K.used;
  bool grown = false;  // the last fill lacked boundary faces: its hole grew, fill again
  std::optional<GrowScratch> scratch;
  for (int round = 0; round < kMoveRounds; ++round) {
    st.move_rounds = round + 1;
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
        st.move_grown += more;
        M.nout += more;
        if (!more) break;
      }
    }
    st.move_taken_out = M.nout;
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
                              Update how, const Delaunay3dOptions& opt, Delaunay3dStats& st) {
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
    st.remove_rebuilt = fresh;
    start = filled.tet.data(), start_used = filled.used;
  }
  MovedStart3d moved;
  if (!fresh && how == Update::Move) {
    const auto t1 = Clock::now();
    const bool same_points =
        S.duplicates == K.ndup && mesh::dup_changes(ex, K.dup_map(), dup_map, n) == 0;
    if (same_points) moved = moved_start(ex, K, R.xyz.data(), n, opt, st);
    fresh = !moved.ok;
    st.move_rebuilt = fresh;
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
    if (how == Update::Insert) st.inserted_points = S.m - (K.n - K.ndup - K.nremoved);
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
      st.move_reinserted = moved.nout;
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
  void insert(const double* xyz, std::int64_t n, bool on_device, Delaunay3dStats& st) override {
    if (n == 0 && K_.n) return;
    Exec ex(opt_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    ::gpugeom::detail::require_device_memory(ex, K_.n + n, kLeastBytesPerPoint,
                                             "a 3D Delaunay tetrahedralisation", "points");
    KeptArrays R = with_points(ex, K_, xyz, n, on_device, false, st);
    before_.commit(K_, kept_update(ex, K_, std::move(R), K_.n + n, Update::Insert, opt_, st));
  }
  void move(const double* xyz, bool on_device, Delaunay3dStats& st) override {
    Exec ex(opt_);
    const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
    ::gpugeom::detail::require_device_memory(ex, K_.n, kLeastBytesPerPoint,
                                             "a 3D Delaunay tetrahedralisation", "points");
    KeptArrays R = with_points(ex, K_, xyz, K_.n, on_device, true, st);
    before_.commit(K_, kept_update(ex, K_, std::move(R), K_.n, Update::Move, opt_, st));
  }
  void remove(const std::int32_t* idx, std::int64_t count, bool on_device,
              Delaunay3dStats& st) override {
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
