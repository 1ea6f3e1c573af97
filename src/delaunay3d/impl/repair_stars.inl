// Phase 2 of the incremental method on the executor (thesis 5.3.2; Shewchuk's star splaying):
// the tetrahedralisation phase 1 left, whose failed faces are not locally Delaunay, repaired by
// the splayer the digital method uses (stars.inl), then its flat tetrahedra left out. Included
// inside an executor's namespace after splay.inl; the patch that follows is repair.inl.
//
// A vertex whose faces are all locally Delaunay has a convex star in the tetrahedralisation
// (the link edge (a, b) of star(v) is reflex exactly where the face (v, a, b) is not locally
// Delaunay), so only the failed vertices' stars are made anew, by Flip-Flop on the lifted star
// (flip_flop). The splayer then works on those
// and builds the others from the tetrahedralisation when a round first reads them
// (SplayScope), so the work follows the failed vertices' neighbourhoods, not the store.
//
// Building stars (MeshStars::build): the slots around the wanted vertices come from one pass
// over the store (each slot's vertices that are wanted, as keys (vertex, slot)), sorted, so a
// star's triangles come in slot order on every run; a copy of the stars as built (triangles and
// their slots) stays for the patch.
//
// The patch: a changed star's old tetrahedra that its new star lacks go (their slots are freed),
// and each new tetrahedron comes from the star of its lowest finite vertex (all of a new
// tetrahedron's stars changed, so that one is built). New tetrahedra take the freed slots in
// slot order, then new ones at the end. Across each face, the neighbour is found in the star of
// a finite vertex of the face: the link triangle across the face's link edge there; it is new
// (its index comes from its lowest vertex's star) or was kept, and then its slot is in that
// vertex's old star, and its face towards the region is pointed at the new tetrahedron.

// An executor array reallocated to cap entries, keeping its first `keep` and filling the rest
// with *fill where given (phase 1's store and phase 2's old stars grow this way).
template <class T>
void regrow(Exec& ex, typename Exec::template Buffer<T>& b, std::int64_t cap, std::int64_t keep,
            const T* fill = nullptr) {
  auto nb = ex.template alloc<T>(std::size_t(cap));
  if (keep) ex.copy(b.data(), keep, nb.data());
  if (fill) ex.fill(nb.data() + keep, cap - keep, *fill);
  b = std::move(nb);
}

struct RepairCount {
  std::int64_t failed_vertices = 0, stars_built = 0, stars_changed = 0;
  std::int64_t removed = 0, added = 0, rounds = 0, insertions = 0;
  double build_ms = 0, splay_ms = 0, patch_ms = 0;
  double check_ms = 0, take_ms = 0;  // (of splay_ms, with the sorts between them in neither)
};

// ---- Flip-Flop on a lifted star (thesis 5.2.2 one dimension up) ----
// A failed vertex's star as the tetrahedralisation has it is convex at every link edge but
// those of its failed faces. Flip-Flop makes it convex where it is: a reflex link edge is
// flipped where the two new triangles stay positive around v; where it cannot be, the corner
// inside the cone of the other three is not extreme, and its link edges are flipped until it has
// three, whose triangles become one. (Making the star anew from its link's vertices, as the
// digital method makes a star from its working set, took seconds a star on the thousands of
// triangles around an integer grid's hull-plane points: each vertex scans the whole star.)
struct StarEdge {
  std::int32_t a, b;
};

// Link edge a -> b of triangles (a, b, c) and (b, a, d) replaced by (c, d): triangles (a, d, c)
// and (d, b, c), when both stay positively oriented around v. c, d: the new edge's ends. The
// lanes L search together; lane 0 asks the predicates and writes.
template <class Lanes>
GG_HD inline bool star_flip(const Lanes& L, const Geo& g, std::int32_t v, LinkTri* t, int n,
                            std::int32_t a, std::int32_t b, std::int32_t& c, std::int32_t& d) {
  const int i1 = link_find_edge(L, t, n, a, b), i2 = link_find_edge(L, t, n, b, a);
  if (i1 < 0 || i2 < 0) return false;
  c = link_third(t[i1], a, b);
  d = link_third(t[i2], a, b);
  if (c == d) return false;
  const std::int32_t cc = c, dd = d;
  if (!on_lane0(L, [&] {
        return orient_ext(g, v, a, dd, cc) > 0 && orient_ext(g, v, dd, b, cc) > 0 ? 1 : 0;
      }))
    return false;
  L.sync();  // (every lane has read both triangles)
  if (L.rank == 0) {
    t[i1] = LinkTri{a, d, c};
    t[i2] = LinkTri{d, b, c};
  }
  L.sync();
  return true;
}

// Flip-Flop on the star t[0, n) of v, from the link edges between failed vertices (failed: the
// vertices of failed faces, the infinity point included; only those edges can be reflex); work:
// room for wcap edges (the link edges still to test; where it fills, the edges that did not fit
// are found by testing every edge again once it empties). Returns the new count, or -1 where a
// step that cannot fail on a star did. The lanes L share the scans (a failed star's edges each
// search the star, and a corner that is not extreme searches it per flip: on one thread the
// longest star was the whole launch, 9 ms of uniform 10^6's phase 2); every step is decided the
// same on every lane, and the work list and the star change as one lane would change them.
template <class Lanes>
GG_HD inline int flip_flop(const Lanes& L, const Geo& g, std::int32_t v, LinkTri* t, int n,
                           const std::int8_t* failed, StarEdge* work, int wcap) {
  int nw = 0;
  bool lost = false;
  auto push = [&](std::int32_t a, std::int32_t b) {
    if (nw < wcap) {
      if (L.rank == 0) work[nw] = StarEdge{a, b};
      ++nw;
    } else {
      lost = true;
    }
  };
  // Every link edge a -> b with keep(a, b), in triangle then edge order.
  auto push_all = [&](auto keep) {
    for (int base = 0; base < n; base += L.size) {
      const int i = base + L.rank;
      StarEdge mine[3];
      int k = 0;
      if (i < n) {
        const std::int32_t e[3] = {t[i].a, t[i].b, t[i].c};
        for (int j = 0; j < 3; ++j)
          if (keep(e[j], e[(j + 1) % 3])) mine[k++] = StarEdge{e[j], e[(j + 1) % 3]};
      }
      int all = 0;
      const int at = nw + L.exclusive_scan(k, &all);
      for (int z = 0; z < k; ++z)
        if (at + z < wcap) work[at + z] = mine[z];
      if (nw + all > wcap) lost = true;
      nw = nw + all < wcap ? nw + all : wcap;
    }
  };
  push_all([&](std::int32_t a, std::int32_t b) { return a < b && failed[a] && failed[b]; });
  for (std::int64_t guard = 0;; ++guard) {
    if (guard > 100000000) return -1;
    if (nw == 0) {
      if (!lost) return n;
      lost = false;
      push_all([](std::int32_t a, std::int32_t b) { return a < b; });
      if (nw == 0) return n;
    }
    L.sync();  // (the pushes, to every lane)
    StarEdge ed = work[--nw];
    int i1 = link_find_edge(L, t, n, ed.a, ed.b);
    if (i1 < 0) {
      const std::int32_t x = ed.a;
      ed.a = ed.b, ed.b = x;
      i1 = link_find_edge(L, t, n, ed.a, ed.b);
      if (i1 < 0) continue;  // flipped away since it was listed
    }
    const std::int32_t a = ed.a, b = ed.b;
    const int j = link_find_edge(L, t, n, b, a);
    if (j < 0) return -1;  // (an open star)
    const std::int32_t c = link_third(t[i1], a, b), d = link_third(t[j], a, b);
    if (!on_lane0(L, [&] { return link_reflex(g, v, LinkTri{a, b, c}, d) ? 1 : 0; })) continue;
    std::int32_t nc, nd;
    if (star_flip(L, g, v, t, n, a, b, nc, nd)) {
      push(a, d), push(d, b), push(b, c), push(c, a);
      continue;
    }
    // Not flippable: the corner inside the cone of the other three is not extreme; its link
    // edges are flipped until it has three neighbours, then its three triangles become one.
    const std::int32_t x = on_lane0(L, [&] { return orient_ext(g, v, a, d, c) < 0 ? a : b; });
    for (int step = 0;; ++step) {
      if (step > 4 * n + 16) return -1;
      int deg = 0, first = -1;
      for (int base = 0; base < n; base += L.size) {
        const int i = base + L.rank;
        const std::uint32_t mask = L.ballot(i < n && t[i].has(x));
        if (mask && first < 0) first = base + lowest_lane(mask);
        deg += L.count(mask);
      }
      if (deg == 0) break;
      if (deg == 3) {
        const LinkTri f = t[first];
        const std::int32_t y0 = f.a == x ? f.b : f.b == x ? f.c : f.a;
        const int i0 = link_find_edge(L, t, n, x, y0);
        if (i0 < 0) return -1;
        const std::int32_t y1 = link_third(t[i0], x, y0);
        const int i2 = link_find_edge(L, t, n, x, y1);
        if (i2 < 0) return -1;
        const std::int32_t y2 = link_third(t[i2], x, y1);
        if (on_lane0(L, [&] { return orient_ext(g, v, y0, y1, y2) <= 0 ? 1 : 0; })) return -1;
        // (the others keep their order, read a stride then written at or below it; the new
        // one comes last)
        int k = 0;
        for (int base = 0; base < n; base += L.size) {
          const int i = base + L.rank;
          const bool keep = i < n && !t[i].has(x);
          const LinkTri q = keep ? t[i] : LinkTri{};
          const std::uint32_t mask = L.ballot(keep);
          L.sync();
          if (keep) t[k + L.below(mask)] = q;
          k += L.count(mask);
        }
        if (L.rank == 0) t[k] = LinkTri{y0, y1, y2};
        L.sync();
        n = k + 1;
        push(y0, y1), push(y1, y2), push(y2, y0);
        break;
      }
      bool flipped = false;
      for (int i = link_next_with(L, t, n, 0, x); i < n && !flipped;
           i = link_next_with(L, t, n, i + 1, x)) {
        const std::int32_t y = t[i].a == x ? t[i].b : t[i].b == x ? t[i].c : t[i].a;
        std::int32_t fc, fd;  // (x, y) -> (fc, fd): the two new triangles' edges
        if (star_flip(L, g, v, t, n, x, y, fc, fd)) {
          push(x, fd), push(fd, y), push(y, fc), push(fc, x), push(fc, fd);
          flipped = true;
        }
      }
      if (!flipped) return -1;
    }
  }
}

// What MeshStars::build writes a star with: the stars of vs (runs laid), the old stars (the
// tetrahedralisation's, copied), failed (null: copies only; else made convex by Flip-Flop from
// the failed vertices' edges), and bad (a count of stars that could not be made).
struct BuildArgs {
  Geo g;
  const std::int32_t* vs;
  LinkTri* tri;
  LinkVert* vt;
  const std::int64_t* off;
  const std::int32_t* cap;
  std::int32_t *cnt, *nvt;
  std::int8_t* built;
  const LinkTri* ot;
  const std::int64_t* oo;
  const std::int32_t* oc;
  const std::int8_t* failed;
  std::int64_t* bad;
};
// The star of vs[j], with the lanes L: copied from its old star, made convex where failed is
// given (the vertex table's room holds Flip-Flop's work list: cap entries of 8 bytes), then
// its vertex table.
template <class Lanes>
GG_HD void build_star(const Lanes& L, std::int64_t j, const BuildArgs& a) {
  const std::int32_t v = a.vs[j];
  LinkTri* t = a.tri + a.off[v];
  const LinkTri* o = a.ot + a.oo[v];
  int n = a.oc[v];
  for (int i = L.rank; i < n; i += L.size) t[i] = o[i];
  L.sync();
  if (a.failed) {
    static_assert(sizeof(LinkVert) == sizeof(StarEdge), "the work list's room");
    n = flip_flop(L, a.g, v, t, n, a.failed, reinterpret_cast<StarEdge*>(a.vt + a.off[v]),
                  a.cap[v]);
    if (n < 0) {
      if (L.rank == 0) atomic_add(a.bad, std::int64_t(1));
      return;
    }
  }
  if (L.rank != 0) return;
  a.cnt[v] = n;
  a.nvt[v] = link_table(t, n, a.vt + a.off[v]);
  a.built[v] = a.failed ? 2 : 1;
}

// The tetrahedralisation's stars, built into the splayer's store as they are wanted.
class MeshStars {
 public:
  using u64 = unsigned long long;
  MeshStars(Exec& ex, const Geo& g, const Tet* tet, std::int64_t used)
      : ex_(ex), g_(g), tet_(tet), used_(used), m_(g.m) {}
  // (not in the constructor: nvcc's extended lambdas need an enclosing function whose address
  // can be taken)
  void start() {
    Exec& ex = ex_;
    const Tet* tet = tet_;
    const std::size_t m = std::size_t(m_);
    S.m = m_;
    S.cnt = ex.template alloc<std::int32_t>(m);
    S.cap = ex.template alloc<std::int32_t>(m);
    S.nvt = ex.template alloc<std::int32_t>(m);
    S.off = ex.template alloc<std::int64_t>(m + 1);
    ex.fill(S.cnt.data(), m_, std::int32_t(0));
    ex.fill(S.cap.data(), m_, std::int32_t(0));
    ex.fill(S.nvt.data(), m_, std::int32_t(0));
    ex.fill(S.off.data(), m_ + 1, std::int64_t(0));
    built = ex.template alloc<std::int8_t>(m);
    want_ = ex.template alloc<std::int8_t>(m);
    ex.fill(built.data(), m_, std::int8_t(0));
    ex.fill(want_.data(), m_, std::int8_t(0));
    ooff = ex.template alloc<std::int64_t>(m);
    ocnt = ex.template alloc<std::int32_t>(m);
    ex.fill(ocnt.data(), m_, std::int32_t(0));
    verts_ = ex.template alloc<std::int32_t>(m);
    ctr_ = ex.template alloc<std::int64_t>(2);
    // The tetrahedra around each vertex (the size of its star).
    deg_ = ex.template alloc<std::int32_t>(m);
    std::int32_t* deg = deg_.data();
    ex.fill(deg, m_, std::int32_t(0));
    const std::int32_t I = m_;
    ex.for_each_index(
        used_, GG_LAMBDA(std::int64_t t) {
          const Tet T = tet[t];
          if (T.v[0] < 0) return;
          for (int k = 0; k < 4; ++k)
            if (T.v[k] != I) atomic_add(deg + T.v[k], std::int32_t(1));
        });
  }

  // The stars of the vertices with flag[v] != 0 (those not built yet), from the
  // tetrahedralisation: copied (built 1), or made convex by Flip-Flop (create: built 2). flag may
  // be want_ itself, which is left clear. Returns how many were built.
  std::int64_t build_flagged(const std::int8_t* flag, bool create) {
    std::int8_t* want = want_.data();
    const std::int8_t* b = built.data();
    const std::int64_t nv = ex_.compact_indices(
        m_, GG_LAMBDA(std::int64_t v) { return flag[v] && !b[v]; }, verts_.data());
    if (nv == 0) return 0;
    if (flag != want) {  // (want_ marks the stars being built; fill marks only unbuilt ones)
      const std::int32_t* vs = verts_.data();
      ex_.for_each_index(
          nv, GG_LAMBDA(std::int64_t j) { want[vs[j]] = 1; });
    }
    build(nv, create ? flag : nullptr);
    return nv;
  }

  // The stars the first round checks (first_): the made ones, and the old link vertices that a
  // made star lost (Flip-Flop found them not extreme there): those still hold the tetrahedra
  // with it, which no check from the made star sees. Lost: an old link vertex with no entry in
  // the new vertex table, found by one sort of records (star, vertex, new?) over the made stars
  // (a scan of the new table per old triangle was quadratic: seconds on the thousands of
  // triangles of grids' hull-plane stars, on one GPU thread each).
  void mark_first() {
    first_ = ex_.template alloc<std::int8_t>(std::size_t(m_));
    std::int8_t* first = first_.data();
    const std::int8_t* b = built.data();
    ex_.for_each_index(
        m_, GG_LAMBDA(std::int64_t v) { first[v] = b[v] == 2 ? 1 : 0; });
    std::int32_t* vs = verts_.data();
    const std::int64_t nm = ex_.compact_indices(
        m_, GG_LAMBDA(std::int64_t v) { return b[v] == 2; }, vs);
    if (nm == 0) return;
    const std::int64_t* oo = ooff.data();
    const std::int32_t* oc = ocnt.data();
    const LinkVert* vt = S.vt.data();
    const std::int64_t* off = S.off.data();
    const std::int32_t* nvt = S.nvt.data();
    auto roff_d = ex_.template alloc<std::int64_t>(std::size_t(nm + 1));
    std::int64_t* roff = roff_d.data();
    ex_.exclusive_scan_of(
        nm + 1,
        GG_LAMBDA(std::int64_t j)->std::int64_t {
          return j < nm ? 3 * std::int64_t(oc[vs[j]]) + nvt[vs[j]] : 0;
        },
        roff);
    std::int64_t total = 0;
    ex_.to_host(roff + nm, 1, &total);
    // (star << 33 | vertex << 1 | new: a vertex's old records sort before its new one)
    auto rec_d = ex_.template alloc<u64>(std::size_t(std::max<std::int64_t>(total, 1)));
    u64* rec = rec_d.data();
    const LinkTri* ot = otri_.data();
    const std::int32_t I = m_;
    ex_.for_each_index(
        nm, GG_LAMBDA(std::int64_t j) {
          const std::int32_t v = vs[j];
          const u64 hi = u64(std::uint32_t(v)) << 33;
          u64* r = rec + roff[j];
          for (std::int32_t i = 0; i < oc[v]; ++i) {
            const LinkTri t = ot[oo[v] + i];
            *r++ = hi | u64(std::uint32_t(t.a)) << 1;
            *r++ = hi | u64(std::uint32_t(t.b)) << 1;
            *r++ = hi | u64(std::uint32_t(t.c)) << 1;
          }
          for (std::int32_t i = 0; i < nvt[v]; ++i)
            *r++ = hi | u64(std::uint32_t(vt[off[v] + i].x)) << 1 | 1u;
        });
    ex_.sort(rec, total);
    // The last record of each (star, vertex) is old exactly when the new table lacks the vertex.
    ex_.for_each_index(
        total, GG_LAMBDA(std::int64_t i) {
          const u64 r = rec[i];
          if ((r & 1u) || (i + 1 < total && rec[i + 1] >> 1 == r >> 1)) return;
          const std::int32_t y = std::int32_t((r >> 1) & 0xFFFFFFFFu);
          if (y != I) first[y] = 1;
        });
  }

  // Before a splaying round (SplayScope::fill): the listed stars not built yet, and the link
  // vertices' stars of the listed ones that are built (all) or changed (else), in one build
  // (each costs a pass over the store); where all, the link vertices of the listed stars that
  // build made come in a second.
  void fill(const std::int32_t* list, std::int64_t nl, bool all) {
    if (mark_listed(list, nl, all) > 0 && all) mark_listed(list, nl, all);
  }
  std::int64_t mark_listed(const std::int32_t* list, std::int64_t nl, bool all) {
    std::int8_t* want = want_.data();
    const std::int8_t* b = built.data();
    const LinkVert* vt = S.vt.data();
    const std::int64_t* off = S.off.data();
    const std::int32_t* nvt = S.nvt.data();
    const std::int32_t I = m_;
    ex_.for_each_index(
        nl, GG_LAMBDA(std::int64_t j) {
          const std::int32_t v = list[j];
          if (!b[v]) {
            want[v] = 1;
            return;
          }
          if (!all && b[v] != 2) return;
          for (std::int32_t i = 0; i < nvt[v]; ++i) {
            const std::int32_t u = vt[off[v] + i].x;
            if (u != I && !b[u]) want[u] = 1;
          }
        });
    return build_flagged(want, false);
  }

  // Builds the stars of verts_[0, nv) (increasing; want_ marks them): copies, or where failed is
  // given (the failed vertices, m + 1 flags), made convex by Flip-Flop.
  void build(std::int64_t nv, const std::int8_t* flag) {
    const bool create = flag != nullptr;
    const auto t0 = Clock::now();
    stars_built += nv;
    const std::int32_t* vs = verts_.data();
    const std::int32_t* deg = deg_.data();
    const std::int8_t* want = want_.data();
    // Where each star's slots go among the keys, and in the old stars' arrays.
    auto koff_d = ex_.template alloc<std::int64_t>(std::size_t(nv + 1));
    std::int64_t* koff = koff_d.data();
    ex_.exclusive_scan_of(
        nv + 1, GG_LAMBDA(std::int64_t j)->std::int64_t { return j < nv ? deg[vs[j]] : 0; }, koff);
    std::int64_t total = 0;
    ex_.to_host(koff + nv, 1, &total);
    reserve_old(oused_ + total);
    // The slots around them, as keys (vertex, slot), in order.
    auto keys_d = ex_.template alloc<u64>(std::size_t(std::max<std::int64_t>(total, 1)));
    u64* keys = keys_d.data();
    std::int64_t* ctr = ctr_.data();
    ex_.fill(ctr, 2, std::int64_t(0));
    const Tet* tet = tet_;
    const std::int32_t I = m_;
    ex_.for_each_index(
        used_, GG_LAMBDA(std::int64_t t) {
          const Tet T = tet[t];
          if (T.v[0] < 0) return;
          for (int k = 0; k < 4; ++k)
            if (T.v[k] != I && want[T.v[k]])
              keys[atomic_add(ctr, std::int64_t(1))] = u64(std::uint32_t(T.v[k])) << 32 | u64(t);
        });
    if (total > 0) ex_.sort(keys, total);
    // The old stars: each slot's face opposite the vertex, oriented as a link triangle.
    {
      LinkTri* ot = otri_.data();
      std::int32_t* os = oslot_.data();
      std::int64_t* oo = ooff.data();
      std::int32_t* oc = ocnt.data();
      const std::int64_t base = oused_;
      ex_.for_each_index(
          nv, GG_LAMBDA(std::int64_t j) {
            const std::int32_t v = vs[j];
            oo[v] = base + koff[j];
            oc[v] = std::int32_t(koff[j + 1] - koff[j]);
            for (std::int64_t i = koff[j]; i < koff[j + 1]; ++i) {
              const std::int32_t t = std::int32_t(keys[i] & 0xFFFFFFFFu);
              const Tet T = tet[t];
              int k = 0;
              while (T.v[k] != v) ++k;
              ot[base + i] =
                  LinkTri{T.v[face_vertex(k, 0)], T.v[face_vertex(k, 1)], T.v[face_vertex(k, 2)]};
              os[base + i] = t;
            }
          });
      oused_ += total;
    }
    // Runs in the splayer's store (a star over k link vertices has 2 k - 4 triangles; twice its
    // size and 8 leaves room to grow), then the stars.
    lay_runs(
        ex_, S, GG_LAMBDA(std::int64_t v)->std::int32_t { return want[v] ? 2 * deg[v] + 8 : 0; });
    const BuildArgs a{g_,           vs,           S.tri.data(), S.vt.data(),  S.off.data(),
                      S.cap.data(), S.cnt.data(), S.nvt.data(), built.data(), otri_.data(),
                      ooff.data(),  ocnt.data(),  flag,         ctr + 1};
    // (made stars on a warp each: see flip_flop; copies on a thread each)
    if (create)
      ex_.for_each_lanes(
          nv, GG_LAMBDA(std::int64_t j, const Exec::Lanes& L) { build_star(L, j, a); });
    else
      ex_.for_each_index(
          nv, GG_LAMBDA(std::int64_t j) { build_star(SoloLanes{}, j, a); });
    std::int64_t bad = 0;
    ex_.to_host(ctr + 1, 1, &bad);
    if (bad)
      throw Error(ErrorCode::Internal,
                  "internal error in 3D Delaunay phase 2: a failed vertex's star could not be "
                  "made convex; please report this input");
    std::int8_t* clear = want_.data();
    ex_.for_each_index(
        nv, GG_LAMBDA(std::int64_t j) { clear[vs[j]] = 0; });
    build_ms += ms_since(t0);
  }

  // Room for `need` entries in the old stars' arrays (kept; doubled at least).
  void reserve_old(std::int64_t need) {
    if (need <= ocap_) return;
    const std::int64_t cap = std::max<std::int64_t>(need, 2 * ocap_ + 1024);
    regrow(ex_, otri_, cap, oused_);
    regrow(ex_, oslot_, cap, oused_);
    ocap_ = cap;
  }

  // state (public: nvcc's extended lambdas may not live in private members)
  Exec& ex_;
  Geo g_;
  const Tet* tet_;
  std::int64_t used_;
  std::int32_t m_;
  StarStore S;
  typename Exec::template Buffer<std::int8_t> built, want_, first_;
  typename Exec::template Buffer<std::int32_t> deg_, verts_;
  typename Exec::template Buffer<std::int64_t> ctr_;
  // The stars as built: star(v)'s triangles otri_[ooff[v], + ocnt[v]), each from slot oslot_.
  typename Exec::template Buffer<std::int64_t> ooff;
  typename Exec::template Buffer<std::int32_t> ocnt;
  typename Exec::template Buffer<LinkTri> otri_;
  typename Exec::template Buffer<std::int32_t> oslot_;
  std::int64_t oused_ = 0, ocap_ = 0;
  std::int64_t stars_built = 0;
  double build_ms = 0;
};
