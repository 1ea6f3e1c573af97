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
using NdL = NdLayout<S>;
using NdCand = CandOf<S>;
constexpr S kNoSite = NdL::kNoSite;

// Line l of the pass along axis a: its first voxel, whose coordinates go to v (v[a] = 0).
GG_INLINE std::int64_t nd_line(const NdL& L, int a, std::int64_t l, std::int64_t v[]) {
  const std::int64_t st = L.stride[a];
  const std::int64_t base = (l / st) * st * L.n[a] + l % st;
  L.coords(S(base), v);
  return base;
}

GG_INLINE NdCand nd_decode(const NdL& L, int a, S s, const std::int64_t v[]) {
  NdCand c{s, 0.0, 0.0};
  if (s == kNoSite) return c;
  std::int64_t x[kMaxAxes];
  L.coords(s, x);
  for (int k = 0; k < L.nd; ++k) {
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
inline void nd_pass_first(Exec& ex, const NdL& L, const std::uint8_t* mask, S* feat) {
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

// Pass a > 0 over every line, in place in feat; the stacks live in stk at the lines' positions.
template <bool Iso>
void nd_pass_t(Exec& ex, const NdL& L, const NdMetric& M, int a, S* feat, S* stk) {
  const NdL Ly = L;
  const NdMetric Mt = M;
  const std::int64_t len = L.n[a], st = L.stride[a];
  ex.for_each_index(
      L.count() / len, GG_LAMBDA(std::int64_t l) {
        std::int64_t v[kMaxAxes];
        const std::int64_t base = nd_line(Ly, a, l, v);
        S* f = feat + base;
        S* s = stk + base;
        std::int64_t n = 0;
        NdCand top{kNoSite, 0, 0}, second{kNoSite, 0, 0};
        for (std::int64_t t = 0; t < len; ++t) {
          const S cs = f[t * st];
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
        for (std::int64_t t = 0; t < len; ++t) {
          while (nxt.s != kNoSite && cand_beats<Iso, Num>(Ly, Mt, a, nxt, cur, t, v)) {
            ++k;
            cur = nxt;
            nxt = nd_decode(Ly, a, k + 1 < n ? s[(k + 1) * st] : kNoSite, v);
          }
          f[t * st] = cur.s;
        }
      });
}

inline void nd_transform(Exec& ex, const NdL& L, const NdMetric& M, const std::uint8_t* mask,
                         S* feat, S* stk, Stats* stats) {
  double last = now_ms();
  auto step = [&](int a) {
    if (!stats) return;
    ex.sync();
    const double now = now_ms();
    stats->phase_ms.push_back({"pass_" + std::to_string(a), now - last});
    last = now;
  };
  nd_pass_first(ex, L, mask, feat);
  step(0);
  for (int a = 1; a < L.nd; ++a) {
    if (M.iso)
      nd_pass_t<true>(ex, L, M, a, feat, stk);
    else
      nd_pass_t<false>(ex, L, M, a, feat, stk);
    step(a);
  }
}

// The backend entry for an N-D grid: upload, feature transform, outputs, download (as run.inl
// for 2D and 3D).
inline void run_nd(const Request& rq, Output& out, Stats& stats) {
  Exec ex(rq.run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  const NdL L(rq.nd);
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
    nd_transform(ex, L, rq.nd_metric, mask_p, fp, stk.data(), rq.run.profile ? &stats : nullptr);
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
  emit_outputs(ex, rq, L, rq.nd_metric, fp, RankLabels<NdL>{rp, L}, out, lib, 0, nvox);
  stats.phase_ms.push_back({"outputs_device", out.device_outputs_at - t2});
  if (rq.device_out) hand_over(ex, lib, out);
  stats.phase_ms.push_back({"outputs", now_ms() - t2});
  stats.counters["index_bits"] = 8 * std::int64_t(sizeof(S));
}
