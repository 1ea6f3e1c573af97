// Star splaying's checks (stars.inl tells the whole method): the ring of a vertex in a link, the
// edge and link-vertex tests that ask one star for another's vertices, the proof that every star
// agrees, and the scope of the stars a round reads. Included after stars.inl.

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
