// Tier 2 of the adaptive predicates, for whole-number coordinates (integer grids, pixel and
// voxel indices, quantised scans): the determinant in 64- and 128-bit integers, exact when the
// magnitudes stay within the limits below. Degenerate input of this kind sends most tests past
// the filter, and this costs a small fraction of the expansion arithmetic. Each function
// returns false (sign untouched) when its inputs do not qualify.
//
// Bit budgets (|coordinate| <= 2^k, so every difference fits k + 1 bits):
//   orient3d, k = 28: 2x2 minors < 2^59 (int64), the 3x3 < 3 * 2^88 (int128).
//   incircle, k = 28: lifts and 2x2 minors < 2^59, each product < 2^118, their sum < 2^120.
//   insphere, k = 23: 2x2 minors < 2^49, 3x3 minors < 3 * 2^73, lifts < 3 * 2^48,
//                     each product < 9 * 2^121, the sum of four < 2^126.3 < 2^127.
#pragma once
#include <cmath>

#include "base/hd.hpp"

namespace gpugeom::exact {

constexpr double kIntLimit2d = 268435456.0;  // 2^28
constexpr double kIntLimitOrient3d = 268435456.0;
constexpr double kIntLimitInsphere = 8388608.0;  // 2^23

GG_INLINE bool small_integer(double v, double limit = kIntLimit2d) {
  return std::fabs(v) <= limit && v == std::floor(v);
}
template <int N, int D>
GG_INLINE bool all_small_integers(const double* const* p, double limit) {
  for (int i = 0; i < N; ++i)
    for (int c = 0; c < D; ++c)
      if (!small_integer(p[i][c], limit)) return false;
  return true;
}
GG_INLINE int sign_i128(__int128 v) {
  return (v > 0) - (v < 0);
}

// incircle(a, b, c, d) (the sign convention of predicates.hpp).
GG_HD inline bool incircle_int(const double* a, const double* b, const double* c, const double* d,
                               int& sign) {
  const double* p[4] = {a, b, c, d};
  if (!all_small_integers<4, 2>(p, kIntLimit2d)) return false;
  using i64 = long long;
  const i64 dx = i64(d[0]), dy = i64(d[1]);
  const i64 adx = i64(a[0]) - dx, ady = i64(a[1]) - dy, bdx = i64(b[0]) - dx, bdy = i64(b[1]) - dy,
            cdx = i64(c[0]) - dx, cdy = i64(c[1]) - dy;
  const i64 al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy, cl = cdx * cdx + cdy * cdy;
  const __int128 det = __int128(al) * (bdx * cdy - cdx * bdy) +
                       __int128(bl) * (cdx * ady - adx * cdy) +
                       __int128(cl) * (adx * bdy - bdx * ady);
  sign = sign_i128(det);
  return true;
}

// det[r0; r1; r2] of integer rows whose 2x2 minors fit int64 (expanded along the z column).
GG_INLINE __int128 det3_i128(const long long* r0, const long long* r1, const long long* r2) {
  const long long m12 = r1[0] * r2[1] - r2[0] * r1[1];
  const long long m02 = r0[0] * r2[1] - r2[0] * r0[1];
  const long long m01 = r0[0] * r1[1] - r1[0] * r0[1];
  return __int128(r0[2]) * m12 - __int128(r1[2]) * m02 + __int128(r2[2]) * m01;
}

// orient3d(a, b, c, d) = -det[a-d; b-d; c-d].
GG_HD inline bool orient3d_int(const double* a, const double* b, const double* c, const double* d,
                               int& sign) {
  const double* p[4] = {a, b, c, d};
  if (!all_small_integers<4, 3>(p, kIntLimitOrient3d)) return false;
  long long r[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r[i][k] = (long long)(p[i][k]) - (long long)(d[k]);
  sign = -sign_i128(det3_i128(r[0], r[1], r[2]));
  return true;
}

// insphere(a, b, c, d, e) = -det[[a-e, |a-e|^2]; ...; [d-e, |d-e|^2]], expanded along the lift
// column as in translated.hpp.
GG_HD inline bool insphere_int(const double* a, const double* b, const double* c, const double* d,
                               const double* e, int& sign) {
  const double* p[5] = {a, b, c, d, e};
  if (!all_small_integers<5, 3>(p, kIntLimitInsphere)) return false;
  long long r[4][3], l[4];
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) r[i][k] = (long long)(p[i][k]) - (long long)(e[k]);
    l[i] = r[i][0] * r[i][0] + r[i][1] * r[i][1] + r[i][2] * r[i][2];
  }
  const __int128 det =
      -__int128(l[0]) * det3_i128(r[1], r[2], r[3]) + __int128(l[1]) * det3_i128(r[0], r[2], r[3]) -
      __int128(l[2]) * det3_i128(r[0], r[1], r[3]) + __int128(l[3]) * det3_i128(r[0], r[1], r[2]);
  sign = -sign_i128(det);
  return true;
}

// The minors simulation of simplicity needs (sos.hpp's ExpansionMinors, same meaning), for rows
// of whole numbers: p the coordinates, w = |p|^2 (nullptr where there is no lift column). Within
// insphere_int's bound (|coordinate| <= 2^23): differences < 2^24, lift differences < 2^48, so
// a 3x3 minor with the lift column last has int64 2x2 minors and an int128 sum (< 2^99); the
// orientation minors of orient3d_int's bound (2^28) have at most 2 columns (< 2^59).
struct IntMinors {
  const long long (*p)[3];
  const long long* w;
  static GG_HD __int128 det(const long long (*m)[3], int n) {
    if (n == 1) return m[0][0];
    if (n == 2) return __int128(m[0][0]) * m[1][1] - __int128(m[0][1]) * m[1][0];
    return det3_i128(m[0], m[1], m[2]);
  }
  // det [p[cols] 1] over the q + 1 rows rl: the q x q differences to the last row.
  GG_HD int orient(int q, const int* rl, const int* cols) const {
    if (q == 0) return 1;
    long long m[3][3] = {};
    for (int i = 0; i < q; ++i)
      for (int j = 0; j < q; ++j) m[i][j] = p[rl[i]][cols[j]] - p[rl[q]][cols[j]];
    return sign_i128(det(m, q));
  }
  // det [p[cols] w 1] over the q + 2 rows rl.
  GG_HD int lifted(int q, const int* rl, const int* cols) const {
    long long m[3][3] = {};
    for (int i = 0; i <= q; ++i) {
      for (int j = 0; j < q; ++j) m[i][j] = p[rl[i]][cols[j]] - p[rl[q + 1]][cols[j]];
      m[i][q] = w[rl[i]] - w[rl[q + 1]];
    }
    return sign_i128(det(m, q + 1));
  }
};

}  // namespace gpugeom::exact
