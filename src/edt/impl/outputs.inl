// What both modes of the backend entry share (run.inl: a whole grid, slices.inl: slice by
// slice): where each output goes, the per-voxel outputs of a computed block, the grid's sites
// on the executor. Included once per executor, before the packings' namespaces.

// Unrolls the loop that follows under nvcc, whose arrays then stay in registers (host compilers
// choose for themselves).
#if defined(__CUDACC__)
#define GG_EDT_UNROLL _Pragma("unroll")
#else
#define GG_EDT_UNROLL
#endif

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

// Labels of a whole grid: rank[v] is the label of the site at voxel v.
template <class Lay>
struct RankLabels {
  const std::int32_t* rank;
  Lay L;
  template <class S>
  GG_INLINE std::int32_t operator()(S f, std::int64_t) const {
    return rank[L.voxel_of(f)];
  }
};

// The coordinates of voxel i of a block (v: Lay::kAxes entries) and of a site f: the 2D / 3D
// layouts decode their bit fields or raster indices (plane k of a block is slice plane_z(k)),
// the N-D layouts their raster indices (nd.inl's NdL).
template <class Lay>
GG_INLINE void voxel_position(const Lay& L, std::int64_t i, std::int64_t v[]) {
  if constexpr (Lay::kAxes > 3) {
    L.position(i, v);
  } else {
    const std::uint32_t nx = std::uint32_t(L.n[0]), ny = std::uint32_t(L.n[1]);
    const std::uint32_t rest = std::uint32_t(i) / nx;
    v[0] = std::int64_t(std::uint32_t(i) - rest * nx);
    v[1] = std::int64_t(rest % ny);
    v[2] = L.plane_z(rest / ny);
  }
}
template <class Lay, class S>
GG_INLINE void site_position(const Lay& L, S f, std::int64_t c[]) {
  if constexpr (Lay::kAxes > 3) {
    L.coords(f, c);
  } else {
    GG_EDT_UNROLL
    for (int k = 0; k < Lay::kAxes; ++k)
      if (k < L.nd) c[k] = L.coord(f, k);
  }
}

// Labels are int32: a grid's sites are counted before anything is computed.
inline void check_label_count(const Request& rq, std::int64_t sites) {
  if (rq.want_labels && sites > 0x7fffffff)
    throw Error(ErrorCode::InvalidInput,
                "labels are int32 site indices: the grid has " + std::to_string(sites) +
                    " sites, at most 2^31-1 can be labelled (ask for features instead)");
}

// Per-voxel outputs of one computed block (whole grid or one slice), written `at` voxels into
// arrays of `total` voxels: in place where the destination is the executor's memory, else
// through a block-sized array on the executor and one copy back each. Lay: the block's site
// packing; label_of(site, i): the label of the site voxel i holds (called only when labels are
// asked for).
template <class Lay, class S, class LabelOf>
inline void emit_outputs(Exec& ex, const Request& rq, const Lay& L,
                         const MetricT<Lay::kAxes>& metric, const S* feat, LabelOf label_of,
                         Output& out, DeviceArrays& lib, std::int64_t at, std::int64_t total) {
  const std::int64_t n = L.count();
  const Lay Ly = L;
  const MetricT<Lay::kAxes> Mt = metric;
  const bool iso = metric.iso;
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
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) {
          const S f = feat[i];
          if (lp) lp[i] = label_of(f, i);
          if (!dist) return;
          std::int64_t v[Lay::kAxes] = {}, c[Lay::kAxes] = {};
          voxel_position(Ly, i, v);
          site_position(Ly, f, c);
          std::int64_t q = 0;
          double r = 0;
          auto term = [&](int k) {
            const std::int64_t d = c[k] - v[k];
            q += d * d;
            r += Mt.w[k] * double(d * d);
          };
          if constexpr (Lay::kAxes <= 3) {
            // (2D / 3D: unrolled and guarded, the arrays stay in registers: 8192^2 1.30 -> 1.19
            // ms with outputs; N-D: the plain loop, measured faster there, nd.inl)
            GG_EDT_UNROLL
            for (int k = 0; k < Lay::kAxes; ++k)
              if (k < Ly.nd) term(k);
          } else {
            for (int k = 0; k < Ly.nd; ++k) term(k);
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

// Sums counts below 2^63 and ors a flag in the top bit (a carry out of two flags is lost).
constexpr std::uint64_t kNanFlag = std::uint64_t(1) << 63;
struct CountAndFlag {
  GG_INLINE std::uint64_t operator()(std::uint64_t a, std::uint64_t b) const {
    return ((a + b) & (kNanFlag - 1)) | ((a | b) & kNanFlag);
  }
};

// The grid as the transform reads it (a byte per voxel, nonzero = site) on the executor, and
// its site count; throws for NaN values or no site. The host grid's bytes cross the bus as they
// are; a uint8 / bool grid with the non-zero rule is its own mask.
inline const std::uint8_t* grid_mask(Exec& ex, const Request& rq, std::int64_t nvox,
                                     typename Exec::template Buffer<unsigned char>& raw,
                                     typename Exec::template Buffer<std::uint8_t>& mbuf,
                                     std::int64_t& sites, bool may_be_empty = false) {
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
  // The site count in the low 63 bits, a NaN flag in the top one.
  auto sum = ex.template alloc<std::uint64_t>(1);
  ex.transform_reduce_into(
      nvox,
      GG_LAMBDA(std::int64_t i)->std::uint64_t {
        const std::uint8_t v = mask[i];
        return v == 0 ? 0 : (bytes_mask || v == 1) ? 1 : kNanFlag;
      },
      std::uint64_t(0), CountAndFlag{}, sum.data());
  std::uint64_t h = 0;
  ex.to_host(sum.data(), 1, &h);
  if (h & kNanFlag) throw Error(ErrorCode::InvalidInput, "the grid contains NaN values");
  sites = std::int64_t(h);
  if (sites == 0 && !may_be_empty)
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
