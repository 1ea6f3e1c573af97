// Exact floating-point expansion arithmetic (Priest/Shewchuk's published method, written from
// the paper's description): a number is a sum of doubles, non-overlapping, in increasing
// magnitude, with zeros removed; its sign is the sign of the last component.
//
// Every rounding operation goes through the *_rn helpers: on the device they are the
// intrinsics that nvcc never fuses into an FMA, which would break the error-free transforms.
// Host code is compiled with -ffp-contract=off for the same reason.
#pragma once
#include <cmath>

#include "base/hd.hpp"

namespace gpugeom::exact {

GG_INLINE double add_rn(double a, double b) {
#ifdef __CUDA_ARCH__
  return __dadd_rn(a, b);
#else
  return a + b;
#endif
}
GG_INLINE double sub_rn(double a, double b) {
#ifdef __CUDA_ARCH__
  return __dsub_rn(a, b);
#else
  return a - b;
#endif
}
GG_INLINE double mul_rn(double a, double b) {
#ifdef __CUDA_ARCH__
  return __dmul_rn(a, b);
#else
  return a * b;
#endif
}
GG_INLINE double fma_rn(double a, double b, double c) {
#ifdef __CUDA_ARCH__
  return __fma_rn(a, b, c);
#else
  return std::fma(a, b, c);
#endif
}

// x + y == a + b exactly, x = fl(a + b).
GG_INLINE void two_sum(double a, double b, double& x, double& y) {
  x = add_rn(a, b);
  double bv = sub_rn(x, a);
  double av = sub_rn(x, bv);
  y = add_rn(sub_rn(a, av), sub_rn(b, bv));
}
// Same, valid when |a| >= |b| (or a == 0).
GG_INLINE void fast_two_sum(double a, double b, double& x, double& y) {
  x = add_rn(a, b);
  y = sub_rn(b, sub_rn(x, a));
}
GG_INLINE void two_diff(double a, double b, double& x, double& y) {
  two_sum(a, -b, x, y);
}
// x + y == a * b exactly (the FMA gives the rounding error of the product).
GG_INLINE void two_product(double a, double b, double& x, double& y) {
  x = mul_rn(a, b);
  y = fma_rn(a, b, -x);
}

GG_INLINE int expansion_sign(int n, const double* e) {
  return n == 0 ? 0 : (e[n - 1] > 0.0) - (e[n - 1] < 0.0);
}

// h = e + f. Merges the components by magnitude, then carries with two_sum, dropping zeros.
// h must hold elen + flen doubles and may not alias e or f.
GG_HD inline int expansion_sum(int elen, const double* e, int flen, const double* f, double* h) {
  int i = 0, j = 0, k = 0;
  if (elen + flen == 0) return 0;
  auto next = [&]() -> double {
    if (j >= flen || (i < elen && std::fabs(e[i]) < std::fabs(f[j]))) return e[i++];
    return f[j++];
  };
  double q = next();
  for (int n = 1; n < elen + flen; ++n) {
    double g = next(), qn, hh;
    two_sum(q, g, qn, hh);
    if (hh != 0.0) h[k++] = hh;
    q = qn;
  }
  if (q != 0.0) h[k++] = q;
  return k;
}

// h = b * e; h must hold 2 * elen doubles.
GG_HD inline int scale_expansion(int elen, const double* e, double b, double* h) {
  if (elen == 0 || b == 0.0) return 0;
  int k = 0;
  double q, hh;
  two_product(e[0], b, q, hh);
  if (hh != 0.0) h[k++] = hh;
  for (int i = 1; i < elen; ++i) {
    double p1, p0, s;
    two_product(e[i], b, p1, p0);
    two_sum(q, p0, s, hh);
    if (hh != 0.0) h[k++] = hh;
    fast_two_sum(p1, s, q, hh);
    if (hh != 0.0) h[k++] = hh;
  }
  if (q != 0.0) h[k++] = q;
  return k;
}

// Adds the expansion t (length tl) into the running sum held in acc (length len), using other
// as the destination and swapping the two buffers, so callers ping-pong without copies.
GG_INLINE void accumulate(double*& acc, double*& other, int& len, const double* t, int tl) {
  const int nl = expansion_sum(len, acc, tl, t, other);
  double* x = acc;
  acc = other;
  other = x;
  len = nl;
}
// Copies the result to out when the ping-pong left it in the other buffer.
GG_INLINE void settle(const double* acc, int len, double* out) {
  if (acc != out)
    for (int i = 0; i < len; ++i) out[i] = acc[i];
}

// h = e * f. h and tmp2 hold 2*elen*flen doubles each, tmp1 holds 2*elen.
GG_HD inline int expansion_product(int elen, const double* e, int flen, const double* f, double* h,
                                   double* tmp1, double* tmp2) {
  int len = 0;
  double* acc = h;
  double* other = tmp2;
  for (int j = 0; j < flen; ++j)
    accumulate(acc, other, len, tmp1, scale_expansion(elen, e, f[j], tmp1));
  settle(acc, len, h);
  return len;
}

}  // namespace gpugeom::exact
