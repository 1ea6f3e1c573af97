// The transform of grids of 4 to 8 axes (thesis 4.2.6): a line pass per axis, each over the
// grid's independent lines, one line an item. Included by packings.inl in namespaces nd32 and
// nd64, with S (the site index type) defined. The 2D and 3D grids keep their banded passes
// (pba.inl): an N-D line is short (a 128^4 grid has 2^21 lines of 128 along each axis), so a
// line an item fills the executor without bands.
//
// Pass 0 finds each voxel's nearest site on its own line (a sweep each way). Pass a > 0 then
// holds at every voxel the nearest site within its hyperplane of axes < a, and replaces it by the
// nearest within axes <= a: the line's non-dominated candidates on a stack (Lemma 4.2, exact),
// then each position's winner by a walk forward (Lemma 4.3). Ties go to the site first in
// raster order at every step, so the result is "the nearest site, first in C order".

using Num = std::conditional_t<Exec::backend == Backend::Cuda, double, std::int64_t>;
using NdCand = CandOf<S>;
constexpr S kNoSite = S(~S(0));  // (no site; never a raster index: grids hold fewer elements)

// Sites are raster indices, so packed order is raster order and ties go to the first site in C
// order, as in 2D and 3D. S is uint32 where the grid has fewer than 2^32 - 1 elements (coordinates
// decoded by multiply-high divisions), else uint64.
//
// The layout of the grid computed, ND axes (4 to 8, a compile-time constant: every loop over the
// axes unrolls and every per-axis array stays in registers or the kernel's parameters; with the
// axis count known at run time only, the pass kernel kept an 816-byte stack frame and moved
// about 300 bytes an element through local memory, docs/performance.md). A whole grid, or a
// block of slices (zs: the volume's index along C axis 0 of each of the block's planes; the
// sites keep their volume's raster indices).
template <int ND>
struct NdL {
  static constexpr int kAxes = ND;
  static constexpr int nd = ND;
  std::int64_t n[ND], stride[ND];
  Divider by[ND];                     // by n[k] (32-bit indices only)
  const std::uint16_t* zs = nullptr;  // executor memory; null: a whole grid
  NdL() = default;
  explicit NdL(const NdShape& s, const std::uint16_t* z = nullptr) : zs(z) {
    std::int64_t st = 1;
    for (int k = 0; k < ND; ++k) {
      n[k] = s.n[k];
      stride[k] = st;
      st *= n[k];
      by[k] = Divider::of(std::uint32_t(n[k] < 0xFFFFFFFF ? n[k] : 1));
    }
  }
  std::int64_t count() const { return stride[ND - 1] * n[ND - 1]; }
  GG_INLINE S quotient(int k, S s) const {
    if constexpr (sizeof(S) == 4)
      return by[k].div(s);
    else
      return s / S(n[k]);
  }
  // Every coordinate of site (or voxel) s.
  GG_INLINE void coords(S s, std::int64_t c[]) const {
    for (int k = 0; k < ND - 1; ++k) {
      const S q = quotient(k, s);
      c[k] = std::int64_t(s - q * S(n[k]));
      s = q;
    }
    c[ND - 1] = std::int64_t(s);
  }
  // Coordinate a of site s (the exact tests of edt_common.hpp, and the features): every axis
  // decoded, a selected (no array indexed by a).
  GG_INLINE std::int64_t coord(S s, int a) const {
    std::int64_t r = 0;
    for (int k = 0; k < ND - 1; ++k) {
      const S q = quotient(k, s);
      if (k == a) r = std::int64_t(s - q * S(n[k]));
      s = q;
    }
    return a == ND - 1 ? std::int64_t(s) : r;
  }
  // Where voxel i of the grid computed lies in the volume.
  GG_INLINE void position(std::int64_t i, std::int64_t v[]) const {
    coords(S(i), v);
    if (zs) v[ND - 1] = zs[v[ND - 1]];
  }
  GG_INLINE std::int64_t voxel_of(S s) const { return std::int64_t(s); }
  GG_INLINE bool before(S q, S p) const { return q < p; }
};

// The metric of ND axes (the exact tests take the layout's axis count).
template <int ND>
MetricT<ND> nd_metric(const NdMetric& M) {
  MetricT<ND> m;
  m.iso = M.iso;
  for (int k = 0; k < ND; ++k) m.wh[k] = M.wh[k], m.wl[k] = M.wl[k], m.w[k] = M.w[k];
  return m;
}

// Line l of a pass along an axis of stride st and length len: its first voxel, whose coordinates
// go to v (v[a] = 0).
template <int ND>
GG_INLINE std::int64_t nd_line(const NdL<ND>& L, std::int64_t st, std::int64_t len, std::int64_t l,
                               std::int64_t v[]) {
  const std::int64_t base = (l / st) * st * len + l % st;
  L.position(base, v);
  return base;
}

template <int ND>
GG_INLINE NdCand nd_decode(const NdL<ND>& L, int a, S s, const std::int64_t v[]) {
  NdCand c{s, 0.0, 0.0};
  if (s == kNoSite) return c;
  std::int64_t x[ND];
  L.coords(s, x);
  for (int k = 0; k < ND; ++k) {
    const double d = double(x[k] - v[k]);
    if (k == a)
      c.t = double(x[k]);
    else
      c.f += d * d;
  }
  return c;
}

// Pass 0: the nearest site on each line of axis 0, ties to the lower index. Sites are the
// voxels whose mask byte is non-zero, or (mask null) those whose feature is themselves.
template <int ND>
inline void nd_pass_first(Exec& ex, const NdL<ND>& L, const std::uint8_t* mask, S* feat) {
  const std::int64_t len = L.n[0];
  ex.for_each_index(
      L.count() / len, GG_LAMBDA(std::int64_t l) {
        S* f = feat + l * len;
        const std::uint8_t* m = mask ? mask + l * len : nullptr;
        const S base = S(l * len);
        S last = kNoSite;  // forward: the nearest site at or before t
        for (std::int64_t t = 0; t < len; ++t) {
          if (m ? m[t] != 0 : f[t] != kNoSite) last = base + S(t);
          f[t] = last;
        }
        S next = kNoSite;  // backward: the nearest at or after t wins only if strictly nearer
        for (std::int64_t t = len - 1; t >= 0; --t) {
          const S cur = f[t];
          if (cur == base + S(t)) {
            next = cur;
            continue;
          }
          if (next != kNoSite &&
              (cur == kNoSite || std::int64_t(next - base) - t < t - std::int64_t(cur - base)))
            f[t] = next;
        }
      });
}

// Pass a over every line, in place in feat; the stacks live in stk at the lines' positions. The
// loads run ahead of the loop (it is latency-bound, as band_stack in pba.inl).
template <bool Iso, int ND>
void nd_pass_t(Exec& ex, const NdL<ND>& L, const MetricT<ND>& M, int a, S* feat, S* stk) {
  const NdL<ND> Ly = L;
  const MetricT<ND> Mt = M;
  const std::int64_t len = L.n[a], st = L.stride[a];
  ex.for_each_index(
      L.count() / len, GG_LAMBDA(std::int64_t l) {
        std::int64_t v[ND];
        const std::int64_t base = nd_line(Ly, st, len, l, v);
        S* f = feat + base;
        S* s = stk + base;
        std::int64_t n = 0;
        NdCand top{kNoSite, 0, 0}, second{kNoSite, 0, 0};
        S ahead1 = f[0];
        S ahead2 = len > 1 ? f[st] : kNoSite;
        for (std::int64_t t = 0; t < len; ++t) {
          const S cs = ahead1;
          ahead1 = ahead2;
          if (t + 2 < len) ahead2 = f[(t + 2) * st];
          if (cs == kNoSite) continue;
          const NdCand c = nd_decode(Ly, a, cs, v);
          while (n >= 2 && cand_dominated<Iso, Num>(Ly, Mt, a, second, top, c, v)) {
            --n;
            top = second;
            if (n >= 2) second = nd_decode(Ly, a, s[(n - 2) * st], v);
          }
          s[n * st] = cs;
          ++n;
          second = top;
          top = c;
        }
        if (n == 0) return;  // no site in the line's hyperplanes yet: it stays empty
        std::int64_t k = 0;
        NdCand cur = nd_decode(Ly, a, s[0], v);
        NdCand nxt = nd_decode(Ly, a, n > 1 ? s[st] : kNoSite, v);
        S after = n > 2 ? s[2 * st] : kNoSite;  // the one after nxt, loaded an advance ahead
        for (std::int64_t t = 0; t < len; ++t) {
          while (nxt.s != kNoSite && cand_beats<Iso, Num>(Ly, Mt, a, nxt, cur, t, v)) {
            ++k;
            cur = nxt;
            nxt = nd_decode(Ly, a, after, v);
            after = k + 2 < n ? s[(k + 2) * st] : kNoSite;
          }
          f[t * st] = cur.s;
        }
      });
}

// The passes of a whole grid, in place in feat (see nd_pass_first for what it holds first).
// With 32-bit indices the first two run as the 3D transform's x and y passes (grid_transform.inl:
// a warp per row, windowed and tiled where they pay), on the grid seen as a 3D grid of n0 x n1 x
// (the rest) packed by raster index, which is the N-D raster index: their lines are the N-D
// grid's lines along those axes, and every candidate lies in its voxel's plane.
template <int ND>
inline void nd_transform(Exec& ex, const NdL<ND>& L, const MetricT<ND>& M, const std::uint8_t* mask,
                         S* feat, S* stk, const Tuning& tune, std::int64_t sites, EdtStats* stats) {
  double last = now_ms();
  auto step = [&](int a) {
    if (!stats) return;
    ex.sync();
    const double now = now_ms();
    stats->phase_ms.push_back({"pass_" + std::to_string(a), now - last});
    last = now;
  };
  int done = 1;
  if constexpr (sizeof(S) == 4) {
    edt::Layout L3;
    L3.nd = 3;
    L3.n[0] = L.n[0];
    L3.n[1] = L.n[1];
    L3.n[2] = L.count() / (L.n[0] * L.n[1]);
    L3.linear = true;
    Metric M3;
    M3.iso = M.iso;
    for (int k = 0; k < 3; ++k) M3.wh[k] = M.wh[k], M3.wl[k] = M.wl[k], M3.w[k] = M.w[k];
    // (S is uint32_t here; the cast only lets the 64-bit instantiation compile this branch)
    linear::feature_transform(ex, LinearLayout(L3), M3, reinterpret_cast<std::uint32_t*>(feat),
                              mask, tune, sites, nullptr, {}, 2);
    done = 2;
  } else {
    nd_pass_first(ex, L, mask, feat);
  }
  step(done - 1);
  for (int a = done; a < L.nd; ++a) {
    if (M.iso)
      nd_pass_t<true, ND>(ex, L, M, a, feat, stk);
    else
      nd_pass_t<false, ND>(ex, L, M, a, feat, stk);
    step(a);
  }
}

// The backend entry for an N-D grid: upload, feature transform, outputs, download (as run.inl
// for 2D and 3D).
template <int ND>
inline void run_nd_t(const Request& rq, Output& out, EdtStats& stats) {
  Exec ex(rq.run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  const NdL<ND> L(rq.nd);
  const MetricT<ND> M = nd_metric<ND>(rq.nd_metric);
  const std::int64_t nvox = L.count();
  {
    // The grid where it is uploaded and its mask, the features and the stacks (an index each),
    // then the outputs the library allocates.
    const auto& in = rq.into;
    double per = 2.0 * sizeof(S) + 1;
    if (rq.grid && !rq.grid_on_device) per += double(io::scalar_size(rq.type));
    if (rq.want_sqdist && !in.sqdist_int && !in.sqdist_real) per += 8;
    if (rq.want_distance == 32 && !in.distance32) per += 4;
    if (rq.want_distance == 64 && !in.distance64) per += 8;
    if (rq.want_features && !in.features) per += 4.0 * L.nd;
    if (rq.want_labels) per += in.labels ? 4 : 8;
    ::gpugeom::detail::require_device_memory(ex, nvox, per, "a distance transform", "voxels");
  }
  DeviceArrays lib;
  typename Exec::template Buffer<unsigned char> raw;
  typename Exec::template Buffer<std::uint8_t> mbuf;
  const std::uint8_t* mask_p = nullptr;
  std::int64_t site_count = rq.site_count;
  auto feat = ex.template alloc<S>(std::size_t(nvox));
  S* fp = feat.data();
  const std::int64_t ns = rq.grid ? 0 : std::int64_t(rq.nd_sites.size());
  auto sites = ex.template alloc<S>(std::size_t(ns));
  const double t0 = now_ms();
  if (rq.grid) {
    mask_p = grid_mask(ex, rq, nvox, raw, mbuf, site_count);
    check_label_count(rq, site_count);
  } else {
    std::vector<S> h(rq.nd_sites.begin(), rq.nd_sites.end());
    ex.from_host(h.data(), ns, sites.data());
    ex.fill(fp, nvox, kNoSite);
    const S* sp = sites.data();
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) { fp[std::int64_t(sp[i])] = sp[i]; });
  }
  ex.sync();
  stats.phase_ms.push_back({"upload", now_ms() - t0});
  const double t1 = now_ms();
  {
    auto stk = ex.template alloc<S>(std::size_t(nvox));
    nd_transform(ex, L, M, mask_p, fp, stk.data(), rq.tune, site_count,
                 rq.run.profile ? &stats : nullptr);
    ex.sync();
  }
  out.transform_ms = now_ms() - t1;
  stats.phase_ms.push_back({"transform", out.transform_ms});
  const double t2 = now_ms();
  // Labels: each site voxel's label (a mask's raster rank, or a list's lowest index among
  // duplicates), so a voxel's label is one lookup.
  auto rank = ex.template alloc<std::int32_t>(rq.want_labels ? std::size_t(nvox) : 0);
  std::int32_t* rp = rank.data();
  if (rq.want_labels && rq.grid) {
    const std::uint8_t* mp = mask_p;
    ex.exclusive_scan_of(
        nvox, GG_LAMBDA(std::int64_t i)->std::int32_t { return mp[i] ? 1 : 0; }, rp);
  } else if (rq.want_labels) {
    ex.fill(rp, nvox, std::int32_t(0x7fffffff));
    const S* sp = sites.data();
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t j) {
          cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> r(rp[std::int64_t(sp[j])]);
          r.fetch_min(std::int32_t(j), cuda::memory_order_relaxed);
        });
  }
  emit_outputs(ex, rq, L, M, fp, RankLabels<NdL<ND>>{rp, L}, out, lib, 0, nvox);
  stats.phase_ms.push_back({"outputs_device", out.device_outputs_at - t2});
  if (rq.device_out) hand_over(ex, lib, out);
  stats.phase_ms.push_back({"outputs", now_ms() - t2});
  stats.index_bits = 8 * std::int64_t(sizeof(S));
}

// A block's candidates (column_candidates, columns.inl): the site at z of column c, as the
// volume's raster index.
struct NdColumnPut {
  S* cand;
  std::int64_t plane;
  GG_INLINE std::int64_t column(std::int64_t c) const { return c; }
  GG_INLINE void operator()(std::int64_t i, std::int64_t c, std::int64_t, std::int64_t z) const {
    cand[i] = z < 0 ? kNoSite : S(z * plane + c);
  }
};

// Labels of a block: those of its planes' candidates (voxel i's site is a candidate of i's plane,
// in the site's column).
struct NdColumnLabels {
  const std::int32_t* lab;
  std::int64_t plane;
  GG_INLINE std::int32_t operator()(S f, std::int64_t i) const {
    return lab[(i / plane) * plane + std::int64_t(f % S(plane))];
  }
};

// The slice-by-slice mode of an N-D grid (as slices.inl for 3D): only the requested indices
// along C axis 0 are computed, from the list of the volume's sites, never from the volume
// itself, so the volume may be larger than the device. Each plane of a block takes, for every
// column, the nearest of the column's sites along axis 0 (columns.inl); the passes along the
// other axes then run on the block.
template <int ND>
inline void run_nd_slices_t(const Request& rq, Output& out, EdtStats& stats) {
  Exec ex(rq.run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  const NdL<ND> V(rq.nd);
  const MetricT<ND> M = nd_metric<ND>(rq.nd_metric);
  constexpr int nd = ND;
  const std::int64_t plane = V.stride[nd - 1], nvox = V.count();
  const std::int64_t nsl = std::int64_t(rq.slices.size());
  const bool labels = rq.want_labels;
  const std::int64_t want = rq.tune.slice_block > 0 ? rq.tune.slice_block : std::int64_t(1) << 24;
  const std::int64_t per_block = std::min(nsl, std::max<std::int64_t>(1, want / plane));
  // Device memory, as slices.inl: the keys (and labels), twice while sorted; a block's arrays
  // (candidates, stacks, labels, staging); the columns' starts and places; the library's arrays
  // of every computed slice; a device grid's mask while its sites are listed.
  const auto& in = rq.into;
  const bool direct = rq.device_out || Exec::backend == Backend::Cpu;
  double per_voxel = 2.0 * sizeof(S) + (labels ? 4 : 0);
  if (!direct) per_voxel += (rq.want_sqdist ? 8 : 0) + rq.want_distance / 8 + (labels ? 4 : 0);
  double lib = 0;
  if (rq.device_out) {
    if (rq.want_sqdist && !in.sqdist_int && !in.sqdist_real) lib += 8;
    if (rq.want_distance == 32 && !in.distance32) lib += 4;
    if (rq.want_distance == 64 && !in.distance64) lib += 8;
    if (labels && !in.labels) lib += 4;
    if (rq.want_features && !in.features) lib += 4.0 * nd;
  }
  const bool bytes_mask = rq.rule == SiteRule::NonZero &&
                          (rq.type == io::ScalarType::U8 || rq.type == io::ScalarType::Bool);
  const double block = double(per_block) * double(plane);
  // listing: the voxels of a grid whose sites are being listed (its mask's bytes), else 0
  auto require = [&](std::int64_t sites, std::int64_t listing) {
    const double keys = double(sites) * (8 + (labels ? 4 : 0));
    const double bytes = keys + std::max(keys, block * per_voxel + double(plane) * 16) +
                         double(nsl) * double(plane) * lib + (!bytes_mask ? double(listing) : 0);
    ::gpugeom::detail::require_device_bytes(ex, std::uint64_t(bytes),
                                            "a distance transform of " + std::to_string(nsl) +
                                                " slices of " + std::to_string(plane) +
                                                " voxels with " + std::to_string(sites) + " sites");
  };
  const double t0 = now_ms();
  typename Exec::template Buffer<std::uint64_t> keys;
  typename Exec::template Buffer<std::int32_t> vals;
  std::int64_t ns = 0;
  if (rq.grid) {
    ns = grid_column_keys(ex, rq, nvox, plane, require, keys);
  } else {
    ns = std::int64_t(rq.column_sites.size());
    check_label_count(rq, ns);
    require(ns, 0);
    keys = ex.template alloc<std::uint64_t>(std::size_t(ns));
    ex.from_host(rq.column_sites.data(), ns, keys.data());
  }
  if (labels) vals = ex.template alloc<std::int32_t>(std::size_t(ns));
  auto start = column_runs(ex, keys.data(), labels ? vals.data() : nullptr, ns, plane);
  ex.sync();
  stats.phase_ms.push_back({"upload", now_ms() - t0});

  auto zs = ex.template alloc<std::uint16_t>(std::size_t(nsl));
  {
    std::vector<std::uint16_t> z(rq.slices.begin(), rq.slices.end());
    ex.from_host(z.data(), nsl, zs.data());
  }
  const std::size_t bv = std::size_t(per_block * plane);
  auto cand = ex.template alloc<S>(bv);
  auto stk = ex.template alloc<S>(bv);
  auto lab = ex.template alloc<std::int32_t>(labels ? bv : 0);
  auto at = ex.template alloc<std::int64_t>(std::size_t(plane));
  DeviceArrays arrays;
  double transform = 0;
  for (std::int64_t k0 = 0; k0 < nsl; k0 += per_block) {
    NdShape bs = rq.nd;
    bs.n[nd - 1] = std::min(per_block, nsl - k0);
    const NdL<ND> Lb(bs, zs.data() + k0);
    const double t1 = now_ms();
    column_candidates(ex, plane, bs.n[nd - 1], zs.data() + k0, keys.data(), vals.data(),
                      start.data(), at.data(), k0 ? rq.slices[std::size_t(k0 - 1)] : -1,
                      labels ? lab.data() : nullptr, NdColumnPut{cand.data(), plane});
    for (int a = 0; a < nd - 1; ++a) {
      if (M.iso)
        nd_pass_t<true, ND>(ex, Lb, M, a, cand.data(), stk.data());
      else
        nd_pass_t<false, ND>(ex, Lb, M, a, cand.data(), stk.data());
    }
    ex.sync();
    transform += now_ms() - t1;
    emit_outputs(ex, rq, Lb, M, cand.data(), NdColumnLabels{lab.data(), plane}, out, arrays,
                 k0 * plane, nsl * plane);
  }
  stats.slices_per_block = per_block;
  stats.index_bits = 8 * std::int64_t(sizeof(S));
  if (rq.device_out) hand_over(ex, arrays, out);
  out.transform_ms = transform;
  stats.phase_ms.push_back({"transform", transform});
}

// The entries (entry.inl): the request's axis count picks the compiled instance.
template <template <int> class Run>
inline void by_axes(int nd, const Request& rq, Output& out, EdtStats& stats) {
  switch (nd) {
    case 4:
      return Run<4>::go(rq, out, stats);
    case 5:
      return Run<5>::go(rq, out, stats);
    case 6:
      return Run<6>::go(rq, out, stats);
    case 7:
      return Run<7>::go(rq, out, stats);
    default:
      return Run<8>::go(rq, out, stats);
  }
}
template <int ND>
struct WholeRun {
  static void go(const Request& rq, Output& out, EdtStats& stats) { run_nd_t<ND>(rq, out, stats); }
};
template <int ND>
struct SliceRun {
  static void go(const Request& rq, Output& out, EdtStats& stats) {
    run_nd_slices_t<ND>(rq, out, stats);
  }
};
inline void run_nd(const Request& rq, Output& out, EdtStats& stats) {
  by_axes<WholeRun>(rq.nd.nd, rq, out, stats);
}
inline void run_nd_slices(const Request& rq, Output& out, EdtStats& stats) {
  by_axes<SliceRun>(rq.nd.nd, rq, out, stats);
}
