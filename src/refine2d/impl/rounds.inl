// One round of Delaunay refinement on the executor; included inside
// gpugeom::refine::{cpu,cuda}_impl, with Exec the executor and quality.hpp's geometry.
//
// A round reads the kept constrained Delaunay triangulation (kept_mesh.inl) and decides, in
// parallel and from that triangulation alone, which subsegments to split and which new points
// to add, and which of them go in this round (no two touching one triangle); refine.inl then
// inserts them. Only the round's candidates are judged: the triangles written since they were
// last judged, and those still bad (a triangle found good stays good while it is unchanged; its
// subsegments' encroachment, too, depends only on its own apex). The order of everything written
// is by index (subsegment, triangle), never by thread timing, so the rounds are the same on
// every executor.

template <class T>
using Buf = typename Exec::template Buffer<T>;

// Kinds of input vertices (refine.inl's corner_kinds).
constexpr std::int8_t kCorner = 1, kAcute = 2;

// A triangulation of one round, in the executor's memory; seg holds subsegment indices.
struct RoundMesh {
  const double* xy;
  const std::int32_t *tri, *nbr, *seg;
  const double* attribute;  // region index + 1 per triangle, or null
  std::int64_t nt;
};

// What a round decided, per subsegment and per triangle (the per-triangle arrays are written
// for the round's candidates only).
struct Decisions {
  Buf<std::int32_t> split;    // per subsegment: 1 to split
  Buf<std::int32_t> half;     // per subsegment to split: a half-edge of it (the least seen)
  Buf<double> point;          // per triangle: its new point
  Buf<std::int32_t> land;     // per triangle: the triangle its point lands in (-1: none)
  Buf<std::uint64_t> key;     // per triangle: its rank (lower first) and index
  Buf<std::int8_t> reason;    // per triangle: SmallAngle left (0: none)
  Buf<std::int8_t> large;     // per triangle: 1 when still too large and not refined
  Buf<std::int8_t> rejected;  // per triangle: 1 when its point would encroach (a split instead)
};

// The bounds a triangle is judged by (device-readable).
struct Bounds {
  double sin2 = 0;      // squared sine of the smallest angle allowed (0: none)
  double cot_half = 0;  // cot(bound / 2) / 2: the off-centre's height over the edge's length
  double lens = 1;      // cos^2(2 bound): encroaches()'s diametral lens
  double max_area = 0;  // global (0: none)
  const double* region_area = nullptr;    // per region (<= 0: none), by attribute - 1
  const double* triangle_area = nullptr;  // per triangle, from the host's sizing function
  const double* grid = nullptr;
  std::int64_t rows = 0, cols = 0;
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
};

GG_HD inline double area_bound(const Bounds& b, const RoundMesh& m, std::int64_t t,
                               const double* p0, const double* p1, const double* p2) {
  double a = b.max_area > 0 ? b.max_area : 0;
  auto take = [&a](double v) {
    if (v > 0 && (a == 0 || v < a)) a = v;
  };
  if (b.region_area && m.attribute) {
    const std::int64_t r = std::int64_t(m.attribute[t]);
    if (r > 0) take(b.region_area[r - 1]);
  }
  if (b.triangle_area) take(b.triangle_area[t]);
  if (b.grid) {
    const double cx = add_rn(add_rn(p0[0], p1[0]), p2[0]) / 3.0;
    const double cy = add_rn(add_rn(p0[1], p1[1]), p2[1]) / 3.0;
    take(grid_sample(b.grid, b.rows, b.cols, b.x0, b.y0, b.x1, b.y1, cx, cy));
  }
  return a;
}

// Marks the subsegment on half-edge e for splitting (several threads may): its flag, and the
// least half-edge seen on it (choose() takes the lower of it and its twin).
GG_INLINE void mark(const RoundMesh& m, std::int32_t* split, std::int32_t* half, std::int64_t e) {
  const std::int32_t j = m.seg[e];
  atomic_max(split + j, std::int32_t(1));
  atomic_min(half + j, std::int32_t(e));
}

// The vertices and bases the terminator reads (device-readable).
struct Terminator {
  const std::int32_t* on_base;  // per point: the base segment a split vertex lies on, else -1
  const std::int32_t* base;     // base segment ends, 2 per base
  const std::int8_t* corner;    // per input vertex: its kind (kAcute: a small input angle)
  std::int64_t n_in;
};

// Shewchuk's terminator, for a triangle whose smallest angle (at vertex k, opposite its shortest
// edge) is below the bound: InputAngle when both edges at that vertex lie on segments (the angle
// is one the input makes), Shell when the shortest edge joins split vertices on two segments
// from one input vertex where segments meet at less than 60 degrees, at equal distances from it
// (concentric-shell vertices of a small input angle, whose split would only cut that angle again);
// else 0.
GG_HD inline std::int8_t forced(const RoundMesh& m, const Terminator& tm, std::int64_t t, int k) {
  if (m.seg[3 * t + (k + 1) % 3] >= 0 && m.seg[3 * t + (k + 2) % 3] >= 0)
    return std::int8_t(SmallAngle::InputAngle);
  const std::int32_t p = m.tri[3 * t + (k + 1) % 3], q = m.tri[3 * t + (k + 2) % 3];
  const std::int32_t bp = tm.on_base[p], bq = tm.on_base[q];
  if (bp < 0 || bq < 0 || bp == bq) return 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const std::int32_t c = tm.base[2 * bp + i];
      if (c != tm.base[2 * bq + j] || c >= tm.n_in || tm.corner[c] != kAcute) continue;
      const double* pc = m.xy + 2 * std::int64_t(c);
      const double* pp = m.xy + 2 * std::int64_t(p);
      const double* pq = m.xy + 2 * std::int64_t(q);
      const double ax = sub_rn(pp[0], pc[0]), ay = sub_rn(pp[1], pc[1]);
      const double bx = sub_rn(pq[0], pc[0]), by = sub_rn(pq[1], pc[1]);
      const double la = add_rn(mul_rn(ax, ax), mul_rn(ay, ay));
      const double lb = add_rn(mul_rn(bx, bx), mul_rn(by, by));
      // Shell vertices are at equal powers of two from the corner, up to their rounding.
      if (std::fabs(sub_rn(la, lb)) <= mul_rn(1e-6, la > lb ? la : lb))
        return std::int8_t(SmallAngle::Shell);
    }
  return 0;
}

// Walks from triangle t towards q without crossing a subsegment. Returns the triangle holding q
// (q strictly inside, or on an edge that is on no subsegment); -1 - e when the subsegment on
// half-edge e stops it (crossed, or holding q); kNoPlace when q is a vertex or the walk ran too
// long.
constexpr std::int64_t kNoPlace = INT64_MIN;
GG_HD inline std::int64_t walk_to(const RoundMesh& m, std::int64_t t, const double* q) {
  double s[pred::kOrient2dScratch];
  for (std::int64_t step = 0; step <= m.nt; ++step) {
    int beyond = -1, zeros = 0, zero_edge = -1;
    for (int i = 0; i < 3; ++i) {
      const int k = int((step + i) % 3);
      const double* a = m.xy + 2 * std::int64_t(m.tri[3 * t + (k + 1) % 3]);
      const double* b = m.xy + 2 * std::int64_t(m.tri[3 * t + (k + 2) % 3]);
      const int o = pred::orient2d(a, b, q, s);
      if (o < 0) {
        beyond = k;
        break;
      }
      if (o == 0) ++zeros, zero_edge = k;
    }
    if (beyond < 0) {
      if (zeros >= 2) return kNoPlace;  // q is a vertex
      if (zeros == 1 && m.seg[3 * t + zero_edge] >= 0) return -1 - (3 * t + zero_edge);
      return t;
    }
    if (m.seg[3 * t + beyond] >= 0) return -1 - (3 * t + beyond);
    const std::int32_t next = m.nbr[3 * t + beyond];
    if (next < 0) return kNoPlace;  // (a boundary edge is always a subsegment)
    t = next;
  }
  return kNoPlace;
}

// The corners (input vertices where segments meet) and the input's size, for the terminator.
struct Corners {
  const std::int8_t* corner;
  std::int64_t n_in;
};

// Shewchuk's terminator for subsegments: a skinny triangle's point that would make the split of
// the subsegment a-b at a small input angle's corner (kAcute) put the new vertex nearer the
// corner than the triangle's shortest edge is long splits nothing (the triangle is left, Shell):
// such splits would only cut the angle at ever smaller shells, and never end.
GG_HD inline bool terminated(const RoundMesh& m, const Corners& cn, std::int32_t a, std::int32_t b,
                             double shortest2) {
  const bool ca = a < cn.n_in && cn.corner[a], cb = b < cn.n_in && cn.corner[b];
  if (ca == cb || (ca ? cn.corner[a] : cn.corner[b]) != kAcute) return false;
  double sp[2];
  const double* pa = m.xy + 2 * std::int64_t(a);
  const double* pb = m.xy + 2 * std::int64_t(b);
  split_point(pa, pb, ca, cb, sp);
  const double* c = ca ? pa : pb;
  const double dx = sub_rn(sp[0], c[0]), dy = sub_rn(sp[1], c[1]);
  return add_rn(mul_rn(dx, dx), mul_rn(dy, dy)) < shortest2;
}

// The slot of triangle u whose neighbour is t (3 when there is none: a broken mesh).
GG_HD inline int slot_facing(const std::int32_t* nbr, std::int64_t u, std::int64_t t) {
  int k = 0;
  while (k < 3 && nbr[3 * u + k] != t) ++k;
  return k;
}

// The ends of half-edge e (its triangle's vertices after the opposite one).
GG_HD inline std::int32_t end_a(const RoundMesh& m, std::int64_t e) {
  return m.tri[3 * (e / 3) + (e % 3 + 1) % 3];
}
GG_HD inline std::int32_t end_b(const RoundMesh& m, std::int64_t e) {
  return m.tri[3 * (e / 3) + (e % 3 + 2) % 3];
}

// Judges the round's candidates (cand: nc triangle indices, or null for every triangle):
// - the subsegments on its edges whose diametral lens holds its apex (encroaches(); that apex is
//   the one vertex to test: the triangle's circumcircle covers the half of the diametral disc on
//   its side unless the apex is inside it, so no other vertex seen from the subsegment can be;
//   Triangle tests the same vertex) are marked for splitting;
// - a bad triangle gets its new point, or splits the subsegment that hides it or that it would
//   encroach upon, or is left (the terminator's triangles, reasons recorded).
// Points are never removed (as in Triangle): a new point that would encroach is not inserted, so
// a free point that encroaches is rare, and the split it causes is all it costs. A candidate
// stays dirty (judged again next round) while it is bad or encroaches.
inline void find_bad(Exec& ex, const RoundMesh& m, const std::int32_t* cand, std::int64_t nc,
                     const Bounds& bounds, const Terminator& tm, const Corners& cn, Decisions& d,
                     std::int8_t* dirty) {
  std::int32_t *split = d.split.data(), *half = d.half.data();
  double* NP = d.point.data();
  std::int32_t* L = d.land.data();
  std::uint64_t* K = d.key.data();
  std::int8_t *R = d.reason.data(), *LG = d.large.data(), *RJ = d.rejected.data();
  const Bounds b = bounds;
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t i) {
        const std::int64_t t = cand ? cand[i] : i;
        L[t] = -1;
        R[t] = 0;
        LG[t] = 0;
        RJ[t] = 0;
        const double* p[3];
        for (int k = 0; k < 3; ++k) p[k] = m.xy + 2 * std::int64_t(m.tri[3 * t + k]);
        bool encroached = false;
        for (int k = 0; k < 3; ++k) {
          if (m.seg[3 * t + k] < 0) continue;
          if (!encroaches(p[(k + 1) % 3], p[(k + 2) % 3], p[k], b.lens)) continue;
          mark(m, split, half, 3 * t + k);
          encroached = true;
        }
        const TriangleShape sh = shape_of(p[0], p[1], p[2]);
        const bool thin = b.sin2 > 0 && skinny(sh, b.sin2);
        const double limit = area_bound(b, m, t, p[0], p[1], p[2]);
        const bool big = limit > 0 && mul_rn(0.5, sh.area2) > limit;
        dirty[t] = thin || big || encroached ? 1 : 0;
        if (!thin && !big) return;
        const int k = sh.shortest;
        if (thin && !big) {
          const std::int8_t f = forced(m, tm, t, k);
          if (f) {
            R[t] = f;
            return;
          }
        }
        // From here the triangle is refined; Limit stays where no point can be placed.
        if (thin) R[t] = std::int8_t(SmallAngle::Limit);
        if (big) LG[t] = 1;
        if (!(sh.area2 > 0)) return;
        double c[2], q[2];
        circumcentre(p[0], p[1], p[2], c);
        if (thin)
          off_centre(p[(k + 1) % 3], p[(k + 2) % 3], c, b.cot_half, q);
        else
          q[0] = c[0], q[1] = c[1];
        if (!std::isfinite(q[0]) || !std::isfinite(q[1])) return;
        // Subsegments in the way: the one hiding q, else those of the landing triangle and its
        // neighbours whose lens q lies in (q would encroach upon them). A skinny triangle splits
        // none the terminator stops; if that leaves none, it is left as it is.
        const bool skinny_only = thin && !big;
        const double shortest2 = sh.l[k];
        const std::int64_t at = walk_to(m, t, q);
        if (at == kNoPlace) return;
        if (at < 0) {
          const std::int64_t e = -1 - at;
          if (skinny_only && terminated(m, cn, end_a(m, e), end_b(m, e), shortest2))
            R[t] = std::int8_t(SmallAngle::Shell);
          else
            mark(m, split, half, e), RJ[t] = 1;
          return;
        }
        int enc = 0, stopped = 0;
        for (int i2 = -1; i2 < 3; ++i2) {
          const std::int64_t u = i2 < 0 ? at : m.nbr[3 * at + i2];
          if (u < 0) continue;
          for (int j = 0; j < 3; ++j) {
            const std::int64_t e = 3 * u + j;
            if (m.seg[e] < 0) continue;
            const std::int32_t ea = end_a(m, e), eb = end_b(m, e);
            if (!encroaches(m.xy + 2 * std::int64_t(ea), m.xy + 2 * std::int64_t(eb), q, b.lens))
              continue;
            ++enc;
            if (skinny_only && terminated(m, cn, ea, eb, shortest2))
              ++stopped;
            else
              mark(m, split, half, e);
          }
        }
        if (enc) {
          if (enc == stopped)
            R[t] = std::int8_t(SmallAngle::Shell);
          else
            RJ[t] = 1;
          return;
        }
        NP[2 * t] = q[0];
        NP[2 * t + 1] = q[1];
        L[t] = std::int32_t(at);
        // (A rank of at least 1: a point's key stays above every split's, see choose().)
        const std::uint32_t rank = badness_rank(sh);
        K[t] = std::uint64_t(rank ? rank : 1u) << 32 | std::uint64_t(t);
      });
}

// A new point's cavity: the triangles whose circumcircles hold it, reachable from its landing
// triangle without crossing a subsegment (the triangles its insertion replaces), at most
// kCavity of them. The in-circle test is the exact predicate's filter, with "cannot tell" taken
// as inside: a definite answer is the exact sign, so the cavity is the same on both executors.
constexpr int kCavity = 64;
GG_HD inline int cavity_of(const RoundMesh& m, std::int32_t land, const double* q,
                           std::int32_t* list) {
  int n = 0;
  list[n++] = land;
  for (int i = 0; i < n; ++i) {
    const std::int64_t t = list[i];
    for (int k = 0; k < 3; ++k) {
      const std::int32_t u = m.nbr[3 * t + k];
      if (u < 0 || m.seg[3 * t + k] >= 0) continue;
      bool seen = false;
      for (int j = 0; j < n && !seen; ++j) seen = list[j] == u;
      if (seen) continue;
      const double* a = m.xy + 2 * std::int64_t(m.tri[3 * std::int64_t(u)]);
      const double* b = m.xy + 2 * std::int64_t(m.tri[3 * std::int64_t(u) + 1]);
      const double* c = m.xy + 2 * std::int64_t(m.tri[3 * std::int64_t(u) + 2]);
      if (pred::incircle_fast(a, b, c, q) < 0) continue;
      if (n == kCavity) return n;  // (a huge cavity: claimed in part)
      list[n++] = u;
    }
  }
  return n;
}

// A round's choice: the subsegment splits and the new points that go in, no two touching one
// triangle. Splits come first (as in Triangle): each claims the triangles beside its
// subsegment with its index. A new point claims its cavity with its key (at least 2^32: a point
// has a positive rank), so every split's claim beats every point's; it goes in when it holds
// all of its cavity: the points of one round replace disjoint sets of triangles, as if inserted
// one after another, so they never crowd each other (two points in one cavity would make an
// edge far shorter than the mesh asks for there, and new bad triangles). A split goes in only
// where its point is a double strictly inside the subsegment and its four triangles keep their
// orientation. The counts are left on the device for the caller's one read: cnt[0] the winning
// splits, cnt[1] the winning points, cnt[2] the triangles the winning splits add (two beside an
// inner subsegment, one on the boundary).
struct Choice {
  Buf<std::int32_t> splits, points;    // winning subsegments, and points as candidate positions
  const std::int32_t* cand = nullptr;  // the candidates (points[i] indexes them)
  Buf<double> at;                      // per subsegment: its split point
  std::int64_t nsplits = 0, npoints = 0, split_tris = 0;  // (set by the caller's read)
};

// A chosen split holds the claims on both triangles beside its subsegment.
struct SplitWins {
  const std::int8_t* ok;
  const std::int32_t *half, *nbr;
  const std::uint64_t* claim;
  GG_HD bool operator()(std::int64_t j) const {
    if (!ok[j]) return false;
    const std::int32_t e = half[j], u = nbr[e];
    return claim[e / 3] == std::uint64_t(j) && (u < 0 || claim[u] == std::uint64_t(j));
  }
};

inline Choice choose(Exec& ex, const RoundMesh& m, Decisions& d, const std::int32_t* cand,
                     std::int64_t nc, std::int64_t nsub, const std::int8_t* corner,
                     std::int64_t n_in, std::int64_t* cnt) {
  Choice c;
  const std::size_t sn = std::size_t(std::max<std::int64_t>(nsub, 1));
  auto claim = ex.template alloc<std::uint64_t>(std::size_t(std::max<std::int64_t>(m.nt, 1)));
  auto ok = ex.template alloc<std::int8_t>(sn);
  c.at = ex.template alloc<double>(2 * sn);
  std::uint64_t* C = claim.data();
  std::int8_t* OK = ok.data();
  double* M = c.at.data();
  ex.fill(C, m.nt, ~std::uint64_t(0));
  const std::int32_t* SP = d.split.data();
  std::int32_t* H = d.half.data();
  const std::int32_t* L = d.land.data();
  const std::uint64_t* K = d.key.data();
  const double* NP = d.point.data();
  ex.for_each_index(
      nsub, GG_LAMBDA(std::int64_t j) {
        OK[j] = 0;
        if (!SP[j]) return;
        // The half-edge on the triangle with the lower index: the same whichever side found it.
        std::int32_t e = H[j];
        const std::int32_t t0 = e / 3, u0 = m.nbr[e];
        if (u0 >= 0 && u0 < t0) {
          const int ku = slot_facing(m.nbr, u0, t0);
          if (ku == 3) return;
          e = 3 * u0 + ku;
        }
        H[j] = e;
        const std::int32_t a = end_a(m, e), b = end_b(m, e);
        const double *pa = m.xy + 2 * std::int64_t(a), *pb = m.xy + 2 * std::int64_t(b);
        double* q = M + 2 * j;
        split_point(pa, pb, a < n_in && corner[a], b < n_in && corner[b], q);
        if (!std::isfinite(q[0]) || !std::isfinite(q[1])) return;
        if ((q[0] == pa[0] && q[1] == pa[1]) || (q[0] == pb[0] && q[1] == pb[1])) return;
        // Both halves of each triangle beside it counter-clockwise (the point is rounded, and may
        // lie a little off the subsegment's line).
        double sc[pred::kOrient2dScratch];
        const std::int32_t t = e / 3;
        const double* pc = m.xy + 2 * std::int64_t(m.tri[3 * std::int64_t(t) + e % 3]);
        if (pred::orient2d(pc, pa, q, sc) <= 0 || pred::orient2d(pc, q, pb, sc) <= 0) return;
        const std::int32_t u = m.nbr[e];
        if (u >= 0) {
          const int ku = slot_facing(m.nbr, u, t);
          if (ku == 3) return;
          const double* pd = m.xy + 2 * std::int64_t(m.tri[3 * std::int64_t(u) + ku]);
          if (pred::orient2d(pd, pb, q, sc) <= 0 || pred::orient2d(pd, q, pa, sc) <= 0) return;
          atomic_min(C + u, std::uint64_t(j));
        }
        atomic_min(C + t, std::uint64_t(j));
        OK[j] = 1;
      });
  // Each point claims its cavity with its rank and its position among the candidates (their
  // order is the triangles', so ties go to the lower triangle); it holds its cavity when every
  // triangle of it kept its key, counted per point in one pass over the claims (no second walk
  // of the cavity).
  auto size = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nc, 1)));
  auto held = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nc, 1)));
  std::int32_t *SZ = size.data(), *HD = held.data();
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t i) {
        const std::int64_t t = cand[i];
        HD[i] = 0;
        SZ[i] = -1;
        if (L[t] < 0) return;
        const std::uint64_t key = (K[t] >> 32 << 32) | std::uint64_t(i);
        std::int32_t list[kCavity];
        const int n = cavity_of(m, L[t], NP + 2 * t, list);
        SZ[i] = n;
        for (int k = 0; k < n; ++k) atomic_min(C + list[k], key);
      });
  ex.for_each_index(
      m.nt, GG_LAMBDA(std::int64_t x) {
        const std::uint64_t v = C[x];
        if (v != ~std::uint64_t(0) && v >> 32) atomic_add(HD + (v & 0xffffffffu), std::int32_t(1));
      });
  c.splits = ex.template alloc<std::int32_t>(sn);
  c.points = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nc, 1)));
  const SplitWins wins{OK, H, m.nbr, C};
  ex.compact_indices_to(
      nsub, GG_LAMBDA(std::int64_t j)->bool { return wins(j); }, c.splits.data(), cnt);
  ex.fill(cnt + 2, 1, std::int64_t(0));
  ex.for_each_index(
      nsub, GG_LAMBDA(std::int64_t j) {
        if (wins(j)) atomic_add(cnt + 2, std::int64_t(m.nbr[H[j]] >= 0 ? 2 : 1));
      });
  // The points that hold their cavities, as positions among the candidates (insert_chosen
  // reads the triangle through cand).
  ex.compact_indices_to(
      nc,
      GG_LAMBDA(std::int64_t i)->bool {
        const std::int64_t t = cand[i];
        if (SZ[i] < 0 || HD[i] != SZ[i]) return false;
        // On an edge of its landing triangle, the triangle beside that edge is split too: it
        // must be this point's as well.
        const std::uint64_t key = (K[t] >> 32 << 32) | std::uint64_t(i);
        const double* q = NP + 2 * t;
        double sc[pred::kOrient2dScratch];
        const std::int64_t l3 = 3 * std::int64_t(L[t]);
        for (int k = 0; k < 3; ++k) {
          const double* a = m.xy + 2 * std::int64_t(m.tri[l3 + (k + 1) % 3]);
          const double* b = m.xy + 2 * std::int64_t(m.tri[l3 + (k + 2) % 3]);
          if (pred::orient2d(a, b, q, sc) != 0) continue;
          const std::int32_t u = m.nbr[l3 + k];
          if (u < 0 || C[u] != key) return false;
        }
        return true;
      },
      c.points.data(), cnt + 1);
  c.cand = cand;
  return c;
}
