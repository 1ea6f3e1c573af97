// The middle tier of the adaptive predicates: exact arithmetic on the differences to the last
// point, between the floating-point filter and the full expansion of the raw coordinates.
//
// Every difference p - q is taken with two_diff. When all of the tails are zero (integer and
// grid input, points that share an exponent range, any input near enough to its neighbours:
// Sterbenz), the translated matrix holds the exact differences, one double each, and its
// determinant in expansion arithmetic is exact: 4x4 in-sphere determinants then need at most
// 1152 components where the raw 5x5 needs 5760, and a GPU slot 24 KB of scratch instead of 114.
// When some tail is not zero, the exact determinant of the rounded heads is compared with a bound
// on what the tails can change (the second-stage bounds of Shewchuk's adaptive predicates, with
// the same margin of 2 as our filters); only what that cannot decide goes on to the full
// expansion (predicates.hpp), which callers can run as a separate pass with few, large slots.
//
// Results: -1, 0, +1 (exact), or kUndecided. The determinants below are those of the filters
// in predicates.hpp, so signs follow the same conventions.
#pragma once
#include <cmath>

#include "predicates/expansion.hpp"

namespace gpugeom::exact {

constexpr int kUndecided = 2;

// Components of the expression trees below (their longest results).
constexpr int kMinor2Len = 4;                   // a*d - b*c
constexpr int kMinor3Len = 3 * 2 * kMinor2Len;  // 3x3 determinant of single doubles: 24

// Scratch (doubles) of det3_plain (besides its result), det3_lifted<LW> and det4_lifted<LW>
// (result included).
constexpr int kDet3PlainScratch = kMinor2Len + 2 * kMinor2Len + kMinor3Len;
template <int LW>
struct Det3Lifted {
  static constexpr int term = 2 * kMinor2Len * LW;
  static constexpr int len = 3 * term;
  static constexpr int scratch = 2 * len + kMinor2Len + term + 2 * kMinor2Len + term;
};
template <int LW>
struct Det4Lifted {
  static constexpr int term = 2 * kMinor3Len * LW;
  static constexpr int len = 4 * term;
  static constexpr int scratch =
      2 * len + kMinor3Len + kDet3PlainScratch + term + 2 * kMinor3Len + term;
};

// Sum of an expansion's components, smallest first (the estimate the bounds are stated for).
GG_INLINE double estimate(int n, const double* e) {
  double q = 0.0;
  for (int i = 0; i < n; ++i) q = add_rn(q, e[i]);
  return q;
}

// a*d - c*b as an expansion of at most 4 components.
GG_HD inline int minor2(double a, double b, double c, double d, double* out) {
  double p[2], q[2], x, y;
  int pl = 0, ql = 0;
  two_product(a, d, x, y);
  if (y != 0.0) p[pl++] = y;
  if (x != 0.0) p[pl++] = x;
  two_product(c, b, x, y);
  if (y != 0.0) q[ql++] = -y;
  if (x != 0.0) q[ql++] = -x;
  return expansion_sum(pl, p, ql, q, out);
}

// det[r0; r1; r2] of rows of three single doubles, expanded along the third column:
// r0z*M(r1,r2) - r1z*M(r0,r2) + r2z*M(r0,r1), M the 2x2 minor of the first two columns.
// out holds kMinor3Len doubles, s kDet3PlainScratch.
GG_HD inline int det3_plain(const double* r0, const double* r1, const double* r2, double* out,
                            double* s) {
  double* m = s;
  double* t = m + kMinor2Len;
  double* alt = t + 2 * kMinor2Len;
  const double* r[3] = {r0, r1, r2};
  double* acc = out;
  double* other = alt;
  int len = 0;
  for (int i = 0; i < 3; ++i) {
    const double* p = r[i == 0 ? 1 : 0];
    const double* q = r[i == 2 ? 1 : 2];
    const int ml = minor2(p[0], p[1], q[0], q[1], m);
    const double z = (i & 1) ? -r[i][2] : r[i][2];
    accumulate(acc, other, len, t, scale_expansion(ml, m, z, t));
  }
  settle(acc, len, out);
  return len;
}

// det of the 3x3 matrix with rows [r_i (two single doubles), l_i (an expansion of at most LW
// components)], expanded along the lift column: l0*M(r1,r2) - l1*M(r0,r2) + l2*M(r0,r1).
// s holds Det3Lifted<LW>::scratch doubles; the result is left at s (returned length).
template <int LW>
GG_HD int det3_lifted(const double (*r)[2], const double* const* l, const int* ll, double* s) {
  using L = Det3Lifted<LW>;
  double* out = s;
  double* alt = out + L::len;
  double* m = alt + L::len;
  double* term = m + kMinor2Len;
  double* tmp1 = term + L::term;
  double* tmp2 = tmp1 + 2 * kMinor2Len;
  double* acc = out;
  double* other = alt;
  int len = 0;
  for (int i = 0; i < 3; ++i) {
    const double* p = r[i == 0 ? 1 : 0];
    const double* q = r[i == 2 ? 1 : 2];
    const int ml = minor2(p[0], p[1], q[0], q[1], m);
    if (i & 1)
      for (int k = 0; k < ml; ++k) m[k] = -m[k];
    accumulate(acc, other, len, term, expansion_product(ml, m, ll[i], l[i], term, tmp1, tmp2));
  }
  settle(acc, len, out);
  return len;
}

// det of the 4x4 matrix with rows [r_i (three single doubles), l_i (at most LW components)],
// expanded along the lift column: -l0*D(r1,r2,r3) + l1*D(r0,r2,r3) - l2*D(r0,r1,r3) +
// l3*D(r0,r1,r2). s holds Det4Lifted<LW>::scratch doubles; the result is left at s.
template <int LW>
GG_HD int det4_lifted(const double (*r)[3], const double* const* l, const int* ll, double* s) {
  using L = Det4Lifted<LW>;
  double* out = s;
  double* alt = out + L::len;
  double* m = alt + L::len;
  double* ms = m + kMinor3Len;
  double* term = ms + kDet3PlainScratch;
  double* tmp1 = term + L::term;
  double* tmp2 = tmp1 + 2 * kMinor3Len;
  double* acc = out;
  double* other = alt;
  int len = 0;
  for (int i = 0; i < 4; ++i) {
    const double* q[3];
    for (int j = 0, k = 0; j < 4; ++j)
      if (j != i) q[k++] = r[j];
    const int ml = det3_plain(q[0], q[1], q[2], m, ms);
    if (!(i & 1))
      for (int k = 0; k < ml; ++k) m[k] = -m[k];
    accumulate(acc, other, len, term, expansion_product(ml, m, ll[i], l[i], term, tmp1, tmp2));
  }
  settle(acc, len, out);
  return len;
}

// Heads of p[i] - q over the first D coordinates; true when every tail is zero.
template <int N, int D, int W>
GG_HD bool translate(const double* const* p, const double* q, double (*h)[W]) {
  bool exact = true;
  for (int i = 0; i < N; ++i)
    for (int c = 0; c < D; ++c) {
      double t;
      two_diff(p[i][c], q[c], h[i][c], t);
      exact = exact && t == 0.0;
    }
  return exact;
}

// |h|^2 over D single doubles, at most 2D components.
template <int D>
GG_HD int square_sum(const double* h, double* out) {
  double parts[2 * D], tmp[2 * D];
  int len = 0;
  for (int c = 0; c < D; ++c) {
    double sq[2], x, y;
    two_product(h[c], h[c], x, y);
    int k = 0;
    if (y != 0.0) sq[k++] = y;
    if (x != 0.0) sq[k++] = x;
    len = expansion_sum(len, parts, k, sq, tmp);
    for (int i = 0; i < len; ++i) parts[i] = tmp[i];
  }
  for (int i = 0; i < len; ++i) out[i] = parts[i];
  return len;
}

// The sign of an exact determinant, or, when it was taken over rounded heads, the sign of its
// estimate if that clears bound * permanent, else kUndecided. perm as the filters compute it.
GG_INLINE int judge(bool exact, int n, const double* det, double perm, double bound) {
  if (exact) return expansion_sign(n, det);
  if (!(perm > 1e-280) || !(perm < 1e290)) return kUndecided;
  const double est = estimate(n, det), err = bound * perm;
  if (est > err || -est > err) return (est > 0.0) - (est < 0.0);
  return kUndecided;
}

}  // namespace gpugeom::exact
