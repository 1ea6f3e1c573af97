// The feature transform of a whole grid (2D or 3D), on the line machinery of pba.inl: the x
// pass from the sites themselves, then windowed or banded passes along y and z. Included after
// pba.inl, once per site packing (the slice-by-slice mode has its own, slices.inl).

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
                                   std::int32_t(rest / ny)};
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
          if (best == kNone || c < bc || (c == bc && Ly.before(s, best))) best = s, bc = c;
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
        const std::int64_t l = a == 1 ? v[2] * Ly.n[0] + v[0] : std::int64_t(v[1]) * Ly.n[0] + v[0];
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
// mask, when given, holds the sites instead (non-zero: a site) and feat's content is not read:
// the x pass reads a byte per voxel instead of a word.
// sites: how many there are (0 if unknown), to choose the windowed passes.
// profile_step(a), when given, is called after the pass along axis a (to time the passes).
// naxes: the passes along axes [0, naxes) only (0: all; grids of more axes run their first two
// passes here, viewed as 3D grids of n0 x n1 x (the rest), nd.inl).
inline void feature_transform(Exec& ex, const Layout& L, const Metric& M, std::uint32_t* feat,
                              const std::uint8_t* mask, const Tuning& tune, std::int64_t sites,
                              EdtStats* stats, const std::function<void(int)>& profile_step = {},
                              int naxes = 0) {
  if (naxes <= 0) naxes = L.nd;
  PassWork w(ex, L, tune, naxes);
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
  auto flags = ex.template alloc<std::uint8_t>(M.iso && reach > 0 ? std::size_t(w.max_items) : 0);
  const bool windowed = M.iso && reach > 0;
  std::uint32_t* cur = feat;  // the windowed passes alternate between feat and stk
  std::uint32_t* other = w.stk.data();
  // Reading a mask, the x pass may write either array: it picks the one that makes the last
  // windowed pass end in feat (no copy back: a whole array's read and write at 16384^2).
  if (mask && windowed && (naxes - 1) % 2 == 1) std::swap(cur, other);
  for (int a = 0; a < naxes; ++a) {
    if (a == 0) {  // the sites themselves are the candidates: the x pass of the rows
      x_pass_rows(ex, L, M, w.gs[0], mask, feat, cur, other, w.lo.data(), w.hi.data());
    } else if (windowed) {
      ex.fill(flags.data(), w.gs[a].lines, std::uint8_t(0));
      window_pass(ex, L, a, reach, cur, other, flags.data(), a == 1 && L.nd == 3);
      // Flagged lines: the banded pass, its stacks in place in cur, colours into other.
      if (!line_pass_tiled(ex, L, M, a, tune.bands[a], tune.tiles, cur, other, flags.data()))
        line_pass_t<true>(ex, L, M, w.gs[a], cur, cur, w.lo.data(), w.hi.data(), other,
                          flags.data());
      std::swap(cur, other);
    } else {
      banded_pass(ex, L, M, tune, w, a, cur, other);
    }
    if (profile_step) profile_step(a);
    if (stats) set_bands(*stats, a, w.gs[a].bands);
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
