// Phase 1's batches (triangulator.inl): each chooses a point per tetrahedron, splits and flips;
// the points not yet inserted follow their tetrahedra through the splits and the flip records.

// One batch: relocate and choose, split, flip.
inline void Triangulator::batch() {
  const auto t0 = Clock::now();
  ++batches_;
  relocate(true);
  u64* best = key_.data();
  std::int32_t* chosen = un2_.data();  // (free until the point list is compacted below)
  const std::int32_t* loc0 = loc_.data();
  const std::int64_t nchosen = ex_.copy_if(
      un_.data(), nun_, chosen, GG_LAMBDA(std::int32_t q) {
        const std::int32_t L = loc0[q];
        return L >= 0 && std::uint32_t(best[L]) == std::uint32_t(q);
      });
  // At most a quarter of the points a batch (every stride-th choice in curve order, spread
  // over the whole set): the last batches would otherwise take half the points at once, and
  // the rounds' lists (4 entries a split, then up to twice that) are the largest arrays
  // after the store. The others give up their choice (their keys cleared for the votes).
  const std::int64_t limit = std::max<std::int64_t>(m_ / 4, 1);
  const std::int64_t stride = (nchosen + limit - 1) / limit;
  const std::int64_t nins = stride > 1 ? (nchosen + stride - 1) / stride : nchosen;
  if (stride > 1)
    ex_.for_each_index(
        nchosen, GG_LAMBDA(std::int64_t r) {
          if (r % stride) best[loc0[chosen[r]]] = ~u64(0);
        });
  // The previous batch's unfinished list (carried: its entries follow the splits' in the
  // first round's list).
  const std::int64_t carried = nact_;
  Counters c = counters();
  reserve(c.used + 3 * nins);
  if (4 * nins + carried > list_cap_) grow_lists(4 * nins + nins + carried);
  fit(ins_, nins);
  fit(split_, 5 * nins);
  used_ = c.used + 3 * nins;  // (the split below hands these out)
  best = key_.data();
  std::int32_t* ins = ins_.data();
  std::int32_t* srank = srank_.data();
  ex_.for_each_index(
      nins, GG_LAMBDA(std::int64_t r) {
        const std::int32_t t = loc0[chosen[r * stride]];
        ins[r] = t;
        srank[t] = std::int32_t(r);
      });
  const std::int32_t first_new = std::int32_t(c.used);
  const Mesh M = M_;
  const mesh::WorkLists L = work_lists();
  std::int32_t* act = L.current(round_ + 1);  // the first flip round's list
  std::int64_t* len = L.count(round_ + 1);
  // The carried entries, set aside in the other list: not those this batch splits (their
  // first child keeps the slot and is listed with the splits), nor the -1 places.
  std::int32_t* kept_list = L.current(round_ + 2);
  const std::int64_t kept = carried == 0
                                ? 0
                                : ex_.copy_if(
                                      act, carried, kept_list, GG_LAMBDA(std::int32_t t) {
                                        return t >= 0 && M.tet[t].v[0] >= 0 && srank[t] < 0;
                                      });
  std::int32_t* sp = split_.data();
  std::int32_t* loc = loc_.data();
  ex_.for_each_index(
      nins, GG_LAMBDA(std::int64_t r) {
        if (r == 0) {
          *len = 4 * nins + kept;
          M.ctr->used = first_new + 3 * nins;
        }
        const std::int32_t t = ins[r], q = std::int32_t(std::uint32_t(best[t]));
        const Tet T = M.tet[t];
        sp[5 * r] = q;
        for (int k = 0; k < 4; ++k) sp[5 * r + 1 + k] = T.v[k];
        auto child = [&](std::int32_t s, std::int32_t rank, int k) {
          return k == 0 ? s : first_new + 3 * rank + k - 1;
        };
        for (int k = 0; k < 4; ++k) {
          Tet C;
          for (int j = 0; j < 4; ++j) C.v[j] = j == k ? q : T.v[j];
          for (int j = 0; j < 4; ++j)
            if (j != k) C.n[j] = enc(child(t, std::int32_t(r), j), k);
          const std::int32_t e = T.n[k], nb = simplex_of(e);
          const int jj = loc_of(e);
          const std::int32_t rn = srank[nb];
          if (rn >= 0) {
            C.n[k] = enc(child(nb, rn, jj), jj);
          } else {
            C.n[k] = e;
            M.tet[nb].n[jj] = enc(child(t, std::int32_t(r), k), k);
          }
          const std::int32_t slot = child(t, std::int32_t(r), k);
          M.tet[slot] = C;
          act[4 * r + k] = slot;
        }
        best[t] = ~u64(0);  // (no vote: the flip rounds' keys are inverted)
        loc[q] = -1;
      });
  ex_.for_each_index(
      kept, GG_LAMBDA(std::int64_t i) { act[4 * nins + i] = kept_list[i]; });
  epoch_splits_ = nins;
  max_nins_ = std::max(max_nins_, nins);
  epoch_first_new_ = first_new;
  remaining_ -= nins;
  dead_ += nins;
  if (dead_ * 4 > nun_) {  // drop inserted points from the list once they are a quarter
    nun_ = ex_.copy_if(
        un_.data(), nun_, un2_.data(), GG_LAMBDA(std::int32_t q) { return loc[q] >= 0; });
    std::swap(un_, un2_);
    dead_ = 0;
  }
  nact_ = 4 * nins + kept;
  // Rounds stop once their list is short, after kCarryAfter of them, unless every point is
  // in: the waves that cross integer grids' hull planes, a flip or a few a round for as many
  // rounds as the grid is wide, go on beside the next batch's rounds instead of alone.
  carry_from_ = remaining_ > 0 && max_rounds_ < 0 ? round_ + 1 + kCarryAfter : INT32_MAX;
  ms_choose_ += ms_since(t0);
  flip_until_stuck();
  if (progress_) progress_(Delaunay3dProgress{"insert_flip", m_ - remaining_, m_, batches_});
}

// Points not yet inserted follow their tetrahedron through this epoch's splits and recorded
// flips (and, when choose, each tetrahedron then picks one of its points); then a new epoch
// of records begins.
inline void Triangulator::relocate(bool choose) {
  const Geo g = g_;
  const Mesh M = M_;
  const std::int32_t* un = un_.data();
  std::int32_t* loc = loc_.data();
  const std::int32_t* srank = srank_.data();
  const std::int32_t* sp = split_.data();
  const std::int32_t first_new = epoch_first_new_;
  u64* best = key_.data();
  const bool moved = epoch_splits_ > 0 || logged_ > 0;
  if (!moved && !choose) return;
  // (the keys hold the flip rounds' stale votes: cleared for the choice, an atomic minimum)
  if (choose) ex_.fill(best, cap_, ~u64(0));
  ex_.for_each_index(
      nun_, GG_LAMBDA(std::int64_t i) {
        const std::int32_t q = un[i];
        std::int32_t L = loc[q];
        if (L < 0) return;  // inserted
        if (moved) {
          const std::int32_t r = srank[L];
          if (r >= 0) {  // child k: the old tetrahedron with vertex k replaced by p
            const std::int32_t* x = sp + 5 * std::int64_t(r);
            int found = 3;
            for (int k = 0; k < 3 && found == 3; ++k) {
              std::int32_t c[4] = {x[1], x[2], x[3], x[4]};
              c[k] = x[0];
              bool in = true;
              for (int j = 0; j < 4 && in; ++j)
                if (j != k) in = orient_with(g, c, j, q) > 0;
              if (in) found = k;
            }
            L = found == 0 ? L : first_new + 3 * r + found - 1;
          }
          L = M.log.follow(L, Side{g, q});
          loc[q] = L;
        }
        if (choose) {
          const u64 key = (u64(choice_key(g, M.tet[L].v, q)) << 32) | u64(std::uint32_t(q));
          atomic_min(best + L, key);
        }
      });
  std::int32_t* sr = srank_.data();
  const std::int32_t* ins = ins_.data();
  ex_.for_each_index(
      epoch_splits_, GG_LAMBDA(std::int64_t r) { sr[ins[r]] = -1; });
  if (logged_ > 0) {
    Counters* ctr = ctr_.data();
    ex_.for_each_index(
        1, GG_LAMBDA(std::int64_t) { ctr->log = 0; });
    if (M_.log.next_epoch(logged_, log_cap_)) ex_.fill(hist_.data(), cap_, Hist{-1, -1});
  }
  logged_ = 0;
  epoch_splits_ = 0;
}
