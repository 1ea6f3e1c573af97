// What the slice-by-slice modes of 3D (slices.inl) and N-D grids (nd.inl) share: a volume's
// sites as column keys (column_key: the site's place in its slice above its index z along C axis
// 0), sorted so that each column's sites form one run ordered by z, and for every column of a
// block of slices the nearest of its sites along z. Included once per executor, before the
// packings' namespaces.

// The sites of a grid on the executor as column keys (raster order; a site's label is its
// place), in chunks of 2^30 voxels (compact_indices writes int32 positions). plane: voxels in a
// slice; z0: the grid's first slice in the layout (a slab's).
inline std::int64_t list_column_keys(Exec& ex, std::int64_t nvox, std::int64_t plane,
                                     const std::uint8_t* mask, std::uint64_t* keys,
                                     std::int64_t z0 = 0) {
  constexpr std::int64_t kChunk = std::int64_t(1) << 30;
  auto vox = ex.template alloc<std::int32_t>(std::size_t(std::min(nvox, kChunk)));
  std::int64_t ns = 0;
  for (std::int64_t c0 = 0; c0 < nvox; c0 += kChunk) {
    const std::uint8_t* mp = mask + c0;
    const std::int64_t k = ex.compact_indices(
        std::min(kChunk, nvox - c0), GG_LAMBDA(std::int64_t i) { return mp[i] != 0; }, vox.data());
    const std::int32_t* vp = vox.data();
    std::uint64_t* kp = keys + ns;
    const std::int64_t first = c0, pl = plane;
    ex.for_each_index(
        k, GG_LAMBDA(std::int64_t i) {
          const std::int64_t v = first + vp[i];
          kp[i] = column_key(v % pl, v / pl + z0);
        });
    ns += k;
  }
  return ns;
}

// The column keys of a grid on the executor (rq.grid), listed there; where the grid is a slab of
// the layout (rq.slab_planes), its sites' z moved to the layout's and the slab's bounds
// (rq.column_sites) appended, and a slab without sites of its own is no error. nvox: the
// layout's voxels; require(sites, voxels listed): the caller's device-memory check. Returns the
// count.
template <class Require>
inline std::int64_t grid_column_keys(Exec& ex, const Request& rq, std::int64_t nvox,
                                     std::int64_t plane, Require require,
                                     typename Exec::template Buffer<std::uint64_t>& keys) {
  const std::int64_t gvox = rq.slab_planes ? rq.slab_planes * plane : nvox;
  const std::int64_t extra = rq.slab_planes ? std::int64_t(rq.column_sites.size()) : 0;
  require(extra, gvox);
  typename Exec::template Buffer<unsigned char> raw;
  typename Exec::template Buffer<std::uint8_t> mbuf;
  std::int64_t count = 0;
  const std::uint8_t* mask = grid_mask(ex, rq, gvox, raw, mbuf, count, extra > 0);
  check_label_count(rq, count + extra);
  require(count + extra, gvox);
  keys = ex.template alloc<std::uint64_t>(std::size_t(count + extra));
  std::int64_t ns = list_column_keys(ex, gvox, plane, mask, keys.data(), rq.slab_first);
  if (extra) ex.from_host(rq.column_sites.data(), extra, keys.data() + ns);
  return ns + extra;
}

// Sorts the keys (with their labels, vals, where asked for: a stable sort keeps repeated sites in
// list order, so a column's run holds a site's first copy first) and returns where each of the
// `columns` columns' runs starts (columns + 1 entries).
inline typename Exec::template Buffer<std::int64_t> column_runs(Exec& ex, std::uint64_t* keys,
                                                                std::int32_t* vals, std::int64_t ns,
                                                                std::int64_t columns) {
  if (vals) {
    ex.for_each_index(
        ns, GG_LAMBDA(std::int64_t i) { vals[i] = std::int32_t(i); });
    ex.sort_by_key(keys, vals, ns);
  } else {
    ex.sort(keys, ns);
  }
  auto start = ex.template alloc<std::int64_t>(std::size_t(columns + 1));
  const std::uint64_t* kp = keys;
  std::int64_t* sp = start.data();
  ex.for_each_index(
      columns + 1, GG_LAMBDA(std::int64_t c) {
        std::int64_t lo = 0, hi = ns;
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
  return start;
}

// For every column c of every plane k of a block (planes of `columns` voxels, plane k being the
// volume's slice zs[k]): the nearest site along z among keys[start[c], start[c+1]), handed to
// put(i, col, k, z) with i = k columns + c and col = put.column(c), what put needs of the column
// (worked out once a column), z = -1 where the column has no site; and its label to lab[i] where
// lab is given. A thread takes one column through the block's planes, so where the
// planes' z increase (the slices of a range, in order) it moves forward from the previous
// plane's place in the run, reading the run about once, where a search per plane and column
// made several scattered reads each (1600^3, every slice: 350 ms of 866). at[c] carries the
// place from block to block: the first key of the column at or above z `prev_z` (-1: none yet).
template <class Put>
inline void column_candidates(Exec& ex, std::int64_t columns, std::int64_t planes,
                              const std::uint16_t* zs, const std::uint64_t* keys,
                              const std::int32_t* vals, const std::int64_t* start, std::int64_t* at,
                              std::int64_t prev_z, std::int32_t* lab, Put put) {
  ex.for_each_index(
      columns, GG_LAMBDA(std::int64_t c) {
        const std::int64_t s = start[c], e = start[c + 1];
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
        const auto col = put.column(c);
        std::int64_t lo = prev_z < 0 ? s : at[c], prev = prev_z;  // keys before lo: below prev
        // The keys around lo (and their labels, once asked for) stay in registers while lo
        // stays: most planes then read nothing.
        constexpr std::uint64_t kNoKey = ~std::uint64_t(0);
        std::uint64_t above = kNoKey, below = kNoKey;
        std::int32_t lab_above = -1, lab_below = -1;
        auto refresh = [&]() {
          above = lo < e ? keys[lo] : kNoKey;
          below = lo > s ? keys[lo - 1] : kNoKey;
          lab_above = lab_below = -1;
        };
        refresh();
        for (std::int64_t k = 0; k < planes; ++k) {
          const std::int64_t z0 = zs[k], i = k * columns + c;
          const std::uint64_t want = column_key(c, z0);
          if (z0 < prev) {  // planes out of order: search the whole run again
            lo = first_at_least(s, e, want);
            refresh();
          } else if (above < want) {  // (kNoKey is above every key)
            // the first key at or above z0: the next one (slices in order), else a search
            ++lo;
            if (lo < e && keys[lo] < want) lo = first_at_least(lo + 1, e, want);
            refresh();
          }
          prev = z0;
          // The nearer of the sites above and below; ties to the one below (smaller z: first
          // in raster order).
          bool use_below = below != kNoKey;
          if (use_below && above != kNoKey)
            use_below =
                z0 - std::int64_t(below & kColumnZMask) <= std::int64_t(above & kColumnZMask) - z0;
          if (!use_below && above == kNoKey) {
            put(i, col, k, std::int64_t(-1));
            continue;
          }
          put(i, col, k, std::int64_t((use_below ? below : above) & kColumnZMask));
          if (!lab) continue;
          // A repeated site's label is its first copy's (a stable sort kept the list order):
          // the site above is its first copy (lo is the first key at or above z0), the one below
          // may have copies before it.
          if (use_below) {
            if (lab_below < 0) lab_below = vals[first_at_least(s, lo - 1, below)];
            lab[i] = lab_below;
          } else {
            if (lab_above < 0) lab_above = vals[lo];
            lab[i] = lab_above;
          }
        }
        at[c] = lo;
      });
}
