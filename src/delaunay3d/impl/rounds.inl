// Phase 1's flip rounds, scheduled (triangulator.inl) by mesh/flip_schedule.hpp: chunks of
// rounds as kernels, the short lists' rounds in one team, a halted round's room made. The steps
// are FlipRound's (flip_round.inl).

// Phase 1's side of the schedule (mesh/flip_schedule.hpp): the flip log's epochs planned per
// chunk, a halted round's room made, the list carried to the next batch, and the test mode's
// cut (Tuning::Del3d::max_flip_rounds: what is left goes to phase 2).
struct FlipPhase {
  Triangulator& T;
  std::int32_t first = 0;  // the chunk's first round

  std::int64_t pending() const { return T.nact_; }
  std::int64_t team_max() const { return 2 * std::int64_t(T.ex_.team_size()); }
  bool team_fits() const { return true; }  // (a round without room halts the team)
  // The flip log: a round records at most one flip per list entry, in practice at most 0.7
  // (0.3 on average). A new epoch starts where the next round may not fit, and the chunk holds
  // the rounds that should; a round that does not fit halts (end_chunk makes the room).
  std::int64_t plan() {
    const std::int64_t per_round = T.nact_ - T.nact_ * 3 / 10;
    if (T.logged_ + per_round > T.log_cap_) T.relocate(false);
    first = T.round_ + 1;
    return std::clamp<std::int64_t>((T.log_cap_ - T.logged_) / std::max<std::int64_t>(per_round, 1),
                                    1, Triangulator::kChunk);
  }
  void team(std::int64_t limit) { T.team_rounds(first, team_max(), limit); }
  void kernels(std::int64_t rounds) {
    for (std::int64_t k = 0; k < rounds; ++k) T.launch_round(first + std::int32_t(k), 4 * T.nact_);
    kernel_rounds = rounds;
  }
  mesh::ChunkEnd end_chunk(bool team) {
    Counters c = T.counters();  // one read per chunk
    std::int32_t last =
        team ? std::int32_t(c.team_end) - 1 : first + std::int32_t(kernel_rounds) - 1;
    const bool carry = c.halt && c.carry;
    if (c.halt) {  // (the halted round did nothing: it runs again after the room is made, or
                   // in the next batch, carried)
      last = std::int32_t(c.halt_round) - 1;
      T.used_ = c.used;
      T.logged_ = c.log;
      const Counters need = c;
      c.halt = c.carry = 0;
      c.carries += carry;
      c.need_slots = c.need_log = c.need_list = c.need_ring = 0;
      T.ex_.from_host(&c, 1, T.ctr_.data());
      if (!carry) T.make_room(need);
      c = T.counters();
    }
    const std::int64_t rounds = last - T.round_;
    T.round_ = last;
    T.used_ = c.used;
    T.logged_ = c.log;
    T.nact_ = c.len[(T.round_ + 1) & 1];
    if (c.errors) T.check_errors();
    return {rounds, carry};  // (carried: nact_ entries wait in the list of round_ + 1)
  }
  void out_of_rounds() {
    if (T.max_rounds_ < 0)
      throw Error(ErrorCode::Internal,
                  "internal error: 3D flipping did not converge; please report this input");
    const mesh::WorkLists L = T.work_lists();  // (test mode: the rest is phase 2's)
    std::int64_t* len = L.count(T.round_ + 1);
    T.ex_.for_each_index(
        1, GG_LAMBDA(std::int64_t) { *len = 0; });
    T.nact_ = 0;
  }
  std::int64_t kernel_rounds = 0;
};

inline void Triangulator::flip_until_stuck() {
  FlipPhase p{*this};
  mesh::run_rounds(p, max_rounds_ >= 0 ? max_rounds_ : kMaxRounds, sched_);
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

// Rounds from `round` on in one team (mesh::team_rounds), while the list is non-empty and at
// most `max` long, nothing halts and fewer than `limit` have run; leaves the round it stopped
// at in the counters (team_end).
inline void Triangulator::team_rounds(std::int32_t round, std::int64_t max, std::int64_t limit) {
  const FlipRound R0 = make_round(round);
  Counters* ctr = ctr_.data();
  const std::int32_t stop = mesh::team_stop(round, limit);
  ex_.team(GG_LAMBDA(const Exec::Team& t) {
    auto room = [](const FlipRound& R, std::int64_t) { return !R.halted(); };
    auto steps = [&](const FlipRound& R, std::int64_t n) {
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
    };
    mesh::team_rounds(t, R0, max, stop, &ctr->team_end, room, steps);
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
