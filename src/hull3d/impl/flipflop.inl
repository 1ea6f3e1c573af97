// Phase 2 (thesis Alg. 5.4, Flip-Flop): flips the star-shaped polyhedron into the convex hull.
// Included inside gpugeom::hull3d::{cpu,cuda}_impl after construct.inl.
//
// Each round, every facet on the work list decides for the edges it owns (those shared with a
// higher slot) what Alg. 5.4 does: a 3-1 flip when a degree-3 endpoint can be removed (the
// edge is reflex, or the vertex is labelled non-extreme); a label on the non-extreme endpoint
// when the edge is reflex but cannot be flipped (Lemma 5.1); a 2-2 flip when the edge is
// flippable and either reflex with no labelled vertex involved, or it lowers the degree of the
// smallest labelled vertex involved. Labels take effect the next round, so every decision of a
// round reads the same state. A facet proposes its first flip; a flip claims its two or three
// facets and goes ahead when its key is the highest on each of them (keys: the round, then a
// fixed scatter of the slot), so results never depend on timing. Neighbour pointers are fixed
// in a second phase as in delaunay2d. Changed facets and their neighbours, outvoted proposers
// and the facets around newly labelled vertices form the next list.
//
// No round waits for the host: kernels read the list length on the executor, and the host looks
// once per few rounds. Once the list and the surface are small, when a round is a few hundred
// facets and the cost is launches and memory latency, one team (a thread block) runs the
// remaining rounds in one launch with barriers between the steps.
//
// The geometry is in edge_action and the topology in surface.inl; the loop itself only moves
// lists, so a polyhedron one dimension higher needs those two parts replaced, not this one.

constexpr std::int64_t kMaxFlipRounds = 4000000;

// Puts facet x on the next round's list once.
struct Enlist {
  std::int32_t* mark;
  std::int32_t* next;
  std::int64_t* count;
  std::int32_t round;
  GG_HD void operator()(std::int32_t x) const {
    const std::int32_t one[1] = {x};
    many(one);
  }
  // K facets at once: the K marks are claimed with independent atomics (in flight
  // together rather than one after another) and the new ones appended with one atomic.
  template <int K>
  GG_HD void many(const std::int32_t (&x)[K]) const {
    bool fresh[K];
    int m = 0;
    for (int j = 0; j < K; ++j) fresh[j] = atomic_exchange(mark + x[j], round) != round;
    for (int j = 0; j < K; ++j) m += fresh[j];
    if (m == 0) return;
    std::int64_t at = atomic_add(count, std::int64_t(m));
    for (int j = 0; j < K; ++j)
      if (fresh[j]) next[at++] = x[j];
  }
};

// The decisions of a round, in two steps so that no thread walks a facet's three edges one
// after another: edge() decides one edge (filter first; the exact stage for what the filter
// cannot tell) and writes its action, then propose() takes a facet's first flip among its edges
// and votes for it on the two or three facets that flip would change.
struct Decide {
  Surface Sf;
  const std::int8_t* ne;
  std::int32_t* labround;
  std::int32_t* newlab;
  std::int32_t* prop;
  std::int32_t* clm;
  u64* vote;
  std::int8_t* eact;  // per facet and edge: the action of this round (kNone: none, or not owned)
  Counters* ctr;
  std::int32_t s, round;
  // Edge k of facet f, decided where f owns it (the neighbour's slot is not lower) and labels
  // recorded; false when the filter could not tell.
  template <class O>
  GG_HD bool edge(std::int32_t f, int k, const O& o) const {
    std::int8_t* out = eact + 3 * std::int64_t(f) + k;
    const std::int32_t e = Sf.to[3 * f + k], g = simplex_of(e);
    if (Sf.tv[3 * f] < 0 || g < f) {
      *out = kNone;
      return true;
    }
    const std::int32_t c = Sf.tv[3 * f + k], a = Sf.tv[3 * f + (k + 1) % 3],
                       b = Sf.tv[3 * f + (k + 2) % 3], d = Sf.tv[3 * g + loc_of(e)];
    const int act = edge_action(o, s, a, b, c, d, Sf.deg[a], Sf.deg[b], ne);
    if (act == kUndecided) return false;
    if (act == kLabelA || act == kLabelB) {
      const std::int32_t x = act == kLabelA ? a : b;
      if (!ne[x] && atomic_exchange(labround + x, round) != round)
        newlab[append_slot(&ctr->labels)] = x;
      *out = kNone;
    } else {
      *out = std::int8_t(act);
    }
    return true;
  }
  // The exact stage's item: enc(facet, edge).
  template <class O>
  GG_HD void operator()(std::int32_t item, const O& o) const {
    edge(simplex_of(item), loc_of(item), o);
  }
  GG_HD void propose(std::int32_t f) const {
    prop[f] = -1;
    if (Sf.tv[3 * f] < 0) return;
    std::int32_t pr = -1;
    for (int k = 0; k < 3 && pr < 0; ++k) {
      const int act = eact[3 * std::int64_t(f) + k];
      if (act != kNone) pr = (act << 2) | k;
    }
    prop[f] = pr;
    if (pr < 0) return;
    // The vote (the topology is not changed before every facet has voted).
    const int k = pr & 3, kind = pr >> 2;
    std::int32_t* c = clm + 3 * std::int64_t(f);
    if (kind == kFlip22) {
      c[0] = f, c[1] = simplex_of(Sf.to[3 * f + k]), c[2] = -1;
    } else {
      int L[3];
      fan3(Sf, f, kind == kRemoveA ? (k + 1) % 3 : (k + 2) % 3, c, L);
    }
    const u64 key = vote_key(f);
    for (int j = 0; j < 3; ++j)
      if (c[j] >= 0) atomic_max(vote + c[j], key);
  }
  GG_HD u64 vote_key(std::int32_t f) const { return mesh::vote_key(round, f); }
};

// Ends flip round `parity`'s bookkeeping: per-round counts into the totals, its list emptied.
GG_HD inline void end_flip_round(Counters* c, int parity) {
  c->exact_all += c->exact;
  c->labels_all += c->labels;
  c->exact = c->labels = 0;
  c->flip_rounds += c->len[parity] > 0;
  c->len[parity] = 0;
}

// The steps of one Flip-Flop round, each over the round's work list (item i is facet act[i]).
// Round r reads list r & 1 and writes list (r + 1) & 1.
struct FlipRound {
  Decide dec;
  Enlist next;
  Geo geo;
  mesh::WorkLists lists;
  std::int8_t* ne;
  const std::int32_t* act;
  std::int32_t round;  // (dec.round; mesh/flip_schedule.hpp's team rounds read it here)

  GG_HD void set_round(std::int32_t r) {
    round = r;
    dec.round = r;
    act = lists.current(r);
    next.next = lists.next(r);
    next.count = lists.next_count(r);
    next.round = r + 1;
  }
  GG_HD const std::int64_t* count() const { return lists.count(dec.round); }
  GG_HD void advance() { set_round(round + 1); }
  // 1. Edge j % 3 of the list's facet j / 3 with the filter; false: it needs the exact stage
  // (as item enc(facet, edge)).
  GG_HD bool edge_fast(std::int64_t j) const {
    return dec.edge(act[j / 3], int(j % 3), FastOrient{geo});
  }
  GG_HD std::int32_t edge_item(std::int64_t j) const { return enc(act[j / 3], int(j % 3)); }
  // 2. The facet's proposal and vote.
  GG_HD void propose(std::int64_t i) const { dec.propose(act[i]); }
  // 3. Flip the winners (phase 1); outvoted proposers try again next round.
  GG_HD void flip(std::int64_t i) const {
    const std::int32_t f = act[i], pr = dec.prop[f];
    if (pr < 0) return;
    const Surface& Sf = dec.Sf;
    const u64 key = dec.vote_key(f);
    const std::int32_t* c = dec.clm + 3 * std::int64_t(f);
    bool won = true;
    for (int j = 0; j < 3; ++j) won = won && (c[j] < 0 || dec.vote[c[j]] == key);
    if (!won) {
      dec.prop[f] = -1;
      next(f);
      return;
    }
    const int k = pr & 3, kind = pr >> 2;
    if (kind == kFlip22) {
      flip22(Sf, f, k, dec.round);
      atomic_add(&dec.ctr->flips22, std::int64_t(1));
    } else {
      remove3(Sf, f, kind == kRemoveA ? (k + 1) % 3 : (k + 2) % 3, dec.round);
      atomic_add(&dec.ctr->flips31, std::int64_t(1));
    }
  }
  // 4. Phase 2: outer neighbour pointers; the changed facets and their neighbours go next.
  GG_HD void fix(std::int64_t i) const {
    const std::int32_t f = act[i], pr = dec.prop[f];
    if (pr < 0) return;
    const Surface& Sf = dec.Sf;
    const std::int32_t* c = dec.clm + 3 * std::int64_t(f);
    if ((pr >> 2) == kFlip22) {
      std::int32_t x[8];
      for (int side = 0; side < 2; ++side) {
        const std::int32_t y = c[side];
        x[4 * side] = y;
        x[4 * side + 1] = fix_edge(Sf, y, 0, dec.round);
        x[4 * side + 2] = fix_edge(Sf, y, 2, dec.round);
        x[4 * side + 3] = simplex_of(Sf.to[3 * y + 1]);
      }
      next.many(x);
    } else {
      std::int32_t x[4] = {f, 0, 0, 0};
      for (int l = 0; l < 3; ++l) x[l + 1] = fix_edge(Sf, f, l, dec.round);
      next.many(x);
    }
  }
  // 5. The round's labels take effect, and the facets around them (with their neighbours) go
  // next: thread t of T takes every T-th label and facet. Nothing to do on most rounds.
  GG_HD void labels(std::int64_t t, std::int64_t T, std::int64_t used) const {
    const std::int64_t nl = dec.ctr->labels;
    if (nl == 0) return;
    for (std::int64_t i = t; i < nl; i += T) ne[dec.newlab[i]] = 1;
    for (std::int64_t f = t; f < used; f += T) list_labelled(f);
  }
  // ... and the facets around them, with their neighbours, go next (facet f of the surface).
  GG_HD void list_labelled(std::int64_t fi) const {
    const std::int32_t f = std::int32_t(fi);
    const Surface& Sf = dec.Sf;
    if (Sf.tv[3 * f] < 0) return;
    bool hit = false;
    for (int k = 0; k < 3; ++k) hit = hit || dec.labround[Sf.tv[3 * f + k]] == dec.round;
    if (!hit) return;
    std::int32_t x[4] = {f, 0, 0, 0};
    for (int k = 0; k < 3; ++k) x[k + 1] = simplex_of(Sf.to[3 * f + k]);
    next.many(x);
  }
};

class FlipFlop {
 public:
  explicit FlipFlop(PassState& S) : S_(S) {}

  // The rounds' schedule is mesh/flip_schedule.hpp's: chunks of rounds with no wait in between
  // (every kernel reads its work-list length on the executor, so a round past the last one does
  // nothing, and the host checks for the end once per chunk), and once the list is short, one
  // team runs the rounds in a single launch. This class is the schedule's phase.
  static constexpr int kChunk = 4;

  void run() {
    Exec& ex = S_.ex;
    const std::int64_t used = S_.used;
    list_[0] = ex.template alloc<std::int32_t>(std::size_t(used));
    list_[1] = ex.template alloc<std::int32_t>(std::size_t(used));
    prop_ = ex.template alloc<std::int32_t>(std::size_t(used));
    clm_ = ex.template alloc<std::int32_t>(std::size_t(3 * used));
    eact_ = ex.template alloc<std::int8_t>(std::size_t(3 * used));
    vote_ = ex.template alloc<u64>(std::size_t(used));
    mark_ = ex.template alloc<std::int32_t>(std::size_t(used));
    ne_ = ex.template alloc<std::int8_t>(std::size_t(S_.n));
    labround_ = ex.template alloc<std::int32_t>(std::size_t(S_.n));
    newlab_ = ex.template alloc<std::int32_t>(std::size_t(S_.n));
    ex.fill(vote_.data(), used, u64(0));
    ex.fill(mark_.data(), used, std::int32_t(-1));
    ex.fill(ne_.data(), S_.n, std::int8_t(0));
    ex.fill(labround_.data(), S_.n, std::int32_t(-1));
    std::int32_t* act = list_[0].data();
    ex.for_each_index(
        used, GG_LAMBDA(std::int64_t f) { act[f] = std::int32_t(f); });
    Counters* ctr = S_.ctr.data();
    ex.for_each_index(
        1, GG_LAMBDA(std::int64_t) {
          ctr->len[0] = used;
          ctr->len[1] = 0;
        });
    S_.exact_list(3 * used);
    round_ = 0;
    len_ = used;
    mesh::ScheduleCounts counts;
    mesh::run_rounds(*this, kMaxFlipRounds, counts);
    const Counters c = S_.counters();
    S_.st.flip_rounds += c.flip_rounds;
    S_.st.flips22 += c.flips22;
    S_.st.flips31 += c.flips31;
    S_.st.labelled_nonextreme += c.labels_all;
  }

  // The schedule's phase (mesh/flip_schedule.hpp). A team takes about two facets a thread (a
  // round then costs a few dependent memory accesses per step rather than a launch per step);
  // the surface must be small too, since the team scans it on rounds that label.
  std::int64_t pending() const { return len_; }
  std::int64_t team_max() const { return 2 * std::int64_t(S_.ex.team_size()); }
  bool team_fits() const {
    return S_.used <= 8 * team_max() && S_.slots.slots() >= S_.ex.team_size();
  }
  std::int64_t plan() const { return kChunk; }
  void team(std::int64_t limit) {
    from_ = round_;
    team_rounds(round_, team_max(), limit);
  }
  void kernels(std::int64_t rounds) {
    from_ = round_;
    for (std::int64_t k = 0; k < rounds; ++k) step(round_++);
  }
  mesh::ChunkEnd end_chunk(bool team) {
    // One read: both list lengths and the round a team stopped at (adjacent fields).
    std::int64_t l[3];
    S_.ex.to_host(S_.ctr.data()->len, 3, l);
    if (team) round_ = std::int32_t(l[2]);
    len_ = l[round_ & 1];
    return {round_ - from_, false};
  }
  [[noreturn]] void out_of_rounds() const {
    throw Error(ErrorCode::Internal, "convex hull: Flip-Flop did not finish");
  }

  FlipRound make_round(std::int32_t round) {
    FlipRound R;
    R.dec = Decide{S_.surface(),
                   ne_.data(),
                   labround_.data(),
                   newlab_.data(),
                   prop_.data(),
                   clm_.data(),
                   vote_.data(),
                   eact_.data(),
                   S_.ctr.data(),
                   S_.g.n,
                   0};
    R.next = Enlist{mark_.data(), nullptr, nullptr, 0};
    R.geo = S_.g;
    R.lists = mesh::WorkLists{{list_[0].data(), list_[1].data()}, S_.ctr.data()->len};
    R.ne = ne_.data();
    R.set_round(round);
    return R;
  }

  // One round as a few kernels, each over the list length read on the executor.
  void step(std::int32_t round) {
    Exec& ex = S_.ex;
    const FlipRound R = make_round(round);
    Counters* ctr = S_.ctr.data();
    const std::int64_t used = S_.used;
    const std::int64_t* nact = R.count();
    std::int32_t* exl = S_.exact_list(3 * used);
    ex.for_each_counted(
        nact, 3 * used,
        GG_LAMBDA(std::int64_t j) {
          if (!R.edge_fast(j)) exl[append_slot(&ctr->exact)] = R.edge_item(j);
        },
        3);
    S_.exact_pass(R.dec);
    ex.for_each_counted(
        nact, used, GG_LAMBDA(std::int64_t i) { R.propose(i); });
    ex.for_each_counted(
        nact, used, GG_LAMBDA(std::int64_t i) { R.flip(i); });
    ex.for_each_counted(
        nact, used, GG_LAMBDA(std::int64_t i) { R.fix(i); });
    const std::int64_t T = std::max<std::int64_t>(1, std::min(used, ex.concurrency()));
    ex.for_each_index(
        T, GG_LAMBDA(std::int64_t t) { R.labels(t, T, used); });
    const int parity = round & 1;
    ex.for_each_index(
        1, GG_LAMBDA(std::int64_t) { end_flip_round(ctr, parity); });
  }

  // Rounds from `round` on in one team (mesh::team_rounds), while the list is non-empty and at
  // most `max` long and fewer than `limit` have run; leaves the round it stopped at in the
  // counters.
  void team_rounds(std::int32_t round, std::int64_t max, std::int64_t limit) {
    Exec& ex = S_.ex;
    const FlipRound R0 = make_round(round);
    Counters* ctr = S_.ctr.data();
    const SlotView scratch = S_.slots.view();
    const std::int64_t used = S_.used;
    const std::int32_t stop = mesh::team_stop(round, limit);
    ex.team(GG_LAMBDA(const Exec::Team& t) {
      const ExactOrient exact{R0.geo, scratch[t.rank]};
      auto room = [](const FlipRound&, std::int64_t) { return true; };
      auto steps = [&](const FlipRound& R, std::int64_t n) {
        for (std::int64_t j = t.rank; j < 3 * n; j += t.size)
          if (!R.edge_fast(j)) {
            atomic_add(&ctr->exact, std::int64_t(1));
            R.dec(R.edge_item(j), exact);
          }
        t.barrier();
        for (std::int64_t i = t.rank; i < n; i += t.size) R.propose(i);
        t.barrier();
        for (std::int64_t i = t.rank; i < n; i += t.size) R.flip(i);
        t.barrier();
        for (std::int64_t i = t.rank; i < n; i += t.size) R.fix(i);
        t.barrier();
        R.labels(t.rank, t.size, used);
        t.barrier();
        if (t.rank == 0) end_flip_round(ctr, R.round & 1);
        t.barrier();
      };
      mesh::team_rounds(t, R0, max, stop, &ctr->round, room, steps);
    });
  }

  PassState& S_;
  typename Exec::template Buffer<std::int32_t> list_[2], prop_, clm_, mark_, labround_, newlab_;
  typename Exec::template Buffer<u64> vote_;
  typename Exec::template Buffer<std::int8_t> ne_, eact_;
  std::int32_t round_ = 0, from_ = 0;  // the next round; the chunk's first
  std::int64_t len_ = 0;               // the next round's list length, as last read
};
