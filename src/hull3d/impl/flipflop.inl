// Phase 2 (thesis Alg. 5.4, Flip-Flop): flips the star-shaped polyhedron into the convex hull.
// Included inside gpugeom::hull3d::{cpu,cuda}_impl after construct.inl.
//
// Each round, every facet on the work list decides for the edges it owns (those shared with a
// higher slot) what Alg. 5.4 does: a 3-1 flip when a degree-3 endpoint can be removed (the
// edge is reflex, or the vertex is labelled non-extreme); a label on the non-extreme endpoint
// when the edge is reflex but cannot be flipped (Lemma 5.1); a 2-2 flip when the edge is
// flippable and either reflex with no labelled vertex involved, or it lowers the degree of the
// smallest labelled vertex involved. Labels take effect the next round, so every decision of a
// round reads the same state. A facet proposes its first flip; a flip claims its two or three
// facets and goes ahead when its key is the highest on each of them (keys: the round, then a
// fixed scramble of the slot), so results never depend on timing. Neighbour pointers are fixed
// in a second phase as in delaunay2d. Changed facets and their neighbours, outvoted proposers
// and the facets around newly labelled vertices form the next list.
//
// The geometry is in edge_action and the topology in surface.inl; the loop itself only moves
// lists, so a polyhedron one dimension higher needs those two parts replaced, not this one.

constexpr std::int64_t kMaxFlipRounds = 4000000;

GG_INLINE std::uint32_t scramble(std::uint32_t x) {  // a bijection: distinct slots, distinct keys
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

// One facet's decisions for the edges it owns, and the vote of its proposal (the first flip it
// found) on the two or three facets that flip would change; false when the filter could not
// tell (nothing is written then but labels, which the exact stage finds again).
struct Decide {
  Surface Sf;
  const std::int8_t* ne;
  std::int32_t* labround;
  std::int32_t* newlab;
  std::int32_t* prop;
  std::int32_t* clm;
  u64* vote;
  Counters* ctr;
  std::int32_t s, round;
  template <class O>
  GG_HD bool operator()(std::int32_t f, const O& o) const {
    prop[f] = -1;
    if (Sf.tv[3 * f] < 0) return true;
    std::int32_t pr = -1;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t e = Sf.to[3 * f + k], g = facet_of(e);
      if (g < f) continue;
      const std::int32_t c = Sf.tv[3 * f + k], a = Sf.tv[3 * f + (k + 1) % 3],
                         b = Sf.tv[3 * f + (k + 2) % 3], d = Sf.tv[3 * g + loc_of(e)];
      const int act = edge_action(o, s, a, b, c, d, Sf.deg[a], Sf.deg[b], ne);
      if (act == kUndecided) return false;
      if (act == kLabelA || act == kLabelB) {
        const std::int32_t x = act == kLabelA ? a : b;
        if (!ne[x] && atomic_exchange(labround + x, round) != round)
          newlab[append_slot(&ctr->labels)] = x;
      } else if (act != kNone && pr < 0) {
        pr = (act << 2) | k;
      }
    }
    prop[f] = pr;
    if (pr < 0) return true;
    // The vote (the topology is not changed before every facet has voted).
    const int k = pr & 3, kind = pr >> 2;
    std::int32_t* c = clm + 3 * std::int64_t(f);
    if (kind == kFlip22) {
      c[0] = f, c[1] = facet_of(Sf.to[3 * f + k]), c[2] = -1;
    } else {
      int L[3];
      fan3(Sf, f, kind == kRemoveA ? (k + 1) % 3 : (k + 2) % 3, c, L);
    }
    const u64 key = vote_key(f);
    for (int j = 0; j < 3; ++j)
      if (c[j] >= 0) atomic_max(vote + c[j], key);
    return true;
  }
  GG_HD u64 vote_key(std::int32_t f) const {
    return (u64(std::uint32_t(round)) << 32) | scramble(std::uint32_t(f));
  }
};
// Puts facet x on the next round's list once.
struct Enlist {
  std::int32_t* mark;
  std::int32_t* next;
  std::int64_t* count;
  std::int32_t round;
  GG_HD void operator()(std::int32_t x) const {
    if (atomic_exchange(mark + x, round) != round) next[append_slot(count)] = x;
  }
};

class FlipFlop {
 public:
  explicit FlipFlop(PassState& S) : S_(S) {}

  // Rounds run in chunks with no wait in between: every kernel reads its work-list length on
  // the executor, so a round past the last one does nothing, and the host checks for the end
  // once per chunk.
  static constexpr int kChunk = 4;

  void run() {
    Exec& ex = S_.ex;
    const std::int64_t used = S_.used;
    act_ = ex.template alloc<std::int32_t>(std::size_t(used));
    next_ = ex.template alloc<std::int32_t>(std::size_t(used));
    prop_ = ex.template alloc<std::int32_t>(std::size_t(used));
    clm_ = ex.template alloc<std::int32_t>(std::size_t(3 * used));
    vote_ = ex.template alloc<u64>(std::size_t(used));
    mark_ = ex.template alloc<std::int32_t>(std::size_t(used));
    ne_ = ex.template alloc<std::int8_t>(std::size_t(S_.n));
    labround_ = ex.template alloc<std::int32_t>(std::size_t(S_.n));
    newlab_ = ex.template alloc<std::int32_t>(std::size_t(S_.n));
    ex.fill(vote_.data(), used, u64(0));
    ex.fill(mark_.data(), used, std::int32_t(-1));
    ex.fill(ne_.data(), S_.n, std::int8_t(0));
    ex.fill(labround_.data(), S_.n, std::int32_t(-1));
    std::int32_t* act = act_.data();
    ex.for_each_index(
        used, GG_LAMBDA(std::int64_t f) { act[f] = std::int32_t(f); });
    Counters* ctr = S_.ctr.data();
    ex.for_each_index(
        1, GG_LAMBDA(std::int64_t) {
          ctr->len[0] = used;
          ctr->len[1] = 0;
        });
    S_.exact_list(used);
    std::int32_t round = 0;
    for (;;) {
      for (int k = 0; k < kChunk; ++k) step(round++);
      std::int64_t len[2];
      ex.to_host(ctr->len, 2, len);
      if (len[round & 1] == 0) break;
      if (round >= kMaxFlipRounds)
        throw Error(ErrorCode::Internal, "convex hull: Flip-Flop did not finish");
    }
    const Counters c = S_.counters();
    S_.st.counters["flip_rounds"] += c.flip_rounds;
    S_.st.counters["flips22"] += c.flips22;
    S_.st.counters["flips31"] += c.flips31;
    S_.st.counters["labelled_nonextreme"] += c.labels_all;
  }

  void step(std::int32_t round) {
    Exec& ex = S_.ex;
    const Geo geo = S_.g;
    const std::int32_t s = geo.n;
    const Surface Sf = S_.surface();
    const std::int32_t* act = act_.data();
    std::int32_t* prop = prop_.data();
    std::int32_t* clm = clm_.data();
    u64* vote = vote_.data();
    std::int32_t* mark = mark_.data();
    std::int32_t* next = next_.data();
    std::int8_t* ne = ne_.data();
    std::int32_t* labround = labround_.data();
    std::int32_t* newlab = newlab_.data();
    Counters* ctr = S_.ctr.data();
    const std::int64_t used = S_.used;
    const std::int64_t* nact = &ctr->len[round & 1];
    std::int32_t* exl = S_.exact_list(used);

    // 1. Decide and vote (filter; undecided facets go to the exact stage whole).
    const Decide decide{Sf, ne, labround, newlab, prop, clm, vote, ctr, s, round};
    ex.for_each_counted(
        nact, used, GG_LAMBDA(std::int64_t i) {
          const std::int32_t f = act[i];
          if (!decide(f, FastOrient{geo})) exl[append_slot(&ctr->exact)] = f;
        });
    S_.exact_pass(decide);
    // 2. Flip the winners (phase 1); outvoted proposers try again next round.
    const Enlist enlist{mark, next, &ctr->len[(round + 1) & 1], round + 1};
    ex.for_each_counted(
        nact, used, GG_LAMBDA(std::int64_t i) {
          const std::int32_t f = act[i], pr = prop[f];
          if (pr < 0) return;
          const u64 key = decide.vote_key(f);
          const std::int32_t* c = clm + 3 * std::int64_t(f);
          bool won = true;
          for (int j = 0; j < 3; ++j) won = won && (c[j] < 0 || vote[c[j]] == key);
          if (!won) {
            prop[f] = -1;
            enlist(f);
            return;
          }
          const int k = pr & 3, kind = pr >> 2;
          if (kind == kFlip22) {
            flip22(Sf, f, k, round);
            atomic_add(&ctr->flips22, std::int64_t(1));
          } else {
            remove3(Sf, f, kind == kRemoveA ? (k + 1) % 3 : (k + 2) % 3, round);
            atomic_add(&ctr->flips31, std::int64_t(1));
          }
        });
    // 3. Phase 2: outer neighbour pointers; the changed facets and their neighbours go next.
    ex.for_each_counted(
        nact, used, GG_LAMBDA(std::int64_t i) {
          const std::int32_t f = act[i], pr = prop[f];
          if (pr < 0) return;
          const int kind = pr >> 2;
          const std::int32_t* c = clm + 3 * std::int64_t(f);
          if (kind == kFlip22) {
            for (int side = 0; side < 2; ++side) {
              const std::int32_t x = c[side];
              enlist(x);
              enlist(fix_edge(Sf, x, 0, round));
              enlist(fix_edge(Sf, x, 2, round));
              enlist(facet_of(Sf.to[3 * x + 1]));
            }
          } else {
            enlist(f);
            for (int l = 0; l < 3; ++l) enlist(fix_edge(Sf, f, l, round));
          }
        });
    // 4. Labels take effect; the facets around each new label (and their neighbours) go next.
    // On rounds that label nothing every thread leaves at once.
    const std::int64_t T = std::max<std::int64_t>(1, std::min(used, ex.concurrency()));
    ex.for_each_index(
        T, GG_LAMBDA(std::int64_t t) {
          const std::int64_t nl = ctr->labels;
          if (nl == 0) return;
          for (std::int64_t i = t; i < nl; i += T) ne[newlab[i]] = 1;
          for (std::int64_t fi = t; fi < used; fi += T) {
            const std::int32_t f = std::int32_t(fi);
            if (Sf.tv[3 * f] < 0) continue;
            bool hit = false;
            for (int k = 0; k < 3; ++k) hit = hit || labround[Sf.tv[3 * f + k]] == round;
            if (!hit) continue;
            enlist(f);
            for (int k = 0; k < 3; ++k) enlist(facet_of(Sf.to[3 * f + k]));
          }
        });
    S_.reset_counters(round & 1);
    std::swap(act_, next_);
  }

  PassState& S_;
  typename Exec::template Buffer<std::int32_t> act_, next_, prop_, clm_, mark_, labround_, newlab_;
  typename Exec::template Buffer<u64> vote_;
  typename Exec::template Buffer<std::int8_t> ne_;
};
