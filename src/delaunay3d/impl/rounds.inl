// Phase 1's flip rounds, scheduled (triangulator.inl): chunks of rounds as kernels, the short
// lists' rounds in one team, a halted round's room made. The steps are FlipRound's
// (flip_round.inl).

inline void Triangulator::flip_until_stuck() {
  std::int64_t rounds_here = 0;
  const std::int64_t team_max = 2 * std::int64_t(ex_.team_size());
  while (nact_ > 0) {
    if (max_rounds_ >= 0 && rounds_here >= max_rounds_) {  // (test mode: leave it to phase 2)
      const mesh::WorkLists L = work_lists();
      std::int64_t* len = L.count(round_ + 1);
      ex_.for_each_index(
          1, GG_LAMBDA(std::int64_t) { *len = 0; });
      nact_ = 0;
      break;
    }
    // The flip log: a round records at most one flip per list entry, in practice at most
    // 0.7 (0.3 on average). A new epoch starts where the next round may not fit, and the
    // chunk holds the rounds that should; a round that does not fit halts (make_room).
    const std::int64_t per_round = nact_ - nact_ * 3 / 10;
    if (logged_ + per_round > log_cap_) relocate(false);
    const std::int32_t first = round_ + 1;
    std::int64_t chunk = std::clamp<std::int64_t>(
        (log_cap_ - logged_) / std::max<std::int64_t>(per_round, 1), 1, kChunk);
    if (max_rounds_ >= 0) chunk = std::min<std::int64_t>(chunk, max_rounds_ - rounds_here);
    const bool team = nact_ <= team_max;
    const auto t0 = Clock::now();
    if (team)
      team_rounds(first, team_max, max_rounds_ >= 0 ? chunk : std::int64_t(1) << 30);
    else
      for (std::int64_t k = 0; k < chunk; ++k) launch_round(first + std::int32_t(k), 4 * nact_);
    Counters c = counters();  // one read per chunk
    (team ? ms_team_ : ms_wide_) += ms_since(t0);
    ++(team ? team_calls_ : chunks_);
    std::int32_t last = team ? std::int32_t(c.team_end) - 1 : first + std::int32_t(chunk) - 1;
    const bool carry = c.halt && c.carry;
    if (c.halt) {  // (the halted round did nothing: it runs again after the room is made, or
                   // in the next batch, carried)
      last = std::int32_t(c.halt_round) - 1;
      used_ = c.used;
      logged_ = c.log;
      const Counters need = c;
      c.halt = c.carry = 0;
      c.carries += carry;
      c.need_slots = c.need_log = c.need_list = c.need_ring = 0;
      ex_.from_host(&c, 1, ctr_.data());
      if (!carry) make_room(need);
      c = counters();
    }
    rounds_here += last - round_;
    round_ = last;
    used_ = c.used;
    logged_ = c.log;
    nact_ = c.len[(round_ + 1) & 1];
    if (c.errors) check_errors();
    if (carry) break;  // (nact_ entries wait in the list of round_ + 1)
  }
}

inline FlipRound Triangulator::make_round(std::int32_t round) {
  FlipRound R;
  R.g = g_;
  R.M = M_;
  R.L = work_lists();
  R.dec = dec_.data();
  R.tally = tally_.data();
  R.round = round;
  R.log_cap = log_cap_;
  R.list_cap = list_cap_;
  R.span = list_cap_;
  R.carry_from = carry_from_;
  R.carry_max = kCarryList;
  return R;
}

// One round as kernels, each over the list length read on the executor (bound sizes the
// grids; every kernel covers the whole list whatever its length), and a scan of the
// decisions over bound entries (those past the length count nothing).
inline void Triangulator::launch_round(std::int32_t round, std::int64_t bound) {
  FlipRound R = make_round(round);
  R.span = std::min<std::int64_t>(bound, list_cap_);
  const std::int64_t* count = R.count();
  ex_.for_each_index(
      1, GG_LAMBDA(std::int64_t) { R.begin(); });
  // (the test: tens of millions of sphere tests a run, latency-bound; 3 blocks of 256 a
  // multiprocessor give it 80 registers, with the exact tiers out of line, geometry.inl)
  ex_.template for_each_counted<3>(
      count, bound, GG_LAMBDA(std::int64_t i) { R.test(i); });
  ex_.for_each_counted(
      count, bound, GG_LAMBDA(std::int64_t i) { R.decide(i); });
  ex_.exclusive_scan_of(
      R.span + 1,
      GG_LAMBDA(std::int64_t i)->Tally {
        return i < *count ? R.tally_at(i) : Tally{0, 0, 0};
      },
      R.tally);
  ex_.for_each_index(
      1, GG_LAMBDA(std::int64_t) { R.settle(); });
  ex_.for_each_counted(
      count, bound, GG_LAMBDA(std::int64_t i) { R.flip(i); });
  ex_.for_each_counted(
      R.flips(), bound, GG_LAMBDA(std::int64_t i) { R.fix(i); });
  ex_.for_each_counted(
      count, bound, GG_LAMBDA(std::int64_t i) { R.relist(i); });
}

// Rounds from `round` on in one team, while the list is non-empty and at most `max` long,
// nothing halts and fewer than `limit` have run; leaves the round it stopped at in the
// counters (team_end).
inline void Triangulator::team_rounds(std::int32_t round, std::int64_t max, std::int64_t limit) {
  const FlipRound R0 = make_round(round);
  Counters* ctr = ctr_.data();
  const std::int32_t stop = std::int32_t(std::min<std::int64_t>(round + limit, INT32_MAX));
  ex_.team(GG_LAMBDA(const Exec::Team& t) {
    FlipRound R = R0;
    std::int32_t r = round;
    for (;;) {
      const std::int64_t n = *R.count();
      if (n == 0 || n > max || r >= stop || ctr->halt) break;
      t.barrier();  // (every thread has read the length before the round's first write)
      if (t.rank == 0) R.begin();
      t.barrier();
      for (std::int64_t i = t.rank; i < n; i += t.size) R.test(i);
      t.barrier();
      for (std::int64_t i = t.rank; i < n; i += t.size) R.decide(i);
      t.barrier();
      team_tally(t, R, n);
      if (t.rank == 0) R.settle();
      t.barrier();
      for (std::int64_t i = t.rank; i < n; i += t.size) R.flip(i);
      t.barrier();
      const std::int64_t nf = *R.flips();
      for (std::int64_t i = t.rank; i < nf; i += t.size) R.fix(i);
      t.barrier();
      for (std::int64_t i = t.rank; i < n; i += t.size) R.relist(i);
      t.barrier();
      R.round = ++r;
    }
    if (t.rank == 0) ctr->team_end = r;
  });
}

// The prefix of the decisions over the list inside a team (ends with a barrier): each thread
// sums a contiguous piece, the team scans the sums, and each thread writes its piece's
// prefixes, so that the order is the list's whatever the team's size. (A team's list is at
// most two entries a thread, far below the 2^21 each packed count may reach.)
template <class Team>
inline GG_HD void Triangulator::team_tally(const Team& t, const FlipRound& R, std::int64_t n) {
  const std::int64_t piece = (n + t.size - 1) / t.size;
  const std::int64_t lo = std::min<std::int64_t>(n, t.rank * piece);
  const std::int64_t hi = std::min<std::int64_t>(n, lo + piece);
  auto pack = [](const Tally& x) {
    return std::int64_t(x.w23) | (std::int64_t(x.w32) << 21) | (std::int64_t(x.lost) << 42);
  };
  auto unpack = [](std::int64_t v) {
    constexpr std::int64_t mask = (std::int64_t(1) << 21) - 1;
    return Tally{std::int32_t(v & mask), std::int32_t((v >> 21) & mask), std::int32_t(v >> 42)};
  };
  Tally mine{0, 0, 0};
  for (std::int64_t i = lo; i < hi; ++i) mine = mine + R.tally_at(i);
  std::int64_t total = 0;
  Tally run = unpack(t.exclusive_scan(pack(mine), &total));
  for (std::int64_t i = lo; i < hi; ++i) {
    const Tally x = R.tally_at(i);
    R.tally[i] = run;
    run = run + x;
  }
  if (t.rank == 0) R.tally[n] = unpack(total);
  t.barrier();
}

// What a halted round needs (settle's counts), made: a larger store, list, ring or log,
// or a new epoch of records.
inline void Triangulator::make_room(const Counters& c) {
  if (c.need_list > list_cap_) grow_lists(std::max(c.need_list, list_cap_ + list_cap_ / 4));
  if (c.need_slots > cap_) reserve(c.need_slots);
  if (c.need_ring > ring_cap_) grow_ring(std::max(c.need_ring, ring_cap_ + ring_cap_ / 4));
  if (c.log + c.need_log > log_cap_) {
    relocate(false);
    if (c.need_log > log_cap_) grow_log(std::max(c.need_log, log_cap_ + log_cap_ / 4));
  }
}
