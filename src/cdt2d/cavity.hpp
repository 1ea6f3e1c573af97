// One segment piece's cavity in a triangulation (internal to cdt2d; device and host code).
//
// A segment piece u-w (no input point strictly between) that is not an edge crosses a strip of
// triangles. Removing them leaves two polygons, one on each side of the piece, whose vertices
// all see it; triangulating each by Anglada's rule (the apex of an edge is the polygon vertex
// whose circle through the edge holds no other: "An improved incremental algorithm for
// constructing restricted Delaunay triangulations", 1997; Shewchuk and Brown, "Fast segment
// insertion and incremental construction of constrained Delaunay triangulations", 2015) makes
// the piece an edge and leaves the triangulation constrained Delaunay if it was before. The
// strip of K triangles becomes K triangles again, in the same slots, so cavities that share no
// triangle, and no triangle beside one, are rebuilt at the same time without locks.
//
// Every decision is an exact predicate on the input coordinates.
#pragma once
#include <cstdint>

#include "base/hd.hpp"
#include "exec/atomics.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::cdt {

// The triangulation: counter-clockwise triangles, the triangle opposite vertex k of triangle t at
// nbr[3t + k] (-1 on the hull), the segment an edge lies on at seg[3t + k] (-1: none; marks only
// ever decrease, compared as unsigned so that -1 is the largest), a triangle of each vertex.
struct MeshView {
  const double* xy;
  std::int32_t *tri, *nbr, *seg, *vt;
  GG_HD const double* p(std::int32_t v) const { return xy + 2 * std::int64_t(v); }
};

GG_INLINE int orient(const MeshView& m, std::int32_t a, std::int32_t b, std::int32_t c) {
  if (const int r = pred::orient2d_fast(m.p(a), m.p(b), m.p(c))) return r;
  double s[pred::kOrient2dScratch];
  return pred::orient2d_exact(m.p(a), m.p(b), m.p(c), s);
}

// Is w on the line a-b strictly past u (towards b) and not past b? (u, w on that line.) Points
// of one line are ordered by the coordinate along which it moves more; the sign of a
// difference of doubles is exact.
GG_INLINE bool ahead(const MeshView& m, std::int32_t a, std::int32_t b, std::int32_t u,
                     std::int32_t w) {
  const double *pa = m.p(a), *pb = m.p(b), *pu = m.p(u), *pw = m.p(w);
  const double dx = pb[0] - pa[0], dy = pb[1] - pa[1];
  const int d = (dx < 0 ? -dx : dx) >= (dy < 0 ? -dy : dy) ? 0 : 1;
  const double sgn = pb[d] > pa[d] ? 1.0 : -1.0;
  return (pw[d] - pu[d]) * sgn > 0 && (pb[d] - pw[d]) * sgn >= 0;
}

GG_INLINE int index_of(const MeshView& m, std::int32_t t, std::int32_t v) {
  const std::int32_t* x = m.tri + 3 * std::int64_t(t);
  return x[0] == v ? 0 : x[1] == v ? 1 : 2;
}

// Marks the edge opposite vertex k of triangle t, on both sides, as lying on segment id (the
// smallest id wins where several do).
GG_INLINE void mark_edge(const MeshView& m, std::int32_t t, int k, std::int32_t id) {
  auto* s = reinterpret_cast<std::uint32_t*>(m.seg);
  atomic_min(s + 3 * std::int64_t(t) + k, std::uint32_t(id));
  const std::int32_t o = m.nbr[3 * std::int64_t(t) + k];
  if (o < 0) return;
  int ko = 0;
  while (m.nbr[3 * std::int64_t(o) + ko] != t) ++ko;
  atomic_min(s + 3 * std::int64_t(o) + ko, std::uint32_t(id));
}

// At vertex u of segment a-b: an edge from u to a vertex v on the segment ahead of u (v >= 0;
// the edge opposite vertex k of t), or the triangle t (u its vertex iu) whose corner at u holds
// the direction to b (v = -1), or nothing found (t = -1: the triangulation is broken).
struct Wedge {
  std::int32_t t = -1, v = -1;
  int iu = 0, k = 0;
};

GG_INLINE Wedge find_wedge(const MeshView& m, std::int32_t a, std::int32_t b, std::int32_t u,
                           std::int64_t max_steps) {
  // Counter-clockwise around u from one of its triangles, then clockwise if the hull stops it.
  const std::int32_t start = m.vt[u];
  for (int dir = 0; dir < 2; ++dir) {
    std::int32_t s = start;
    for (std::int64_t steps = 0; s >= 0 && steps <= max_steps; ++steps) {
      const int i = index_of(m, s, u);
      const std::int32_t v1 = m.tri[3 * std::int64_t(s) + (i + 1) % 3],
                         v2 = m.tri[3 * std::int64_t(s) + (i + 2) % 3];
      if (v1 == b || (orient(m, a, b, v1) == 0 && ahead(m, a, b, u, v1)))
        return {s, v1, i, (i + 2) % 3};  // the edge u-v1 is opposite v2
      if (v2 == b || (orient(m, a, b, v2) == 0 && ahead(m, a, b, u, v2)))
        return {s, v2, i, (i + 1) % 3};
      if (orient(m, u, v1, b) > 0 && orient(m, u, v2, b) < 0) return {s, -1, i, 0};
      s = m.nbr[3 * std::int64_t(s) + (dir == 0 ? (i + 1) % 3 : (i + 2) % 3)];
      if (s == start) return {};  // all the way round: no corner holds b
    }
  }
  return {};
}

enum WalkStatus : int { kWalkOk = 0, kWalkCrosses = 1, kWalkLost = 2 };
struct WalkEnd {
  int status = kWalkLost;
  std::int32_t w = -1;      // the piece's far end (kWalkOk)
  std::int32_t other = -1;  // the segment of a crossed edge (kWalkCrosses)
  std::int32_t count = 0;   // triangles crossed
};

// Walks segment a-b from its vertex u through the triangles it crosses (starting in the corner
// wd found) up to the next input point on it, w. The visitor sees each crossed triangle
// (triangle(t)), and the edges of the two polygons in order from u to w: left(x, y, outside,
// mark) for the side left of a->b, right(...) for the other, with the triangle across each
// edge and the edge's segment mark. Stops at an edge already on a segment (the two cross).
template <class Visitor>
GG_INLINE WalkEnd walk_piece(const MeshView& m, std::int32_t a, std::int32_t b, std::int32_t u,
                             const Wedge& wd, std::int64_t max_steps, Visitor& vis) {
  WalkEnd end;
  std::int32_t t = wd.t;
  const std::int64_t t3 = 3 * std::int64_t(t);
  std::int32_t l = m.tri[t3 + (wd.iu + 2) % 3], r = m.tri[t3 + (wd.iu + 1) % 3];
  vis.triangle(t);
  vis.left(u, l, m.nbr[t3 + (wd.iu + 1) % 3], m.seg[t3 + (wd.iu + 1) % 3]);
  vis.right(u, r, m.nbr[t3 + (wd.iu + 2) % 3], m.seg[t3 + (wd.iu + 2) % 3]);
  int k = wd.iu;  // the crossed edge of t: opposite u, then opposite the vertex left behind
  end.count = 1;
  for (std::int64_t steps = 0; steps <= max_steps; ++steps) {
    const std::int64_t tk = 3 * std::int64_t(t) + k;
    if (m.seg[tk] != -1) {
      end.status = kWalkCrosses;
      end.other = m.seg[tk];
      return end;
    }
    const std::int32_t o = m.nbr[tk];
    if (o < 0) return end;  // (lost: a segment cannot leave the hull)
    const std::int64_t o3 = 3 * std::int64_t(o);
    const int il = index_of(m, o, l), ir = index_of(m, o, r), ix = 3 - il - ir;
    const std::int32_t x = m.tri[o3 + ix];
    vis.triangle(o);
    ++end.count;
    const int side = x == b ? 0 : orient(m, a, b, x);
    if (side >= 0) vis.left(l, x, m.nbr[o3 + ir], m.seg[o3 + ir]);  // edge l-x, opposite r
    if (side <= 0) vis.right(r, x, m.nbr[o3 + il], m.seg[o3 + il]);
    if (side == 0) {  // the piece ends at x
      end.status = kWalkOk;
      end.w = x;
      return end;
    }
    if (side > 0)
      l = x, k = il;  // it leaves o by x-r, opposite l
    else
      r = x, k = ir;
    t = o;
  }
  return end;
}

// Scratch ints a cavity of `count` triangles needs for rebuild_cavity.
GG_INLINE std::int64_t cavity_ints(std::int32_t count) {
  return 15 * std::int64_t(count) + 40;
}

// The cavity's arrays in one scratch block: the slots of its triangles, and each polygon's
// vertices from u to w with, per edge, the triangle outside it and its segment mark.
struct CavityCollect {
  std::int32_t *slots, *lv, *lo, *lm, *rv, *ro, *rm;
  std::int32_t ns = 0, nl = 0, nr = 0;
  GG_HD void triangle(std::int32_t t) { slots[ns++] = t; }
  GG_HD void left(std::int32_t x, std::int32_t y, std::int32_t out, std::int32_t mark) {
    if (nl == 0) lv[nl++] = x;
    lo[nl - 1] = out, lm[nl - 1] = mark, lv[nl++] = y;
  }
  GG_HD void right(std::int32_t x, std::int32_t y, std::int32_t out, std::int32_t mark) {
    if (nr == 0) rv[nr++] = x;
    ro[nr - 1] = out, rm[nr - 1] = mark, rv[nr++] = y;
  }
};

// A polygon edge whose outside is the cavity itself: an edge x-y off the piece whose triangles
// on both sides the piece crosses (y's whole fan is crossed when the fan's outline is reflex at
// x). The polygon then runs x, y, x (an antenna), both sides of x-y are polygon edges, and the
// new triangles on them are made neighbours of each other.
constexpr std::int32_t kAntenna = -2;
struct AntennaSides {
  std::int32_t* at;  // (slot, k, x, y) per side
  std::int32_t n = 0;
  GG_HD void add(std::int32_t slot, int k, std::int32_t x, std::int32_t y) {
    at[4 * n] = slot, at[4 * n + 1] = k, at[4 * n + 2] = x, at[4 * n + 3] = y, ++n;
  }
  GG_HD bool pair_up(const MeshView& m) const {
    for (std::int32_t i = 0; i < n; ++i) {
      std::int32_t j = 0;
      while (j < n && !(at[4 * j + 2] == at[4 * i + 3] && at[4 * j + 3] == at[4 * i + 2])) ++j;
      if (j == n) return false;
      m.nbr[3 * std::int64_t(at[4 * i]) + at[4 * i + 1]] = at[4 * j];
    }
    return true;
  }
};

// Triangle `slot` gets the polygon edge x-y (opposite its vertex k), with the triangle outside
// it, which is pointed back at slot.
GG_INLINE void attach(const MeshView& m, std::int32_t slot, int k, std::int32_t x, std::int32_t y,
                      std::int32_t out, std::int32_t mark, AntennaSides& ant) {
  m.seg[3 * std::int64_t(slot) + k] = mark;
  if (out == kAntenna) {
    ant.add(slot, k, x, y);
    return;
  }
  m.nbr[3 * std::int64_t(slot) + k] = out;
  if (out < 0) return;
  const std::int64_t o3 = 3 * std::int64_t(out);
  for (int j = 0; j < 3; ++j) {
    const std::int32_t e1 = m.tri[o3 + (j + 1) % 3], e2 = m.tri[o3 + (j + 2) % 3];
    if ((e1 == x && e2 == y) || (e1 == y && e2 == x)) m.nbr[o3 + j] = slot;
  }
}

// Triangulates the polygon c[0..len-1] (its vertices left of c[0]->c[len-1], each edge
// c[e]-c[e+1] with the triangle outside it o[e] and mark g[e]) by Anglada's rule into the slots
// slots[next...]; returns the slot whose edge c[0]-c[len-1] is opposite its vertex 2, or -1 if
// a triangle came out flat (never, for a cavity of a triangulation). The apex is the first
// vertex with the smallest circle, so an antenna's second copy of x is never one (its circle
// through x would be flat). stack: 4 * len ints.
GG_INLINE std::int32_t triangulate_polygon(const MeshView& m, const std::int32_t* c,
                                           const std::int32_t* o, const std::int32_t* g,
                                           std::int32_t len, const std::int32_t* slots,
                                           std::int32_t& next, std::int32_t* stack,
                                           AntennaSides& ant, double* s) {
  std::int32_t top = -1, sp = 0;
  stack[0] = 0, stack[1] = len - 1, stack[2] = -1, stack[3] = 0, sp = 1;
  while (sp > 0) {
    --sp;
    const std::int32_t i = stack[4 * sp], j = stack[4 * sp + 1], ps = stack[4 * sp + 2],
                       pk = stack[4 * sp + 3];
    std::int32_t a = i + 1;  // the apex: no other vertex inside the circle through c[i], c[j]
    for (std::int32_t v = i + 2; v < j; ++v)
      if (pred::incircle(m.p(c[i]), m.p(c[j]), m.p(c[a]), m.p(c[v]), s) > 0) a = v;
    if (orient(m, c[i], c[j], c[a]) <= 0) return -1;
    const std::int32_t t = slots[next++];
    const std::int64_t t3 = 3 * std::int64_t(t);
    m.tri[t3] = c[i], m.tri[t3 + 1] = c[j], m.tri[t3 + 2] = c[a];
    m.seg[t3 + 2] = -1;
    if (ps >= 0)
      m.nbr[t3 + 2] = ps, m.nbr[3 * std::int64_t(ps) + pk] = t;
    else
      top = t;
    if (j - a == 1) {  // c[a]-c[j], opposite vertex 0
      attach(m, t, 0, c[a], c[j], o[a], g[a], ant);
    } else {
      m.seg[t3] = -1;
      stack[4 * sp] = a, stack[4 * sp + 1] = j, stack[4 * sp + 2] = t, stack[4 * sp + 3] = 0;
      ++sp;
    }
    if (a - i == 1) {  // c[i]-c[a], opposite vertex 1
      attach(m, t, 1, c[i], c[a], o[i], g[i], ant);
    } else {
      m.seg[t3 + 1] = -1;
      stack[4 * sp] = i, stack[4 * sp + 1] = a, stack[4 * sp + 2] = t, stack[4 * sp + 3] = 1;
      ++sp;
    }
    m.vt[c[i]] = t, m.vt[c[j]] = t, m.vt[c[a]] = t;
  }
  return top;
}

template <class T>
GG_INLINE void reverse(T* x, std::int32_t n) {
  for (std::int32_t i = 0, j = n - 1; i < j; ++i, --j) {
    const T v = x[i];
    x[i] = x[j], x[j] = v;
  }
}

// Rebuilds the cavity of segment id's piece from u (its corner wd) so that the piece is an edge
// marked id. mine: an array over the triangles whose entries this call may overwrite for the
// cavity's triangles (the round's claims: the cavity and its outside are this call's alone);
// ints: cavity_ints(count) scratch; s: incircle scratch. Returns the piece's far end, or -1 if
// the cavity could not be rebuilt (a broken triangulation); antennas: the antenna edges met.
GG_INLINE std::int32_t rebuild_cavity(const MeshView& m, std::int32_t a, std::int32_t b,
                                      std::int32_t u, const Wedge& wd, std::int32_t id,
                                      std::int32_t count, std::int64_t max_steps,
                                      std::uint64_t* mine, std::int32_t* ints, double* s,
                                      std::int32_t& antennas) {
  const std::int32_t cap = count + 2;
  CavityCollect cv{ints,
                   ints + count,
                   ints + count + cap,
                   ints + count + 2 * cap,
                   ints + count + 3 * cap,
                   ints + count + 4 * cap,
                   ints + count + 5 * cap};
  std::int32_t* stack = ints + count + 6 * cap;  // 4 * cap
  AntennaSides ant{ints + count + 10 * cap};     // 4 * cap
  const WalkEnd end = walk_piece(m, a, b, u, wd, max_steps, cv);
  if (end.status != kWalkOk || end.count != count || cv.nl + cv.nr != count + 4) return -1;
  // Polygon edges whose outside is one of the cavity's triangles are antenna sides.
  constexpr std::uint64_t kCavity = ~std::uint64_t(0);  // (no claim key: ids are below 2^31)
  for (std::int32_t q = 0; q < count; ++q) mine[cv.slots[q]] = kCavity;
  for (std::int32_t e = 0; e + 1 < cv.nl; ++e)
    if (cv.lo[e] >= 0 && mine[cv.lo[e]] == kCavity) cv.lo[e] = kAntenna;
  for (std::int32_t e = 0; e + 1 < cv.nr; ++e)
    if (cv.ro[e] >= 0 && mine[cv.ro[e]] == kCavity) cv.ro[e] = kAntenna;
  std::int32_t next = 0;
  const std::int32_t lt =
      triangulate_polygon(m, cv.lv, cv.lo, cv.lm, cv.nl, cv.slots, next, stack, ant, s);
  // The right polygon from w back to u has its vertices left of w->u.
  reverse(cv.rv, cv.nr);
  reverse(cv.ro, cv.nr - 1);
  reverse(cv.rm, cv.nr - 1);
  const std::int32_t rt =
      lt < 0 ? -1
             : triangulate_polygon(m, cv.rv, cv.ro, cv.rm, cv.nr, cv.slots, next, stack, ant, s);
  if (rt < 0 || next != count || !ant.pair_up(m)) return -1;
  antennas = ant.n / 2;
  m.nbr[3 * std::int64_t(lt) + 2] = rt, m.nbr[3 * std::int64_t(rt) + 2] = lt;
  m.seg[3 * std::int64_t(lt) + 2] = id, m.seg[3 * std::int64_t(rt) + 2] = id;
  return end.w;
}

}  // namespace gpugeom::cdt
