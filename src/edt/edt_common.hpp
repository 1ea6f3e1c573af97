// Shared device/host pieces of the distance transform: how a site is packed into 32 bits, and
// the exact comparisons every pass makes.
//
// A site is stored as its coordinates packed into one uint32 so that comparing packed values
// compares sites lexicographically by (z, y, x): the raster order. Ties between equally near
// sites always go to the smaller packed value, in every pass, which makes the result
// independent of the order of the passes (whole volume, or slice by slice) and equal to "the
// nearest site with the smallest raster index". Two packings keep that order:
//   Layout        bit fields (x in the low bits, then y, then z): two instructions to decode,
//                 where the extents' bit widths sum to 32 or less (1024^3, 65536 x 65536);
//   LinearLayout  the voxel's raster index x + nx (y + ny z): a multiply-high division to
//                 decode, for every grid of fewer than 2^32 - 1 voxels (1600^3, 1625^3).
// The slice-by-slice mode keeps them where they fit, and past 2^32 - 1 voxels packs a site by
// its column and looks its z up (ColumnLayout), so volumes of any voxel count go by slices.
// Ties then compare (z, packed) through Layout::before.
// The passes (impl/*.inl) are compiled once for each (see edt_cuda.cu / edt_cpu.cpp).
//
// Distances are sum_k w_k * d_k^2 with w_k = sampling_k^2 (1 when isotropic). Every decision is
// the sign of sum_k w_k * I_k for integers I_k: exact in int64 when isotropic, otherwise by a
// floating filter and an exact expansion fallback (w_k is split into two doubles exactly).
#pragma once
#include <cstdint>

#include "base/hd.hpp"
#include "predicates/expansion.hpp"

namespace gpugeom::edt {

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

// Choices that change the speed of the passes, never their result (EdtOptions has them for
// benchmarks and tests): PBA band counts per axis (0: by size), the windowed passes' reach
// (-1: by site density, 0: never), the GPU's shared-memory tiles (-1: where they pay, 0: never,
// 1: wherever they fit), how many voxels of slices are computed together.
struct Tuning {
  std::int64_t bands[3] = {0, 0, 0};
  std::int64_t window_reach = -1;
  int tiles = -1;
  std::int64_t slice_block = 0;  // slice-by-slice mode: voxels per block of slices (0: 2^24)
};

// n / d for every 32-bit n, by one multiply-high (Granlund & Montgomery, "Division by invariant
// integers using multiplication", 1994, fig. 4.1): m and the shifts are set once per divisor.
struct Divider {
  std::uint32_t m = 1;
  int s1 = 0, s2 = 0;
  static Divider of(std::uint32_t d) {  // d >= 1
    int l = 0;
    while ((std::uint64_t(1) << l) < d) ++l;
    Divider v;
    v.m = std::uint32_t(((std::uint64_t(1) << 32) * ((std::uint64_t(1) << l) - d)) / d + 1);
    v.s1 = l < 1 ? l : 1;
    v.s2 = l > 1 ? l - 1 : 0;
    return v;
  }
  GG_INLINE std::uint32_t div(std::uint32_t n) const {
#if defined(__CUDA_ARCH__)
    const std::uint32_t t = __umulhi(m, n);
#else
    const std::uint32_t t = std::uint32_t((std::uint64_t(m) * n) >> 32);
#endif
    return (t + ((n - t) >> s1)) >> s2;
  }
};

// The grid's shape and the bit-field packing (the default; see LinearLayout).
struct Layout {
  static constexpr int kAxes = 3;
  int nd = 2;
  std::int64_t n[3] = {1, 1, 1};  // extent along x, y, z (z = 1 in 2D)
  int shift[3] = {0, 0, 0};       // bit position of x, y, z in a packed site
  std::uint32_t mask[3] = {0, 0, 0};
  // Sites are packed as raster indices (LinearLayout), for grids whose bit fields need more
  // than 32 bits. (The divisors that decode them live in LinearLayout only: the bit-field
  // kernels keep their parameter block as it was.)
  bool linear = false;
  // Slice-by-slice mode only: sites packed by column (ColumnLayout), for volumes of 2^32 - 1
  // voxels or more.
  bool columns = false;
  std::int64_t count() const { return n[0] * n[1] * n[2]; }
  GG_INLINE std::int64_t stride(int a) const { return a == 0 ? 1 : (a == 1 ? n[0] : n[0] * n[1]); }
  GG_INLINE std::uint32_t pack(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return std::uint32_t(x) << shift[0] | std::uint32_t(y) << shift[1] |
           std::uint32_t(z) << shift[2];
  }
  GG_INLINE std::int64_t coord(std::uint32_t s, int a) const { return (s >> shift[a]) & mask[a]; }
  GG_INLINE std::int64_t voxel_of(std::uint32_t s) const {
    return coord(s, 0) + n[0] * (coord(s, 1) + n[1] * coord(s, 2));
  }
  // The site at voxel v (raster index of a whole grid).
  GG_INLINE std::uint32_t pack_voxel(std::int64_t v) const {
    return pack(v % n[0], (v / n[0]) % n[1], v / (n[0] * n[1]));
  }
  // The z of plane k of the block held: k itself for a whole grid (the slice layouts hold
  // planes of chosen z).
  GG_INLINE std::int64_t plane_z(std::int64_t k) const { return k; }
  // Is site q first in raster order before site p? (Packed order is raster order here.)
  GG_INLINE bool before(std::uint32_t q, std::uint32_t p) const { return q < p; }
  // Either packing, chosen at run time (host-side packing of site lists).
  std::uint32_t pack_any(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return linear ? std::uint32_t(x + n[0] * (y + n[1] * z)) : pack(x, y, z);
  }
};

// The same shape with sites packed as raster indices x + nx (y + ny z) (absolute z: a slice's
// layout keeps the volume's nx and ny). Packed order is raster order, as with the bit fields.
struct LinearLayout : Layout {
  Divider by_x, by_xy;  // by nx and by nx * ny
  LinearLayout() = default;
  LinearLayout(const Layout& L)  // NOLINT: the passes convert implicitly (host side)
      : Layout(L),
        by_x(Divider::of(std::uint32_t(L.n[0]))),
        by_xy(Divider::of(std::uint32_t(L.n[0] * L.n[1]))) {}
  GG_INLINE std::uint32_t pack(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return std::uint32_t(x) +
           std::uint32_t(n[0]) * (std::uint32_t(y) + std::uint32_t(n[1]) * std::uint32_t(z));
  }
  GG_INLINE std::int64_t coord(std::uint32_t s, int a) const {
    if (a == 0) return s - std::uint32_t(n[0]) * by_x.div(s);
    if (a == 1) return by_x.div(s) - std::uint32_t(n[1]) * by_xy.div(s);
    return by_xy.div(s);
  }
  GG_INLINE std::int64_t voxel_of(std::uint32_t s) const { return s; }
  GG_INLINE std::uint32_t pack_voxel(std::int64_t v) const { return std::uint32_t(v); }
};

// The slice-by-slice mode computes a block of slices at a time, as the planes of a grid of
// n[2] planes whose plane k is the volume's slice zs[k]; only the x and y passes run, and a
// plane's candidates are the nearest sites along z of its columns (x, y). Where the volume's
// own packing holds its sites (fewer than 2^32 - 1 voxels), they keep it (absolute z).
template <class Base>
struct SlicePlanes : Base {
  static constexpr bool kColumns = false;
  const std::uint16_t* zs = nullptr;  // executor memory, n[2] entries
  SlicePlanes() = default;
  SlicePlanes(const Base& L, const std::uint16_t* z, const std::uint16_t*) : Base(L), zs(z) {}
  GG_INLINE std::int64_t plane_z(std::int64_t k) const { return zs[k]; }
  // The candidate of column (x, y) of plane k: the site at z.
  GG_INLINE std::uint32_t candidate(std::int64_t x, std::int64_t y, std::int64_t,
                                    std::int64_t z) const {
    return Base::pack(x, y, z);
  }
};

// Sites packed by column, for volumes of any voxel count: a plane's candidates are one site per
// column at most, and every site the x and y passes of a plane meet is one of its candidates.
// So a site is packed as (x, y, plane k) in bit fields (x low; they fit 32 bits: a slice holds
// fewer than 2^31 - 1 voxels, and the block takes as many planes as fit the rest), and its z is
// looked up in the block's table of the candidates' z (zcol[k nx ny + x + nx y]). Packed order
// is not raster order: ties compare z first (before(); the two sites a pass compares always lie
// in one plane).
struct ColumnLayout : Layout {
  static constexpr bool kColumns = true;
  const std::uint16_t* zs = nullptr;    // executor memory, n[2] entries
  const std::uint16_t* zcol = nullptr;  // executor memory, n[0] n[1] n[2] entries
  ColumnLayout() = default;
  // The plane field takes the bits of n[2] planes, above x and y.
  ColumnLayout(const Layout& L, const std::uint16_t* z, const std::uint16_t* zc)
      : Layout(L), zs(z), zcol(zc) {
    int b = 0;
    while ((std::int64_t(1) << b) < n[2]) ++b;
    mask[2] = b ? std::uint32_t((std::uint64_t(1) << b) - 1) : 0;
  }
  GG_INLINE std::int64_t plane_z(std::int64_t k) const { return zs[k]; }
  // (A slice whose x and y take all 32 bits has blocks of one plane and no plane field: no
  // shift by 32.)
  GG_INLINE std::uint32_t candidate(std::int64_t x, std::int64_t y, std::int64_t k,
                                    std::int64_t) const {
    return std::uint32_t(x) << shift[0] | std::uint32_t(y) << shift[1] |
           (mask[2] ? std::uint32_t(k) << shift[2] : 0u);
  }
  GG_INLINE std::int64_t plane(std::uint32_t s) const {
    return mask[2] ? (s >> shift[2]) & mask[2] : 0;
  }
  // The candidate's slot in the block: k nx ny + x + nx y.
  GG_INLINE std::int64_t slot(std::uint32_t s) const {
    return (plane(s) * n[1] + Layout::coord(s, 1)) * n[0] + Layout::coord(s, 0);
  }
  // (kNone has no slot: its z reads as 0, and no decision uses it.)
  GG_INLINE std::int64_t coord(std::uint32_t s, int a) const {
    if (a < 2) return Layout::coord(s, a);
    return s == kNone ? 0 : zcol[slot(s)];
  }
  GG_INLINE bool before(std::uint32_t q, std::uint32_t p) const {
    const std::int64_t zq = coord(q, 2), zp = coord(p, 2);
    return zq < zp || (zq == zp && q < p);
  }
};

// A site of the slice-by-slice mode: its column x + nx y above its z (z < 2^16: extents are at
// most 65536), so sorted keys list each column's sites in z order.
constexpr int kColumnZBits = 16;
constexpr std::uint64_t kColumnZMask = (std::uint64_t(1) << kColumnZBits) - 1;
GG_INLINE std::uint64_t column_key(std::int64_t column, std::int64_t z) {
  return std::uint64_t(column) << kColumnZBits | std::uint64_t(z);
}

// The most axes a grid may have (N-D transforms, nd_layout.hpp); 2D and 3D grids take the
// three-axis layouts above.
constexpr int kMaxAxes = 8;

// Per-axis weights w_k = sampling_k^2 of D axes (internal order: axis 0 is C's last).
template <int D>
struct MetricT {
  bool iso = true;
  double wh[D], wl[D];  // w_k = wh + wl exactly (sampling_k^2)
  double w[D];          // rounded, for filters and output distances
  GG_HD MetricT() {
    for (int k = 0; k < D; ++k) wh[k] = 1, wl[k] = 0, w[k] = 1;
  }
};
using Metric = MetricT<3>;
using NdMetric = MetricT<kMaxAxes>;

// sign(sum_k w_k I_k) over the first K axes, exactly. The I_k are integers below 2^51 held in
// T: int64_t, or double, where they are exact too (every product the passes form is below
// 2^51: make_layout and make_nd_layout bound the extents so). Doubles are faster than 64-bit
// integer multiplies on the GPU, integers faster on the CPU; each executor picks its own
// (pba.inl).
template <int D, class T>
GG_INLINE int weighted_sign(const MetricT<D>& m, const T (&I)[D], int K = D) {
  if (m.iso) {
    T s = 0;
    for (int k = 0; k < K; ++k) s += I[k];  // exact: below 2^53
    return (s > 0) - (s < 0);
  }
  double approx = 0, mag = 0;
  for (int k = 0; k < K; ++k) {
    const double t = m.w[k] * double(I[k]);
    approx += t;
    mag += t < 0 ? -t : t;
  }
  const double bound = (4 + 2 * K) * 1.1102230246251565e-16 * mag;
  if (approx > bound) return 1;
  if (-approx > bound) return -1;
  double acc[4 * D], tmp[4 * D], part[4];
  int len = 0;
  for (int k = 0; k < K; ++k) {
    const double h[2] = {m.wl[k], m.wh[k]};
    const int hl = m.wl[k] != 0 ? 2 : 1;
    const int pl = exact::scale_expansion(hl, m.wl[k] != 0 ? h : h + 1, double(I[k]), part);
    const int nl = exact::expansion_sum(len, acc, pl, part, tmp);
    for (int i = 0; i < nl; ++i) acc[i] = tmp[i];
    len = nl;
  }
  return exact::expansion_sign(len, acc);
}

// Does site q beat site p at voxel position (v[0], v[1], v[2])? Nearer, or as near and first
// in raster order.
template <class T, class Lay, class S>
GG_INLINE bool beats(const Lay& L, const MetricT<Lay::kAxes>& m, S q, S p, const std::int64_t v[]) {
  T I[Lay::kAxes] = {};
  for (int k = 0; k < L.nd; ++k) {
    const T dq = T(L.coord(q, k) - v[k]), dp = T(L.coord(p, k) - v[k]);
    I[k] = dq * dq - dp * dp;
  }
  const int s = weighted_sign(m, I, L.nd);
  return s < 0 || (s == 0 && L.before(q, p));
}

// Along axis a of a line whose other coordinates are v[], can site b be dropped given its
// neighbours a_ (before) and c (after) in the candidate list? Yes when the A|B bisector lies at
// or beyond the B|C bisector, unless the three tie exactly at a grid point that B wins.
template <class T, class Lay, class S>
GG_INLINE bool dominated(const Lay& L, const MetricT<Lay::kAxes>& m, int a, S A, S B, S C,
                         const std::int64_t v[]) {
  const T ta = T(L.coord(A, a)), tb = T(L.coord(B, a)), tc = T(L.coord(C, a));
  T I[Lay::kAxes] = {};
  for (int p = 0; p < L.nd; ++p) {
    if (p == a) {
      I[p] = (tc - tb) * (tb - ta) * (ta - tc);
    } else {
      const T da = T(L.coord(A, p) - v[p]), db = T(L.coord(B, p) - v[p]),
              dc = T(L.coord(C, p) - v[p]);
      I[p] = (tc - tb) * (db * db - da * da) - (tb - ta) * (dc * dc - db * db);
    }
  }
  const int s = weighted_sign(m, I, L.nd);
  if (s != 0) return s > 0;
  // u == v: B's cell on this line is one point. Keep B only if that point is a grid point
  // where B is first in raster order among the three.
  if (!(L.before(B, A) && L.before(B, C))) return true;
  double num = m.w[a] * double(tb * tb - ta * ta);
  for (int p = 0; p < L.nd; ++p) {
    if (p == a) continue;
    const double da = double(L.coord(A, p) - v[p]), db = double(L.coord(B, p) - v[p]);
    num += m.w[p] * (db * db - da * da);
  }
  const double u = num / (2 * m.w[a] * double(tb - ta));
  const std::int64_t t0 = std::int64_t(u < 0 ? u - 0.5 : u + 0.5);
  std::int64_t w[Lay::kAxes];
  for (int k = 0; k < L.nd; ++k) w[k] = v[k];
  w[a] = t0;
  T J[Lay::kAxes] = {};
  for (int k = 0; k < L.nd; ++k) {
    const T db = T(L.coord(B, k) - w[k]), da = T(L.coord(A, k) - w[k]);
    J[k] = db * db - da * da;
  }
  return weighted_sign(m, J, L.nd) != 0;  // not a grid-point tie: B colours nothing
}

// A candidate as the line passes compare it: its site, its position t along the pass axis and,
// when the metric is isotropic, f = its squared distance to the line (the other axes). With
// those two numbers the isotropic tests are a few exact double operations (values < 2^51);
// anisotropic metrics take the general exact tests above.
template <class S>
struct CandOf {
  S s;
  double t, f;
};

// Iso: the metric is isotropic (known at compile time, so the isotropic kernels carry none of
// the general tests' registers except the exact-tie fallback). Num: the exact tests' number
// type (each executor's own, pba.inl).
template <bool Iso, class Num, class Lay, class S>
GG_INLINE bool cand_dominated(const Lay& L, const MetricT<Lay::kAxes>& M, int a, const CandOf<S>& A,
                              const CandOf<S>& B, const CandOf<S>& C, const std::int64_t v[]) {
  if constexpr (Iso) {
    const double e = (C.t - B.t) * (B.f - A.f) - (B.t - A.t) * (C.f - B.f) +
                     (C.t - B.t) * (B.t - A.t) * (A.t - C.t);
    if (e != 0) return e > 0;
  }
  return dominated<Num>(L, M, a, A.s, B.s, C.s, v);  // anisotropic, or an exact tie
}

// Does Q beat P at position t of the line through v along axis a?
template <bool Iso, class Num, class Lay, class S>
GG_INLINE bool cand_beats(const Lay& L, const MetricT<Lay::kAxes>& M, int a, const CandOf<S>& Q,
                          const CandOf<S>& P, std::int64_t t, const std::int64_t v[]) {
  if constexpr (Iso) {
    const double dq = Q.t - double(t), dp = P.t - double(t);
    const double e = (Q.f + dq * dq) - (P.f + dp * dp);
    return e < 0 || (e == 0 && L.before(Q.s, P.s));
  } else {
    std::int64_t w[Lay::kAxes];
    for (int k = 0; k < L.nd; ++k) w[k] = v[k];
    w[a] = t;
    return beats<Num>(L, M, Q.s, P.s, w);
  }
}

}  // namespace gpugeom::edt
