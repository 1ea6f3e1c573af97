// Stars for every point on the executor (thesis 4.5.2, phases 2 and 3): a convex star per point
// from its working set by beneath-beyond, then star splaying in rounds until every star agrees
// with its neighbours' (Shewchuk), then the tetrahedra. Included inside an executor's namespace
// after geometry.inl and link.inl.
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

// The ring of x in the link t[0, n): the link vertices next to x, each once, into r (room for
// kRing). k = 0: the link lacks x. Returns false where the ring is longer than kRing.
constexpr int kRing = 48;
GG_HD inline bool link_ring(const LinkTri* t, int n, std::int32_t x, std::int32_t* r, int& k) {
  k = 0;
  for (int i = 0; i < n; ++i) {
    if (!t[i].has(x)) continue;
    const std::int32_t y3[3] = {t[i].a, t[i].b, t[i].c};
    for (int a = 0; a < 3; ++a) {
      const std::int32_t y = y3[a];
      if (y == x) continue;
      bool seen = false;
      for (int h = 0; h < k && !seen; ++h) seen = r[h] == y;
      if (seen) continue;
      if (k == kRing) return false;
      r[k++] = y;
    }
  }
  return true;
}

// The tetrahedra around the edge (v, u) as star(v) and star(u) have them (both have the edge):
// rings A (the link vertices next to u in star(v)) and B (next to v in star(u)). Where they
// differ, a vertex of B that lies in the sphere of one of star(v)'s tetrahedra at u is asked
// of star(v), and the other way round. (Most missing neighbours show here first: a point y the
// working sets missed between v and its neighbours is in the ring of v in star(u), and inside
// a sphere of star(v).)
template <class Ask>
GG_HD inline void edge_rings(const Geo& g, std::int32_t v, const LinkTri* tv, int nv,
                             const std::int32_t* A, int na, std::int32_t u, const LinkTri* tu,
                             int nu, const std::int32_t* B, int nb, Ask ask) {
  auto pull = [&](std::int32_t s, const LinkTri* ts, int ns, std::int32_t at,
                  const std::int32_t* mine, int nm, const std::int32_t* theirs, int nt) {
    for (int j = 0; j < nt; ++j) {
      const std::int32_t y = theirs[j];
      if (y == g.m || y == s) continue;
      bool in = false;
      for (int h = 0; h < nm && !in; ++h) in = mine[h] == y;
      if (in) continue;
      for (int h = 0; h < ns; ++h)
        if (ts[h].has(at) && link_reflex(g, s, ts[h], y)) {
          ask(s, y);
          break;
        }
    }
  };
  pull(v, tv, nv, u, A, na, B, nb);
  pull(u, tu, nu, v, B, nb, A, na);
}

// The vertex round's check of the link vertex u of star(v); hv: the hash of u's ring in star(v)
// (its vertex table's entry). Where star(u) has v too (in its vertex table, vu[0, ku)), equal
// ring hashes pass the pair; else the rings around the edge are compared (edge_rings), once
// for the pair: by the lower of the two where both stars are checked this round (u_listed).
// Where star(u) lacks v, star(u) takes v where v would change it; where it would not, star(u) is
// convex over v and lacks it, so the tetrahedra of star(v) at u are not in star(u): star(u) has
// a vertex inside the sphere of one of them (see the tetrahedra's check), which star(v) takes.
// Returns false where no such vertex was found (an error). Rings longer than kRing are left to
// the tetrahedra's check.
template <class Ask>
GG_HD inline bool check_link_vertex(const Geo& g, std::int32_t v, const LinkTri* tv, int nv,
                                    std::uint32_t hv, std::int32_t u, const LinkTri* tu, int nu,
                                    const LinkVert* vu, int ku, bool u_listed, Ask ask) {
  int j = 0;
  while (j < ku && vu[j].x != v) ++j;
  if (j < ku) {
    if (vu[j].h == hv || (u < v && u_listed)) return true;
    std::int32_t A[kRing], B[kRing];
    int na = 0, nb = 0;
    if (link_ring(tu, nu, v, B, nb) && link_ring(tv, nv, u, A, na))
      edge_rings(g, v, tv, nv, A, na, u, tu, nu, B, nb, ask);
    return true;
  }
  if (link_conflicts(g, u, tu, nu, v)) {
    ask(u, v);
    return true;
  }
  const std::int32_t I = g.m;
  for (int x = 0; x < ku; ++x) {  // (each vertex of star(u) once)
    const std::int32_t y = vu[x].x;
    if (y == v || y == I) continue;
    for (int h = 0; h < nv; ++h)
      if (tv[h].has(u) && !tv[h].has(y) && link_reflex(g, v, tv[h], y)) {
        ask(v, y);
        return true;
      }
  }
  return false;
}

// The vertex round's check of star(v), for the entries [j0, j1) of its vertex table
// (check_link_vertex; a star's entries are checked in pieces by several threads, else one
// thread spent as long on a large star as the rest of the round). listed(u): star(u) is
// checked this round too. fresh(u): star(u) changed in the last take; a pair of stars neither
// of which did was checked after both last changed (every star that changes is listed in the
// next round, which comes before any other take), and would ask for the same again. Returns
// the count of failed checks.
constexpr int kCheckPiece = 4;  // (vertex table entries a thread; a star has about 15)
template <class Listed, class Fresh, class Ask>
GG_HD inline int check_star_vertices(const Geo& g, std::int32_t v, int j0, int j1,
                                     const LinkTri* tri, const LinkVert* vt,
                                     const std::int64_t* off, const std::int32_t* cnt,
                                     const std::int32_t* nvt, Listed listed, Fresh fresh, Ask ask) {
  int stuck = 0;
  const std::int64_t o = off[v];
  const bool fresh_v = fresh(v);
  for (int j = j0; j < j1; ++j) {
    const LinkVert e = vt[o + j];
    const std::int32_t u = e.x;
    if (u == g.m || (!fresh_v && !fresh(u))) continue;
    const std::int64_t ou = off[u];
    if (!check_link_vertex(g, v, tri + o, cnt[v], e.h, u, tri + ou, cnt[u], vt + ou, nvt[u],
                           listed(u), ask))
      ++stuck;
  }
  return stuck;
}

// The tetrahedra's check of the triangle i of star(v): the tetrahedron must be in the stars of
// its other finite vertices; where star(w) lacks it, star(w) takes those of its vertices that
// would change it, and where none would, star(w) holds a vertex inside the tetrahedron's sphere,
// which star(v) takes. Returns the count of failed checks.
template <class Ask>
GG_HD inline int check_tetrahedron(const Geo& g, std::int32_t v, const LinkTri& t,
                                   const LinkTri* tri, const std::int64_t* off,
                                   const std::int32_t* cnt, Ask ask) {
  const std::int32_t I = g.m;
  const std::int32_t q[4] = {v, t.a, t.b, t.c};
  int stuck = 0;
  for (int k = 1; k < 4; ++k) {
    const std::int32_t w = q[k];
    if (w == I) continue;
    std::int32_t o[3];
    for (int a = 0, z = 0; a < 4; ++a)
      if (a != k) o[z++] = q[a];
    const LinkTri* tw = tri + off[w];
    const int nw = cnt[w];
    if (link_find(tw, nw, o[0], o[1], o[2]) >= 0) continue;
    bool asked = false;
    for (int a = 0; a < 3; ++a)
      if (!link_has_vertex(tw, nw, o[a]) && link_conflicts(g, w, tw, nw, o[a])) {
        ask(w, o[a]);
        asked = true;
      }
    for (int x = 0; x < nw && !asked; ++x) {
      const std::int32_t y3[3] = {tw[x].a, tw[x].b, tw[x].c};
      for (int a = 0; a < 3 && !asked; ++a) {
        const std::int32_t y = y3[a];
        if (y == q[0] || y == q[1] || y == q[2] || y == q[3]) continue;
        if (in_sphere_ext(g, q, y)) {
          ask(v, y);
          asked = true;
        }
      }
    }
    if (!asked) ++stuck;
  }
  return stuck;
}

// The proof that the stars agree, a triangle at a time: each tetrahedron is counted from its
// lowest finite built vertex's star, looked up in the stars of its other finite built vertices.
// prove_triangle gives, for the triangle t of star(v), 0 where v is not that vertex, else 1 plus
// the lookups that succeed, or a failure where one fails. Every star holds a tetrahedron
// once, so the stars agree exactly when nothing fails and the sum over every built star's
// triangles is their count: a tetrahedron that some star held but its lowest vertex's star did not
// would be a triangle left over. built(w): 0 where star(w) is not built (SplayScope: the
// tetrahedralisation's star, which agrees with every star built from it and never changed; a
// changed star with such a vertex fails), 1 built, 2 changed. (A thread per triangle: a thread
// per star spent seconds on the stars of thousands of triangles over grids' hull planes.)
struct ProofSum {
  std::int64_t counted, failed;
};
struct ProofAdd {
  GG_HD ProofSum operator()(const ProofSum& x, const ProofSum& y) const {
    return ProofSum{x.counted + y.counted, x.failed + y.failed};
  }
};
template <class Built>
GG_HD inline ProofSum prove_triangle(const Geo& g, std::int32_t v, const LinkTri& t,
                                     const LinkTri* tri, const std::int64_t* off,
                                     const std::int32_t* cnt, Built built) {
  const std::int32_t I = g.m;
  const std::int32_t q[4] = {v, t.a, t.b, t.c};
  const bool changed = built(v) == 2;
  for (int k = 1; k < 4; ++k) {
    if (q[k] == I) continue;
    if (!built(q[k])) {
      if (changed) return ProofSum{0, 1};
      continue;
    }
    if (q[k] < v) return ProofSum{0, 0};
  }
  std::int64_t mine = 1;
  for (int k = 1; k < 4; ++k) {
    if (q[k] == I || !built(q[k])) continue;
    std::int32_t o[3];
    for (int a = 0, z = 0; a < 4; ++a)
      if (a != k) o[z++] = q[a];
    if (link_find(tri + off[q[k]], cnt[q[k]], o[0], o[1], o[2]) < 0) return ProofSum{0, 1};
    ++mine;
  }
  return ProofSum{mine, 0};
}

// Phase 3: star splaying until every star agrees (see the top). Returns the rounds.
struct SplayCount {
  std::int64_t rounds = 0, insertions = 0, requests = 0, vertex_rounds = 0;
  std::int64_t spills = 0;  // (checks run again for the requests that outgrew the buffer)
  double check_ms = 0, sort_ms = 0, take_ms = 0;  // (where the rounds' time goes)
  bool gave_up = false;                           // a star outgrew kHugeStar (see there)
};
// Stars of points on planes with many points (the hull planes of integer grids) grow to
// thousands of triangles while splaying, a wave a round, and one thread takes each vertex
// into such a star in time linear in its size (quadratic in all): on the GPU a grid of 10^5
// points ran past a minute. Past this size the splaying stops and the caller falls back to the
// incremental method (the same result). Measured largest stars: 62-178 triangles on uniform,
// gaussian, ball, sphere, thin sphere and thin box inputs; 4 278 on a grid of 10^5 points.
constexpr std::int32_t kHugeStar = 512;
// (vertex_rounds false: the tetrahedra's rounds and the proof alone, for the tests of those)
// What a splaying covers. By default every star, built before it starts (the digital method).
// With built set (phase 2 of the incremental method, repair.inl), only the stars near the
// failed vertices: built[v] is 0 where star(v) is not built (it is the tetrahedralisation's),
// 1 where it was built from the tetrahedralisation, 2 where it changed (made anew, or took a
// vertex). The stars built when it starts are checked first, and before each round fill(list, n)
// builds the listed stars that are not built yet and then the stars of the listed stars' link
// vertices, so that a round reads built stars only; a star the splaying never reaches keeps the
// tetrahedralisation's, which agrees with every star built from it (the proof, prove_triangle).
// huge: the size past which the splaying gives up (kHugeStar; none where nothing falls back).
// first: the stars the first round checks (null: the built ones). fill's third argument says
// whether every listed star's link vertices are read this round (the first round, where every
// pair is fresh, and the tetrahedra's rounds); else only the changed ones' are (a pair of
// unchanged stars is not checked again: check_star_vertices).
struct SplayScope {
  std::int8_t* built = nullptr;
  const std::int8_t* first = nullptr;
  std::function<void(const std::int32_t*, std::int64_t, bool)> fill;
  std::int32_t huge = kHugeStar;
};
// The take's arrays (splay_stars): the sorted requests R, each star's first request (first)
// and next (pos), the stars, and what a take marks: next (dirty bits of the stars to check
// again), chg (the take in which a star changed: tk), built (2: changed), grow (no room left).
struct TakeArgs {
  Geo g;
  const unsigned long long* R;
  const std::int32_t* first;
  std::int32_t* pos;
  LinkTri* tri;
  LinkVert* vt;
  std::int64_t* off;
  std::int32_t *cap, *cnt, *nvt;
  std::int8_t* next;
  std::int32_t* chg;
  std::int8_t *built, *grow;
  digital3d_impl::StarCounters* C;
  std::int64_t slots;
  std::int32_t huge, tk, I;
};
// Stars of this many triangles take their vertices on a warp (a thread's sphere tests over the
// thousands of triangles of a grid's hull-plane star, a vertex after another, were most of the
// splaying's time on the GPU); most stars have 20 to 60.
constexpr std::int32_t kWideStar = 256;
constexpr std::int64_t kAllWide = std::int64_t(1) << 16;  // (stars in a take: 2^21 lanes)
// The star of request group k takes its vertices in order, with the lanes L. Wide stars list
// their marked triangles (link_insert's mk) in their own vertex-table area, which is written
// anew once the star changed (a star that marks triangles changes, now or in the next pass).
template <class Lanes>
GG_HD void take_star(const Lanes& L, std::int64_t k, const TakeArgs& a) {
  const std::int32_t e = a.first[k + 1];
  std::int32_t p = a.pos[k];
  const std::int32_t v = std::int32_t(a.R[p] >> 32);
  std::int64_t o = a.off[v];
  std::int32_t cp = a.cap[v];
  int n = a.cnt[v];
  std::int64_t took = 0;
  bool moved = false;
  constexpr int kMarked = 32;
  std::int32_t own[kMarked];
  for (; p < e; ++p) {
    const std::int32_t x = std::int32_t(a.R[p] & 0xFFFFFFFFu);
    if (p > a.first[k] && a.R[p] == a.R[p - 1]) continue;
    bool changed = false;
    LinkTri* t = a.tri + o;
    const bool wide = Lanes::size > 1;
    std::int32_t* mk = wide ? reinterpret_cast<std::int32_t*>(a.vt + o) : own;
    const int r =
        link_insert(L, a.g, v, t, n, cp, x, mk, wide ? 2 * cp : kMarked, [&](const LinkTri& gone) {
          const std::int32_t y3[3] = {gone.a, gone.b, gone.c};
          for (int z = 0; z < 3; ++z)
            if (y3[z] != a.I) a.next[y3[z]] = 3;
          changed = true;
        });
    changed = L.any(changed);
    if (r == kLinkNoRoom) {
      // A new run past the last one, taken here where the slots there allow (a pass more for
      // the few stars that outgrow theirs cost as much as the round's take), else the star
      // stops and grows between passes (regrow_stars).
      const std::int32_t want = grown_cap(cp);
      std::int64_t at = 0;
      if (L.rank == 0) at = atomic_add(&a.C->bump, std::int64_t(want));
      at = L.broadcast(at);
      if (at + want <= a.slots) {
        for (int i = L.rank; i < n; i += L.size) a.tri[at + i] = t[i];
        L.sync();
        o = at;
        cp = want;
        moved = true;  // (its vertex table is written again below, in the new run)
        --p;           // (the same vertex again)
        continue;
      }
      if (L.rank == 0) {
        a.grow[v] = 1;
        atomic_add(&a.C->overflow, std::int64_t(1));
      }
      break;
    }
    if (r == kLinkBroken) {
      if (L.rank == 0) atomic_add(&a.C->broken, std::int64_t(1));
      break;
    }
    if (changed) {
      ++took;
      if (L.rank == 0) {
        a.next[v] = 3, a.chg[v] = a.tk;
        if (a.built) a.built[v] = 2;
      }
    }
    n = r;
    if (n > a.huge) {
      if (L.rank == 0) atomic_add(&a.C->huge, std::int64_t(1));
      ++p;
      break;
    }
  }
  L.sync();
  if (L.rank != 0) return;
  if (moved) a.off[v] = o, a.cap[v] = cp, a.chg[v] = a.tk;
  a.cnt[v] = n;
  a.pos[k] = p;
  if (a.chg[v] == a.tk) a.nvt[v] = link_table(a.tri + o, n, a.vt + o);
  if (took) atomic_add(&a.C->taken, took);
}

inline SplayCount splay_stars(Exec& ex, const Geo& g, StarStore& S,
                              typename Exec::template Buffer<digital3d_impl::StarCounters>& ctr,
                              bool vertex_rounds = true, std::int64_t first_requests = 0,
                              const SplayScope& scope = SplayScope{}) {
  using digital3d_impl::StarCounters;
  using u64 = unsigned long long;
  const std::int64_t m = S.m;
  const std::int32_t I = g.m;
  SplayCount out;
  // Two dirty bits a star: 1 its link vertices, 2 its tetrahedra are to be checked.
  auto dirty_d = ex.template alloc<std::int8_t>(std::size_t(m));
  std::int8_t* dirty = dirty_d.data();
  std::int8_t* built = scope.built;
  const std::int8_t* first_check = scope.first ? scope.first : built;
  if (built)
    ex.for_each_index(
        m, GG_LAMBDA(std::int64_t v) { dirty[v] = first_check[v] ? 3 : 0; });
  else
    ex.fill(dirty, m, std::int8_t(3));
  auto list_d = ex.template alloc<std::int32_t>(std::size_t(m));
  // The round in which a star was last listed for its vertices (check_link_vertex's u_listed).
  auto mark_d = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int32_t* mark = mark_d.data();
  ex.fill(mark, m, std::int32_t(0));
  // The take in which a star last changed (the takes counted from 1; 0: created so, and the
  // first round checks every pair).
  auto chg_d = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int32_t* chg = chg_d.data();
  ex.fill(chg, m, std::int32_t(0));
  std::int32_t takes = 0;
  // (the rounds' buffers, allocated once: a round of a few requests must not pay allocations;
  // the first round asks about 7 a star, later ones far fewer, and a star is one group)
  // (first_requests > 0, for the tests: a smaller buffer, so that requests overflow it)
  std::int64_t req_cap =
      first_requests > 0 ? first_requests : std::max<std::int64_t>(1 << 16, 8 * m);
  auto req = ex.template alloc<u64>(std::size_t(req_cap));
  auto first_d = ex.template alloc<std::int32_t>(std::size_t(m + 1));
  auto pos_d = ex.template alloc<std::int32_t>(std::size_t(m));
  auto grow_d = ex.template alloc<std::int8_t>(std::size_t(m));
  StarCounters* C = ctr.data();
  // The tetrahedra's rounds run only once a proof failed (tets_mode), on the stars changed since
  // (dirty bit 2); a proof that fails with no request since the last one is an error.
  bool tets_mode = !vertex_rounds, asked = true;
  for (;;) {
    // The round's kind: the vertex rounds first (cheap, and most of what is missing); once
    // quiet, the proof (prove_triangle), which ends the splaying where it holds; in tets_mode the
    // tetrahedra's rounds before it.
    std::int32_t* list = list_d.data();
    std::int8_t bit = 1;
    std::int64_t nl = !vertex_rounds
                          ? 0
                          : ex.compact_indices(
                                m, GG_LAMBDA(std::int64_t v) { return (dirty[v] & 1) != 0; }, list);
    if (nl == 0 && tets_mode) {
      bit = 2;
      nl = ex.compact_indices(
          m, GG_LAMBDA(std::int64_t v) { return (dirty[v] & 2) != 0; }, list);
    }
    ++out.rounds;
    if (nl > 0 && scope.fill) scope.fill(list, nl, bit == 2 || takes == 0);
    if (out.rounds > 100000) throw Error(ErrorCode::Internal, "digital 3D Delaunay: splaying");
    auto tc = Clock::now();
    const LinkTri* tri = S.tri.data();
    const std::int64_t* off = S.off.data();
    const std::int32_t* cnt = S.cnt.data();
    if (nl == 0) {
      // (toff: each built star's first triangle among all built stars' triangles)
      auto toff_d = ex.template alloc<std::int64_t>(std::size_t(m + 1));
      std::int64_t* toff = toff_d.data();
      ex.exclusive_scan_of(
          m + 1,
          GG_LAMBDA(std::int64_t v)->std::int64_t {
            return v < m && (!built || built[v]) ? cnt[v] : 0;
          },
          toff);
      std::int64_t ntri = 0;
      ex.to_host(toff + m, 1, &ntri);
      // (kProofPiece triangles a thread, one atomic each for the sums)
      constexpr std::int64_t kProofPiece = 32;
      const StarCounters zero{};
      ex.from_host(&zero, 1, C);
      ex.for_each_index((ntri + kProofPiece - 1) / kProofPiece, GG_LAMBDA(std::int64_t p) {
        const auto built_at = [&](std::int32_t w) -> int { return built ? built[w] : 1; };
        ProofSum sum{0, 0};
        const std::int64_t e1 = (p + 1) * kProofPiece < ntri ? (p + 1) * kProofPiece : ntri;
        for (std::int64_t e = p * kProofPiece; e < e1; ++e) {
          std::int64_t lo = 0, hi = m - 1;  // (the star: the last v with toff[v] <= e)
          while (lo < hi) {
            const std::int64_t mid = (lo + hi + 1) / 2;
            if (toff[mid] <= e)
              lo = mid;
            else
              hi = mid - 1;
          }
          sum = ProofAdd{}(sum, prove_triangle(g, std::int32_t(lo), tri[off[lo] + (e - toff[lo])],
                                               tri, off, cnt, built_at));
        }
        if (sum.counted) atomic_add(&C->requests, sum.counted);
        if (sum.failed) atomic_add(&C->stuck, sum.failed);
      });
      StarCounters c;
      ex.to_host(C, 1, &c);
      const ProofSum sum{c.requests, c.stuck};
      out.check_ms += ms_since(tc);
      if (sum.failed == 0 && sum.counted == ntri) break;  // every star agrees with every other
      if (tets_mode && !asked)
        throw Error(ErrorCode::Internal,
                    "internal error in the digital 3D Delaunay method: the stars disagree but "
                    "checking them asked for nothing; please report this input");
      tets_mode = true;
      asked = false;
      if (built)
        ex.for_each_index(
            m, GG_LAMBDA(std::int64_t v) { dirty[v] = built[v] ? 2 : 0; });
      else
        ex.fill(dirty, m, std::int8_t(2));
      continue;
    }
    const bool vertices = bit == 1;
    out.vertex_rounds += vertices ? 1 : 0;
    {
      const std::int32_t r = std::int32_t(out.rounds);
      ex.for_each_index(
          nl, GG_LAMBDA(std::int64_t j) {
            dirty[list[j]] &= std::int8_t(~bit);
            mark[list[j]] = r;
          });
    }
    // Check (read-only on the stars): requests into req. Vertex rounds: a thread per
    // kCheckPiece entries of the listed stars' vertex tables, or per entry where the stars are
    // few (kAllWide: the launch then lasts as long as its longest thread, and the GPU has
    // threads to spare); tetrahedra rounds: a thread per triangle. toff: the first thread of
    // each listed star.
    const int piece = nl <= kAllWide ? 1 : kCheckPiece;
    const std::int32_t* nvt = S.nvt.data();
    const LinkVert* vt = S.vt.data();
    auto toff_d = ex.template alloc<std::int64_t>(std::size_t(nl + 1));
    std::int64_t* toff = toff_d.data();
    ex.exclusive_scan_of(
        nl + 1,
        GG_LAMBDA(std::int64_t j)->std::int64_t {
          if (j == nl) return 0;
          return vertices ? (nvt[list[j]] + piece - 1) / piece : cnt[list[j]];
        },
        toff);
    std::int64_t ntri = 0;
    ex.to_host(toff + nl, 1, &ntri);
    // Where the requests outgrow req, those that fit stay, and the threads that had one that
    // did not are listed (spill) and run again once req is larger (a request asked twice is
    // taken once), rather than the whole round again.
    auto spill_d = ex.template alloc<std::int64_t>(std::size_t(std::max<std::int64_t>(ntri, 1)));
    typename Exec::template Buffer<std::int64_t> again_d;
    const std::int64_t* again = nullptr;  // (the threads to run again; null: all)
    std::int64_t nrun = ntri, kept = 0, nreq = 0;
    for (;;) {
      StarCounters start{};
      start.requests = kept;
      ex.from_host(&start, 1, C);
      u64* R = req.data();
      std::int64_t* spill = spill_d.data();
      const std::int64_t rc = req_cap;
      const std::int32_t r = std::int32_t(out.rounds);
      ex.for_each_index(
          nrun, GG_LAMBDA(std::int64_t t) {
            const std::int64_t e = again ? again[t] : t;
            // (requests leave a thread kBatch at a time: one atomic for several)
            constexpr int kBatch = 8;
            u64 batch[kBatch];
            int nbatch = 0;
            bool lost = false;
            auto flush = [&] {
              const std::int64_t at = atomic_add(&C->requests, std::int64_t(nbatch));
              for (int k = 0; k < nbatch; ++k)
                if (at + k < rc)
                  R[at + k] = batch[k];
                else
                  lost = true;
              nbatch = 0;
            };
            auto ask = [&](std::int32_t star, std::int32_t vertex) {
              batch[nbatch++] = u64(std::uint32_t(star)) << 32 | std::uint32_t(vertex);
              if (nbatch == kBatch) flush();
            };
            std::int64_t lo = 0, hi = nl - 1;  // (the star: the last j with toff[j] <= e)
            while (lo < hi) {
              const std::int64_t mid = (lo + hi + 1) / 2;
              if (toff[mid] <= e)
                lo = mid;
              else
                hi = mid - 1;
            }
            const std::int32_t v = list[lo];
            int stuck = 0;
            if (vertices) {
              const int j0 = int(e - toff[lo]) * piece;
              const int j1 = j0 + piece < nvt[v] ? j0 + piece : nvt[v];
              stuck = check_star_vertices(
                  g, v, j0, j1, tri, vt, off, cnt, nvt,
                  [&](std::int32_t u) { return mark[u] == r; },
                  [&](std::int32_t u) { return chg[u] == takes; }, ask);
            } else {
              stuck = check_tetrahedron(g, v, tri[off[v] + (e - toff[lo])], tri, off, cnt, ask);
            }
            if (nbatch) flush();
            if (lost) spill[atomic_add(&C->spilled, std::int64_t(1))] = e;
            if (stuck) atomic_add(&C->stuck, std::int64_t(stuck));
          });
      StarCounters c;
      ex.to_host(C, 1, &c);
      if (c.stuck)
        throw Error(ErrorCode::Internal,
                    "internal error in the digital 3D Delaunay method: inconsistent stars that "
                    "no insertion separates; please report this input");
      nreq = c.requests;
      if (nreq <= req_cap) break;
      ++out.spills;
      kept = req_cap;  // (every slot below it was written)
      req_cap = nreq + nreq / 4;
      auto req2 = ex.template alloc<u64>(std::size_t(req_cap));
      ex.copy(req.data(), kept, req2.data());
      req = std::move(req2);
      again_d = ex.template alloc<std::int64_t>(std::size_t(c.spilled));
      ex.copy(spill_d.data(), c.spilled, again_d.data());
      again = again_d.data();
      nrun = c.spilled;
    }
    out.check_ms += ms_since(tc);
    out.requests += nreq;
    if (nreq == 0) continue;
    tc = Clock::now();
    asked = true;
    // Take: sorted requests, one thread per star in vertex order.
    const std::int32_t tk = ++takes;
    u64* R = req.data();
    ex.sort(R, nreq);
    std::int32_t* first = first_d.data();
    const std::int64_t ng = ex.compact_indices(
        nreq, GG_LAMBDA(std::int64_t i) { return i == 0 || (R[i] >> 32) != (R[i - 1] >> 32); },
        first);
    out.sort_ms += ms_since(tc);  // (the compaction's count came back: the sort is done)
    tc = Clock::now();
    {
      const std::int32_t end = std::int32_t(nreq);
      ex.from_host(&end, 1, first + ng);
    }
    std::int32_t* pos = pos_d.data();
    ex.copy(first, ng, pos);
    std::int8_t* next = dirty;
    std::int8_t* grow = grow_d.data();
    for (int pass = 0;; ++pass) {
      if (pass > 40) throw Error(ErrorCode::Internal, "digital 3D Delaunay: stars kept outgrowing");
      StarCounters start{};
      start.bump = S.used;
      ex.from_host(&start, 1, C);
      ex.fill(grow, m, std::int8_t(0));
      LinkTri* tri = S.tri.data();
      LinkVert* vt = S.vt.data();
      std::int64_t* off = S.off.data();
      std::int32_t* cap = S.cap.data();
      std::int32_t* cnt = S.cnt.data();
      std::int32_t* nvt = S.nvt.data();
      const std::int64_t slots = S.slots;
      const std::int32_t huge = scope.huge;
      const TakeArgs a{g,    R,   first, pos,  tri, vt,    off,  cap, cnt, nvt,
                       next, chg, built, grow, C,   slots, huge, tk,  I};
      // Stars of kWideStar triangles or more take on a warp each (take_star), after the rest
      // have taken a thread each; a star that grew past it in the first kernel and stopped
      // (no room) is picked up by the second as the next pass would, the same steps in order.
      // A take of few stars runs every star on a warp: the launch is as long as its longest
      // star's chain of insertions, and the GPU has lanes to spare (phase 2's takes: a
      // failed star takes tens of vertices in its first round).
      const std::int32_t wide = ng <= kAllWide ? 0 : kWideStar;
      if (wide > 0)
        ex.for_each_index(
            ng, GG_LAMBDA(std::int64_t k) {
              if (pos[k] < first[k + 1] && cnt[std::int32_t(R[pos[k]] >> 32)] < wide)
                take_star(SoloLanes{}, k, a);
            });
      ex.for_each_lanes(
          ng, GG_LAMBDA(std::int64_t k, const Exec::Lanes& L) {
            if (pos[k] < first[k + 1] && cnt[std::int32_t(R[pos[k]] >> 32)] >= wide)
              take_star(L, k, a);
          });
      StarCounters c;
      ex.to_host(C, 1, &c);
      S.used = std::min(c.bump, S.slots);  // (past the slots: a run was refused, none is left)
      out.insertions += c.taken;
      if (c.broken)
        throw Error(ErrorCode::Internal,
                    "internal error in the digital 3D Delaunay method: a star that was not "
                    "convex took a vertex; please report this input");
      if (c.huge) {
        out.gave_up = true;
        return out;
      }
      if (!c.overflow) break;
      regrow_stars(ex, S, grow);
    }
    out.take_ms += ms_since(tc);
  }
  return out;
}

// The tetrahedra of consistent stars (splay_stars done), in prepared point indices: each finite
// one from the star of its lowest vertex, in star order, positively oriented; flat ones (four
// points on one plane: the perturbation puts such layers over hull facets' planes) are left out,
// as the incremental method leaves them (repair.inl, drop_flats). Neighbours across faces come from
// the stars' links; -1 on the hull and next to a flat tetrahedron. orig maps the prepared indices
// to the caller's.
inline mesh::Compacted<Exec> star_tets(Exec& ex, const Geo& g, StarStore& S,
                                       const std::int32_t* orig, std::int64_t& flats) {
  const std::int64_t m = S.m;
  const std::int32_t I = g.m;
  const LinkTri* tri = S.tri.data();
  const std::int64_t* off = S.off.data();
  const std::int32_t* cnt = S.cnt.data();
  // Per triangle slot: its tetrahedron's output index, -1 where it gives none here.
  auto idx_d = ex.template alloc<std::int32_t>(std::size_t(S.slots));
  std::int32_t* idx = idx_d.data();
  auto per = ex.template alloc<std::int64_t>(std::size_t(m + 1));
  std::int64_t* np = per.data();
  auto nflat = ex.template alloc<std::int64_t>(1);
  std::int64_t* nf = nflat.data();
  ex.fill(nf, 1, std::int64_t(0));
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        const std::int32_t v = std::int32_t(i);
        const LinkTri* t = tri + off[v];
        std::int32_t k = 0;
        for (int j = 0; j < cnt[v]; ++j) {
          const LinkTri& x = t[j];
          std::int32_t mark = -1;
          if (x.a != I && x.b != I && x.c != I && v < x.a && v < x.b && v < x.c) {
            const std::int32_t q[4] = {v, x.a, x.b, x.c};
            if (!flat_ext(g, q))
              mark = k++;
            else
              atomic_add(nf, std::int64_t(1));
          }
          idx[off[v] + j] = mark;
        }
        np[v] = k;
      });
  ex.fill(np + m, 1, std::int64_t(0));  // (the scan's last term, which no star writes)
  ex.exclusive_scan(np, np, m + 1);
  ex.to_host(nf, 1, &flats);
  std::int64_t count = 0;
  ex.to_host(np + m, 1, &count);
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        const std::int64_t base = np[i];
        for (int j = 0; j < cnt[i]; ++j)
          if (idx[off[i] + j] >= 0) idx[off[i] + j] += std::int32_t(base);
      });
  mesh::Compacted<Exec> f;
  f.count = count;
  f.simplices = ex.template alloc<std::int32_t>(std::size_t(4 * count));
  f.neighbors = ex.template alloc<std::int32_t>(std::size_t(4 * count));
  std::int32_t* sv = f.simplices.data();
  std::int32_t* sn = f.neighbors.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        const std::int32_t v = std::int32_t(i);
        const LinkTri* t = tri + off[v];
        for (int j = 0; j < cnt[v]; ++j) {
          const std::int32_t at = idx[off[v] + j];
          if (at < 0) continue;
          const std::int32_t q[4] = {v, t[j].a, t[j].b, t[j].c};
          for (int k = 0; k < 4; ++k) {
            sv[4 * at + k] = orig[q[k]];
            // The face opposite q[k], seen from its vertex f: in star(f) this tetrahedron is the
            // triangle of the other three, and across the link edge (p, r) of the face lies the
            // neighbour's triangle, whose third vertex d is the neighbour's fourth vertex.
            const std::int32_t f = q[k == 0 ? 1 : 0];
            std::int32_t pr[2], z = 0;
            for (int a = 0; a < 4; ++a)
              if (a != k && q[a] != f) pr[z++] = q[a];
            const LinkTri* tf = tri + off[f];
            const int nf2 = cnt[f];
            std::int32_t d = -1;
            int across = -1;
            for (int a = 0; a < nf2 && d < 0; ++a)
              if (tf[a].has(pr[0]) && tf[a].has(pr[1]) && !tf[a].has(q[k])) {
                d = link_third(tf[a], pr[0], pr[1]);
                across = a;
              }
            std::int32_t nb = -1;
            if (d >= 0 && d != I && f < d && f < pr[0] && f < pr[1]) {
              nb = idx[off[f] + across];  // (f is the neighbour's lowest vertex: that triangle)
            } else if (d >= 0 && d != I) {
              const std::int32_t w[4] = {f, pr[0], pr[1], d};
              std::int32_t lo = w[0];
              for (int a = 1; a < 4; ++a) lo = w[a] < lo ? w[a] : lo;
              std::int32_t o3[3], y = 0;
              for (int a = 0; a < 4; ++a)
                if (w[a] != lo) o3[y++] = w[a];
              const int at2 = link_find(tri + off[lo], cnt[lo], o3[0], o3[1], o3[2]);
              if (at2 >= 0) nb = idx[off[lo] + at2];
            }
            sn[4 * at + k] = nb;
          }
        }
      });
  return f;
}
