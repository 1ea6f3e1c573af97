// The middle tier of the adaptive predicates: exact arithmetic on the differences to the last
// point, between the floating-point filter and the full expansion of the raw coordinates.
//
// Every difference p - q is taken with two_diff. When all of the tails are zero (integer and
// grid input, points that share an exponent range, any input near enough to its neighbours:
// Sterbenz), the translated matrix holds the exact differences, one double each, and its
// determinant in expansion arithmetic is exact: 4x4 in-sphere determinants then need at most
// 1152 components where the raw 5x5 needs 5760, and a GPU slot 23.9 KB of scratch instead of 114.1.
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

// Scratch (doubles) of det3_plain, besides its result.
constexpr int kDet3PlainScratch = kMinor2Len + 2 * kMinor2Len + kMinor3Len;
// Sizes for det_lifted<N, LW> (N = 3 or 4): its minors, their scratch, one product term, the
// result, and the whole scratch it needs (result included).
template <int N, int LW>
struct DetLifted {
  static constexpr int minor = N == 3 ? kMinor2Len : kMinor3Len;
  static constexpr int minor_scratch = N == 3 ? 0 : kDet3PlainScratch;
  static constexpr int term = 2 * minor * LW;
  static constexpr int len = N * term;
  static constexpr int scratch = 2 * len + minor + minor_scratch + term + 2 * minor + term;
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

// det of the NxN matrix (N = 3 or 4) with rows [r_i (N - 1 single doubles), l_i (an
// expansion of at most LW components)], expanded along the lift column: the sum over i of
// (-1)^(i + N - 1) l_i times the minor of the other rows, i.e. for N = 3
// l0*M(r1,r2) - l1*M(r0,r2) + l2*M(r0,r1), and for N = 4 -l0*D(r1,r2,r3) + l1*D(r0,r2,r3) -
// l2*D(r0,r1,r3) + l3*D(r0,r1,r2). s holds DetLifted<N, LW>::scratch doubles; the result is
// left at s (returned length).
template <int N, int LW>
GG_HD int det_lifted(const double (*r)[N - 1], const double* const* l, const int* ll, double* s) {
  static_assert(N == 3 || N == 4, "3x3 and 4x4 determinants only");
  using L = DetLifted<N, LW>;
  double* out = s;
  double* alt = out + L::len;
  double* m = alt + L::len;
  double* ms = m + L::minor;
  double* term = ms + L::minor_scratch;
  double* tmp1 = term + L::term;
  double* tmp2 = tmp1 + 2 * L::minor;
  double* acc = out;
  double* other = alt;
  int len = 0;
  for (int i = 0; i < N; ++i) {
    const double* q[N - 1];
    for (int j = 0, k = 0; j < N; ++j)
      if (j != i) q[k++] = r[j];
    int ml;
    if constexpr (N == 3)
      ml = minor2(q[0][0], q[0][1], q[1][0], q[1][1], m);
    else
      ml = det3_plain(q[0], q[1], q[2], m, ms);
    if ((i + N - 1) & 1)
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
