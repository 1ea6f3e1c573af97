// Batch insertion with parallel flipping (thesis 5.3 in 2D), one algorithm for both
// executors; included inside gpugeom::del2d::{cpu,cuda}_impl after prepare.inl and mesh.inl.
//
// Each batch: every triangle holding points not yet inserted takes the one nearest its
// circumcentre and splits around it. Then rounds of flips: every triangle on the work list
// tests its edges (filter, then an exact pass over the compacted undecided tests), proposes to
// flip its first illegal edge, and a flip goes ahead when its proposer has the highest
// priority (a fixed scramble of the slot number) among the proposals touching either of its
// two triangles, so every round flips and the result never depends on timing. Flipped and
// outvoted triangles form the next list. Splits and flips are recorded; at the start of the
// next batch each point not yet inserted follows its triangle through the records (the
// thesis' history) and takes part in the choice in the same pass, so the points are read once
// per batch. The final triangulation is the Delaunay triangulation of the perturbed points;
// flat triangles on the hull (collinear hull points the perturbation moved inward) are flipped
// away at the end, which leaves every finite triangle of positive area.

// Exact-pass threads, each with an 8 kB scratch slice: enough to fill the GPU on degenerate
// input (an integer grid sends most in-circle tests to the exact stage), at most ~0.5 GB.
constexpr std::int64_t kExactSlotsMin = 1024, kExactSlotsMax = 65536;
constexpr std::int64_t kMaxRounds = 1000000;  // per batch; every round flips at least once
constexpr bool kReadAhead = Exec::backend == Backend::Cuda;  // (see the flip kernel)
constexpr std::int64_t kSmallRound = 8192;  // (counted: rounds whose launches are mostly latency)
// Lists this short run this many rounds between two reads of the counters.
constexpr std::int64_t kChunkList = 65536;
constexpr int kChunkRounds = 4;
constexpr std::int64_t kWinBuckets = 4096;  // (check_round)

// (Every member is public: nvcc's extended lambdas may not live in private members.)
class Triangulator {
 public:
  Triangulator(Exec& ex, Prepared& P, Stats& st, bool profile)
      : ex_(ex), P_(P), st_(st), profile_(profile) {
    m_ = std::int32_t(P.m);
    tmax_ = 2 * std::int64_t(m_) - 2;
    // Tests only (Tuning::Del2d::slot_base): slots numbered from base_ rather than 0, up to
    // the encoding's last slot, so that small inputs run through the top of the wide encoding
    // (bit 31 set in neighbour pointers and list entries). The slot-indexed arrays are then
    // addressed through pointers offset by -base_ (tri(), best(), srank(), M_).
    const detail::Tuning::Del2d& forced = ex.tuning().del2d;
    base_ = std::clamp<std::int64_t>(forced.slot_base, 0, Adj::kMaxSlots - tmax_);
    g_.p = P.pts.data();
    g_.s[0] = P.kernel[0];
    g_.s[1] = P.kernel[1];
    g_.m = m_;
    const std::size_t T = std::size_t(tmax_), n = std::size_t(m_);
    tri_ = ex.template alloc<Tri>(T);
    vote_ = ex.template alloc<u64>(T);  // (also the batches' claims: see claim_of)
    split_rank_ = ex.template alloc<std::int32_t>(T);
    lists_[0] = ex.template alloc<std::int32_t>(T);
    lists_[1] = ex.template alloc<std::int32_t>(T);
    dec_ = ex.template alloc<std::int8_t>(T);
    // The exact pass's list holds a sixteenth of the slots (at least 2^20, so the rounds that
    // run unchecked never overflow it): the filter decides nearly every test on most input,
    // and a round with more undecided entries decides them in further passes.
    exact_cap_ =
        std::min(tmax_, forced.exact_entries > 0 ? forced.exact_entries
                                                 : std::max<std::int64_t>(tmax_ / 16, 1 << 20));
    const std::size_t X = std::size_t(exact_cap_);
    exl_ = ex.template alloc<std::int32_t>(X);
    exd_ = ex.template alloc<std::int8_t>(3 * X);
    exc_ = ex.template alloc<std::int32_t>(X);
    ex.fill(exc_.data(), exact_cap_, std::int32_t(0));
    loc_ = ex.template alloc<std::int32_t>(n);
    un_ = ex.template alloc<std::int32_t>(n);
    ins_cap_ = forced.batch_points > 0 ? forced.batch_points
                                       : std::max<std::int64_t>(1024, 3 * (m_ / 8) + 1);
    ins_ = ex.template alloc<std::int32_t>(std::size_t(ins_cap_));
    split_ = ex.template alloc<std::int32_t>(std::size_t(4 * ins_cap_));
    ctr_ = ex.template alloc<Counters>(1);
    hist_ = ex.template alloc<Hist>(T);
    slots_ = ScratchSlots<Exec>(
        ex, std::clamp<std::int64_t>(tmax_ / 64, kExactSlotsMin, kExactSlotsMax), kIncircleScratch);
    // The winning proposals of a checked round are counted in buckets of slots, each no
    // larger than the log.
    win_shift_ = 0;
    while ((tmax_ >> win_shift_) >= kWinBuckets) ++win_shift_;
    wins_ = ex.template alloc<std::int64_t>(std::size_t((tmax_ >> win_shift_) + 1));
    log_cap_ = std::max(log_capacity(ex, forced.log_records, tmax_), std::int64_t(1) << win_shift_);
    rec_ = ex.template alloc<std::int32_t>(std::size_t(FlipLog::kStride * log_cap_));
    M_ = Mesh{tri(), vote_.data() - base_, FlipLog{rec_.data(), hist_.data() - base_, 0},
              std::int32_t(base_)};
    ex.fill(hist_.data(), tmax_, Hist{-1, -1});
    ex.fill(vote_.data(), tmax_, u64(0));
    ex.fill(split_rank_.data(), tmax_, std::int32_t(-1));
    Counters zero{};
    ex.from_host(&zero, 1, ctr_.data());
  }

  // peel_flats false leaves the flat triangles on the hull (the Delaunay triangulation of the
  // perturbed points, which a later start needs: DynamicDelaunay2d drops them from its output).
  void run(bool peel_flats = true) {
    auto t0 = clock::now();
    start();
    remaining_ = nun_;
    while (remaining_ > 0) batch();
    phase("insert", t0);
    if (!peel_flats) return;
    t0 = clock::now();
    peel();
    phase("peel", t0);
  }

  // Finite triangles in input indices, neighbours among them, left on the executor.
  using Finished = mesh::Compacted<Exec>;
  struct FiniteTriangles {  // (the store as the output step reads it)
    const Tri* tri;         // from slot base: position t is slot base + t
    const std::int32_t* orig;
    std::int32_t m;  // the infinity point
    std::int32_t base;
    GG_HD bool live(std::int64_t t) const {
      const std::int32_t* v = tri[t].v;
      return v[0] != m && v[1] != m && v[2] != m;
    }
    GG_HD mesh::SimplexRecord<3> get(std::int64_t t) const {
      const Tri T = tri[t];
      mesh::SimplexRecord<3> r;
      for (int k = 0; k < 3; ++k) r.v[k] = orig[T.v[k]], r.n[k] = simplex_of(T.n[k]) - base;
      return r;
    }
  };
  // Frees what only the insertion and flip rounds use (everything but the triangle store and
  // the counters), so the output arrays that finish() makes reuse that memory instead of adding
  // to it: the device peak of a triangulation is then the rounds', not rounds' plus output's
  // (issue 23). Call after run() and report()'s counters are safe (they live on in ctr_).
  void release_work() {
    auto drop = [](auto& b) { b = std::remove_reference_t<decltype(b)>(); };
    drop(hist_), drop(split_rank_), drop(rec_), drop(split_), drop(vote_);
    drop(lists_[0]), drop(lists_[1]), drop(exl_), drop(exc_), drop(loc_), drop(un_);
    drop(ins_), drop(dec_), drop(exd_), drop(slots_), drop(wins_);
  }
  Finished finish() {
    // (the extended triangulation has 2m - 2 slots, all in use)
    return mesh::compact_live<3>(
        ex_, tmax_, FiniteTriangles{tri_.data(), P_.orig.data(), m_, std::int32_t(base_)});
  }

  using clock = std::chrono::steady_clock;
  void phase(const char* name, clock::time_point t0) {
    ex_.sync();
    st_.phase_ms.push_back({name, ms_since(t0)});
  }
  mesh::WorkLists work_lists() {
    return mesh::WorkLists{{lists_[0].data(), lists_[1].data()}, ctr_.data()->len};
  }
  Counters counters() {
    Counters c;
    ex_.to_host(ctr_.data(), 1, &c);
    return c;
  }

  // The first triangle and its three infinite neighbours; every other point is located.
  void start() {
    const std::int32_t a = P_.first[0], b = P_.first[1], c = P_.first[2], I = m_;
    const std::int32_t B = std::int32_t(base_);
    auto e = [B](std::int32_t s, int k) { return enc(B + s, k); };
    // slot 0 (a,b,c); slot 1 (c,b,I) across bc; slot 2 (a,c,I) across ca; slot 3 (b,a,I).
    const Tri first[4] = {{{a, b, c}, {e(1, 2), e(2, 2), e(3, 2)}, -1, 0},
                          {{c, b, I}, {e(3, 1), e(2, 0), e(0, 0)}, -1, 0},   // (b,I) (I,c) (c,b)
                          {{a, c, I}, {e(1, 1), e(3, 0), e(0, 1)}, -1, 0},   // (c,I) (I,a) (a,c)
                          {{b, a, I}, {e(2, 1), e(1, 0), e(0, 2)}, -1, 0}};  // (a,I) (I,b) (b,a)
    ex_.from_host(first, 4, tri_.data());
    ntri_ = 4;
    const Geo g = g_;
    std::int32_t* loc = loc_.data();
    const Tri* tri = tri_.data();
    Counters* ctr = ctr_.data();
    ex_.for_each_index(
        m_, GG_LAMBDA(std::int64_t i) {
          const std::int32_t q = std::int32_t(i);
          if (q == a || q == b || q == c) {
            loc[q] = -1;
            return;
          }
          std::int32_t found = -1;
          for (std::int32_t t = 0; t < 4 && found < 0; ++t)
            if (inside_ext(g, tri[t].v, q)) found = B + t;
          loc[q] = found;
          if (found < 0) atomic_add(&ctr->lost, std::int64_t(1));
        });
    nun_ = ex_.compact_indices(
        m_, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, un_.data());
    check_lost();
  }

  // The same from a given triangulation (the digital method's sketch, issue 20) instead of the
  // first triangle: tris, counter-clockwise triangles of prepared indices covering the convex
  // hull of their vertices with each directed edge once, gets its hull edges joined to the
  // infinity vertex (2k - 2 slots for its k vertices, as the insertions would have left); the
  // other points are located by walks; then the whole of it is flipped until Delaunay, and the
  // batches insert the rest as they do after start(). P.kernel must lie inside it.
  // start_delaunay: the start is already the Delaunay triangulation of its vertices under the
  // perturbation, flat hull triangles included (DynamicDelaunay2d's kept one): its edges are not
  // tested (on a grid every test is a cocircular one, decided by the exact stage).
  void run_from(const std::int32_t* tris, const std::int32_t* twin, std::int64_t f,
                const std::int32_t* near, bool peel_flats = true, bool start_delaunay = false) {
    auto t0 = clock::now();
    start_from(tris, twin, f, near, start_delaunay);
    phase("start", t0);
    t0 = clock::now();
    remaining_ = nun_;
    while (remaining_ > 0) batch();
    phase("insert", t0);
    t0 = clock::now();
    if (!peel_flats) return;
    peel();
    phase("peel", t0);
  }

  // All in executor memory: tris (3 f), twin (per half-edge 3t + k, vertex k to k + 1: its
  // reverse or -1), near (per prepared point, a start vertex near it or -1, where its walk
  // begins; or null). The records are built on the executor: the hull edges numbered by a scan
  // in half-edge order, each vertex's outgoing and incoming hull edge found by scatter.
  void start_from(const std::int32_t* tris, const std::int32_t* twin, std::int64_t f,
                  const std::int32_t* near, bool start_delaunay) {
    const std::int32_t I = m_, B = std::int32_t(base_);
    const std::int64_t nh = 3 * f;
    auto in = ex_.template alloc<std::int8_t>(std::size_t(m_));
    auto outs = ex_.template alloc<std::int32_t>(std::size_t(m_));
    auto ins = ex_.template alloc<std::int32_t>(std::size_t(m_));
    auto from = ex_.template alloc<std::int32_t>(std::size_t(m_));
    auto hpos = ex_.template alloc<std::int64_t>(std::size_t(nh + 1));
    std::int8_t* used = in.data();
    std::int32_t* out_slot = outs.data();
    std::int32_t* in_slot = ins.data();
    std::int32_t* slot_of = from.data();
    std::int64_t* pos = hpos.data();
    ex_.fill(used, m_, std::int8_t(0));
    ex_.fill(out_slot, m_, std::int32_t(-1));
    ex_.fill(in_slot, m_, std::int32_t(-1));
    ex_.fill(slot_of, m_, std::numeric_limits<std::int32_t>::max());
    ex_.exclusive_scan_of(
        nh + 1, GG_LAMBDA(std::int64_t e)->std::int64_t { return e < nh && twin[e] < 0; }, pos);
    std::int64_t nb = 0;
    ex_.to_host(pos + nh, 1, &nb);
    if (f + nb > tmax_)
      throw Error(ErrorCode::Internal, "start triangulation: " + std::to_string(f + nb) +
                                           " slots for at most " + std::to_string(tmax_));
    Tri* tri = tri_.data();
    ex_.for_each_index(
        f, GG_LAMBDA(std::int64_t t) {
          Tri T;
          for (int k = 0; k < 3; ++k) {
            T.v[k] = tris[3 * t + k];
            used[T.v[k]] = 1;
            atomic_min(&slot_of[T.v[k]], std::int32_t(t));
          }
          T.stamp = -1, T.pair = 0;
          for (int k = 0; k < 3; ++k) {
            const std::int64_t e = 3 * t + (k + 1) % 3;  // the edge opposite vertex k
            const std::int32_t o = twin[e];
            if (o >= 0) {
              T.n[k] = enc(B + o / 3, (o % 3 + 2) % 3);
            } else {  // a hull edge a->b: the infinite triangle (b, a, I) across
              const std::int32_t slot = std::int32_t(f + pos[e]);
              T.n[k] = enc(B + slot, 2);
              out_slot[T.v[(k + 1) % 3]] = slot, in_slot[T.v[(k + 2) % 3]] = slot;
            }
          }
          tri[t] = T;
        });
    // Each hull vertex has one outgoing and one incoming hull edge: as many of each as edges.
    auto cnt = ex_.template alloc<std::int64_t>(3);
    ex_.transform_reduce_into(
        m_, GG_LAMBDA(std::int64_t v)->std::int64_t { return out_slot[v] >= 0; }, std::int64_t(0),
        thrust::plus<std::int64_t>(), cnt.data());
    ex_.transform_reduce_into(
        m_, GG_LAMBDA(std::int64_t v)->std::int64_t { return in_slot[v] >= 0; }, std::int64_t(0),
        thrust::plus<std::int64_t>(), cnt.data() + 1);
    ex_.transform_reduce_into(
        m_, GG_LAMBDA(std::int64_t v)->std::int64_t { return used[v]; }, std::int64_t(0),
        thrust::plus<std::int64_t>(), cnt.data() + 2);
    std::int64_t c[3];
    ex_.to_host(cnt.data(), 3, c);
    if (c[0] != nb || c[1] != nb)
      throw Error(ErrorCode::Internal, "start triangulation: its boundary passes a vertex twice");
    const std::int64_t k = c[2];
    if (f + nb != 2 * k - 2)
      throw Error(ErrorCode::Internal, "start triangulation: " + std::to_string(f + nb) +
                                           " slots for " + std::to_string(k) +
                                           " vertices (a triangulation of a disk has 2k - 2)");
    ex_.for_each_index(
        nh, GG_LAMBDA(std::int64_t e) {
          if (twin[e] >= 0) return;
          const std::int64_t t = e / 3;
          const int j = int(e % 3);  // a = v[j] -> b = v[j + 1]; opposite vertex j + 2
          const std::int32_t a = tris[e], b = tris[3 * t + (j + 1) % 3];
          Tri X;
          X.v[0] = b, X.v[1] = a, X.v[2] = I;
          X.n[2] = enc(B + std::int32_t(t), (j + 2) % 3);
          X.n[0] = enc(B + in_slot[a], 1);   // across (a, I): the hull edge ending at a
          X.n[1] = enc(B + out_slot[b], 0);  // across (I, b): the hull edge starting at b
          X.stamp = -1, X.pair = 0;
          tri[f + pos[e]] = X;
        });
    ntri_ = f + nb;
    // Each walk from a triangle of its hint's (a slot of the start), else from the first.
    auto walk_from = ex_.template alloc<std::int32_t>(std::size_t(m_));
    std::int32_t* from_slot = walk_from.data();
    ex_.for_each_index(
        m_, GG_LAMBDA(std::int64_t q) {
          const std::int32_t v = near ? near[q] : -1;
          from_slot[q] = v >= 0 && used[v] ? slot_of[v] : 0;
        });
    // The other points, each located by a walk (stochastic: the leaving edge drawn; a scan of
    // every slot bounds it). Counted: steps, walks that ended in the scan, the longest walk.
    const Geo g = g_;
    std::int32_t* loc = loc_.data();
    const std::int8_t* inside = used;
    Counters* ctr = ctr_.data();
    const std::int64_t nt = ntri_;
    auto walk_stats = ex_.template alloc<std::int64_t>(3);  // steps, scans, longest walk
    std::int64_t* ws = walk_stats.data();
    ex_.fill(ws, 3, std::int64_t(0));
    ex_.for_each_index(
        m_, GG_LAMBDA(std::int64_t i) {
          const std::int32_t q = std::int32_t(i);
          if (inside[q]) {
            loc[q] = -1;
            return;
          }
          std::int64_t t = from_slot[q];
          for (std::int64_t step = 0; step <= nt; ++step) {
            const Tri T = tri[t];
            int leave = -1;
            // The edges in an order drawn by hashing (point, step): a walk that always prefers
            // the same edge can cycle in a triangulation that is not Delaunay (the start's: a few
            // such points each cost a walk of every slot, then a scan of them all, seconds at
            // 10^7); drawn, it ends with probability one (the stochastic walk).
            const int r =
                int(mesh::scatter(std::uint32_t(q) * 2654435761u + std::uint32_t(step)) % 3);
            for (int j = 0; j < 3 && leave < 0; ++j) {
              const int kk = (r + j) % 3;
              if (orient_ext(g, T.v[(kk + 1) % 3], T.v[(kk + 2) % 3], q) < 0) leave = kk;
            }
            if (leave < 0) {
              loc[q] = B + std::int32_t(t);
              atomic_add(&ws[0], step);
              atomic_max(&ws[2], step);
              return;
            }
            t = simplex_of(T.n[leave]) - B;
          }
          atomic_add(&ws[1], std::int64_t(1));
          for (t = 0; t < nt; ++t)
            if (inside_ext(g, tri[t].v, q)) {
              loc[q] = B + std::int32_t(t);
              return;
            }
          loc[q] = -1;
          atomic_add(&ctr->lost, std::int64_t(1));
        });
    {
      std::int64_t w[3];
      ex_.to_host(ws, 3, w);
      st_.counters["start_walk_steps"] = w[0];
      st_.counters["start_walk_scans"] = w[1];
      st_.counters["start_walk_longest"] = w[2];
    }
    nun_ = ex_.compact_indices(
        m_, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, un_.data());
    check_lost();
    if (start_delaunay) return;
    // Every slot's edges tested, and flipped until Delaunay; the flips are logged, so the points
    // follow their triangles when the first batch relocates them.
    const mesh::WorkLists L = work_lists();
    std::int32_t* act = L.current(round_ + 1);
    std::int64_t* len = L.count(round_ + 1);
    ex_.for_each_index(
        nt, GG_LAMBDA(std::int64_t i) {
          if (i == 0) *len = nt;
          act[i] = list_entry(B + std::int32_t(i), -1);
        });
    nact_ = nt;
    flip_until_delaunay(false);
  }

  void check_lost() {
    Counters c = counters();
    if (c.lost)
      throw Error(ErrorCode::Internal,
                  "internal error: " + std::to_string(c.lost) +
                      " point(s) could not be located; please report this input");
  }

  // One batch. The points move (through the last batch's split and flips) and choose in one
  // pass; the chosen points are then collected in curve order.
  void batch() {
    ++batches_;
    mark("other");
    relocate(true);
    mark("relocate+choose");
    // The chosen points in curve order, so that the new slots (and the work lists, which
    // follow them) go through the plane along the curve: neighbouring slots then share memory
    // sectors of the points and of each other, where triangle order scattered every access.
    // (The work lists are free between batches: one holds them, the other the new list.)
    u64* claim = this->claims();
    std::int32_t* ins = ins_.data();
    std::int32_t* chosen = spare_list();
    const std::int64_t nchosen = ex_.copy_if(un_.data(), nun_, chosen, Chosen{loc_.data(), claim});
    // A batch inserts at most ins_cap_ points (its split records are sized for that): the
    // first ones along the curve; the other triangles keep their points for the next batch.
    const std::int64_t nins = std::min(nchosen, ins_cap_);
    mark("compact chosen");
    std::int32_t* srank = this->srank();
    const std::int32_t* locc = loc_.data();
    const std::int64_t cap = ins_cap_;
    ex_.for_each_index(
        nchosen, GG_LAMBDA(std::int64_t r) {
          const std::int32_t t = locc[chosen[r]];
          if (r >= cap) {
            claim[t] = 0;  // (no claim may outlive the split: the rounds' votes would lose to it)
            return;
          }
          ins[r] = t;
          srank[t] = std::int32_t(r);
        });
    const Mesh M = M_;
    const std::int32_t first_new = std::int32_t(base_ + ntri_);
    const mesh::WorkLists L = work_lists();
    std::int32_t* act = L.current(round_ + 1);  // the next round's list
    std::int64_t* len = L.count(round_ + 1);
    std::int32_t* sp = split_.data();
    std::int32_t* loc = loc_.data();
    ex_.for_each_index(
        nins, GG_LAMBDA(std::int64_t r) {
          if (r == 0) *len = 3 * nins;
          const std::int32_t t = ins[r], q = claimant_of(claim[t]);
          const std::int32_t base = first_new + 2 * std::int32_t(r);
          sp[4 * r] = q;  // what the points of t need to find their child later
          for (int k = 0; k < 3; ++k) sp[4 * r + 1 + k] = M.tri[t].v[k];
          split_triangle(M, t, q, base, srank, first_new);
          claim[t] = 0;
          loc[q] = -1;
          act[3 * r] = t;
          act[3 * r + 1] = base;
          act[3 * r + 2] = base + 1;
        });
    ntri_ += 2 * nins;
    mark("split");
    epoch_splits_ = nins;
    epoch_first_new_ = first_new;
    remaining_ -= nins;
    dead_ += nins;
    if (dead_ * 4 > nun_) {  // drop inserted points from the list once they are a quarter
      std::int32_t* kept = spare_list();  // (the other list holds the rounds' first list)
      nun_ = ex_.copy_if(un_.data(), nun_, kept, NotInserted{loc});
      ex_.copy(kept, nun_, un_.data());
      dead_ = 0;
    }
    mark("compact points");
    nact_ = 3 * nins;
    flip_until_delaunay(true);  // the list holds the children of the splits, new point first
  }

  // A batch's choice shares the vote array with the flip rounds (they never overlap): each
  // point claims its triangle with its choice key (its top 31 bits) and index, complemented so
  // that the largest claim is the best point (the rounds' keys also win by atomic max). A
  // claim's high word is then at least 2^31, above every round number in a vote key, so the
  // votes the rounds left need no clearing; the split sets its triangles' entries to 0 (none).
  GG_HD static u64 claim_of(std::uint32_t choice, std::int32_t q) {
    return ~((u64(choice >> 1) << 32) | u64(std::uint32_t(q)));
  }
  GG_HD static std::int32_t claimant_of(u64 claim) { return std::int32_t(~std::uint32_t(claim)); }
  // q is the point its triangle chose.
  struct Chosen {
    const std::int32_t* loc;
    const u64* claim;
    GG_HD bool operator()(std::int32_t q) const {
      const std::int32_t L = loc[q];
      return L >= 0 && claimant_of(claim[L]) == q;
    }
  };
  // Flip records the log holds. Past its capacity the points are relocated (a pass over all
  // points not yet inserted), so it takes what memory is left, from a quarter as many records
  // as points (6 B a point; the memory check before launch counts this) to as many as the
  // most flips of any round (24 B). It never changes the result (flip_round). Measured on
  // uniform input at 10^6: a batch logs up to about 0.7 m flips, one round up to 0.45 m.
  // (At least 2^20 records: the rounds that run unchecked, several between two reads of the
  // counters, stay below that.)
  static std::int64_t log_capacity(Exec& ex, std::int64_t forced_records, std::int64_t tmax) {
    if (forced_records > 0) return forced_records;
    const std::int64_t least = std::max<std::int64_t>(tmax / 8, 1 << 20);
    const std::int64_t most = std::max<std::int64_t>(tmax / 2, least);
    // (a margin for the pool's blocks and the temporary storage of compactions)
    const std::uint64_t avail = ex.available_memory();
    const std::uint64_t margin = (std::uint64_t(1) << 29) + avail / 64;
    const std::int64_t fit = avail > margin
                                 ? std::int64_t(std::min<std::uint64_t>(
                                       (avail - margin) / (FlipLog::kStride * sizeof(std::int32_t)),
                                       std::uint64_t(most)))
                                 : 0;
    return std::clamp(fit, least, most);
  }
  // The work list that the next round does not read (free between rounds and batches).
  std::int32_t* spare_list() { return work_lists().current(round_); }

  struct NotInserted {
    const std::int32_t* loc;
    GG_HD bool operator()(std::int32_t q) const { return loc[q] >= 0; }
  };

  // f(i) for every i < *count (on the executor), *count <= bound. (The executor's counted
  // grid covers the bound in whole waves; an earlier one-wave cap left a partial second wave at
  // these kernels' occupancy: fix and flip kernels 20-60% slower.)
  template <class F>
  void listed(const std::int64_t* count, std::int64_t bound, F f) {
    ex_.for_each_counted(count, bound, f);
  }

  // Rounds of flips over the work list until no edge of it is illegal. A round: the edge tests
  // (each entry stops at its first illegal edge, proposes it and votes at once; an entry the
  // filter cannot decide goes to the exact pass, which goes on from there and votes), the flips
  // (a proposal that won both its triangles), and the fix of the flipped pairs' outer edges.
  // The list lengths stay on the executor: short lists (a batch's last rounds) run several
  // rounds between two reads of the counters, so that the host's round trip does not leave
  // the GPU idle once per round (a round past the end finds an empty list and does nothing).
  void flip_until_delaunay(bool first_round) {
    std::int64_t rounds_here = 0;
    while (nact_ > 0) {
      // A list at most doubles per round, and a round flips at most one pair per entry and
      // tmax / 2 pairs in all. Rounds run unchecked (several between two reads of the
      // counters) while their records fit the log and their undecided entries the exact
      // list; a round that could overflow either is checked (flip_round's `checked`).
      int chunk = nact_ <= kChunkList ? kChunkRounds : 1;
      auto records = [&](int rounds) {
        std::int64_t b = nact_, r = 0;
        for (int c = 0; c < rounds; ++c, b = std::min(2 * b, tmax_)) r += std::min(b, tmax_ / 2);
        return r;
      };
      auto longest = [&](int rounds) {
        std::int64_t b = nact_;
        for (int c = 1; c < rounds; ++c) b = std::min(2 * b, tmax_);
        return b;
      };
      // (A check costs the host a round trip; relocating all points that are left, many
      // more: the log is only emptied when a check finds it would overflow.)
      if (logged_ + records(chunk) > log_cap_ || longest(chunk) > exact_cap_) chunk = 1;
      const bool checked = logged_ + records(1) > log_cap_ || nact_ > exact_cap_;
      if ((rounds_here += chunk) > kMaxRounds)
        throw Error(ErrorCode::Internal,
                    "internal error: flipping did not converge; please report this input");
      std::int64_t bound = nact_;
      for (int c = 0; c < chunk; ++c, bound = std::min(2 * bound, tmax_)) {
        flip_round(bound, first_round, checked);
        first_round = false;
      }
      const Counters c = counters();
      mark("flip: counters");
      flips_ += c.log - logged_;  // one record per flip
      logged_ = c.log;
      nact_ = c.len[(round_ + 1) & 1];
    }
  }

  // One round over its work list (at most bound long); the next round's list is appended.
  // checked: the host reads the round's counts before its flips: undecided entries past the
  // exact list's capacity go through further exact passes, and when the winning proposals
  // would overflow the flip log, the points are relocated first (the log is then empty), and
  // if they still overflow it, the flips are made in parts by slot, the points relocated
  // between two parts. Every proposal that won still flips in this round, so the schedule,
  // and the result, do not depend on either capacity.
  void flip_round(std::int64_t bound, bool first_round, bool checked) {
    ++round_;
    const Geo g = g_;
    const Mesh M = M_;
    const std::int32_t round = round_;
    const mesh::WorkLists L = work_lists();
    const std::int32_t* act = L.current(round);
    std::int8_t* dec = dec_.data();
    std::int32_t* exl = exl_.data();
    Counters* ctr = ctr_.data();
    const int p = round & 1;  // this round's tests append to exact[p]
    const std::int64_t* count = L.count(round);
    const std::int64_t exact_cap = exact_cap_;
    // In a batch's first round the list holds the children of the splits, and only their
    // edges opposite the new point need a test: the edges at the new point are locally
    // Delaunay (the point lies inside the old triangle's circumcircle, so the circle through
    // it and an old edge leaves the old triangle's third vertex outside; for an infinite
    // triangle the point lies beyond the old edge, which keeps both half-planes clear).
    // Later rounds skip the diagonal a flip just made (locally Delaunay by the flip), which
    // the list entry carries.
    const int edges = first_round ? 1 : 3;
    listed(
        count, bound, GG_LAMBDA(std::int64_t i) {
          const std::int32_t t = slot_of(act[i]);
          const int known = legal_edge_of(act[i]);
          const Tri T = M.tri[t];
          int res = -1;
          for (int k = 0; k < edges; ++k) {
            if (k == known) continue;
            const std::int32_t d = M.tri[simplex_of(T.n[k])].v[loc_of(T.n[k])];
            const int r = illegal_fast(g, T.v, d);
            if (r > 0) res = k;
            if (r == 0) res = mesh::undecided_at(k);
            if (r >= 0) break;
          }
          dec[i] = std::int8_t(res);
          if (mesh::is_undecided(res)) {
            const std::int64_t at = append_slot(&ctr->exact[p]);
            if (at < exact_cap) exl[at] = std::int32_t(i);  // (the rest: see exact_rest)
          } else if (res >= 0) {
            propose(M, round, t, simplex_of(T.n[res]));
          }
        });
    mark("flip: test");
    exact_pass(bound, edges, &ctr->exact[p], true);
    mark("flip: exact");
    std::vector<std::int64_t> cuts;
    if (checked) {
      cuts = check_round(bound, edges);
      mark("flip: check");
    }
    cuts.push_back(std::numeric_limits<std::int32_t>::max());
    vote_and_flip(act, count, bound, 0, cuts[0], true);
    for (std::size_t k = 1; k < cuts.size(); ++k) {  // the log full: the points move on first
      ++split_rounds_;
      const Counters c = counters();
      flips_ += c.log - logged_;
      logged_ = c.log;
      relocate(false);
      ++relocations_;
      vote_and_flip(act, count, bound, cuts[k - 1], cuts[k], false);
    }
    mark("flip: vote+flip");
    fix_round(act, count, bound);
    mark("flip: fix");
  }

  // The round's proposals into the counters (entries that decided on an illegal edge).
  void count_proposals(std::int64_t bound) {
    const std::int64_t* count = work_lists().count(round_);
    const std::int8_t* dec = dec_.data();
    ex_.transform_reduce_into(
        bound, GG_LAMBDA(std::int64_t i)->std::int64_t { return i < *count && dec[i] >= 0; },
        std::int64_t(0), thrust::plus<std::int64_t>(), &ctr_.data()->proposals);
  }
  // The host's part of a checked round (see flip_round): returns where the round's flips are
  // cut into parts (slots from the slot base; none: one part).
  std::vector<std::int64_t> check_round(std::int64_t bound, int edges) {
    const int p = round_ & 1;
    const std::int32_t round = round_;
    const mesh::WorkLists L = work_lists();
    const std::int32_t* act = L.current(round);
    const std::int64_t* count = L.count(round);
    std::int8_t* dec = dec_.data();
    std::int32_t* exl = exl_.data();
    Counters* ctr = ctr_.data();
    const std::int64_t exact_cap = exact_cap_;
    // Each proposal flips at most once: counted (a byte an entry, on the executor), they bound
    // the round's records. Counted before the read of the exact count, so that a round whose
    // exact list did not overflow costs one round trip.
    count_proposals(bound);
    Counters c = counters();
    // Entries left undecided (past the list's capacity) are collected and decided in turn.
    if (c.exact[p] > exact_cap_) {
      for (std::int64_t left = c.exact[p] - exact_cap_; left > 0;) {
        ++exact_rest_passes_;
        ex_.for_each_index(
            1, GG_LAMBDA(std::int64_t) { ctr->exact_rest = 0; });
        listed(
            count, bound, GG_LAMBDA(std::int64_t i) {
              if (!mesh::is_undecided(dec[i])) return;
              const std::int64_t at = append_slot(&ctr->exact_rest);
              if (at < exact_cap) exl[at] = std::int32_t(i);
            });
        exact_pass(bound, edges, &ctr->exact_rest, false);
        left = counters().exact_rest - exact_cap_;
      }
      count_proposals(bound);  // (the further passes proposed too)
      c = counters();
    }
    // The winners are counted (a pass as long as the flips' own) only when the proposals
    // alone would overflow the log.
    if (logged_ + c.proposals <= log_cap_) return {};
    relocate(false);
    ++relocations_;
    if (c.proposals <= log_cap_) return {};
    // The winning proposals per range of slots: each flip writes one record.
    const Mesh M = M_;
    const int shift = win_shift_;
    std::int64_t* wins = wins_.data();
    const std::int64_t buckets = wins_.size();
    ex_.fill(wins, buckets, std::int64_t(0));
    listed(
        count, bound, GG_LAMBDA(std::int64_t i) {
          const int k = dec[i];
          if (k < 0) return;
          const std::int32_t t = slot_of(act[i]);
          const u64 key = key_of(M, round, t);
          if (M.vote[t] == key && M.vote[simplex_of(M.tri[t].n[k])] == key)
            atomic_add(wins + ((t - M.base) >> shift), std::int64_t(1));
        });
    std::vector<std::int64_t> w(std::size_t(buckets), 0);
    ex_.to_host(wins, buckets, w.data());
    std::int64_t total = 0;
    for (const std::int64_t x : w) total += x;
    std::vector<std::int64_t> cuts;
    if (total <= log_cap_) return cuts;
    // (a bucket holds at most 2^shift <= log_cap_ proposers: every part flips)
    std::int64_t sum = 0;
    for (std::int64_t b = 0; b < buckets; ++b) {
      if (sum + w[std::size_t(b)] > log_cap_) {
        cuts.push_back(b << shift);
        sum = 0;
      }
      sum += w[std::size_t(b)];
    }
    return cuts;
  }

  // The votes counted and the winning proposals from slots in [lo, hi) (counted from the slot
  // base) flipped; on the first part, every entry that does not flip is listed for the next
  // round.
  void vote_and_flip(const std::int32_t* act, const std::int64_t* count, std::int64_t bound,
                     std::int64_t lo_in, std::int64_t hi_in, bool first_part) {
    const Mesh M = M_;  // (after a relocation: the log's new numbering)
    const std::int32_t round = round_;
    const mesh::WorkLists L = work_lists();
    const std::int8_t* dec = dec_.data();
    Counters* ctr = ctr_.data();
    const std::int32_t lo = std::int32_t(lo_in), hi = std::int32_t(hi_in);
    std::int32_t* next = L.next(round);
    std::int64_t* next_len = L.next_count(round);
    const std::int32_t log_base = M.log.base;
    listed(
        count, bound, GG_LAMBDA(std::int64_t i) {
          const int k = dec[i];
          if (k < 0) return;
          const std::int32_t t = slot_of(act[i]);
          const u64 key = key_of(M, round, t);
          const u64 won = M.vote[t];
          // On the GPU the records are read at once, not after the votes that make them this
          // thread's (a record read that way may be changing; it is then left unused): the
          // kernel waits on memory, and this takes two round trips off each flip.
          Tri T;
          if (kReadAhead && first_part) T = M.tri[t];
          if (won == key) {  // t is this proposal's: no other thread writes it this round
            if (!kReadAhead || !first_part) T = M.tri[t];
            const std::int32_t nb = simplex_of(T.n[k]);
            Tri N;
            if (kReadAhead) N = M.tri[nb];
            if (M.vote[nb] == key) {
              if (t - M.base < lo || t - M.base >= hi) return;  // another part's
              if (!kReadAhead) N = M.tri[nb];
              std::int64_t at, rec;
              append_flip(next_len, &ctr->log, at, rec);
              flip_phase1(M, t, T, k, nb, N, round, log_base + std::int32_t(rec));
              // t' = (v_k, v_k+1, d): the diagonal is opposite its vertex 1; n' = (v_k, d,
              // v_k+2): opposite its vertex 2
              next[at] = list_entry(t, 1);
              next[at + 1] = list_entry(nb, 2);
              return;
            }
          } else if (M.vote[voter(M, won)] == won) {
            return;  // the proposal that took t won its own triangle too: it flips t, lists it
          }
          if (first_part) next[append_slot(next_len)] = list_entry(t, -1);  // lost: tests again
        });
  }

  // Exact decisions for the entries the filter left open, from the undecided edge on, one
  // thread per edge (an exact test is long: the round waits for the slowest thread); then each
  // entry proposes its first illegal edge (exc counts an entry's finished edges). A bounded
  // number of threads, each with its own scratch, strides over the list (its length stays on
  // the executor). It decides the first exact_cap_ entries of the list whose length is at
  // *listed; the round's first pass (first) also does the round's bookkeeping.
  void exact_pass(std::int64_t bound, int edges, const std::int64_t* listed, bool first) {
    const Geo g = g_;
    const Mesh M = M_;
    const std::int32_t round = round_;
    const mesh::WorkLists L = work_lists();
    const std::int32_t* act = L.current(round);
    std::int8_t* dec = dec_.data();
    std::int8_t* exd = exd_.data();
    std::int32_t* exc = exc_.data();
    const std::int32_t* exl = exl_.data();
    Counters* ctr = ctr_.data();
    const int p = round & 1;
    const CountAt count{listed, 3, exact_cap_};
    bound = std::min(bound, exact_cap_);
    auto decide = GG_LAMBDA(std::int64_t j, double* scr) {
      const std::int32_t i = exl[j / 3];
      const int k = int(j % 3);
      int r = -1;
      if (k >= mesh::undecided_face(dec[i]) && k < edges && k != legal_edge_of(act[i])) {
        const Tri T = M.tri[slot_of(act[i])];
        const std::int32_t d = M.tri[simplex_of(T.n[k])].v[loc_of(T.n[k])];
        r = illegal_fast(g, T.v, d);
        if (r == 0) r = illegal_exact(g, T.v, d, scr);
      }
      exd[j] = std::int8_t(r);
      // the last of the entry's three edges proposes (its acquire sees the others'
      // decisions): no second kernel, which would be a launch per round even when the
      // filter decided everything
      cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> done(exc[j / 3]);
      if (done.fetch_add(1, cuda::memory_order_acq_rel) != 2) return;
      done.store(0, cuda::memory_order_relaxed);  // ready for the next round
      const std::int64_t e = j - j % 3;
      const int illegal = exd[e] > 0 ? 0 : exd[e + 1] > 0 ? 1 : exd[e + 2] > 0 ? 2 : -1;
      dec[i] = std::int8_t(illegal);
      if (illegal < 0) return;
      const std::int32_t t = slot_of(act[i]);
      propose(M, round, t, simplex_of(M.tri[t].n[illegal]));
    };
    if (!first) {
      slots_.run_counted(ex_, 3 * bound, count, decide);
      return;
    }
    slots_.run_counted(
        ex_, 3 * bound, count, decide,
        GG_LAMBDA() {  // between the round's two uses of these counters
          const std::int64_t len = ctr->len[p];
          ctr->rounds += len > 0;
          ctr->small_rounds += len > 0 && len < kSmallRound;
          ctr->listed += len;
          ctr->exact_total += ctr->exact[p];
          ctr->len[p ^ 1] = 0;    // this round's flips append here (the last round's list)
          ctr->exact[p ^ 1] = 0;  // the next round's tests append here
        });
  }

  // Phase 2 of the round's flips: each proposer fixes the outer edges of its pair. (Over the
  // whole list: a list of the flips alone, appended in the flip kernel, measured slower.)
  void fix_round(const std::int32_t* act, const std::int64_t* count, std::int64_t bound) {
    const Mesh M = M_;
    const std::int32_t round = round_;
    listed(
        count, bound, GG_LAMBDA(std::int64_t i) {
          const std::int32_t t = slot_of(act[i]);
          Tri T;
          if (kReadAhead) {  // (an unflipped record may be changing: then unused)
            T = M.tri[t];
            if (T.stamp != round || !(T.pair & 1)) return;
          } else {
            if (M.tri[t].stamp != round || !(M.tri[t].pair & 1)) return;
            T = M.tri[t];  // flipped: only this thread writes its pointers
          }
          const std::int32_t nb = T.pair >> 1;
          fix_pair(M, t, T, nb, M.tri[nb], round);
        });
  }

  // Points not yet inserted follow their triangle through this epoch's split and recorded
  // flips (and, when choose, each triangle then picks one of its points); then a new epoch of
  // records begins.
  void relocate(bool choose) {
    const Geo g = g_;
    const Mesh M = M_;
    const std::int32_t* un = un_.data();
    std::int32_t* loc = loc_.data();
    const std::int32_t* srank = this->srank();
    const std::int32_t* sp = split_.data();
    const std::int32_t first_new = epoch_first_new_;
    u64* claim = this->claims();
    const bool moved = epoch_splits_ > 0 || logged_ > 0;
    if (!moved && !choose) return;
    ex_.for_each_index(
        nun_, GG_LAMBDA(std::int64_t i) {
          const std::int32_t q = un[i];
          std::int32_t L = loc[q];
          if (L < 0) return;  // inserted
          if (moved) {
            const std::int32_t r = srank[L];
            if (r >= 0) {  // children: L = (p, v1, v2), c1 = (p, v2, v0), c2 = (p, v0, v1)
              const std::int32_t* x = sp + 4 * std::int64_t(r);
              const std::int32_t p = x[0], c1 = first_new + 2 * r;
              if (orient_ext(g, p, x[2], q) > 0)
                L = orient_ext(g, p, x[3], q) < 0 ? L : c1;
              else
                L = orient_ext(g, p, x[1], q) > 0 ? c1 + 1 : c1;
            }
            L = follow_history(g, M, L, q);
            loc[q] = L;
          }
          if (choose) {
            atomic_max(claim + L, claim_of(choice_key(g, M.tri[L].v, q), q));
          }
        });
    std::int32_t* sr = this->srank();
    const std::int32_t* ins = ins_.data();
    ex_.for_each_index(
        epoch_splits_, GG_LAMBDA(std::int64_t r) { sr[ins[r]] = -1; });
    if (logged_ > 0) {
      Counters* ctr = ctr_.data();
      ex_.for_each_index(
          1, GG_LAMBDA(std::int64_t) { ctr->log = 0; });
      if (M_.log.next_epoch(logged_, log_cap_)) ex_.fill(hist_.data(), tmax_, Hist{-1, -1});
    }
    logged_ = 0;
    epoch_splits_ = 0;
  }

  // Flat triangles: collinear vertices the perturbation ordered counter-clockwise. They can
  // only lie on the hull; each is flipped with the infinite triangle across its long edge,
  // which makes its middle vertex a hull vertex, until none is left next to the outside.
  void peel() {
    const std::int32_t m = m_;
    const Geo g = g_;
    const Tri* tri = this->tri();
    const std::int32_t B = std::int32_t(base_);
    // Flat triangles come in runs along a hull line, and each run has one next to the outside
    // (the hull edge over the run lies on that line too): first look only there, reading the
    // points of the few triangles on the hull rather than those of every triangle.
    auto flat = GG_LAMBDA(const Tri& T)->bool {
      const std::int32_t a = T.v[0], b = T.v[1], c = T.v[2];
      if (a == m || b == m || c == m) return false;
      if (pred::orient2d_fast(g.at(a), g.at(b), g.at(c)) != 0) return false;
      double s[kOrient2dScratch];
      return pred::orient2d_exact(g.at(a), g.at(b), g.at(c), s) == 0;
    };
    const std::int64_t on_hull = ex_.compact_indices(
        tmax_,
        GG_LAMBDA(std::int64_t t) {
          const Tri T = tri[B + t];
          const int gi = T.v[0] == m ? 0 : T.v[1] == m ? 1 : T.v[2] == m ? 2 : -1;
          return gi >= 0 && flat(tri[simplex_of(T.n[gi])]);
        },
        lists_[0].data());
    const std::int64_t nflat =
        on_hull == 0
            ? 0
            : ex_.compact_indices(
                  tmax_, GG_LAMBDA(std::int64_t t) { return flat(tri[B + t]); }, lists_[0].data());
    st_.counters["flat_triangles"] = nflat;
    if (nflat == 0) return;
    if (B != 0) {  // positions to slots
      std::int32_t* l0 = lists_[0].data();
      ex_.for_each_index(
          nflat, GG_LAMBDA(std::int64_t i) { l0[i] += B; });
    }
    const Mesh M = M_;
    const std::int32_t* act = lists_[0].data();  // (the rounds are over: any list will do)
    std::int8_t* dec = dec_.data();
    Counters* ctr = ctr_.data();
    ex_.for_each_index(
        1, GG_LAMBDA(std::int64_t) { ctr->peel_list = nflat; });
    for (;;) {
      ++round_;
      const std::int32_t round = round_;
      ex_.for_each_index(
          1, GG_LAMBDA(std::int64_t) { ctr->flips = 0; });
      ex_.for_each_index(
          nflat, GG_LAMBDA(std::int64_t i) {
            const std::int32_t t = act[i];
            const Tri T = M.tri[t];
            dec[i] = -1;
            if (infinite(T, m)) return;
            for (int k = 0; k < 3; ++k) {
              const std::int32_t nb = simplex_of(T.n[k]);
              if (infinite(M.tri[nb], m) &&
                  between(g.at(T.v[(k + 1) % 3]), g.at(T.v[k]), g.at(T.v[(k + 2) % 3]))) {
                dec[i] = std::int8_t(k);
                propose(M, round, t, nb);
                return;
              }
            }
          });
      ex_.for_each_index(
          nflat, GG_LAMBDA(std::int64_t i) {
            const int k = dec[i];
            if (k < 0) return;
            const std::int32_t t = act[i];
            const u64 key = key_of(M, round, t);
            if (M.vote[t] != key) return;
            if (M.vote[simplex_of(M.tri[t].n[k])] == key) {
              flip_phase1(M, t, k, round, -1);  // no point is left to follow it
              atomic_add(&ctr->flips, std::int64_t(1));
            }
          });
      fix_round(act, &ctr->peel_list, nflat);
      const Counters c = counters();
      flips_ += c.flips;
      if (c.flips == 0) break;
    }
  }

  GG_HD static bool infinite(const Tri& T, std::int32_t m) {
    return T.v[0] == m || T.v[1] == m || T.v[2] == m;
  }
  // b strictly between a and c, all three on one line (lexicographic order of coordinates).
  GG_HD static bool between(const double* a, const double* b, const double* c) {
    auto less = [](const double* u, const double* v) {
      return u[0] < v[0] || (u[0] == v[0] && u[1] < v[1]);
    };
    return (less(a, b) && less(b, c)) || (less(c, b) && less(b, a));
  }

  // RunOptions::profile: each step is synchronised and timed (slower; for finding where the time
  // goes), reported as phases "insert/<step>".
  void mark(const char* step) {
    if (!profile_) return;
    ex_.sync();
    const auto now = clock::now();
    prof_[step] += ms_between(last_, now);
    last_ = now;
  }
  void report() {
    const Counters c = counters();
    for (auto& p : prof_) st_.phase_ms.push_back({"insert/" + p.first, p.second});
    st_.counters["batches"] = batches_;
    st_.counters["flip_rounds"] = c.rounds;
    st_.counters["flips"] = flips_;
    st_.counters["exact_predicates"] = c.exact_total;  // work-list entries the filter left open
    st_.counters["work_list_entries"] = c.listed;
    st_.counters["small_flip_rounds"] = c.small_rounds;
    st_.counters["exact_rest_passes"] = exact_rest_passes_;  // past the exact list's capacity
    st_.counters["log_relocations"] = relocations_;          // within a batch, for a full log
    st_.counters["split_flip_rounds"] = split_rounds_;       // flip parts past the first
  }

  Tri* tri() { return tri_.data() - base_; }
  u64* claims() { return vote_.data() - base_; }
  std::int32_t* srank() { return split_rank_.data() - base_; }

  // state
  Exec& ex_;
  Prepared& P_;
  Stats& st_;
  bool profile_ = false;
  Geo g_;
  Mesh M_;
  std::int32_t m_ = 0;
  std::int64_t tmax_ = 0, ntri_ = 0, nun_ = 0, nact_ = 0;
  std::int64_t base_ = 0;  // the first slot's number (0 but in tests)
  std::int32_t round_ = 0;
  std::int64_t batches_ = 0, flips_ = 0;
  std::int64_t log_cap_ = 0, logged_ = 0;
  std::int64_t remaining_ = 0, dead_ = 0, epoch_splits_ = 0;  // points; list entries; splits
  // capacities: the most points a batch inserts (a uniform batch inserts at most about a
  // third of the points: measured 0.33 m at 10^6; the rest wait for the next batch), flip
  // records, exact-list entries; the shift of the winners' buckets (check_round)
  std::int64_t ins_cap_ = 0, exact_cap_ = 0;
  int win_shift_ = 0;
  std::int64_t exact_rest_passes_ = 0, relocations_ = 0, split_rounds_ = 0;
  std::int32_t epoch_first_new_ = 0;
  std::map<std::string, double> prof_;
  clock::time_point last_ = clock::now();
  typename Exec::template Buffer<Tri> tri_;
  typename Exec::template Buffer<Hist> hist_;
  typename Exec::template Buffer<std::int32_t> split_rank_, rec_, split_;
  typename Exec::template Buffer<u64> vote_;
  typename Exec::template Buffer<std::int32_t> lists_[2];  // the rounds' work lists
  typename Exec::template Buffer<std::int32_t> exl_, exc_, loc_, un_, ins_;
  typename Exec::template Buffer<std::int8_t> dec_, exd_;  // per entry; per exact-list edge
  typename Exec::template Buffer<Counters> ctr_;
  typename Exec::template Buffer<std::int64_t> wins_;  // winning proposals per slot bucket
  ScratchSlots<Exec> slots_;                           // of the exact pass
};

// The device memory a triangulation needs per point at least, checked before any launch: the
// rounds' arrays with the flip log at its least (docs/performance.md, H100 80 GB: 167.7 B a
// point measured at 5·10^8; where memory is left the log takes more, up to 236 B a point).
constexpr double kLeastBytesPerPoint = 168;

// The pipeline after the preparation: body(P, f) takes the result.
template <class Body>
inline void triangulate_prepared(Exec& ex, Prepared& P, bool profile, Stats& st, Body body,
                                 bool peel_flats = true) {
  // The rounds' arrays, checked again now that the points are prepared: where they exceed the
  // driver's free memory, the preparation's freed blocks go back to the driver first
  // (require_memory), so that the largest arrays are not cut from the pool's pieces of them.
  ::gpugeom::detail::require_device_memory(ex, P.m, kLeastBytesPerPoint - 20,
                                           "a 2D Delaunay triangulation", "points");
  Triangulator T(ex, P, st, profile);
  T.run(peel_flats);
  const auto t0 = std::chrono::steady_clock::now();
  T.report();
  T.release_work();
  auto f = T.finish();
  body(P, f);
  st.phase_ms.push_back({"output", ms_since(t0)});
}

// The whole pipeline; the result stays on the executor (f) with P's duplicate map.
// before(P) runs once the distinct points are known, before the device work.
template <class Before, class Body>
inline void triangulate_core(Exec& ex, const double* xy, std::int64_t n, bool on_device,
                             bool profile, Stats& st, Before before, Body body,
                             bool peel_flats = true) {
  auto t0 = std::chrono::steady_clock::now();
  Prepared P = prepare(ex, xy, n, on_device);
  before(P);
  st.counters["points"] = n;
  st.counters["distinct_points"] = P.m;
  st.counters["duplicates"] = P.duplicates;
  ex.sync();
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  st.phase_ms.push_back({"upload", P.upload_ms});  // (part of prepare)
  triangulate_prepared(ex, P, profile, st, body, peel_flats);
}

// The three outputs' lengths, checked against the caller's arrays before any is written.
inline void check_into(const Triangulation2dBuffers& into, std::int64_t count, std::int64_t n) {
  deliver::check(into.triangles, 3 * count, "triangles");
  deliver::check(into.neighbors, 3 * count, "neighbors");
  deliver::check(into.duplicate_of, n, "duplicate_of");
}

// The host entries' result arrays. On the GPU the host is idle while the device triangulates:
// they are sized for the most triangles m distinct points can have (2m - 5; cut to the count
// later, keeping the pages) and faulted in meanwhile, so the copy back runs at the transfer's
// rate.
inline void size_host_results(const Triangulation2dBuffers& into, std::int64_t n, const Prepared& P,
                              Output& out, detail::Prefault& pf) {
  if constexpr (Exec::backend == Backend::Cuda) {
    const std::int64_t bound = 3 * delaunay2d_max_triangles(P.m);
    if (!into.triangles) out.triangles.resize(std::size_t(bound));
    if (!into.neighbors) out.neighbors.resize(std::size_t(bound));
    if (!into.duplicate_of) out.duplicate_of.resize(std::size_t(n));
    pf.add(out.triangles.data(), out.triangles.size() * sizeof(std::int32_t));
    pf.add(out.neighbors.data(), out.neighbors.size() * sizeof(std::int32_t));
    pf.add(out.duplicate_of.data(), out.duplicate_of.size() * sizeof(std::int32_t));
    pf.start();
  }
}

inline void deliver_host_results(Exec& ex, const Triangulation2dBuffers& into, std::int64_t n,
                                 Prepared& P, typename Triangulator::Finished& f, Output& out,
                                 Stats& st, detail::Prefault& pf) {
  const auto t0 = std::chrono::steady_clock::now();
  pf.wait();
  st.phase_ms.push_back({"prefault_wait", ms_since(t0)});
  check_into(into, f.count, n);
  out.num_duplicates = P.duplicates;
  out.num_triangles = f.count;
  deliver::to_host(ex, f.simplices.data(), 3 * f.count, into.triangles, out.triangles);
  deliver::to_host(ex, f.neighbors.data(), 3 * f.count, into.neighbors, out.neighbors);
  if (P.duplicates)
    deliver::to_host(ex, P.dup.data(), n, into.duplicate_of, out.duplicate_of);
  else
    deliver::fill_host(ex, n, std::int32_t(-1), into.duplicate_of, out.duplicate_of);
  st.phase_ms.push_back({"copy_back", ms_since(t0)});
}

inline void triangulate_impl(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                             Output& out, Stats& st) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint,
                                           "a 2D Delaunay triangulation", "points");
  detail::Prefault pf;
  triangulate_core(
      ex, xy, n, false, opt.profile, st,
      [&](Prepared& P) { size_host_results(opt.into, n, P, out, pf); },
      [&](Prepared& P, typename Triangulator::Finished& f) {
        deliver_host_results(ex, opt.into, n, P, f, out, st, pf);
      });
}

// Points in executor memory, result left there (or in the caller's arrays of that memory).
inline void triangulate_device_impl(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
                                    DeviceOutput& out, Stats& st) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint - 16,
                                           "a 2D Delaunay triangulation", "points");
  triangulate_core(
      ex, xy, n, true, opt.profile, st, [](Prepared&) {},
      [&](Prepared& P, typename Triangulator::Finished& f) {
        const Triangulation2dBuffers& into = opt.into;
        check_into(into, f.count, n);
        if (!P.dup.size() && !into.duplicate_of)  // no duplicates: all -1
          P.dup = ex.template alloc<std::int32_t>(std::size_t(n));
        std::int32_t* dup = P.dup.size() ? P.dup.data() : into.duplicate_of.data;
        if (!P.duplicates) ex.fill(dup, n, std::int32_t(-1));
        auto tri = deliver::place(ex, f.simplices, 3 * f.count, into.triangles);
        auto nb = deliver::place(ex, f.neighbors, 3 * f.count, into.neighbors);
        auto dp = deliver::place(ex, P.dup, P.dup.size() ? n : 0, into.duplicate_of);
        ex.sync();  // the caller may read them now (and free them on any stream)
        out.num_triangles = f.count;
        out.num_duplicates = P.duplicates;
        out.triangles = tri.own();
        out.neighbors = nb.own();
        out.duplicate_of = dp.own();
      });
}

// The Triangulator from a start (executor memory: f triangles of input indices, mapped to
// prepared indices in place, their twins, and per input point a start vertex near it or null),
// after prepare(P); the result left on the executor for finish(). kernel, when given, is the
// kernel point to use (strictly inside the start's hull under the perturbation), else one is
// placed inside the start's first triangle.
inline typename Triangulator::Finished run_from_start(
    Exec& ex, Prepared& P, std::int64_t n, std::int32_t* tris, std::int64_t f,
    const std::int32_t* twin, const std::int32_t* hint, bool profile, Stats& st,
    const double* kernel = nullptr, bool peel_flats = true, bool start_delaunay = false) {
  auto t0 = std::chrono::steady_clock::now();
  // Input index -> prepared index (a duplicate's: the point kept for it).
  auto d_inv = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* inv = d_inv.data();
  const std::int32_t* orig = P.orig.data();
  const std::int32_t* dup = P.duplicates ? P.dup.data() : nullptr;
  ex.for_each_index(
      P.m, GG_LAMBDA(std::int64_t j) { inv[orig[j]] = std::int32_t(j); });
  if (dup)
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          if (dup[i] >= 0) inv[i] = inv[dup[i]];
        });
  ex.for_each_index(
      3 * f, GG_LAMBDA(std::int64_t e) { tris[e] = inv[tris[e]]; });
  // The hints in prepared indices too (a point's own entry at its prepared index).
  auto d_near = ex.template alloc<std::int32_t>(hint ? std::size_t(P.m) : 0);
  std::int32_t* near = d_near.data();
  if (hint) {
    ex.fill(near, P.m, std::int32_t(-1));
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          if ((!dup || dup[i] < 0) && hint[i] >= 0 && hint[i] < n) near[inv[i]] = inv[hint[i]];
        });
  }
  // The kernel point: the one given (strictly inside the start's hull), else one inside the
  // start's first triangle.
  if (kernel) {
    P.kernel[0] = kernel[0], P.kernel[1] = kernel[1];
  } else {
    std::int32_t id[3];
    ex.to_host(tris, 3, id);
    double p[3][2];
    for (int k = 0; k < 3; ++k) ex.to_host(P.pts.data() + 2 * std::int64_t(id[k]), 2, p[k]);
    const double* v[3] = {p[0], p[1], p[2]};
    if (!kernel_point(v, id, std::int32_t(P.m), P.kernel))
      throw Error(ErrorCode::InvalidArgument,
                  "start triangulation: no kernel point inside its first triangle");
  }
  d_inv = {};
  ex.sync();
  st.phase_ms.push_back({"start_map", ms_since(t0)});
  Triangulator T(ex, P, st, profile);
  T.run_from(tris, twin, f, hint ? near : nullptr, peel_flats, start_delaunay);
  t0 = std::chrono::steady_clock::now();
  T.report();
  T.release_work();
  auto out = T.finish();
  st.phase_ms.push_back({"finish", ms_since(t0)});
  return out;
}
