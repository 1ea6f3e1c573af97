// The triangle store and its two local transformations, included inside
// gpugeom::del2d::{cpu,cuda}_impl after geometry.inl.
//
// Triangle t is the record tri[t]: vertices v[0..2] (counter-clockwise; vertex m is the
// infinity point) and neighbours n[k] = 4 * (triangle across the edge opposite vertex k) + (that
// triangle's local index of its vertex opposite the same edge). Slots are never freed: a split
// keeps the old slot for one child and takes two new ones, a flip rewrites its two slots, so the
// extended triangulation of m + 1 vertices ends with exactly 2m - 2 slots, all in use.

// (The neighbour encoding and the vote keys come from mesh/adjacency.hpp and mesh/priority.hpp.)
// Every triangle has three neighbours, so the encoding is read as unsigned: slots up to 2^30,
// 2^29 points (WideAdjacency).
using Adj = mesh::WideAdjacency;
GG_INLINE std::int32_t enc(std::int32_t s, int k) {
  return Adj::enc(s, k);
}
GG_INLINE std::int32_t simplex_of(std::int32_t e) {
  return Adj::simplex_of(e);
}
GG_INLINE int loc_of(std::int32_t e) {
  return Adj::loc_of(e);
}
using mesh::vote_key;
using mesh::voter_of;

// (atomic_add/min/max/exchange and append_slot come from exec/atomics.hpp.)

// The figures the rounds keep on the executor; the host reads them once per few rounds.
struct Counters {
  std::int64_t flips;       // in the peel rounds (insertion flips are counted by their records)
  std::int64_t len[2];      // work-list lengths: round r reads len[r & 1] (mesh/work_list.hpp)
  std::int64_t exact[2];    // entries the filter left to round r's exact pass: exact[r & 1]
  std::int64_t proposals;   // a checked round's proposals (each flips at most once)
  std::int64_t log;         // flip records since the last relocation
  std::int64_t lost;        // points no triangle claimed (a bug guard: reported, never silent)
  std::int64_t peel_list;   // length of the peel's list
  std::int64_t exact_rest;  // entries listed by a further exact pass (check_round)
  // totals over the flip rounds, for Stats: rounds with a non-empty list, those shorter than
  // kSmallRound, list entries, entries sent to the exact pass
  std::int64_t rounds, small_rounds, listed, exact_total;
  // The round a team stopped at (did not run: mesh::team_rounds).
  std::int64_t team_end;
};

// One triangle in one 32-byte record, one memory sector: the flip rounds are bound by scattered
// accesses, and a triangle's vertices and neighbours then come in one access, and a flip writes
// whole sectors (each scattered 4-byte write costs a sector's traffic).
struct alignas(32) Tri {
  std::int32_t v[3];
  std::int32_t n[3];
  std::int32_t stamp;  // round in which the slot was last flipped
  std::int32_t pair;   // of that flip: 2 * partner slot, + 1 on the proposer's slot
};
// Flip history since the last relocation (mesh/history.hpp): record = {t', n' slots, the new
// diagonal's two vertices, the next records that rewrote t' and n'}, so a point can follow its
// triangle through the flips.
using Hist = mesh::FlipHist;
using FlipLog = mesh::FlipLog<2, 2>;

struct Mesh {
  Tri* tri;
  u64* vote;
  FlipLog log;
  std::int32_t base;  // the first slot's number (0 but in tests: Triangulator::base_)
};

// A proposal's key in round `round` from slot t, and the slot a key names. Priorities scramble
// the slot's rank from the first slot, so that the schedule (and the output's order) does not
// depend on where slot numbering starts.
GG_INLINE u64 key_of(const Mesh& M, std::int32_t round, std::int32_t t) {
  return vote_key(round, t - M.base);
}
GG_INLINE std::int32_t voter(const Mesh& M, u64 key) {
  return voter_of(key) + M.base;
}

// A work-list entry: the slot, and the local index of an edge known to be locally Delaunay
// (the diagonal its flip just made) in bits 30-31 as index + 1 (slots stay below 2^30; the
// entry is read as unsigned, like the neighbour encoding).
GG_INLINE std::int32_t list_entry(std::int32_t slot, int legal) {
  return std::int32_t(std::uint32_t(slot) | (std::uint32_t(legal + 1) << 30));
}
GG_INLINE std::int32_t slot_of(std::int32_t entry) {
  return entry & 0x3FFFFFFF;
}
GG_INLINE int legal_edge_of(std::int32_t entry) {
  return int(std::uint32_t(entry) >> 30) - 1;
}

// A work-list entry's decision: the first illegal edge (0..2), none (-1), or
// mesh::undecided_at(k) when the filter could not decide edge k and the exact pass goes on
// from there.

// atomic_max without the read first, for keys that usually win (each proposal of a fresh
// round): the atomic then needs no reply, and the thread does not wait on a load.
GG_INLINE void vote_max(u64* p, u64 v) {
  cuda::atomic_ref<u64, cuda::thread_scope_device> r(*p);
  (void)r.fetch_max(v, cuda::memory_order_relaxed);
}
// A flip's two slots in the next list (at, at + 1) and its record number (rec): on the GPU one
// thread of each group of converged threads bumps both counters, with no wait between the two
// atomics (the flip kernel waits on memory round trips).
GG_INLINE void append_flip(std::int64_t* next, std::int64_t* log, std::int64_t& at,
                           std::int64_t& rec) {
#ifdef __CUDA_ARCH__
  namespace cg = cooperative_groups;
  const cg::coalesced_group g = cg::coalesced_threads();
  unsigned long long a = 0, b = 0;
  if (g.thread_rank() == 0) {
    a = atomicAdd(reinterpret_cast<unsigned long long*>(next), 2ull * g.size());
    b = atomicAdd(reinterpret_cast<unsigned long long*>(log), (unsigned long long)g.size());
  }
  at = std::int64_t(g.shfl(a, 0)) + 2 * std::int64_t(g.thread_rank());
  rec = std::int64_t(g.shfl(b, 0)) + g.thread_rank();
#else
  at = atomic_add(next, std::int64_t(2));
  rec = atomic_add(log, std::int64_t(1));
#endif
}
// Proposer t asks to flip with nb: its key goes to both triangles, the largest key wins each.
GG_INLINE void propose(const Mesh& M, std::int32_t round, std::int32_t t, std::int32_t nb) {
  const u64 key = key_of(M, round, t);
  vote_max(M.vote + t, key);
  vote_max(M.vote + nb, key);
}

// Splits triangle t at point p into child k = (p, v[k+1], v[k+2]) in slots c[k] = t, base,
// base + 1. split_rank / base give the child slots of neighbours split in the same batch; a
// neighbour not split gets its back pointer from the child that now holds the shared edge.
GG_HD inline void split_triangle(const Mesh& M, std::int32_t t, std::int32_t p, std::int32_t base,
                                 const std::int32_t* split_rank, std::int32_t first_new) {
  const Tri T = M.tri[t];
  const std::int32_t c[3] = {t, base, base + 1};
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const std::int32_t s = c[k], o = T.n[k];
    const std::int32_t nb = simplex_of(o);
    const int j = loc_of(o);
    const std::int32_t r = split_rank[nb];
    std::int32_t across = o;
    if (r >= 0)
      across = enc(j == 0 ? nb : first_new + 2 * r + (j - 1), 0);
    else
      M.tri[nb].n[j] = enc(s, 0);
    M.tri[s] = Tri{{p, T.v[k1], T.v[k2]}, {across, enc(c[k1], 2), enc(c[k2], 1)}, -1, 0};
  }
}

// Flips the edge opposite vertex k of triangle t (phase 1 of 2): quad v[k], v[k+1], d, v[k+2]
// becomes t' = (v[k], v[k+1], d) in slot t and n' = (v[k], d, v[k+2]) in slot nb. T and N are
// the two slots' records, nb = simplex_of(T.n[k]). The four outer neighbour pointers are left as
// they were (phase 2 fixes them once every flip of the round is done). record: the flip's
// global record number, or -1 for none.
GG_HD inline void flip_phase1(const Mesh& M, std::int32_t t, const Tri& T, int k, std::int32_t nb,
                              const Tri& N, std::int32_t round, std::int32_t record) {
  const int j = loc_of(T.n[k]);
  const int k1 = (k + 1) % 3, k2 = (k + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const std::int32_t vk = T.v[k], d = N.v[j];
  const std::int32_t slots[2] = {t, nb};
  Hist h[2];
  if (record >= 0) M.log.load(slots, h);  // (loads before the stores)
  M.tri[t] = Tri{{vk, T.v[k1], d}, {N.n[j1], enc(nb, 2), T.n[k2]}, round, 2 * nb + 1};
  M.tri[nb] = Tri{{vk, d, T.v[k2]}, {N.n[j2], T.n[k1], enc(t, 1)}, round, 2 * t};
  if (record >= 0) M.log.append(record, slots, {vk, d}, h);
}
GG_HD inline void flip_phase1(const Mesh& M, std::int32_t t, int k, std::int32_t round,
                              std::int32_t record) {
  const Tri T = M.tri[t];
  const std::int32_t nb = simplex_of(T.n[k]);
  flip_phase1(M, t, T, k, nb, M.tri[nb], round, record);
}

// Where point q is after the recorded flips, starting from slot L: at each flip, t' or n'
// by the side of the new diagonal it lies on.
struct DiagonalSide {
  const Geo& g;
  std::int32_t q;
  GG_HD int operator()(const std::int32_t* diagonal) const {
    return orient_ext(g, diagonal[0], diagonal[1], q) > 0 ? 1 : 0;
  }
};
GG_HD inline std::int32_t follow_history(const Geo& g, const Mesh& M, std::int32_t L,
                                         std::int32_t q) {
  return M.log.follow(L, DiagonalSide{g, q});
}

// The local index of the vertex opposite the directed edge a -> b in slot s, or -1. (Field by
// field: other threads of the fix phase may be writing the record's neighbour pointers.)
GG_INLINE int opposite_of(const Mesh& M, std::int32_t s, std::int32_t a, std::int32_t b) {
  const std::int32_t* v = M.tri[s].v;
  const std::int32_t v0 = v[0], v1 = v[1], v2 = v[2];
  return v1 == a && v2 == b ? 0 : v2 == a && v0 == b ? 1 : v0 == a && v1 == b ? 2 : -1;
}

// Phase 2 (mesh/flip_fix.hpp) for one outer edge of a flipped pair, whose record X was read
// after phase 1, given the stamp of the neighbour across it. A flipped neighbour's copy of the
// edge is in it or its partner; found by the edge's vertices.
struct PairStore {
  const Mesh& M;
  std::int32_t a, b;  // the edge as the neighbour sees it
  GG_HD void set(std::int32_t s, int i, std::int32_t e) const { M.tri[s].n[i] = e; }
  GG_HD std::int32_t moved(std::int32_t outer) const {
    const std::int32_t s = simplex_of(outer);
    const int i = opposite_of(M, s, a, b);
    if (i >= 0) return enc(s, i);
    const std::int32_t y = M.tri[s].pair >> 1;
    return enc(y, opposite_of(M, y, a, b));
  }
};
GG_HD inline void fix_edge(const Mesh& M, std::int32_t x, const Tri& X, int l, std::int32_t round,
                           std::int32_t stamp) {
  mesh::fix_face<Adj>(PairStore{M, X.v[(l + 2) % 3], X.v[(l + 1) % 3]}, x, l, X.n[l],
                      stamp == round);
}

// Phase 2 for flipped pair t (the proposer's slot) and nb: its four outer edges. The four
// neighbours' stamps are read together first (the writes that follow would otherwise keep
// each read waiting on the one before).
GG_HD inline void fix_pair(const Mesh& M, std::int32_t t, const Tri& T, std::int32_t nb,
                           const Tri& N, std::int32_t round) {
  const std::int32_t st0 = M.tri[simplex_of(T.n[0])].stamp, st2 = M.tri[simplex_of(T.n[2])].stamp;
  const std::int32_t sn0 = M.tri[simplex_of(N.n[0])].stamp, sn1 = M.tri[simplex_of(N.n[1])].stamp;
  fix_edge(M, t, T, 0, round, st0);
  fix_edge(M, t, T, 2, round, st2);
  fix_edge(M, nb, N, 0, round, sn0);
  fix_edge(M, nb, N, 1, round, sn1);
}
