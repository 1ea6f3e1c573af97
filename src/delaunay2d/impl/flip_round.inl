// The 2D flip round (triangulator.inl, rounds.inl), as the kernels see it: the round's arrays
// and counters, and its steps, each a function of one list entry (or one exact test), as the 3D
// round's FlipRound is; rounds.inl schedules them. Included inside
// gpugeom::del2d::{cpu,cuda}_impl after mesh.inl.
//
// A round: test (each entry stops at its first illegal edge, proposes it and votes at once; an
// entry the filter cannot decide goes to the exact list), decide (the exact pass, one test per
// edge, the entry's last test proposing), then vote_flip (a proposal that won both its
// triangles flips, the rest are listed again) and fix (the flipped pairs' outer edges). A
// checked round (rounds.inl's check_round) adds relist_undecided, proposes and wins.

constexpr bool kReadAhead = Exec::backend == Backend::Cuda;  // (see vote_flip)
constexpr std::int64_t kSmallRound = 8192;  // (counted: rounds whose launches are mostly latency)

// Whether a round of n list entries runs unchecked: its records (a round flips at most one pair
// per entry, and half the slots in all) fit the flip log after the `logged` records of the
// epoch, and its undecided entries the exact list. Read by the host before a chunk of kernels
// or a team, and by a team before each of its rounds (rounds.inl).
GG_HD inline bool round_fits(std::int64_t logged, std::int64_t n, std::int64_t half_slots,
                             std::int64_t log_cap, std::int64_t exact_cap) {
  return logged + (n < half_slots ? n : half_slots) <= log_cap && n <= exact_cap;
}

struct FlipRound {
  Geo g;
  Mesh M;  // (taken after any relocation of the round: the log's numbering)
  std::int32_t round;
  // Edges tested per entry: in a batch's first round the list holds the children of the
  // splits, and only their edges opposite the new point need a test (the edges at the new point
  // are locally Delaunay: the point lies inside the old triangle's circumcircle, so the circle
  // through it and an old edge leaves the old triangle's third vertex outside; for an infinite
  // triangle the point lies beyond the old edge, which keeps both half-planes clear). Later
  // rounds skip the diagonal a flip just made (locally Delaunay by the flip), which the list
  // entry carries.
  int edges;
  mesh::WorkLists L;
  const std::int32_t* act;  // this round's list (L.current(round)) and its length
  const std::int64_t* len;
  std::int32_t* next;  // the next round's list and its length
  std::int64_t* next_len;
  std::int8_t* dec;   // per entry: its decision (mesh::undecided_at while the exact pass runs)
  std::int8_t* exd;   // per exact test (3 an entry of the exact list): its result
  std::int32_t* exc;  // per exact entry: its finished tests
  std::int32_t* exl;  // the exact list: entries the filter left undecided
  std::int64_t exact_cap;
  Counters* ctr;

  GG_HD int parity() const { return round & 1; }
  // The functor of round r (its lists).
  GG_HD void go_to(std::int32_t r) {
    round = r;
    act = L.current(r);
    len = L.count(r);
    next = L.next(r);
    next_len = L.next_count(r);
  }
  // (mesh/flip_schedule.hpp's team rounds: the list's length, and the next round, whose
  // entries are all but the first round's children and test three edges)
  GG_HD const std::int64_t* count() const { return len; }
  GG_HD void advance() {
    go_to(round + 1);
    edges = 3;
  }

  // The filter's tests of entry i's edges up to the first illegal one, which it proposes; an
  // edge the filter cannot decide sends the entry to the exact list (its place past the list's
  // capacity: rounds.inl's check_round lists it again).
  GG_HD void test(std::int64_t i) const {
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
      const std::int64_t at = append_slot(&ctr->exact[parity()]);
      if (at < exact_cap) exl[at] = std::int32_t(i);
    } else if (res >= 0) {
      propose(M, round, t, simplex_of(T.n[res]));
    }
  }

  // Exact test j: edge j % 3 of the exact list's entry j / 3, from the undecided edge on (an
  // exact test is long: one thread an edge, so the round waits for the slowest edge, not the
  // slowest entry). The last of the entry's three tests to finish (its acquire sees the
  // others' results) decides the entry and proposes: no second kernel, which would be a launch
  // per round even when the filter decided everything.
  GG_HD void decide(std::int64_t j, double* scr) const {
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
    cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> done(exc[j / 3]);
    if (done.fetch_add(1, cuda::memory_order_acq_rel) != 2) return;
    done.store(0, cuda::memory_order_relaxed);  // ready for the next round
    const std::int64_t e = j - j % 3;
    const int illegal = exd[e] > 0 ? 0 : exd[e + 1] > 0 ? 1 : exd[e + 2] > 0 ? 2 : -1;
    dec[i] = std::int8_t(illegal);
    if (illegal < 0) return;
    const std::int32_t t = slot_of(act[i]);
    propose(M, round, t, simplex_of(M.tri[t].n[illegal]));
  }

  // The round's bookkeeping (one thread), between the two uses of the counters it resets: the
  // totals, and the next round's list and exact list emptied.
  GG_HD void tally() const {
    const int p = parity();
    const std::int64_t len = ctr->len[p];
    ctr->rounds += len > 0;
    ctr->small_rounds += len > 0 && len < kSmallRound;
    ctr->listed += len;
    ctr->exact_total += ctr->exact[p];
    ctr->len[p ^ 1] = 0;    // this round's flips append here (the last round's list)
    ctr->exact[p ^ 1] = 0;  // the next round's tests append here
  }

  // A checked round whose exact list overflowed: entry i, still undecided, listed again for a
  // further exact pass.
  GG_HD void relist_undecided(std::int64_t i) const {
    if (!mesh::is_undecided(dec[i])) return;
    const std::int64_t at = append_slot(&ctr->exact_rest);
    if (at < exact_cap) exl[at] = std::int32_t(i);
  }

  // Whether entry i proposed (a checked round counts them: each flips at most once).
  GG_HD bool proposed(std::int64_t i) const { return i < *len && dec[i] >= 0; }

  // A checked round whose proposals could overflow the flip log: entry i's winning proposal
  // counted in its range of slots (2^shift slots a bucket).
  GG_HD void count_win(std::int64_t i, std::int64_t* wins, int shift) const {
    const int k = dec[i];
    if (k < 0) return;
    const std::int32_t t = slot_of(act[i]);
    const u64 key = key_of(M, round, t);
    if (M.vote[t] == key && M.vote[simplex_of(M.tri[t].n[k])] == key)
      atomic_add(wins + ((t - M.base) >> shift), std::int64_t(1));
  }

  // Where vote_flip's entries and records go. On the GPU (and in a team): atomics on the
  // counters, in any order.
  struct ByAtomics {
    static constexpr bool kApply = true;
    std::int64_t* next_len;
    std::int64_t* log;
    GG_HD void flip(std::int64_t& at, std::int64_t& rec) { append_flip(next_len, log, at, rec); }
    GG_HD std::int64_t one() { return append_slot(next_len); }
  };
  // On the CPU executor: the places of CpuExec::append_in_order (list 0: the next round's
  // entries, list 1: the flip records), in the order of the round's list.
  template <class Place>
  struct InOrder {
    static constexpr bool kApply = Place::kApply;
    Place& p;
    void flip(std::int64_t& at, std::int64_t& rec) {
      at = p.take(0, 2);
      rec = p.take(1, 1);
    }
    std::int64_t one() { return p.take(0, 1); }
  };
  GG_HD void vote_flip(std::int64_t i, std::int32_t lo, std::int32_t hi, bool first_part) const {
    ByAtomics place{next_len, &ctr->log};
    vote_flip(i, lo, hi, first_part, place);
  }

  // Entry i's proposal counted against the votes: a proposal that won both its triangles, from
  // a slot in [lo, hi) (counted from the slot base), flips and lists its two triangles; on the
  // first part (first_part) an entry that does not flip is listed for the next round. The
  // entries and the record go where `place` says (a place whose kApply is false only counts
  // them: nothing is written).
  template <class Place>
  GG_HD void vote_flip(std::int64_t i, std::int32_t lo, std::int32_t hi, bool first_part,
                       Place& place) const {
    const int k = dec[i];
    if (k < 0) return;
    const std::int32_t t = slot_of(act[i]);
    const u64 key = key_of(M, round, t);
    const u64 won = M.vote[t];
    // On the GPU the records are read at once, not after the votes that make them this
    // thread's (a record read that way may be changing; it is then left unused): the kernel
    // waits on memory, and this takes two round trips off each flip.
    Tri T;
    if (kReadAhead && first_part) T = M.tri[t];
    if (won == key) {  // t is this proposal's: no other thread writes it this round
      if (!kReadAhead || !first_part) T = M.tri[t];
      const std::int32_t nb = simplex_of(T.n[k]);
      Tri N;
      if (kReadAhead) N = M.tri[nb];
      if (M.vote[nb] == key) {
        if (t - M.base < lo || t - M.base >= hi) return;  // another part's
        std::int64_t at, rec;
        place.flip(at, rec);
        if constexpr (!Place::kApply) return;
        if (!kReadAhead) N = M.tri[nb];
        flip_phase1(M, t, T, k, nb, N, round, M.log.base + std::int32_t(rec));
        // t' = (v_k, v_k+1, d): the diagonal is opposite its vertex 1; n' = (v_k, d, v_k+2):
        // opposite its vertex 2
        next[at] = list_entry(t, 1);
        next[at + 1] = list_entry(nb, 2);
        return;
      }
    } else if (M.vote[voter(M, won)] == won) {
      return;  // the proposal that took t won its own triangle too: it flips t, lists it
    }
    if (!first_part) return;
    const std::int64_t at = place.one();  // lost: tests again
    if constexpr (Place::kApply) next[at] = list_entry(t, -1);
  }

  // Phase 2 of the round's flips: entry i, when its slot is a flipped pair's proposer, fixes
  // the pair's four outer edges. (Over the whole list: a list of the flips alone, appended in
  // vote_flip, measured slower.)
  GG_HD void fix(std::int64_t i) const {
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
  }
};
