// Stars for every point on the executor (thesis 4.5.2, phases 2 and 3): a convex star per point
// from its working set by beneath-beyond, then star splaying in rounds until every star agrees
// with its neighbours' (Shewchuk), then the tetrahedra. Included inside an executor's namespace
// after geometry.inl and link.inl; the splaying's checks and rounds follow in splay_checks.inl
// and splay.inl.
//
// Storage (the thesis' two-part storage, in one array): each star owns a run of triangle slots
// (off, cap) of which cnt are used, and in the same places of a second array its vertex table
// (each link vertex with a hash of its ring; see LinkVert). A star that outgrows its run while
// taking vertices gets a new run of twice the room past the last one, from the slots kept free
// there; where none are left it stops, and between passes every run is laid out again.
//
// Splaying: rounds of two kinds over the dirty stars. Link-vertex rounds first (a thread per
// few entries of a star's vertex table): for each link vertex u of star(v), a star(u) lacking v
// takes it where v would change it (else star(v) takes a vertex of star(u) inside one of its
// spheres at u), and around an edge both have, each takes the other's ring vertices inside its
// spheres there (edge_rings). Once those are quiet, tetrahedra rounds: a tetrahedron of star(v)
// must be in the stars of its other finite vertices; where star(w) lacks one, star(w) takes those
// of its vertices that would change it, and where none would, star(w) holds a vertex inside the
// tetrahedron's sphere, which star(v) takes. Every request changes its star ("would it change" is
// the exact test), so the rounds end; the last checks every star's tetrahedra, the proof that all
// agree (design-notes.md measures why the vertex rounds come first). The requests (star, vertex)
// are sorted; each star takes its vertices in vertex order on one thread. A star is the convex star
// of the vertices offered to it whatever their order, and stars only take vertices, so the rounds
// end in the same stars on every executor and thread count, which are the stars of the Delaunay
// tetrahedralisation once they all agree. Dirty for the next round: a star that took a vertex,
// and the vertices of every triangle it lost (their stars may still hold the tetrahedron).

namespace digital3d_impl {

struct StarCounters {
  std::int64_t requests, overflow, broken, stuck, taken, huge, spilled;
  std::int64_t bump;  // (the take's next free slot past the last run)
};

}  // namespace digital3d_impl

// A star's vertex table: each link vertex once, with a hash of its ring (the link vertices
// next to it). Two stars that both have the edge (v, u) have the same tetrahedra around it when
// the ring of u in star(v) and the ring of v in star(u) are the same set (the splaying's edge
// test, edge_rings, compares exactly that), so equal hashes let the vertex rounds pass the pair
// after one short scan of star(u)'s table instead of its triangles (twice) and star(v)'s: most
// pairs after the first round agree (97 % at 10^5). A collision can only pass a pair that
// differs; the proof that ends the splaying looks up every tetrahedron, so the tetrahedra's
// rounds then find it, and the result is the same.
struct LinkVert {
  std::int32_t x;
  std::uint32_t h;  // the ring's hash: ring_mix summed over the ring, each vertex twice
};

GG_INLINE std::uint32_t ring_mix(std::int32_t y) {
  std::uint32_t z = std::uint32_t(y) * 0x9E3779B1u;  // (a 32-bit finaliser: any good mix will do)
  z ^= z >> 15;
  z *= 0x85EBCA77u;
  z ^= z >> 13;
  z *= 0xC2B2AE3Du;
  return z ^ (z >> 16);
}

// The vertex table of the link t[0, n) into vt (room for n: a closed link over k >= 4 vertices
// has 2 k - 4 >= k triangles). Each triangle adds its other two vertices to the hash of each of
// its vertices; a ring vertex is in the two triangles at its ring edge, so counts twice on
// either side. Returns the count.
GG_HD inline int link_table_into(const LinkTri* t, int n, LinkVert* vt) {
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const std::int32_t y3[3] = {t[i].a, t[i].b, t[i].c};
    const std::uint32_t h3[3] = {ring_mix(y3[0]), ring_mix(y3[1]), ring_mix(y3[2])};
    for (int a = 0; a < 3; ++a) {
      int j = 0;
      while (j < k && vt[j].x != y3[a]) ++j;
      if (j == k) vt[k++] = LinkVert{y3[a], 0u};
      vt[j].h += h3[(a + 1) % 3] + h3[(a + 2) % 3];
    }
  }
  return k;
}
// Large stars (the thousands of triangles around an integer grid's hull-plane points, where the
// scans above cost a million steps a star): an open-addressing table over the n places (a
// closed link over k vertices has 2 k - 4 = n triangles, so about half of them fill), then
// compacted in table order, which depends on the vertices alone. Returns -1 where the link is
// not closed (the table filled).
GG_HD inline int link_table_hashed(const LinkTri* t, int n, LinkVert* vt) {
  for (int i = 0; i < n; ++i) vt[i] = LinkVert{-1, 0u};
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const std::int32_t y3[3] = {t[i].a, t[i].b, t[i].c};
    const std::uint32_t h3[3] = {ring_mix(y3[0]), ring_mix(y3[1]), ring_mix(y3[2])};
    for (int a = 0; a < 3; ++a) {
      int j = int(h3[a] % std::uint32_t(n));
      while (vt[j].x != -1 && vt[j].x != y3[a]) j = j + 1 == n ? 0 : j + 1;
      if (vt[j].x == -1) {
        if (++k == n) return -1;
        vt[j].x = y3[a];
      }
      vt[j].h += h3[(a + 1) % 3] + h3[(a + 2) % 3];
    }
  }
  int w = 0;
  for (int j = 0; j < n; ++j)
    if (vt[j].x != -1) vt[w++] = vt[j];
  return w;
}
GG_HD inline int link_table(const LinkTri* t, int n, LinkVert* vt) {
  // (built in the thread's own memory where it fits, which is most stars: the scans for each
  // vertex then stay near, and the array is written once)
  constexpr int kNear = 64;
  if (n > 2 * kNear - 4) {
    const int k = link_table_hashed(t, n, vt);
    return k >= 0 ? k : link_table_into(t, n, vt);
  }
  LinkVert near[kNear];
  const int k = link_table_into(t, n, near);
  for (int j = 0; j < k; ++j) vt[j] = near[j];
  return k;
}

// The stars: triangle runs (off, cap; cnt used) and, in the same places of vt, their vertex
// tables (nvt entries each), kept up to date by whatever changes a star.
struct StarStore {
  typename Exec::template Buffer<LinkTri> tri;
  typename Exec::template Buffer<LinkVert> vt;
  typename Exec::template Buffer<std::int64_t> off;
  typename Exec::template Buffer<std::int32_t> cap, cnt, nvt;
  std::int64_t m = 0, slots = 0, used = 0, growths = 0;  // (slots: tri's size; used: runs laid)
};

// The room of a star's new run when it outgrows cap: twice, plus 8 (between passes here, and
// in the take's kernel where the slots past the last run allow).
GG_INLINE std::int32_t grown_cap(std::int32_t cap) {
  return 2 * cap + 8;
}

// New runs for the stars with room(v) > 0, of that room, the used triangles and vertex tables
// moved along. Where the slots past the last run hold them, the new runs go there and nothing
// else moves (the stars that outgrow their runs are a few, late in the splaying, and a
// re-layout of every star for them cost as much as a round); else every star is laid out
// again in a new array, with a quarter more room at its end for later growth.
template <class Room>
inline void lay_runs(Exec& ex, StarStore& S, Room room) {
  const std::int64_t m = S.m;
  const std::int32_t* c1 = S.cap.data();
  auto add_d = ex.template alloc<std::int64_t>(std::size_t(m + 1));
  std::int64_t* add = add_d.data();
  ex.exclusive_scan_of(
      m + 1, GG_LAMBDA(std::int64_t v)->std::int64_t { return v < m ? room(v) : 0; }, add);
  std::int64_t need = 0;
  ex.to_host(add + m, 1, &need);
  if (need == 0) return;
  if (S.used + need <= S.slots) {
    LinkTri* t = S.tri.data();
    LinkVert* vt = S.vt.data();
    std::int64_t* off = S.off.data();
    std::int32_t* cap = S.cap.data();
    const std::int32_t* cnt = S.cnt.data();
    const std::int32_t* nvt = S.nvt.data();
    const std::int64_t base = S.used;
    ex.for_each_index(
        m, GG_LAMBDA(std::int64_t v) {
          const std::int32_t r = room(v);
          if (r == 0) return;
          const std::int64_t to = base + add[v];
          for (std::int32_t i = 0; i < cnt[v]; ++i) t[to + i] = t[off[v] + i];
          for (std::int32_t i = 0; i < nvt[v]; ++i) vt[to + i] = vt[off[v] + i];
          off[v] = to;
          cap[v] = r;
        });
    S.used += need;
    ++S.growths;
    return;
  }
  auto cap2 = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int32_t* c2 = cap2.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t v) {
        const std::int32_t r = room(v);
        c2[v] = r > 0 ? r : c1[v];
      });
  ex.exclusive_scan_of(
      m + 1, GG_LAMBDA(std::int64_t v)->std::int64_t { return v < m ? c2[v] : 0; }, add);
  std::int64_t total = 0;
  ex.to_host(add + m, 1, &total);
  const std::int64_t slots = std::max<std::int64_t>(total + total / 4, 1);
  auto tri2 = ex.template alloc<LinkTri>(std::size_t(slots));
  auto vt2_d = ex.template alloc<LinkVert>(std::size_t(slots));
  LinkTri* t2 = tri2.data();
  LinkVert* vt2 = vt2_d.data();
  const LinkTri* t1 = S.tri.data();
  const LinkVert* vt1 = S.vt.data();
  const std::int64_t* o1 = S.off.data();
  const std::int32_t* cnt = S.cnt.data();
  const std::int32_t* nvt = S.nvt.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t v) {
        for (std::int32_t i = 0; i < cnt[v]; ++i) t2[add[v] + i] = t1[o1[v] + i];
        for (std::int32_t i = 0; i < nvt[v]; ++i) vt2[add[v] + i] = vt1[o1[v] + i];
      });
  S.tri = std::move(tri2);
  S.vt = std::move(vt2_d);
  S.off = std::move(add_d);
  S.cap = std::move(cap2);
  S.slots = slots;
  S.used = total;
  ++S.growths;
}

// New runs of twice the room plus 8 for the stars with grow[v] != 0.
inline void regrow_stars(Exec& ex, StarStore& S, const std::int8_t* grow) {
  const std::int32_t* c1 = S.cap.data();
  lay_runs(
      ex, S, GG_LAMBDA(std::int64_t v)->std::int32_t { return grow[v] ? grown_cap(c1[v]) : 0; });
}

// Phase 2: the convex star of every point v from its working set ws[wo[v], wo[v] + wn[v]) (at
// least three points): the link of v among the first three and the infinity point, then every
// other point taken in turn.
inline StarStore create_stars(Exec& ex, const Geo& g, std::int64_t m, const std::int64_t* wo,
                              const std::int32_t* wn, const std::int32_t* ws,
                              typename Exec::template Buffer<digital3d_impl::StarCounters>& ctr) {
  using digital3d_impl::StarCounters;
  StarStore S;
  S.m = m;
  S.cnt = ex.template alloc<std::int32_t>(std::size_t(m));
  S.cap = ex.template alloc<std::int32_t>(std::size_t(m));
  S.nvt = ex.template alloc<std::int32_t>(std::size_t(m));
  S.off = ex.template alloc<std::int64_t>(std::size_t(m + 1));
  {  // (a star over k link vertices has 2 k - 4 triangles; k is at most the set plus infinity)
    std::int32_t* cap = S.cap.data();
    std::int32_t* cnt = S.cnt.data();
    std::int32_t* nvt = S.nvt.data();
    ex.for_each_index(
        m, GG_LAMBDA(std::int64_t v) {
          cap[v] = 0;
          cnt[v] = 0;
          nvt[v] = 0;
        });
    lay_runs(
        ex, S, GG_LAMBDA(std::int64_t v)->std::int32_t { return 2 * wn[v] + 8; });
    S.growths = 0;
  }
  auto redo_d = ex.template alloc<std::int8_t>(std::size_t(m));
  std::int8_t* redo = redo_d.data();
  ex.fill(redo, m, std::int8_t(1));
  StarCounters* C = ctr.data();
  for (int pass = 0;; ++pass) {
    if (pass > 40) throw Error(ErrorCode::Internal, "digital 3D Delaunay: stars kept outgrowing");
    const StarCounters zero{};
    ex.from_host(&zero, 1, C);
    LinkTri* tri = S.tri.data();
    LinkVert* vt = S.vt.data();
    const std::int64_t* off = S.off.data();
    const std::int32_t* cap = S.cap.data();
    std::int32_t* cnt = S.cnt.data();
    std::int32_t* nvt = S.nvt.data();
    ex.for_each_index(
        m, GG_LAMBDA(std::int64_t i) {
          if (!redo[i]) return;
          const std::int32_t v = std::int32_t(i);
          LinkTri* t = tri + off[v];
          const std::int64_t b = wo[v], e = wo[v] + wn[v];
          link_start(g, v, ws[b], ws[b + 1], ws[b + 2], t);
          int n = 4;
          for (std::int64_t j = b + 3; j < e; ++j) {
            const int r = link_insert(g, v, t, n, cap[v], ws[j], [](const LinkTri&) {});
            if (r == kLinkNoRoom) {
              atomic_add(&C->overflow, std::int64_t(1));
              cnt[v] = n;
              return;
            }
            if (r == kLinkBroken) {
              atomic_add(&C->broken, std::int64_t(1));
              break;
            }
            n = r;
          }
          cnt[v] = n;
          nvt[v] = link_table(t, n, vt + off[v]);
          redo[i] = 0;
        });
    StarCounters c;
    ex.to_host(C, 1, &c);
    if (c.broken)
      throw Error(ErrorCode::Internal,
                  "internal error in the digital 3D Delaunay method: a star creation step found "
                  "a star that was not convex; please report this input");
    if (!c.overflow) break;
    regrow_stars(ex, S, redo);  // (the stars that stopped start again with twice the room)
  }
  return S;
}
