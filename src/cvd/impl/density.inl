// The density on the executor: checked, quantised to 16 bits of its maximum, spread over the
// Voronoi grid, and the initial sites drawn from it. One algorithm for both executors, whether
// the caller's density is on the host or on the device; included inside gpugeom::cvd::
// {cpu,cuda}_impl before lloyd.inl.

using edt::Layout;

struct MaxBad {  // the density's maximum, and how many values are NaN, infinite or negative
  double max;
  std::int64_t bad;
};
struct MaxBadOp {
  GG_HD MaxBad operator()(const MaxBad& a, const MaxBad& b) const {
    return {a.max > b.max ? a.max : b.max, a.bad + b.bad};
  }
};
template <class T>
inline MaxBad density_max(Exec& ex, const void* d, std::int64_t np) {
  const T* g = static_cast<const T*>(d);
  auto r = ex.template alloc<MaxBad>(1);
  ex.transform_reduce_into(
      np,
      GG_LAMBDA(std::int64_t i)->MaxBad {
        const double v = double(g[i]);
        const bool ok = v >= 0 && v <= 1.7976931348623157e308;  // (false for NaN)
        return MaxBad{ok ? v : 0.0, ok ? 0 : 1};
      },
      MaxBad{0.0, 0}, MaxBadOp{}, r.data());
  MaxBad h;
  ex.to_host(r.data(), 1, &h);
  return h;
}

// q[p] = round(density(p) / max * 65535), pixel by pixel (as the host did: the same doubles).
template <class T>
inline void quantise(Exec& ex, const void* d, std::int64_t np, double vmax, std::uint32_t* q) {
  const T* g = static_cast<const T*>(d);
  ex.for_each_index(
      np,
      GG_LAMBDA(std::int64_t i) { q[i] = std::uint32_t(llround(double(g[i]) / vmax * kLevels)); });
}

// The quantised density per pixel, and its maximum; throws Error(InvalidInput) for bad values.
struct Quantised {
  typename Exec::template Buffer<std::uint32_t> q;
  double vmax = 0;
};
inline Quantised quantised_density(Exec& ex, const Request& rq, std::int64_t np) {
  typename Exec::template Buffer<unsigned char> raw;
  const void* d = grid_input::on_executor(ex, rq.density, np, rq.type, rq.on_device, raw);
  MaxBad mb{0, 0};
  grid_input::visit(rq.type, [&](auto tag) { mb = density_max<decltype(tag)>(ex, d, np); });
  if (mb.bad)
    throw Error(ErrorCode::InvalidInput,
                "the density must be finite and non-negative everywhere (" +
                    std::to_string(mb.bad) + " values are not)");
  if (!(mb.max > 0))
    throw Error(ErrorCode::InvalidInput, "the density is zero everywhere: no cell has a centroid");
  Quantised Q;
  Q.vmax = mb.max;
  Q.q = ex.template alloc<std::uint32_t>(std::size_t(np));
  grid_input::visit(rq.type,
                    [&](auto tag) { quantise<decltype(tag)>(ex, d, np, mb.max, Q.q.data()); });
  return Q;
}

// Each grid point takes its pixel's weight.
inline void spread(Exec& ex, const edt::Layout& L, const std::int64_t pext[3], int s,
                   const std::uint32_t* q, std::uint32_t* w) {
  const edt::Layout Ly = L;
  const std::int64_t px = pext[0], py = pext[1];
  ex.for_each_index(
      L.count(), GG_LAMBDA(std::int64_t i) {
        const std::int64_t x = i % Ly.n[0], y = (i / Ly.n[0]) % Ly.n[1],
                           z = i / (Ly.n[0] * Ly.n[1]);
        w[i] = q[(x / s) + px * ((y / s) + py * (z / s))];
      });
}

// Density-weighted draw of distinct grid points: a pixel with probability proportional to its
// weight (cumulative sums over pixels, not grid points: s^d times less memory when
// supersampled), then one of its s^d grid points uniformly. The random numbers come from the
// host's generator in their fixed order; the executor finds the pixel of each (a binary search
// in the sums), in batches, so only the draws cross the bus. Returns grid coordinates, nd per
// site, internal axis order.
inline std::vector<std::int32_t> draw_sites(Exec& ex, const edt::Layout& L, const std::uint32_t* q,
                                            std::int64_t np, const std::int64_t pext[3], int s,
                                            std::int64_t want, std::uint64_t seed) {
  using u64 = std::uint64_t;
  std::int64_t per = 1;  // grid points per pixel
  for (int a = 0; a < L.nd; ++a) per *= s;
  auto cumb = ex.template alloc<u64>(std::size_t(np) + 1);
  u64* cum = cumb.data();
  ex.exclusive_scan_of(
      np + 1, GG_LAMBDA(std::int64_t i)->u64 { return i < np ? u64(q[i]) : u64(0); }, cum);
  auto posb = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      np, GG_LAMBDA(std::int64_t i)->std::int64_t { return q[i] > 0 ? 1 : 0; }, std::int64_t(0),
      thrust::plus<std::int64_t>(), posb.data());
  std::int64_t positive = 0;
  u64 total = 0;
  ex.to_host(posb.data(), 1, &positive);
  ex.to_host(cum + np, 1, &total);
  positive *= per;
  if (want > positive)
    throw Error(ErrorCode::InvalidInput,
                "asked for " + std::to_string(want) +
                    " sites but the density is positive at only " + std::to_string(positive) +
                    " grid points: ask for fewer sites or a larger supersample");
  if (want >= (std::int64_t(1) << 31))
    throw Error(ErrorCode::InvalidInput, "too many sites (at most 2^31-1)");
  // Grid point k (0 <= k < per) of pixel p, as a raster index of the grid.
  auto point = [&](std::int64_t p, std::int64_t k) {
    const std::int64_t px = p % pext[0], py = (p / pext[0]) % pext[1], pz = p / (pext[0] * pext[1]);
    const std::int64_t x = px * s + k % s, y = py * s + (k / s) % s, z = pz * s + k / (s * s);
    return x + L.n[0] * (y + L.n[1] * (L.nd == 3 ? z : 0));
  };
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<u64> pick(0, total - 1);
  std::uniform_int_distribution<std::int64_t> sub(0, per - 1);
  std::unordered_set<std::int64_t> used;
  used.reserve(std::size_t(want) * 2);
  std::vector<std::int64_t> chosen;
  chosen.reserve(std::size_t(want));
  const std::int64_t tries = 50 * want + 1000;
  std::vector<u64> r;
  std::vector<std::int64_t> k, pix;
  for (std::int64_t done = 0; done < tries && std::int64_t(chosen.size()) < want;) {
    // A batch of draws, a little more than the sites still missing (copies are rare).
    const std::int64_t missing = want - std::int64_t(chosen.size());
    const std::int64_t b = std::min(tries - done, missing + missing / 8 + 1024);
    r.resize(std::size_t(b));
    k.resize(std::size_t(b));
    pix.resize(std::size_t(b));
    for (std::int64_t j = 0; j < b; ++j) r[j] = pick(rng), k[j] = sub(rng);
    auto rb = ex.template alloc<u64>(std::size_t(b));
    auto pb = ex.template alloc<std::int64_t>(std::size_t(b));
    ex.from_host(r.data(), b, rb.data());
    const u64* rd = rb.data();
    std::int64_t* pd = pb.data();
    ex.for_each_index(
        b, GG_LAMBDA(std::int64_t j) {  // the pixel whose weight interval holds r: last cum <= r
          const u64 x = rd[j];
          std::int64_t lo = 0, hi = np + 1;  // cum[lo] <= x < cum[hi] (cum[np + 1] = inf)
          while (hi - lo > 1) {
            const std::int64_t mid = lo + (hi - lo) / 2;
            if (cum[mid] <= x)
              lo = mid;
            else
              hi = mid;
          }
          pd[j] = lo;
        });
    ex.to_host(pd, b, pix.data());
    for (std::int64_t j = 0; j < b && std::int64_t(chosen.size()) < want; ++j) {
      const std::int64_t i = point(pix[j], k[j]);
      if (used.insert(i).second) chosen.push_back(i);
    }
    done += b;
  }
  if (std::int64_t(chosen.size()) < want) {  // nearly full: the first free points, in order
    std::vector<std::uint32_t> hq(static_cast<std::size_t>(np));
    ex.to_host(q, np, hq.data());
    for (std::int64_t p = 0; p < np && std::int64_t(chosen.size()) < want; ++p)
      for (std::int64_t j = 0; j < per && hq[p] > 0 && std::int64_t(chosen.size()) < want; ++j)
        if (used.insert(point(p, j)).second) chosen.push_back(point(p, j));
  }
  std::vector<std::int32_t> out;
  out.reserve(chosen.size() * L.nd);
  for (std::int64_t i : chosen) {
    out.push_back(std::int32_t(i % L.n[0]));
    out.push_back(std::int32_t((i / L.n[0]) % L.n[1]));
    if (L.nd == 3) out.push_back(std::int32_t(i / (L.n[0] * L.n[1])));
  }
  return out;
}
