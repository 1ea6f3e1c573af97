// Phase 1 of the 3D Delaunay tetrahedralisation (thesis 5.3.1, Alg. 5.6), one algorithm for
// both executors; included inside gpugeom::del3d::{cpu,cuda}_impl after geometry.inl.
//
// Each batch: every tetrahedron holding points not yet inserted takes the one nearest its
// circumcentre and splits around it (1-4). Then rounds of flips: every tetrahedron on the
// work list tests its faces; at its first face that is not locally Delaunay it proposes the
// flip that removes it, 2-3 when the segment between the two apexes crosses the face, 3-2
// when it passes outside across one edge of the face and that edge has degree 3 (otherwise
// the face cannot be flipped now). A flip goes ahead when its proposer holds the highest
// vote key (mesh/priority.hpp) on every tetrahedron it rewrites, so every round flips. What
// the winners are handed (a 2-3 flip's third slot, a record, places in the next list) follows
// their ranks in list order (Tally), so the whole run, slot numbers and list orders included,
// never depends on timing. The flipped tetrahedra and the outvoted proposers form the next
// list. Flips are recorded (mesh/history.hpp); before the next choice each point not yet
// inserted follows its tetrahedron through the split and the records.
// A batch's rounds stop once their list is short (a few rounds in): what is left goes on
// with the next batch's rounds (the last batch flips to the end), as gDel3D leaves small
// lists to later rounds; integer grids' hull planes otherwise cost a long chain of rounds per
// batch.
//
// In 3D flipping can get stuck (Joe): faces that are not locally Delaunay but cannot be flipped.
// After the last batch every face is tested, and the vertices of the failed ones go to phase 2
// (repair.inl), which repairs the tetrahedralisation by star splaying on the executor.
//
// The parts: the rounds' steps as one functor (flip_round.inl), the store and its growth
// (store.inl), this class with the start (start.inl), the batches and the points' relocation
// (batch.inl), the rounds' schedule (rounds.inl), the failed faces, output and statistics
// (finish.inl); the pipeline around it is triangulate.inl.

// (Every member is public: nvcc's extended lambdas may not live in private members.)
class Triangulator : public TetStore {
 public:
  // by_cavities: the CPU executor's own schedule (one_by_one.inl) rather than the batches;
  // only the store is then made.
  Triangulator(Exec& ex, const double* pts, std::int32_t m, const mesh::Tetra& first,
               std::int64_t max_rounds, const ProgressFn& progress, Delaunay3dStats& st,
               bool by_cavities = false)
      : TetStore(ex), st_(st), max_rounds_(max_rounds), progress_(progress) {
    m_ = m;
    cavities_ = by_cavities;
    g_.p = pts;
    for (int k = 0; k < 3; ++k) g_.s[k] = first.s[k];
    g_.m = m;
    first_ = first;
    // (one slot per thread that may hold one at a time on the CPU; on the GPU enough that
    // threads rarely wait, at 114 KB a slot)
    pool_ = LeasePool<Exec>(
        ex, std::clamp<std::int64_t>(std::min<std::int64_t>(ex.concurrency(), m / 8), 64, 1024),
        pred::kInsphereScratch);
    g_.lease = pool_.view;
    scratch_bytes_ = std::int64_t(pool_.scratch.size()) * 8;
    const std::size_t n = std::size_t(m);
    loc_ = ex.template alloc<std::int32_t>(n);
    const std::int64_t m64 = m;
    ctr_ = ex.template alloc<Counters>(1);
    Counters zero{};
    ex.from_host(&zero, 1, ctr_.data());
    if (cavities_) {  // (the store at the size the cavities' threads take: one_by_one.inl)
      // (8 slots a point in the parts' ranges, a quarter in the split parts' room, and 1024 for
      // each part and split part of the sample's stage and the rest's)
      const std::int64_t parts = mesh::cavities::kLockingPartsPerThread +
                                 mesh::cavities::kSplitsPerThread;  // (a thread's, a stage)
      std::int64_t threads = 1;
      if constexpr (Exec::backend == Backend::Cpu) threads = ex.team_size();
      grow(std::min(m64 * 17 / 2 + 16384 + 2 * 1024 * parts * threads, kMaxSlots));
      return;
    }
    un_ = ex.template alloc<std::int32_t>(n);
    un2_ = ex.template alloc<std::int32_t>(n);
    // First sizes, from what uniform points use (design notes, "Phase 1's memory"): slots in
    // use reach 7.2-7.33 a point (7.35 held; more on small sets: the constant), lists 2.2 (batches
    // of at most a quarter of the points; 2.4 at 10^6), records of an epoch 1.9 (1.75 held: a new
    // epoch starts early), freed slots waiting 0.5-0.8. Each grows where a round needs more
    // (settle halts the round, make_room grows).
    grow(std::min(m64 * 147 / 20 + 4096, kMaxSlots));
    grow_lists(std::max<std::int64_t>(m64 * 9 / 4, 1024));
    grow_ring(std::max<std::int64_t>(m64 * 3 / 4, 1024));
    grow_log(std::max<std::int64_t>(m64 * 7 / 4, 1 << 16));
  }

  void run() {
    if (cavities_) {
      insert_by_cavities(ex_);
      ex_.sync();
      release_phase1();
      return;
    }
    start();
    insert_all();
  }
  // The CPU executor's own schedule (one_by_one.inl) where no knob asks for the batches.
  static bool cavities_for(Exec& ex) {
    const detail::Tuning::Del3d& knobs = ex.tuning().del3d;
    return Exec::backend == Backend::Cpu && !knobs.batches && knobs.max_flip_rounds < 0;
  }
  // one_by_one.inl: the points one by one by their cavities, the threads over chunks of the
  // curve (CPU only).
  template <class E>
  void insert_by_cavities(E& ex);
  std::int64_t cavity_insertions_ = 0, deferred_ = 0;
  // The batches, until every located point is inserted; then phase 1's arrays go.
  void insert_all() {
    remaining_ = nun_;
    while (remaining_ > 0) batch();
    ex_.sync();
    release_phase1();
  }

  // start.inl: the first tetrahedron, or a kept tetrahedralisation (DynamicDelaunay3d), with
  // every other point located in it.
  void start();
  void first_five(Tet* t) const;
  static constexpr std::int32_t kKeptInfinity = -2;  // (start_from's infinity point)
  void start_from(const Tet* kept, std::int64_t used, const std::int32_t* inv,
                  const std::int32_t* near);
  void flip_start();
  void check_errors();

  // batch.inl: one batch (choose, split, flip), and the points following their tetrahedra.
  void batch();
  void relocate(bool choose);

  // rounds.inl: the flip rounds' schedule. Rounds run in chunks with no wait in between:
  // every kernel reads its list length on the executor, and a round that could outgrow the
  // store or the flip log halts itself and the rest of the chunk, for the host to make room;
  // the host reads the counters once per chunk. Once the list is short (the long tail of each
  // batch), one team runs the rounds in a single launch with barriers between the steps.
  static constexpr int kChunk = 4;
  static constexpr std::int64_t kMaxRounds = 1000000;  // per batch (a guard: tens are usual)
  // When a batch's rounds hand their list to the next batch (FlipRound::begin): constants, the
  // same on both executors, so that the run is. Measured on the H100 (performance.md,
  // 2026-11-28, the carried lists): after 4 rounds at 2 048 entries or fewer, grid 100³ took
  // 533 rounds instead of 4 955; after 16, or at 256 entries, it ran 1 000 and 900.
  static constexpr std::int32_t kCarryAfter = 4;
  static constexpr std::int64_t kCarryList = 2048;
  void flip_until_stuck();
  FlipRound make_round(std::int32_t round);
  void launch_round(std::int32_t round, std::int64_t bound);
  void team_rounds(std::int32_t round, std::int64_t max, std::int64_t limit);
  template <class Team>
  static GG_HD void team_tally(const Team& t, const FlipRound& R, std::int64_t n);
  void make_room(const Counters& c);

  // finish.inl: the faces phase 1 left, the finite tetrahedra, the statistics.
  std::int64_t find_failed(typename Exec::template Buffer<std::int8_t>& failed, std::int64_t& flat,
                           const std::int8_t* only = nullptr);
  using Finished = mesh::Compacted<Exec>;  // finite tetrahedra in input indices, on the executor
  template <class Into = mesh::OwnArrays>  // (where the arrays go: mesh/compact.hpp)
  Finished finish(const std::int32_t* orig, Into into = {});
  void report();

  // state (the store's is TetStore's)
  Delaunay3dStats& st_;
  std::int64_t max_rounds_ = -1;
  const ProgressFn& progress_;
  Geo g_;
  mesh::Tetra first_;
  std::int64_t nun_ = 0, nact_ = 0, used_ = 0;  // points not yet inserted; list; slots
  std::int32_t round_ = 0;
  std::int32_t carry_from_ = INT32_MAX;  // (FlipRound::carry_from for the batch's rounds)
  std::int64_t batches_ = 0, max_nins_ = 0;
  std::int64_t logged_ = 0;  // records of the epoch
  std::int64_t remaining_ = 0, dead_ = 0, epoch_splits_ = 0;
  std::int32_t epoch_first_new_ = 0;
  double ms_choose_ = 0;
  mesh::ScheduleCounts sched_;  // (how the flip rounds ran: rounds.inl)
  LeasePool<Exec> pool_;
};
