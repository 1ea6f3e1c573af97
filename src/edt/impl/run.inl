// The backend entry: upload, feature transform (whole grid or slice by slice), outputs,
// download. Included after pba.inl and jfa.inl.

// Per-voxel outputs of one computed block (whole grid or one slice) appended at `at`, into
// host arrays that `sizer` is sizing.
inline void emit_outputs(Exec& ex, const Request& rq, const Layout& L, const std::uint32_t* feat,
                         const std::uint32_t* sorted_sites, const std::int32_t* sorted_idx,
                         std::int64_t nsites, const std::int32_t* rank_grid, Output& out,
                         std::int64_t at, std::int64_t total, HostSizer& sizer) {
  const std::int64_t n = L.count();
  const Layout Ly = L;
  const Metric Mt = rq.metric;
  // One kernel writes exactly the distance arrays asked for: nothing computed or copied in vain.
  const bool iso = rq.metric.iso;
  const bool dist = rq.want_sqdist || rq.want_distance;
  auto sqi = ex.template alloc<std::int64_t>(rq.want_sqdist && iso ? std::size_t(n) : 0);
  auto sqr = ex.template alloc<double>(rq.want_sqdist && !iso ? std::size_t(n) : 0);
  auto d64 = ex.template alloc<double>(rq.want_distance == 64 ? std::size_t(n) : 0);
  auto d32 = ex.template alloc<float>(rq.want_distance == 32 ? std::size_t(n) : 0);
  std::int64_t* si = sqi.data();
  double* sr = sqr.data();
  double* dd = d64.data();
  float* df = d32.data();
  auto lab = ex.template alloc<std::int32_t>(rq.want_labels ? std::size_t(n) : 0);
  std::int32_t* lp = lab.data();
  if (dist || rq.want_labels) {  // one pass over the features writes every array asked for
    const std::uint32_t nx = std::uint32_t(L.n[0]), ny = std::uint32_t(L.n[1]);
    const std::int64_t ns = nsites;
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          const std::uint32_t f = feat[i];
          if (lp) {
            if (rank_grid) {  // whole grid: the label of every site voxel is at hand
              lp[i] = rank_grid[Ly.voxel_of(f)];
            } else {  // slices: lower_bound of the site in the sorted list
              std::int64_t lo = 0, hi = ns;
              while (lo < hi) {
                const std::int64_t mid = (lo + hi) / 2;
                if (sorted_sites[mid] < f)
                  lo = mid + 1;
                else
                  hi = mid;
              }
              lp[i] = sorted_idx ? sorted_idx[lo] : std::int32_t(lo);
            }
          }
          if (!dist) return;
          const std::uint32_t rest = std::uint32_t(i) / nx;
          const std::int64_t v[3] = {std::int64_t(std::uint32_t(i) - rest * nx),
                                     std::int64_t(rest % ny), std::int64_t(rest / ny) + Ly.z0};
          std::int64_t q = 0;
          double r = 0;
          for (int k = 0; k < Ly.nd; ++k) {
            const std::int64_t d = Ly.coord(f, k) - v[k];
            q += d * d;
            r += Mt.w[k] * double(d * d);
          }
          const double d2 = Mt.iso ? double(q) : r;
          if (si) si[i] = q;
          if (sr) sr[i] = r;
          if (dd) dd[i] = sqrt(d2);
          if (df) df[i] = float(sqrt(d2));
        });
  }
  ex.sync();  // distances and labels are on the device: the device-resident result
  out.device_outputs_at = now_ms();
  sizer.join();  // the host arrays (size_outputs) are ready for the copies
  if (si) {
    out.sqdist_int.resize(total);
    ex.to_host(si, n, out.sqdist_int.data() + at);
  }
  if (sr) {
    out.sqdist_real.resize(total);
    ex.to_host(sr, n, out.sqdist_real.data() + at);
  }
  if (dd) {
    out.dist64.resize(total);
    ex.to_host(dd, n, out.dist64.data() + at);
  }
  if (df) {
    out.dist32.resize(total);
    ex.to_host(df, n, out.dist32.data() + at);
  }
  if (rq.want_labels) {
    out.labels.resize(total);
    ex.to_host(lp, n, out.labels.data() + at);
  }
  if (rq.want_features) {
    auto c = ex.template alloc<std::int32_t>(std::size_t(n));
    std::int32_t* cp = c.data();
    out.features.resize(std::size_t(total) * L.nd);
    for (int j = 0; j < L.nd; ++j) {  // C axis j is internal axis nd-1-j
      const int a = L.nd - 1 - j;
      ex.for_each_index(
          n, GG_LAMBDA(std::int64_t i) { cp[i] = std::int32_t(Ly.coord(feat[i], a)); });
      ex.to_host(cp, n, out.features.data() + std::size_t(j) * total + at);
    }
  }
}

// Starts zero-filling the result arrays the request asks for (total voxels each) on host
// threads, to overlap the device work: filled on the calling thread as each copy back began,
// their page faults were most of an end-to-end call.
inline void size_outputs(HostSizer& sizer, const Request& rq, Output& out, std::int64_t total) {
  const bool iso = rq.metric.iso;
  if (rq.want_sqdist && iso) sizer.add(out.sqdist_int, total, std::int64_t(0), "squared distances");
  if (rq.want_sqdist && !iso) sizer.add(out.sqdist_real, total, 0.0, "squared distances");
  if (rq.want_distance == 64) sizer.add(out.dist64, total, 0.0, "distances");
  if (rq.want_distance == 32) sizer.add(out.dist32, total, 0.0f, "distances");
  if (rq.want_labels) sizer.add(out.labels, total, std::int32_t(0), "labels");
  if (rq.want_features)
    sizer.add(out.features, total * rq.layout.nd, std::int32_t(0), "nearest-site coordinates");
}

inline void run_impl(const Request& rq, Output& out, Stats& stats) {
  Exec ex(rq.run);
  const Layout L = rq.layout;
  const std::int64_t nvox = L.count();
  // The sorted site list: for labels, and for the slice-by-slice mode.
  std::int64_t ns = 0;
  auto sites = ex.template alloc<std::uint32_t>(rq.mask ? 0 : rq.sites.size());
  auto sidx = ex.template alloc<std::int32_t>(rq.mask ? 0 : rq.sites.size());
  auto mask = ex.template alloc<std::uint8_t>(rq.mask ? std::size_t(nvox) : 0);
  const double t0 = now_ms();
  if (rq.mask) {
    ex.from_host(rq.mask, nvox, mask.data());
  } else {
    ns = std::int64_t(rq.sites.size());
    ex.from_host(rq.sites.data(), ns, sites.data());
    std::int32_t* ip = sidx.data();
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) { ip[i] = std::int32_t(i); });
    ex.sort_by_key(sites.data(), sidx.data(), ns);  // stable: duplicates keep the lower index
  }
  std::uint32_t* sorted = sites.data();
  const std::int32_t* sorted_idx = rq.mask ? nullptr : sidx.data();
  if (rq.mask && !rq.slices.empty()) {  // raster order = packed order
    auto vox = ex.template alloc<std::int32_t>(std::size_t(nvox));
    const std::uint8_t* mp = mask.data();
    ns = ex.compact_indices(
        nvox, GG_LAMBDA(std::int64_t i) { return mp[i] != 0; }, vox.data());
    sites = ex.template alloc<std::uint32_t>(std::size_t(ns));
    sorted = sites.data();
    const std::int32_t* vp = vox.data();
    const Layout Ly = L;
    std::uint32_t* sp = sorted;
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) {
          const std::int64_t v = vp[i];
          sp[i] = Ly.pack(v % Ly.n[0], (v / Ly.n[0]) % Ly.n[1], v / (Ly.n[0] * Ly.n[1]));
        });
  }
  ex.sync();
  stats.phase_ms.push_back({"upload", now_ms() - t0});
  // After the upload, so that it does not compete with it; from a million voxels (below, a
  // thread per array costs more than the fill it would overlap).
  HostSizer sizer;
  const std::int64_t total =
      rq.slices.empty() ? nvox : std::int64_t(rq.slices.size()) * L.n[0] * L.n[1];
  if (total >= (std::int64_t(1) << 20)) size_outputs(sizer, rq, out, total);

  if (rq.slices.empty()) {
    auto feat = ex.template alloc<std::uint32_t>(std::size_t(nvox));
    std::uint32_t* fp = feat.data();
    // A mask goes to the transform as it is: its x pass reads a byte per voxel (JFA starts
    // from the packed features).
    const std::uint8_t* site_mask = rq.mask ? mask.data() : nullptr;
    if (rq.mask && rq.method == EdtMethod::Jfa) {
      init_features(ex, L, site_mask, fp);
    } else if (!rq.mask) {
      ex.fill(fp, nvox, kNone);
      const std::uint32_t* sp = sorted;
      const Layout Ly = L;
      ex.for_each_index(
          ns, GG_LAMBDA(std::int64_t i) { fp[Ly.voxel_of(sp[i])] = sp[i]; });
    }
    ex.sync();
    const double t1 = now_ms();
    // run.profile times each pass (a synchronisation after each: for tuning only).
    double last = t1;
    auto step = [&](int a) {
      ex.sync();
      const double now = now_ms();
      stats.phase_ms.push_back({std::string("pass_") + "xyz"[a], now - last});
      last = now;
    };
    if (rq.method == EdtMethod::Jfa)
      jump_flood(ex, L, rq.metric, fp);
    else if (rq.run.profile)
      feature_transform(ex, L, rq.metric, fp, site_mask, rq.tune, L.nd, rq.site_count, &stats,
                        step);
    else
      feature_transform(ex, L, rq.metric, fp, site_mask, rq.tune, L.nd, rq.site_count, &stats);
    ex.sync();
    out.transform_ms = now_ms() - t1;
    stats.phase_ms.push_back({"transform", out.transform_ms});
    const double t2 = now_ms();
    // Labels: the label of every site voxel in a grid (raster rank of a mask's sites, or the
    // lowest index among a list's duplicates), so each voxel's label is one lookup.
    auto rank = ex.template alloc<std::int32_t>(rq.want_labels ? std::size_t(nvox) : 0);
    std::int32_t* rp = rank.data();
    if (rq.want_labels && rq.mask) {
      const std::uint8_t* mp = mask.data();
      ex.exclusive_scan_of(
          nvox, GG_LAMBDA(std::int64_t i)->std::int32_t { return mp[i] ? 1 : 0; }, rp);
    } else if (rq.want_labels) {
      ex.fill(rp, nvox, std::int32_t(0x7fffffff));
      const std::uint32_t* sp = sorted;
      const std::int32_t* ip = sorted_idx;
      const Layout Ly = L;
      ex.for_each_index(
          ns, GG_LAMBDA(std::int64_t j) {
            cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> r(rp[Ly.voxel_of(sp[j])]);
            r.fetch_min(ip[j], cuda::memory_order_relaxed);
          });
    }
    emit_outputs(ex, rq, L, fp, sorted, sorted_idx, ns, rp, out, 0, nvox, sizer);
    // Labels' grid, distance and label kernels, before any copy back (features excluded).
    stats.phase_ms.push_back({"outputs_device", out.device_outputs_at - t2});
    stats.phase_ms.push_back({"outputs", now_ms() - t2});
    return;
  }

  // Slice by slice: sites sorted by (y, x, z) give, for each (x, y) and a slice z0, the
  // nearest site along z by binary search; then the x and y passes run on that slice alone.
  const std::int64_t nxy = L.n[0] * L.n[1];
  auto keys = ex.template alloc<std::uint64_t>(std::size_t(ns));
  auto order = ex.template alloc<std::uint32_t>(std::size_t(ns));
  {
    std::uint64_t* kp = keys.data();
    std::uint32_t* op = order.data();
    const std::uint32_t* sp = sorted;
    const Layout Ly = L;
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) {
          const std::uint32_t s = sp[i];
          kp[i] = (std::uint64_t(Ly.coord(s, 1) * Ly.n[0] + Ly.coord(s, 0)) << 32) |
                  std::uint64_t(Ly.coord(s, 2));
          op[i] = s;
        });
    ex.sort_by_key(kp, op, ns);
  }
  Layout Ls = L;
  Ls.n[2] = 1;
  auto feat = ex.template alloc<std::uint32_t>(std::size_t(nxy));
  const std::int64_t nsl = std::int64_t(rq.slices.size());
  double transform = 0;
  for (std::int64_t k = 0; k < nsl; ++k) {
    Ls.z0 = rq.slices[k];
    const double t1 = now_ms();
    std::uint32_t* fp = feat.data();
    const std::uint64_t* kp = keys.data();
    const std::uint32_t* op = order.data();
    const std::int64_t z0 = Ls.z0, nsites = ns;
    ex.for_each_index(
        nxy, GG_LAMBDA(std::int64_t c) {
          const std::uint64_t want = (std::uint64_t(c) << 32) | std::uint64_t(z0);
          std::int64_t lo = 0, hi = nsites;  // first key >= (c, z0)
          while (lo < hi) {
            const std::int64_t mid = (lo + hi) / 2;
            if (kp[mid] < want)
              lo = mid + 1;
            else
              hi = mid;
          }
          std::uint32_t best = kNone;
          std::int64_t bd = 0;
          if (lo < nsites && (kp[lo] >> 32) == std::uint64_t(c)) {
            best = op[lo];
            bd = std::int64_t(kp[lo] & 0xffffffffu) - z0;
          }
          if (lo > 0 && (kp[lo - 1] >> 32) == std::uint64_t(c)) {  // below: wins ties (smaller z)
            const std::int64_t d = z0 - std::int64_t(kp[lo - 1] & 0xffffffffu);
            if (best == kNone || d <= bd) best = op[lo - 1];
          }
          fp[c] = best;
        });
    feature_transform(ex, Ls, rq.metric, fp, nullptr, rq.tune, 2, 0, &stats);
    ex.sync();
    transform += now_ms() - t1;
    emit_outputs(ex, rq, Ls, fp, sorted, sorted_idx, ns, nullptr, out, k * nxy, nsl * nxy, sizer);
  }
  out.transform_ms = transform;
  stats.phase_ms.push_back({"transform", transform});
}

// The entry points edt_backend.hpp and edt_device.hpp declare, the same for both executors.
void run(const Request& req, Output& out, Stats& stats) {
  run_impl(req, out, stats);
}
void feature_transform_held(Exec& ex, const Layout& L, const Metric& M, std::uint32_t* feat,
                            std::int64_t sites) {
  feature_transform(ex, L, M, feat, nullptr, Tuning{}, L.nd, sites, nullptr);
}
