// The backend entry: upload, feature transform (whole grid or slice by slice), outputs,
// download. Included after pba.inl and jfa.inl.

// Where one output goes: the caller's array (into), else the library's: on the executor
// (device_out, kept in `lib`), or the host array `host`. `at` voxels in.
template <class T>
struct Dest {
  T* final = nullptr;   // where the values end up (host or executor memory)
  bool direct = false;  // final is executor memory: kernels write it in place
};
template <class T>
inline Dest<T> dest_of(Exec& ex, const Request& rq, const OutBuffer<T>& into, bool want,
                       std::int64_t total, std::int64_t at, typename Exec::template Buffer<T>& lib,
                       HostVector<T>& host) {
  Dest<T> d;
  if (!want) return d;
  // On the CPU executor host memory is executor memory: every output is written in place.
  const bool on_exec = rq.device_out || Exec::backend == Backend::Cpu;
  if (into) {
    d.final = into.data + at;
  } else if (rq.device_out) {
    if (!lib.size()) lib = ex.template alloc<T>(std::size_t(total));
    d.final = lib.data() + at;
  } else {
    host.resize(std::size_t(total));  // (HostVector: no fill; the copy back touches the pages)
    d.final = host.data() + at;
  }
  d.direct = on_exec;
  return d;
}

// The library's arrays of a device_out run, kept until every block is written.
struct DeviceArrays {
  typename Exec::template Buffer<std::int64_t> sqi;
  typename Exec::template Buffer<double> sqr, d64;
  typename Exec::template Buffer<float> d32;
  typename Exec::template Buffer<std::int32_t> feat, lab;
};

// Per-voxel outputs of one computed block (whole grid or one slice), written `at` voxels into
// arrays of `total` voxels: in place where the destination is the executor's memory, else
// through a block-sized array on the executor and one copy back each.
inline void emit_outputs(Exec& ex, const Request& rq, const Layout& L, const std::uint32_t* feat,
                         const std::uint32_t* sorted_sites, const std::int32_t* sorted_idx,
                         std::int64_t nsites, const std::int32_t* rank_grid, Output& out,
                         DeviceArrays& lib, std::int64_t at, std::int64_t total) {
  const std::int64_t n = L.count();
  const Layout Ly = L;
  const Metric Mt = rq.metric;
  const bool iso = rq.metric.iso;
  const auto dsi = dest_of(ex, rq, rq.into.sqdist_int, rq.want_sqdist && iso, total, at, lib.sqi,
                           out.sqdist_int);
  const auto dsr = dest_of(ex, rq, rq.into.sqdist_real, rq.want_sqdist && !iso, total, at, lib.sqr,
                           out.sqdist_real);
  const auto d64 =
      dest_of(ex, rq, rq.into.distance64, rq.want_distance == 64, total, at, lib.d64, out.dist64);
  const auto d32 =
      dest_of(ex, rq, rq.into.distance32, rq.want_distance == 32, total, at, lib.d32, out.dist32);
  const auto dlb = dest_of(ex, rq, rq.into.labels, rq.want_labels, total, at, lib.lab, out.labels);
  // Staging arrays on the executor for the outputs that go to host memory.
  auto stage = [&](const auto& d) {
    using T = std::remove_pointer_t<decltype(d.final)>;
    return ex.template alloc<T>(d.final && !d.direct ? std::size_t(n) : 0);
  };
  auto ssi = stage(dsi);
  auto ssr = stage(dsr);
  auto s64 = stage(d64);
  auto s32 = stage(d32);
  auto slb = stage(dlb);
  auto where = [](const auto& d, auto& st) { return d.direct ? d.final : st.data(); };
  std::int64_t* si = where(dsi, ssi);
  double* sr = where(dsr, ssr);
  double* dd = where(d64, s64);
  float* df = where(d32, s32);
  std::int32_t* lp = where(dlb, slb);
  const bool dist = si || sr || dd || df;
  if (dist || lp) {  // one pass over the features writes every array asked for
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
  auto back = [&](const auto& d, const auto& st) {
    if (d.final && !d.direct) ex.to_host(st.data(), n, d.final);
  };
  back(dsi, ssi);
  back(dsr, ssr);
  back(d64, s64);
  back(d32, s32);
  back(dlb, slb);
  if (rq.want_features) {
    // Features: nd arrays of `total` each, C axis j being internal axis nd-1-j.
    std::int32_t* fin = nullptr;
    if (rq.into.features) {
      fin = rq.into.features.data;
    } else if (rq.device_out) {
      if (!lib.feat.size()) lib.feat = ex.template alloc<std::int32_t>(std::size_t(total) * L.nd);
      fin = lib.feat.data();
    } else {
      out.features.resize(std::size_t(total) * L.nd);
      fin = out.features.data();
    }
    const bool direct = rq.device_out || Exec::backend == Backend::Cpu;
    auto c = ex.template alloc<std::int32_t>(direct ? 0 : std::size_t(n));
    for (int j = 0; j < L.nd; ++j) {
      const int a = L.nd - 1 - j;
      std::int32_t* cp = direct ? fin + std::size_t(j) * total + at : c.data();
      ex.for_each_index(
          n, GG_LAMBDA(std::int64_t i) { cp[i] = std::int32_t(Ly.coord(feat[i], a)); });
      if (!direct) ex.to_host(cp, n, fin + std::size_t(j) * total + at);
    }
  }
}

// A grid's sites marked on the executor: mask[i] = 1 for a site, 2 for a NaN, else 0.
template <class T>
inline void rule_mask(Exec& ex, const void* grid, std::int64_t n, bool zero, std::uint8_t* mask) {
  const T* g = static_cast<const T*>(grid);
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        const T v = g[i];
        mask[i] = v != v ? 2 : ((v == T(0)) == zero ? 1 : 0);
      });
}

// The grid as the transform reads it (a byte per voxel, nonzero = site) on the executor, and
// its site count; throws for NaN values or no site. The host grid's bytes cross the bus as they
// are; a uint8 / bool grid with the non-zero rule is its own mask.
inline const std::uint8_t* grid_mask(Exec& ex, const Request& rq, std::int64_t nvox,
                                     typename Exec::template Buffer<unsigned char>& raw,
                                     typename Exec::template Buffer<std::uint8_t>& mbuf,
                                     std::int64_t& sites) {
  const void* src = grid_input::on_executor(ex, rq.grid, nvox, rq.type, rq.grid_on_device, raw);
  const bool zero = rq.rule == SiteRule::Zero;
  const bool bytes_mask =
      !zero && (rq.type == io::ScalarType::U8 || rq.type == io::ScalarType::Bool);
  const std::uint8_t* mask = static_cast<const std::uint8_t*>(src);
  if (!bytes_mask) {
    mbuf = ex.template alloc<std::uint8_t>(std::size_t(nvox));
    std::uint8_t* m = mbuf.data();
    grid_input::visit(rq.type, [&](auto tag) { rule_mask<decltype(tag)>(ex, src, nvox, zero, m); });
    mask = m;
  }
  // Sites in the low 32 bits, NaN voxels above: a grid holds fewer than 2^32 - 1 voxels, so
  // neither part overflows.
  auto sum = ex.template alloc<std::uint64_t>(1);
  ex.transform_reduce_into(
      nvox,
      GG_LAMBDA(std::int64_t i)->std::uint64_t {
        const std::uint8_t v = mask[i];
        return v == 0 ? 0 : (bytes_mask || v == 1) ? 1 : std::uint64_t(1) << 32;
      },
      std::uint64_t(0), thrust::plus<std::uint64_t>(), sum.data());
  std::uint64_t h = 0;
  ex.to_host(sum.data(), 1, &h);
  if (h >> 32) throw Error(ErrorCode::InvalidInput, "the grid contains NaN values");
  sites = std::int64_t(h);
  if (sites == 0)
    throw Error(ErrorCode::InvalidInput, std::string("the grid has no site (no ") +
                                             (zero ? "zero" : "nonzero") +
                                             " element): every distance would be infinite");
  return mask;
}

// The library's arrays of a device_out run to the caller (after the last block is written).
inline void hand_over(Exec& ex, DeviceArrays& lib, Output& out) {
  ex.sync();
  if (lib.sqi.size()) out.dev_sqdist_int = lib.sqi.hand_over();
  if (lib.sqr.size()) out.dev_sqdist_real = lib.sqr.hand_over();
  if (lib.d64.size()) out.dev_dist64 = lib.d64.hand_over();
  if (lib.d32.size()) out.dev_dist32 = lib.d32.hand_over();
  if (lib.feat.size()) out.dev_features = lib.feat.hand_over();
  if (lib.lab.size()) out.dev_labels = lib.lab.hand_over();
}

inline void run_impl(const Request& rq, Output& out, Stats& stats) {
  Exec ex(rq.run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  if (rq.slices.empty()) {  // (slice-by-slice holds a part; it is the mode for large volumes)
    // The grid where it is uploaded (its mask: 1 B a voxel where the grid is not one) and the
    // packed sites, then the larger of the passes' second array (4 B) and what the outputs add:
    // the labels' rank grid and the arrays the library allocates (measured: 9 B a voxel with a
    // float32 distance, 17 with labels too).
    const auto& in = rq.into;
    const bool bytes = rq.rule == SiteRule::NonZero &&
                       (rq.type == io::ScalarType::U8 || rq.type == io::ScalarType::Bool);
    double per = 4;
    if (rq.grid && !rq.grid_on_device) per += double(io::scalar_size(rq.type));
    if (rq.grid && !bytes) per += 1;
    double outs = 0;
    if (rq.want_sqdist && !in.sqdist_int && !in.sqdist_real) outs += 8;
    if (rq.want_distance == 32 && !in.distance32) outs += 4;
    if (rq.want_distance == 64 && !in.distance64) outs += 8;
    if (rq.want_features && !in.features) outs += 4.0 * rq.layout.nd;
    if (rq.want_labels) outs += in.labels ? 4 : 8;
    per += outs > 4 ? outs : 4;
    ::gpugeom::detail::require_device_memory(ex, rq.layout.count(), per, "a distance transform",
                                             "voxels");
  }
  const Layout L = rq.layout;
  const std::int64_t nvox = L.count();
  DeviceArrays lib;
  // The sorted site list: for labels, and for the slice-by-slice mode.
  std::int64_t ns = 0;
  auto sites = ex.template alloc<std::uint32_t>(rq.grid ? 0 : rq.sites.size());
  auto sidx = ex.template alloc<std::int32_t>(rq.grid ? 0 : rq.sites.size());
  typename Exec::template Buffer<unsigned char> raw;
  typename Exec::template Buffer<std::uint8_t> mbuf;
  const std::uint8_t* mask_p = nullptr;
  std::int64_t site_count = rq.site_count;
  const double t0 = now_ms();
  if (rq.grid) {
    mask_p = grid_mask(ex, rq, nvox, raw, mbuf, site_count);
    if (rq.want_labels && site_count > 0x7fffffff)
      throw Error(ErrorCode::InvalidInput,
                  "labels are int32 site indices: the grid has " + std::to_string(site_count) +
                      " sites, at most 2^31-1 can be labelled (ask for features instead)");
  } else {
    ns = std::int64_t(rq.sites.size());
    ex.from_host(rq.sites.data(), ns, sites.data());
    std::int32_t* ip = sidx.data();
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) { ip[i] = std::int32_t(i); });
    ex.sort_by_key(sites.data(), sidx.data(), ns);  // stable: duplicates keep the lower index
  }
  std::uint32_t* sorted = sites.data();
  const std::int32_t* sorted_idx = rq.grid ? nullptr : sidx.data();
  if (rq.grid && !rq.slices.empty()) {  // raster order = packed order
    // In chunks of at most 2^30 voxels: compact_indices writes int32 positions.
    constexpr std::int64_t kChunk = std::int64_t(1) << 30;
    auto vox = ex.template alloc<std::int32_t>(std::size_t(std::min(nvox, kChunk)));
    sites = ex.template alloc<std::uint32_t>(std::size_t(site_count));
    sorted = sites.data();
    ns = 0;
    for (std::int64_t c0 = 0; c0 < nvox; c0 += kChunk) {
      const std::uint8_t* mp = mask_p + c0;
      const std::int64_t k = ex.compact_indices(
          std::min(kChunk, nvox - c0), GG_LAMBDA(std::int64_t i) { return mp[i] != 0; },
          vox.data());
      const std::int32_t* vp = vox.data();
      const Layout Ly = L;
      std::uint32_t* sp = sorted + ns;
      const std::int64_t first = c0;
      ex.for_each_index(
          k, GG_LAMBDA(std::int64_t i) { sp[i] = Ly.pack_voxel(first + vp[i]); });
      ns += k;
    }
  }
  ex.sync();
  stats.phase_ms.push_back({"upload", now_ms() - t0});

  if (rq.slices.empty()) {
    auto feat = ex.template alloc<std::uint32_t>(std::size_t(nvox));
    std::uint32_t* fp = feat.data();
    // A mask goes to the transform as it is: its x pass reads a byte per voxel (JFA starts
    // from the packed features).
    const std::uint8_t* site_mask = mask_p;
    if (rq.grid && rq.method == EdtMethod::Jfa) {
      init_features(ex, L, site_mask, fp);
    } else if (!rq.grid) {
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
      feature_transform(ex, L, rq.metric, fp, site_mask, rq.tune, L.nd, site_count, &stats, step);
    else
      feature_transform(ex, L, rq.metric, fp, site_mask, rq.tune, L.nd, site_count, &stats);
    ex.sync();
    out.transform_ms = now_ms() - t1;
    stats.phase_ms.push_back({"transform", out.transform_ms});
    const double t2 = now_ms();
    // Labels: the label of every site voxel in a grid (raster rank of a mask's sites, or the
    // lowest index among a list's duplicates), so each voxel's label is one lookup.
    auto rank = ex.template alloc<std::int32_t>(rq.want_labels ? std::size_t(nvox) : 0);
    std::int32_t* rp = rank.data();
    if (rq.want_labels && rq.grid) {
      const std::uint8_t* mp = mask_p;
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
    emit_outputs(ex, rq, L, fp, sorted, sorted_idx, ns, rp, out, lib, 0, nvox);
    // Labels' grid, distance and label kernels, before any copy back (features excluded).
    stats.phase_ms.push_back({"outputs_device", out.device_outputs_at - t2});
    if (rq.device_out) hand_over(ex, lib, out);
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
    emit_outputs(ex, rq, Ls, fp, sorted, sorted_idx, ns, nullptr, out, lib, k * nxy, nsl * nxy);
  }
  if (rq.device_out) hand_over(ex, lib, out);
  out.transform_ms = transform;
  stats.phase_ms.push_back({"transform", transform});
}
