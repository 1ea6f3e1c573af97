// The slice-by-slice mode: only the requested z slices are computed, from the list of the
// volume's sites, never from the volume itself; so a volume may be larger than the device, and
// (with ColumnLayout) hold any number of voxels: extents up to 65536, a slice fewer than
// 2^31 - 1 voxels.
//
// The sites are column keys (column_key: the column x + nx y above the z), sorted once, so each
// column's sites form one run ordered by z (columns.inl). Slices are computed in blocks of about
// 2^24 voxels (one slice of 1024^2 alone left the device mostly idle between launches): each plane
// of a block takes, for every column, the nearest of its sites along z (a binary search in the
// column's run; ties to the smaller z, as raster order has it), and the x and y passes run on
// the block. Included after pba.inl in one namespace per block layout (Layout: SlicePlanes of
// the volume's own packing, or ColumnLayout).

// Where a block's columns put their candidates (column_candidates, columns.inl): the packed site
// (kNone where the column has no site) and, with ColumnLayout, its z, per plane and column.
struct SliceColumns {
  std::uint32_t* cand;
  std::uint16_t* zcol;
  Layout L;
  struct Column {
    std::uint32_t x, y;
  };
  GG_INLINE Column column(std::int64_t c) const {
    const std::uint32_t nx = std::uint32_t(L.n[0]);
    const std::uint32_t y = std::uint32_t(c) / nx;
    return {std::uint32_t(c) - y * nx, y};
  }
  GG_INLINE void operator()(std::int64_t i, Column col, std::int64_t k, std::int64_t z) const {
    if (z < 0) {
      cand[i] = kNone;
      return;
    }
    cand[i] = L.candidate(col.x, col.y, k, z);
    if constexpr (Layout::kColumns) zcol[i] = std::uint16_t(z);
  }
};

// Labels of a block: those of its planes' candidates (voxel i's site is a candidate of i's
// plane).
struct ColumnLabels {
  const std::int32_t* lab;
  Layout L;
  GG_INLINE std::int32_t operator()(std::uint32_t f, std::int64_t i) const {
    const std::int64_t nxy = L.n[0] * L.n[1];
    return lab[(i / nxy) * nxy + L.coord(f, 1) * L.n[0] + L.coord(f, 0)];
  }
};

// Planes per block: about `voxels` (0: 2^24), at least one; packed by column, as many as the
// plane field's bits above x and y allow.
inline std::int64_t planes_per_block(const edt::Layout& L, std::int64_t voxels,
                                     std::int64_t slices) {
  const std::int64_t nxy = L.n[0] * L.n[1];
  std::int64_t k = std::max<std::int64_t>(1, (voxels > 0 ? voxels : std::int64_t(1) << 24) / nxy);
  if (Layout::kColumns) k = std::min<std::int64_t>(k, std::int64_t(1) << (32 - L.shift[2]));
  return std::min(k, slices);
}

inline void run_slices(const Request& rq, Output& out, EdtStats& stats) {
  Exec ex(rq.run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  const edt::Layout L = rq.layout;
  const std::int64_t nxy = L.n[0] * L.n[1], nvox = L.count();
  const std::int64_t nsl = std::int64_t(rq.slices.size());
  const bool labels = rq.want_labels;
  const std::int64_t per_block = planes_per_block(L, rq.tune.slice_block, nsl);
  // Device memory, checked before any launch and again once a device grid's sites are counted:
  // the sites' keys (and labels), twice while they are sorted; then a block's arrays (its
  // candidates, the passes' second array, the z table by column, labels, and the outputs'
  // staging) with the columns' starts and places; the library's arrays for every computed slice
  // (device_out); a device grid's mask while its sites are listed (unless the grid is one).
  const double block = double(per_block) * double(nxy);
  const auto& in = rq.into;
  const bool direct = rq.device_out || Exec::backend == Backend::Cpu;
  double per_voxel = 4 + 4 + (Layout::kColumns ? 2 : 0) + (labels ? 4 : 0);
  if (!direct) per_voxel += (rq.want_sqdist ? 8 : 0) + rq.want_distance / 8 + (labels ? 4 : 0);
  double lib = 0;  // a byte count per computed voxel
  if (rq.device_out) {
    if (rq.want_sqdist && !in.sqdist_int && !in.sqdist_real) lib += 8;
    if (rq.want_distance == 32 && !in.distance32) lib += 4;
    if (rq.want_distance == 64 && !in.distance64) lib += 8;
    if (labels && !in.labels) lib += 4;
    if (rq.want_features && !in.features) lib += 12;
  }
  const bool bytes_mask = rq.rule == SiteRule::NonZero &&
                          (rq.type == io::ScalarType::U8 || rq.type == io::ScalarType::Bool);
  // listing: the voxels of a grid whose sites are being listed (its mask's bytes), else 0
  auto require = [&](std::int64_t sites, std::int64_t listing) {
    const double keys = double(sites) * (8 + (labels ? 4 : 0));
    const double bytes = keys + std::max(keys, block * per_voxel + double(nxy) * 16) +
                         double(nsl) * double(nxy) * lib + (!bytes_mask ? double(listing) : 0);
    ::gpugeom::detail::require_device_bytes(
        ex, std::uint64_t(bytes),
        "a distance transform of " + std::to_string(nsl) + " slices of " + std::to_string(L.n[0]) +
            " x " + std::to_string(L.n[1]) + " voxels with " + std::to_string(sites) + " sites");
  };
  const double t0 = now_ms();
  typename Exec::template Buffer<std::uint64_t> keys;
  typename Exec::template Buffer<std::int32_t> vals;
  std::int64_t ns = 0;
  if (rq.grid) {  // the grid on the executor: its sites listed there
    ns = grid_column_keys(ex, rq, nvox, nxy, require, keys);
  } else {
    ns = std::int64_t(rq.column_sites.size());
    check_label_count(rq, ns);
    require(ns, 0);
    keys = ex.template alloc<std::uint64_t>(std::size_t(ns));
    ex.from_host(rq.column_sites.data(), ns, keys.data());
  }
  // Labels: the raster rank of a grid's site, the index of a listed one.
  if (labels) vals = ex.template alloc<std::int32_t>(std::size_t(ns));
  auto start = column_runs(ex, keys.data(), labels ? vals.data() : nullptr, ns, nxy);
  ex.sync();
  stats.phase_ms.push_back({"upload", now_ms() - t0});

  // The slices' z on the executor (plane_z of each block), and a block's arrays.
  auto zs = ex.template alloc<std::uint16_t>(std::size_t(nsl));
  {
    std::vector<std::uint16_t> z(rq.slices.begin(), rq.slices.end());
    ex.from_host(z.data(), nsl, zs.data());
  }
  const std::size_t bv = std::size_t(per_block * nxy);
  auto cand = ex.template alloc<std::uint32_t>(bv);
  auto zcol = ex.template alloc<std::uint16_t>(Layout::kColumns ? bv : 0);
  auto lab = ex.template alloc<std::int32_t>(labels ? bv : 0);
  auto at = ex.template alloc<std::int64_t>(std::size_t(nxy));
  DeviceArrays arrays;
  double transform = 0, steps[3] = {0, 0, 0};
  std::int64_t bands[2] = {0, 0};
  for (std::int64_t k0 = 0; k0 < nsl; k0 += per_block) {
    edt::Layout planes = L;
    planes.n[2] = std::min(per_block, nsl - k0);
    const Layout Lb(planes, zs.data() + k0, zcol.data());
    const double t1 = now_ms();
    // run.profile times each step (a synchronisation after each: for tuning only).
    double last = t1;
    auto step = [&](int j) {
      if (!rq.run.profile) return;
      ex.sync();
      const double now = now_ms();
      steps[j] += now - last;
      last = now;
    };
    column_candidates(ex, nxy, planes.n[2], zs.data() + k0, keys.data(), vals.data(), start.data(),
                      at.data(), k0 ? rq.slices[std::size_t(k0 - 1)] : -1,
                      labels ? lab.data() : nullptr, SliceColumns{cand.data(), zcol.data(), Lb});
    step(0);
    PassWork w(ex, Lb, rq.tune, 2);
    for (int a = 0; a < 2; ++a) {
      banded_pass(ex, Lb, rq.metric, rq.tune, w, a, cand.data(), w.stk.data());
      bands[a] = w.gs[a].bands;
      step(1 + a);
    }
    ex.sync();
    transform += now_ms() - t1;
    emit_outputs(ex, rq, Lb, rq.metric, cand.data(), ColumnLabels{lab.data(), Lb}, out, arrays,
                 k0 * nxy, nsl * nxy);
  }
  for (int a = 0; a < 2; ++a) set_bands(stats, a, bands[a]);
  stats.slices_per_block = per_block;
  if (rq.device_out) hand_over(ex, arrays, out);
  out.transform_ms = transform;
  if (rq.run.profile) {
    stats.phase_ms.push_back({"candidates", steps[0]});
    stats.phase_ms.push_back({"pass_x", steps[1]});
    stats.phase_ms.push_back({"pass_y", steps[2]});
  }
  stats.phase_ms.push_back({"transform", transform});
}
