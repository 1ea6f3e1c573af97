// Phase 1's flip round (triangulator.inl), as the kernels and the team see it: the counters on
// the executor, the store's view (Mesh), the ranks that hand out what a flip needs (Tally), the
// side of a recorded flip a point lies on (Side), where a flipped neighbour's face went
// (FaceStore), and the round's steps, one functor (FlipRound). Included inside
// gpugeom::del3d::{cpu,cuda}_impl after geometry.inl.

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
  GG_HD void advance() { ++round; }  // (mesh/flip_schedule.hpp's team rounds)

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
