// Input preparation on the executor: validation, Hilbert order, duplicates, the first triangle
// (thesis 6.4). Included inside gpugeom::del2d::{cpu,cuda}_impl after geometry.inl.

using u64 = std::uint64_t;

using Cand2 = mesh::Cand<2>;  // (the reductions come from mesh/prepare.hpp)

struct Prepared {
  typename Exec::template Buffer<double> pts;         // 2 per distinct point, curve order
  typename Exec::template Buffer<std::int32_t> orig;  // input index of each
  typename Exec::template Buffer<std::int32_t> dup;   // n entries (duplicate_of), when any
  std::int64_t m = 0;
  std::int64_t duplicates = 0;
  std::int32_t first[3] = {0, 0, 0};  // the first triangle, counter-clockwise
  double kernel[2] = {0, 0};
  double upload_ms = 0;
  mesh::Bounds<2> box{};  // the points' bounding box
};

// The kernel point s: strictly inside the counter-clockwise triangle (v[0], v[1], v[2]) of
// point indices id under the perturbation, with index m (the infinity vertex's). The
// centroid almost always is; weighted means cover rounding in slivers. False if none is.
inline bool kernel_point(const double* const v[3], const std::int32_t id[3], std::int32_t m,
                         double s[2]) {
  std::vector<double> scratch(std::size_t(pred::kOrient2dScratch));
  const int w[4][3] = {{1, 1, 1}, {1, 1, 2}, {1, 2, 1}, {2, 1, 1}};
  for (int t = 0; t < 4; ++t) {
    double c[2];
    for (int d = 0; d < 2; ++d)
      c[d] = (w[t][0] * v[0][d] + w[t][1] * v[1][d] + w[t][2] * v[2][d]) /
             double(w[t][0] + w[t][1] + w[t][2]);
    bool in = true;
    for (int j = 0; j < 3; ++j)
      in = in && pred::orient2d_sos(v[j], id[j], v[(j + 1) % 3], id[(j + 1) % 3], c, m,
                                    scratch.data()) > 0;
    if (in) {
      s[0] = c[0], s[1] = c[1];
      return true;
    }
  }
  return false;
}

// xy: on the host, or on the executor when on_device.
inline Prepared prepare(Exec& ex, const double* xy, std::int64_t n, bool on_device) {
  Prepared P;
  const auto t0 = Clock::now();
  // Points already on the executor are read where they are (no copy: 16 B a point less in
  // the preparation), and so are host points on the CPU executor (whose memory they are: the
  // copy cost 5-8 ms of 10^6 points on 2 threads, its fresh pages included); host points are
  // uploaded to the GPU.
  typename Exec::template Buffer<double> raw;
  const double* r = xy;
  if (!on_device && Exec::backend != Backend::Cpu) {
    raw = ex.template alloc<double>(std::size_t(2 * n));
    ex.from_host(xy, 2 * n, raw.data());
    r = raw.data();
  }
  P.upload_ms = ms_since(t0);

  // Validation and the bounding box in one reduction. (-0 and +0 are one value in what
  // follows: sort_distinct's keys and comparisons, and its copies of the points have +0.)
  const mesh::Bounds<2> box = P.box = mesh::bounds<2>(ex, r, n);
  if (box.bad)
    throw Error(ErrorCode::InvalidInput,
                std::to_string(box.bad) +
                    " point coordinate(s) are NaN, infinite or outside the range the exact "
                    "predicates support (0 or magnitude in [1.8e-43, 1.5e54]); remove or "
                    "rescale those points");
  // Hilbert order, duplicates merged.
  mesh::SortedPoints<Exec> S = mesh::sort_distinct<2>(ex, r, n, box);
  const std::int64_t m = P.m = S.m;
  P.duplicates = S.duplicates;
  P.pts = std::move(S.pts);
  P.orig = std::move(S.orig);
  P.dup = std::move(S.dup);
  double* pts = P.pts.data();
  if (m < 3)
    throw Error(ErrorCode::DegenerateInput,
                "fewer than 3 distinct points (" + std::to_string(m) +
                    "): a triangulation needs at least 3 points not on one line");

  // The first triangle: lexicographic extremes a, b and the point farthest from line ab.
  const mesh::Extremes<2> ab = mesh::extremes<2>(ex, pts, m);
  const double ax = ab.lo.x[0], ay = ab.lo.x[1], bx = ab.hi.x[0], by = ab.hi.x[1];
  Cand2 c = mesh::reduce_cand<2>(
      ex, m,
      GG_LAMBDA(std::int64_t i)->Cand2 {
        using pred::mul_rn;  // no FMA: both executors pick the same point
        using pred::sub_rn;
        const double o2 = sub_rn(mul_rn(sub_rn(bx, ax), sub_rn(pts[2 * i + 1], ay)),
                                 mul_rn(sub_rn(by, ay), sub_rn(pts[2 * i], ax)));
        return mesh::cand_of<2>(pts, i, o2 < 0 ? -o2 : o2);
      },
      mesh::Farthest<2>{});
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
  P.first[0] = ab.lo.i;
  P.first[1] = ab.hi.i;
  P.first[2] = c.i;
  if (oc < 0) std::swap(P.first[0], P.first[1]);
  const double* v[3] = {P.first[0] == ab.lo.i ? pa : pb, P.first[0] == ab.lo.i ? pb : pa, pc};
  if (!kernel_point(v, P.first, std::int32_t(m), P.kernel))
    throw Error(ErrorCode::DegenerateInput,
                "the points are too close to collinear for a kernel point to be placed inside "
                "their first triangle in double precision");
  return P;
}
