// Input preparation on the executor: validation, Hilbert order, duplicates, the first triangle
// (thesis 6.4). Included inside gpugeom::del2d::{cpu,cuda}_impl after geometry.inl.

using u64 = std::uint64_t;

struct Bounds {
  double lo[2], hi[2];
  std::int64_t bad;  // coordinates that are NaN, Inf or outside the exact range
};
struct BoundsOp {
  GG_HD Bounds operator()(const Bounds& a, const Bounds& b) const {
    Bounds r;
    for (int d = 0; d < 2; ++d) {
      r.lo[d] = a.lo[d] < b.lo[d] ? a.lo[d] : b.lo[d];
      r.hi[d] = a.hi[d] > b.hi[d] ? a.hi[d] : b.hi[d];
    }
    r.bad = a.bad + b.bad;
    return r;
  }
};

// A point and its index, ordered lexicographically by (x, y) then index.
struct Extreme {
  double x, y;
  std::int32_t i;
};
struct MinLex {
  GG_HD Extreme operator()(const Extreme& a, const Extreme& b) const {
    if (a.x != b.x) return a.x < b.x ? a : b;
    if (a.y != b.y) return a.y < b.y ? a : b;
    return a.i < b.i ? a : b;
  }
};
struct MaxLex {
  GG_HD Extreme operator()(const Extreme& a, const Extreme& b) const {
    if (a.x != b.x) return a.x > b.x ? a : b;
    if (a.y != b.y) return a.y > b.y ? a : b;
    return a.i < b.i ? a : b;
  }
};
struct Farthest {  // x holds |orientation|, the largest wins, then the smaller index
  GG_HD Extreme operator()(const Extreme& a, const Extreme& b) const {
    if (a.x != b.x) return a.x > b.x ? a : b;
    return a.i < b.i ? a : b;
  }
};

// Doubles as unsigned keys with the same order (-0 was turned into +0 before).
GG_INLINE u64 ordered_key(double v) {
  u64 u;
  memcpy(&u, &v, 8);
  return (u >> 63) ? ~u : (u | (u64(1) << 63));
}

struct Prepared {
  typename Exec::template Buffer<double> pts;         // 2 per distinct point, curve order
  typename Exec::template Buffer<std::int32_t> orig;  // input index of each
  typename Exec::template Buffer<std::int32_t> dup;   // n entries (duplicate_of), when any
  std::int64_t m = 0;
  std::int64_t duplicates = 0;
  std::int32_t first[3] = {0, 0, 0};  // the first triangle, counter-clockwise
  double kernel[2] = {0, 0};
  double upload_ms = 0;
};

// xy: on the host, or on the executor when on_device.
// (after_upload is a std::function: nvcc refuses a lambda type as a template argument of a
// function holding device lambdas.)
inline Prepared prepare(Exec& ex, const double* xy, std::int64_t n, bool on_device,
                        const std::function<void()>& after_upload) {
  Prepared P;
  const auto t0 = Clock::now();
  auto raw = ex.template alloc<double>(std::size_t(2 * n));
  if (on_device)
    ex.copy(xy, 2 * n, raw.data());
  else
    ex.from_host(xy, 2 * n, raw.data());
  P.upload_ms = ms_since(t0);
  after_upload();
  double* r = raw.data();

  // Validation and the bounding box in one reduction; -0 becomes +0 (so equal points have
  // equal bits).
  auto box_dev = ex.template alloc<Bounds>(1);
  Bounds init;
  init.lo[0] = init.lo[1] = 1e308;
  init.hi[0] = init.hi[1] = -1e308;
  init.bad = 0;
  ex.transform_reduce_into(
      n,
      GG_LAMBDA(std::int64_t i)->Bounds {
        Bounds b;
        b.bad = 0;
        for (int d = 0; d < 2; ++d) {
          double v = r[2 * i + d] + 0.0;
          r[2 * i + d] = v;
          const bool ok = pred::in_exact_range(v);
          b.bad += ok ? 0 : 1;
          b.lo[d] = ok ? v : 1e308;
          b.hi[d] = ok ? v : -1e308;
        }
        return b;
      },
      init, BoundsOp{}, box_dev.data());
  Bounds box;
  ex.to_host(box_dev.data(), 1, &box);
  if (box.bad)
    throw Error(ErrorCode::InvalidInput,
                std::to_string(box.bad) +
                    " point coordinate(s) are NaN, infinite or outside the range the exact "
                    "predicates support (0 or magnitude in [1.8e-43, 1.5e54]); remove or "
                    "rescale those points");

  // Hilbert order; equal points get equal keys.
  spatial::Box sbox;
  for (int d = 0; d < 3; ++d) sbox.lo[d] = sbox.hi[d] = 0;
  for (int d = 0; d < 2; ++d) sbox.lo[d] = box.lo[d], sbox.hi[d] = box.hi[d];
  auto keys = ex.template alloc<u64>(std::size_t(n));
  auto order = ex.template alloc<std::int32_t>(std::size_t(n));
  u64* k = keys.data();
  std::int32_t* o = order.data();
  ex.for_each_index(
      n, GG_LAMBDA(std::int64_t i) {
        k[i] = spatial::hilbert_key<2>(r + 2 * i, sbox);
        o[i] = std::int32_t(i);
      });
  ex.sort_by_key(k, o, n);
  // Distinct points with equal keys (a curve cell holds several points) or duplicates: make
  // equal points adjacent by sorting on (key, x, y), least significant first (stable sorts).
  auto same_key = ex.template alloc<std::int64_t>(1);
  ex.transform_reduce_into(
      n, GG_LAMBDA(std::int64_t i)->std::int64_t { return i > 0 && k[i] == k[i - 1] ? 1 : 0; },
      std::int64_t(0), thrust::plus<std::int64_t>(), same_key.data());
  std::int64_t nsame = 0;
  ex.to_host(same_key.data(), 1, &nsame);
  if (nsame) {
    auto tmp = ex.template alloc<u64>(std::size_t(n));
    u64* t = tmp.data();
    for (int pass = 0; pass < 3; ++pass) {
      ex.for_each_index(
          n, GG_LAMBDA(std::int64_t i) {
            const std::int32_t j = o[i];
            t[i] = pass == 0   ? ordered_key(r[2 * j + 1])
                   : pass == 1 ? ordered_key(r[2 * j])
                               : spatial::hilbert_key<2>(r + 2 * j, sbox);
          });
      ex.sort_by_key(t, o, n);
    }
  }

  // Duplicates: a point equal to its predecessor in this order (runs keep input order, so the
  // first of a run has the smallest input index).
  auto kept = ex.template alloc<std::int32_t>(std::size_t(n));
  auto is_dup = GG_LAMBDA(std::int64_t i)->bool {
    if (i == 0) return false;
    const std::int32_t a = o[i], b = o[i - 1];
    return r[2 * a] == r[2 * b] && r[2 * a + 1] == r[2 * b + 1];
  };
  const std::int64_t m = ex.compact_indices(
      n, GG_LAMBDA(std::int64_t i) { return !is_dup(i); }, kept.data());
  P.m = m;
  P.duplicates = n - m;
  P.pts = ex.template alloc<double>(std::size_t(2 * m));
  P.orig = ex.template alloc<std::int32_t>(std::size_t(m));
  double* pts = P.pts.data();
  std::int32_t* orig = P.orig.data();
  const std::int32_t* kp = kept.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        const std::int32_t j = o[kp[i]];
        orig[i] = j;
        pts[2 * i] = r[2 * j];
        pts[2 * i + 1] = r[2 * j + 1];
      });
  // duplicate_of: the kept point of each run (its rank is the number of kept points up to and
  // including the position, minus one).
  if (P.duplicates) {
    auto rank = ex.template alloc<std::int32_t>(std::size_t(n));
    P.dup = ex.template alloc<std::int32_t>(std::size_t(n));
    std::int32_t* rk = rank.data();
    std::int32_t* dp = P.dup.data();
    ex.exclusive_scan_of(
        n, GG_LAMBDA(std::int64_t i)->std::int32_t { return is_dup(i) ? 0 : 1; }, rk);
    ex.for_each_index(
        n, GG_LAMBDA(std::int64_t i) { dp[o[i]] = is_dup(i) ? orig[rk[i] - 1] : -1; });
  }
  if (m < 3)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 3 distinct points (" + std::to_string(m) +
                    "): a triangulation needs at least 3 points not on one line");

  // The first triangle: lexicographic extremes a, b and the point farthest from line ab.
  auto ext = ex.template alloc<Extreme>(3);
  Extreme* e = ext.data();
  auto as_ext = GG_LAMBDA(std::int64_t i)->Extreme {
    return Extreme{pts[2 * i], pts[2 * i + 1], std::int32_t(i)};
  };
  const Extreme big{1e308, 1e308, 0}, small{-1e308, -1e308, 0};
  ex.transform_reduce_into(m, as_ext, big, MinLex{}, e);
  ex.transform_reduce_into(m, as_ext, small, MaxLex{}, e + 1);
  Extreme ab[2];
  ex.to_host(e, 2, ab);
  const double ax = ab[0].x, ay = ab[0].y, bx = ab[1].x, by = ab[1].y;
  ex.transform_reduce_into(
      m,
      GG_LAMBDA(std::int64_t i)->Extreme {
        using pred::mul_rn;  // no FMA: both executors pick the same point
        using pred::sub_rn;
        const double o2 = sub_rn(mul_rn(sub_rn(bx, ax), sub_rn(pts[2 * i + 1], ay)),
                                 mul_rn(sub_rn(by, ay), sub_rn(pts[2 * i], ax)));
        return Extreme{o2 < 0 ? -o2 : o2, 0.0, std::int32_t(i)};
      },
      Extreme{-1.0, 0.0, 0}, Farthest{}, e + 2);
  Extreme c;
  ex.to_host(e + 2, 1, &c);
  const double pa[2] = {ax, ay}, pb[2] = {bx, by};
  std::vector<double> scratch(std::size_t(pred::kIncircleScratch));
  double pc[2];
  ex.to_host(pts + 2 * std::int64_t(c.i), 2, pc);
  int oc = pred::orient2d(pa, pb, pc, scratch.data());
  if (oc == 0) {  // the rounded search found no witness: decide exactly over all points
    auto wit = ex.template alloc<std::int32_t>(std::size_t(m));
    const std::int64_t nw = ex.compact_indices(
        m,
        GG_LAMBDA(std::int64_t i) {
          double s[kOrient2dScratch];
          return pred::orient2d(pa, pb, pts + 2 * i, s) != 0;
        },
        wit.data());
    if (nw == 0)
      throw Error(ErrorCode::DegenerateInput,
                  "all " + std::to_string(m) +
                      " distinct points lie on one line: they have no 2D triangulation");
    ex.to_host(wit.data(), 1, &c.i);
    ex.to_host(pts + 2 * std::int64_t(c.i), 2, pc);
    oc = pred::orient2d(pa, pb, pc, scratch.data());
  }
  P.first[0] = ab[0].i;
  P.first[1] = ab[1].i;
  P.first[2] = c.i;
  if (oc < 0) std::swap(P.first[0], P.first[1]);
  // The kernel point: strictly inside the first triangle under the perturbation, with SoS
  // index m. The centroid almost always is; weighted means cover rounding in slivers.
  const double* v[3] = {P.first[0] == ab[0].i ? pa : pb, P.first[0] == ab[0].i ? pb : pa, pc};
  const int w[4][3] = {{1, 1, 1}, {1, 1, 2}, {1, 2, 1}, {2, 1, 1}};
  bool found = false;
  for (int t = 0; t < 4 && !found; ++t) {
    double s[2];
    for (int d = 0; d < 2; ++d)
      s[d] = (w[t][0] * v[0][d] + w[t][1] * v[1][d] + w[t][2] * v[2][d]) /
             double(w[t][0] + w[t][1] + w[t][2]);
    bool in = true;
    for (int j = 0; j < 3; ++j)
      in = in && pred::orient2d_sos(v[j], P.first[j], v[(j + 1) % 3], P.first[(j + 1) % 3], s,
                                    std::int32_t(m), scratch.data()) > 0;
    if (in) {
      P.kernel[0] = s[0];
      P.kernel[1] = s[1];
      found = true;
    }
  }
  if (!found)
    throw Error(ErrorCode::DegenerateInput,
                "the points are too close to collinear for a kernel point to be placed inside "
                "their first triangle in double precision");
  return P;
}
