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

constexpr std::int64_t kMaxBands = 64;

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
    v[0] = 0, v[1] = l % L.n[1], v[2] = L.plane_z(l / L.n[1]);
  } else if (a == 1) {
    v[0] = l % L.n[0], v[1] = 0, v[2] = L.plane_z(l / L.n[0]);
  } else {
    v[0] = l % L.n[0], v[1] = l / L.n[0], v[2] = 0;
  }
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
  if (g.bands > kMaxBands) g.bands = kMaxBands;
  g.band_len = (g.len + g.bands - 1) / g.bands;
  return g;
}

// The live candidates of one line: band b keeps the slice [lo_b, hi_b) of its own stack. Merges
// only move these bounds (pops come off the tail of the upper group and the head of the lower
// one; nothing is copied), and the list of the line is the concatenation of the slices.
struct Segs {
  std::uint32_t* stk;
  std::int64_t base, stride, band_len, lines, l;
  std::int32_t* lo;
  std::int32_t* hi;
  GG_INLINE std::uint32_t& at(std::int64_t b, std::int32_t i) const {
    return stk[base + (b * band_len + i) * stride];
  }
  GG_INLINE std::int32_t& L(std::int64_t b) const { return lo[b * lines + l]; }
  GG_INLINE std::int32_t& H(std::int64_t b) const { return hi[b * lines + l]; }
};

// A candidate as the passes compare it: its packed site, its position t along the pass axis
// and, when the metric is isotropic, f = its squared distance to the line (other axes). With
// those two numbers the isotropic tests are a few exact double operations (values < 2^51);
// anisotropic metrics take the general exact tests of edt_common.hpp.
using Cand = CandOf<std::uint32_t>;

GG_INLINE Cand decode(const Layout& L, int a, std::uint32_t s, const std::int64_t v[3]) {
  Cand c{s, double(L.coord(s, a)), 0.0};
  for (int k = 0; k < 3; ++k)
    if (k != a && k < L.nd) {
      const double d = double(std::int32_t(L.coord(s, k)) - std::int32_t(v[k]));
      c.f += d * d;
    }
  return c;
}

// One band's stack: scans positions [t0, t1) of a line (in[base + t * stride]) and keeps the
// band's non-dominated candidates at stk[base + (t0 + i) * stride], i < n; returns n. In place
// when stk == in: the slot written never lies ahead of the position read. The top two stay in
// registers; loads run two positions ahead (the loop is latency-bound). A flat loop (each step
// pops or pushes) was tried to keep lanes converged: 10-35 % slower.
template <bool Iso>
GG_INLINE std::int32_t band_stack(const Layout& L, const Metric& M, int a, const std::int64_t v[3],
                                  const std::uint32_t* in, std::uint32_t* stk, std::int64_t base,
                                  std::int64_t stride, std::int64_t t0, std::int64_t t1) {
  std::uint32_t* s = stk + base + t0 * stride;
  std::int32_t n = 0;
  Cand top{kNone, 0, 0}, second{kNone, 0, 0};
  std::uint32_t ahead1 = t0 < t1 ? in[base + t0 * stride] : kNone;
  std::uint32_t ahead2 = t0 + 1 < t1 ? in[base + (t0 + 1) * stride] : kNone;
  for (std::int64_t t = t0; t < t1; ++t) {
    const std::uint32_t cs = ahead1;
    ahead1 = ahead2;
    if (t + 2 < t1) ahead2 = in[base + (t + 2) * stride];
    if (cs == kNone) continue;
    const Cand c = decode(L, a, cs, v);
    while (n >= 2 && cand_dominated<Iso, Num>(L, M, a, second, top, c, v)) {
      --n;
      top = second;
      if (n >= 2) second = decode(L, a, s[(n - 2) * stride], v);
    }
    s[n * stride] = cs;
    ++n;
    second = top;
    top = c;
  }
  return n;
}

// Merges band groups [bl, br) and [br, be) of one line (Algorithm 4.1 on the slices): pops
// come off the tail of the upper group and the head of the lower one; only bounds move.
template <bool Iso>
GG_INLINE void merge_groups(const Layout& L, const Metric& M, int a, const std::int64_t v[3],
                            const Segs& S, std::int64_t bl, std::int64_t br, std::int64_t be) {
  // Tail of the upper group: band ub, index ui (ub < bl: empty).
  std::int64_t ub = br - 1;
  while (ub >= bl && S.H(ub) == S.L(ub)) --ub;
  std::int32_t ui = ub >= bl ? S.H(ub) - 1 : -1;
  auto back = [&](std::int64_t& b, std::int32_t& i) {  // the live element before (b, i)
    if (i > S.L(b)) {
      --i;
      return;
    }
    do --b;
    while (b >= bl && S.H(b) == S.L(b));
    i = b >= bl ? S.H(b) - 1 : -1;
  };
  std::int64_t ucount = 0;
  for (std::int64_t b = bl; b < br; ++b) ucount += S.H(b) - S.L(b);
  // Walk the lower group's elements in order.
  std::int64_t vb = br;
  std::int32_t vi = S.L(br);
  std::int64_t dropped = 0;  // lower-group elements popped (always a prefix)
  int pushed = 0;            // lower-group elements on the stack (0 or 1 while popping)
  Cand last{kNone, 0, 0};
  while (true) {
    while (vb < be && vi >= S.H(vb)) {
      ++vb;
      if (vb < be) vi = S.L(vb);
    }
    if (vb >= be) break;
    const Cand c = decode(L, a, S.at(vb, vi), v);
    while (ucount + pushed >= 2) {
      Cand t, sec;
      if (pushed == 1) {
        t = last;
        sec = decode(L, a, S.at(ub, ui), v);
      } else {
        t = decode(L, a, S.at(ub, ui), v);
        std::int64_t pb = ub;
        std::int32_t pi = ui;
        back(pb, pi);
        sec = decode(L, a, S.at(pb, pi), v);
      }
      if (!cand_dominated<Iso, Num>(L, M, a, sec, t, c, v)) break;
      if (pushed == 1) {
        pushed = 0;
        ++dropped;
      } else {
        back(ub, ui);
        --ucount;
      }
    }
    last = c;
    if (++pushed == 2) break;  // lower-group sites never dominate each other
    ++vi;
  }
  // Upper group: everything after the tail (ub, ui) is gone.
  for (std::int64_t b = br - 1; b >= bl; --b) {
    if (b > ub)
      S.H(b) = S.L(b);
    else if (b == ub)
      S.H(b) = ui + 1;
    else
      break;
  }
  // Lower group: drop the popped prefix.
  for (std::int64_t b = br; b < be && dropped > 0; ++b) {
    const std::int64_t take = S.H(b) - S.L(b) < dropped ? S.H(b) - S.L(b) : dropped;
    S.L(b) += std::int32_t(take);
    dropped -= take;
  }
}

// Colours positions [t0, t1) of band b0 into out[out_base + t * out_stride]: the first winner by
// binary search over the line's concatenated slices, then a walk forward (Lemma 4.3).
template <bool Iso>
GG_INLINE void colour_band(const Layout& L, const Metric& M, int a, const std::int64_t v[3],
                           const Segs& S, std::int64_t nbands, std::int64_t t0, std::int64_t t1,
                           std::uint32_t* out, std::int64_t out_base, std::int64_t out_stride) {
  std::int32_t pre[kMaxBands + 1];  // live elements before each band
  pre[0] = 0;
  for (std::int64_t b = 0; b < nbands; ++b) pre[b + 1] = pre[b] + S.H(b) - S.L(b);
  const std::int64_t n = pre[nbands];
  if (n == 0) {
    for (std::int64_t t = t0; t < t1; ++t) out[out_base + t * out_stride] = kNone;
    return;
  }
  auto locate = [&](std::int64_t k, std::int64_t& b, std::int32_t& i) {  // k-th live element
    std::int64_t lo = 0, hi = nbands - 1;  // last band with pre[b] <= k
    while (lo < hi) {
      const std::int64_t m = (lo + hi + 1) / 2;
      if (pre[m] <= k)
        lo = m;
      else
        hi = m - 1;
    }
    b = lo;
    i = S.L(b) + std::int32_t(k - pre[b]);
  };
  auto next = [&](std::int64_t& b, std::int32_t& i) {
    ++i;
    while (b < nbands && i >= S.H(b)) {
      ++b;
      if (b < nbands) i = S.L(b);
    }
  };
  std::int64_t lo_k = 0, hi_k = n - 1;  // first k whose successor does not beat it at t0
  while (lo_k < hi_k) {
    const std::int64_t mid = (lo_k + hi_k) / 2;
    std::int64_t b, b2;
    std::int32_t i, i2;
    locate(mid, b, i);
    b2 = b, i2 = i;
    next(b2, i2);
    if (cand_beats<Iso, Num>(L, M, a, decode(L, a, S.at(b2, i2), v), decode(L, a, S.at(b, i), v),
                             t0, v))
      lo_k = mid + 1;
    else
      hi_k = mid;
  }
  std::int64_t cb, nb;
  std::int32_t ci, ni;
  locate(lo_k, cb, ci);  // the current winner; (nb, ni) its successor
  nb = cb, ni = ci;
  next(nb, ni);
  Cand cur = decode(L, a, S.at(cb, ci), v);
  Cand nxt = decode(L, a, nb < nbands ? S.at(nb, ni) : kNone, v);
  // The element after nxt is loaded one advance ahead, to hide its latency.
  std::int64_t ab = nb;
  std::int32_t ai = ni;
  if (ab < nbands) next(ab, ai);
  std::uint32_t after = ab < nbands ? S.at(ab, ai) : kNone;
  for (std::int64_t t = t0; t < t1; ++t) {
    while (nxt.s != kNone && cand_beats<Iso, Num>(L, M, a, nxt, cur, t, v)) {
      cur = nxt;
      nxt = decode(L, a, after, v);
      if (ab < nbands) next(ab, ai);
      after = ab < nbands ? S.at(ab, ai) : kNone;
    }
    out[out_base + t * out_stride] = cur.s;
  }
}

// The line pass with every band of every line an independent item, stacks in global memory.
// Colours go to out (which may be cand). With flags, only the lines flagged non-zero are
// computed (the others' items return at once).
template <bool Iso>
void line_pass_t(Exec& ex, const Layout& L, const Metric& M, const PassGeom& g, std::uint32_t* cand,
                 std::uint32_t* stk, std::int32_t* lo, std::int32_t* hi, std::uint32_t* out,
                 const std::uint8_t* flags) {
  const Layout Ly = L;
  const Metric Mt = M;
  const PassGeom G = g;
  ex.for_each_index(
      G.lines * G.bands, GG_LAMBDA(std::int64_t item) {
        const std::int64_t b = item / G.lines, l = item % G.lines;
        if (flags && !flags[l]) return;
        std::int64_t v[3];
        line_coords(Ly, G.a, l, v);
        const std::int64_t t0 = b * G.band_len;
        const std::int64_t t1 = t0 + G.band_len < G.len ? t0 + G.band_len : G.len;
        lo[item] = 0;
        hi[item] =
            band_stack<Iso>(Ly, Mt, G.a, v, cand, stk, line_base(Ly, G.a, l), G.stride, t0, t1);
      });
  for (std::int64_t width = 1; width < G.bands; width *= 2) {
    const std::int64_t groups = (G.bands + 2 * width - 1) / (2 * width);
    const std::int64_t wd = width;
    ex.for_each_index(
        G.lines * groups, GG_LAMBDA(std::int64_t item) {
          const std::int64_t grp = item / G.lines, l = item % G.lines;
          const std::int64_t bl = grp * 2 * wd, br = bl + wd;
          if (br >= G.bands || (flags && !flags[l])) return;
          const std::int64_t be = br + wd < G.bands ? br + wd : G.bands;
          const Segs S{stk, line_base(Ly, G.a, l), G.stride, G.band_len, G.lines, l, lo, hi};
          std::int64_t v[3];
          line_coords(Ly, G.a, l, v);
          merge_groups<Iso>(Ly, Mt, G.a, v, S, bl, br, be);
        });
  }
  ex.for_each_index(
      G.lines * G.bands, GG_LAMBDA(std::int64_t item) {
        const std::int64_t b0 = item / G.lines, l = item % G.lines;
        if (flags && !flags[l]) return;
        const Segs S{stk, line_base(Ly, G.a, l), G.stride, G.band_len, G.lines, l, lo, hi};
        std::int64_t v[3];
        line_coords(Ly, G.a, l, v);
        const std::int64_t t0 = b0 * G.band_len;
        const std::int64_t t1 = t0 + G.band_len < G.len ? t0 + G.band_len : G.len;
        colour_band<Iso>(Ly, Mt, G.a, v, S, G.bands, t0, t1, out, S.base, G.stride);
      });
}

// A pass on tiles in on-chip memory, where the backend has them (edt_cuda.cu); returns false
// when it does not apply (then the general pass runs).
bool line_pass_tiled(Exec& ex, const Layout& L, const Metric& M, int a, std::int64_t bands,
                     int tiles, std::uint32_t* cand, std::uint32_t* out, const std::uint8_t* flags);

inline void line_pass(Exec& ex, const Layout& L, const Metric& M, const PassGeom& g,
                      std::uint32_t* cand, std::uint32_t* stk, std::int32_t* lo, std::int32_t* hi) {
  if (M.iso)
    line_pass_t<true>(ex, L, M, g, cand, stk, lo, hi, cand, nullptr);
  else
    line_pass_t<false>(ex, L, M, g, cand, stk, lo, hi, cand, nullptr);
}

// The working arrays of the passes along axes [0, naxes) of a grid: a word per voxel (the banded
// passes' stacks, or the other array of passes that do not work in place) and each (line,
// band) item's live bounds.
struct PassWork {
  typename Exec::template Buffer<std::uint32_t> stk;
  typename Exec::template Buffer<std::int32_t> lo, hi;
  PassGeom gs[3];
  std::int64_t max_items = 0;
  PassWork(Exec& ex, const Layout& L, const Tuning& tune, int naxes)
      : stk(ex.template alloc<std::uint32_t>(std::size_t(L.count()))) {
    for (int a = 0; a < naxes; ++a) {
      gs[a] = make_geom(L, a, ex.concurrency(), tune.bands[a]);
      max_items = gs[a].lines * gs[a].bands > max_items ? gs[a].lines * gs[a].bands : max_items;
    }
    lo = ex.template alloc<std::int32_t>(std::size_t(max_items));
    hi = ex.template alloc<std::int32_t>(std::size_t(max_items));
  }
};

// The banded pass along axis a over every line, in place in cand (stacks in scratch): on tiles
// where the backend has them, else in global memory.
inline void banded_pass(Exec& ex, const Layout& L, const Metric& M, const Tuning& tune, PassWork& w,
                        int a, std::uint32_t* cand, std::uint32_t* scratch) {
  if (!line_pass_tiled(ex, L, M, a, tune.bands[a], tune.tiles, cand, cand, nullptr))
    line_pass(ex, L, M, w.gs[a], cand, scratch, w.lo.data(), w.hi.data());
}
