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
struct Cand {
  std::uint32_t s;
  double t, f;
};

GG_INLINE Cand decode(const Layout& L, int a, std::uint32_t s, const std::int64_t v[3]) {
  Cand c{s, double(L.coord(s, a)), 0.0};
  for (int k = 0; k < 3; ++k)
    if (k != a && k < L.nd) {
      const double d = double(std::int32_t(L.coord(s, k)) - std::int32_t(v[k]));
      c.f += d * d;
    }
  return c;
}

// Iso: the metric is isotropic (known at compile time, so the isotropic kernels carry none of
// the general tests' registers except the exact-tie fallback).
template <bool Iso>
GG_INLINE bool cand_dominated(const Layout& L, const Metric& M, int a, const Cand& A, const Cand& B,
                              const Cand& C, const std::int64_t v[3]) {
  if constexpr (Iso) {
    const double e = (C.t - B.t) * (B.f - A.f) - (B.t - A.t) * (C.f - B.f) +
                     (C.t - B.t) * (B.t - A.t) * (A.t - C.t);
    if (e != 0) return e > 0;
  }
  return dominated<Num>(L, M, a, A.s, B.s, C.s, v);  // anisotropic, or an exact tie
}

template <bool Iso>
GG_INLINE bool cand_beats(const Layout& L, const Metric& M, int a, const Cand& Q, const Cand& P,
                          std::int64_t t, const std::int64_t v[3]) {
  if constexpr (Iso) {
    const double dq = Q.t - double(t), dp = P.t - double(t);
    const double e = (Q.f + dq * dq) - (P.f + dp * dp);
    return e < 0 || (e == 0 && Q.s < P.s);
  } else {
    std::int64_t w[3] = {v[0], v[1], v[2]};
    w[a] = t;
    return beats<Num>(L, M, Q.s, P.s, w);
  }
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
    while (n >= 2 && cand_dominated<Iso>(L, M, a, second, top, c, v)) {
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
      if (!cand_dominated<Iso>(L, M, a, sec, t, c, v)) break;
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
    if (cand_beats<Iso>(L, M, a, decode(L, a, S.at(b2, i2), v), decode(L, a, S.at(b, i), v), t0, v))
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
    while (nxt.s != kNone && cand_beats<Iso>(L, M, a, nxt, cur, t, v)) {
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

// A pass along y or z on tiles in on-chip memory, where the backend has them (edt_cuda.cu);
// returns false when it does not apply (then the general pass runs).
bool line_pass_tiled(Exec& ex, const Layout& L, const Metric& M, int a, std::int64_t bands,
                     int tiles, std::uint32_t* cand, std::uint32_t* out, const std::uint8_t* flags);

inline void line_pass(Exec& ex, const Layout& L, const Metric& M, const PassGeom& g,
                      std::uint32_t* cand, std::uint32_t* stk, std::int32_t* lo, std::int32_t* hi) {
  if (M.iso)
    line_pass_t<true>(ex, L, M, g, cand, stk, lo, hi, cand, nullptr);
  else
    line_pass_t<false>(ex, L, M, g, cand, stk, lo, hi, cand, nullptr);
}

// The windowed pass (isotropic metrics, axes y and z): every voxel looks for its nearest
// candidate outward along its line, nearest positions first, and stops once the next distance
// along the line alone exceeds the best found (a candidate there costs at least that much; ties
// at equal cost go to the smaller packed site, the raster rule of every pass). Where sites are
// not sparse this ends within a few positions, far cheaper than building the line's envelope.
// A voxel not settled within R positions flags its line; those lines then take the banded pass
// (the exact envelope), so the result is the same as the banded pass's everywhere.
// Reads cand, writes out (a different array).
// Cost arithmetic: 32-bit integers where every squared distance fits them (extents up to
// 2^15: three squares below 2^30 each), which takes about a third of the instructions of the
// exact doubles (measured: 310 instructions per voxel in this pass, issue-bound); Num otherwise.
template <class C>
void window_pass_t(Exec& ex, const Layout& L, int a, std::int64_t R, const std::uint32_t* cand,
                   std::uint32_t* out, std::uint8_t* flags) {
  const Layout Ly = L;
  const std::int64_t len = L.n[a], stride = L.stride(a);
  const std::uint32_t nx = std::uint32_t(L.n[0]), ny = std::uint32_t(L.n[1]);
  if (R > len) R = len;  // d never exceeds the line: d * d stays within C
  ex.for_each_index(
      L.count(), GG_LAMBDA(std::int64_t i64) {
        const std::uint32_t i = std::uint32_t(i64), rest = i / nx;
        const std::int32_t v[3] = {std::int32_t(i - rest * nx), std::int32_t(rest % ny),
                                   std::int32_t(rest / ny + Ly.z0)};
        const std::int32_t t0 = v[a];
        // Squared distance along the line (d) and to it (the other axes), exactly in C.
        auto cost = [&](std::uint32_t s, std::int32_t d) {
          C c = C(d) * C(d);
          for (int k = 0; k < Ly.nd; ++k)
            if (k != a) {
              const std::int32_t e = std::int32_t(Ly.coord(s, k)) - v[k];
              c += C(e) * C(e);
            }
          return c;
        };
        std::uint32_t best = cand[i];
        C bc = best == kNone ? C(0) : cost(best, 0);
        auto take = [&](std::uint32_t s, std::int32_t d) {
          if (s == kNone) return;
          const C c = cost(s, d);
          if (best == kNone || c < bc || (c == bc && s < best)) best = s, bc = c;
        };
        // One distance per step: where the window pays (dense sites) most voxels settle at the
        // first or second step; loading four distances at once was measured 1.3-2x slower.
        for (std::int32_t d = 1; d <= std::int32_t(R); ++d) {
          if (best != kNone && C(d) * C(d) > bc) {
            out[i] = best;
            return;
          }
          if (t0 - d >= 0) take(cand[i - d * stride], d);
          if (t0 + d < len) take(cand[i + d * stride], d);
        }
        if (best != kNone && C(R + 1) * C(R + 1) > bc) {
          out[i] = best;
          return;
        }
        if (R + 1 >= t0 + 1 && R + 1 >= len - t0) {  // the whole line was seen
          out[i] = best;
          return;
        }
        const std::int64_t l =
            a == 1 ? (v[2] - Ly.z0) * Ly.n[0] + v[0] : std::int64_t(v[1]) * Ly.n[0] + v[0];
        flags[l] = 1;  // every writer writes 1
      });
}

// The windowed pass as a kernel of the backend's own (edt_cuda.cu: several voxels a thread,
// blocks ordered so the rows a window reads are still in cache); false where there is none
// (then the generic loop above runs).
bool window_pass_kernel(Exec& ex, const Layout& L, int a, std::int64_t R, const std::uint32_t* cand,
                        std::uint32_t* out, std::uint8_t* flags, bool in_plane);

// in_plane: every candidate lies in its voxel's z plane (the y pass of a whole 3D grid, after
// the x pass), so the z term of the costs is zero.
inline void window_pass(Exec& ex, const Layout& L, int a, std::int64_t R, const std::uint32_t* cand,
                        std::uint32_t* out, std::uint8_t* flags, bool in_plane) {
  if (window_pass_kernel(ex, L, a, R, cand, out, flags, in_plane)) return;
  if (L.n[0] <= 32768 && L.n[1] <= 32768 && L.n[2] <= 32768)
    window_pass_t<std::uint32_t>(ex, L, a, R, cand, out, flags);
  else
    window_pass_t<Num>(ex, L, a, R, cand, out, flags);
}

// The x pass of a whole grid, where every candidate is a site of the row itself. Sites come
// from mask (non-zero: a site) when it is given, else from in (a site's own packed
// coordinates, kNone elsewhere); nearest sites go to out, which may be in. scratch is an
// array of count() words that is neither in (when read) nor out. Each backend provides it
// (edt_cpu.cpp: the general line pass, whose row walks suit a CPU cache; edt_cuda.cu: a warp
// per row segment holding its sites as ballot bits, reading the 1-byte mask where there is
// one).
void x_pass_rows(Exec& ex, const Layout& L, const Metric& M, const PassGeom& g,
                 const std::uint8_t* mask, const std::uint32_t* in, std::uint32_t* out,
                 std::uint32_t* scratch, std::int32_t* lo, std::int32_t* hi);

// feat: in = voxel's own packed coordinates where it is a site, else kNone; out = nearest site.
// mask, when given (a whole grid only), holds the sites instead (non-zero: a site) and feat's
// content is not read: the x pass reads a byte per voxel instead of a word.
// sites: how many there are (0 if unknown), to choose the windowed passes.
// naxes: how many axes to sweep, from x (all of them for a whole grid; x and y for a slice whose
// candidates already hold the nearest site along z).
// profile_step(a), when given, is called after the pass along axis a (to time the passes).
inline void feature_transform(Exec& ex, const Layout& L, const Metric& M, std::uint32_t* feat,
                              const std::uint8_t* mask, const Tuning& tune, int naxes,
                              std::int64_t sites, Stats* stats,
                              const std::function<void(int)>& profile_step = {}) {
  auto stk = ex.template alloc<std::uint32_t>(std::size_t(L.count()));
  std::int64_t max_items = 0;
  PassGeom gs[3];
  for (int a = 0; a < naxes; ++a) {
    gs[a] = make_geom(L, a, ex.concurrency(), tune.bands[a]);
    max_items = gs[a].lines * gs[a].bands > max_items ? gs[a].lines * gs[a].bands : max_items;
  }
  auto lo = ex.template alloc<std::int32_t>(std::size_t(max_items));
  auto hi = ex.template alloc<std::int32_t>(std::size_t(max_items));
  // Windowed passes where sites are dense enough that most voxels settle within the reach,
  // judged by the mean site spacing (voxels per site)^(1/d). CPU executor (the generic loop):
  // spacing at most 4, reach 16, the rule first tuned for that loop when it ran on the GPU too
  // (512^3: 10 % 8.9 -> 5.7 ms, but 1 % 7.7 -> 12.2 ms). CUDA (window_kernel, 4 voxels a
  // thread), measured on the H100 against the banded passes: reach 32 is as fast as 16 from
  // 3 % sites up and much faster below; it pays in 2D from 1 % sites (8192^2: 1 % 1.51 -> 1.26
  // ms, 3 % 1.68 -> 0.97) but not at 0.3 % (1.34 -> 2.32), and in 3D from 0.3 % (512^3: 0.3 %
  // 6.35 -> 5.55 ms, 1 % 7.11 -> 3.83) but not at 0.1 % (5.64 -> 8.92). Hence spacing at most
  // 10 in 2D and 8 in 3D. sites = 0: unknown, never windowed.
  // tune.window_reach >= 0 forces the reach (0: never).
  constexpr bool gpu = Exec::backend == Backend::Cuda;
  const double spacing = sites > 0 ? std::pow(double(L.count()) / double(sites), 1.0 / L.nd) : 0;
  std::int64_t reach = 0;
  if (tune.window_reach >= 0)
    reach = tune.window_reach;
  else if (sites > 0 && spacing <= (gpu ? (L.nd == 2 ? 10.0 : 8.0) : 4.0))
    reach = gpu ? 32 : 16;
  auto flags = ex.template alloc<std::uint8_t>(M.iso && reach > 0 ? std::size_t(max_items) : 0);
  // A whole grid starts with the sites themselves (x_pass_rows); a slice starts with sites
  // from other slices, so it takes the general line pass.
  const bool whole = naxes == L.nd;
  const bool windowed = M.iso && reach > 0;
  std::uint32_t* cur = feat;  // the windowed passes alternate between feat and stk
  std::uint32_t* other = stk.data();
  // Reading a mask, the x pass may write either array: it picks the one that makes the last
  // windowed pass end in feat (no copy back: a whole array's read and write at 16384^2).
  if (whole && mask && windowed && (naxes - 1) % 2 == 1) std::swap(cur, other);
  for (int a = 0; a < naxes; ++a) {
    const std::int64_t bands = tune.bands[a];
    if (a == 0 && whole) {
      x_pass_rows(ex, L, M, gs[0], mask, feat, cur, other, lo.data(), hi.data());
    } else if (a > 0 && windowed) {
      ex.fill(flags.data(), gs[a].lines, std::uint8_t(0));
      window_pass(ex, L, a, reach, cur, other, flags.data(), whole && a == 1 && L.nd == 3);
      // Flagged lines: the banded pass, its stacks in place in cur, colours into other.
      if (!line_pass_tiled(ex, L, M, a, bands, tune.tiles, cur, other, flags.data()))
        line_pass_t<true>(ex, L, M, gs[a], cur, cur, lo.data(), hi.data(), other, flags.data());
      std::swap(cur, other);
    } else if (a == 0 || !line_pass_tiled(ex, L, M, a, bands, tune.tiles, cur, cur, nullptr)) {
      line_pass(ex, L, M, gs[a], cur, other, lo.data(), hi.data());
    }
    if (profile_step) profile_step(a);
    if (stats) stats->counters[std::string("bands_") + "xyz"[a]] = gs[a].bands;
  }
  if (cur != feat) ex.copy(cur, L.count(), feat);
}

// Marks sites: feat[i] = packed(i) where site[i] != 0.
inline void init_features(Exec& ex, const Layout& L, const std::uint8_t* site,
                          std::uint32_t* feat) {
  const Layout Ly = L;
  const std::uint32_t nx = std::uint32_t(L.n[0]), ny = std::uint32_t(L.n[1]);
  ex.for_each_index(
      L.count(), GG_LAMBDA(std::int64_t i64) {
        const std::uint32_t i = std::uint32_t(i64), rest = i / nx;
        feat[i] = site[i] ? Ly.pack(i - rest * nx, rest % ny, rest / ny) : kNone;
      });
}
