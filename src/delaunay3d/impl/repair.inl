// Phase 2 of the incremental method, the patch (repair_stars.inl tells the whole phase): the
// failed vertices' stars splayed, the changed stars' tetrahedra put back into the store, and
// the flat tetrahedra left out. Included after repair_stars.inl.

// Phase 2 on the store tet[0, used) that phase 1 left, where failed[v] != 0 marks the vertices
// of its failed faces. grow(slots) makes room for that many slots and returns the store (which
// may move). Returns the slots in use after; new tetrahedra take the freed slots first.
// (grow is a std::function: nvcc's extended lambdas may not sit in a function templated on a
// local lambda's type)
inline std::int64_t repair_tets(Exec& ex, const Geo& g, Tet* tet, std::int64_t used,
                                const std::int8_t* failed,
                                const std::function<Tet*(std::int64_t)>& grow, RepairCount& rc) {
  const std::int32_t m = g.m, I = m;
  MeshStars M(ex, g, tet, used);
  M.start();
  rc.failed_vertices = M.build_flagged(failed, true);
  M.mark_first();
  auto t0 = Clock::now();
  auto ctr = ex.template alloc<digital3d_impl::StarCounters>(1);
  SplayScope scope;
  scope.built = M.built.data();
  scope.first = M.first_.data();
  scope.fill = [&M](const std::int32_t* list, std::int64_t nl, bool all) { M.fill(list, nl, all); };
  scope.huge = std::numeric_limits<std::int32_t>::max();
  const double built_before = M.build_ms;
  const SplayCount sc = splay_stars(
      ex, g, M.S, ctr, true, std::max<std::int64_t>(1 << 16, 64 * rc.failed_vertices), scope);
  rc.splay_ms = ms_since(t0) - (M.build_ms - built_before);
  rc.rounds = sc.rounds;
  rc.check_ms = sc.check_ms;
  rc.take_ms = sc.take_ms;
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
  // Old against new, per changed star, by one sort of both lists' triangles (a star of
  // thousands of triangles over a grid's hull plane made a search per triangle quadratic):
  // records (star, triangle's sorted vertices), sorted by the last two then, stably, by the
  // first two; a record without an equal neighbour is an old triangle the star lost (its slot is
  // freed) or a new one.
  using u64 = unsigned long long;
  auto rb_d = ex.template alloc<std::int64_t>(std::size_t(nc + 1));
  std::int64_t* rb = rb_d.data();
  ex.exclusive_scan_of(
      nc + 1,
      GG_LAMBDA(std::int64_t j)->std::int64_t { return j < nc ? oc[cv[j]] + cnt[cv[j]] : 0; }, rb);
  std::int64_t nrec = 0;
  ex.to_host(rb + nc, 1, &nrec);
  const std::size_t nr = std::size_t(std::max<std::int64_t>(nrec, 1));
  auto k0_d = ex.template alloc<u64>(nr), k1_d = ex.template alloc<u64>(nr);
  auto s0_d = ex.template alloc<u64>(nr), s1_d = ex.template alloc<u64>(nr);
  auto ref_d = ex.template alloc<std::int64_t>(nr), ord_d = ex.template alloc<std::int64_t>(nr);
  u64 *k0 = k0_d.data(), *k1 = k1_d.data(), *s0 = s0_d.data(), *s1 = s1_d.data();
  std::int64_t* ref = ref_d.data();  // 2 (place in the old stars) or 2 (place in the runs) + 1
  std::int64_t* ord = ord_d.data();
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t j) {
        const std::int32_t v = cv[j];
        for (std::int32_t i = 0; i < oc[v] + cnt[v]; ++i) {
          const bool old = i < oc[v];
          const LinkTri x = old ? ot[oo[v] + i] : tri[off[v] + i - oc[v]];
          std::int32_t y[3] = {x.a, x.b, x.c};
          for (int p = 0; p < 2; ++p)
            for (int q = 0; q < 2 - p; ++q)
              if (y[q] > y[q + 1]) {
                const std::int32_t z = y[q];
                y[q] = y[q + 1], y[q + 1] = z;
              }
          const std::int64_t r = rb[j] + i;
          k0[r] = u64(std::uint32_t(v)) << 32 | std::uint32_t(y[0]);
          k1[r] = u64(std::uint32_t(y[1])) << 32 | std::uint32_t(y[2]);
          ref[r] = old ? 2 * (oo[v] + i) : 2 * (off[v] + i - oc[v]) + 1;
        }
      });
  ex.for_each_index(
      nrec, GG_LAMBDA(std::int64_t r) {
        s1[r] = k1[r];
        ord[r] = r;
      });
  ex.sort_by_key(s1, ord, nrec);
  ex.for_each_index(
      nrec, GG_LAMBDA(std::int64_t i) { s0[i] = k0[ord[i]]; });
  ex.sort_by_key(s0, ord, nrec);
  auto dead_d = ex.template alloc<std::int8_t>(std::size_t(used));
  std::int8_t* dead = dead_d.data();
  ex.fill(dead, used, std::int8_t(0));
  auto fresh_d = ex.template alloc<std::int8_t>(std::size_t(std::max<std::int64_t>(M.S.slots, 1)));
  std::int8_t* fresh = fresh_d.data();  // (per run place: a triangle its star did not have)
  ex.fill(fresh, std::max<std::int64_t>(M.S.slots, 1), std::int8_t(0));
  ex.for_each_index(
      nrec, GG_LAMBDA(std::int64_t i) {
        const std::int64_t r = ord[i];
        auto same = [&](std::int64_t h) {
          return h >= 0 && h < nrec && k0[ord[h]] == k0[r] && k1[ord[h]] == k1[r];
        };
        if (same(i - 1) || same(i + 1)) return;
        if (ref[r] % 2 == 0)
          dead[os[ref[r] / 2]] = 1;
        else
          fresh[ref[r] / 2] = 1;
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
          idx[off[v] + i] = lowest && fresh[off[v] + i] ? k++ : -1;
        }
        per[j] = k;
      });
  ex.fill(per + nc, 1, std::int64_t(0));
  ex.exclusive_scan(per, per, nc + 1);
  std::int64_t nn = 0;
  ex.to_host(per + nc, 1, &nn);
  // Each new tetrahedron's star and place in it, so that what follows runs a thread per new
  // tetrahedron (a thread per star searched a large star's triangles once per face of each of
  // its tetrahedra: the square of its size in one thread; grids' hull-plane stars).
  auto own_d = ex.template alloc<std::int32_t>(std::size_t(std::max<std::int64_t>(nn, 1)));
  auto pos_d = ex.template alloc<std::int64_t>(std::size_t(std::max<std::int64_t>(nn, 1)));
  std::int32_t* own = own_d.data();
  std::int64_t* pos = pos_d.data();
  ex.for_each_index(
      nc, GG_LAMBDA(std::int64_t j) {
        const std::int32_t v = cv[j];
        for (std::int32_t i = 0; i < cnt[v]; ++i)
          if (idx[off[v] + i] >= 0) {
            const std::int32_t k = idx[off[v] + i] += std::int32_t(per[j]);
            own[k] = v;
            pos[k] = off[v] + i;
          }
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
      nn, GG_LAMBDA(std::int64_t at) {
        const LinkTri t = tri[pos[at]];
        const std::int32_t x[3] = {t.a, t.b, t.c};
        const int lo = x[1] < x[0] && x[1] < x[2] ? 1 : x[2] < x[0] && x[2] < x[1] ? 2 : 0;
        tet[slot_of(at)] =
            Tet{{own[at], x[lo], x[(lo + 1) % 3], x[(lo + 2) % 3]}, {-1, -1, -1, -1}};
      });
  // Their neighbours (see the top), and the kept tetrahedra's faces towards them.
  auto err_d = ex.template alloc<std::int64_t>(1);
  std::int64_t* err = err_d.data();
  ex.fill(err, 1, std::int64_t(0));
  ex.for_each_index(
      nn, GG_LAMBDA(std::int64_t at) {
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
          tet[s].n[k] = enc(nb, l);
          if (kept) tet[nb].n[l] = enc(s, k);
        }
      });
  // A guard: every new tetrahedron's neighbours point back at it.
  ex.for_each_index(
      nn, GG_LAMBDA(std::int64_t k) {
        const std::int32_t s = slot_of(k);
        for (int f = 0; f < 4; ++f) {
          const std::int32_t e = tet[s].n[f];
          if (e == kNoNeighbour || tet[simplex_of(e)].v[0] < 0 ||
              tet[simplex_of(e)].n[loc_of(e)] != enc(s, f))
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

// How many flat tetrahedra lie next to the outside (share a face with an infinite one). Flat
// tetrahedra lie in layers over planes of the hull's facets, between the hull's facets on that
// plane and the faces of the tetrahedra of positive volume below them; where there is a layer
// the two differ, so a facet on the plane has a flat tetrahedron under it. None here: none at
// all, and drop_flats need not read every tetrahedron's points (2D's peel looks the same way).
inline std::int64_t flats_next_to_outside(Exec& ex, const Geo& g, const Tet* tet,
                                          std::int64_t used) {
  auto n_d = ex.template alloc<std::int64_t>(1);
  std::int64_t* n = n_d.data();
  ex.fill(n, 1, std::int64_t(0));
  ex.for_each_index(
      used, GG_LAMBDA(std::int64_t t) {
        const Tet T = tet[t];
        if (T.v[0] < 0) return;
        for (int k = 0; k < 4; ++k) {
          if (T.v[k] != g.m) continue;
          const Tet& N = tet[simplex_of(T.n[k])];
          std::int32_t q[4];
          for (int j = 0; j < 4; ++j) q[j] = N.v[j];
          if (flat_ext(g, q)) atomic_add(n, std::int64_t(1));
        }
      });
  std::int64_t flats = 0;
  ex.to_host(n, 1, &flats);
  return flats;
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
