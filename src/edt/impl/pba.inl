// Parallel Banding Algorithm (thesis 4.2), one algorithm for both executors; included inside
// gpugeom::edt::cpu_impl / cuda_impl with Exec defined.
//
// The transform is a sequence of line passes, one per axis (x, then y, then z). In the pass
// along axis a every line holds, at each position, the nearest site found so far within that
// position's hyperplane (or none); the pass replaces it by the nearest site within the line's
// whole plane. Each pass is the thesis' Phase 2 + Phase 3 on every line:
//   stacks  - each band of each line keeps its non-dominated candidates (Lemma 4.2, exact)
//   merge   - bands are merged pairwise, log2(bands) rounds (Algorithm 4.1), lists kept as
//             arrays in place so the merged list of a line starts at its first band
//   colour  - each band finds its first position's winner by binary search on the list, then
//             walks forward (Lemma 4.3).
// Phase 1 (band sweeping) is the same machinery on the x axis, where a candidate is a site of
// the line itself. Work O(M log bands), with NL * bands independent items per step.

// Exact integer arithmetic in doubles on the GPU, in int64 on the CPU (edt_common.hpp).
using Num = std::conditional_t<Exec::backend == Backend::Cuda, double, std::int64_t>;

struct PassGeom {
  int a;
  std::int64_t len, lines, stride;
  std::int64_t bands, band_len;
};

GG_INLINE std::int64_t line_base(const Layout& L, int a, std::int64_t l) {
  if (a == 0) return l * L.n[0];
  if (a == 1) return (l / L.n[0]) * L.n[0] * L.n[1] + l % L.n[0];
  return l;
}
GG_INLINE void line_coords(const Layout& L, int a, std::int64_t l, std::int64_t v[3]) {
  if (a == 0) {
    v[0] = 0, v[1] = l % L.n[1], v[2] = l / L.n[1];
  } else if (a == 1) {
    v[0] = l % L.n[0], v[1] = 0, v[2] = l / L.n[0];
  } else {
    v[0] = l % L.n[0], v[1] = l / L.n[0], v[2] = 0;
  }
  v[2] += L.z0;
}

inline PassGeom make_geom(const Layout& L, int a, std::int64_t want_items, std::int64_t bands) {
  PassGeom g;
  g.a = a;
  g.len = L.n[a];
  g.lines = L.count() / g.len;
  g.stride = L.stride(a);
  if (bands <= 0) {  // enough items to fill the executor, bands of at least 16 positions
    bands = 1;
    while (bands * g.lines < want_items && bands * 2 * 16 <= g.len) bands *= 2;
  }
  g.bands = bands < 1 ? 1 : (bands > g.len ? g.len : bands);
  g.band_len = (g.len + g.bands - 1) / g.bands;
  return g;
}

inline void line_pass(Exec& ex, const Layout& L, const Metric& M, const PassGeom& g,
                      std::uint32_t* cand, std::uint32_t* stk, std::int32_t* counts) {
  const Layout Ly = L;
  const Metric Mt = M;
  const PassGeom G = g;
  // Stacks of non-dominated candidates per band.
  ex.for_each_index(G.lines * G.bands, GG_LAMBDA(std::int64_t item) {
    const std::int64_t b = item / G.lines, l = item % G.lines;
    const std::int64_t base = line_base(Ly, G.a, l);
    std::int64_t v[3];
    line_coords(Ly, G.a, l, v);
    const std::int64_t t0 = b * G.band_len;
    const std::int64_t t1 = t0 + G.band_len < G.len ? t0 + G.band_len : G.len;
    std::uint32_t* s = stk + base + t0 * G.stride;
    std::int32_t n = 0;
    for (std::int64_t t = t0; t < t1; ++t) {
      const std::uint32_t c = cand[base + t * G.stride];
      if (c == kNone) continue;
      while (n >= 2 && dominated<Num>(Ly, Mt, G.a, s[(n - 2) * G.stride], s[(n - 1) * G.stride], c, v)) --n;
      s[n * G.stride] = c;
      ++n;
    }
    counts[item] = n;
  });
  // Pairwise merges of neighbouring band groups.
  for (std::int64_t width = 1; width < G.bands; width *= 2) {
    const std::int64_t groups = (G.bands + 2 * width - 1) / (2 * width);
    const std::int64_t wd = width;
    ex.for_each_index(G.lines * groups, GG_LAMBDA(std::int64_t item) {
      const std::int64_t grp = item / G.lines, l = item % G.lines;
      const std::int64_t bl = grp * 2 * wd, br = bl + wd;
      if (br >= G.bands) return;
      const std::int64_t base = line_base(Ly, G.a, l);
      std::int64_t v[3];
      line_coords(Ly, G.a, l, v);
      std::uint32_t* left = stk + base + bl * G.band_len * G.stride;
      const std::uint32_t* right = stk + base + br * G.band_len * G.stride;
      std::int32_t top = counts[bl * G.lines + l];
      const std::int32_t nr = counts[br * G.lines + l];
      std::int32_t i = 0, from_right = 0;
      for (; i < nr; ++i) {
        const std::uint32_t c = right[i * G.stride];
        while (from_right < 2 && top >= 2 &&
               dominated<Num>(Ly, Mt, G.a, left[(top - 2) * G.stride], left[(top - 1) * G.stride], c, v)) {
          --top;
          from_right = from_right > 0 ? from_right - 1 : 0;
        }
        left[top * G.stride] = c;
        ++top;
        if (++from_right >= 2) {  // right-band sites never dominate each other: copy the rest
          for (++i; i < nr; ++i, ++top) left[top * G.stride] = right[i * G.stride];
          break;
        }
      }
      counts[bl * G.lines + l] = top;
    });
  }
  // Colouring: binary search for each band's first winner, then a forward walk.
  ex.for_each_index(G.lines * G.bands, GG_LAMBDA(std::int64_t item) {
    const std::int64_t b = item / G.lines, l = item % G.lines;
    const std::int64_t base = line_base(Ly, G.a, l);
    std::int64_t v[3];
    line_coords(Ly, G.a, l, v);
    const std::int64_t t0 = b * G.band_len;
    const std::int64_t t1 = t0 + G.band_len < G.len ? t0 + G.band_len : G.len;
    const std::uint32_t* s = stk + base;
    const std::int32_t n = counts[l];
    if (n == 0) {
      for (std::int64_t t = t0; t < t1; ++t) cand[base + t * G.stride] = kNone;
      return;
    }
    v[G.a] = t0;
    std::int32_t lo = 0, hi = n - 1;  // first k whose successor does not beat it at t0
    while (lo < hi) {
      const std::int32_t mid = (lo + hi) / 2;
      if (beats<Num>(Ly, Mt, s[(mid + 1) * G.stride], s[mid * G.stride], v)) lo = mid + 1;
      else hi = mid;
    }
    std::int32_t k = lo;
    for (std::int64_t t = t0; t < t1; ++t) {
      v[G.a] = t;
      while (k + 1 < n && beats<Num>(Ly, Mt, s[(k + 1) * G.stride], s[k * G.stride], v)) ++k;
      cand[base + t * G.stride] = s[k * G.stride];
    }
  });
}

// The x pass of a whole grid, where every candidate is a site of the row itself: the nearest
// site to the left and to the right of each voxel come from a max scan and a reverse min scan
// of site positions over the whole array (positions outside the voxel's row are ignored). All
// accesses are coalesced, unlike a thread walking each row.
inline void x_pass_by_scans(Exec& ex, const Layout& L, std::uint32_t* feat) {
  const std::int64_t n = L.count();
  auto left = ex.template alloc<std::int32_t>(std::size_t(n));
  auto right = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* lp = left.data();
  std::int32_t* rp = right.data();
  ex.for_each_index(n, GG_LAMBDA(std::int64_t i) {
    const bool site = feat[i] != kNone;
    lp[i] = site ? std::int32_t(i) : -1;
    rp[i] = site ? std::int32_t(i) : 0x7fffffff;
  });
  ex.inclusive_scan(lp, lp, n, GG_LAMBDA(std::int32_t a, std::int32_t b) { return a > b ? a : b; }, false);
  ex.inclusive_scan(rp, rp, n, GG_LAMBDA(std::int32_t a, std::int32_t b) { return a < b ? a : b; }, true);
  const Layout Ly = L;
  ex.for_each_index(n, GG_LAMBDA(std::int64_t i) {
    const std::int64_t x = i % Ly.n[0], row = i - x;
    const std::int64_t l = lp[i], r = rp[i];
    const bool hl = l >= row, hr = r < row + Ly.n[0];
    std::int64_t s = -1;
    if (hl && hr) s = (i - l <= r - i) ? l : r;  // a tie goes left: the smaller x
    else if (hl) s = l;
    else if (hr) s = r;
    if (s < 0) {
      feat[i] = kNone;
    } else {
      const std::int64_t rest = s / Ly.n[0];
      feat[i] = Ly.pack(s % Ly.n[0], rest % Ly.n[1], rest / Ly.n[1]);
    }
  });
}

// feat: in = voxel's own packed coordinates where it is a site, else kNone; out = nearest site.
// naxes: how many axes to sweep, from x (all of them for a whole grid; x and y for a slice whose
// candidates already hold the nearest site along z).
// profile_step(a), when given, is called after the pass along axis a (to time the passes).
inline void feature_transform(Exec& ex, const Layout& L, const Metric& M, std::uint32_t* feat,
                              const std::int64_t bands_override[3], int naxes, Stats* stats,
                              const std::function<void(int)>& profile_step = {}) {
  auto stk = ex.template alloc<std::uint32_t>(std::size_t(L.count()));
  std::int64_t max_items = 0;
  PassGeom gs[3];
  for (int a = 0; a < naxes; ++a) {
    gs[a] = make_geom(L, a, ex.concurrency(), bands_override ? bands_override[a] : 0);
    max_items = gs[a].lines * gs[a].bands > max_items ? gs[a].lines * gs[a].bands : max_items;
  }
  auto counts = ex.template alloc<std::int32_t>(std::size_t(max_items));
  // A whole grid starts with the sites themselves: on the GPU the x pass is two scans. A slice
  // starts with sites from other slices, so it takes the general line pass.
  // On the CPU a thread walking its own rows is cache-friendly, and faster than the scans.
  const bool whole = naxes == L.nd && Exec::backend == Backend::Cuda;
  for (int a = 0; a < naxes; ++a) {
    if (a == 0 && whole) x_pass_by_scans(ex, L, feat);
    else line_pass(ex, L, M, gs[a], feat, stk.data(), counts.data());
    if (profile_step) profile_step(a);
    if (stats) stats->counters[std::string("bands_") + "xyz"[a]] = a == 0 && whole ? 0 : gs[a].bands;
  }
}

// Marks sites: feat[i] = packed(i) where site[i] != 0.
inline void init_features(Exec& ex, const Layout& L, const std::uint8_t* site, std::uint32_t* feat) {
  const Layout Ly = L;
  ex.for_each_index(L.count(), GG_LAMBDA(std::int64_t i) {
    const std::int64_t x = i % Ly.n[0], y = (i / Ly.n[0]) % Ly.n[1], z = i / (Ly.n[0] * Ly.n[1]);
    feat[i] = site[i] ? Ly.pack(x, y, z) : kNone;
  });
}
