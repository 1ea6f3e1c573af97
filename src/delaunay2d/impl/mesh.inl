// The triangle store and its two local transformations, included inside
// gpugeom::del2d::{cpu,cuda}_impl after geometry.inl.
//
// Triangle t has vertices tv[3t..3t+2] (counter-clockwise; vertex m is the infinity point) and
// neighbours to[3t+k] = 4 * (triangle across the edge opposite vertex k) + (that triangle's
// local index of its vertex opposite the same edge). Slots are never freed: a split keeps the
// old slot for one child and takes two new ones, a flip rewrites its two slots, so the extended
// triangulation of m + 1 vertices ends with exactly 2m - 2 slots, all in use.

GG_INLINE std::int32_t enc(std::int32_t t, int k) {
  return t * 4 + k;
}
GG_INLINE std::int32_t tri_of(std::int32_t e) {
  return e >> 2;
}
GG_INLINE int loc_of(std::int32_t e) {
  return e & 3;
}

// (atomic_add/min/max/exchange and append_slot come from exec/atomics.hpp.)

// Per-round figures, the only values copied back while flipping.
struct Counters {
  std::int64_t flips;  // in the peel rounds (insertion flips are counted by their records)
  std::int64_t next;   // triangles in the next round's work list
  std::int64_t exact;  // edge tests the filter left to the exact pass this round
  std::int64_t log;    // flip records since the last relocation
  std::int64_t lost;   // points no triangle claimed (a bug guard: reported, never silent)
};

struct Mesh {
  std::int32_t* tv;
  std::int32_t* to;
  std::int32_t* stamp;  // round in which the slot was last flipped
  std::int32_t* pair;   // 2 * partner slot + 1 on the proposer's slot of that flip
  std::int32_t* remap;  // 3 per slot: where an old edge of a flipped slot went
  u64* vote;
  std::int32_t* mark;  // round in which the slot was put on the next work list
  // Flip history since the last relocation (thesis 5.3.4): record r = {t', n' slots, the new
  // diagonal's two vertices, the next record that rewrote the t' slot, same for n'}, and per
  // slot its first and latest record, so a point can follow its triangle through the flips.
  std::int32_t* rec;
  std::int32_t* slot_first;
  std::int32_t* slot_last;
};

// A work-list entry: the slot, and the local index of an edge known to be locally Delaunay
// (the diagonal its flip just made) in bits 29-30 as index + 1 (slots stay below 2^29).
GG_INLINE std::int32_t list_entry(std::int32_t slot, int legal) {
  return slot | ((legal + 1) << 29);
}
GG_INLINE std::int32_t slot_of(std::int32_t entry) {
  return entry & 0x1FFFFFFF;
}
GG_INLINE int legal_edge_of(std::int32_t entry) {
  return ((entry >> 29) & 3) - 1;
}

// The first edge a triangle's tests found illegal (+1), or -1.
GG_INLINE int first_illegal(const std::int8_t* dec) {
  return dec[0] > 0 ? 0 : dec[1] > 0 ? 1 : dec[2] > 0 ? 2 : -1;
}
// A flip proposal's key: newer rounds win over stale keys, then a fixed scramble of the slot.
GG_INLINE u64 vote_key(std::int32_t round, std::int32_t t) {
  return (u64(round) << 32) | u64(scatter(std::uint32_t(t)));
}

// Splits triangle t at point p into child k = (p, v[k+1], v[k+2]) in slots c[k] = t, base,
// base + 1. split_rank / base give the child slots of neighbours split in the same batch; a
// neighbour not split gets its back pointer from the child that now holds the shared edge.
GG_HD inline void split_triangle(const Mesh& M, std::int32_t t, std::int32_t p, std::int32_t base,
                                 const std::int32_t* split_rank, std::int32_t first_new) {
  const std::int32_t v[3] = {M.tv[3 * t], M.tv[3 * t + 1], M.tv[3 * t + 2]};
  const std::int32_t o[3] = {M.to[3 * t], M.to[3 * t + 1], M.to[3 * t + 2]};
  const std::int32_t c[3] = {t, base, base + 1};
  for (int k = 0; k < 3; ++k) {
    const std::int32_t s = c[k];
    M.tv[3 * s] = p;
    M.tv[3 * s + 1] = v[(k + 1) % 3];
    M.tv[3 * s + 2] = v[(k + 2) % 3];
    M.to[3 * s + 1] = enc(c[(k + 1) % 3], 2);
    M.to[3 * s + 2] = enc(c[(k + 2) % 3], 1);
    const std::int32_t nb = tri_of(o[k]);
    const int j = loc_of(o[k]);
    const std::int32_t r = split_rank[nb];
    if (r >= 0) {
      const std::int32_t ns = j == 0 ? nb : first_new + 2 * r + (j - 1);
      M.to[3 * s] = enc(ns, 0);
    } else {
      M.to[3 * s] = o[k];
      M.to[3 * nb + j] = enc(s, 0);
    }
  }
}

// Flips the edge opposite vertex k of triangle t (phase 1 of 2): quad v[k], v[k+1], d, v[k+2]
// becomes t' = (v[k], v[k+1], d) in slot t and n' = (v[k], d, v[k+2]) in slot nb. The four
// outer neighbour pointers are left as they were (phase 2 fixes them, once every flip of the
// round has recorded where its old edges went).
GG_HD inline void flip_phase1(const Mesh& M, std::int32_t t, int k, std::int32_t round,
                              std::int32_t record) {
  const std::int32_t e = M.to[3 * t + k];
  const std::int32_t nb = tri_of(e);
  const int j = loc_of(e);
  const int k1 = (k + 1) % 3, k2 = (k + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const std::int32_t vk = M.tv[3 * t + k], v1 = M.tv[3 * t + k1], v2 = M.tv[3 * t + k2];
  const std::int32_t d = M.tv[3 * nb + j];
  const std::int32_t tA = M.to[3 * t + k2], tD = M.to[3 * t + k1];
  const std::int32_t nB = M.to[3 * nb + j1], nC = M.to[3 * nb + j2];
  M.tv[3 * t] = vk, M.tv[3 * t + 1] = v1, M.tv[3 * t + 2] = d;
  M.to[3 * t] = nB, M.to[3 * t + 1] = enc(nb, 2), M.to[3 * t + 2] = tA;
  M.tv[3 * nb] = vk, M.tv[3 * nb + 1] = d, M.tv[3 * nb + 2] = v2;
  M.to[3 * nb] = nC, M.to[3 * nb + 1] = tD, M.to[3 * nb + 2] = enc(t, 1);
  M.remap[3 * t + k2] = enc(t, 2);
  M.remap[3 * t + k1] = enc(nb, 1);
  M.remap[3 * nb + j1] = enc(t, 0);
  M.remap[3 * nb + j2] = enc(nb, 0);
  M.stamp[t] = round, M.stamp[nb] = round;
  M.pair[t] = 2 * nb + 1, M.pair[nb] = 2 * t;
  if (record < 0) return;
  std::int32_t* r = M.rec + 6 * std::int64_t(record);
  r[0] = t, r[1] = nb, r[2] = vk, r[3] = d, r[4] = -1, r[5] = -1;
  for (int side = 0; side < 2; ++side) {
    const std::int32_t s = side ? nb : t;
    const std::int32_t prev = M.slot_last[s];
    if (prev >= 0)
      M.rec[6 * std::int64_t(prev) + 4 + (M.rec[6 * std::int64_t(prev)] == s ? 0 : 1)] = record;
    else
      M.slot_first[s] = record;
    M.slot_last[s] = record;
  }
}

// Where point q is after the recorded flips, starting from slot L.
GG_HD inline std::int32_t follow_history(const Geo& g, const Mesh& M, std::int32_t L,
                                         std::int32_t q) {
  for (std::int32_t r = M.slot_first[L]; r >= 0;) {
    const std::int32_t* x = M.rec + 6 * std::int64_t(r);
    const int side = orient_ext(g, x[2], x[3], q) > 0 ? 1 : 0;
    L = x[side];
    r = x[4 + side];
  }
  return L;
}

// Phase 2 for one outer edge (slot x, local l) of a flipped pair: follow the neighbour to
// where its edge went if it flipped too, else point the neighbour back at x.
GG_HD inline void fix_edge(const Mesh& M, std::int32_t x, int l, std::int32_t round) {
  const std::int32_t old = M.to[3 * x + l];
  const std::int32_t s = tri_of(old);
  const int i = loc_of(old);
  if (M.stamp[s] == round)
    M.to[3 * x + l] = M.remap[3 * s + i];
  else
    M.to[3 * s + i] = enc(x, l);
}
