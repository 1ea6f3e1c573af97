// Star splaying's rounds (stars.inl tells the whole method): each star takes the vertices asked
// of it, in vertex order on one thread, round after round until every star agrees; then the
// tetrahedra of the stars. Included after splay_checks.inl.

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
