// Phase 2 of the incremental method on the executor (thesis 5.3.2; Shewchuk's star splaying):
// the tetrahedralisation phase 1 left, whose failed faces are not locally Delaunay, repaired by
// the splayer the digital method uses (stars.inl), then its flat tetrahedra left out. Included
// inside an executor's namespace after stars.inl.
//
// A vertex whose faces are all locally Delaunay has a convex star in the tetrahedralisation
// (the link edge (a, b) of star(v) is reflex exactly where the face (v, a, b) is not locally
// Delaunay), so only the failed vertices' stars are made anew: each the convex star of its
// link's vertices (what Flip-Flop on the lifted star gives). The splayer then works on those
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

struct RepairCount {
  std::int64_t failed_vertices = 0, stars_built = 0, stars_changed = 0;
  std::int64_t removed = 0, added = 0, rounds = 0, insertions = 0;
  double build_ms = 0, splay_ms = 0, patch_ms = 0;
};

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
  // tetrahedralisation: copied (built 1), or made anew as the convex star of their link's
  // vertices (create: built 2). flag may be want_ itself, which is left clear. Returns how many
  // were built.
  std::int64_t build_flagged(const std::int8_t* flag, bool create) {
    std::int8_t* want = want_.data();
    const std::int8_t* b = built.data();
    ex_.for_each_index(
        m_, GG_LAMBDA(std::int64_t v) { want[v] = flag[v] && !b[v] ? 1 : 0; });
    const std::int64_t nv = ex_.compact_indices(
        m_, GG_LAMBDA(std::int64_t v) { return want[v] != 0; }, verts_.data());
    if (nv > 0) build(nv, create);
    return nv;
  }

  // The stars of the made stars' old link vertices: a vertex that a made star left out (it was
  // not extreme there) still holds the tetrahedra with it, and the first round must see that.
  void build_old_neighbours() {
    std::int8_t* want = want_.data();
    const std::int8_t* b = built.data();
    const LinkTri* ot = otri_.data();
    const std::int64_t* oo = ooff.data();
    const std::int32_t* oc = ocnt.data();
    const std::int32_t I = m_;
    ex_.for_each_index(
        m_, GG_LAMBDA(std::int64_t v) {
          if (b[v] != 2) return;
          for (std::int32_t i = 0; i < oc[v]; ++i) {
            const LinkTri t = ot[oo[v] + i];
            const std::int32_t y3[3] = {t.a, t.b, t.c};
            for (int a = 0; a < 3; ++a)
              if (y3[a] != I && !b[y3[a]]) want[y3[a]] = 1;
          }
        });
    build_flagged(want, false);
  }

  // Before a splaying round (SplayScope::fill): the listed stars, then their link vertices'.
  void fill(const std::int32_t* list, std::int64_t nl) {
    std::int8_t* want = want_.data();
    const std::int8_t* b = built.data();
    ex_.for_each_index(
        nl, GG_LAMBDA(std::int64_t j) {
          if (!b[list[j]]) want[list[j]] = 1;
        });
    build_flagged(want, false);
    const LinkVert* vt = S.vt.data();
    const std::int64_t* off = S.off.data();
    const std::int32_t* nvt = S.nvt.data();
    const std::int32_t I = m_;
    ex_.for_each_index(
        nl, GG_LAMBDA(std::int64_t j) {
          const std::int32_t v = list[j];
          for (std::int32_t i = 0; i < nvt[v]; ++i) {
            const std::int32_t u = vt[off[v] + i].x;
            if (u != I && !b[u]) want[u] = 1;
          }
        });
    build_flagged(want, false);
  }

  // Builds the stars of verts_[0, nv) (increasing; want_ marks them).
  void build(std::int64_t nv, bool create) {
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
    LinkTri* tri = S.tri.data();
    LinkVert* vt = S.vt.data();
    const std::int64_t* off = S.off.data();
    const std::int32_t* cap = S.cap.data();
    std::int32_t* cnt = S.cnt.data();
    std::int32_t* nvt = S.nvt.data();
    std::int8_t* bl = built.data();
    const LinkTri* ot = otri_.data();
    const std::int64_t* oo = ooff.data();
    const std::int32_t* oc = ocnt.data();
    const Geo g = g_;
    ex_.for_each_index(
        nv, GG_LAMBDA(std::int64_t j) {
          const std::int32_t v = vs[j];
          LinkTri* t = tri + off[v];
          const LinkTri* o = ot + oo[v];
          int n = oc[v];
          if (!create) {
            for (int i = 0; i < n; ++i) t[i] = o[i];
          } else {
            // The link's finite vertices (the vertex table's room holds them), then the convex
            // star of v over them, as the digital method makes a star from its working set.
            LinkVert* x = vt + off[v];
            const int k = link_table_into(o, n, x);
            std::int32_t w[3];
            int nw = 0, first = 0;
            for (int i = 0; i < k && nw < 3; ++i)
              if (x[i].x != I) w[nw++] = x[i].x, first = i + 1;
            if (nw < 3) {  // (a vertex of a tetrahedralisation has three finite neighbours)
              atomic_add(ctr + 1, std::int64_t(1));
              return;
            }
            link_start(g, v, w[0], w[1], w[2], t);
            n = 4;
            for (int i = first; i < k; ++i) {
              if (x[i].x == I) continue;
              const int r = link_insert(g, v, t, n, cap[v], x[i].x, [](const LinkTri&) {});
              if (r < 0) {
                atomic_add(ctr + 1, std::int64_t(1));
                return;
              }
              n = r;
            }
          }
          cnt[v] = n;
          nvt[v] = link_table(t, n, vt + off[v]);
          bl[v] = create ? 2 : 1;
        });
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
    auto t2 = ex_.template alloc<LinkTri>(std::size_t(cap));
    auto s2 = ex_.template alloc<std::int32_t>(std::size_t(cap));
    if (oused_) {
      ex_.copy(otri_.data(), oused_, t2.data());
      ex_.copy(oslot_.data(), oused_, s2.data());
    }
    otri_ = std::move(t2);
    oslot_ = std::move(s2);
    ocap_ = cap;
  }

  // state (public: nvcc's extended lambdas may not live in private members)
  Exec& ex_;
  Geo g_;
  const Tet* tet_;
  std::int64_t used_;
  std::int32_t m_;
  StarStore S;
  typename Exec::template Buffer<std::int8_t> built, want_;
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

// Phase 2 on the store tet[0, used) that phase 1 left, where failed[v] != 0 marks the vertices
// of its failed faces. grow(slots) makes room for that many slots and returns the store (which
// may move). Returns the slots in use after; new tetrahedra take the freed slots first.
template <class Grow>
inline std::int64_t repair_tets(Exec& ex, const Geo& g, Tet* tet, std::int64_t used,
                                const std::int8_t* failed, Grow grow, RepairCount& rc) {
  const std::int32_t m = g.m, I = m;
  MeshStars M(ex, g, tet, used);
  M.start();
  rc.failed_vertices = M.build_flagged(failed, true);
  M.build_old_neighbours();
  auto t0 = Clock::now();
  auto ctr = ex.template alloc<digital3d_impl::StarCounters>(1);
  SplayScope scope;
  scope.built = M.built.data();
  scope.fill = [&M](const std::int32_t* list, std::int64_t nl) { M.fill(list, nl); };
  scope.huge = std::numeric_limits<std::int32_t>::max();
  const double built_before = M.build_ms;
  const SplayCount sc = splay_stars(
      ex, g, M.S, ctr, true, std::max<std::int64_t>(1 << 16, 64 * rc.failed_vertices), scope);
  rc.splay_ms = ms_since(t0) - (M.build_ms - built_before);
  rc.rounds = sc.rounds;
  rc.insertions = sc.insertions;
  t0 = Clock::now();

  // The changed stars, and the old tetrahedra they lost (their slots are freed).
  const std::int8_t* bl = M.built.data();
  auto cv_d = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int32_t* cv = cv_d.data();
  const std::int64_t nc = ex.compact_indices(
      m, GG_LAMBDA(std::int64_t v) { return bl[v] == 2; }, cv);
  rc.stars_changed = nc;
  const LinkTri* tri = M.S.tri.data();
  const std::int64_t* off = M.S.off.data();
  const std::int32_t* cnt = M.S.cnt.data();
  const LinkTri* ot = M.otri_.data();
  const std::int32_t* os = M.oslot_.data();
  const std::int64_t* oo = M.ooff.data();
  const std::int32_t* oc = M.ocnt.data();
  auto dead_d = ex.template alloc<std::int8_t>(std::size_t(used));
  std::int8_t* dead = dead_d.data();
  ex.fill(dead, used, std::int8_t(0));
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t j) {
        const std::int32_t v = cv[j];
        for (std::int32_t i = 0; i < oc[v]; ++i) {
          const LinkTri o = ot[oo[v] + i];
          if (link_find(tri + off[v], cnt[v], o.a, o.b, o.c) < 0) dead[os[oo[v] + i]] = 1;
        }
      });
  // The new tetrahedra: each from its lowest finite vertex's star, where that star held it not
  // before; idx: its index among them (-1 for the other triangles of the changed stars' runs).
  auto idx_d = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(M.S.slots, 1)));
  std::int32_t* idx = idx_d.data();
  auto per_d = ex.template alloc<std::int64_t>(std::size_t(nc + 1));
  std::int64_t* per = per_d.data();
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t j) {
        const std::int32_t v = cv[j];
        const LinkTri* t = tri + off[v];
        std::int32_t k = 0;
        for (std::int32_t i = 0; i < cnt[v]; ++i) {
          const LinkTri x = t[i];
          const bool lowest =
              (x.a == I || x.a > v) && (x.b == I || x.b > v) && (x.c == I || x.c > v);
          idx[off[v] + i] = lowest && link_find(ot + oo[v], oc[v], x.a, x.b, x.c) < 0 ? k++ : -1;
        }
        per[j] = k;
      });
  ex.fill(per + nc, 1, std::int64_t(0));
  ex.exclusive_scan(per, per, nc + 1);
  std::int64_t nn = 0;
  ex.to_host(per + nc, 1, &nn);
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t j) {
        const std::int32_t v = cv[j];
        for (std::int32_t i = 0; i < cnt[v]; ++i)
          if (idx[off[v] + i] >= 0) idx[off[v] + i] += std::int32_t(per[j]);
      });
  // Their slots: the freed ones in slot order, then new ones; freed slots left over die.
  auto fs_d = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(used, 1)));
  std::int32_t* fs = fs_d.data();
  const std::int64_t nd = ex.compact_indices(
      used, GG_LAMBDA(std::int64_t t) { return dead[t] != 0; }, fs);
  rc.removed = nd;
  rc.added = nn;
  const std::int64_t now_used = used + std::max<std::int64_t>(0, nn - nd);
  tet = grow(now_used);
  const std::int64_t first_new = used;
  auto slot_of = GG_LAMBDA(std::int64_t k)->std::int32_t {
    return std::int32_t(k < nd ? fs[k] : first_new + (k - nd));
  };
  if (nd > nn)
    ex.for_each_index(
        nd - nn, GG_LAMBDA(std::int64_t i) {
          tet[fs[nn + i]] = Tet{{-1, -1, -1, -1}, {-1, -1, -1, -1}};
        });
  // The new tetrahedra's vertices: the lowest vertex, then its link triangle turned to start at
  // its lowest vertex (an even permutation: how a star was built must not show in the output).
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t j) {
        const std::int32_t v = cv[j];
        for (std::int32_t i = 0; i < cnt[v]; ++i) {
          const std::int32_t at = idx[off[v] + i];
          if (at < 0) continue;
          const LinkTri t = tri[off[v] + i];
          const std::int32_t x[3] = {t.a, t.b, t.c};
          const int lo = x[1] < x[0] && x[1] < x[2] ? 1 : x[2] < x[0] && x[2] < x[1] ? 2 : 0;
          tet[slot_of(at)] = Tet{{v, x[lo], x[(lo + 1) % 3], x[(lo + 2) % 3]}, {-1, -1, -1, -1}};
        }
      });
  // Their neighbours (see the top), and the kept tetrahedra's faces towards them.
  auto err_d = ex.template alloc<std::int64_t>(1);
  std::int64_t* err = err_d.data();
  ex.fill(err, 1, std::int64_t(0));
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t j) {
        const std::int32_t v = cv[j];
        for (std::int32_t i = 0; i < cnt[v]; ++i) {
          const std::int32_t at = idx[off[v] + i];
          if (at < 0) continue;
          const std::int32_t s = slot_of(at);
          std::int32_t q[4];
          for (int k = 0; k < 4; ++k) q[k] = tet[s].v[k];
          for (int k = 0; k < 4; ++k) {
            std::int32_t fv[3], z = 0;
            for (int a = 0; a < 4; ++a)
              if (a != k) fv[z++] = q[a];
            const int fi = fv[0] != I ? 0 : 1;  // (a face has at most one infinite vertex)
            const std::int32_t f = fv[fi], p = fv[(fi + 1) % 3], r = fv[(fi + 2) % 3];
            const LinkTri* tf = tri + off[f];
            std::int32_t d = -1;
            for (std::int32_t a = 0; a < cnt[f] && d < 0; ++a)
              if (tf[a].has(p) && tf[a].has(r) && !tf[a].has(q[k])) d = link_third(tf[a], p, r);
            if (d < 0) {
              atomic_add(err, std::int64_t(1));
              continue;
            }
            const std::int32_t w[4] = {f, p, r, d};
            bool all_changed = true;
            std::int32_t lo = -1;
            for (int a = 0; a < 4; ++a) {
              if (w[a] == I) continue;
              all_changed = all_changed && bl[w[a]] == 2;
              if (lo < 0 || w[a] < lo) lo = w[a];
            }
            std::int32_t nb = -1;
            if (all_changed) {  // new, where its lowest vertex's star made it
              std::int32_t o3[3], y = 0;
              for (int a = 0; a < 4; ++a)
                if (w[a] != lo) o3[y++] = w[a];
              const int at2 = link_find(tri + off[lo], cnt[lo], o3[0], o3[1], o3[2]);
              if (at2 >= 0 && idx[off[lo] + at2] >= 0) nb = slot_of(idx[off[lo] + at2]);
            }
            bool kept = false;
            if (nb < 0) {  // kept: its slot from f's old star
              for (std::int32_t a = 0; a < oc[f] && nb < 0; ++a) {
                const LinkTri o = ot[oo[f] + a];
                if (o.has(p) && o.has(r) && o.has(d)) nb = os[oo[f] + a];
              }
              kept = nb >= 0 && !dead[nb];
              if (!kept) {
                atomic_add(err, std::int64_t(1));
                continue;
              }
            }
            std::int32_t l = 0;
            while (l < 4 && tet[nb].v[l] != d) ++l;
            if (l == 4) {
              atomic_add(err, std::int64_t(1));
              continue;
            }
            tet[s].n[k] = mesh::enc(nb, l);
            if (kept) tet[nb].n[l] = mesh::enc(s, k);
          }
        }
      });
  // A guard: every new tetrahedron's neighbours point back at it.
  ex.for_each_index(
      nn, GG_LAMBDA(std::int64_t k) {
        const std::int32_t s = slot_of(k);
        for (int f = 0; f < 4; ++f) {
          const std::int32_t e = tet[s].n[f];
          if (e < 0 || tet[mesh::simplex_of(e)].v[0] < 0 ||
              tet[mesh::simplex_of(e)].n[mesh::loc_of(e)] != mesh::enc(s, f))
            atomic_add(err, std::int64_t(1));
        }
      });
  std::int64_t errors = 0;
  ex.to_host(err, 1, &errors);
  if (errors)
    throw Error(ErrorCode::Internal,
                "internal error in 3D Delaunay phase 2: " + std::to_string(errors) +
                    " face(s) of the repaired region could not be linked; please report this "
                    "input");
  rc.stars_built = M.stars_built;
  rc.build_ms = M.build_ms;
  rc.patch_ms = ms_since(t0);
  return now_used;
}

// The flat tetrahedra (flat_ext) leave the store: they lie in layers over hull facets' planes,
// the tetrahedra of positive volume tile the hull by themselves, and the output (finite live
// slots, -1 across a face to a slot that is not) then has the hull's facets on those planes.
// Returns how many went.
inline std::int64_t drop_flats(Exec& ex, const Geo& g, Tet* tet, std::int64_t used) {
  auto n_d = ex.template alloc<std::int64_t>(1);
  std::int64_t* n = n_d.data();
  ex.fill(n, 1, std::int64_t(0));
  ex.for_each_index(
      used, GG_LAMBDA(std::int64_t t) {
        if (tet[t].v[0] < 0) return;
        std::int32_t q[4];
        for (int k = 0; k < 4; ++k) q[k] = tet[t].v[k];
        if (!flat_ext(g, q)) return;
        tet[t].v[0] = -1;
        atomic_add(n, std::int64_t(1));
      });
  std::int64_t flats = 0;
  ex.to_host(n, 1, &flats);
  return flats;
}
