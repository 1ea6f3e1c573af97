// Double-word ("double-double") arithmetic with proven error bounds, for the predicates' tier
// between the floating-point filter and the exact expansions (predicates.hpp).
//
// A value is hi + lo with |lo| <= ulp(hi) / 2. The two operations are the published algorithms
// of Joldes, Muller and Popescu ("Tight and rigorous error bounds for basic building blocks of
// double-word arithmetic", ACM TOMS 2017), written from the paper's description:
//   add: AccurateDWPlusDW (their Algorithm 6), relative error at most 3u^2 / (1 - 4u);
//   mul: DWTimesDW with FMAs (their Algorithm 12), relative error at most 5u^2 (their bound;
//        later work tightens it to 4u^2), u = 2^-53,
// both as long as nothing underflows or overflows, which the callers make sure of by the
// magnitudes they accept. Each relative error is at most c u^2 (|x| + |y|) for a sum and
// c u^2 |x| |y| for a product, the form that an error bound proportional to the permanent of
// an expression needs (see insphere_dw in predicates.hpp).
#pragma once
#include "predicates/expansion.hpp"

namespace gpugeom::exact {

struct DW {
  double hi, lo;
};

// a - b exactly (a difference of two doubles always fits a double word).
GG_INLINE DW dw_diff(double a, double b) {
  DW r;
  two_diff(a, b, r.hi, r.lo);
  return r;
}

GG_INLINE DW dw_neg(DW x) {
  return DW{-x.hi, -x.lo};
}

GG_INLINE DW dw_add(DW x, DW y) {
  double sh, sl, th, tl, vh, vl;
  two_sum(x.hi, y.hi, sh, sl);
  two_sum(x.lo, y.lo, th, tl);
  const double c = add_rn(sl, th);
  fast_two_sum(sh, c, vh, vl);
  const double w = add_rn(tl, vl);
  DW z;
  fast_two_sum(vh, w, z.hi, z.lo);
  return z;
}

GG_INLINE DW dw_sub(DW x, DW y) {
  return dw_add(x, dw_neg(y));
}

GG_INLINE DW dw_mul(DW x, DW y) {
  double ch, cl1;
  two_product(x.hi, y.hi, ch, cl1);
  const double tl0 = mul_rn(x.lo, y.lo);
  const double tl1 = fma_rn(x.hi, y.lo, tl0);
  const double cl2 = fma_rn(x.lo, y.hi, tl1);
  const double cl3 = add_rn(cl1, cl2);
  DW z;
  fast_two_sum(ch, cl3, z.hi, z.lo);
  return z;
}

}  // namespace gpugeom::exact
