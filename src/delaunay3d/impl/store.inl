// Phase 1's store (triangulator.inl): the tetrahedra and every per-slot, per-list and per-point
// array of the rounds, with their growth. The Triangulator is the algorithm over it; this is
// where its memory is sized, grown and given back, so that the two can be read apart.
//
// (Every member is public: nvcc's extended lambdas may not live in private members, and the
// Triangulator's kernels read these arrays.)
struct TetStore {
  explicit TetStore(Exec& ex) : ex_(ex) {}

  // The kernels' view of the store.
  void set_mesh();
  void grow(std::int64_t cap);
  void grow_lists(std::int64_t entries);
  void grow_ring(std::int64_t entries);
  void grow_log(std::int64_t records);
  // A per-batch array (nothing kept) of at least n entries.
  template <class T>
  void fit(typename Exec::template Buffer<T>& b, std::int64_t n) {
    if (std::int64_t(b.size()) >= n) return;
    b = typename Exec::template Buffer<T>();
    b = ex_.template alloc<T>(std::size_t(std::max<std::int64_t>(n + n / 4, 1024)));
    note_bytes();
  }
  // Room for `slots`: an eighth more than now at least (each growth copies the store), but
  // never past the 2^30 - 1 slots the neighbour encoding (tet.hpp) can address.
  static constexpr std::int64_t kMaxSlots = kMaxTetSlots;
  void reserve(std::int64_t slots);

  // Phase 1's int32 arrays (what held_bytes counts and release_phase1 frees).
  std::array<typename Exec::template Buffer<std::int32_t>*, 10> int32_arrays() {
    return {&srank_, &freeq_, &lists_[0], &lists_[1], &rec_, &loc_, &un_, &un2_, &ins_, &split_};
  }
  std::int64_t held_bytes();
  void note_bytes() { peak_bytes_ = std::max(peak_bytes_, held_bytes()); }
  void release_phase1();

  Counters counters() {
    Counters c;
    ex_.to_host(ctr_.data(), 1, &c);
    return c;
  }
  mesh::WorkLists work_lists() {
    return mesh::WorkLists{{lists_[0].data(), lists_[1].data()}, ctr_.data()->len};
  }
  // Phase 2 (repair.inl) rewrites the store: room for `slots`, then the slots in use.
  Tet* store_for(std::int64_t slots) {
    reserve(slots);
    return tet_.data();
  }
  void set_used(std::int64_t used) {
    Counters c = counters();
    c.used = used;
    ex_.from_host(&c, 1, ctr_.data());
  }

  Exec& ex_;
  std::int32_t m_ = 0;
  Mesh M_{};
  std::int64_t cap_ = 0, log_cap_ = 0, list_cap_ = 0, ring_cap_ = 0;  // capacities
  bool phase1_released_ = false;    // release_phase1 ran: grow keeps the store only
  bool cavities_ = false;           // the CPU's cavities (one_by_one.inl): the store alone
  std::int64_t scratch_bytes_ = 0;  // the exact stages' (the Triangulator's lease pool)
  std::int64_t peak_bytes_ = 0;
  typename Exec::template Buffer<Tet> tet_;
  typename Exec::template Buffer<Hist> hist_;
  typename Exec::template Buffer<std::int32_t> srank_, rec_, split_, freeq_;
  // Per slot: the flip rounds' votes, and the choice of a batch's points (cleared before it).
  typename Exec::template Buffer<u64> key_;
  typename Exec::template Buffer<std::int32_t> lists_[2];
  typename Exec::template Buffer<std::int32_t> loc_, un_, un2_, ins_;
  typename Exec::template Buffer<Tally> tally_;
  typename Exec::template Buffer<std::int8_t> dec_;
  typename Exec::template Buffer<Counters> ctr_;
};

inline void TetStore::set_mesh() {
  M_ = Mesh{tet_.data(),   key_.data(), FlipLog{rec_.data(), hist_.data(), M_.log.base},
            freeq_.data(), cap_,        ring_cap_,
            ctr_.data()};
}

// Capacity for cap slots: every per-slot array grows, keeping what it holds. One array at a
// time, so that at most one array is held twice (the largest inputs fill the device: a
// whole second store would not fit).
inline void TetStore::grow(std::int64_t cap) {
  if (phase1_released_) {  // phase 2 and the output read the store only (release_phase1)
    const Counters c = counters();
    regrow<Tet>(ex_, tet_, cap, std::min<std::int64_t>(c.used, cap_), nullptr);
    cap_ = cap;
    M_ = Mesh{tet_.data(), nullptr, FlipLog{}, nullptr, cap_, 0, ctr_.data()};
    return;
  }
  const std::int32_t minus1 = -1;
  if (cavities_) {  // (the cavities' schedule counts no slots until it ends: all are kept)
    regrow<Tet>(ex_, tet_, cap, cap_, nullptr);
    cap_ = cap;
    set_mesh();
    note_bytes();
    return;
  }
  const std::int64_t keep = cap_ ? std::min<std::int64_t>(counters().used, cap_) : 0;
  regrow<Tet>(ex_, tet_, cap, keep, nullptr);
  const u64 none = ~u64(0);
  const Hist nohist{-1, -1};
  regrow(ex_, key_, cap, keep, &none);
  regrow(ex_, hist_, cap, keep, &nohist);
  regrow(ex_, srank_, cap, keep, &minus1);
  cap_ = cap;
  set_mesh();
  note_bytes();
}

// The two work lists (keeping their entries) and the decisions' scratch, for lists of up to
// `entries` (a list holds distinct slots: never more than the slots in use).
inline void TetStore::grow_lists(std::int64_t entries) {
  const Counters c = counters();
  for (int l = 0; l < 2; ++l)
    regrow<std::int32_t>(ex_, lists_[l], entries, std::min(c.len[l], list_cap_), nullptr);
  dec_ = typename Exec::template Buffer<std::int8_t>();
  tally_ = typename Exec::template Buffer<Tally>();
  dec_ = ex_.template alloc<std::int8_t>(std::size_t(entries));
  tally_ = ex_.template alloc<Tally>(std::size_t(entries) + 1);
  list_cap_ = entries;
  note_bytes();
}

// The ring of freed slots, unrolled into `entries`.
inline void TetStore::grow_ring(std::int64_t entries) {
  Counters c = counters();
  auto freeq = ex_.template alloc<std::int32_t>(std::size_t(entries));
  if (ring_cap_) {
    const std::int64_t nfree = c.free_tail - c.free_head;
    const std::int32_t* q = freeq_.data();
    std::int32_t* nq = freeq.data();
    const std::int64_t head = c.free_head, ocap = ring_cap_;
    ex_.for_each_index(
        nfree, GG_LAMBDA(std::int64_t i) { nq[i] = q[(head + i) % ocap]; });
    c.free_head = 0;
    c.free_tail = nfree;
    ex_.from_host(&c, 1, ctr_.data());
  }
  freeq_ = std::move(freeq);
  ring_cap_ = entries;
  set_mesh();
  note_bytes();
}

// The flip log, for epochs of up to `records` (keeping the epoch's records).
inline void TetStore::grow_log(std::int64_t records) {
  const std::int64_t keep = log_cap_ ? FlipLog::kStride * counters().log : 0;
  regrow<std::int32_t>(ex_, rec_, FlipLog::kStride * records, keep, nullptr);
  log_cap_ = records;
  set_mesh();
  note_bytes();
}

inline void TetStore::reserve(std::int64_t slots) {
  if (slots <= cap_) return;
  if (slots > kMaxSlots)
    throw Error(ErrorCode::OutOfMemory,
                "the tetrahedralisation needs more than 2^30 - 1 tetrahedra (about 1.4·10^8 "
                "points), more than the 32-bit neighbour encoding can address");
  grow(std::min(std::max(slots, cap_ + cap_ / 8), kMaxSlots));
}

// Bytes phase 1 holds on the executor (its arrays and the exact stages' scratch), and the
// most it held.
inline std::int64_t TetStore::held_bytes() {
  std::int64_t b = std::int64_t(tet_.size()) * sizeof(Tet) + std::int64_t(hist_.size()) * 8 +
                   std::int64_t(key_.size()) * 8 + std::int64_t(dec_.size()) +
                   std::int64_t(tally_.size()) * sizeof(Tally) + scratch_bytes_;
  for (const auto* x : int32_arrays()) b += std::int64_t(x->size()) * 4;
  return b + std::int64_t(m_) * (sizeof(double) * 3 + sizeof(std::int32_t));  // (prepare's)
}

// Phase 1's working arrays, once it is done: what follows (failed faces, phase 2, the
// output) reads only the store, the counters and the points.
inline void TetStore::release_phase1() {
  for (auto* b : int32_arrays()) *b = typename Exec::template Buffer<std::int32_t>();
  key_ = typename Exec::template Buffer<u64>();
  hist_ = typename Exec::template Buffer<Hist>();
  dec_ = typename Exec::template Buffer<std::int8_t>();
  tally_ = typename Exec::template Buffer<Tally>();
  M_ = Mesh{tet_.data(), nullptr, FlipLog{}, nullptr, cap_, 0, ctr_.data()};
  // A later growth (star splaying may add more tetrahedra than the store holds) must not
  // copy out of the arrays just freed (it did: a crash on the CPU, an invalid output or an
  // error on the GPU, where splaying repaired many vertices).
  phase1_released_ = true;
}
