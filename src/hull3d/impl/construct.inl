// Phase 1 (thesis Alg. 5.3): a star-shaped polyhedron whose vertices are input points and
// which holds every input point. Included inside gpugeom::hull3d::{cpu,cuda}_impl after
// surface.inl.
//
// Every point outside the current polyhedron belongs to the facet whose cone from s holds it.
// Each round, every facet with points takes the farthest one above it and splits around it;
// the other points of a split facet move to the child whose cone holds them, and a point that
// falls inside its child is dropped for good (it is inside the polyhedron, hence not extreme).
// Splitting inside a facet's cone keeps the polyhedron star-shaped from s.

// Exact-stage threads of the split passes, each with a kScratch slice (3.9 kB).
constexpr std::int64_t kExactSlots = 16384;

// Counters on the executor. The per-round fields are added into the totals when a kernel resets
// them, so the host reads them only when it must (a round's sizes) or once at the end.
struct Counters {
  std::int64_t exact;   // items the filter left to the exact stage of the current pass
  std::int64_t labels;  // vertices labelled non-extreme this flip round
  std::int64_t len[2];  // flip work-list lengths, by round parity
  std::int64_t round;   // the flip round a team stopped at (read with len in one copy), or
                        // the insertion rounds a team ran (read with split and live)
  std::int64_t split;   // facets split this insertion round
  std::int64_t live;    // points still outside after this insertion round (next to split)
  std::int64_t exact_all, flips22, flips31, labels_all, flip_rounds;  // totals
};

// Buffers of one hull computation, shared by the two phases. (Every member is public: nvcc's
// extended lambdas may not live in private members.)
struct PassState {
  Exec& ex;
  Geo g;
  std::int64_t n = 0;                                   // points
  std::int64_t cap = 0;                                 // facet slots
  std::int64_t used = 0;                                // slots handed out
  typename Exec::template Buffer<double> kernel_point;  // Geo::s
  typename Exec::template Buffer<std::int32_t> tv, to, stamp, remap, deg;
  typename Exec::template Buffer<Counters> ctr;
  ScratchSlots<Exec> slots;  // of the exact stages (passes, and teams: one per thread)
  typename Exec::template Buffer<std::int32_t> exl;  // exact-stage work list
  std::int64_t exl_cap = 0;
  Hull3dStats& st;

  PassState(Exec& e, const double* pts, std::int64_t np, const double* s, Hull3dStats& stats)
      : ex(e), n(np), st(stats) {
    kernel_point = ex.template alloc<double>(3);
    ex.from_host(s, 3, kernel_point.data());
    g.p = pts;
    g.s = kernel_point.data();
    g.n = std::int32_t(np);
    // A closed triangulated sphere on V <= n vertices has 2V - 4 facets, but V is mostly far
    // below n: the store starts smaller and grows (reserve) as the rounds need.
    cap = first_facet_slots(np, ex.tuning().hull3d.first_facet_slots);
    tv = ex.template alloc<std::int32_t>(std::size_t(3 * cap));
    to = ex.template alloc<std::int32_t>(std::size_t(3 * cap));
    stamp = ex.template alloc<std::int32_t>(std::size_t(cap));
    remap = ex.template alloc<std::int32_t>(std::size_t(3 * cap));
    deg = ex.template alloc<std::int32_t>(std::size_t(np));
    ctr = ex.template alloc<Counters>(1);
    slots = ScratchSlots<Exec>(ex, kExactSlots, kScratch);
    ex.fill(deg.data(), np, std::int32_t(0));
    ex.fill(stamp.data(), cap, std::int32_t(-1));
    Counters z{};
    ex.from_host(&z, 1, ctr.data());
  }
  Surface surface() {
    return Surface{tv.data(), to.data(), stamp.data(), remap.data(), deg.data()};
  }
  // Room for `need` facet slots: the store grows to at least twice its size (at most 2n, the
  // most a hull of n points has, and kMaxFacetSlots), keeping slots [0, used). Surfaces taken
  // before a call are stale after it.
  void reserve(std::int64_t need) {
    if (need <= cap) return;
    if (need > kMaxFacetSlots)
      throw Error(ErrorCode::InvalidInput,
                  "convex hull: more than " + std::to_string(kMaxFacetSlots / 2) +
                      " extreme points (the facets' int32 encoding holds 2^29 slots)");
    const std::int64_t grown = std::min({std::max(need, 2 * cap), 2 * n, kMaxFacetSlots});
    auto grow = [&](auto& buf, std::int64_t per, std::int64_t keep, bool fill_rest) {
      using T = std::remove_reference_t<decltype(*buf.data())>;
      auto nb = ex.template alloc<T>(std::size_t(per * grown));
      ex.copy(buf.data(), per * keep, nb.data());
      if (fill_rest) ex.fill(nb.data() + per * keep, per * (grown - keep), T(-1));
      buf = std::move(nb);
    };
    grow(tv, 3, used, false);
    grow(to, 3, used, false);
    grow(stamp, 1, used, true);
    grow(remap, 3, used, false);
    cap = grown;
    st.facet_store_grown += 1;
  }
  // Zeroes the per-round counters of an insertion round on the executor (no host round trip),
  // adding them into the totals.
  void reset_counters() {
    Counters* c = ctr.data();
    ex.for_each_index(
        1, GG_LAMBDA(std::int64_t) {
          c->exact_all += c->exact;
          c->exact = 0;
        });
  }
  Counters counters() {
    Counters c;
    ex.to_host(ctr.data(), 1, &c);
    return c;
  }
  // A work list for the exact stage of at least `items` entries.
  std::int32_t* exact_list(std::int64_t items) {
    if (items > exl_cap) {
      exl_cap = std::max<std::int64_t>(items, 1024);
      exl = ex.template alloc<std::int32_t>(std::size_t(exl_cap));
    }
    return exl.data();
  }
  // Runs f(item, ExactOrient) for the items the filter queued this round (their count is read
  // on the executor, so no copy to the host is needed to launch).
  template <class F>
  void exact_pass(F f) {
    slots.run_counted(ex, exl_cap, CountAt{&ctr.data()->exact}, ExactItem<F>{exl.data(), g, f});
  }
  template <class F>
  struct ExactItem {
    const std::int32_t* list;
    Geo g;
    F f;
    GG_HD void operator()(std::int64_t j, double* s) const { f(list[j], ExactOrient{g, s}); }
  };
};

// Where a point of split facet f (split rank r, new slots from base) goes, given its child c
// from locate_child: -1 when it dropped inside the polyhedron.
GG_INLINE std::int32_t child_slot(int c, std::int32_t f, std::int32_t r, std::int32_t base) {
  return c < 0 ? -1 : c == 0 ? f : base + 2 * r + (c - 1);
}
// Point q of split facet f (split rank r) after the splits: inserted (loc -1), moved to a child
// or dropped; false when o cannot tell (loc is left as it was).
template <class O>
GG_HD bool place_point(const O& o, std::int32_t s, std::int32_t* loc, const std::int32_t* spl,
                       std::int32_t q, std::int32_t f, std::int32_t r, std::int32_t base) {
  const std::int32_t* x = spl + 4 * r;
  if (x[0] == q) {  // inserted
    loc[q] = -1;
    return true;
  }
  const int c = locate_child(o, s, x[0], x + 1, q);
  if (c == kUndecided) return false;
  loc[q] = child_slot(c, f, r, base);
  return true;
}
// Splits the r-th facet of the round's list at its farthest point, recording (point, old
// corners) in spl for the point location after it.
GG_HD inline void split_listed(const Surface& Sf, std::int64_t r, const std::int32_t* list,
                               const u64* best, const std::int32_t* rank, std::int32_t* spl,
                               std::int32_t base) {
  const std::int32_t f = list[r];
  const std::int32_t p = point_of_key(best[f]);
  spl[4 * r] = p;
  for (int k = 0; k < 3; ++k) spl[4 * r + 1 + k] = Sf.tv[3 * f + k];
  split_facet(Sf, f, p, base + 2 * std::int32_t(r), rank, base);
}

// The exact stage of the two point-location kernels below (namespace-scope functors: nvcc
// allows no lambda type as a template argument of a function that defines device lambdas).
struct LocateFirstExact {
  const std::int32_t* F;
  std::int32_t* loc;
  std::int32_t s;
  GG_HD void operator()(std::int32_t q, const ExactOrient& o) const {
    const int r = locate_first(o, s, F, q);
    loc[q] = r == kLost ? -1 : r;  // (kLost cannot happen with exact signs)
  }
};
struct LocateChildExact {
  std::int32_t* loc;
  const std::int32_t* rank;
  const std::int32_t* spl;
  std::int32_t s, base;
  GG_HD void operator()(std::int32_t q, const ExactOrient& o) const {
    const std::int32_t f = ~loc[q];
    place_point(o, s, loc, spl, q, f, rank[f], base);
  }
};

using mesh::team_compact;

class Constructor {
 public:
  Constructor(PassState& S, const Tetra& t) : S_(S), t_(t) {}

  // Late rounds, once few points are left, run in one team (see team_rounds).
  static constexpr std::int64_t kTeamLive = 4;   // points per team thread
  static constexpr std::int64_t kTeamUsed = 64;  // facet slots per team thread

  void run() {
    start();
    std::int64_t rounds = 0;
    const std::int64_t T = S_.ex.team_size();
    const bool team_ok = S_.slots.slots() >= T;
    while (live_n_ > 0) {
      if (team_ok && live_n_ <= kTeamLive * T && S_.used <= kTeamUsed * T) {
        rounds += team_rounds(kTeamLive * T, kTeamUsed * T);
      } else {
        round();
        ++rounds;
      }
    }
    S_.st.insert_rounds += rounds;
  }

  void start() {
    Exec& ex = S_.ex;
    const std::int64_t n = S_.n;
    const std::int32_t a = t_.v[0], b = t_.v[1], c = t_.v[2], d = t_.v[3];
    std::int32_t fv[12], fo[12];
    first_facets(t_, fv, fo);
    ex.from_host(fv, 12, S_.tv.data());
    ex.from_host(fo, 12, S_.to.data());
    std::int32_t* deg = S_.deg.data();
    ex.for_each_index(
        4, GG_LAMBDA(std::int64_t k) {
          deg[k == 0 ? a : k == 1 ? b : k == 2 ? c : d] = 3;
        });
    S_.used = 4;
    cap_ = S_.cap;
    list_cap_ = cap_ / 3 + 4;
    loc_ = ex.template alloc<std::int32_t>(std::size_t(n));
    live_ = ex.template alloc<std::int32_t>(std::size_t(n));
    live2_ = ex.template alloc<std::int32_t>(std::size_t(n));
    best_ = ex.template alloc<u64>(std::size_t(cap_));
    rank_ = ex.template alloc<std::int32_t>(std::size_t(cap_));
    list_ = ex.template alloc<std::int32_t>(std::size_t(list_cap_));
    spl_ = ex.template alloc<std::int32_t>(std::size_t(4 * list_cap_));
    ex.fill(best_.data(), cap_, u64(0));
    ex.fill(rank_.data(), cap_, std::int32_t(-1));
    // Locate every point among the four cones (filter, then the exact stage on the rest).
    auto fvb = ex.template alloc<std::int32_t>(12);
    ex.from_host(fv, 12, fvb.data());
    const std::int32_t* F = fvb.data();
    std::int32_t* loc = loc_.data();
    Counters* ctr = S_.ctr.data();
    std::int32_t* exl = S_.exact_list(n);
    const Geo geo = S_.g;
    const std::int32_t s = geo.n;
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          const std::int32_t q = std::int32_t(i);
          if (q == a || q == b || q == c || q == d) {
            loc[i] = -1;
            return;
          }
          const int r = locate_first(FastOrient{geo}, s, F, q);
          if (r == kUndecided) {
            exl[append_slot(&ctr->exact)] = q;
            return;
          }
          loc[i] = r;
        });
    S_.exact_pass(LocateFirstExact{F, loc, s});
    S_.reset_counters();
    live_n_ = ex.compact_indices(
        n, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, live_.data());
  }

  // Room for a round that may split every facet holding a point: at most min(used, points
  // left) facets split, two new slots each; scratch for that many splits.
  void make_room(std::int64_t used, std::int64_t live) {
    const std::int64_t splits = std::min(used, live);
    if (used + 2 * splits > cap_) {
      S_.reserve(std::min(used + 2 * splits, kMaxFacetSlots));
      cap_ = S_.cap;
      best_ = S_.ex.template alloc<u64>(std::size_t(cap_));  // (all 0 / -1 between rounds)
      rank_ = S_.ex.template alloc<std::int32_t>(std::size_t(cap_));
      S_.ex.fill(best_.data(), cap_, u64(0));
      S_.ex.fill(rank_.data(), cap_, std::int32_t(-1));
    }
    if (splits + 4 > list_cap_) {
      list_cap_ = std::max(splits + 4, 2 * list_cap_);
      list_ = S_.ex.template alloc<std::int32_t>(std::size_t(list_cap_));
      spl_ = S_.ex.template alloc<std::int32_t>(std::size_t(4 * list_cap_));
    }
  }

  void round() {
    make_room(S_.used, live_n_);
    Exec& ex = S_.ex;
    const Geo geo = S_.g;
    const std::int32_t s = geo.n;
    std::int32_t* loc = loc_.data();
    const std::int32_t* live = live_.data();
    u64* best = best_.data();
    std::int32_t* tv = S_.tv.data();
    const std::int64_t nl = live_n_;
    // Each facet's farthest point (grouped: in early rounds nearly every point aims at one of
    // a few facets).
    ex.for_each_index(
        nl, GG_LAMBDA(std::int64_t j) {
          const std::int32_t q = live[j], f = loc[q];
          atomic_max_grouped(best + f,
                             distance_key(geo, tv[3 * f], tv[3 * f + 1], tv[3 * f + 2], q));
        });
    // The facets that split, in slot order; two new slots each. Their count stays on the
    // executor until the end of the round. (No overflow: make_room made room for a split of
    // every facet holding a point.)
    const std::int64_t used = S_.used;
    std::int32_t* list = list_.data();
    Counters* ctr = S_.ctr.data();
    const std::int64_t* m = &ctr->split;
    ex.compact_indices_to(
        used, GG_LAMBDA(std::int64_t f) { return best[f] != 0; }, list, &ctr->split);
    if (used + 2 * std::min(used, nl) > cap_) {  // (only at kMaxFacetSlots: count the splits)
      std::int64_t splits = 0;
      ex.to_host(&ctr->split, 1, &splits);
      if (used + 2 * splits > cap_) S_.reserve(used + 2 * splits);  // (throws: too many)
    }
    std::int32_t* rank = rank_.data();
    std::int32_t* spl = spl_.data();
    const Surface Sf = S_.surface();
    const std::int32_t base = std::int32_t(used);
    ex.for_each_counted(
        m, used, GG_LAMBDA(std::int64_t r) { rank[list[r]] = std::int32_t(r); });
    ex.for_each_counted(
        m, used, GG_LAMBDA(std::int64_t r) { split_listed(Sf, r, list, best, rank, spl, base); });
    // Points of split facets move to a child or drop out.
    std::int32_t* exl = S_.exact_list(nl);
    ex.for_each_index(
        nl, GG_LAMBDA(std::int64_t j) {
          const std::int32_t q = live[j], f = loc[q], r = rank[f];
          if (r >= 0 && !place_point(FastOrient{geo}, s, loc, spl, q, f, r, base)) {
            exl[append_slot(&ctr->exact)] = q;
            loc[q] = ~f;  // decided below
          }
        });
    S_.exact_pass(LocateChildExact{loc, rank, spl, s, base});
    S_.reset_counters();
    ex.for_each_counted(
        m, used, GG_LAMBDA(std::int64_t r) {
          best[list[r]] = 0;
          rank[list[r]] = -1;
        });
    ex.copy_if_to(
        live, nl, live2_.data(), GG_LAMBDA(std::int32_t q) { return loc[q] >= 0; }, &ctr->live);
    std::swap(live_, live2_);
    // The round's one wait: facets split and points left (adjacent fields, one copy).
    std::int64_t sizes[2];
    ex.to_host(&ctr->split, 2, sizes);
    S_.used = used + 2 * sizes[0];
    live_n_ = sizes[1];
    if (S_.used > cap_)
      throw Error(ErrorCode::Internal, "convex hull: facet store overflow while inserting");
  }

  // The rounds of round(), from the current one on, in one team launch while at most max_live
  // points are left and at most max_used slots are handed out: a round is then a few
  // dependent memory accesses per step, not a dozen launches and a host wait. The steps and
  // their order are round()'s, and the two compactions keep index order (a scan over the
  // threads' contiguous ranges), so the surface is the same slot for slot. Returns the rounds
  // run.
  std::int64_t team_rounds(std::int64_t max_live, std::int64_t max_used) {
    // Rounds run while used <= max_used, each adding at most 2 * max_live slots.
    make_room(max_used + max_live, max_live);
    Exec& ex = S_.ex;
    const Geo geo = S_.g;
    const std::int32_t s = geo.n;
    std::int32_t* loc = loc_.data();
    std::int32_t* live_a = live_.data();  // the live list of even rounds (odd: live_b)
    std::int32_t* live_b = live2_.data();
    u64* best = best_.data();
    std::int32_t* list = list_.data();
    std::int32_t* rank = rank_.data();
    std::int32_t* spl = spl_.data();
    const Surface Sf = S_.surface();
    Counters* ctr = S_.ctr.data();
    const SlotView scratch = S_.slots.view();
    const std::int64_t used0 = S_.used, live0 = live_n_;
    ex.team(GG_LAMBDA(const Exec::Team& t) {
      const ExactOrient exact{geo, scratch[t.rank]};
      const std::int64_t T = t.size;
      std::int64_t used = used0, nl = live0, rounds = 0;
      while (nl > 0 && nl <= max_live && used <= max_used) {
        const std::int32_t* live = (rounds & 1) ? live_b : live_a;
        std::int32_t* keep = (rounds & 1) ? live_a : live_b;
        for (std::int64_t j = t.rank; j < nl; j += T) {
          const std::int32_t q = live[j], f = loc[q];
          atomic_max(best + f,
                     distance_key(geo, Sf.tv[3 * f], Sf.tv[3 * f + 1], Sf.tv[3 * f + 2], q));
        }
        t.barrier();
        // The split facets in slot order.
        const std::int64_t m = team_compact(
            t, used, [&](std::int64_t f) { return best[f] != 0; },
            [&](std::int64_t f, std::int64_t at) {
              list[at] = std::int32_t(f);
              rank[f] = std::int32_t(at);
            });
        t.barrier();
        const std::int32_t base = std::int32_t(used);
        for (std::int64_t r = t.rank; r < m; r += T)
          split_listed(Sf, r, list, best, rank, spl, base);
        t.barrier();
        for (std::int64_t j = t.rank; j < nl; j += T) {
          const std::int32_t q = live[j], f = loc[q], r = rank[f];
          if (r >= 0 && !place_point(FastOrient{geo}, s, loc, spl, q, f, r, base)) {
            atomic_add(&ctr->exact_all, std::int64_t(1));
            place_point(exact, s, loc, spl, q, f, r, base);
          }
        }
        t.barrier();
        for (std::int64_t r = t.rank; r < m; r += T) {
          best[list[r]] = 0;
          rank[list[r]] = -1;
        }
        // The points still outside, in order (as copy_if).
        const std::int64_t left = team_compact(
            t, nl, [&](std::int64_t j) { return loc[live[j]] >= 0; },
            [&](std::int64_t j, std::int64_t at) { keep[at] = live[j]; });
        t.barrier();
        used += 2 * m;
        nl = left;
        ++rounds;
      }
      if (t.rank == 0) {
        ctr->round = rounds;
        ctr->split = (used - used0) / 2;
        ctr->live = nl;
      }
    });
    // One read: rounds run, slots handed out, points left (adjacent fields).
    std::int64_t r[3];
    ex.to_host(&ctr->round, 3, r);
    S_.used += 2 * r[1];
    live_n_ = r[2];
    if (r[0] & 1) std::swap(live_, live2_);
    if (S_.used > cap_)
      throw Error(ErrorCode::Internal, "convex hull: facet store overflow while inserting");
    return r[0];
  }

  PassState& S_;
  Tetra t_;
  std::int64_t cap_ = 0, live_n_ = 0, list_cap_ = 0;
  typename Exec::template Buffer<std::int32_t> loc_, live_, live2_, rank_, list_, spl_;
  typename Exec::template Buffer<u64> best_;
};
