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
//
// The parts: the store (store.inl), this class with the start (start.inl), the batches and the
// points' relocation (batch.inl), the flip round's steps (flip_round.inl) and their schedule
// (rounds.inl), the flat triangles' peel, the
// output and the statistics (finish.inl); the pipeline around it is triangulate.inl.

constexpr std::int64_t kMaxRounds = 1000000;  // per batch; every round flips at least once
// Lists this short run this many rounds between two reads of the counters.
constexpr std::int64_t kChunkList = 65536;
constexpr int kChunkRounds = 4;

// (Every member is public: nvcc's extended lambdas may not live in private members.)
class Triangulator : public TriStore {
 public:
  Triangulator(Exec& ex, Prepared& P, Delaunay2dStats& st, bool profile)
      : TriStore(ex, P), st_(st), profile_(profile) {
    g_.p = P.pts.data();
    g_.s[0] = P.kernel[0];
    g_.s[1] = P.kernel[1];
    g_.m = m_;
  }

  // peel_flats false leaves the flat triangles on the hull (the Delaunay triangulation of the
  // perturbed points, which a later start needs: DynamicDelaunay2d drops them from its output).
  void run(bool peel_flats = true) {
    auto t0 = clock::now();
    if (!insert_one_by_one(ex_)) {
      start();
      remaining_ = nun_;
      while (remaining_ > 0) batch();
    }
    phase("insert", t0);
    if (!peel_flats) return;
    t0 = clock::now();
    peel();
    phase("peel", t0);
  }

  // start.inl: the first triangle, or a given triangulation, with every other point located.
  void write_first();
  void start();
  void run_from(const std::int32_t* tris, const std::int32_t* twin, std::int64_t f,
                const std::int32_t* near, bool peel_flats = true, bool start_delaunay = false);
  void start_from(const std::int32_t* tris, const std::int32_t* twin, std::int64_t f,
                  const std::int32_t* near, bool start_delaunay);
  void check_lost();

  // one_by_one.inl: the CPU executor's own schedule, the points one by one by their cavities
  // (false where the batches run instead: CUDA, or the batches' knobs set).
  template <class E>
  bool insert_one_by_one(E& ex);

  // batch.inl: one batch (choose, split, flip), and the points following their triangles.
  void batch();
  void relocate(bool choose);
  // The work list that the next round does not read (free between rounds and batches).
  std::int32_t* spare_list() { return work_lists().current(round_); }

  // rounds.inl: rounds of flips until Delaunay.
  // f(i) for every i < *count (on the executor), *count <= bound. (The executor's counted
  // grid covers the bound in whole waves; an earlier one-wave cap left a partial second wave at
  // these kernels' occupancy: fix and flip kernels 20-60% slower.)
  template <class F>
  void listed(const std::int64_t* count, std::int64_t bound, F f) {
    ex_.for_each_counted(count, bound, f);
  }
  void flip_until_delaunay(bool first_round);
  bool needs_check() const;
  FlipRound make_round(int edges = 3);
  std::int64_t team_list();
  void team_rounds(bool first_round, std::int64_t max, std::int64_t limit);
  void flip_round(std::int64_t bound, bool first_round, bool checked);
  void count_proposals(std::int64_t bound);
  std::vector<std::int64_t> check_round(std::int64_t bound, int edges);
  void vote_and_flip(std::int64_t bound, std::int64_t lo_in, std::int64_t hi_in, bool first_part);
  template <class E>
  bool flips_in_order(E& ex, const FlipRound& R, std::int32_t lo, std::int32_t hi, bool first_part);
  void exact_pass(std::int64_t bound, int edges, const std::int64_t* listed, bool first);

  // finish.inl: the flat triangles peeled, the finite triangles in input indices (left on the
  // executor), the statistics.
  void peel();
  using Finished = mesh::Compacted<Exec>;
  template <class Into = mesh::OwnArrays>
  Finished finish(Into into = {});
  using clock = std::chrono::steady_clock;
  void phase(const char* name, clock::time_point t0) {
    ex_.sync();
    st_.phase_ms.push_back({name, ms_since(t0)});
  }
  void mark(const char* step);
  void report();

  // state (the store's is TriStore's)
  Delaunay2dStats& st_;
  bool profile_ = false;
  Geo g_;
  std::int64_t ntri_ = 0, nun_ = 0, nact_ = 0;  // slots in use; points not yet inserted; list
  std::int32_t round_ = 0;
  std::int64_t batches_ = 0, flips_ = 0;
  std::int64_t logged_ = 0;                                   // records of the epoch
  std::int64_t remaining_ = 0, dead_ = 0, epoch_splits_ = 0;  // points; list entries; splits
  std::int64_t exact_rest_passes_ = 0, relocations_ = 0, split_rounds_ = 0;
  std::int64_t cavity_insertions_ = 0, deferred_ = 0;  // (one_by_one.inl)
  mesh::ScheduleCounts sched_;                         // (how the flip rounds ran: rounds.inl)
  std::int32_t epoch_first_new_ = 0;
  std::map<std::string, double> prof_;
  clock::time_point last_ = clock::now();
};
