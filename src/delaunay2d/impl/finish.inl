// The end of the 2D Triangulator (triangulator.inl): the flat hull triangles peeled, the finite
// triangles in input indices, the statistics.

GG_HD inline bool has_infinity(const Tri& T, std::int32_t m) {
  return T.v[0] == m || T.v[1] == m || T.v[2] == m;
}
// b strictly between a and c, all three on one line (lexicographic order of coordinates).
GG_HD inline bool strictly_between(const double* a, const double* b, const double* c) {
  auto less = [](const double* u, const double* v) {
    return u[0] < v[0] || (u[0] == v[0] && u[1] < v[1]);
  };
  return (less(a, b) && less(b, c)) || (less(c, b) && less(b, a));
}

// The store as the output step reads it: finite triangles in input indices, neighbours among
// them.
struct FiniteTriangles {
  const Tri* tri;  // from slot base: position t is slot base + t
  const std::int32_t* orig;
  std::int32_t m;  // the infinity point
  std::int32_t base;
  GG_HD bool live(std::int64_t t) const {
    const std::int32_t* v = tri[t].v;
    return v[0] != m && v[1] != m && v[2] != m;
  }
  GG_HD void prefetch(std::int64_t t) const { prefetch_on_host(tri + t); }
  GG_HD void order_names(std::int64_t t, std::int32_t* w) const {  // (curve positions)
    for (int k = 0; k < 3; ++k) w[k] = tri[t].v[k];
  }
  GG_HD mesh::SimplexRecord<3> get(std::int64_t t) const {
    const Tri T = tri[t];
    mesh::SimplexRecord<3> r;
    for (int k = 0; k < 3; ++k) r.v[k] = orig[T.v[k]], r.n[k] = simplex_of(T.n[k]) - base;
    return r;
  }
};

// Flat triangles: collinear vertices the perturbation ordered counter-clockwise. They can
// only lie on the hull; each is flipped with the infinite triangle across its long edge,
// which makes its middle vertex a hull vertex, until none is left next to the outside.
inline void Triangulator::peel() {
  const std::int32_t m = m_;
  const Geo g = g_;
  const Tri* tri = this->tri();
  const std::int32_t B = std::int32_t(base_);
  // Flat triangles come in runs along a hull line, and each run has one next to the outside
  // (the hull edge over the run lies on that line too): first look only there, reading the
  // points of the few triangles on the hull rather than those of every triangle.
  auto flat = GG_LAMBDA(const Tri& T)->bool {
    const std::int32_t a = T.v[0], b = T.v[1], c = T.v[2];
    if (a == m || b == m || c == m) return false;
    if (pred::orient2d_fast(g.at(a), g.at(b), g.at(c)) != 0) return false;
    double s[kOrient2dScratch];
    return pred::orient2d_exact(g.at(a), g.at(b), g.at(c), s) == 0;
  };
  const std::int64_t on_hull = ex_.compact_indices(
      tmax_,
      GG_LAMBDA(std::int64_t t) {
        const Tri T = tri[B + t];
        const int gi = T.v[0] == m ? 0 : T.v[1] == m ? 1 : T.v[2] == m ? 2 : -1;
        return gi >= 0 && flat(tri[simplex_of(T.n[gi])]);
      },
      lists_[0].data());
  const std::int64_t nflat =
      on_hull == 0
          ? 0
          : ex_.compact_indices(
                tmax_, GG_LAMBDA(std::int64_t t) { return flat(tri[B + t]); }, lists_[0].data());
  st_.flat_triangles = nflat;
  if (nflat == 0) return;
  ready_rounds();  // (flipped as the rounds flip)
  if (B != 0) {    // positions to slots
    std::int32_t* l0 = lists_[0].data();
    ex_.for_each_index(
        nflat, GG_LAMBDA(std::int64_t i) { l0[i] += B; });
  }
  const Mesh M = M_;
  const std::int32_t* act = lists_[0].data();  // (the rounds are over: any list will do)
  std::int8_t* dec = dec_.data();
  Counters* ctr = ctr_.data();
  ex_.for_each_index(
      1, GG_LAMBDA(std::int64_t) { ctr->peel_list = nflat; });
  for (;;) {
    ++round_;
    const std::int32_t round = round_;
    ex_.for_each_index(
        1, GG_LAMBDA(std::int64_t) { ctr->flips = 0; });
    ex_.for_each_index(
        nflat, GG_LAMBDA(std::int64_t i) {
          const std::int32_t t = act[i];
          const Tri T = M.tri[t];
          dec[i] = -1;
          if (has_infinity(T, m)) return;
          for (int k = 0; k < 3; ++k) {
            const std::int32_t nb = simplex_of(T.n[k]);
            if (has_infinity(M.tri[nb], m) &&
                strictly_between(g.at(T.v[(k + 1) % 3]), g.at(T.v[k]), g.at(T.v[(k + 2) % 3]))) {
              dec[i] = std::int8_t(k);
              propose(M, round, t, nb);
              return;
            }
          }
        });
    ex_.for_each_index(
        nflat, GG_LAMBDA(std::int64_t i) {
          const int k = dec[i];
          if (k < 0) return;
          const std::int32_t t = act[i];
          const u64 key = key_of(M, round, t);
          if (M.vote[t] != key) return;
          if (M.vote[simplex_of(M.tri[t].n[k])] == key) {
            flip_phase1(M, t, k, round, -1);  // no point is left to follow it
            atomic_add(&ctr->flips, std::int64_t(1));
          }
        });
    FlipRound F = make_round();  // (its fix over the peel's list)
    F.act = act;
    F.len = &ctr->peel_list;
    listed(
        F.len, nflat, GG_LAMBDA(std::int64_t i) { F.fix(i); });
    const Counters c = counters();
    flips_ += c.flips;
    if (c.flips == 0) break;
  }
}

// The finite triangles in the curve order of their vertices (mesh/compact.hpp): the slots'
// order follows the schedule, and the output must not (the CPU executor's schedule is not the
// GPU's, and both give the same arrays).
template <class Into>
Triangulator::Finished Triangulator::finish(Into into) {
  // (the extended triangulation has 2m - 2 slots, all in use)
  return mesh::compact_live_sorted<3>(
      ex_, tmax_, FiniteTriangles{tri_.data(), P_.orig.data(), m_, std::int32_t(base_)}, m_, into);
}

inline void Triangulator::report() {
  const Counters c = counters();
  for (auto& p : prof_) st_.phase_ms.push_back({"insert/" + p.first, p.second});
  st_.batches = batches_;
  st_.cavity_insertions = cavity_insertions_;
  st_.deferred_points = deferred_;
  st_.flip_rounds = c.rounds;
  st_.flips = flips_;
  st_.exact_predicates = c.exact_total;  // work-list entries the filter left open
  st_.work_list_entries = c.listed;
  st_.small_flip_rounds = c.small_rounds;
  st_.team_flip_rounds = sched_.team_rounds;
  st_.exact_rest_passes = exact_rest_passes_;  // past the exact list's capacity
  st_.log_relocations = relocations_;          // within a batch, for a full log
  st_.split_flip_rounds = split_rounds_;       // flip parts past the first
}

// RunOptions::profile: each step is synchronised and timed (slower; for finding where the time
// goes), reported as phases "insert/<step>".
inline void Triangulator::mark(const char* step) {
  if (!profile_) return;
  ex_.sync();
  const auto now = clock::now();
  prof_[step] += ms_between(last_, now);
  last_ = now;
}
