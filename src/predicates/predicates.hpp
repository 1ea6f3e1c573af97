// Exact geometric predicates, callable from host and device code.
//
// Each predicate is adaptive, in tiers, each run only when the one before cannot tell:
//   1. a floating-point filter with a proven error bound (*_fast; 0 means "cannot tell");
//   2. for whole-number coordinates, 128-bit integer arithmetic (*_int; integer.hpp); for
//      in-sphere, otherwise, double-word arithmetic with a proven bound (insphere_dw), which
//      decides points that are nearly but not exactly cospherical (points rounded from a
//      sphere) without scratch;
//   3. exact arithmetic on the differences to the last point (*_translated; translated.hpp),
//      exact when the differences are, else bounded; kUndecided when it cannot tell;
//   4. the full expansion of the raw coordinates (*_exact).
// *_mid runs tiers 1-3; the adaptive functions run all four. The *_sos variants add simulation
// of simplicity (sos.hpp) and never return 0 for distinct indices; *_sos_mid and *_sos_last
// split them the same way, so that a GPU pass can run tier 3 on many small scratch slots and
// leave tier 4 to a second, short list with a few large ones (exec/split_pass.hpp).
//
// Sign conventions (all points double[dim]):
//   orient2d(a,b,c)      > 0  iff a,b,c counter-clockwise          = det[b-a; c-a]
//   orient3d(a,b,c,d)    > 0  iff d lies on the side of triangle abc where (b-a)x(c-a)
//                             points, i.e. tetrahedron abcd is positively oriented
//                             = det[b-a; c-a; d-a]
//   incircle(a,b,c,d)    > 0  iff d inside the circle through a,b,c (abc counter-clockwise)
//   insphere(a,b,c,d,e)  > 0  iff e inside the sphere through a,b,c,d (abcd positive)
//   orient4d(a,b,c,d,e)  4D points; = det[b-a; c-a; d-a; e-a]
//   orient4d_lifted(..)  orient4d of the 3D points lifted to (x,y,z,x^2+y^2+z^2)
//                        = -insphere(a,b,c,d,e); what star splaying in 4D uses
//
// Exactness holds for coordinates that are 0 or of magnitude in [2^-142, 2^180] (about
// 1.8e-43 .. 1.5e54): beyond that the products of the exact stage could under- or overflow.
// in_exact_range() tells; the algorithms refuse other inputs with a clear error.
//
// Scratch: the k*Scratch doubles given below (the k*MidScratch ones for the *_mid functions).
// Host code may use the overloads in include/gpugeom/predicates.hpp, which bring their own;
// device code passes a local array (small predicates) or a slice of global memory (see
// exec/split_pass.hpp). Per slot: in-sphere 114.1 KB in full (14 262 doubles), 23.9 KB up to tier 3
// with SoS (2 988 doubles).
#pragma once
#include <initializer_list>
#include <cmath>

#include "predicates/double_word.hpp"
#include "predicates/integer.hpp"
#include "predicates/sos.hpp"
#include "predicates/translated.hpp"

namespace gpugeom::pred {

using namespace ::gpugeom::exact;

constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
// Filter bounds: Shewchuk's published first-stage bounds for these expression trees, times
// 2 as a margin (it costs nothing measurable in the fraction of cases decided).
constexpr double kOrient2dBound = 2 * (3.0 + 16.0 * kEps) * kEps;
constexpr double kOrient3dBound = 2 * (7.0 + 56.0 * kEps) * kEps;
constexpr double kIncircleBound = 2 * (10.0 + 96.0 * kEps) * kEps;
constexpr double kInsphereBound = 2 * (16.0 + 224.0 * kEps) * kEps;
// Bounds of tier 3 on the exact determinant of the rounded differences (the published second-
// stage bounds, same margin): what the differences' tails can change, relative to the permanent.
constexpr double kOrient3dBoundB = 2 * (3.0 + 28.0 * kEps) * kEps;
constexpr double kIncircleBoundB = 2 * (4.0 + 48.0 * kEps) * kEps;
constexpr double kInsphereBoundB = 2 * (5.0 + 72.0 * kEps) * kEps;
// Below this permanent the filter's relative bound could be spoiled by underflow: go exact.
constexpr double kTinyPermanent = 1e-280;

GG_INLINE bool in_exact_range(double v) {
  double a = std::fabs(v);
  return a == 0.0 || (a >= 0x1p-142 && a <= 0x1p180);
}

GG_INLINE int sign_of(double d) {
  return (d > 0.0) - (d < 0.0);
}
GG_INLINE int decide(double det, double perm, double bound) {
  if (!(perm > kTinyPermanent) || !(perm < 1e290)) return 0;
  double err = bound * perm;
  if (det > err || -det > err) return sign_of(det);
  return 0;
}

// ---- scratch sizes (doubles) ----
constexpr int kOrient2dScratch = Om<2>::len + Om<2>::scratch + SosScratch<2, 0>::value;
constexpr int kOrient3dScratch = Om<3>::len + Om<3>::scratch + SosScratch<3, 0>::value;
constexpr int kIncircleScratch = cmax(Lm<2, 4>::len + Lm<2, 4>::scratch, SosScratch<2, 4>::value);
constexpr int kInsphereScratch = cmax(Lm<3, 6>::len + Lm<3, 6>::scratch, SosScratch<3, 6>::value);
constexpr int kOrient4dScratch = cmax(Lm<3, 1>::len + Lm<3, 1>::scratch, SosScratch<3, 1>::value);
// Tiers 1-3 (the *_mid functions), and tiers 1-3 with SoS on an exact zero (*_sos_mid).
constexpr int kOrient3dMidScratch = kMinor3Len + kDet3PlainScratch;
constexpr int kIncircleMidScratch = DetLifted<3, 4>::scratch;
constexpr int kInsphereMidScratch = DetLifted<4, 6>::scratch;
constexpr int kOrient4dMidScratch = DetLifted<4, 1>::scratch;
constexpr int kOrient3dSosMidScratch = cmax(kOrient3dMidScratch, SosScratch<3, 0>::value);
constexpr int kIncircleSosMidScratch = cmax(kIncircleMidScratch, SosScratch<2, 4>::value);
constexpr int kInsphereSosMidScratch = cmax(kInsphereMidScratch, SosScratch<3, 6>::value);
constexpr int kOrient4dSosMidScratch = cmax(kOrient4dMidScratch, SosScratch<3, 1>::value);
static_assert(kOrient3dScratch >= kOrient3dSosMidScratch &&
                  kIncircleScratch >= kIncircleSosMidScratch &&
                  kInsphereScratch >= kInsphereSosMidScratch &&
                  kOrient4dScratch >= kOrient4dSosMidScratch,
              "the adaptive predicates run tier 3 in their own scratch");

// ---- filters ----
GG_INLINE int orient2d_fast(const double* a, const double* b, const double* c) {
  double l = mul_rn(sub_rn(a[0], c[0]), sub_rn(b[1], c[1]));
  double r = mul_rn(sub_rn(a[1], c[1]), sub_rn(b[0], c[0]));
  return decide(sub_rn(l, r), add_rn(std::fabs(l), std::fabs(r)), kOrient2dBound);
}

// det[a-d; b-d; c-d] and its permanent (orient3d is minus that determinant).
GG_INLINE void orient3d_terms(const double* a, const double* b, const double* c, const double* d,
                              double& det, double& perm) {
  double adx = sub_rn(a[0], d[0]), bdx = sub_rn(b[0], d[0]), cdx = sub_rn(c[0], d[0]);
  double ady = sub_rn(a[1], d[1]), bdy = sub_rn(b[1], d[1]), cdy = sub_rn(c[1], d[1]);
  double adz = sub_rn(a[2], d[2]), bdz = sub_rn(b[2], d[2]), cdz = sub_rn(c[2], d[2]);
  double bc1 = mul_rn(bdx, cdy), bc2 = mul_rn(bdy, cdx);
  double ca1 = mul_rn(cdx, ady), ca2 = mul_rn(cdy, adx);
  double ab1 = mul_rn(adx, bdy), ab2 = mul_rn(ady, bdx);
  det = add_rn(add_rn(mul_rn(adz, sub_rn(bc1, bc2)), mul_rn(bdz, sub_rn(ca1, ca2))),
               mul_rn(cdz, sub_rn(ab1, ab2)));
  perm = add_rn(add_rn(mul_rn(add_rn(std::fabs(bc1), std::fabs(bc2)), std::fabs(adz)),
                       mul_rn(add_rn(std::fabs(ca1), std::fabs(ca2)), std::fabs(bdz))),
                mul_rn(add_rn(std::fabs(ab1), std::fabs(ab2)), std::fabs(cdz)));
}

GG_INLINE int orient3d_fast(const double* a, const double* b, const double* c, const double* d) {
  double det, perm;
  orient3d_terms(a, b, c, d, det, perm);
  // det = det[a-d; b-d; c-d] = -det[b-a; c-a; d-a]
  return -decide(det, perm, kOrient3dBound);
}

// The in-circle determinant det[[a-d, |a-d|^2]; [b-d, ..]; [c-d, ..]] and its permanent.
GG_INLINE void incircle_terms(const double* a, const double* b, const double* c, const double* d,
                              double& det, double& perm) {
  double adx = sub_rn(a[0], d[0]), bdx = sub_rn(b[0], d[0]), cdx = sub_rn(c[0], d[0]);
  double ady = sub_rn(a[1], d[1]), bdy = sub_rn(b[1], d[1]), cdy = sub_rn(c[1], d[1]);
  double bc1 = mul_rn(bdx, cdy), bc2 = mul_rn(cdx, bdy);
  double ca1 = mul_rn(cdx, ady), ca2 = mul_rn(adx, cdy);
  double ab1 = mul_rn(adx, bdy), ab2 = mul_rn(bdx, ady);
  double al = add_rn(mul_rn(adx, adx), mul_rn(ady, ady));
  double bl = add_rn(mul_rn(bdx, bdx), mul_rn(bdy, bdy));
  double cl = add_rn(mul_rn(cdx, cdx), mul_rn(cdy, cdy));
  det = add_rn(add_rn(mul_rn(al, sub_rn(bc1, bc2)), mul_rn(bl, sub_rn(ca1, ca2))),
               mul_rn(cl, sub_rn(ab1, ab2)));
  perm = add_rn(add_rn(mul_rn(add_rn(std::fabs(bc1), std::fabs(bc2)), al),
                       mul_rn(add_rn(std::fabs(ca1), std::fabs(ca2)), bl)),
                mul_rn(add_rn(std::fabs(ab1), std::fabs(ab2)), cl));
}

GG_INLINE int incircle_fast(const double* a, const double* b, const double* c, const double* d) {
  double det, perm;
  incircle_terms(a, b, c, d, det, perm);
  return decide(det, perm, kIncircleBound);
}

// The 4x4 determinant det[[a-e, la], [b-e, lb], [c-e, lc], [d-e, ld]] by 2x2 minors of the
// first two columns, its permanent alongside. Shared by insphere and orient4d.
GG_INLINE void det4_translated(const double* a, const double* b, const double* c, const double* d,
                               const double* e, double la, double lb, double lc, double ld,
                               double& det, double& perm) {
  double aex = sub_rn(a[0], e[0]), bex = sub_rn(b[0], e[0]), cex = sub_rn(c[0], e[0]),
         dex = sub_rn(d[0], e[0]);
  double aey = sub_rn(a[1], e[1]), bey = sub_rn(b[1], e[1]), cey = sub_rn(c[1], e[1]),
         dey = sub_rn(d[1], e[1]);
  double aez = sub_rn(a[2], e[2]), bez = sub_rn(b[2], e[2]), cez = sub_rn(c[2], e[2]),
         dez = sub_rn(d[2], e[2]);
  double aexbey = mul_rn(aex, bey), bexaey = mul_rn(bex, aey);
  double bexcey = mul_rn(bex, cey), cexbey = mul_rn(cex, bey);
  double cexdey = mul_rn(cex, dey), dexcey = mul_rn(dex, cey);
  double dexaey = mul_rn(dex, aey), aexdey = mul_rn(aex, dey);
  double aexcey = mul_rn(aex, cey), cexaey = mul_rn(cex, aey);
  double bexdey = mul_rn(bex, dey), dexbey = mul_rn(dex, bey);
  double ab = sub_rn(aexbey, bexaey), bc = sub_rn(bexcey, cexbey), cd = sub_rn(cexdey, dexcey),
         da = sub_rn(dexaey, aexdey), ac = sub_rn(aexcey, cexaey), bd = sub_rn(bexdey, dexbey);
  // 3x3 minors of rows (x, y, z): abc = det[a;b;c] etc.
  double abc = add_rn(sub_rn(mul_rn(aez, bc), mul_rn(bez, ac)), mul_rn(cez, ab));
  double bcd = add_rn(sub_rn(mul_rn(bez, cd), mul_rn(cez, bd)), mul_rn(dez, bc));
  double cda = add_rn(add_rn(mul_rn(cez, da), mul_rn(dez, ac)), mul_rn(aez, cd));
  double dab = add_rn(add_rn(mul_rn(dez, ab), mul_rn(aez, bd)), mul_rn(bez, da));
  det = add_rn(sub_rn(mul_rn(ld, abc), mul_rn(lc, dab)), sub_rn(mul_rn(lb, cda), mul_rn(la, bcd)));
  double pab = add_rn(std::fabs(aexbey), std::fabs(bexaey));
  double pbc = add_rn(std::fabs(bexcey), std::fabs(cexbey));
  double pcd = add_rn(std::fabs(cexdey), std::fabs(dexcey));
  double pda = add_rn(std::fabs(dexaey), std::fabs(aexdey));
  double pac = add_rn(std::fabs(aexcey), std::fabs(cexaey));
  double pbd = add_rn(std::fabs(bexdey), std::fabs(dexbey));
  double aezp = std::fabs(aez), bezp = std::fabs(bez), cezp = std::fabs(cez), dezp = std::fabs(dez);
  double pabc = add_rn(add_rn(mul_rn(aezp, pbc), mul_rn(bezp, pac)), mul_rn(cezp, pab));
  double pbcd = add_rn(add_rn(mul_rn(bezp, pcd), mul_rn(cezp, pbd)), mul_rn(dezp, pbc));
  double pcda = add_rn(add_rn(mul_rn(cezp, pda), mul_rn(dezp, pac)), mul_rn(aezp, pcd));
  double pdab = add_rn(add_rn(mul_rn(dezp, pab), mul_rn(aezp, pbd)), mul_rn(bezp, pda));
  perm = add_rn(add_rn(mul_rn(std::fabs(ld), pabc), mul_rn(std::fabs(lc), pdab)),
                add_rn(mul_rn(std::fabs(lb), pcda), mul_rn(std::fabs(la), pbcd)));
}

GG_INLINE double lift3(const double* p, const double* e) {
  double x = sub_rn(p[0], e[0]), y = sub_rn(p[1], e[1]), z = sub_rn(p[2], e[2]);
  return add_rn(add_rn(mul_rn(x, x), mul_rn(y, y)), mul_rn(z, z));
}

GG_INLINE int insphere_fast(const double* a, const double* b, const double* c, const double* d,
                            const double* e) {
  double det, perm;
  det4_translated(a, b, c, d, e, lift3(a, e), lift3(b, e), lift3(c, e), lift3(d, e), det, perm);
  return -decide(det, perm, kInsphereBound);  // det = det(M); insphere = -det(M)
}

// In-sphere with a semi-static bound: the filter's determinant, and in place of its permanent
// one from the differences' largest magnitudes per axis, mx, my, mz. Why it is a bound: every
// term of the permanent as det4_translated computes it is a rounded sum of rounded products of
// the differences' magnitudes, and rounding is monotone, so each term is at most the same
// expression with every |x| replaced by mx (|y| by my, |z| by mz): the 2x2 minors' terms
// 2 (mx my), the 3x3 minors' 3 (mz (2 (mx my))), the lifts L = (mx^2 + my^2) + mz^2, the whole
// 4 (L (3 (mz (2 (mx my))))), each operation rounded as here (the doublings are exact). That
// permanent's bound, kInsphereBound, then holds for it too. It costs maxima where the
// permanent cost some 50 operations: what the Bowyer-Watson cavities on the CPU spend most of
// their tests in. Where a magnitude is outside [2^-150, 2^190] (so that an underflow or an
// overflow could spoil the bound: every product then stays in [2^-600, 2^960]), or the bound
// cannot tell, 0: the caller goes on to insphere_fast's sharper bound and the later tiers.
// (x > y ? x : y compiles to one instruction; std::fmax's NaN rules need several)
GG_INLINE double max2(double x, double y) {
  return x > y ? x : y;
}
GG_INLINE double min2(double x, double y) {
  return x < y ? x : y;
}
GG_INLINE int insphere_semistatic(const double* a, const double* b, const double* c,
                                  const double* d, const double* e) {
  const double aex = sub_rn(a[0], e[0]), bex = sub_rn(b[0], e[0]), cex = sub_rn(c[0], e[0]),
               dex = sub_rn(d[0], e[0]);
  const double aey = sub_rn(a[1], e[1]), bey = sub_rn(b[1], e[1]), cey = sub_rn(c[1], e[1]),
               dey = sub_rn(d[1], e[1]);
  const double aez = sub_rn(a[2], e[2]), bez = sub_rn(b[2], e[2]), cez = sub_rn(c[2], e[2]),
               dez = sub_rn(d[2], e[2]);
  const double mx =
      max2(max2(std::fabs(aex), std::fabs(bex)), max2(std::fabs(cex), std::fabs(dex)));
  const double my =
      max2(max2(std::fabs(aey), std::fabs(bey)), max2(std::fabs(cey), std::fabs(dey)));
  const double mz =
      max2(max2(std::fabs(aez), std::fabs(bez)), max2(std::fabs(cez), std::fabs(dez)));
  const double lo = min2(min2(mx, my), mz), hi = max2(max2(mx, my), mz);
  if (!(lo >= 0x1p-150) || !(hi <= 0x1p190)) return 0;
  const double aexbey = mul_rn(aex, bey), bexaey = mul_rn(bex, aey);
  const double bexcey = mul_rn(bex, cey), cexbey = mul_rn(cex, bey);
  const double cexdey = mul_rn(cex, dey), dexcey = mul_rn(dex, cey);
  const double dexaey = mul_rn(dex, aey), aexdey = mul_rn(aex, dey);
  const double aexcey = mul_rn(aex, cey), cexaey = mul_rn(cex, aey);
  const double bexdey = mul_rn(bex, dey), dexbey = mul_rn(dex, bey);
  const double ab = sub_rn(aexbey, bexaey), bc = sub_rn(bexcey, cexbey),
               cd = sub_rn(cexdey, dexcey), da = sub_rn(dexaey, aexdey),
               ac = sub_rn(aexcey, cexaey), bd = sub_rn(bexdey, dexbey);
  const double abc = add_rn(sub_rn(mul_rn(aez, bc), mul_rn(bez, ac)), mul_rn(cez, ab));
  const double bcd = add_rn(sub_rn(mul_rn(bez, cd), mul_rn(cez, bd)), mul_rn(dez, bc));
  const double cda = add_rn(add_rn(mul_rn(cez, da), mul_rn(dez, ac)), mul_rn(aez, cd));
  const double dab = add_rn(add_rn(mul_rn(dez, ab), mul_rn(aez, bd)), mul_rn(bez, da));
  auto lift = [](double x, double y, double z) {
    return add_rn(add_rn(mul_rn(x, x), mul_rn(y, y)), mul_rn(z, z));
  };
  const double la = lift(aex, aey, aez), lb = lift(bex, bey, bez), lc = lift(cex, cey, cez),
               ld = lift(dex, dey, dez);
  const double det =
      add_rn(sub_rn(mul_rn(ld, abc), mul_rn(lc, dab)), sub_rn(mul_rn(lb, cda), mul_rn(la, bcd)));
  const double minor3 = mul_rn(3.0, mul_rn(mz, 2.0 * mul_rn(mx, my)));
  const double perm = 4.0 * mul_rn(lift(mx, my, mz), minor3);
  const double err = mul_rn(kInsphereBound, perm);
  if (det > err) return -1;  // insphere = -det(M)
  if (-det > err) return 1;
  return 0;
}

// In-sphere in double-word arithmetic (double_word.hpp): the determinant of the filter, on the
// exact differences, every operation a double-word one; 0 where its bound cannot tell (or the
// magnitudes are outside those the bound holds for).
//
// The bound: write P(v) for the permanent of a subexpression v (its terms in absolute value)
// and E(v) for its error. Differences are exact (E = 0). A sum adds at most 3u^2 (|x| + |y|)
// and a product 5u^2 |x| |y| to its operands' errors, so that E(v) <= k(v) u^2 P(v) with
// k(x + y) = max(k(x), k(y)) + 3 and k(x y) = k(x) + k(y) + 5 (up to terms in u^4): 2x2 minors
// 8, 3x3 minors 19, lifts 11, lift times minor 35, the determinant 41. The filter's permanent,
// from rounded differences and rounded operations, is at least (1 - 17u) times the exact one;
// the bound below is twice 41 u^2 of it, and a head above it fixes the sign (|lo| <= u |hi|).
// Magnitudes: nonzero differences in [2^-180, 2^190] keep every partial permanent in
// [2^-900, 2^960], so an underflow adds at most 2^-170 of it, no operation overflows, and
// the published bounds (which assume neither) hold up to that.
constexpr double kInsphereBoundDW = 2 * (41.0 + 64.0 * kEps) * kEps * kEps;
GG_INLINE bool dw_in_range(double h) {
  const double a = std::fabs(h);
  return a == 0.0 || (a >= 0x1p-180 && a <= 0x1p190);
}
GG_COLD int insphere_dw(const double* a, const double* b, const double* c, const double* d,
                        const double* e) {
  const double* p[4] = {a, b, c, d};
  DW y[4][3];  // the differences to e
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      y[i][k] = dw_diff(p[i][k], e[k]);
      if (!dw_in_range(y[i][k].hi)) return 0;
    }
  DW l[4];
  for (int i = 0; i < 4; ++i)
    l[i] = dw_add(dw_add(dw_mul(y[i][0], y[i][0]), dw_mul(y[i][1], y[i][1])),
                  dw_mul(y[i][2], y[i][2]));
  // 2x2 minors of the first two columns (as det4_translated's ab, bc, ...)
  auto m = [&](int i, int j) { return dw_sub(dw_mul(y[i][0], y[j][1]), dw_mul(y[j][0], y[i][1])); };
  const DW ab = m(0, 1), bc = m(1, 2), cd = m(2, 3), da = m(3, 0), ac = m(0, 2), bd = m(1, 3);
  const DW abc = dw_add(dw_sub(dw_mul(y[0][2], bc), dw_mul(y[1][2], ac)), dw_mul(y[2][2], ab));
  const DW bcd = dw_add(dw_sub(dw_mul(y[1][2], cd), dw_mul(y[2][2], bd)), dw_mul(y[3][2], bc));
  const DW cda = dw_add(dw_add(dw_mul(y[2][2], da), dw_mul(y[3][2], ac)), dw_mul(y[0][2], cd));
  const DW dab = dw_add(dw_add(dw_mul(y[3][2], ab), dw_mul(y[0][2], bd)), dw_mul(y[1][2], da));
  const DW det = dw_add(dw_sub(dw_mul(l[3], abc), dw_mul(l[2], dab)),
                        dw_sub(dw_mul(l[1], cda), dw_mul(l[0], bcd)));
  double fd, perm;
  det4_translated(a, b, c, d, e, lift3(a, e), lift3(b, e), lift3(c, e), lift3(d, e), fd, perm);
  const double err = kInsphereBoundDW * perm;
  if (det.hi > err) return -1;  // insphere = -det(M)
  if (det.hi < -err) return 1;
  return 0;
}

GG_INLINE int orient4d_fast(const double* a, const double* b, const double* c, const double* d,
                            const double* e) {
  double det, perm;
  det4_translated(a, b, c, d, e, sub_rn(a[3], e[3]), sub_rn(b[3], e[3]), sub_rn(c[3], e[3]),
                  sub_rn(d[3], e[3]), det, perm);
  return decide(det, perm, kInsphereBound);  // det[x-e] = det(M) = orient4d
}

// ---- exact stages (s: scratch of the predicate's k*Scratch doubles) ----
GG_HD inline int orient2d_exact(const double* a, const double* b, const double* c, double* s) {
  const double* r[3] = {a, b, c};
  const int cols[2] = {0, 1};
  int n = orient_minor<2>(r, cols, s, s + Om<2>::len);
  return expansion_sign(n, s);
}
GG_HD inline int orient3d_exact(const double* a, const double* b, const double* c, const double* d,
                                double* s) {
  const double* r[4] = {a, b, c, d};
  const int cols[3] = {0, 1, 2};
  int n = orient_minor<3>(r, cols, s, s + Om<3>::len);
  return -expansion_sign(n, s);
}

template <int D, int LW>
GG_HD inline int lifted_det_sign(const double* const* r, const double* const* lift,
                                 const int* liftlen, double* s) {
  const int cols[3] = {0, 1, 2};
  int n = lifted_minor<D, LW>(r, cols, lift, liftlen, s, s + Lm<D, LW>::len);
  return expansion_sign(n, s);
}

GG_HD inline int incircle_exact(const double* a, const double* b, const double* c, const double* d,
                                double* s) {
  const double* r[4] = {a, b, c, d};
  SquareLifts<4, 2> l(r);
  return lifted_det_sign<2, 4>(r, l.p, l.len, s);
}
GG_HD inline int insphere_exact(const double* a, const double* b, const double* c, const double* d,
                                const double* e, double* s) {
  const double* r[5] = {a, b, c, d, e};
  SquareLifts<5, 3> l(r);
  return -lifted_det_sign<3, 6>(r, l.p, l.len, s);
}
GG_HD inline int orient4d_exact(const double* a, const double* b, const double* c, const double* d,
                                const double* e, double* s) {
  const double* r[5] = {a, b, c, d, e};
  const double* l[5];
  int ll[5];
  for (int i = 0; i < 5; ++i) {
    l[i] = r[i] + 3;
    ll[i] = r[i][3] != 0.0 ? 1 : 0;
  }
  return lifted_det_sign<3, 1>(r, l, ll, s);
}

// ---- tier 3: exact arithmetic on the translated matrix (translated.hpp) ----
GG_HD inline int orient3d_translated(const double* a, const double* b, const double* c,
                                     const double* d, double* s) {
  const double* p[3] = {a, b, c};
  double h[3][3];
  const bool ex = translate<3, 3, 3>(p, d, h);
  const int n = det3_plain(h[0], h[1], h[2], s, s + kMinor3Len);
  double det = 0.0, perm = 0.0;
  if (!ex) orient3d_terms(a, b, c, d, det, perm);
  const int r = judge(ex, n, s, perm, kOrient3dBoundB);
  return r == kUndecided ? r : -r;  // orient3d = -det[a-d; b-d; c-d]
}
GG_HD inline int incircle_translated(const double* a, const double* b, const double* c,
                                     const double* d, double* s) {
  const double* p[3] = {a, b, c};
  double h[3][2], w[3][4];
  const bool ex = translate<3, 2, 2>(p, d, h);
  const double* l[3] = {w[0], w[1], w[2]};
  int ll[3];
  for (int i = 0; i < 3; ++i) ll[i] = square_lift<2>(h[i], w[i]);
  const int n = det_lifted<3, 4>(h, l, ll, s);
  double det = 0.0, perm = 0.0;
  if (!ex) incircle_terms(a, b, c, d, det, perm);
  return judge(ex, n, s, perm, kIncircleBoundB);
}
GG_HD inline int insphere_translated(const double* a, const double* b, const double* c,
                                     const double* d, const double* e, double* s) {
  const double* p[4] = {a, b, c, d};
  double h[4][3], w[4][6];
  const bool ex = translate<4, 3, 3>(p, e, h);
  const double* l[4] = {w[0], w[1], w[2], w[3]};
  int ll[4];
  for (int i = 0; i < 4; ++i) ll[i] = square_lift<3>(h[i], w[i]);
  const int n = det_lifted<4, 6>(h, l, ll, s);
  double det = 0.0, perm = 0.0;
  if (!ex)
    det4_translated(a, b, c, d, e, lift3(a, e), lift3(b, e), lift3(c, e), lift3(d, e), det, perm);
  const int r = judge(ex, n, s, perm, kInsphereBoundB);
  return r == kUndecided ? r : -r;  // insphere = -det(M)
}
// No published second-stage bound covers a free fourth column: exact differences or undecided.
GG_HD inline int orient4d_translated(const double* a, const double* b, const double* c,
                                     const double* d, const double* e, double* s) {
  const double* p[4] = {a, b, c, d};
  double h[4][4];
  if (!translate<4, 4, 4>(p, e, h)) return kUndecided;
  double r[4][3];
  const double* l[4] = {&h[0][3], &h[1][3], &h[2][3], &h[3][3]};
  int ll[4];
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) r[i][k] = h[i][k];
    ll[i] = h[i][3] != 0.0 ? 1 : 0;
  }
  return expansion_sign(det_lifted<4, 1>(r, l, ll, s), s);  // orient4d = det(M)
}

// ---- tiers 1-3 (scratch: k*MidScratch); kUndecided leaves the rest to *_exact ----
// orient3d's and incircle's: the filter, whole numbers, then the translated expansion.
#define GG_MID_OF_FOUR(P)                                                                      \
  GG_HD inline int P##_mid(const double* a, const double* b, const double* c, const double* d, \
                           double* s) {                                                        \
    if (int r = P##_fast(a, b, c, d)) return r;                                                \
    int si;                                                                                    \
    if (P##_int(a, b, c, d, si)) return si;                                                    \
    return P##_translated(a, b, c, d, s);                                                      \
  }
GG_MID_OF_FOUR(orient3d)
GG_MID_OF_FOUR(incircle)
#undef GG_MID_OF_FOUR
GG_HD inline int insphere_mid(const double* a, const double* b, const double* c, const double* d,
                              const double* e, double* s) {
  if (int r = insphere_fast(a, b, c, d, e)) return r;
  int si;
  if (insphere_int(a, b, c, d, e, si)) return si;
  if (int r = insphere_dw(a, b, c, d, e)) return r;
  return insphere_translated(a, b, c, d, e, s);
}
GG_HD inline int orient4d_mid(const double* a, const double* b, const double* c, const double* d,
                              const double* e, double* s) {
  if (int r = orient4d_fast(a, b, c, d, e)) return r;
  return orient4d_translated(a, b, c, d, e, s);
}

// ---- adaptive: every tier ----
GG_HD inline int orient2d(const double* a, const double* b, const double* c, double* s) {
  int r = orient2d_fast(a, b, c);
  return r ? r : orient2d_exact(a, b, c, s);
}
GG_HD inline int orient3d(const double* a, const double* b, const double* c, const double* d,
                          double* s) {
  int r = orient3d_mid(a, b, c, d, s);
  return r != kUndecided ? r : orient3d_exact(a, b, c, d, s);
}
GG_HD inline int incircle(const double* a, const double* b, const double* c, const double* d,
                          double* s) {
  int r = incircle_mid(a, b, c, d, s);
  return r != kUndecided ? r : incircle_exact(a, b, c, d, s);
}
GG_HD inline int insphere(const double* a, const double* b, const double* c, const double* d,
                          const double* e, double* s) {
  int r = insphere_mid(a, b, c, d, e, s);
  return r != kUndecided ? r : insphere_exact(a, b, c, d, e, s);
}
GG_HD inline int orient4d(const double* a, const double* b, const double* c, const double* d,
                          const double* e, double* s) {
  int r = orient4d_mid(a, b, c, d, e, s);
  return r != kUndecided ? r : orient4d_exact(a, b, c, d, e, s);
}
GG_HD inline int orient4d_lifted(const double* a, const double* b, const double* c, const double* d,
                                 const double* e, double* s) {
  return -insphere(a, b, c, d, e, s);
}

// ---- simulation of simplicity (indices must be distinct) ----
// Each predicate P's entries with SoS chain the same three steps: P_mid (tiers 1-3) or P_exact
// (tier 4), then P_tie (SoS) on an exact zero; P_sos runs P_sos_mid and, where tier 3 could not
// tell, P_sos_last. GG_SOS_CHAIN4 and GG_SOS_CHAIN5 write them for four and five points.
#define GG_SOS_STEP(P, STEP, FIRST, PARAMS, POINTS, ALL) \
  GG_HD inline int P##_sos_##STEP PARAMS {               \
    const int r = P##_##FIRST POINTS;                    \
    return r != 0 ? r : P##_tie ALL;                     \
  }
#define GG_SOS_CHAIN(P, PARAMS, POINTS, ALL)       \
  GG_SOS_STEP(P, mid, mid, PARAMS, POINTS, ALL)    \
  GG_SOS_STEP(P, last, exact, PARAMS, POINTS, ALL) \
  GG_HD inline int P##_sos PARAMS {                \
    const int r = P##_sos_mid ALL;                 \
    return r != kUndecided ? r : P##_sos_last ALL; \
  }
#define GG_SOS_CHAIN4(P)                                                                   \
  GG_SOS_CHAIN(P,                                                                          \
               (const double* a, int ia, const double* b, int ib, const double* c, int ic, \
                const double* d, int id, double* s),                                       \
               (a, b, c, d, s), (a, ia, b, ib, c, ic, d, id, s))
#define GG_SOS_CHAIN5(P)                                                                   \
  GG_SOS_CHAIN(P,                                                                          \
               (const double* a, int ia, const double* b, int ib, const double* c, int ic, \
                const double* d, int id, const double* e, int ie, double* s),              \
               (a, b, c, d, e, s), (a, ia, b, ib, c, ic, d, id, e, ie, s))

// Each *_sos_mid returns the sign, resolving an exact zero by SoS, or kUndecided when tier 3
// could not tell; *_sos_last finishes such a test (tier 4, then SoS on a zero).
GG_HD inline int orient2d_sos(const double* a, int ia, const double* b, int ib, const double* c,
                              int ic, double* s) {
  if (int r = orient2d(a, b, c, s)) return r;
  const double* r[3] = {a, b, c};
  int idx[3] = {ia, ib, ic};
  std::uint32_t from;
  if (const int f =
          sos_first_point_terms<3, 2>(r, ExpansionMinors<2, 0>{r, nullptr, nullptr, s}, from))
    return f;
  int co[3];
  int parity = sort_rows<3, 2>(r, idx, nullptr, nullptr, co);
  return parity * sos_resolve<2, 0>(r, nullptr, nullptr, s, co, from);
}

// The ties of whole-number points (integer.hpp's bounds) are resolved in integers: the same
// terms as the expansions give, with no scratch (tiers 1-2 with SoS: *_sos_quick below).
// The rows as whole numbers, with their lifts |p|^2.
template <int N>
GG_HD inline void int_rows(const double* const* r, long long (*p)[3], long long* w) {
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < 3; ++k) p[i][k] = (long long)(r[i][k]);
    w[i] = p[i][0] * p[i][0] + p[i][1] * p[i][1] + p[i][2] * p[i][2];
  }
}
// N = 5: in-sphere (lifted); N = 4: orientation.
template <int N>
GG_HD inline int sos_int(const double* const* pts, const int* ids, int sign_factor) {
  constexpr bool kLift = N == 5;
  long long p[N][3], w[N];
  int_rows<N>(pts, p, w);
  // the first terms on the rows as given (sos.hpp: no sort), nearly always enough
  int first;
  std::uint32_t from = sos_past_first_terms<3, 6>();  // (the lift terms are always all taken)
  if constexpr (kLift)
    first = sos_lift_terms<5, 3>(pts, ids, IntMinors{p, w});
  else
    first = sos_first_point_terms<4, 3>(pts, IntMinors{p, w}, from);
  if (first != 0) return sign_factor * first;
  const double* r[N];
  int idx[N];
  for (int i = 0; i < N; ++i) r[i] = pts[i], idx[i] = ids[i];
  int co[N];
  const int parity = sort_rows<N, 3>(r, idx, nullptr, nullptr, co);
  int_rows<N>(r, p, w);  // (in the sorted order)
  if constexpr (kLift)
    return sign_factor * parity * sos_resolve_by<3, 6>(IntMinors{p, w}, co, from);
  else
    return sign_factor * parity * sos_resolve_by<3, 0>(IntMinors{p, nullptr}, co, from);
}

GG_HD inline int orient3d_tie(const double* a, int ia, const double* b, int ib, const double* c,
                              int ic, const double* d, int id, double* s) {
  const double* r[4] = {a, b, c, d};
  int idx[4] = {ia, ib, ic, id};
  if (all_small_integers<4, 3>(r, kIntLimitOrient3d)) return sos_int<4>(r, idx, -1);
  std::uint32_t from;
  if (const int f =
          sos_first_point_terms<4, 3>(r, ExpansionMinors<3, 0>{r, nullptr, nullptr, s}, from))
    return -f;
  int co[4];
  int parity = sort_rows<4, 3>(r, idx, nullptr, nullptr, co);
  return -parity * sos_resolve<3, 0>(r, nullptr, nullptr, s, co, from);
}
// orient3d with SoS without scratch: the sign, or kUndecided where the filter cannot tell and
// the points are not small whole numbers (then orient3d_sos, with scratch, must).
GG_HD inline int orient3d_sos_quick(const double* a, int ia, const double* b, int ib,
                                    const double* c, int ic, const double* d, int id) {
  if (int r = orient3d_fast(a, b, c, d)) return r;
  int si;
  if (!orient3d_int(a, b, c, d, si)) return kUndecided;
  if (si) return si;
  const double* r[4] = {a, b, c, d};
  const int idx[4] = {ia, ib, ic, id};
  return sos_int<4>(r, idx, -1);
}
GG_SOS_CHAIN4(orient3d)

GG_HD inline int incircle_tie(const double* a, int ia, const double* b, int ib, const double* c,
                              int ic, const double* d, int id, double* s) {
  const double* r[4] = {a, b, c, d};
  int idx[4] = {ia, ib, ic, id};
  if (const int f = sos_lift_terms<4, 2>(r, idx, ExpansionMinors<2, 4>{r, nullptr, nullptr, s}))
    return f;
  SquareLifts<4, 2> l(r);
  int co[4];
  int parity = sort_rows<4, 2>(r, idx, l.p, l.len, co);
  return parity * sos_resolve<2, 4>(r, l.p, l.len, s, co, sos_past_first_terms<2, 4>());
}
GG_SOS_CHAIN4(incircle)

GG_HD inline int insphere_tie(const double* a, int ia, const double* b, int ib, const double* c,
                              int ic, const double* d, int id, const double* e, int ie, double* s) {
  const double* r[5] = {a, b, c, d, e};
  int idx[5] = {ia, ib, ic, id, ie};
  if (all_small_integers<5, 3>(r, kIntLimitInsphere)) return sos_int<5>(r, idx, -1);
  if (const int f = sos_lift_terms<5, 3>(r, idx, ExpansionMinors<3, 6>{r, nullptr, nullptr, s}))
    return -f;
  SquareLifts<5, 3> l(r);
  int co[5];
  int parity = sort_rows<5, 3>(r, idx, l.p, l.len, co);
  return -parity * sos_resolve<3, 6>(r, l.p, l.len, s, co, sos_past_first_terms<3, 6>());
}
// insphere with SoS without scratch, as orient3d_sos_quick.
GG_HD inline int insphere_sos_quick(const double* a, int ia, const double* b, int ib,
                                    const double* c, int ic, const double* d, int id,
                                    const double* e, int ie) {
  if (int r = insphere_fast(a, b, c, d, e)) return r;
  int si;
  if (!insphere_int(a, b, c, d, e, si)) {
    const int r = insphere_dw(a, b, c, d, e);
    return r ? r : kUndecided;
  }
  if (si) return si;
  const double* r[5] = {a, b, c, d, e};
  const int idx[5] = {ia, ib, ic, id, ie};
  return sos_int<5>(r, idx, -1);
}
GG_SOS_CHAIN5(insphere)

GG_HD inline int orient4d_tie(const double* a, int ia, const double* b, int ib, const double* c,
                              int ic, const double* d, int id, const double* e, int ie, double* s) {
  const double* r[5] = {a, b, c, d, e};
  int idx[5] = {ia, ib, ic, id, ie};
  const double* l[5];
  int ll[5];
  for (int i = 0; i < 5; ++i) {
    l[i] = r[i] + 3;
    ll[i] = r[i][3] != 0.0 ? 1 : 0;
  }
  int co[5];
  int parity = sort_rows<5, 4>(r, idx, l, ll, co);
  return parity * sos_resolve<3, 1>(r, l, ll, s, co);
}
GG_SOS_CHAIN5(orient4d)
GG_HD inline int orient4d_lifted_sos(const double* a, int ia, const double* b, int ib,
                                     const double* c, int ic, const double* d, int id,
                                     const double* e, int ie, double* s) {
  return -insphere_sos(a, ia, b, ib, c, ic, d, id, e, ie, s);
}

#undef GG_SOS_CHAIN5
#undef GG_SOS_CHAIN4
#undef GG_SOS_CHAIN
#undef GG_SOS_STEP

}  // namespace gpugeom::pred
