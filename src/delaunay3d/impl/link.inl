// Stars as links (thesis 3.2.3 and 5.3.2; Shewchuk's star splaying), for the one splayer
// (stars.inl) that both methods use; included after geometry.inl.
//
// The star of a vertex v is its link: triangles (a, b, c) such that (v, a, b, c) is a positively
// oriented tetrahedron, a triangulated sphere around v (the infinity point is a vertex of the
// links of hull vertices). Lifted to 4D, a star is convex when every link edge is: for link
// triangles (a, b, c) and (b, a, d), d lies outside the sphere of (v, a, b, c). A convex star is
// the star of v in the Delaunay tetrahedralisation of v and its link's vertices, and it takes a
// vertex x as Bowyer-Watson would: the triangles whose spheres contain x go, and x is joined to
// the boundary of the region they covered.

struct LinkTri {
  std::int32_t a, b, c;
  GG_INLINE bool has(std::int32_t x) const { return a == x || b == x || c == x; }
};

// (A triangle a conflict mark is on keeps ~a in a: vertices are never negative.)
GG_INLINE std::int32_t link_unmark(std::int32_t a) {
  return a < 0 ? ~a : a;
}

// The lowest set lane of a ballot's mask (not 0).
GG_INLINE int lowest_lane(std::uint32_t mask) {
#ifdef __CUDA_ARCH__
  return __ffs(int(mask)) - 1;
#else
  return __builtin_ctz(mask);
#endif
}
// f() on lane 0 alone, its int result to every lane (a predicate that may borrow scratch for
// its exact stages is then asked once, not once a lane).
template <class Lanes, class F>
GG_HD int on_lane0(const Lanes& L, F f) {
  int r = 0;
  if (L.rank == 0) r = f();
  return L.broadcast(r);
}

// The first triangle with the directed edge a -> b among t[0, n), or -1 (marks ignored); the
// lanes L scan it together.
template <class Lanes>
GG_HD int link_find_edge(const Lanes& L, const LinkTri* t, int n, std::int32_t a, std::int32_t b) {
  for (int base = 0; base < n; base += L.size) {
    const int i = base + L.rank;
    bool hit = false;
    if (i < n) {
      const std::int32_t x = link_unmark(t[i].a);
      hit = (x == a && t[i].b == b) || (t[i].b == a && t[i].c == b) || (t[i].c == a && x == b);
    }
    const std::uint32_t mask = L.ballot(hit);
    if (mask) return base + lowest_lane(mask);
  }
  return -1;
}
// The first triangle at index from or later that has the vertex x, or n.
template <class Lanes>
GG_HD int link_next_with(const Lanes& L, const LinkTri* t, int n, int from, std::int32_t x) {
  for (int base = from; base < n; base += L.size) {
    const int i = base + L.rank;
    const std::uint32_t mask = L.ballot(i < n && t[i].has(x));
    if (mask) return base + lowest_lane(mask);
  }
  return n;
}

// The vertex of t that is neither a nor b.
GG_INLINE std::int32_t link_third(const LinkTri& t, std::int32_t a, std::int32_t b) {
  return t.a != a && t.a != b ? t.a : t.b != a && t.b != b ? t.b : t.c;
}

// The index of the triangle on vertices {a, b, c} (any order), or -1.
GG_HD inline int link_find(const LinkTri* t, int n, std::int32_t a, std::int32_t b,
                           std::int32_t c) {
  for (int i = 0; i < n; ++i)
    if (t[i].has(a) && t[i].has(b) && t[i].has(c)) return i;
  return -1;
}

GG_HD inline bool link_has_vertex(const LinkTri* t, int n, std::int32_t x) {
  for (int i = 0; i < n; ++i)
    if (t[i].has(x)) return true;
  return false;
}

// Is d inside the sphere of the tetrahedron (v, t)? (For a link edge shared with the triangle
// whose third vertex is d: the edge is reflex.)
GG_INLINE bool link_reflex(const Geo& g, std::int32_t v, const LinkTri& t, std::int32_t d) {
  const std::int32_t q[4] = {v, t.a, t.b, t.c};
  return in_sphere_ext(g, q, d);
}

// Would the convex star t[0, n) of v change by taking x (some triangle's sphere holds x)?
GG_HD inline bool link_conflicts(const Geo& g, std::int32_t v, const LinkTri* t, int n,
                                 std::int32_t x) {
  if (x == v || x == g.m) return false;  // (the infinity point is inside no sphere)
  for (int i = 0; i < n; ++i)
    if (link_reflex(g, v, t[i], x)) return true;
  return false;
}

// The first convex star of v: the link of v among {v, a, b, c, infinity}, the face (a, b, c) and
// three triangles with the infinity point, each turned to be positively oriented around v. t
// needs room for 4. (A star built from a few points need not hold the kernel point s for which
// orient_ext reads the infinity point, so the infinite triangles are turned by the star's own
// points: (v, x, y, infinity) is positive when the rest of the star lies on the negative side of
// (v, x, y), as a hull facet's tetrahedron with the infinity point has the hull's inside there.)
GG_HD inline void link_start(const Geo& g, std::int32_t v, std::int32_t a, std::int32_t b,
                             std::int32_t c, LinkTri* t) {
  const std::int32_t I = g.m;
  const bool pos = orient_ext(g, v, a, b, c) > 0;
  t[0] = pos ? LinkTri{a, b, c} : LinkTri{a, c, b};
  // (with (a, b, c) positive around v, each edge taken backwards has the star on its negative
  // side)
  const LinkTri& f = t[0];
  t[1] = LinkTri{f.b, f.a, I};
  t[2] = LinkTri{f.c, f.b, I};
  t[3] = LinkTri{f.a, f.c, I};
}

// Link insertion's outcomes besides the new count.
constexpr int kLinkNoRoom = -1;  // it would not fit in cap (t unchanged)
constexpr int kLinkBroken = -2;  // a new triangle was not positive: the star was not convex (t
                                 // unchanged)

// The convex star t[0, n) of v (room for cap) takes x: the triangles whose spheres contain x
// go (gone(tri) is called for each, before it goes) and x is joined to the edges around them.
// Returns the new count, or kLinkNoRoom / kLinkBroken with t as it was. (The count alone does
// not tell a change: a region with one vertex inside has as many edges around as triangles.)
// The new triangles come last, in the order of the edges found.
//
// The region's boundary: the edges of marked triangles whose reverse is in no marked triangle
// (a link is closed, so the triangle across is an unmarked one). Regions are small beside
// large stars, so the marked triangles are listed in mk (room for mk_cap; past it every
// triangle is scanned) and the reverses looked up among them alone: time linear in the star for
// the spheres, quadratic in the region only.
//
// The lanes L (exec/lanes.hpp) share the work: the spheres, the boundary and the compaction
// stride over the lanes, each step ordered by index as one lane would order it, so any number
// of lanes gives the same star. mk is then shared by the lanes; gone runs on the lane that holds
// the triangle.
template <class Lanes, class Gone>
GG_HD int link_insert(const Lanes& L, const Geo& g, std::int32_t v, LinkTri* t, int n, int cap,
                      std::int32_t x, std::int32_t* mk, int mk_cap, Gone gone) {
  if (x == v || x == g.m) return n;
  const int W = L.size;
  int c = 0;
  for (int base = 0; base < n; base += W) {
    const int i = base + L.rank;
    const bool in = i < n && link_reflex(g, v, t[i], x);
    const std::uint32_t mask = L.ballot(in);
    if (in) {
      const int at = c + L.below(mask);
      if (at < mk_cap) mk[at] = i;
      t[i].a = ~t[i].a;
    }
    c += L.count(mask);
  }
  if (c == 0) return n;
  L.sync();  // (the marks and mk, to every lane)
  const bool listed = c <= mk_cap;
  const int k = listed ? c : n;
  auto unmark_all = [&] {
    for (int i = L.rank; i < n; i += W) t[i].a = link_unmark(t[i].a);
    L.sync();
  };
  // Is the directed edge a -> b in a marked triangle?
  auto in_marked = [&](std::int32_t a, std::int32_t b) {
    for (int h = 0; h < k; ++h) {
      const LinkTri& q = t[listed ? mk[h] : h];
      if (q.a >= 0) continue;
      const std::int32_t qa = ~q.a;
      if ((qa == a && q.b == b) || (q.b == a && q.c == b) || (q.c == a && qa == b)) return true;
    }
    return false;
  };
  // The boundary edges of the marked triangle at h (mk's h-th, or t[h]): emit(j, a, b) for
  // each, j counting them; returns the count.
  auto edges_at = [&](int h, auto emit) {
    const LinkTri q = t[listed ? mk[h] : h];
    if (q.a >= 0) return 0;
    const std::int32_t e[3] = {~q.a, q.b, q.c};
    int j = 0;
    for (int z = 0; z < 3; ++z)
      if (!in_marked(e[(z + 1) % 3], e[z])) emit(j++, e[z], e[(z + 1) % 3]);
    return j;
  };
  // The boundary: its size b, then its triangles with x from n on (the edges in h order).
  int b = 0;
  for (int base = 0; base < k; base += W) {
    const int h = base + L.rank;
    const int mine = h < k ? edges_at(h, [](int, std::int32_t, std::int32_t) {}) : 0;
    int all = 0;
    L.exclusive_scan(mine, &all);
    b += all;
  }
  if (n + b > cap) {
    unmark_all();
    return kLinkNoRoom;
  }
  for (int base = 0, w = n; base < k; base += W) {
    const int h = base + L.rank;
    const int mine = h < k ? edges_at(h, [](int, std::int32_t, std::int32_t) {}) : 0;
    int all = 0;
    const int at = w + L.exclusive_scan(mine, &all);
    if (mine)
      edges_at(h, [&](int j, std::int32_t p, std::int32_t q) { t[at + j] = LinkTri{p, q, x}; });
    w += all;
  }
  L.sync();
  // (a guard: a convex star's new triangles are positive by construction; those with the
  // infinity point are left out, see link_start)
  bool bad = false;
  for (int i = n + L.rank; i < n + b; i += W)
    bad = bad || (!t[i].has(g.m) && orient_ext(g, v, t[i].a, t[i].b, t[i].c) <= 0);
  if (L.any(bad)) {
    unmark_all();
    return kLinkBroken;
  }
  // Keep the unmarked, then the new ones, in order (read a stride, then write it: the kept go
  // to places at or below where they were read).
  int kept = 0;
  for (int base = 0; base < n + b; base += W) {
    const int i = base + L.rank;
    LinkTri q{};
    bool keep = false;
    if (i < n + b) {
      q = t[i];
      if (i < n && q.a < 0)
        gone(LinkTri{~q.a, q.b, q.c});
      else
        keep = true;
    }
    const std::uint32_t mask = L.ballot(keep);
    L.sync();
    if (keep) t[kept + L.below(mask)] = q;
    kept += L.count(mask);
  }
  L.sync();
  return kept;
}
// One lane, the marked triangles listed in the thread's own memory.
template <class Gone>
GG_HD int link_insert(const Geo& g, std::int32_t v, LinkTri* t, int n, int cap, std::int32_t x,
                      Gone gone) {
  constexpr int kMarked = 32;
  std::int32_t mk[kMarked];
  return link_insert(SoloLanes{}, g, v, t, n, cap, x, mk, kMarked, gone);
}
