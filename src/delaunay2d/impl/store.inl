// The 2D Triangulator's store (triangulator.inl): the triangles and every per-slot, per-list,
// per-point and per-record array of the batches and rounds, sized once from the point count
// (2m - 2 slots: the extended triangulation never has more), and given back before the output.
//
// (Every member is public: nvcc's extended lambdas may not live in private members, and the
// Triangulator's kernels read these arrays.)

// Exact-pass threads, each with an 8 kB scratch slice: enough to fill the GPU on degenerate
// input (an integer grid sends most in-circle tests to the exact stage), at most ~0.5 GB.
constexpr std::int64_t kExactSlotsMin = 1024, kExactSlotsMax = 65536;
constexpr std::int64_t kWinBuckets = 4096;  // (check_round)

struct TriStore {
  TriStore(Exec& ex, Prepared& P) : ex_(ex), P_(P) {
    m_ = std::int32_t(P.m);
    tmax_ = 2 * std::int64_t(m_) - 2;
    // Tests only (Tuning::Del2d::slot_base): slots numbered from base_ rather than 0, up to
    // the encoding's last slot, so that small inputs run through the top of the wide encoding
    // (bit 31 set in neighbour pointers and list entries). The slot-indexed arrays are then
    // addressed through pointers offset by -base_ (tri(), claims(), srank(), M_).
    const detail::Tuning::Del2d& forced = ex.tuning().del2d;
    base_ = std::clamp<std::int64_t>(forced.slot_base, 0, Adj::kMaxSlots - tmax_);
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
    Counters zero{};
    ex.from_host(&zero, 1, ctr_.data());
  }

  // The batches' and flip rounds' arrays set to their first state, before their first use
  // (start, start_from, and the peel where it flips). The CPU executor's schedule uses none of
  // them, and their pages are then never touched: filling them took 40 MB of fresh pages at
  // 10^6 points, 8-10 ms on the 2-core machine.
  void ready_rounds() {
    if (rounds_ready_) return;
    ex_.fill(hist_.data(), tmax_, Hist{-1, -1});
    ex_.fill(vote_.data(), tmax_, u64(0));
    ex_.fill(split_rank_.data(), tmax_, std::int32_t(-1));
    ex_.fill(exc_.data(), exact_cap_, std::int32_t(0));
    rounds_ready_ = true;
  }
  static std::int64_t log_capacity(Exec& ex, std::int64_t forced_records, std::int64_t tmax);
  void release_work();

  mesh::WorkLists work_lists() {
    return mesh::WorkLists{{lists_[0].data(), lists_[1].data()}, ctr_.data()->len};
  }
  Counters counters() {
    Counters c;
    ex_.to_host(ctr_.data(), 1, &c);
    return c;
  }
  // The slot-indexed arrays, addressed by slot number (from base_).
  Tri* tri() { return tri_.data() - base_; }
  u64* claims() { return vote_.data() - base_; }
  std::int32_t* srank() { return split_rank_.data() - base_; }

  Exec& ex_;
  Prepared& P_;
  Mesh M_;
  std::int32_t m_ = 0;
  std::int64_t tmax_ = 0;
  std::int64_t base_ = 0;  // the first slot's number (0 but in tests)
  // capacities: the most points a batch inserts (a uniform batch inserts at most about a
  // third of the points: measured 0.33 m at 10^6; the rest wait for the next batch), flip
  // records, exact-list entries; the shift of the winners' buckets (check_round)
  std::int64_t ins_cap_ = 0, log_cap_ = 0, exact_cap_ = 0;
  int win_shift_ = 0;
  bool rounds_ready_ = false;  // (ready_rounds)
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

// Flip records the log holds. Past its capacity the points are relocated (a pass over all
// points not yet inserted), so it takes what memory is left, from a quarter as many records
// as points (6 B a point; the memory check before launch counts this) to as many as the
// most flips of any round (24 B). It never changes the result (flip_round). Measured on
// uniform input at 10^6: a batch logs up to about 0.7 m flips, one round up to 0.45 m.
// (At least 2^20 records: the rounds that run unchecked, several between two reads of the
// counters, stay below that.)
inline std::int64_t TriStore::log_capacity(Exec& ex, std::int64_t forced_records,
                                           std::int64_t tmax) {
  if (forced_records > 0) return forced_records;
  const std::int64_t least = std::max<std::int64_t>(tmax / 8, 1 << 20);
  const std::int64_t most = std::max<std::int64_t>(tmax / 2, least);
  // (a margin for the pool's blocks and the temporary storage of compactions)
  const std::uint64_t avail = ex.available_memory();
  const std::uint64_t margin = (std::uint64_t(1) << 29) + avail / 64;
  const std::int64_t fit =
      avail > margin
          ? std::int64_t(std::min<std::uint64_t>(
                (avail - margin) / (FlipLog::kStride * sizeof(std::int32_t)), std::uint64_t(most)))
          : 0;
  return std::clamp(fit, least, most);
}

// Frees what only the insertion and flip rounds use (everything but the triangle store and
// the counters), so the output arrays that finish() makes reuse that memory instead of adding
// to it: the device peak of a triangulation is then the rounds', not rounds' plus output's
// (issue 23). Call after run() and report()'s counters are safe (they live on in ctr_).
inline void TriStore::release_work() {
  auto drop = [](auto& b) { b = std::remove_reference_t<decltype(b)>(); };
  drop(hist_), drop(split_rank_), drop(rec_), drop(split_), drop(vote_);
  drop(lists_[0]), drop(lists_[1]), drop(exl_), drop(exc_), drop(loc_), drop(un_);
  drop(ins_), drop(dec_), drop(exd_), drop(slots_), drop(wins_);
}
