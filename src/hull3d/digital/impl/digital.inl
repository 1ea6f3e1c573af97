// The digital 3D convex hull (issue 20, thesis 4.4, DigiHull3D), included inside
// gpugeom::hull3d::{cpu,cuda}_impl after hull.inl. On the m distinct points in curve order:
//
//  1a. Slices: the points are framed in a cubic grid (g voxels a side, the points in its middle
//      80 %, as the thesis scales them); on each of the grid's six faces, each pixel takes the
//      point nearest to it in 3D among the points nearest the face in their columns, by jump
//      flooding (a slice of the digital Voronoi diagram; the cells that reach a face far from
//      the points are those of points near the hull). S': the points with a pixel.
//  2.  The hull of S' (the Flip-Flop hull of this module, in place of the thesis' star
//      splaying: the same exact machinery, on the few points of S').
//  3a. The digital depth test (Lemma 4.10): the facets of C(S') drawn into six depth images
//      (R pixels a side, cubic pixels; each facet in the directions it faces, its depth raised
//      by a bound on its rounding); a point is kept where, in some direction, its depth is at
//      most one pixel behind the image's (or the image is empty there). Every point outside or
//      on C(S') is kept (the lemma: in the direction of the largest component of the normal of
//      a facet it is beyond, its depth is at most one pixel behind that facet's plane, which is
//      in front of the hull's front surface there); the others are strictly inside C(S'), hence
//      inside C(S).
//  3b. The hull of S' and the points kept (the same machinery), in curve order.
//
// Why the result is the incremental method's, triangle for triangle: the perturbation depends
// only on the points' coordinates (predicates/sos.hpp); the points of the last pass include
// every vertex of the perturbed hull of all points (a point strictly inside the exact hull is
// no such vertex), so the perturbed hulls agree, and so do the extreme-point
// tests and the second pass on the extreme points alone (impl/hull.inl). The sketch's quality
// decides only the speed.

namespace digital_hull {

GG_INLINE std::uint64_t bits_of(double d) {
#ifdef __CUDA_ARCH__
  return std::uint64_t(__double_as_longlong(d));
#else
  std::uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
#endif
}
GG_INLINE double double_of(std::uint64_t b) {
#ifdef __CUDA_ARCH__
  return __longlong_as_double(static_cast<long long>(b));
#else
  double d;
  std::memcpy(&d, &b, sizeof d);
  return d;
#endif
}
GG_INLINE std::uint32_t bits_of(float f) {
#ifdef __CUDA_ARCH__
  return __float_as_uint(f);
#else
  std::uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
#endif
}
// Doubles as unsigned keys of the same order (for atomic minima).
GG_INLINE std::uint64_t order_key(double d) {
  const std::uint64_t b = bits_of(d);
  return (b >> 63) ? ~b : (b | (std::uint64_t(1) << 63));
}
GG_INLINE double from_order_key(std::uint64_t k) {
  return double_of((k >> 63) ? (k & ~(std::uint64_t(1) << 63)) : ~k);
}
// A facet's pixel centres in a depth image: the first pixel, tiles across and down.
struct Box {
  std::int64_t x0, y0, tx, ty;
};
constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
// One pixel (the drawn depths carry their own rounding margin).
constexpr double kTau = 1.0;

// Every product below is rounded on its own (pred::mul_rn and friends: no fused multiply-add),
// so that both executors choose the same sketch points and keep the same points.
using pred::add_rn;
using pred::mul_rn;
using pred::sub_rn;

// The frame: grid coordinates G = (p - o) / h, the points in [0.1 g, 0.9 g].
struct Frame {
  double o[3];
  double h;
  GG_INLINE double at(const double* p, int d) const { return (p[d] - o[d]) / h; }
};

}  // namespace digital_hull

// Points kept by the method's sketch and depth test (inQ), or false where no sketch hull exists
// (the caller runs the incremental method). pts: the m distinct points in curve order.
inline bool digital_candidates(Exec& ex, const double* pts, std::int64_t m,
                               const mesh::Bounds<3>& box, std::int64_t grid, Hull3dStats& st,
                               std::int64_t n_input, std::int8_t* inQ) {
  using namespace digital_hull;
  auto t0 = Clock::now();
  double ext = 0;
  for (int d = 0; d < 3; ++d) ext = std::max(ext, box.hi[d] - box.lo[d]);
  if (!(ext > 0) || !std::isfinite(ext)) return false;
  std::int64_t g = grid;
  if (!g) {
    g = 64;
    while (g < 1024 && g * g < m) g *= 2;
  }
  const double h = ext / (0.8 * double(g));
  Frame F;
  F.h = h;
  for (int d = 0; d < 3; ++d) F.o[d] = 0.5 * (box.lo[d] + box.hi[d]) - 0.5 * double(g) * h;
  st.digital_grid = g;
  // 1a. The six slices.
  auto d_inS = ex.template alloc<std::int8_t>(std::size_t(m));
  std::int8_t* inS = d_inS.data();
  ex.fill(inS, m, std::int8_t(0));
  {
    const std::int64_t np = g * g;
    auto d_win = ex.template alloc<std::uint64_t>(std::size_t(np));
    auto d_a = ex.template alloc<std::int32_t>(std::size_t(np));
    auto d_b = ex.template alloc<std::int32_t>(std::size_t(np));
    std::uint64_t* win = d_win.data();
    for (int face = 0; face < 6; ++face) {
      const int a = face / 2, u = (a + 1) % 3, v = (a + 2) % 3;
      const bool high = face % 2;
      const double gg = double(g);
      auto depth = [=] GG_HD(const double* p) {
        const double z = F.at(p, a);
        return high ? gg - z : z;
      };
      auto cell = [=] GG_HD(double c) {
        const std::int64_t i = std::int64_t(floor(c));
        return i < 0 ? std::int64_t(0) : (i >= g ? g - 1 : i);
      };
      ex.fill(win, np, kEmpty);
      ex.for_each_index(
          m, GG_LAMBDA(std::int64_t i) {
            const double* p = pts + 3 * i;
            const std::int64_t q = cell(F.at(p, v)) * g + cell(F.at(p, u));
            const std::uint32_t bits = bits_of(float(depth(p)));  // (non-negative: ordered)
            atomic_min(&win[q], std::uint64_t(bits) << 32 | std::uint64_t(i));
          });
      std::int32_t* A = d_a.data();
      ex.for_each_index(
          np, GG_LAMBDA(std::int64_t q) {
            A[q] = win[q] == kEmpty ? -1 : std::int32_t(win[q] & 0xffffffffu);
          });
      // Jump flooding, by the 3D distance from the pixel's centre on the face (the steps
      // g/2, ..., 1, then 1 again).
      std::int64_t k = g / 2;
      bool extra = false;
      while (k >= 1) {
        const std::int32_t* from = d_a.data();
        std::int32_t* to = d_b.data();
        const std::int64_t step = k;
        ex.for_each_index(
            np, GG_LAMBDA(std::int64_t q) {
              const std::int64_t x = q % g, y = q / g;
              const double cx = double(x) + 0.5, cy = double(y) + 0.5;
              std::int32_t best = -1;
              double bd = 0;
              for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                  const std::int64_t qx = x + dx * step, qy = y + dy * step;
                  if (qx < 0 || qy < 0 || qx >= g || qy >= g) continue;
                  const std::int32_t s = from[qy * g + qx];
                  if (s < 0) continue;
                  const double* p = pts + 3 * std::int64_t(s);
                  const double eu = F.at(p, u) - cx, ev = F.at(p, v) - cy, ez = depth(p);
                  const double d2 = add_rn(add_rn(mul_rn(eu, eu), mul_rn(ev, ev)), mul_rn(ez, ez));
                  if (best < 0 || d2 < bd || (d2 == bd && s < best)) best = s, bd = d2;
                }
              to[q] = best;
            });
        std::swap(d_a, d_b);
        if (k == 1 && !extra)
          extra = true;
        else
          k /= 2;
      }
      const std::int32_t* own = d_a.data();
      ex.for_each_index(
          np, GG_LAMBDA(std::int64_t q) {
            if (own[q] >= 0) inS[own[q]] = 1;
          });
    }
  }
  auto d_spos = ex.template alloc<std::int32_t>(std::size_t(m));
  const std::int64_t ns = ex.compact_indices(
      m, GG_LAMBDA(std::int64_t i) { return inS[i] != 0; }, d_spos.data());
  st.sketch_points = ns;
  ex.sync();
  st.phase_ms.emplace_back("digital_slices", ms_since(t0));
  if (ns < 4) return false;
  // 2. The sketch's hull (its own counters and phases are not the result's).
  t0 = Clock::now();
  Result S1;
  {
    auto sub = ex.template alloc<double>(std::size_t(3 * ns));
    double* sp = sub.data();
    const std::int32_t* spos = d_spos.data();
    ex.for_each_index(
        3 * ns, GG_LAMBDA(std::int64_t i) { sp[i] = pts[3 * std::int64_t(spos[i / 3]) + i % 3]; });
    Hull3dStats inner;
    try {
      S1 = distinct_hull(ex, sp, ns, inner, n_input);
    } catch (const Error& e) {
      if (e.code() != ErrorCode::DegenerateInput) throw;
      return false;  // (S' flat: no sketch)
    }
    std::int32_t* t = S1.facets.simplices.data();
    ex.for_each_index(
        3 * S1.facets.count, GG_LAMBDA(std::int64_t i) { t[i] = spos[t[i]]; });
  }
  const std::int64_t nf = S1.facets.count;
  st.sketch_facets = nf;
  ex.sync();
  st.phase_ms.emplace_back("digital_sketch_hull", ms_since(t0));
  // 3a. The depth images: direction dir looks along axis a = dir / 2, towards +a (dir even:
  // depth z = X_a, front = least) or -a (depth z = -X_a); X = (p - o) / hr, hr = g h / R.
  t0 = Clock::now();
  const std::int64_t R = std::max<std::int64_t>(16, g / 2);
  st.digital_render = R;
  const double hr = double(g) * h / double(R);
  Frame X;
  X.h = hr;
  for (int d = 0; d < 3; ++d) X.o[d] = F.o[d];
  const std::int64_t npix = R * R;
  auto d_img = ex.template alloc<std::uint64_t>(std::size_t(6 * npix));
  std::uint64_t* img = d_img.data();
  ex.fill(img, 6 * npix, kEmpty);
  {
    // Work: (facet, direction, tile of 16 x 16 pixel centres in the facet's box), from a scan
    // of the tile counts; a facet is drawn in the directions it faces (the front surface: those
    // facets' projections tile the hull's).
    constexpr std::int64_t kTile = 16;
    const std::int32_t* T = S1.facets.simplices.data();
    auto box_of = [=] GG_HD(std::int64_t w, Box & b) -> bool {
      const std::int64_t f = w / 6;
      const int dir = int(w % 6), a = dir / 2, u = (a + 1) % 3, v = (a + 2) % 3;
      const double sg = dir % 2 ? -1.0 : 1.0;
      const double *P0 = pts + 3 * std::int64_t(T[3 * f]),
                   *P1 = pts + 3 * std::int64_t(T[3 * f + 1]),
                   *P2 = pts + 3 * std::int64_t(T[3 * f + 2]);
      double e1[3], e2[3];
      for (int d = 0; d < 3; ++d)
        e1[d] = X.at(P1, d) - X.at(P0, d), e2[d] = X.at(P2, d) - X.at(P0, d);
      const double n[3] = {sub_rn(mul_rn(e1[1], e2[2]), mul_rn(e1[2], e2[1])),
                           sub_rn(mul_rn(e1[2], e2[0]), mul_rn(e1[0], e2[2])),
                           sub_rn(mul_rn(e1[0], e2[1]), mul_rn(e1[1], e2[0]))};
      if (!(-sg * n[a] > 0)) return false;  // (facing away, or seen edge on)
      double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
      const double* Ps[3] = {P0, P1, P2};
      for (const double* P : Ps) {
        const double c[2] = {X.at(P, u), X.at(P, v)};
        for (int j = 0; j < 2; ++j) lo[j] = fmin(lo[j], c[j]), hi[j] = fmax(hi[j], c[j]);
      }
      // pixel centres i + 0.5 in [lo, hi]
      const std::int64_t x0 = std::int64_t(ceil(lo[0] - 0.5)),
                         x1 = std::int64_t(floor(hi[0] - 0.5));
      const std::int64_t y0 = std::int64_t(ceil(lo[1] - 0.5)),
                         y1 = std::int64_t(floor(hi[1] - 0.5));
      const std::int64_t cx0 = x0 < 0 ? 0 : x0, cy0 = y0 < 0 ? 0 : y0;
      const std::int64_t cx1 = x1 >= R ? R - 1 : x1, cy1 = y1 >= R ? R - 1 : y1;
      if (cx1 < cx0 || cy1 < cy0) return false;
      b.x0 = cx0, b.y0 = cy0;
      b.tx = (cx1 - cx0) / kTile + 1, b.ty = (cy1 - cy0) / kTile + 1;
      return true;
    };
    const std::int64_t nw = 6 * nf;
    auto d_off = ex.template alloc<std::int64_t>(std::size_t(nw + 1));
    std::int64_t* off = d_off.data();
    ex.exclusive_scan_of(
        nw + 1,
        GG_LAMBDA(std::int64_t w)->std::int64_t {
          Box b;
          return w < nw && box_of(w, b) ? b.tx * b.ty : 0;
        },
        off);
    std::int64_t ntiles = 0;
    ex.to_host(off + nw, 1, &ntiles);
    auto d_tw = ex.template alloc<std::int32_t>(std::size_t(ntiles));
    std::int32_t* tw = d_tw.data();
    ex.for_each_index(
        nw, GG_LAMBDA(std::int64_t w) {
          for (std::int64_t j = off[w]; j < off[w + 1]; ++j) tw[j] = std::int32_t(w);
        });
    ex.for_each_index(
        ntiles, GG_LAMBDA(std::int64_t j) {
          const std::int64_t w = tw[j];
          Box b;
          if (!box_of(w, b)) return;
          const std::int64_t f = w / 6, k = j - off[w];
          const int dir = int(w % 6), a = dir / 2, u = (a + 1) % 3, v = (a + 2) % 3;
          const double sg = dir % 2 ? -1.0 : 1.0;
          const double* P[3] = {pts + 3 * std::int64_t(T[3 * f]),
                                pts + 3 * std::int64_t(T[3 * f + 1]),
                                pts + 3 * std::int64_t(T[3 * f + 2])};
          double pu[3], pv[3], pa[3];
          for (int c = 0; c < 3; ++c)
            pu[c] = X.at(P[c], u), pv[c] = X.at(P[c], v), pa[c] = X.at(P[c], a);
          // The plane: X_a = pa0 + alpha (U - pu0) + beta (V - pv0).
          const double du1 = pu[1] - pu[0], dv1 = pv[1] - pv[0], da1 = pa[1] - pa[0];
          const double du2 = pu[2] - pu[0], dv2 = pv[2] - pv[0], da2 = pa[2] - pa[0];
          const double det = sub_rn(mul_rn(du1, dv2), mul_rn(du2, dv1));
          if (det == 0) return;
          const double alpha = sub_rn(mul_rn(da1, dv2), mul_rn(da2, dv1)) / det,
                       beta = sub_rn(mul_rn(du1, da2), mul_rn(du2, da1)) / det;
          // The drawn depth raised by a bound on its rounding and on the coverage test's (a
          // pixel centre a rounding outside the facet): depths may only err towards the back,
          // which keeps more points, never fewer.
          const double margin =
              mul_rn(1e-9 * double(R), add_rn(add_rn(1.0, fabs(alpha)), fabs(beta)));
          const std::int64_t tx0 = b.x0 + (k % b.tx) * kTile, ty0 = b.y0 + (k / b.tx) * kTile;
          std::uint64_t* im = img + dir * npix;
          for (std::int64_t y = ty0; y < ty0 + kTile && y < R; ++y)
            for (std::int64_t x = tx0; x < tx0 + kTile && x < R; ++x) {
              const double cu = double(x) + 0.5, cv = double(y) + 0.5;
              // inside or on the projected triangle (either orientation)
              double e[3];
              for (int c = 0; c < 3; ++c) {
                const int c2 = (c + 1) % 3;
                e[c] =
                    sub_rn(mul_rn(pu[c2] - pu[c], cv - pv[c]), mul_rn(pv[c2] - pv[c], cu - pu[c]));
              }
              const bool in =
                  (e[0] >= 0 && e[1] >= 0 && e[2] >= 0) || (e[0] <= 0 && e[1] <= 0 && e[2] <= 0);
              if (!in) continue;
              const double z =
                  sg * add_rn(add_rn(pa[0], mul_rn(alpha, cu - pu[0])), mul_rn(beta, cv - pv[0]));
              atomic_min(&im[y * R + x], order_key(z + margin));
            }
        });
  }
  // Each point: kept where some image is empty at its pixel or at most kTau in front of it.
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t i) {
        if (inS[i]) {
          inQ[i] = 1;
          return;
        }
        const double* p = pts + 3 * i;
        bool keep = false;
        for (int dir = 0; dir < 6 && !keep; ++dir) {
          const int a = dir / 2, u = (a + 1) % 3, v = (a + 2) % 3;
          const double sg = dir % 2 ? -1.0 : 1.0;
          std::int64_t x = std::int64_t(floor(X.at(p, u))), y = std::int64_t(floor(X.at(p, v)));
          x = x < 0 ? 0 : (x >= R ? R - 1 : x);
          y = y < 0 ? 0 : (y >= R ? R - 1 : y);
          const std::uint64_t e = img[dir * npix + y * R + x];
          keep = e == kEmpty || sg * X.at(p, a) - from_order_key(e) <= kTau;
        }
        inQ[i] = keep;
      });
  ex.sync();
  st.phase_ms.emplace_back("digital_depth_test", ms_since(t0));
  return true;
}

// The hull of m distinct points in curve order by the digital method (its result in their
// indices, as distinct_hull's).
inline Result digital_distinct_hull(Exec& ex, const double* pts, std::int64_t m,
                                    const mesh::Bounds<3>& box, std::int64_t grid, Hull3dStats& st,
                                    std::int64_t n_input) {
  auto d_inQ = ex.template alloc<std::int8_t>(std::size_t(m));
  std::int8_t* inQ = d_inQ.data();
  if (!digital_candidates(ex, pts, m, box, grid, st, n_input, inQ)) {
    st.digital_fallback = 1;
    st.hull_input = m;
    return distinct_hull(ex, pts, m, st, n_input);
  }
  st.digital_fallback = 0;
  auto d_q = ex.template alloc<std::int32_t>(std::size_t(m));
  const std::int32_t* qpos = d_q.data();
  const std::int64_t nq = ex.compact_indices(
      m, GG_LAMBDA(std::int64_t i) { return inQ[i] != 0; }, d_q.data());
  st.depth_kept = nq - st.sketch_points;
  st.hull_input = nq;
  auto sub = ex.template alloc<double>(std::size_t(3 * nq));
  double* sp = sub.data();
  ex.for_each_index(
      3 * nq, GG_LAMBDA(std::int64_t i) { sp[i] = pts[3 * std::int64_t(qpos[i / 3]) + i % 3]; });
  Result R = distinct_hull(ex, sp, nq, st, n_input);
  std::int32_t* t = R.facets.simplices.data();
  ex.for_each_index(
      3 * R.facets.count, GG_LAMBDA(std::int64_t i) { t[i] = qpos[t[i]]; });
  std::int32_t* vx = R.vertices.data();
  ex.for_each_index(
      R.num_vertices, GG_LAMBDA(std::int64_t j) { vx[j] = qpos[vx[j]]; });
  return R;
}
