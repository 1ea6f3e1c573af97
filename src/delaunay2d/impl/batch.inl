// The 2D Triangulator's batches (triangulator.inl): each triangle holding points not yet
// inserted chooses one, the chosen split their triangles, and the flip rounds follow; the points
// not yet inserted follow their triangles through the splits and the flip records.

// A batch's choice shares the vote array with the flip rounds (they never overlap): each
// point claims its triangle with its choice key (its top 31 bits) and index, complemented so
// that the largest claim is the best point (the rounds' keys also win by atomic max). A
// claim's high word is then at least 2^31, above every round number in a vote key, so the
// votes the rounds left need no clearing; the split sets its triangles' entries to 0 (none).
GG_HD inline u64 claim_of(std::uint32_t choice, std::int32_t q) {
  return ~((u64(choice >> 1) << 32) | u64(std::uint32_t(q)));
}
GG_HD inline std::int32_t claimant_of(u64 claim) {
  return std::int32_t(~std::uint32_t(claim));
}
// q is the point its triangle chose.
struct Chosen {
  const std::int32_t* loc;
  const u64* claim;
  GG_HD bool operator()(std::int32_t q) const {
    const std::int32_t L = loc[q];
    return L >= 0 && claimant_of(claim[L]) == q;
  }
};
struct NotInserted {
  const std::int32_t* loc;
  GG_HD bool operator()(std::int32_t q) const { return loc[q] >= 0; }
};

// One batch. The points move (through the last batch's split and flips) and choose in one
// pass; the chosen points are then collected in curve order.
inline void Triangulator::batch() {
  ++batches_;
  mark("other");
  relocate(true);
  mark("relocate+choose");
  // The chosen points in curve order, so that the new slots (and the work lists, which
  // follow them) go through the plane along the curve: neighbouring slots then share memory
  // sectors of the points and of each other, where triangle order scattered every access.
  // (The work lists are free between batches: one holds them, the other the new list.)
  u64* claim = this->claims();
  std::int32_t* ins = ins_.data();
  std::int32_t* chosen = spare_list();
  const std::int64_t nchosen = ex_.copy_if(un_.data(), nun_, chosen, Chosen{loc_.data(), claim});
  // A batch inserts at most ins_cap_ points (its split records are sized for that): the
  // first ones along the curve; the other triangles keep their points for the next batch.
  const std::int64_t nins = std::min(nchosen, ins_cap_);
  mark("compact chosen");
  std::int32_t* srank = this->srank();
  const std::int32_t* locc = loc_.data();
  const std::int64_t cap = ins_cap_;
  ex_.for_each_index(
      nchosen, GG_LAMBDA(std::int64_t r) {
        const std::int32_t t = locc[chosen[r]];
        if (r >= cap) {
          claim[t] = 0;  // (no claim may outlive the split: the rounds' votes would lose to it)
          return;
        }
        ins[r] = t;
        srank[t] = std::int32_t(r);
      });
  const Mesh M = M_;
  const std::int32_t first_new = std::int32_t(base_ + ntri_);
  const mesh::WorkLists L = work_lists();
  std::int32_t* act = L.current(round_ + 1);  // the next round's list
  std::int64_t* len = L.count(round_ + 1);
  std::int32_t* sp = split_.data();
  std::int32_t* loc = loc_.data();
  ex_.for_each_index(
      nins, GG_LAMBDA(std::int64_t r) {
        if (r == 0) *len = 3 * nins;
        const std::int32_t t = ins[r], q = claimant_of(claim[t]);
        const std::int32_t base = first_new + 2 * std::int32_t(r);
        sp[4 * r] = q;  // what the points of t need to find their child later
        for (int k = 0; k < 3; ++k) sp[4 * r + 1 + k] = M.tri[t].v[k];
        split_triangle(M, t, q, base, srank, first_new);
        claim[t] = 0;
        loc[q] = -1;
        act[3 * r] = t;
        act[3 * r + 1] = base;
        act[3 * r + 2] = base + 1;
      });
  ntri_ += 2 * nins;
  mark("split");
  epoch_splits_ = nins;
  epoch_first_new_ = first_new;
  remaining_ -= nins;
  dead_ += nins;
  if (dead_ * 4 > nun_) {  // drop inserted points from the list once they are a quarter
    std::int32_t* kept = spare_list();  // (the other list holds the rounds' first list)
    nun_ = ex_.copy_if(un_.data(), nun_, kept, NotInserted{loc});
    ex_.copy(kept, nun_, un_.data());
    dead_ = 0;
  }
  mark("compact points");
  nact_ = 3 * nins;
  flip_until_delaunay(true);  // the list holds the children of the splits, new point first
}

// Points not yet inserted follow their triangle through this epoch's split and recorded
// flips (and, when choose, each triangle then picks one of its points); then a new epoch of
// records begins.
inline void Triangulator::relocate(bool choose) {
  const Geo g = g_;
  const Mesh M = M_;
  const std::int32_t* un = un_.data();
  std::int32_t* loc = loc_.data();
  const std::int32_t* srank = this->srank();
  const std::int32_t* sp = split_.data();
  const std::int32_t first_new = epoch_first_new_;
  u64* claim = this->claims();
  const bool moved = epoch_splits_ > 0 || logged_ > 0;
  if (!moved && !choose) return;
  ex_.for_each_index(
      nun_, GG_LAMBDA(std::int64_t i) {
        const std::int32_t q = un[i];
        std::int32_t L = loc[q];
        if (L < 0) return;  // inserted
        if (moved) {
          const std::int32_t r = srank[L];
          if (r >= 0) {  // children: L = (p, v1, v2), c1 = (p, v2, v0), c2 = (p, v0, v1)
            const std::int32_t* x = sp + 4 * std::int64_t(r);
            const std::int32_t p = x[0], c1 = first_new + 2 * r;
            if (orient_ext(g, p, x[2], q) > 0)
              L = orient_ext(g, p, x[3], q) < 0 ? L : c1;
            else
              L = orient_ext(g, p, x[1], q) > 0 ? c1 + 1 : c1;
          }
          L = follow_history(g, M, L, q);
          loc[q] = L;
        }
        if (choose) {
          atomic_max(claim + L, claim_of(choice_key(g, M.tri[L].v, q), q));
        }
      });
  std::int32_t* sr = this->srank();
  const std::int32_t* ins = ins_.data();
  ex_.for_each_index(
      epoch_splits_, GG_LAMBDA(std::int64_t r) { sr[ins[r]] = -1; });
  if (logged_ > 0) {
    Counters* ctr = ctr_.data();
    ex_.for_each_index(
        1, GG_LAMBDA(std::int64_t) { ctr->log = 0; });
    if (M_.log.next_epoch(logged_, log_cap_)) ex_.fill(hist_.data(), tmax_, Hist{-1, -1});
  }
  logged_ = 0;
  epoch_splits_ = 0;
}
