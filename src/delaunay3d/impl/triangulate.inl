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

using u64 = std::uint64_t;
using FlipLog = mesh::FlipLog<3, 6>;  // slots; payload: kind, then the five vertices
using Hist = mesh::FlipHist;

struct Counters {
  std::int64_t len[2];                // work list lengths (mesh::WorkLists)
  std::int64_t nflip[2];              // the round's flips (records), by round parity
  std::int64_t log;                   // records of the epoch
  std::int64_t used;                  // slots handed out
  std::int64_t free_head, free_tail;  // the ring of freed slots
  // Where the round's flips draw from (settle): the counters as the round found them.
  std::int64_t at_used, at_log, at_head, at_tail;
  std::int64_t flips23, flips32, rounds, unflippable, failed_faces, flat, lost, errors;
  std::int64_t halt, halt_round;  // a round found no room: it and the rest of its chunk wait
  std::int64_t team_end;          // the round a team stopped at (did not run)
  // What the halted round needs (settle): slots, flip records, next-list entries, ring entries.
  std::int64_t need_slots, need_log, need_list, need_ring;
  std::int64_t halts;  // rounds halted for room (each runs again)
  // The batch's rounds stopped with their list carried into the next batch (FlipRound::begin);
  // how many batches did.
  std::int64_t carry, carries;
  // High-water marks (sizing): the longest list, the most records of an epoch, the most freed
  // slots waiting in the ring.
  std::int64_t max_len, max_log, max_free;
};

// The store as the kernels see it.
struct Mesh {
  Tet* tet;
  u64* vote;
  FlipLog log;
  std::int32_t* freeq;  // freed slots, a ring of `ring` entries
  std::int64_t cap, ring;
  Counters* ctr;
};

// A round's flips, counted in list order up to an entry (an exclusive prefix over the list):
// the winning 2-3 and 3-2 proposals and the outvoted ones. Everything a flip is handed (its
// third slot, the slot it frees into the ring, its record, its place in the next list) is a
// function of these ranks, so that no slot number, record or list position depends on which
// thread came first: the whole run, not only its result, is the same on every run, thread
// count and executor.
struct Tally {
  std::int32_t w23, w32, lost;
  GG_HD Tally operator+(const Tally& o) const {
    return Tally{w23 + o.w23, w32 + o.w32, lost + o.lost};
  }
};

// A list entry's decision (FlipRound::dec): -1 none, else face | kind << 2, plus one of these
// once the votes are read.
constexpr int kWon = 16, kLost = 32;
GG_HD inline Tally tally_of(std::int8_t d) {
  if (d < 0) return Tally{0, 0, 0};
  if (d & kWon) return ((d >> 2) & 3) ? Tally{0, 1, 0} : Tally{1, 0, 0};
  return Tally{0, 0, (d & kLost) ? 1 : 0};
}

// The face of v opposite k, oriented outward.
GG_INLINE void face_of(const std::int32_t* v, int k, std::int32_t* f) {
  for (int i = 0; i < 3; ++i) f[i] = v[face_vertex(k, i)];
}

// Which side of a recorded flip holds q (payload: kind, x0, x1, x2, u, w).
// 2-3: the slots hold (x_e, x_e+1, u, w); q lies in slot e when it is on the positive side of
// the plane (x_e, u, w) (taken as orient(x_e, q, u, w) > 0) and not of (x_e+1, u, w).
// 3-2: the slots hold (x0, x1, x2, u) and (x0, x2, x1, w) with payload (c, u', w', a, b) stored
// as (x0, x1, x2) = (c, u', w'): slot 0 on the positive side of that plane.
struct Side {
  Geo g;
  std::int32_t q;
  GG_HD int operator()(const std::int32_t* P) const {
    if (P[0] == 1) return orient_ext(g, P[1], P[2], P[3], q) > 0 ? 0 : 1;
    int w[3];
    for (int e = 0; e < 3; ++e) w[e] = orient_ext(g, P[1 + e], q, P[4], P[5]);
    for (int e = 0; e < 3; ++e)
      if (w[e] > 0 && w[(e + 1) % 3] < 0) return e;
    return 0;  // (unreachable for a point inside the flipped region)
  }
};

// Where a face of a flipped neighbour went (mesh::fix_face's store): the face (f0, f1, f2) of
// the flipped slot simplex_of(outer) now lies in one of the slots of that slot's flip record.
struct FaceStore {
  Mesh M;
  std::int32_t f[3];
  GG_HD void set(std::int32_t slot, int face, std::int32_t e) const { M.tet[slot].n[face] = e; }
  GG_HD std::int32_t moved(std::int32_t outer) const {
    const std::int32_t o = simplex_of(outer);
    const std::int32_t* x = M.log.record(M.log.hist[o].last >> FlipLog::kSideBits);
    const int sides = x[3] == 1 ? 2 : 3;  // (x[3]: the payload's kind)
    for (int s = 0; s < sides; ++s) {
      const int l = opposite_of_face(M.tet[x[s]].v, f[0], f[1], f[2]);
      if (l >= 0) return enc(x[s], l);
    }
    atomic_add(&M.ctr->errors, std::int64_t(1));
    return outer;
  }
};

// A 3-2 proposal's third tetrahedron (decision r = face | kind << 2, kind = 1 + the edge's
// place on the face): across the face opposite c, the face's vertex off the edge. (Found
// again from the proposer rather than kept: one int32 less per list entry.)
GG_HD inline std::int32_t third_of(const Tet& T, int r) {
  std::int32_t x[3];
  face_of(T.v, r & 3, x);
  const std::int32_t c = x[(((r >> 2) & 3) + 1) % 3];
  const int kk = T.v[0] == c ? 0 : T.v[1] == c ? 1 : T.v[2] == c ? 2 : 3;
  return simplex_of(T.n[kk]);
}

// One flip round's steps, each a function of one list entry (or flip), so that the same code
// runs as kernels or inside a team: begin (one thread), test, decide, then the exclusive prefix
// of the decisions' tallies over the list (tally), settle (one thread), flip, fix (over the
// round's flips), relist. A list entry may be -1 (an outvoted proposer that another flip
// rewrote: its place was reserved before the flips ran); it does nothing.
struct FlipRound {
  Geo g;
  Mesh M;
  mesh::WorkLists L;
  std::int8_t* dec;  // per list entry: the proposal (face | kind << 2), or -1
  Tally* tally;      // per list entry: the decisions before it; at the list's end, all
  std::int32_t round;
  std::int64_t log_cap;
  std::int64_t list_cap;  // entries each list holds
  std::int64_t span;      // the longest list the decisions' scan covers (a longer one halts)
  // A round from carry_from on whose list is at most carry_max entries stops the batch's
  // rounds: its list goes on in the next batch's rounds (Triangulator::batch).
  std::int32_t carry_from;
  std::int64_t carry_max;

  GG_HD const std::int64_t* count() const { return L.count(round); }
  GG_HD const std::int64_t* flips() const { return &M.ctr->nflip[round & 1]; }
  GG_HD bool halted() const { return M.ctr->halt != 0; }

  // The round's counters. A round that could need more slots or records than there are, or
  // whose list is longer than the decisions' scan covers, halts (nothing of it runs) until the
  // host grows the store, starts a new epoch of records or runs it with a larger bound.
  GG_HD void begin() const {
    Counters* ctr = M.ctr;
    if (ctr->halt) return;
    const std::int64_t n = *count();
    *L.next_count(round) = 0;
    ctr->nflip[round & 1] = 0;
    if (n == 0) return;  // (a round past the last one: nothing to do)
    if (round >= carry_from && n <= carry_max) {
      ctr->halt = 1;
      ctr->halt_round = round;
      ctr->carry = 1;
      return;
    }
    if (n > span) {
      ctr->halt = 1;
      ctr->halt_round = round;
      ctr->need_list = n;
      ctr->halts += 1;
      return;
    }
    ctr->rounds += 1;
  }

  // Tests and proposals: at its first face that is not locally Delaunay and can be flipped, a
  // tetrahedron votes for the flip on every tetrahedron the flip rewrites.
  GG_HD void test(std::int64_t i) const {
    if (halted()) return;
    Counters* ctr = M.ctr;
    const std::int32_t t = L.current(round)[i];
    int res = -1;
    std::int32_t t3 = -1;
    bool stuck = false;
    const Tet T = t >= 0 ? M.tet[t] : Tet{{-1, -1, -1, -1}, {-1, -1, -1, -1}};
    if (T.v[0] >= 0) {
      for (int k = 0; k < 4 && res < 0; ++k) {
        const std::int32_t nb = simplex_of(T.n[k]);
        const std::int32_t d = M.tet[nb].v[loc_of(T.n[k])];
        if (!in_sphere_ext(g, T.v, d)) continue;
        std::int32_t x[3];
        face_of(T.v, k, x);
        const std::int32_t u = T.v[k];
        int neg = -1, nneg = 0;
        for (int e = 0; e < 3; ++e)
          if (orient_ext(g, x[e], x[(e + 1) % 3], u, d) < 0) neg = e, ++nneg;
        if (nneg == 0) {
          res = k;
        } else if (nneg == 1) {  // 3-2 if the edge x_neg x_neg+1 has degree 3
          const std::int32_t c = x[(neg + 2) % 3];
          const int kk = T.v[0] == c ? 0 : T.v[1] == c ? 1 : T.v[2] == c ? 2 : 3;
          const std::int32_t z = simplex_of(T.n[kk]);
          if (M.tet[z].v[loc_of(T.n[kk])] == d) {
            res = k | ((neg + 1) << 2);
            t3 = z;
          } else {
            stuck = true;
          }
        } else {
          stuck = true;
        }
        if (res >= 0) {  // (inverted keys: the smallest wins, so ~0 is no vote)
          const u64 key = ~mesh::vote_key(round, t);
          atomic_min(M.vote + t, key);
          atomic_min(M.vote + nb, key);
          if (t3 >= 0) atomic_min(M.vote + t3, key);
        }
      }
    }
    if (stuck && res < 0) atomic_add(&ctr->unflippable, std::int64_t(1));
    dec[i] = std::int8_t(res);
  }

  // Decisions: a proposal that holds the vote on every tetrahedron it rewrites wins; the
  // others are outvoted (the votes are all in: test has run over the whole list).
  GG_HD void decide(std::int64_t i) const {
    if (halted()) return;
    const int r = dec[i];
    if (r < 0) return;
    const std::int32_t t = L.current(round)[i];
    const u64 key = ~mesh::vote_key(round, t);
    const Tet T = M.tet[t];
    const std::int32_t nb = simplex_of(T.n[r & 3]);
    const bool won =
        M.vote[t] == key && M.vote[nb] == key && (!(r >> 2) || M.vote[third_of(T, r)] == key);
    dec[i] = std::int8_t(r | (won ? kWon : kLost));
  }
  GG_HD Tally tally_at(std::int64_t i) const { return tally_of(dec[i]); }

  // One thread, once tally holds the prefix over the list (its entry n: the totals): the round
  // takes its slots, records and next list from the counters as they are, in list order.
  GG_HD void settle() const {
    Counters* ctr = M.ctr;
    if (ctr->halt) return;
    const std::int64_t n = *count();
    if (n == 0) return;
    const Tally all = tally[n];
    {  // room for what the flips take; else the round halts before any of them runs
      const std::int64_t avail = ctr->free_tail - ctr->free_head;
      const std::int64_t popped = all.w23 < avail ? all.w23 : avail;
      const std::int64_t slots = ctr->used + all.w23 - popped;
      const std::int64_t records = std::int64_t(all.w23) + all.w32;
      const std::int64_t next = 3 * std::int64_t(all.w23) + 2 * std::int64_t(all.w32) + all.lost;
      // (the flips pop and push in the same step: the ring holds both at once)
      const std::int64_t ring = avail + all.w32;
      if (slots > M.cap || ctr->log + records > log_cap || next > list_cap || ring > M.ring) {
        ctr->halt = 1;
        ctr->halt_round = round;
        ctr->need_slots = slots;
        ctr->need_log = records;
        ctr->need_list = next;
        ctr->need_ring = ring;
        ctr->halts += 1;
        return;
      }
    }
    ctr->at_used = ctr->used;
    ctr->at_log = ctr->log;
    ctr->at_head = ctr->free_head;
    ctr->at_tail = ctr->free_tail;
    const std::int64_t avail = ctr->free_tail - ctr->free_head;
    const std::int64_t popped = all.w23 < avail ? all.w23 : avail;
    ctr->free_head += popped;
    ctr->free_tail += all.w32;
    ctr->used += all.w23 - popped;
    ctr->log += all.w23 + all.w32;
    ctr->nflip[round & 1] = all.w23 + all.w32;
    ctr->flips23 += all.w23;
    ctr->flips32 += all.w32;
    *L.next_count(round) = 3 * std::int64_t(all.w23) + 2 * std::int64_t(all.w32) + all.lost;
    if (n > ctr->max_len) ctr->max_len = n;
    if (ctr->log > ctr->max_log) ctr->max_log = ctr->log;
    if (ctr->free_tail - ctr->free_head > ctr->max_free)
      ctr->max_free = ctr->free_tail - ctr->free_head;
  }

  // Flips: the winners, each with what its ranks hand it (settle).
  GG_HD void flip(std::int64_t i) const {
    if (halted()) return;
    const int r = dec[i];
    if (r < 0 || !(r & kWon)) return;
    const Counters* ctr = M.ctr;
    const Tally at = tally[i];
    const std::int32_t t = L.current(round)[i];
    const Tet T = M.tet[t];
    const int k = r & 3, kind = (r >> 2) & 3;
    const std::int32_t nb = simplex_of(T.n[k]);
    const std::int32_t z = kind ? third_of(T, r) : -1;
    Tet old[3];
    old[0] = T;
    old[1] = M.tet[nb];
    std::int32_t x[3];
    face_of(T.v, k, x);
    const std::int32_t u = T.v[k], w = old[1].v[loc_of(T.n[k])];
    Tet y[3];
    std::int32_t slots[3];
    std::int32_t payload[6];
    int nold, nnew;
    if (kind == 0) {  // 2-3: (x_e, x_e+1, u, w)
      nold = 2, nnew = 3;
      // (the third slot: a slot freed in an earlier round, else a new one)
      const std::int64_t avail = ctr->at_tail - ctr->at_head;
      slots[0] = t, slots[1] = nb;
      slots[2] = at.w23 < avail ? M.freeq[(ctr->at_head + at.w23) % M.ring]
                                : std::int32_t(ctr->at_used + (at.w23 - avail));
      for (int e = 0; e < 3; ++e) {
        y[e].v[0] = x[e], y[e].v[1] = x[(e + 1) % 3], y[e].v[2] = u, y[e].v[3] = w;
      }
      payload[0] = 0, payload[1] = x[0], payload[2] = x[1], payload[3] = x[2];
      payload[4] = u, payload[5] = w;
    } else {  // 3-2 around edge (a, b): (c, u, w, a) and (c, w, u, b)
      nold = 3, nnew = 2;
      old[2] = M.tet[z];
      const int e = kind - 1;
      const std::int32_t a = x[e], b = x[(e + 1) % 3], c = x[(e + 2) % 3];
      slots[0] = t, slots[1] = nb, slots[2] = z;
      y[0].v[0] = c, y[0].v[1] = u, y[0].v[2] = w, y[0].v[3] = a;
      y[1].v[0] = c, y[1].v[1] = w, y[1].v[2] = u, y[1].v[3] = b;
      payload[0] = 1, payload[1] = c, payload[2] = u, payload[3] = w;
      payload[4] = a, payload[5] = b;
    }
    // Neighbours: faces among the new tetrahedra, else the old outer pointer as it was (the
    // fix step settles the outer ones).
    for (int s = 0; s < nnew; ++s)
      for (int l = 0; l < 4; ++l) {
        std::int32_t f[3];
        face_of(y[s].v, l, f);
        std::int32_t e = kNoNeighbour;  // (an encoding may be negative: found, not e >= 0)
        bool found = false;
        for (int s2 = 0; s2 < nnew && !found; ++s2) {
          const int l2 = s2 == s ? -1 : opposite_of_face(y[s2].v, f[0], f[1], f[2]);
          if (l2 >= 0) e = enc(slots[s2], l2), found = true;
        }
        for (int o = 0; o < nold && !found; ++o) {
          const int lo = opposite_of_face(old[o].v, f[0], f[1], f[2]);
          if (lo >= 0) e = old[o].n[lo], found = true;
        }
        y[s].n[l] = e;
      }
    for (int s = 0; s < nnew; ++s) M.tet[slots[s]] = y[s];
    if (kind) {
      Tet dead;
      dead.v[0] = dead.v[1] = dead.v[2] = dead.v[3] = -1;
      dead.n[0] = dead.n[1] = dead.n[2] = dead.n[3] = -1;
      M.tet[z] = dead;
      M.freeq[(ctr->at_tail + at.w32) % M.ring] = z;
    }
    Hist h[3];
    M.log.load(slots, h);
    M.log.append(record(at.w23 + at.w32), slots, payload, h);
    std::int32_t* next = L.next(round);
    const std::int64_t to = 3 * std::int64_t(at.w23) + 2 * std::int64_t(at.w32);
    for (int s = 0; s < nnew; ++s) next[to + s] = slots[s];
  }
  // Whether a flip of this round rewrote slot s (its latest record is one of the round's: a
  // flip records every slot it rewrites, the freed one included).
  GG_HD bool flipped_now(std::int32_t s) const {
    return (M.log.hist[s].last >> FlipLog::kSideBits) >= record(0);
  }
  // The round's j-th flip's record (flips are numbered in list order).
  GG_HD std::int32_t record(std::int64_t j) const {
    return M.log.base + std::int32_t(M.ctr->at_log + j);
  }

  // Phase 2 of the flips: outer faces point to where their neighbours' faces went.
  GG_HD void fix(std::int64_t i) const {
    if (halted()) return;
    const std::int32_t* x = M.log.record(record(i));
    const int nnew = x[3] == 1 ? 2 : 3;
    for (int s = 0; s < nnew; ++s) {
      const std::int32_t ys = x[s];
      const Tet Y = M.tet[ys];
      for (int l = 0; l < 4; ++l) {
        const std::int32_t o = simplex_of(Y.n[l]);
        if (o == x[0] || o == x[1] || o == x[2]) continue;  // inner
        FaceStore S{M, {0, 0, 0}};
        face_of(Y.v, l, S.f);
        mesh::fix_face<TetAdjacency>(S, ys, l, Y.n[l], flipped_now(o));
      }
    }
  }

  // Outvoted proposers test again, in the places settle reserved after the flips' slots (a
  // proposer rewritten by another flip is listed by it: its place gets -1).
  GG_HD void relist(std::int64_t i) const {
    if (halted()) return;
    const int r = dec[i];
    if (r < 0 || !(r & kLost)) return;
    const std::int32_t t = L.current(round)[i];
    const Tally all = tally[*count()];
    const std::int64_t to = 3 * std::int64_t(all.w23) + 2 * std::int64_t(all.w32) + tally[i].lost;
    L.next(round)[to] = flipped_now(t) ? -1 : t;
  }
};

// (Every member is public: nvcc's extended lambdas may not live in private members.)
class Triangulator {
 public:
  Triangulator(Exec& ex, const double* pts, std::int32_t m, const mesh::Tetra& first,
               std::int64_t max_rounds, const ProgressFn& progress, Stats& st)
      : ex_(ex), st_(st), max_rounds_(max_rounds), progress_(progress) {
    m_ = m;
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
    const std::size_t n = std::size_t(m);
    loc_ = ex.template alloc<std::int32_t>(n);
    un_ = ex.template alloc<std::int32_t>(n);
    un2_ = ex.template alloc<std::int32_t>(n);
    ctr_ = ex.template alloc<Counters>(1);
    Counters zero{};
    ex.from_host(&zero, 1, ctr_.data());
    // First sizes, from what uniform points use (design notes, "Phase 1's memory"): slots in
    // use reach 7.2-7.33 a point (7.35 held; more on small sets: the constant), lists 2.2 (batches
    // of at most a quarter of the points; 2.4 at 10^6), records of an epoch 1.9 (1.75 held: a new
    // epoch starts early), freed slots waiting 0.5-0.8. Each grows where a round needs more
    // (settle halts the round, make_room grows).
    const std::int64_t m64 = m;
    grow(std::min(m64 * 147 / 20 + 4096, kMaxSlots));
    grow_lists(std::max<std::int64_t>(m64 * 9 / 4, 1024));
    grow_ring(std::max<std::int64_t>(m64 * 3 / 4, 1024));
    grow_log(std::max<std::int64_t>(m64 * 7 / 4, 1 << 16));
  }

  // The kernels' view of the store.
  void set_mesh() {
    M_ = Mesh{tet_.data(),   key_.data(), FlipLog{rec_.data(), hist_.data(), M_.log.base},
              freeq_.data(), cap_,        ring_cap_,
              ctr_.data()};
  }

  // Capacity for cap slots: every per-slot array grows, keeping what it holds. One array at a
  // time, so that at most one array is held twice (the largest inputs fill the device: a
  // whole second store would not fit).
  void grow(std::int64_t cap) {
    if (phase1_released_) {  // phase 2 and the output read the store only (release_phase1)
      const Counters c = counters();
      regrow<Tet>(ex_, tet_, cap, std::min<std::int64_t>(c.used, cap_), nullptr);
      cap_ = cap;
      M_ = Mesh{tet_.data(), nullptr, FlipLog{}, nullptr, cap_, 0, ctr_.data()};
      return;
    }
    const std::int64_t keep = cap_ ? std::min<std::int64_t>(counters().used, cap_) : 0;
    regrow<Tet>(ex_, tet_, cap, keep, nullptr);
    const u64 none = ~u64(0);
    const std::int32_t minus1 = -1;
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
  void grow_lists(std::int64_t entries) {
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
  void grow_ring(std::int64_t entries) {
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
  void grow_log(std::int64_t records) {
    const std::int64_t keep = log_cap_ ? FlipLog::kStride * counters().log : 0;
    regrow<std::int32_t>(ex_, rec_, FlipLog::kStride * records, keep, nullptr);
    log_cap_ = records;
    set_mesh();
    note_bytes();
  }
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
  void reserve(std::int64_t slots) {
    if (slots <= cap_) return;
    if (slots > kMaxSlots)
      throw Error(ErrorCode::OutOfMemory,
                  "the tetrahedralisation needs more than 2^30 - 1 tetrahedra (about 1.4·10^8 "
                  "points), more than the 32-bit neighbour encoding can address");
    grow(std::min(std::max(slots, cap_ + cap_ / 8), kMaxSlots));
  }
  // What a halted round needs (settle's counts), made: a larger store, list, ring or log,
  // or a new epoch of records.
  void make_room(const Counters& c) {
    if (c.need_list > list_cap_) grow_lists(std::max(c.need_list, list_cap_ + list_cap_ / 4));
    if (c.need_slots > cap_) reserve(c.need_slots);
    if (c.need_ring > ring_cap_) grow_ring(std::max(c.need_ring, ring_cap_ + ring_cap_ / 4));
    if (c.log + c.need_log > log_cap_) {
      relocate(false);
      if (c.need_log > log_cap_) grow_log(std::max(c.need_log, log_cap_ + log_cap_ / 4));
    }
  }

  // Phase 1's int32 arrays (what held_bytes counts and release_phase1 frees).
  std::array<typename Exec::template Buffer<std::int32_t>*, 10> int32_arrays() {
    return {&srank_, &freeq_, &lists_[0], &lists_[1], &rec_, &loc_, &un_, &un2_, &ins_, &split_};
  }

  // Bytes phase 1 holds on the executor (its arrays and the exact stages' scratch), and the
  // most it held.
  std::int64_t held_bytes() {
    std::int64_t b = std::int64_t(tet_.size()) * sizeof(Tet) + std::int64_t(hist_.size()) * 8 +
                     std::int64_t(key_.size()) * 8 + std::int64_t(dec_.size()) +
                     std::int64_t(tally_.size()) * sizeof(Tally) +
                     std::int64_t(pool_.scratch.size()) * 8;
    for (const auto* x : int32_arrays()) b += std::int64_t(x->size()) * 4;
    return b + std::int64_t(m_) * (sizeof(double) * 3 + sizeof(std::int32_t));  // (prepare's)
  }
  void note_bytes() { peak_bytes_ = std::max(peak_bytes_, held_bytes()); }

  // Phase 1's working arrays, once it is done: what follows (failed faces, phase 2, the
  // output) reads only the store, the counters and the points.
  void release_phase1() {
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

  void run() {
    start();
    insert_all();
  }
  // The batches, until every located point is inserted; then phase 1's arrays go.
  void insert_all() {
    remaining_ = nun_;
    while (remaining_ > 0) batch();
    ex_.sync();
    release_phase1();
  }

  // A kept tetrahedralisation (DynamicDelaunay3d, issue 47) in place of the first tetrahedron:
  // kept (executor memory, `used` slots) is a store as phase 2 leaves it, the Delaunay
  // tetrahedralisation of the perturbed points with its infinite tetrahedra and flat ones
  // (vertices as input indices, kKeptInfinity for the infinity point; dead slots v[0] = -1;
  // neighbours encoded as in the store, slot numbers kept). inv: input index -> prepared index;
  // near: per prepared point not in it, a prepared vertex of it near it (-1: none). The other
  // points are located by walks from a tetrahedron of their near vertex. g_.s must be the kept
  // one's kernel point (strictly inside its hull).
  static constexpr std::int32_t kKeptInfinity = -2;
  void start_from(const Tet* kept, std::int64_t used, const std::int32_t* inv,
                  const std::int32_t* near) {
    reserve(used + 4096);
    const std::int32_t I = m_;
    Tet* tet = tet_.data();
    auto d_in = ex_.template alloc<std::int8_t>(std::size_t(m_));
    auto d_slot = ex_.template alloc<std::int32_t>(std::size_t(m_));
    std::int8_t* in = d_in.data();
    std::int32_t* slot_of = d_slot.data();
    ex_.fill(in, m_, std::int8_t(0));
    ex_.fill(slot_of, m_, std::numeric_limits<std::int32_t>::max());
    ex_.for_each_index(
        used, GG_LAMBDA(std::int64_t t) {
          Tet T = kept[t];
          if (T.v[0] != -1)  // (not dead: kKeptInfinity may come first)
            for (int k = 0; k < 4; ++k) {
              const std::int32_t v = T.v[k] == kKeptInfinity ? I : inv[T.v[k]];
              T.v[k] = v;
              if (v != I) {
                in[v] = 1;
                atomic_min(&slot_of[v], std::int32_t(t));
              }
            }
          tet[t] = T;
        });
    Counters c{};
    c.used = used;
    ex_.from_host(&c, 1, ctr_.data());
    // The other points, each located by a walk (stochastic: the leaving face drawn; a scan of
    // every slot bounds it).
    const Geo g = g_;
    std::int32_t* loc = loc_.data();
    Counters* ctr = ctr_.data();
    auto walk_stats = ex_.template alloc<std::int64_t>(3);  // steps, scans, longest walk
    std::int64_t* ws = walk_stats.data();
    ex_.fill(ws, 3, std::int64_t(0));
    ex_.for_each_index(
        m_, GG_LAMBDA(std::int64_t i) {
          const std::int32_t q = std::int32_t(i);
          if (in[q]) {
            loc[q] = -1;
            return;
          }
          const std::int32_t h = near ? near[q] : -1;
          std::int64_t t = h >= 0 && in[h] ? slot_of[h] : -1;
          for (std::int64_t step = 0; t >= 0 && step <= used; ++step) {
            const Tet T = tet[t];
            int leave = -1;
            const int r =
                int(mesh::scatter(std::uint32_t(q) * 2654435761u + std::uint32_t(step)) % 4);
            for (int j = 0; j < 4 && leave < 0; ++j) {
              const int k = (r + j) % 4;
              if (orient_with(g, T.v, k, q) < 0) leave = k;
            }
            if (leave < 0) {
              loc[q] = std::int32_t(t);
              atomic_add(&ws[0], step);
              atomic_max(&ws[2], step);
              return;
            }
            t = simplex_of(T.n[leave]);
          }
          atomic_add(&ws[1], std::int64_t(1));
          for (t = 0; t < used; ++t)
            if (tet[t].v[0] >= 0 && inside_ext(g, tet[t].v, q)) {
              loc[q] = std::int32_t(t);
              return;
            }
          loc[q] = -1;
          atomic_add(&ctr->lost, std::int64_t(1));
        });
    std::int64_t w[3];
    ex_.to_host(ws, 3, w);
    st_.counters["start_walk_steps"] = w[0];
    st_.counters["start_walk_scans"] = w[1];
    st_.counters["start_walk_longest"] = w[2];
    nun_ = ex_.compact_indices(
        m_, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, un_.data());
    check_errors();
  }

  // Every tetrahedron of the store listed and flipped until stuck (a move's start, whose faces
  // need not be locally Delaunay: flips mend most of them at a round's cost, where phase 2
  // would splay every star they touch; what they cannot mend, phase 2 does). The points not in
  // the store follow the flips through the log, as in a batch.
  void flip_start() {
    const std::int64_t used = counters().used;
    if (used > list_cap_) grow_lists(used);
    const mesh::WorkLists L = work_lists();
    std::int32_t* act = L.current(round_ + 1);
    std::int64_t* len = L.count(round_ + 1);
    const Tet* tet = tet_.data();
    ex_.for_each_index(
        used, GG_LAMBDA(std::int64_t i) {
          if (i == 0) *len = used;
          act[i] = tet[i].v[0] >= 0 ? std::int32_t(i) : -1;
        });
    nact_ = used;
    carry_from_ = INT32_MAX;  // (no batch to carry the list into)
    flip_until_stuck();
    ex_.sync();
  }

  Counters counters() {
    Counters c;
    ex_.to_host(ctr_.data(), 1, &c);
    return c;
  }
  mesh::WorkLists work_lists() {
    return mesh::WorkLists{{lists_[0].data(), lists_[1].data()}, ctr_.data()->len};
  }

  // The first tetrahedron and its four infinite neighbours; every other point is located.
  void start() {
    const std::int32_t I = m_;
    Tet t[5];
    for (int k = 0; k < 4; ++k) t[0].v[k] = first_.v[k];
    for (int k = 0; k < 4; ++k) {  // infinite tetrahedron k + 1 over face k (outward)
      std::int32_t f[3];
      face_of(t[0].v, k, f);
      t[k + 1] = Tet{{f[0], f[1], f[2], I}, {-1, -1, -1, -1}};
    }
    for (int a = 0; a < 5; ++a)  // adjacency by matching faces
      for (int k = 0; k < 4; ++k) {
        std::int32_t f[3];
        face_of(t[a].v, k, f);
        for (int b = 0; b < 5; ++b) {
          const int l = b == a ? -1 : opposite_of_face(t[b].v, f[0], f[1], f[2]);
          if (l >= 0) t[a].n[k] = enc(b, l);
        }
      }
    ex_.from_host(t, 5, tet_.data());
    Counters c{};
    c.used = 5;
    ex_.from_host(&c, 1, ctr_.data());
    const Geo g = g_;
    std::int32_t* loc = loc_.data();
    const Tet* tet = tet_.data();
    Counters* ctr = ctr_.data();
    const std::int32_t a = t[0].v[0], b = t[0].v[1], cc = t[0].v[2], d = t[0].v[3];
    ex_.for_each_index(
        m_, GG_LAMBDA(std::int64_t i) {
          const std::int32_t q = std::int32_t(i);
          if (q == a || q == b || q == cc || q == d) {
            loc[q] = -1;
            return;
          }
          std::int32_t found = -1;
          for (std::int32_t s = 0; s < 5 && found < 0; ++s)
            if (inside_ext(g, tet[s].v, q)) found = s;
          loc[q] = found;
          if (found < 0) atomic_add(&ctr->lost, std::int64_t(1));
        });
    nun_ = ex_.compact_indices(
        m_, GG_LAMBDA(std::int64_t i) { return loc[i] >= 0; }, un_.data());
    check_errors();
  }

  void check_errors() {
    const Counters c = counters();
    if (c.lost || c.errors)
      throw Error(ErrorCode::Internal,
                  "internal error: " + std::to_string(c.lost) + " point(s) could not be located, " +
                      std::to_string(c.errors) + " face(s) lost; please report this input");
  }

  // One batch: relocate and choose, split, flip.
  void batch() {
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

  // Rounds run in chunks with no wait in between: every kernel reads its list length on the
  // executor, and a round that could outgrow the store or the flip log halts itself and the
  // rest of the chunk, for the host to make room; the host reads the counters once per chunk.
  // Once the list is short (the long tail of each batch), one team runs the rounds in a single
  // launch with barriers between the steps.
  static constexpr int kChunk = 4;
  // When a batch's rounds hand their list to the next batch (FlipRound::begin): constants, the
  // same on both executors, so that the run is. Measured on the H100 (performance.md,
  // 2026-11-28, the carried lists): after 4 rounds at 2 048 entries or fewer, grid 100³ took
  // 533 rounds instead of 4 955; after 16, or at 256 entries, it ran 1 000 and 900.
  static constexpr std::int32_t kCarryAfter = 4;
  static constexpr std::int64_t kCarryList = 2048;

  void flip_until_stuck() {
    std::int64_t rounds_here = 0;
    const std::int64_t team_max = 2 * std::int64_t(ex_.team_size());
    while (nact_ > 0) {
      if (max_rounds_ >= 0 && rounds_here >= max_rounds_) {  // (test mode: leave it to phase 2)
        const mesh::WorkLists L = work_lists();
        std::int64_t* len = L.count(round_ + 1);
        ex_.for_each_index(
            1, GG_LAMBDA(std::int64_t) { *len = 0; });
        nact_ = 0;
        break;
      }
      // The flip log: a round records at most one flip per list entry, in practice at most
      // 0.7 (0.3 on average). A new epoch starts where the next round may not fit, and the
      // chunk holds the rounds that should; a round that does not fit halts (make_room).
      const std::int64_t per_round = nact_ - nact_ * 3 / 10;
      if (logged_ + per_round > log_cap_) relocate(false);
      const std::int32_t first = round_ + 1;
      std::int64_t chunk = std::clamp<std::int64_t>(
          (log_cap_ - logged_) / std::max<std::int64_t>(per_round, 1), 1, kChunk);
      if (max_rounds_ >= 0) chunk = std::min<std::int64_t>(chunk, max_rounds_ - rounds_here);
      const bool team = nact_ <= team_max;
      const auto t0 = Clock::now();
      if (team)
        team_rounds(first, team_max, max_rounds_ >= 0 ? chunk : std::int64_t(1) << 30);
      else
        for (std::int64_t k = 0; k < chunk; ++k) launch_round(first + std::int32_t(k), 4 * nact_);
      Counters c = counters();  // one read per chunk
      (team ? ms_team_ : ms_wide_) += ms_since(t0);
      ++(team ? team_calls_ : chunks_);
      std::int32_t last = team ? std::int32_t(c.team_end) - 1 : first + std::int32_t(chunk) - 1;
      const bool carry = c.halt && c.carry;
      if (c.halt) {  // (the halted round did nothing: it runs again after the room is made, or
                     // in the next batch, carried)
        last = std::int32_t(c.halt_round) - 1;
        used_ = c.used;
        logged_ = c.log;
        const Counters need = c;
        c.halt = c.carry = 0;
        c.carries += carry;
        c.need_slots = c.need_log = c.need_list = c.need_ring = 0;
        ex_.from_host(&c, 1, ctr_.data());
        if (!carry) make_room(need);
        c = counters();
      }
      rounds_here += last - round_;
      round_ = last;
      used_ = c.used;
      logged_ = c.log;
      nact_ = c.len[(round_ + 1) & 1];
      if (c.errors) check_errors();
      if (carry) break;  // (nact_ entries wait in the list of round_ + 1)
    }
  }

  FlipRound make_round(std::int32_t round) {
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
  void launch_round(std::int32_t round, std::int64_t bound) {
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

  // Rounds from `round` on in one team, while the list is non-empty and at most `max` long,
  // nothing halts and fewer than `limit` have run; leaves the round it stopped at in the
  // counters (team_end).
  void team_rounds(std::int32_t round, std::int64_t max, std::int64_t limit) {
    const FlipRound R0 = make_round(round);
    Counters* ctr = ctr_.data();
    const std::int32_t stop = std::int32_t(std::min<std::int64_t>(round + limit, INT32_MAX));
    ex_.team(GG_LAMBDA(const Exec::Team& t) {
      FlipRound R = R0;
      std::int32_t r = round;
      for (;;) {
        const std::int64_t n = *R.count();
        if (n == 0 || n > max || r >= stop || ctr->halt) break;
        t.barrier();  // (every thread has read the length before the round's first write)
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
        R.round = ++r;
      }
      if (t.rank == 0) ctr->team_end = r;
    });
  }

  // The prefix of the decisions over the list inside a team (ends with a barrier): each thread
  // sums a contiguous piece, the team scans the sums, and each thread writes its piece's
  // prefixes, so that the order is the list's whatever the team's size. (A team's list is at
  // most two entries a thread, far below the 2^21 each packed count may reach.)
  template <class Team>
  static GG_HD void team_tally(const Team& t, const FlipRound& R, std::int64_t n) {
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

  // Points not yet inserted follow their tetrahedron through this epoch's splits and recorded
  // flips (and, when choose, each tetrahedron then picks one of its points); then a new epoch
  // of records begins.
  void relocate(bool choose) {
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

  // Every face of the tetrahedralisation tested; the vertices of faces that are not locally
  // Delaunay are marked (failed: m + 1 entries). Counts the flat finite tetrahedra (flat_ext)
  // in flat. Returns the number of failed faces. only (per slot, or null: all): the faces of
  // these slots alone (the others' faces are known to be locally Delaunay: DynamicDelaunay3d's
  // slots that no flip or split rewrote).
  std::int64_t find_failed(typename Exec::template Buffer<std::int8_t>& failed, std::int64_t& flat,
                           const std::int8_t* only = nullptr) {
    const Geo g = g_;
    const Mesh M = M_;
    std::int8_t* f = failed.data();
    ex_.fill(f, std::int64_t(m_) + 1, std::int8_t(0));
    Counters* ctr = ctr_.data();
    const Counters c = counters();
    ex_.for_each_index(
        c.used, GG_LAMBDA(std::int64_t t) {
          const Tet T = M.tet[t];
          if (T.v[0] < 0 || (only && !only[t])) return;
          for (int k = 0; k < 4; ++k) {
            const std::int32_t nb = simplex_of(T.n[k]);
            if (nb < t && (!only || only[nb])) continue;  // (each face once, from its higher slot)
            const std::int32_t d = M.tet[nb].v[loc_of(T.n[k])];
            if (!in_sphere_ext(g, T.v, d)) continue;
            atomic_add(&ctr->failed_faces, std::int64_t(1));
            std::int32_t x[3];
            face_of(T.v, k, x);
            for (int j = 0; j < 3; ++j) f[x[j]] = 1;
          }
          if (flat_ext(g, T.v)) atomic_add(&ctr->flat, std::int64_t(1));
        });
    const Counters after = counters();
    flat = after.flat;
    return after.failed_faces;
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

  // Finite tetrahedra in input indices, neighbours among them, left on the executor.
  using Finished = mesh::Compacted<Exec>;
  struct FiniteTets {  // (the store as the output step reads it)
    const Tet* tet;
    const std::int32_t* orig;
    std::int32_t m;
    GG_HD bool live(std::int64_t t) const {
      const std::int32_t* v = tet[t].v;
      return v[0] >= 0 && v[0] != m && v[1] != m && v[2] != m && v[3] != m;
    }
    GG_HD mesh::SimplexRecord<4> get(std::int64_t t) const {
      const Tet T = tet[t];
      mesh::SimplexRecord<4> r;
      for (int k = 0; k < 4; ++k) r.v[k] = orig[T.v[k]], r.n[k] = simplex_of(T.n[k]);
      return r;
    }
  };
  Finished finish(const std::int32_t* orig) {
    const Counters c = counters();
    return mesh::compact_live<4>(ex_, c.used, FiniteTets{tet_.data(), orig, m_});
  }

  void report() {
    const Counters c = counters();
    st_.counters["device_bytes_phase1"] = peak_bytes_;
    st_.counters["slots_used"] = c.used;
    st_.counters["slots_capacity"] = cap_;
    st_.counters["batches"] = batches_;
    st_.counters["max_list"] = c.max_len;
    st_.counters["max_epoch_records"] = c.max_log;
    st_.counters["max_free_slots"] = c.max_free;
    st_.counters["max_splits"] = max_nins_;
    st_.counters["halts"] = c.halts;
    st_.counters["carried_batches"] = c.carries;
    st_.counters["log_capacity"] = log_cap_;
    st_.counters["list_capacity"] = list_cap_;
    st_.counters["ring_capacity"] = ring_cap_;
    st_.counters["flip_rounds"] = c.rounds;
    st_.counters["flips23"] = c.flips23;
    st_.counters["flips32"] = c.flips32;
    st_.counters["unflippable_tests"] = c.unflippable;
    // Where phase 1's time goes (host clock; each part ends with a read of the counters):
    // choosing and splitting, rounds as kernels, rounds in a team.
    st_.counters["us_choose_split"] = std::int64_t(1000 * ms_choose_);
    st_.counters["us_rounds_wide"] = std::int64_t(1000 * ms_wide_);
    st_.counters["us_rounds_team"] = std::int64_t(1000 * ms_team_);
    st_.counters["round_chunks"] = chunks_;
    st_.counters["team_launches"] = team_calls_;
    st_.counters["failed_faces"] = c.failed_faces;
  }

  // state
  Exec& ex_;
  Stats& st_;
  std::int64_t max_rounds_ = -1;
  const ProgressFn& progress_;
  std::int64_t peak_bytes_ = 0;
  Geo g_;
  Mesh M_{};
  mesh::Tetra first_;
  std::int32_t m_ = 0;
  std::int64_t cap_ = 0, nun_ = 0, nact_ = 0, used_ = 0;
  bool phase1_released_ = false;  // release_phase1 ran: grow keeps the store only
  std::int32_t round_ = 0;
  std::int32_t carry_from_ = INT32_MAX;  // (FlipRound::carry_from for the batch's rounds)
  std::int64_t batches_ = 0, max_nins_ = 0;
  std::int64_t log_cap_ = 0, logged_ = 0, list_cap_ = 0, ring_cap_ = 0;
  std::int64_t remaining_ = 0, dead_ = 0, epoch_splits_ = 0;
  std::int32_t epoch_first_new_ = 0;
  double ms_choose_ = 0, ms_wide_ = 0, ms_team_ = 0;
  std::int64_t chunks_ = 0, team_calls_ = 0;
  LeasePool<Exec> pool_;
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

// What both methods start from: the distinct points in curve order (the order of their
// indices; the perturbation follows coordinates, predicates/sos.hpp), their box and the first
// tetrahedron (its centroid is the kernel point).
struct Prepared {
  mesh::SortedPoints<Exec> S;
  mesh::Bounds<3> box;
  mesh::Tetra first;
};
inline Prepared prepare_points(Exec& ex, const double* in, std::int64_t n, bool on_device,
                               Stats& st) {
  const auto t0 = Clock::now();
  auto raw = ex.template alloc<double>(std::size_t(3 * n));
  if (on_device)
    ex.copy(in, 3 * n, raw.data());
  else
    ex.from_host(in, 3 * n, raw.data());
  const mesh::Bounds<3> box = mesh::bounds_in_place<3>(ex, raw.data(), n);
  if (box.bad) mesh::throw_bad_coordinates(box.bad);
  mesh::SortedPoints<Exec> S = mesh::sort_distinct<3>(ex, raw.data(), n, box);
  raw = typename Exec::template Buffer<double>();
  st.counters["points"] = n;
  st.counters["distinct_points"] = S.m;
  st.counters["duplicates"] = S.duplicates;
  if (S.m < 4)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 4 distinct points (" + std::to_string(S.m) +
                    "): a 3D Delaunay triangulation needs 4 points not on one plane");
  const mesh::Tetra first =
      mesh::first_tetrahedron(ex, S.pts.data(), S.m, n, "a 3D Delaunay triangulation", true);
  ex.sync();
  st.phase_ms.push_back({"prepare", ms_since(t0)});
  return Prepared{std::move(S), box, first};
}

// After phase 1: every face tested, and phase 2 (repair.inl) where some are not locally
// Delaunay. The store is then the Delaunay tetrahedralisation of the perturbed points, flat
// tetrahedra included; returns how many of those it holds. Counters and phases into st.
// only: as find_failed's.
inline std::int64_t repair_phase(Exec& ex, Triangulator& T, std::int64_t m,
                                 const ProgressFn& progress, Stats& st,
                                 const std::int8_t* only = nullptr) {
  auto t0 = Clock::now();
  auto failed = ex.template alloc<std::int8_t>(std::size_t(m + 1));
  std::int64_t nflat = 0;
  const std::int64_t nfailed = T.find_failed(failed, nflat, only);
  st.phase_ms.push_back({"find_failed", ms_since(t0)});
  t0 = Clock::now();
  RepairCount rc;
  if (nfailed > 0) {
    if (progress) progress(Delaunay3dProgress{"splay", m, m, 0});
    const std::int64_t used = repair_tets(
        ex, T.g_, T.tet_.data(), T.counters().used, failed.data(),
        [&T](std::int64_t slots) { return T.store_for(slots); }, rc);
    T.set_used(used);
  }
  st.phase_ms.push_back({"splay", ms_since(t0)});
  st.counters["failed_vertices"] = rc.failed_vertices;
  st.counters["stars_built"] = rc.stars_built;
  st.counters["stars_changed"] = rc.stars_changed;
  st.counters["star_insertions"] = rc.insertions;
  st.counters["splay_rounds"] = rc.rounds;
  st.counters["splay_removed"] = rc.removed;
  st.counters["splay_added"] = rc.added;
  st.counters["us_splay_build"] = std::int64_t(1000 * rc.build_ms);
  st.counters["us_splay_rounds"] = std::int64_t(1000 * rc.splay_ms);
  st.counters["us_splay_patch"] = std::int64_t(1000 * rc.patch_ms);
  st.counters["us_splay_check"] = std::int64_t(1000 * rc.check_ms);
  st.counters["us_splay_take"] = std::int64_t(1000 * rc.take_ms);
  return nflat;
}

// The whole pipeline on the executor: prepare, phase 1, phase 2 where phase 1 left failed
// faces, the flat tetrahedra left out, then the finite tetrahedra in input indices (f) with S's
// duplicate map.
template <class Body>
inline void triangulate_core(Exec& ex, const double* in, std::int64_t n, bool on_device,
                             const Delaunay3dOptions& opt, Stats& st, Body body) {
  const std::int64_t max_rounds = ex.tuning().del3d.max_flip_rounds;
  const ProgressFn& progress = opt.progress;
  Prepared P = prepare_points(ex, in, n, on_device, st);
  mesh::SortedPoints<Exec>& S = P.S;
  const mesh::Bounds<3>& box = P.box;
  const mesh::Tetra& first = P.first;
  auto t0 = Clock::now();
  if (opt.method == Method::Digital) {  // DigiDel3D (digital/impl/pipeline.inl)
    auto f = digital_tets(ex, S, box, first, opt.grid, progress, st);
    if (f) {
      t0 = Clock::now();
      body(S, *f);
      st.phase_ms.push_back({"output", ms_since(t0)});
      return;
    }
    // (stars too large to splay here: the incremental method, counter digital_fallback)
  }
  t0 = Clock::now();
  Triangulator T(ex, S.pts.data(), std::int32_t(S.m), first, max_rounds, progress, st);
  T.run();
  st.phase_ms.push_back({"insert_flip", ms_since(t0)});
  const std::int64_t nflat = repair_phase(ex, T, S.m, progress, st);
  t0 = Clock::now();
  std::int64_t flats = 0;
  if (nflat > 0) flats = drop_flats(ex, T.g_, T.tet_.data(), T.counters().used);
  st.counters["flat_tetrahedra"] = flats;
  st.phase_ms.push_back({"drop_flats", ms_since(t0)});
  t0 = Clock::now();
  if (progress) progress(Delaunay3dProgress{"output", S.m, S.m, 0});
  auto f = T.finish(S.orig.data());
  T.report();
  body(S, f);
  st.phase_ms.push_back({"output", ms_since(t0)});
}

// What the output holds beyond the tetrahedra, made on the executor: the vertex map (the last
// tetrahedron of each vertex, copies taking their original's) and the hull facets (faces with no
// neighbour, outward, in tetrahedron order).
struct Extras {
  typename Exec::template Buffer<std::int32_t> vertex_to_simplex, hull_facets;
  std::int64_t num_hull_facets = 0;
};
// dup: the duplicate map (n entries), or null where there is no duplicate.
inline Extras extras(Exec& ex, const std::int32_t* dup, mesh::Compacted<Exec>& f, std::int64_t n) {
  Extras E;
  E.vertex_to_simplex = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* v = E.vertex_to_simplex.data();
  const std::int32_t* tv = f.simplices.data();
  const std::int32_t* nb = f.neighbors.data();
  ex.fill(v, n, std::int32_t(-1));
  ex.for_each_index(
      4 * f.count, GG_LAMBDA(std::int64_t i) { atomic_max(v + tv[i], std::int32_t(i / 4)); });
  if (dup) {
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          if (dup[i] >= 0) v[i] = v[dup[i]];
        });
  }
  auto at = ex.template alloc<std::int32_t>(std::size_t(4 * f.count));
  const std::int64_t nh = ex.compact_indices(
      4 * f.count, GG_LAMBDA(std::int64_t i) { return nb[i] < 0; }, at.data());
  E.num_hull_facets = nh;
  E.hull_facets = ex.template alloc<std::int32_t>(std::size_t(3 * nh + 1));
  std::int32_t* h = E.hull_facets.data();
  const std::int32_t* a = at.data();
  ex.for_each_index(
      nh, GG_LAMBDA(std::int64_t j) {
        const std::int64_t t = a[j] / 4;
        const int k = int(a[j] % 4);
        for (int i = 0; i < 3; ++i) h[3 * j + i] = tv[4 * t + face_vertex(k, i)];
      });
  return E;
}

// The outputs' lengths, checked against the caller's arrays before any is written.
inline void check_into(const Triangulation3dBuffers& into, std::int64_t count, std::int64_t nh,
                       std::int64_t n) {
  deliver::check(into.tetrahedra, 4 * count, "tetrahedra");
  deliver::check(into.neighbors, 4 * count, "neighbors");
  deliver::check(into.duplicate_of, n, "duplicate_of");
  deliver::check(into.vertex_to_simplex, n, "vertex_to_simplex");
  deliver::check(into.hull_facets, 3 * nh, "hull_facets");
}

// The finished tetrahedralisation to host arrays: the caller's (into) or the result's.
inline void to_output(Exec& ex, mesh::SortedPoints<Exec>& S, mesh::Compacted<Exec>& f,
                      std::int64_t n, const Triangulation3dBuffers& into, Output& out) {
  Extras E = extras(ex, S.duplicates ? S.dup.data() : nullptr, f, n);
  check_into(into, f.count, E.num_hull_facets, n);
  out.num_duplicates = S.duplicates;
  out.num_tetrahedra = f.count;
  out.num_hull_facets = E.num_hull_facets;
  deliver::to_host(ex, f.simplices.data(), 4 * f.count, into.tetrahedra, out.tetrahedra);
  deliver::to_host(ex, f.neighbors.data(), 4 * f.count, into.neighbors, out.neighbors);
  if (S.duplicates)
    deliver::to_host(ex, S.dup.data(), n, into.duplicate_of, out.duplicate_of);
  else
    deliver::fill_host(ex, n, std::int32_t(-1), into.duplicate_of, out.duplicate_of);
  deliver::to_host(ex, E.vertex_to_simplex.data(), n, into.vertex_to_simplex,
                   out.vertex_to_simplex);
  deliver::to_host(ex, E.hull_facets.data(), 3 * E.num_hull_facets, into.hull_facets,
                   out.hull_facets);
}

// ... left in executor memory: the caller's arrays (into) or the library's, handed over.
inline void to_device_output(Exec& ex, mesh::SortedPoints<Exec>& S, mesh::Compacted<Exec>& f,
                             std::int64_t n, const Triangulation3dBuffers& into,
                             DeviceOutput& out) {
  Extras E = extras(ex, S.duplicates ? S.dup.data() : nullptr, f, n);
  const std::int64_t nh = E.num_hull_facets;
  check_into(into, f.count, nh, n);
  if (!S.duplicates && !into.duplicate_of)  // no duplicates: the map is all -1
    S.dup = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* dup = S.dup.size() ? S.dup.data() : into.duplicate_of.data;
  if (!S.duplicates) ex.fill(dup, n, std::int32_t(-1));
  auto te = deliver::place(ex, f.simplices, 4 * f.count, into.tetrahedra);
  auto nb = deliver::place(ex, f.neighbors, 4 * f.count, into.neighbors);
  auto dp = deliver::place(ex, S.dup, S.dup.size() ? n : 0, into.duplicate_of);
  auto vs = deliver::place(ex, E.vertex_to_simplex, n, into.vertex_to_simplex);
  auto hf = deliver::place(ex, E.hull_facets, 3 * nh, into.hull_facets);
  ex.sync();  // the caller may read them now (and free them on any stream)
  out.num_tetrahedra = f.count;
  out.num_duplicates = S.duplicates;
  out.num_hull_facets = nh;
  out.tetrahedra = te.own();
  out.neighbors = nb.own();
  out.duplicate_of = dp.own();
  out.vertex_to_simplex = vs.own();
  out.hull_facets = hf.own();
}

// The device memory a tetrahedralisation certainly needs per point: phase 1's store alone
// (7 slots a point at the least, 52 bytes each with the keys, history and split ranks) and the
// points (docs/performance.md has the measured peaks).
constexpr double kLeastBytesPerPoint = 7 * 52 + 40;

inline void triangulate_impl(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                             Output& out, Stats& st) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint,
                                           "a 3D Delaunay tetrahedralisation", "points");
  triangulate_core(ex, xyz, n, false, opt, st,
                   [&](mesh::SortedPoints<Exec>& S, typename Triangulator::Finished& f) {
                     to_output(ex, S, f, n, opt.into, out);
                   });
}

inline void triangulate_device_impl(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                                    DeviceOutput& out, Stats& st) {
  Exec ex(opt);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, st);
  ::gpugeom::detail::require_device_memory(ex, n, kLeastBytesPerPoint - 24,
                                           "a 3D Delaunay tetrahedralisation", "points");
  triangulate_core(ex, xyz, n, true, opt, st,
                   [&](mesh::SortedPoints<Exec>& S, typename Triangulator::Finished& f) {
                     to_device_output(ex, S, f, n, opt.into, out);
                   });
}
