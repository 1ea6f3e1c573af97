// Weighted Lloyd iteration (thesis 4.2.7), one algorithm for both executors; included inside
// gpugeom::cvd::cpu_impl / cuda_impl with Exec and the matching edt_impl namespace defined.
//
// Each iteration runs entirely on the executor; only three scalars come back:
//   1. the sites become a feature grid and PBA gives every grid point its nearest site;
//   2. chunks (the thesis' method): along the last axis c (y in 2D, z in 3D) the points of one
//      cell form one chunk per column (Lemma 4.3). Column prefix sums of w and t*w, computed
//      once, give each chunk's mass and moment from its two ends. The sums are stored at the
//      column's point in the site's own row (2D) or slice (3D): no other site's chunk of that
//      column can claim it (Lemma 4.1: along the column every candidate of that row is at the
//      same offset, so the row's nearest site wins everywhere in the column);
//   3. the stored sums are reduced into their sites by segmented reductions: runs of equal
//      owner along a line (in 3D first along y into the site's row, then along x into the site),
//      each line walked in bands; the runs a band edge cuts are combined with integer atomics,
//      which are exact, so the result never depends on their order;
//   4. every site moves to the grid point nearest its cell's weighted centroid, if that point
//      is strictly nearer the centroid than the site is (exact integer comparison).
// The moments along x (and y, before the y reduction) are never stored: within a line they are
// the coordinate times the mass.

using u64 = std::uint64_t;
using edt::kNone;

constexpr std::int64_t kWalk = 64;  // entries per band of a segmented reduction

GG_INLINE std::int64_t lane_base(const Layout& L, int a, std::int64_t l) {
  if (a == 0) return l * L.n[0];
  if (a == 1) return (l / L.n[0]) * L.n[0] * L.n[1] + l % L.n[0];
  return l;
}
GG_INLINE void lane_coords(const Layout& L, int a, std::int64_t l, std::int64_t v[3]) {
  if (a == 0)
    v[0] = 0, v[1] = l % L.n[1], v[2] = l / L.n[1];
  else if (a == 1)
    v[0] = l % L.n[0], v[1] = 0, v[2] = l / L.n[0];
  else
    v[0] = l % L.n[0], v[1] = l / L.n[0], v[2] = 0;
}
GG_INLINE void voxel_coords(const Layout& L, std::int64_t i, std::int64_t v[3]) {
  v[0] = i % L.n[0];
  v[1] = (i / L.n[0]) % L.n[1];
  v[2] = i / (L.n[0] * L.n[1]);
}
GG_INLINE void add_u64(u64* p, u64 v) {
  atomic_add(p, v);
}

struct Planes {  // one array per axis; a null entry: moment implied by the coordinate
  u64* p[3];
};

// Prefix sums along the last axis c, computed once: Pm = sum of w, Pc = sum of t * w over the
// column up to and including position t.
inline void column_prefix(Exec& ex, const Layout& L, const std::uint32_t* w, u64* Pm, u64* Pc) {
  const int c = L.nd - 1;
  const std::int64_t len = L.n[c], sc = L.stride(c);
  ex.for_each_index(
      L.count() / len, GG_LAMBDA(std::int64_t col) {  // c is the last axis: col = first index
        u64 m = 0, mc = 0;
        for (std::int64_t t = 0; t < len; ++t) {
          const std::int64_t i = col + t * sc;
          m += w[i];
          mc += u64(t) * w[i];
          Pm[i] = m;
          Pc[i] = mc;
        }
      });
}

// Step 2: every chunk's mass Sm and c-moment Sc at its slot, owner O there (kNone elsewhere).
inline void chunk_sums(Exec& ex, const Layout& L, const std::uint32_t* feat, const u64* Pm,
                       const u64* Pc, std::int32_t* top, u64* Sm, u64* Sc, std::uint32_t* O) {
  const Layout Ly = L;
  const int c = L.nd - 1;
  const std::int64_t len = L.n[c], sc = L.stride(c), n = L.count();
  ex.fill(O, n, kNone);
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {  // the top of each chunk leaves its position at the slot
        const std::int64_t t = i / sc;
        const std::uint32_t f = feat[i];
        if (t > 0 && feat[i - sc] == f) return;
        top[i + (Ly.coord(f, c) - t) * sc] = std::int32_t(t);
      });
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {  // the bottom closes it from the two prefix sums
        const std::int64_t t = i / sc;
        const std::uint32_t f = feat[i];
        if (t + 1 < len && feat[i + sc] == f) return;
        const std::int64_t slot = i + (Ly.coord(f, c) - t) * sc;
        const std::int64_t t0 = top[slot];
        const std::int64_t before = i - (t - t0 + 1) * sc;  // the point above the chunk
        Sm[slot] = Pm[i] - (t0 > 0 ? Pm[before] : 0);
        Sc[slot] = Pc[i] - (t0 > 0 ? Pc[before] : 0);
        O[slot] = f;
      });
}

// Step 3: reduces runs of equal owner along axis a. Into slots (the point of the run's line at
// the owner's coordinate a; out_o records the owner) or, when out_o is null, into sites
// (label[] maps an owner's grid point to its site index).
inline void collapse(Exec& ex, const Layout& L, int a, const u64* in_m, Planes in_mom,
                     const std::uint32_t* in_o, u64* out_m, Planes out_mom, std::uint32_t* out_o,
                     const std::int32_t* label) {
  const Layout Ly = L;
  const std::int64_t len = L.n[a], stride = L.stride(a), lines = L.count() / len;
  const std::int64_t bands = (len + kWalk - 1) / kWalk;
  const int nd = L.nd;
  ex.for_each_index(
      lines * bands, GG_LAMBDA(std::int64_t item) {
        const std::int64_t b = item / lines, l = item % lines;  // neighbouring lines together
        const std::int64_t base = lane_base(Ly, a, l);
        std::int64_t v[3];
        lane_coords(Ly, a, l, v);
        const std::int64_t t1 = (b + 1) * kWalk < len ? (b + 1) * kWalk : len;
        std::uint32_t cur = kNone;
        u64 am = 0, ac[3] = {0, 0, 0};
        auto flush = [&]() {
          if (cur == kNone) return;
          std::int64_t d;
          if (out_o) {
            d = base + Ly.coord(cur, a) * stride;
            cuda::atomic_ref<std::uint32_t, cuda::thread_scope_device>(out_o[d]).store(
                cur, cuda::memory_order_relaxed);  // every writer writes the same owner
          } else {
            d = label[Ly.voxel_of(cur)];
          }
          add_u64(out_m + d, am);
          for (int q = 0; q < nd; ++q)
            if (out_mom.p[q]) add_u64(out_mom.p[q] + d, ac[q]);
        };
        for (std::int64_t t = b * kWalk; t < t1; ++t) {
          const std::int64_t e = base + t * stride;
          const std::uint32_t o = in_o[e];
          if (o == kNone) continue;
          if (o != cur) {
            flush();
            cur = o;
            am = ac[0] = ac[1] = ac[2] = 0;
          }
          const u64 m = in_m[e];
          am += m;
          for (int q = 0; q < nd; ++q)
            ac[q] += in_mom.p[q] ? in_mom.p[q][e] : u64(q == a ? t : v[q]) * m;
        }
        flush();
      });
}

inline void lloyd_impl(const Request& rq, Output& out, CvdStats& stats) {
  Exec ex(rq.run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  const Layout L = rq.layout;
  const int nd = L.nd;
  const std::int64_t n = L.count(), np = rq.pext[0] * rq.pext[1] * rq.pext[2];
  const auto t_setup = Clock::now();
  // The density to weights on the grid, and the initial sites (drawn from it unless given).
  auto w = ex.template alloc<std::uint32_t>(std::size_t(n));
  double vmax = 0;
  std::vector<std::int32_t> sites;
  {
    Quantised Q = quantised_density(ex, rq, np);
    vmax = Q.vmax;
    spread(ex, L, rq.pext, rq.s, Q.q.data(), w.data());
    sites = rq.sites.empty()
                ? draw_sites(ex, L, Q.q.data(), np, rq.pext, rq.s, rq.num_sites, rq.seed)
                : rq.sites;
  }
  const std::int64_t ns = std::int64_t(sites.size()) / nd;
  stats.sites = ns;
  // Units of the results: the progress callback needs the energy's from the first iteration.
  const double unit_mass = vmax / kLevels / std::pow(double(rq.s), nd);
  out.unit_energy = unit_mass / (double(rq.s) * rq.s);
  // Site coordinates as one plane per axis.
  std::vector<std::int32_t> planes(std::size_t(ns) * nd);
  for (std::int64_t i = 0; i < ns; ++i)
    for (int q = 0; q < nd; ++q) planes[std::size_t(q) * ns + i] = sites[i * nd + q];
  auto pos = ex.template alloc<std::int32_t>(planes.size());
  ex.from_host(planes.data(), std::int64_t(planes.size()), pos.data());

  auto Pm = ex.template alloc<u64>(std::size_t(n));
  auto Pc = ex.template alloc<u64>(std::size_t(n));
  column_prefix(ex, L, w.data(), Pm.data(), Pc.data());
  auto feat = ex.template alloc<std::uint32_t>(std::size_t(n));
  auto label = ex.template alloc<std::int32_t>(std::size_t(n));
  auto top = ex.template alloc<std::int32_t>(std::size_t(n));
  auto Sm = ex.template alloc<u64>(std::size_t(n));
  auto Sc = ex.template alloc<u64>(std::size_t(n));
  auto O = ex.template alloc<std::uint32_t>(std::size_t(n));
  const bool three = nd == 3;  // 3D: the y reduction into rows needs its own slots
  auto Rm = ex.template alloc<u64>(three ? std::size_t(n) : 0);
  auto Ry = ex.template alloc<u64>(three ? std::size_t(n) : 0);
  auto Rz = ex.template alloc<u64>(three ? std::size_t(n) : 0);
  auto O2 = ex.template alloc<std::uint32_t>(three ? std::size_t(n) : 0);
  auto acc = ex.template alloc<u64>(std::size_t(ns) * (nd + 1));  // mass, then moments
  auto mass = ex.template alloc<u64>(std::size_t(ns));
  auto scal = ex.template alloc<Scalars>(1);
  ex.sync();
  stats.phase_ms.push_back({"setup", ms_since(t_setup)});

  std::int32_t* P = pos.data();
  std::uint32_t* fp = feat.data();
  std::int32_t* lp = label.data();
  const std::uint32_t* wp = w.data();
  u64* ap = acc.data();
  u64* mp = mass.data();
  Scalars* sp = scal.data();
  const Layout Ly = L;
  const auto t_iter = Clock::now();
  double prev_energy = 0;
  for (int it = 1; it <= rq.max_iterations; ++it) {
    // 1. Sites into a feature grid; label[] at a site's point: the lowest site index there.
    ex.fill(fp, n, kNone);
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) {
          const std::int64_t x = P[i], y = nd > 1 ? P[ns + i] : 0, z = nd > 2 ? P[2 * ns + i] : 0;
          const std::uint32_t s = Ly.pack(x, y, z);
          fp[Ly.voxel_of(s)] = s;
          lp[Ly.voxel_of(s)] = 0x7fffffff;
        });
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) {
          const std::int64_t x = P[i], y = P[ns + i], z = nd > 2 ? P[2 * ns + i] : 0;
          cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> r(
              lp[Ly.voxel_of(Ly.pack(x, y, z))]);
          r.fetch_min(std::int32_t(i), cuda::memory_order_relaxed);
        });
    edt_impl::feature_transform_held(ex, L, edt::Metric{}, fp, ns);
    // Energy of this diagram: every term is an exact integer below 2^53.
    ex.transform_reduce_into(
        n,
        GG_LAMBDA(std::int64_t i)->double {
          std::int64_t v[3];
          voxel_coords(Ly, i, v);
          std::int64_t d2 = 0;
          for (int q = 0; q < nd; ++q) {
            const std::int64_t d = Ly.coord(fp[i], q) - v[q];
            d2 += d * d;
          }
          return double(wp[i]) * double(d2);
        },
        0.0, thrust::plus<double>(), &sp->energy);
    // 2. Chunk sums at their slots.
    chunk_sums(ex, L, fp, Pm.data(), Pc.data(), top.data(), Sm.data(), Sc.data(), O.data());
    // 3. Reductions into the sites.
    ex.fill(ap, ns * (nd + 1), u64(0));
    Planes to_sites{{ap + ns, ap + 2 * ns, three ? ap + 3 * ns : nullptr}};
    if (three) {
      ex.fill(Rm.data(), n, u64(0));
      ex.fill(Ry.data(), n, u64(0));
      ex.fill(Rz.data(), n, u64(0));
      ex.fill(O2.data(), n, kNone);
      collapse(ex, L, 1, Sm.data(), Planes{{nullptr, nullptr, Sc.data()}}, O.data(), Rm.data(),
               Planes{{nullptr, Ry.data(), Rz.data()}}, O2.data(), lp);
      collapse(ex, L, 0, Rm.data(), Planes{{nullptr, Ry.data(), Rz.data()}}, O2.data(), ap,
               to_sites, nullptr, lp);
    } else {
      collapse(ex, L, 0, Sm.data(), Planes{{nullptr, Sc.data(), nullptr}}, O.data(), ap, to_sites,
               nullptr, lp);
    }
    // 4. Moves.
    ex.for_each_index(
        1, GG_LAMBDA(std::int64_t) { sp->max_move2 = 0, sp->moved = 0; });
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) {
          std::int64_t p[3] = {0, 0, 0};
          for (int q = 0; q < nd; ++q) p[q] = P[q * ns + i];
          const bool own = lp[p[0] + Ly.n[0] * (p[1] + Ly.n[1] * p[2])] == i;
          const u64 m = own ? ap[i] : 0;
          mp[i] = m;
          if (m == 0) return;  // a duplicate of an earlier site, or a cell of zero density
          // The nearest grid point r of the centroid M/m, per axis (ties upward); compared with
          // p through |m r - M|^2 summed over the axes, exactly in 128 bits.
          std::int64_t r[3] = {0, 0, 0};
          __int128 dn = 0, dp = 0;
          for (int q = 0; q < nd; ++q) {
            const u64 M = ap[(q + 1) * ns + i];
            r[q] = std::int64_t((2 * M + m) / (2 * m));
            const std::int64_t en = std::int64_t(m) * r[q] - std::int64_t(M);
            const std::int64_t ep = std::int64_t(m) * p[q] - std::int64_t(M);
            dn += __int128(en) * en;
            dp += __int128(ep) * ep;
          }
          if (!(dn < dp)) return;
          u64 mv = 0;
          for (int q = 0; q < nd; ++q) {
            mv += u64((r[q] - p[q]) * (r[q] - p[q]));
            P[q * ns + i] = std::int32_t(r[q]);
          }
          cuda::atomic_ref<u64, cuda::thread_scope_device>(sp->max_move2)
              .fetch_max(mv, cuda::memory_order_relaxed);
          add_u64(&sp->moved, 1);
        });
    Scalars h;
    ex.to_host(sp, 1, &h);  // the iteration's one copy back
    out.energy.push_back(h.energy);
    out.iterations = it;
    const bool go = !rq.progress || rq.progress(it, h);
    const bool still = h.moved == 0 || double(h.max_move2) <= rq.move_tol2;
    const bool flat =
        it > 1 && rq.energy_tol > 0 && prev_energy - h.energy <= rq.energy_tol * prev_energy;
    prev_energy = h.energy;
    if (still || flat) {
      out.converged = true;
      break;
    }
    if (!go) break;
  }
  stats.phase_ms.push_back({"iterations", ms_since(t_iter)});
  stats.iterations = out.iterations;
  // The sites in density pixels and the cells' mass in density times pixel area, made on the
  // executor (the same doubles the host made before), then where the caller wants them.
  out.num_sites = ns;
  auto so = ex.template alloc<double>(std::size_t(ns) * nd);
  auto mo = ex.template alloc<double>(std::size_t(ns));
  double* sd = so.data();
  double* md = mo.data();
  const double sf = rq.s;
  ex.for_each_index(
      ns, GG_LAMBDA(std::int64_t i) {
        for (int q = 0; q < nd; ++q) sd[i * nd + q] = (double(P[q * ns + i]) + 0.5) / sf - 0.5;
        md[i] = double(mp[i]) * unit_mass;
      });
  // (The caller's arrays were checked against the site count before any work: cvd.cpp.)
  if (rq.device_out) {
    auto a = deliver::place(ex, so, ns * nd, rq.into.sites);
    auto b = deliver::place(ex, mo, ns, rq.into.mass);
    ex.sync();  // the caller may read them now (and free them on any stream)
    out.dev_sites = a.own();
    out.dev_mass = b.own();
  } else {
    deliver::to_host(ex, sd, ns * nd, rq.into.sites, out.sites);
    deliver::to_host(ex, md, ns, rq.into.mass, out.mass);
  }
}
