// Phase 1 of DigiDel3D (thesis 4.5.2) on the executor: the digital Voronoi diagram of the points
// (edt/impl/point_voronoi.inl) and a working set of nearby points for every point. Included
// inside an executor's namespace after point_voronoi.inl.
//
// The grid is read as a perturbed grid (thesis 4.5.1; the grid points moved along the main
// diagonal): the eight cells at a grid corner then meet as the six tetrahedra of the cube of
// their centres around its main diagonal (Freudenthal's split), and two colours are neighbours
// where they share such a tetrahedron with at least one more colour (a digital Voronoi vertex
// where all four differ, an edge where three do; the thesis takes the fours). Missing points
// (a cell's other points) take the working set of their cell's site and the site itself; a set
// with fewer than three points takes its neighbours' sets too, and one still short the first
// points of the input, so that every star can start. Only the stars' speed depends on these
// sets, never the result.

struct WorkingSets {
  typename Exec::template Buffer<std::int64_t> start;  // per point
  typename Exec::template Buffer<std::int32_t> size;   // per point
  typename Exec::template Buffer<std::int32_t> pts;
  std::int64_t pairs = 0, augmented = 0, total = 0;
};

// The frame of side `side` cells along the longest extent of box (at least 2 cells an axis).
inline point_voronoi_impl::CellFrame digital_frame(const mesh::Bounds<3>& box, std::int64_t side) {
  point_voronoi_impl::CellFrame F;
  F.nd = 3;
  double ext = 0;
  for (int a = 0; a < 3; ++a) ext = std::max(ext, box.hi[a] - box.lo[a]);
  F.h = ext > 0 ? ext / double(side) : 1.0;
  for (int a = 0; a < 3; ++a) {
    F.o[a] = box.lo[a];
    const double cells = std::floor((box.hi[a] - box.lo[a]) / F.h) + 1;
    F.n[a] = std::max<std::int64_t>(2, std::min<std::int64_t>(side, std::int64_t(cells)));
  }
  return F;
}

// Pairs of neighbouring colours from the corners, then every point's working set.
inline WorkingSets working_sets(Exec& ex, std::int64_t m, const point_voronoi_impl::CellFrame& F,
                                const PointVoronoi& V) {
  using u64 = unsigned long long;
  WorkingSets W;
  const std::int64_t nx = F.n[0], ny = F.n[1], nz = F.n[2];
  const std::int64_t corners = (nx - 1) * (ny - 1) * (nz - 1);
  const std::int32_t* colour = V.colour.data();
  std::int64_t cap = std::max<std::int64_t>(1 << 16, 40 * m);
  typename Exec::template Buffer<u64> pk;
  auto cnt_d = ex.template alloc<std::int64_t>(1);
  std::int64_t* cnt = cnt_d.data();
  std::int64_t npk = 0;
  for (;;) {
    pk = ex.template alloc<u64>(std::size_t(cap));
    u64* P = pk.data();
    ex.fill(cnt, 1, std::int64_t(0));
    const std::int64_t pc = cap;
    ex.for_each_index(
        corners, GG_LAMBDA(std::int64_t i) {
          const std::int64_t x = i % (nx - 1), y = (i / (nx - 1)) % (ny - 1),
                             z = i / ((nx - 1) * (ny - 1));
          std::int32_t c[8];
          for (int b = 0; b < 8; ++b)
            c[b] = colour[(x + (b & 1)) + nx * ((y + ((b >> 1) & 1)) + ny * (z + (b >> 2)))];
          if (c[0] == c[1] && c[0] == c[2] && c[0] == c[3] && c[0] == c[4] && c[0] == c[5] &&
              c[0] == c[6] && c[0] == c[7])
            return;
          // The six tetrahedra around the diagonal 0 - 7: 0, 2^i, 2^i + 2^j, 7.
          constexpr int kPath[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
          u64 seen[28];
          int ns = 0;
          for (int t = 0; t < 6; ++t) {
            const std::int32_t q[4] = {c[0], c[kPath[t][0]], c[kPath[t][1]], c[7]};
            int distinct = 0;
            for (int a = 0; a < 4; ++a) {
              bool first = true;
              for (int b = 0; b < a; ++b) first = first && q[b] != q[a];
              distinct += first;
            }
            if (distinct < 3) continue;
            for (int a = 0; a < 4; ++a)
              for (int b = a + 1; b < 4; ++b) {
                if (q[a] == q[b]) continue;
                const std::int32_t lo = q[a] < q[b] ? q[a] : q[b], hi = q[a] < q[b] ? q[b] : q[a];
                const u64 key = u64(std::uint32_t(lo)) << 32 | std::uint32_t(hi);
                bool dup = false;
                for (int s = 0; s < ns && !dup; ++s) dup = seen[s] == key;
                if (!dup && ns < 28) seen[ns++] = key;
              }
          }
          if (!ns) return;
          const std::int64_t at = atomic_add(cnt, std::int64_t(2 * ns));
          if (at + 2 * ns > pc) return;
          for (int s = 0; s < ns; ++s) {
            P[at + 2 * s] = seen[s];
            P[at + 2 * s + 1] = (seen[s] << 32) | (seen[s] >> 32);
          }
        });
    ex.to_host(cnt, 1, &npk);
    if (npk <= cap) break;
    cap = npk;
  }
  // Sorted and unique: the directed pairs by their first point, i.e. each colour's neighbours.
  u64* P = pk.data();
  ex.sort(P, npk);
  auto uq = ex.template alloc<u64>(std::size_t(npk));
  {
    auto ids = ex.template alloc<std::int32_t>(std::size_t(npk));
    std::int32_t* id = ids.data();
    const std::int64_t nu = ex.compact_indices(
        npk, GG_LAMBDA(std::int64_t i) { return i == 0 || P[i] != P[i - 1]; }, id);
    u64* U = uq.data();
    ex.for_each_index(
        nu, GG_LAMBDA(std::int64_t j) { U[j] = P[id[j]]; });
    npk = nu;
  }
  pk = typename Exec::template Buffer<u64>();
  W.pairs = npk / 2;
  const u64* U = uq.data();
  // Each site's neighbours: U[nb_start[s], nb_start[s] + nb_size[s]).
  auto nb_start_d = ex.template alloc<std::int64_t>(std::size_t(m + 1));
  auto nb_size_d = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int64_t* nbs = nb_start_d.data();
  std::int32_t* nbn = nb_size_d.data();
  ex.fill(nbn, m, std::int32_t(0));
  ex.for_each_index(
      npk, GG_LAMBDA(std::int64_t i) {
        const std::int32_t a = std::int32_t(U[i] >> 32);
        atomic_add(&nbn[a], std::int32_t(1));
        if (i == 0 || std::int32_t(U[i - 1] >> 32) != a) nbs[a] = i;
      });
  // Each site's cell-mates (the missing points of its cell): mates[ms[s], ms[s] + mn[s]). Where
  // several points share a cell (the dense parts of clustered input), they are one another's
  // neighbours and their neighbours' too, which the diagram cannot show: each set takes the
  // cell-mates of its base site and of that site's neighbours.
  const std::int32_t* cell = V.cell.data();
  auto ms_d = ex.template alloc<std::int64_t>(std::size_t(m));
  auto mn_d = ex.template alloc<std::int32_t>(std::size_t(m));
  auto mates_d = ex.template alloc<u64>(std::size_t(std::max<std::int64_t>(V.nmiss, 1)));
  std::int64_t* ms = ms_d.data();
  std::int32_t* mn = mn_d.data();
  u64* mates = mates_d.data();
  ex.fill(mn, m, std::int32_t(0));
  if (V.nmiss > 0) {
    const std::int32_t* miss = V.missing.data();
    ex.for_each_index(
        V.nmiss, GG_LAMBDA(std::int64_t i) {
          const std::int32_t p = miss[i];
          mates[i] = u64(std::uint32_t(colour[cell[p]])) << 32 | std::uint32_t(p);
        });
    ex.sort(mates, V.nmiss);
    ex.for_each_index(
        V.nmiss, GG_LAMBDA(std::int64_t i) {
          const std::int32_t s = std::int32_t(mates[i] >> 32);
          atomic_add(&mn[s], std::int32_t(1));
          if (i == 0 || std::int32_t(mates[i - 1] >> 32) != s) ms[s] = i;
        });
  }
  // The working sets: sizes (an upper bound first), then the points, de-duplicated.
  W.start = ex.template alloc<std::int64_t>(std::size_t(m + 1));
  W.size = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int64_t* ws = W.start.data();
  std::int32_t* wn = W.size.data();
  const std::int32_t mm = std::int32_t(m);
  // (bound: the base set, the site, the cell-mates, the neighbours' sets where short, three
  // first points)
  ex.exclusive_scan_of(
      m + 1,
      GG_LAMBDA(std::int64_t p)->std::int64_t {
        if (p == m) return 0;
        const std::int32_t base = colour[cell[p]];
        std::int64_t k = nbn[base] + 1 + mn[base];
        for (std::int32_t j = 0; j < nbn[base]; ++j) {
          const std::int32_t u = std::int32_t(U[nbs[base] + j] & 0xFFFFFFFFu);
          k += mn[u] + (nbn[base] < 4 ? nbn[u] : 0);
        }
        return k + 4;
      },
      ws);
  ex.to_host(ws + m, 1, &W.total);
  W.pts = ex.template alloc<std::int32_t>(std::size_t(W.total));
  std::int32_t* wp = W.pts.data();
  auto aug_d = ex.template alloc<std::int64_t>(1);
  std::int64_t* aug = aug_d.data();
  ex.fill(aug, 1, std::int64_t(0));
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        const std::int32_t p = std::int32_t(i);
        std::int32_t* out = wp + ws[p];
        int k = 0;
        auto add = [&](std::int32_t x) {
          if (x == p) return;
          for (int a = 0; a < k; ++a)
            if (out[a] == x) return;
          out[k++] = x;
        };
        const std::int32_t base = colour[cell[p]];
        auto add_mates = [&](std::int32_t s) {
          for (std::int32_t j = 0; j < mn[s]; ++j)
            add(std::int32_t(mates[ms[s] + j] & 0xFFFFFFFFu));
        };
        add(base);
        add_mates(base);
        for (std::int32_t j = 0; j < nbn[base]; ++j) {
          const std::int32_t u = std::int32_t(U[nbs[base] + j] & 0xFFFFFFFFu);
          add(u);
          add_mates(u);
        }
        if (k < 3) {
          atomic_add(aug, std::int64_t(1));
          for (std::int32_t j = 0; j < nbn[base] && nbn[base] < 4; ++j) {
            const std::int32_t u = std::int32_t(U[nbs[base] + j] & 0xFFFFFFFFu);
            for (std::int32_t l = 0; l < nbn[u]; ++l)
              add(std::int32_t(U[nbs[u] + l] & 0xFFFFFFFFu));
          }
        }
        for (std::int32_t x = 0; k < 3 && x < mm; ++x) add(x);
        wn[p] = k;
      });
  ex.to_host(aug, 1, &W.augmented);
  return W;
}
