// The 2D Triangulator's flip rounds (triangulator.inl): rounds over the work list until no edge
// on it is illegal, each a test (filter, then the exact pass), the votes and flips, and the fix
// of the flipped pairs' outer edges; the host checks a round that could overflow the exact list
// or the flip log.

// Rounds of flips over the work list until no edge of it is illegal. A round: the edge tests
// (each entry stops at its first illegal edge, proposes it and votes at once; an entry the
// filter cannot decide goes to the exact pass, which goes on from there and votes), the flips
// (a proposal that won both its triangles), and the fix of the flipped pairs' outer edges.
// The list lengths stay on the executor: short lists (a batch's last rounds) run several
// rounds between two reads of the counters, so that the host's round trip does not leave
// the GPU idle once per round (a round past the end finds an empty list and does nothing).
inline void Triangulator::flip_until_delaunay(bool first_round) {
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
inline void Triangulator::flip_round(std::int64_t bound, bool first_round, bool checked) {
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
inline void Triangulator::count_proposals(std::int64_t bound) {
  const std::int64_t* count = work_lists().count(round_);
  const std::int8_t* dec = dec_.data();
  ex_.transform_reduce_into(
      bound, GG_LAMBDA(std::int64_t i)->std::int64_t { return i < *count && dec[i] >= 0; },
      std::int64_t(0), thrust::plus<std::int64_t>(), &ctr_.data()->proposals);
}

// The host's part of a checked round (see flip_round): returns where the round's flips are
// cut into parts (slots from the slot base; none: one part).
inline std::vector<std::int64_t> Triangulator::check_round(std::int64_t bound, int edges) {
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
inline void Triangulator::vote_and_flip(const std::int32_t* act, const std::int64_t* count,
                                        std::int64_t bound, std::int64_t lo_in, std::int64_t hi_in,
                                        bool first_part) {
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
inline void Triangulator::exact_pass(std::int64_t bound, int edges, const std::int64_t* listed,
                                     bool first) {
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
inline void Triangulator::fix_round(const std::int32_t* act, const std::int64_t* count,
                                    std::int64_t bound) {
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
