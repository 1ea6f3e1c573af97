// The slice-by-slice mode: only the requested z slices are computed, from the list of the
// volume's sites, never from the volume itself; so a volume may be larger than the device, and
// hold any number of voxels (extents up to 65536, a slice fewer than 2^31 - 1 voxels).
//
// The sites are column keys (column_key: the column x + nx y above the z), sorted once, so each
// column's sites form one run ordered by z. A slice z0 then takes, for every column, the
// nearest of its sites along z (a binary search in the column's run; ties to the smaller z, as
// raster order has it), and runs the x and y passes on the slice alone. Every site those
// passes meet is one column's candidate, so sites are packed by column and their z looked up
// in the slice's table (SliceLayout); the tie rule compares (z, column), which is raster order.
// Included once per executor in namespace `sliced`, after pba.inl (Layout = SliceLayout).

// A column's candidate for slice z0 (kNone where the column has no site), its z and label.
struct SliceColumns {
  std::uint32_t* cand;
  std::uint16_t* zcol;
  std::int32_t* lab;  // null: no labels asked for
};

// For every column c of slice z0: the nearest site along z among keys[start[c], start[c+1]).
inline void column_candidates(Exec& ex, const Layout& Ls, const std::uint64_t* keys,
                              const std::int32_t* vals, const std::int64_t* start, std::int64_t z0,
                              const SliceColumns& out) {
  const Layout Ly = Ls;
  const SliceColumns o = out;
  const std::uint32_t nx = std::uint32_t(Ls.n[0]);
  ex.for_each_index(
      Ls.n[0] * Ls.n[1], GG_LAMBDA(std::int64_t c) {
        const std::int64_t s = start[c], e = start[c + 1];
        // first key of the column at or above z0
        auto first_at_least = [&](std::int64_t lo, std::int64_t hi, std::uint64_t want) {
          while (lo < hi) {
            const std::int64_t mid = (lo + hi) / 2;
            if (keys[mid] < want)
              lo = mid + 1;
            else
              hi = mid;
          }
          return lo;
        };
        const std::int64_t lo = first_at_least(s, e, column_key(c, z0));
        std::int64_t best = -1, bd = 0;
        if (lo < e) best = lo, bd = std::int64_t(keys[lo] & kColumnZMask) - z0;
        if (lo > s) {  // the site below wins ties (smaller z: first in raster order)
          const std::int64_t d = z0 - std::int64_t(keys[lo - 1] & kColumnZMask);
          if (best < 0 || d <= bd) best = lo - 1;
        }
        if (best < 0) {
          o.cand[c] = kNone;
          return;
        }
        const std::uint32_t y = std::uint32_t(c) / nx, x = std::uint32_t(c) - y * nx;
        o.cand[c] = Ly.pack(x, y, 0);
        o.zcol[c] = std::uint16_t(keys[best] & kColumnZMask);
        // The label of a repeated site is its first copy's (a stable sort kept the list order).
        if (o.lab) o.lab[c] = vals[first_at_least(s, best, keys[best])];
      });
}

// Labels of a slice: those of its columns' candidates.
struct ColumnLabels {
  const std::int32_t* lab;
  Layout L;
  GG_INLINE std::int32_t operator()(std::uint32_t f) const { return lab[L.column(f)]; }
};

// The sites of a grid on the executor as column keys (raster order; a site's label is its
// place), in chunks of 2^30 voxels (compact_indices writes int32 positions).
inline std::int64_t list_column_keys(Exec& ex, const edt::Layout& L, const std::uint8_t* mask,
                                     std::uint64_t* keys) {
  constexpr std::int64_t kChunk = std::int64_t(1) << 30;
  const std::int64_t nvox = L.count(), nxy = L.n[0] * L.n[1];
  auto vox = ex.template alloc<std::int32_t>(std::size_t(std::min(nvox, kChunk)));
  std::int64_t ns = 0;
  for (std::int64_t c0 = 0; c0 < nvox; c0 += kChunk) {
    const std::uint8_t* mp = mask + c0;
    const std::int64_t k = ex.compact_indices(
        std::min(kChunk, nvox - c0), GG_LAMBDA(std::int64_t i) { return mp[i] != 0; }, vox.data());
    const std::int32_t* vp = vox.data();
    std::uint64_t* kp = keys + ns;
    const std::int64_t first = c0, plane = nxy;
    ex.for_each_index(
        k, GG_LAMBDA(std::int64_t i) {
          const std::int64_t v = first + vp[i];
          kp[i] = column_key(v % plane, v / plane);
        });
    ns += k;
  }
  return ns;
}

inline void run_slices(const Request& rq, Output& out, Stats& stats) {
  Exec ex(rq.run);
  const ::gpugeom::detail::DevicePeak<Exec> peak(ex, stats);
  const edt::Layout L = rq.layout;
  const std::int64_t nxy = L.n[0] * L.n[1], nvox = L.count();
  const std::int64_t nsl = std::int64_t(rq.slices.size());
  const bool labels = rq.want_labels;
  // Device memory: per column, the candidates, the passes' second array, the z table, the
  // column starts (8 B), labels, and the outputs' staging or the library's arrays (at most
  // 8 + 8 + 4 per computed voxel); per site, the key and the label, twice for the sort; the
  // grid on the device adds its mask (a byte per voxel) unless the grid is one.
  const auto& in = rq.into;
  double per_voxel = 0;  // of the output
  if (rq.want_sqdist) per_voxel += 8;
  if (rq.want_distance) per_voxel += rq.want_distance / 8;
  if (labels) per_voxel += 4;
  if (rq.want_features) per_voxel += 4;
  double outputs = double(nxy) * per_voxel;
  if (rq.device_out) {  // the library's arrays hold every computed slice
    double lib_bytes = 0;
    if (rq.want_sqdist && !in.sqdist_int && !in.sqdist_real) lib_bytes += 8;
    if (rq.want_distance == 32 && !in.distance32) lib_bytes += 4;
    if (rq.want_distance == 64 && !in.distance64) lib_bytes += 8;
    if (labels && !in.labels) lib_bytes += 4;
    if (rq.want_features && !in.features) lib_bytes += 12;
    outputs = double(nsl) * double(nxy) * lib_bytes;
  }
  const double per_site = 2 * (8 + (labels ? 4 : 0));
  const double columns = double(nxy) * (4 + 4 + 2 + 8 + (labels ? 4 : 0)) + outputs;
  const bool bytes_mask = rq.rule == SiteRule::NonZero &&
                          (rq.type == io::ScalarType::U8 || rq.type == io::ScalarType::Bool);
  const double mask_bytes = rq.grid && !bytes_mask ? double(nvox) : 0;
  auto require = [&](std::int64_t sites) {
    ::gpugeom::detail::require_device_memory(
        ex, std::max<std::int64_t>(sites, 1),
        (double(std::max<std::int64_t>(sites, 1)) * per_site + columns + mask_bytes) /
            double(std::max<std::int64_t>(sites, 1)),
        "a distance transform by slices with", "sites");
  };
  const double t0 = now_ms();
  typename Exec::template Buffer<std::uint64_t> keys;
  typename Exec::template Buffer<std::int32_t> vals;
  std::int64_t ns = 0;
  if (rq.grid) {  // the grid on the executor: its sites listed there
    require(0);
    typename Exec::template Buffer<unsigned char> raw;
    typename Exec::template Buffer<std::uint8_t> mbuf;
    std::int64_t count = 0;
    const std::uint8_t* mask = grid_mask(ex, rq, nvox, raw, mbuf, count);
    check_label_count(rq, count);
    require(count);
    keys = ex.template alloc<std::uint64_t>(std::size_t(count));
    ns = list_column_keys(ex, L, mask, keys.data());
  } else {
    ns = std::int64_t(rq.column_sites.size());
    check_label_count(rq, ns);
    require(ns);
    keys = ex.template alloc<std::uint64_t>(std::size_t(ns));
    ex.from_host(rq.column_sites.data(), ns, keys.data());
  }
  // Labels: the raster rank of a grid's site, the index of a listed one; a stable sort keeps
  // repeated sites in list order, so a column's run holds a site's first copy first.
  if (labels) {
    vals = ex.template alloc<std::int32_t>(std::size_t(ns));
    std::int32_t* vp = vals.data();
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) { vp[i] = std::int32_t(i); });
    ex.sort_by_key(keys.data(), vals.data(), ns);
  } else {
    ex.sort(keys.data(), ns);
  }
  auto start = ex.template alloc<std::int64_t>(std::size_t(nxy + 1));
  {
    const std::uint64_t* kp = keys.data();
    std::int64_t* sp = start.data();
    const std::int64_t n = ns;
    ex.for_each_index(
        nxy + 1, GG_LAMBDA(std::int64_t c) {
          std::int64_t lo = 0, hi = n;
          const std::uint64_t want = column_key(c, 0);
          while (lo < hi) {
            const std::int64_t mid = (lo + hi) / 2;
            if (kp[mid] < want)
              lo = mid + 1;
            else
              hi = mid;
          }
          sp[c] = lo;
        });
  }
  ex.sync();
  stats.phase_ms.push_back({"upload", now_ms() - t0});

  auto cand = ex.template alloc<std::uint32_t>(std::size_t(nxy));
  auto zcol = ex.template alloc<std::uint16_t>(std::size_t(nxy));
  auto lab = ex.template alloc<std::int32_t>(labels ? std::size_t(nxy) : 0);
  edt::Layout plane = L;
  plane.n[2] = 1;
  Layout Ls(plane, zcol.data());
  PassWork w(ex, Ls, rq.tune, 2);
  DeviceArrays lib;
  double transform = 0;
  for (std::int64_t k = 0; k < nsl; ++k) {
    Ls.z0 = rq.slices[std::size_t(k)];
    const double t1 = now_ms();
    column_candidates(ex, Ls, keys.data(), vals.data(), start.data(), Ls.z0,
                      SliceColumns{cand.data(), zcol.data(), labels ? lab.data() : nullptr});
    for (int a = 0; a < 2; ++a)
      banded_pass(ex, Ls, rq.metric, rq.tune, w, a, cand.data(), w.stk.data());
    ex.sync();
    transform += now_ms() - t1;
    emit_outputs(ex, rq, Ls, cand.data(), ColumnLabels{lab.data(), Ls}, out, lib, k * nxy,
                 nsl * nxy);
  }
  for (int a = 0; a < 2; ++a) stats.counters[std::string("bands_") + "xy"[a]] = w.gs[a].bands;
  if (rq.device_out) hand_over(ex, lib, out);
  out.transform_ms = transform;
  stats.phase_ms.push_back({"transform", transform});
}
