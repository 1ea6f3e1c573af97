// The mesh refinement keeps from round to round, and its two edits: inserting a round's points
// (subsegment splits and new points, in triangles no two of them share) and restoring the
// constrained Delaunay property by parallel flips. Included inside
// gpugeom::refine::{cpu,cuda}_impl after rounds.inl.
//
// Triangles are flat arrays: tri[3t + k] the vertices counter-clockwise, nbr[3t + k] the triangle
// across the edge opposite vertex k (-1 on the boundary), seg[3t + k] its subsegment (-1 off
// segments; sub_base gives each subsegment's base segment). A triangle an edit writes is marked
// dirty: the next round judges only the dirty triangles (and those still bad), since a triangle
// found good stays good until it is rewritten. An edit writes its triangles in two passes, because
// the triangles beside it may be edited at the same time: the first writes each edited triangle, an
// outer neighbour x kept as the code kUnresolved(x); the second resolves every such code: x
// unedited, its back link is written; x edited this pass (stamp == epoch), the piece of x that
// holds the edge is found among x and its family (the slots its old area went to). No two edits
// write one triangle, so the result never depends on timing. Slots are reused and appended in item
// order: the same input gives the same arrays.
//
// The flips are Lawson's with the exact in-circle test (flip only when strictly inside, never a
// segment): every illegal edge proposes its flip, keyed by its lower half-edge and its list
// position; a flip whose key is the least on both its triangles is done. The least key overall
// always flips, so every pass makes progress; a flip makes the quadrilateral's four outer edges
// the next pass's list, and a proposal that lost is listed again. Starting from a constrained
// Delaunay triangulation with points inserted, only the inserted points' link edges can be
// illegal, so the lists stay as short as the work.

GG_HD inline std::int32_t kUnresolved(std::int32_t x) {
  return -2 - x;
}

struct Kept {
  Buf<double> xy, attr;             // 2 cap_p; cap_t (region index + 1, or empty)
  Buf<std::int32_t> on_base;        // cap_p: the base segment a split vertex lies on, else -1
  Buf<std::int32_t> tri, nbr, seg;  // 3 cap_t
  Buf<std::int8_t> dirty;           // cap_t: judge it next round
  Buf<std::int32_t> sub_base;       // cap_s: per subsegment, its base segment
  Buf<std::int32_t> stamp, fam;     // cap_t, 2 cap_t: the edit pass that last wrote a triangle
  Buf<std::uint64_t> claim;         // cap_t: flip claims, all ones between passes
  Buf<std::int64_t> broken;         // 1: edges found without a twin (a bug), read once at the end
  std::int64_t np = 0, nt = 0, nsub = 0, cap_p = 0, cap_t = 0, cap_s = 0;
  std::int32_t epoch = 0;
  bool has_attr = false;

  RoundMesh view() const {
    return {xy.data(), tri.data(), nbr.data(), seg.data(), has_attr ? attr.data() : nullptr, nt};
  }
};

template <class T>
inline void regrow(Exec& ex, Buf<T>& b, std::size_t used, std::size_t cap, bool fill, T v) {
  Buf<T> nb = ex.template alloc<T>(std::max<std::size_t>(cap, 1));
  if (used) ex.copy(b.data(), std::int64_t(used), nb.data());
  if (fill && cap > used) ex.fill(nb.data() + used, std::int64_t(cap - used), v);
  b = std::move(nb);
}

// Room for need_p points, need_t triangles and need_s subsegments (by half again, so that
// growth is rare).
inline void reserve(Exec& ex, Kept& K, std::int64_t need_p, std::int64_t need_t,
                    std::int64_t need_s) {
  if (need_s > K.cap_s) {
    const std::int64_t cap = std::max(need_s, K.cap_s + K.cap_s / 2 + 1024);
    regrow(ex, K.sub_base, std::size_t(K.nsub), std::size_t(cap), false, std::int32_t(0));
    K.cap_s = cap;
  }
  if (need_p > K.cap_p) {
    const std::int64_t cap = std::max(need_p, K.cap_p + K.cap_p / 2 + 1024);
    regrow(ex, K.xy, 2 * std::size_t(K.np), 2 * std::size_t(cap), false, 0.0);
    regrow(ex, K.on_base, std::size_t(K.np), std::size_t(cap), false, std::int32_t(0));
    K.cap_p = cap;
  }
  if (need_t > K.cap_t) {
    const std::int64_t cap = std::max(need_t, K.cap_t + K.cap_t / 2 + 1024);
    const std::size_t u = std::size_t(K.nt), c = std::size_t(cap);
    regrow(ex, K.tri, 3 * u, 3 * c, false, std::int32_t(0));
    regrow(ex, K.nbr, 3 * u, 3 * c, false, std::int32_t(0));
    regrow(ex, K.seg, 3 * u, 3 * c, false, std::int32_t(0));
    if (K.has_attr) regrow(ex, K.attr, u, c, false, 0.0);
    regrow(ex, K.dirty, u, c, true, std::int8_t(0));
    regrow(ex, K.stamp, u, c, true, std::int32_t(-1));
    regrow(ex, K.fam, 2 * u, 2 * c, false, std::int32_t(-1));
    regrow(ex, K.claim, u, c, true, ~std::uint64_t(0));
    K.cap_t = cap;
  }
}

// The kept mesh from a constrained triangulation in the executor's memory (its marks base
// segment indices), with the n points: each marked edge becomes a subsegment (numbered in the
// order of the half-edges of the triangle with the lower index), and every triangle is dirty.
inline Kept kept_from(Exec& ex, const double* xy, std::int64_t n,
                      const DeviceConstrainedTriangulation2d& dr) {
  Kept K;
  K.has_attr = bool(dr.attribute);
  K.broken = ex.template alloc<std::int64_t>(1);
  ex.fill(K.broken.data(), 1, std::int64_t(0));
  const std::int64_t nt = dr.num_triangles, ne = 3 * nt;
  const std::int32_t *G = dr.segment_of.get(), *N = dr.neighbors.get();
  auto index = ex.template alloc<std::int32_t>(std::size_t(ne) + 1);
  std::int32_t* I = index.data();
  ex.exclusive_scan_of(
      ne + 1,
      GG_LAMBDA(std::int64_t e)->std::int32_t {
        return e < ne && G[e] >= 0 && (N[e] < 0 || e / 3 < N[e]) ? 1 : 0;
      },
      I);
  std::int32_t ns = 0;
  ex.to_host(I + ne, 1, &ns);
  reserve(ex, K, n, nt, ns);
  K.np = n, K.nt = nt, K.nsub = ns;
  ex.copy(xy, 2 * n, K.xy.data());
  ex.fill(K.on_base.data(), n, std::int32_t(-1));
  ex.copy(dr.triangles.get(), 3 * nt, K.tri.data());
  ex.copy(N, 3 * nt, K.nbr.data());
  if (K.has_attr) ex.copy(dr.attribute.get(), nt, K.attr.data());
  ex.fill(K.stamp.data(), nt, std::int32_t(-1));
  ex.fill(K.claim.data(), nt, ~std::uint64_t(0));
  ex.fill(K.dirty.data(), nt, std::int8_t(1));
  std::int32_t *S = K.seg.data(), *SB = K.sub_base.data();
  ex.for_each_index(
      ne, GG_LAMBDA(std::int64_t e) {
        const bool first = G[e] >= 0 && (N[e] < 0 || e / 3 < N[e]);
        S[e] = first ? I[e] : -1;
        if (first) SB[I[e]] = G[e];
      });
  // The other half of each marked inner edge takes its twin's index.
  ex.for_each_index(
      ne, GG_LAMBDA(std::int64_t e) {
        const std::int64_t t = e / 3;
        if (G[e] < 0 || N[e] < 0 || t < N[e]) return;
        const std::int64_t o = N[e];
        for (int j = 0; j < 3; ++j)
          if (N[3 * o + j] == t) S[e] = I[3 * o + j];
      });
  return K;
}

// Device-side view of the kept mesh for the edit kernels.
struct EditView {
  double* xy;
  double* attr;
  std::int32_t *on_base, *tri, *nbr, *seg, *stamp, *fam;
  std::int8_t* dirty;
  std::uint64_t* claim;
};
inline EditView edit_view(Kept& K) {
  EditView v;
  v.xy = K.xy.data();
  v.attr = K.has_attr ? K.attr.data() : nullptr;
  v.on_base = K.on_base.data(), v.tri = K.tri.data(), v.nbr = K.nbr.data();
  v.seg = K.seg.data(), v.stamp = K.stamp.data(), v.fam = K.fam.data();
  v.dirty = K.dirty.data();
  v.claim = K.claim.data();
  return v;
}

GG_HD inline void put(const EditView& V, std::int32_t t, std::int32_t v0, std::int32_t v1,
                      std::int32_t v2, std::int32_t n0, std::int32_t n1, std::int32_t n2,
                      std::int32_t g0, std::int32_t g1, std::int32_t g2) {
  std::int32_t* T = V.tri + 3 * std::int64_t(t);
  std::int32_t* N = V.nbr + 3 * std::int64_t(t);
  std::int32_t* G = V.seg + 3 * std::int64_t(t);
  T[0] = v0, T[1] = v1, T[2] = v2;
  N[0] = n0, N[1] = n1, N[2] = n2;
  G[0] = g0, G[1] = g1, G[2] = g2;
  V.dirty[t] = 1;
}

// An outer neighbour, kept unresolved for the second pass (the boundary stays -1).
GG_HD inline std::int32_t outer(std::int32_t x) {
  return x < 0 ? -1 : kUnresolved(x);
}

// The slot of u whose edge is (a, b) going counter-clockwise in u, or -1.
GG_HD inline int slot_of_edge(const std::int32_t* tri, std::int32_t u, std::int32_t a,
                              std::int32_t b) {
  const std::int32_t* U = tri + 3 * std::int64_t(u);
  for (int j = 0; j < 3; ++j)
    if (U[(j + 1) % 3] == a && U[(j + 2) % 3] == b) return j;
  return -1;
}

// Splits the edge opposite vertex k of t (and its twin in the neighbour u, if any) at point m:
// t keeps (c, a, m), t2 gets (c, m, b); u keeps (d, b, m), u2 gets (d, m, a). The half (a, m)
// takes the mark ga, the half (m, b) the mark gb.
GG_HD inline void split_edge(const EditView& V, std::int32_t t, int k, std::int32_t m,
                             std::int32_t ga, std::int32_t gb, std::int32_t t2, std::int32_t u2,
                             std::int32_t epoch) {
  const std::int64_t b3 = 3 * std::int64_t(t);
  const std::int32_t c = V.tri[b3 + k], a = V.tri[b3 + (k + 1) % 3], b = V.tri[b3 + (k + 2) % 3];
  const std::int32_t u = V.nbr[b3 + k];
  // t's outer edges: (c, a) opposite b, (b, c) opposite a.
  const std::int32_t n_ca = V.nbr[b3 + (k + 2) % 3], g_ca = V.seg[b3 + (k + 2) % 3];
  const std::int32_t n_bc = V.nbr[b3 + (k + 1) % 3], g_bc = V.seg[b3 + (k + 1) % 3];
  if (u >= 0) {
    const std::int64_t u3 = 3 * std::int64_t(u);
    const int ku = slot_facing(V.nbr, u, t);
    const std::int32_t d = V.tri[u3 + ku];
    // u = (d, b, a): (d, b) opposite a, (a, d) opposite b.
    const std::int32_t n_db = V.nbr[u3 + (ku + 2) % 3], g_db = V.seg[u3 + (ku + 2) % 3];
    const std::int32_t n_ad = V.nbr[u3 + (ku + 1) % 3], g_ad = V.seg[u3 + (ku + 1) % 3];
    put(V, u, d, b, m, t2, u2, outer(n_db), gb, -1, g_db);
    put(V, u2, d, m, a, t, outer(n_ad), u, ga, g_ad, -1);
    if (V.attr) V.attr[u2] = V.attr[u];
    V.stamp[u] = V.stamp[u2] = epoch;
    V.fam[2 * std::int64_t(u)] = u2, V.fam[2 * std::int64_t(u) + 1] = -1;
  }
  put(V, t, c, a, m, u >= 0 ? u2 : -1, t2, outer(n_ca), ga, -1, g_ca);
  put(V, t2, c, m, b, u >= 0 ? u : -1, outer(n_bc), t, gb, g_bc, -1);
  if (V.attr) V.attr[t2] = V.attr[t];
  V.stamp[t] = V.stamp[t2] = epoch;
  V.fam[2 * std::int64_t(t)] = t2, V.fam[2 * std::int64_t(t) + 1] = -1;
}

// Splits t at the point m strictly inside it: piece i is t with vertex i replaced by m (piece 0
// in t, pieces 1 and 2 in slots s1, s2).
GG_HD inline void split_triangle(const EditView& V, std::int32_t t, std::int32_t m, std::int32_t s1,
                                 std::int32_t s2, std::int32_t epoch) {
  const std::int64_t b3 = 3 * std::int64_t(t);
  std::int32_t v[3], n[3], g[3];
  for (int k = 0; k < 3; ++k) v[k] = V.tri[b3 + k], n[k] = V.nbr[b3 + k], g[k] = V.seg[b3 + k];
  const std::int32_t p[3] = {t, s1, s2};
  put(V, t, m, v[1], v[2], outer(n[0]), s1, s2, g[0], -1, -1);
  put(V, s1, v[0], m, v[2], t, outer(n[1]), s2, -1, g[1], -1);
  put(V, s2, v[0], v[1], m, t, s1, outer(n[2]), -1, -1, g[2]);
  for (int i = 0; i < 3; ++i) {
    if (V.attr && i) V.attr[p[i]] = V.attr[t];
    V.stamp[p[i]] = epoch;
  }
  V.fam[2 * std::int64_t(t)] = s1, V.fam[2 * std::int64_t(t) + 1] = s2;
}

// The second pass for triangle p: its unresolved outer neighbours linked both ways. Returns
// false when an edge has no twin (a broken mesh: counted by the caller).
GG_HD inline bool resolve(const EditView& V, std::int32_t p, std::int32_t epoch) {
  bool ok = true;
  for (int s = 0; s < 3; ++s) {
    const std::int64_t e = 3 * std::int64_t(p) + s;
    const std::int32_t code = V.nbr[e];
    if (code > -2) continue;
    const std::int32_t x = -2 - code;
    const std::int32_t a = V.tri[3 * std::int64_t(p) + (s + 1) % 3];
    const std::int32_t b = V.tri[3 * std::int64_t(p) + (s + 2) % 3];
    std::int32_t found = -1;
    if (V.stamp[x] == epoch) {
      const std::int32_t cand[3] = {x, V.fam[2 * std::int64_t(x)], V.fam[2 * std::int64_t(x) + 1]};
      for (int i = 0; i < 3 && found < 0; ++i)
        if (cand[i] >= 0 && slot_of_edge(V.tri, cand[i], b, a) >= 0) found = cand[i];
    } else {
      const int j = slot_of_edge(V.tri, x, b, a);
      if (j >= 0) {
        V.nbr[3 * std::int64_t(x) + j] = p;
        found = x;
      }
    }
    V.nbr[e] = found;
    ok = ok && found >= 0;
  }
  return ok;
}

// Lawson's flips from the half-edges in `list` (count entries, -1 skipped) until every edge is
// locally constrained Delaunay. Returns the flips done and counts the passes made (edges found
// without twins go to K.broken).
inline std::int64_t flip_until_legal(Exec& ex, Kept& K, Buf<std::int32_t> list, std::int64_t count,
                                     std::int64_t& passes) {
  std::int64_t flips = 0;
  while (count > 0) {
    ++passes;
    const EditView V = edit_view(K);
    const std::int32_t epoch = ++K.epoch;
    auto key = ex.template alloc<std::uint64_t>(std::size_t(count));
    auto twin = ex.template alloc<std::int32_t>(std::size_t(count));
    auto won = ex.template alloc<std::int8_t>(std::size_t(count));
    std::uint64_t* KEY = key.data();
    std::int32_t *L = list.data(), *TW = twin.data();
    std::int8_t* W = won.data();
    std::int64_t* BAD = K.broken.data();
    constexpr std::uint64_t kNone = ~std::uint64_t(0);
    // Proposals: an illegal edge claims its two triangles.
    ex.for_each_index(
        count, GG_LAMBDA(std::int64_t i) {
          KEY[i] = kNone;
          W[i] = 0;
          const std::int32_t e = L[i];
          if (e < 0) return;
          const std::int32_t t = e / 3, u = V.nbr[e];
          if (u < 0 || V.seg[e] >= 0) return;
          const std::int64_t u3 = 3 * std::int64_t(u);
          const int ku = slot_facing(V.nbr, u, t);
          if (ku == 3) {
            atomic_add(BAD, std::int64_t(1));
            return;
          }
          const std::int32_t* T = V.tri + 3 * std::int64_t(t);
          double s[pred::kIncircleScratch];
          if (pred::incircle(V.xy + 2 * std::int64_t(T[0]), V.xy + 2 * std::int64_t(T[1]),
                             V.xy + 2 * std::int64_t(T[2]), V.xy + 2 * std::int64_t(V.tri[u3 + ku]),
                             s) <= 0)
            return;
          const std::int64_t he = std::min<std::int64_t>(e, u3 + ku);
          KEY[i] = std::uint64_t(he) << 32 | std::uint64_t(i);
          TW[i] = std::int32_t(u3 + ku);
          atomic_min(V.claim + t, KEY[i]);
          atomic_min(V.claim + u, KEY[i]);
        });
    // The flips whose key holds both triangles.
    ex.for_each_index(
        count, GG_LAMBDA(std::int64_t i) {
          if (KEY[i] == kNone) return;
          const std::int32_t e = L[i], t = e / 3, k = e % 3;
          const std::int32_t f = TW[i], u = f / 3, ku = f % 3;
          if (V.claim[t] != KEY[i] || V.claim[u] != KEY[i]) return;
          W[i] = 1;
          const std::int64_t t3 = 3 * std::int64_t(t), u3 = 3 * std::int64_t(u);
          const std::int32_t c = V.tri[t3 + k], a = V.tri[t3 + (k + 1) % 3];
          const std::int32_t b = V.tri[t3 + (k + 2) % 3], d = V.tri[u3 + ku];
          // t = (c, a, b), u = (d, b, a); t' = (c, a, d), u' = (d, b, c).
          const std::int32_t n_ca = V.nbr[t3 + (k + 2) % 3], g_ca = V.seg[t3 + (k + 2) % 3];
          const std::int32_t n_bc = V.nbr[t3 + (k + 1) % 3], g_bc = V.seg[t3 + (k + 1) % 3];
          const std::int32_t n_db = V.nbr[u3 + (ku + 2) % 3], g_db = V.seg[u3 + (ku + 2) % 3];
          const std::int32_t n_ad = V.nbr[u3 + (ku + 1) % 3], g_ad = V.seg[u3 + (ku + 1) % 3];
          put(V, t, c, a, d, outer(n_ad), u, outer(n_ca), g_ad, -1, g_ca);
          put(V, u, d, b, c, outer(n_bc), t, outer(n_db), g_bc, -1, g_db);
          V.stamp[t] = V.stamp[u] = epoch;
          V.fam[2 * std::int64_t(t)] = u, V.fam[2 * std::int64_t(t) + 1] = -1;
          V.fam[2 * std::int64_t(u)] = t, V.fam[2 * std::int64_t(u) + 1] = -1;
        });
    ex.for_each_index(
        count, GG_LAMBDA(std::int64_t i) {
          if (!W[i]) return;
          const std::int32_t t = L[i] / 3, u = TW[i] / 3;
          if (!resolve(V, t, epoch)) atomic_add(BAD, std::int64_t(1));
          if (!resolve(V, u, epoch)) atomic_add(BAD, std::int64_t(1));
        });
    // The next list: a flip's four outer edges, a lost proposal again; claims cleared. The scan
    // carries the flips above bit 40 and the list positions below it (one read per pass).
    constexpr std::int64_t kWin = std::int64_t(1) << 40, kPos = kWin - 1;
    auto offs = ex.template alloc<std::int64_t>(std::size_t(count) + 1);
    std::int64_t* OF = offs.data();
    ex.exclusive_scan_of(
        count + 1,
        GG_LAMBDA(std::int64_t i)->std::int64_t {
          return i == count || KEY[i] == kNone ? 0 : (W[i] ? kWin + 4 : 1);
        },
        OF);
    std::int64_t total = 0;
    ex.to_host(OF + count, 1, &total);
    const std::int64_t next = total & kPos;
    flips += total >> 40;
    Buf<std::int32_t> nl =
        ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(next, 1)));
    std::int32_t* NL = nl.data();
    ex.for_each_index(
        count, GG_LAMBDA(std::int64_t i) {
          if (KEY[i] == kNone) return;
          const std::int32_t t = L[i] / 3, u = TW[i] / 3;
          V.claim[t] = kNone;
          V.claim[u] = kNone;
          const std::int64_t o = OF[i] & kPos;
          if (!W[i]) {
            NL[o] = L[i];
            return;
          }
          // t' = (c, a, d): slots 0 (a, d) and 2 (c, a); u' = (d, b, c): slots 0 and 2.
          NL[o] = 3 * t, NL[o + 1] = 3 * t + 2, NL[o + 2] = 3 * u, NL[o + 3] = 3 * u + 2;
        });
    list = std::move(nl);
    count = next;
  }
  return flips;
}

// Inserts a round's first nsw chosen splits and npw chosen points (choose()): the splits' points
// are appended first, then the new points; each split edge's second halves and each point's two
// new pieces are appended in item order. split_tris: the triangles the nsw splits add, or -1 to
// count them here (a read). Returns the link edges to flip from (4 per item, -1 where none),
// their number in `count`.
// A split keeps its subsegment's index for the half (a, m) and gives the half (m, b) the next
// new index.
inline Buf<std::int32_t> insert_chosen(Exec& ex, Kept& K, const Choice& ch, const Decisions& d,
                                       std::int64_t nsw, std::int64_t npw, std::int64_t split_tris,
                                       std::int64_t& count) {
  const std::int64_t np = K.np, nt = K.nt, nsub = K.nsub;
  // New triangles per split: two with a triangle on each side of it, one on the boundary.
  auto toff = ex.template alloc<std::int64_t>(std::size_t(nsw) + 1);
  std::int64_t* TO = toff.data();
  {
    const std::int32_t *SW = ch.splits.data(), *H = d.half.data(), *N = K.nbr.data();
    ex.exclusive_scan_of(
        nsw + 1,
        GG_LAMBDA(std::int64_t i)->std::int64_t {
          return i == nsw ? 0 : (N[H[SW[i]]] >= 0 ? 2 : 1);
        },
        TO);
  }
  if (split_tris < 0) ex.to_host(TO + nsw, 1, &split_tris);
  reserve(ex, K, np + nsw + npw, nt + split_tris + 2 * npw, nsub + nsw);
  const EditView V = edit_view(K);
  const std::int32_t epoch = ++K.epoch;
  count = 4 * (nsw + npw);
  auto list = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(count, 1)));
  std::int32_t* LI = list.data();
  {
    const std::int32_t *SW = ch.splits.data(), *H = d.half.data();
    std::int32_t* SB = K.sub_base.data();
    const double* M = ch.at.data();
    ex.for_each_index(
        nsw, GG_LAMBDA(std::int64_t i) {
          const std::int32_t j = SW[i], e = H[j], t = e / 3, k = e % 3;
          const std::int32_t v = std::int32_t(np + i);
          V.xy[2 * std::int64_t(v)] = M[2 * j];
          V.xy[2 * std::int64_t(v) + 1] = M[2 * j + 1];
          V.on_base[v] = SB[j];
          const std::int32_t J = std::int32_t(nsub + i);
          SB[J] = SB[j];
          const std::int32_t u = V.nbr[e], t2 = std::int32_t(nt + TO[i]);
          const std::int32_t u2 = u >= 0 ? t2 + 1 : -1;
          split_edge(V, t, k, v, j, J, t2, u2, epoch);
          std::int32_t* o = LI + 4 * i;
          o[0] = 3 * t + 2, o[1] = 3 * t2 + 1;
          o[2] = u >= 0 ? 3 * u + 2 : -1, o[3] = u >= 0 ? 3 * u2 + 1 : -1;
        });
  }
  {
    const std::int32_t *PW = ch.points.data(), *CA = ch.cand, *LD = d.land.data();
    const double* NP = d.point.data();
    ex.for_each_index(
        npw, GG_LAMBDA(std::int64_t i) {
          const std::int32_t w = CA[PW[i]], t = LD[w];
          const std::int32_t v = std::int32_t(np + nsw + i);
          const double* q = NP + 2 * std::int64_t(w);
          V.xy[2 * std::int64_t(v)] = q[0];
          V.xy[2 * std::int64_t(v) + 1] = q[1];
          V.on_base[v] = -1;
          const std::int32_t s1 = std::int32_t(nt + split_tris + 2 * i), s2 = s1 + 1;
          double sc[pred::kOrient2dScratch];
          int on = -1;
          for (int k = 0; k < 3; ++k) {
            const double* a = V.xy + 2 * std::int64_t(V.tri[3 * std::int64_t(t) + (k + 1) % 3]);
            const double* b = V.xy + 2 * std::int64_t(V.tri[3 * std::int64_t(t) + (k + 2) % 3]);
            if (pred::orient2d(a, b, q, sc) == 0) on = k;
          }
          std::int32_t* o = LI + 4 * (nsw + i);
          if (on < 0) {
            split_triangle(V, t, v, s1, s2, epoch);
            o[0] = 3 * t, o[1] = 3 * s1 + 1, o[2] = 3 * s2 + 2, o[3] = -1;
          } else {
            const std::int32_t u = V.nbr[3 * std::int64_t(t) + on];
            split_edge(V, t, on, v, -1, -1, s1, s2, epoch);
            o[0] = 3 * t + 2, o[1] = 3 * s1 + 1, o[2] = 3 * u + 2, o[3] = 3 * s2 + 1;
          }
        });
  }
  // Every piece's outer neighbours linked (the list names each piece once, by its outer edge).
  {
    std::int64_t* BAD = K.broken.data();
    ex.for_each_index(
        count, GG_LAMBDA(std::int64_t i) {
          if (LI[i] >= 0 && !resolve(V, LI[i] / 3, epoch)) atomic_add(BAD, std::int64_t(1));
        });
  }
  K.nsub = nsub + nsw;
  K.np = np + nsw + npw;
  K.nt = nt + split_tris + 2 * npw;
  return list;
}
