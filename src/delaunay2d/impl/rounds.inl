// The 2D Triangulator's flip rounds (triangulator.inl): rounds over the work list until no edge
// on it is illegal, each a test (filter, then the exact pass), the votes and flips, and the fix
// of the flipped pairs' outer edges; the host checks a round that could overflow the exact list
// or the flip log.

// Rounds of flips over the work list until no edge of it is illegal. A round: the edge tests
// (each entry stops at its first illegal edge, proposes it and votes at once; an entry the
// filter cannot decide goes to the exact pass, which goes on from there and votes), the flips
// (a proposal that won both its triangles), and the fix of the flipped pairs' outer edges.
// The schedule is mesh/flip_schedule.hpp's: the list lengths stay on the executor, short lists
// (a batch's last rounds) run several rounds between two reads of the counters, and lists
// short enough for a team whose rounds need no check run in one (team_rounds), until the
// list grows past the team's length or a round needs a check. This phase is what 2D adds:
// its room rule (a round is checked when its records could overflow the flip log or its
// undecided entries the exact list) and its counters.
struct FlipPhase {
  Triangulator& T;
  bool first_round;
  std::int64_t team_list = T.team_list();
  bool checked = false;   // (the chunk's rounds are checked: plan)
  std::int32_t from = 0;  // the round before the chunk's kernels (flip_round counts round_ up)

  std::int64_t pending() const { return T.nact_; }
  std::int64_t team_max() const { return team_list; }
  bool team_fits() const { return !T.needs_check(); }
  // A list at most doubles per round, and a round flips at most one pair per entry and
  // tmax / 2 pairs in all. Rounds run unchecked (several between two reads of the counters)
  // while their records fit the log and their undecided entries the exact list; a round that
  // could overflow either is checked (flip_round's `checked`), alone.
  std::int64_t plan() {
    const std::int64_t nact = T.nact_, tmax = T.tmax_;
    int chunk = nact <= kChunkList ? kChunkRounds : 1;
    auto records = [&](int rounds) {
      std::int64_t b = nact, r = 0;
      for (int c = 0; c < rounds; ++c, b = std::min(2 * b, tmax)) r += std::min(b, tmax / 2);
      return r;
    };
    auto longest = [&](int rounds) {
      std::int64_t b = nact;
      for (int c = 1; c < rounds; ++c) b = std::min(2 * b, tmax);
      return b;
    };
    // (A check costs the host a round trip; relocating all points that are left, many
    // more: the log is only emptied when a check finds it would overflow.)
    if (T.logged_ + records(chunk) > T.log_cap_ || longest(chunk) > T.exact_cap_) chunk = 1;
    checked = T.needs_check();
    return chunk;
  }
  void team(std::int64_t limit) {
    T.team_rounds(first_round, team_list, limit);
    T.mark("flip: team");
  }
  void kernels(std::int64_t rounds) {
    from = T.round_;
    std::int64_t bound = T.nact_;
    for (std::int64_t c = 0; c < rounds; ++c, bound = std::min(2 * bound, T.tmax_)) {
      T.flip_round(bound, first_round, checked);
      first_round = false;
    }
  }
  mesh::ChunkEnd end_chunk(bool team) {
    const Counters c = T.counters();
    T.mark("flip: counters");
    std::int64_t rounds = 0;
    if (team) {
      const std::int32_t last = std::int32_t(c.team_end) - 1;
      if (last <= T.round_) return {};  // (none ran: the kernels take the round)
      rounds = last - T.round_;
      T.round_ = last;
      first_round = false;
    } else {
      rounds = T.round_ - from;
    }
    T.flips_ += c.log - T.logged_;  // one record per flip
    T.logged_ = c.log;
    T.nact_ = c.len[(T.round_ + 1) & 1];
    return {rounds, false};
  }
  [[noreturn]] void out_of_rounds() const {
    throw Error(ErrorCode::Internal,
                "internal error: flipping did not converge; please report this input");
  }
};

inline void Triangulator::flip_until_delaunay(bool first_round) {
  FlipPhase p{*this, first_round};
  mesh::run_rounds(p, kMaxRounds, sched_);
}

// Whether the next round must be checked: its records could overflow the flip log, or its
// undecided entries the exact list (round_fits, flip_round.inl).
inline bool Triangulator::needs_check() const {
  return !round_fits(logged_, nact_, tmax_ / 2, log_cap_, exact_cap_);
}

// The round's functor (flip_round.inl) over the store as it is now (after a relocation: the
// log's new numbering).
inline FlipRound Triangulator::make_round(int edges) {
  FlipRound R;
  R.g = g_;
  R.M = M_;
  R.edges = edges;
  R.L = work_lists();
  R.go_to(round_);
  R.dec = dec_.data();
  R.exd = exd_.data();
  R.exc = exc_.data();
  R.exl = exl_.data();
  R.exact_cap = exact_cap_;
  R.ctr = ctr_.data();
  return R;
}

// The longest list whose rounds run in a team: twice the team's size (the steps stride over it
// in two passes), or Tuning::Del2d::team_list (-1: none).
inline std::int64_t Triangulator::team_list() {
  const std::int64_t forced = ex_.tuning().del2d.team_list;
  if (forced != 0) return std::max<std::int64_t>(forced, 0);
  return 2 * std::int64_t(ex_.team_size());
}

// Rounds from round_ + 1 on in one team (mesh::team_rounds), while the list is non-empty and
// at most `max` long, the round needs no check (round_fits, read on the executor) and fewer
// than `limit` have run; leaves the round it stopped at in the counters (team_end). The steps
// are the kernels' (FlipRound) between barriers, so a team's rounds flip as the kernels'
// would; the exact tests run on the team's first threads, one scratch slot each.
inline void Triangulator::team_rounds(bool first_round, std::int64_t max, std::int64_t limit) {
  FlipRound R0 = make_round(first_round ? 1 : 3);
  R0.go_to(round_ + 1);
  const SlotView scratch = slots_.view();
  const std::int64_t log_cap = log_cap_, half = tmax_ / 2;
  const std::int32_t stop = mesh::team_stop(R0.round, limit);
  ex_.team(GG_LAMBDA(const Exec::Team& t) {
    Counters* ctr = R0.ctr;
    const std::int64_t workers = std::min<std::int64_t>(t.size, scratch.slots);
    auto room = [&](const FlipRound& R, std::int64_t n) {
      return round_fits(ctr->log, n, half, log_cap, R.exact_cap);
    };
    auto steps = [&](const FlipRound& R, std::int64_t n) {
      for (std::int64_t i = t.rank; i < n; i += t.size) R.test(i);
      t.barrier();
      const std::int64_t m = 3 * std::min(ctr->exact[R.parity()], R.exact_cap);
      if (t.rank < workers)
        for (std::int64_t j = t.rank; j < m; j += workers) R.decide(j, scratch[t.rank]);
      t.barrier();
      if (t.rank == 0) R.tally();
      t.barrier();
      for (std::int64_t i = t.rank; i < n; i += t.size)
        R.vote_flip(i, 0, std::numeric_limits<std::int32_t>::max(), true);
      t.barrier();
      for (std::int64_t i = t.rank; i < n; i += t.size) R.fix(i);
      t.barrier();
    };
    mesh::team_rounds(t, R0, max, stop, &ctr->team_end, room, steps);
  });
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
  const int edges = first_round ? 1 : 3;  // (FlipRound::edges)
  const FlipRound R = make_round(edges);
  listed(
      R.len, bound, GG_LAMBDA(std::int64_t i) { R.test(i); });
  mark("flip: test");
  exact_pass(bound, edges, &R.ctr->exact[R.parity()], true);
  mark("flip: exact");
  std::vector<std::int64_t> cuts;
  if (checked) {
    cuts = check_round(bound, edges);
    mark("flip: check");
  }
  cuts.push_back(std::numeric_limits<std::int32_t>::max());
  vote_and_flip(bound, 0, cuts[0], true);
  for (std::size_t k = 1; k < cuts.size(); ++k) {  // the log full: the points move on first
    ++split_rounds_;
    const Counters c = counters();
    flips_ += c.log - logged_;
    logged_ = c.log;
    relocate(false);
    ++relocations_;
    vote_and_flip(bound, cuts[k - 1], cuts[k], false);
  }
  mark("flip: vote+flip");
  const FlipRound F = make_round();
  listed(
      F.len, bound, GG_LAMBDA(std::int64_t i) { F.fix(i); });
  mark("flip: fix");
}

// The round's proposals into the counters (entries that decided on an illegal edge).
inline void Triangulator::count_proposals(std::int64_t bound) {
  const FlipRound R = make_round();
  ex_.transform_reduce_into(
      bound, GG_LAMBDA(std::int64_t i)->std::int64_t { return R.proposed(i); }, std::int64_t(0),
      thrust::plus<std::int64_t>(), &R.ctr->proposals);
}

// The host's part of a checked round (see flip_round): returns where the round's flips are
// cut into parts (slots from the slot base; none: one part).
inline std::vector<std::int64_t> Triangulator::check_round(std::int64_t bound, int edges) {
  const FlipRound R = make_round(edges);
  Counters* ctr = R.ctr;
  const int p = R.parity();
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
          R.len, bound, GG_LAMBDA(std::int64_t i) { R.relist_undecided(i); });
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
  const FlipRound W = make_round(edges);  // (after the relocation)
  const int shift = win_shift_;
  std::int64_t* wins = wins_.data();
  const std::int64_t buckets = wins_.size();
  ex_.fill(wins, buckets, std::int64_t(0));
  listed(
      W.len, bound, GG_LAMBDA(std::int64_t i) { W.count_win(i, wins, shift); });
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
// base) flipped (FlipRound::vote_flip); on the first part, every entry that does not flip is
// listed for the next round.
inline void Triangulator::vote_and_flip(std::int64_t bound, std::int64_t lo_in, std::int64_t hi_in,
                                        bool first_part) {
  const FlipRound R = make_round();  // (after a relocation: the log's new numbering)
  const std::int32_t lo = std::int32_t(lo_in), hi = std::int32_t(hi_in);
  if (flips_in_order(ex_, R, lo, hi, first_part)) return;
  listed(
      R.len, bound, GG_LAMBDA(std::int64_t i) { R.vote_flip(i, lo, hi, first_part); });
}

// On the CPU executor, vote_and_flip's appends go in the list's order (CpuExec::append_in_order:
// no counter shared by the threads, each thread's entries and records in one run of memory);
// returns whether it ran (not on CUDA, whose appends are atomics aggregated per warp).
template <class E>
bool Triangulator::flips_in_order(E& ex, const FlipRound& R, std::int32_t lo, std::int32_t hi,
                                  bool first_part) {
  if constexpr (E::backend != Backend::Cpu) {
    return false;
  } else {
    std::int64_t* const base[2] = {R.next_len, &R.ctr->log};
    ex.template append_in_order<2>(*R.len, base, [&](std::int64_t i, auto& place) {
      FlipRound::InOrder<std::decay_t<decltype(place)>> p{place};
      R.vote_flip(i, lo, hi, first_part, p);
    });
    return true;
  }
}

// The exact pass over the entries the filter left open (FlipRound::decide): a bounded number
// of threads, each with its own scratch, strides over the list (its length stays on the
// executor). It decides the first exact_cap_ entries of the list whose length is at *listed;
// the round's first pass (first) also does the round's bookkeeping (FlipRound::tally).
inline void Triangulator::exact_pass(std::int64_t bound, int edges, const std::int64_t* listed,
                                     bool first) {
  const FlipRound R = make_round(edges);
  const CountAt count{listed, 3, exact_cap_};
  bound = std::min(bound, exact_cap_);
  auto decide = GG_LAMBDA(std::int64_t j, double* scr) {
    R.decide(j, scr);
  };
  if (!first) {
    slots_.run_counted(ex_, 3 * bound, count, decide);
    return;
  }
  slots_.run_counted(
      ex_, 3 * bound, count, decide, GG_LAMBDA() { R.tally(); });
}
