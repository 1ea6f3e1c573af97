// The backend entry for a whole grid: upload, feature transform, outputs, download. Included
// after grid_transform.inl and jfa.inl, once for each site packing (the slice-by-slice mode is
// slices.inl).

inline void run_whole(const Request& rq, Output& out, EdtStats& stats) {
  Exec ex(rq.run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  {
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
  // Sites: a grid's mask, or the caller's list (packed; duplicates possible).
  const std::int64_t ns = rq.grid ? 0 : std::int64_t(rq.sites.size());
  auto sites = ex.template alloc<std::uint32_t>(std::size_t(ns));
  typename Exec::template Buffer<unsigned char> raw;
  typename Exec::template Buffer<std::uint8_t> mbuf;
  const std::uint8_t* mask_p = nullptr;
  std::int64_t site_count = rq.site_count;
  const double t0 = now_ms();
  if (rq.grid) {
    mask_p = grid_mask(ex, rq, nvox, raw, mbuf, site_count);
    check_label_count(rq, site_count);
  } else {
    ex.from_host(rq.sites.data(), ns, sites.data());
  }
  ex.sync();
  stats.phase_ms.push_back({"upload", now_ms() - t0});

  auto feat = ex.template alloc<std::uint32_t>(std::size_t(nvox));
  std::uint32_t* fp = feat.data();
  // A mask goes to the transform as it is: its x pass reads a byte per voxel (JFA starts
  // from the packed features).
  const std::uint8_t* site_mask = mask_p;
  if (rq.grid && rq.method == EdtMethod::Jfa) {
    init_features(ex, L, site_mask, fp);
  } else if (!rq.grid) {
    ex.fill(fp, nvox, kNone);
    const std::uint32_t* sp = sites.data();
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
    feature_transform(ex, L, rq.metric, fp, site_mask, rq.tune, site_count, &stats, step);
  else
    feature_transform(ex, L, rq.metric, fp, site_mask, rq.tune, site_count, &stats);
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
    const std::uint32_t* sp = sites.data();
    const Layout Ly = L;
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t j) {
          cuda::atomic_ref<std::int32_t, cuda::thread_scope_device> r(rp[Ly.voxel_of(sp[j])]);
          r.fetch_min(std::int32_t(j), cuda::memory_order_relaxed);
        });
  }
  emit_outputs(ex, rq, L, rq.metric, fp, RankLabels<Layout>{rp, L}, out, lib, 0, nvox);
  // Labels' grid, distance and label kernels, before any copy back (features excluded).
  stats.phase_ms.push_back({"outputs_device", out.device_outputs_at - t2});
  if (rq.device_out) hand_over(ex, lib, out);
  stats.phase_ms.push_back({"outputs", now_ms() - t2});
}
