// Predicates through the split fast/exact pass on an executor (EXEC, SUITE defined by the
// includer): on CUDA this runs every predicate, exact and SoS stages included, in device code
// and compares with the host evaluation of the same inputs.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "cases.hpp"
#include "predicates/predicates.hpp"
#include "exec/split_pass.hpp"

namespace {
using namespace gpugeom;

struct Run {
  std::vector<std::int8_t> signs;
  std::int64_t exact = 0, last = 0;
};

// kind: 0 orient2d 1 orient3d 2 incircle 3 insphere 4 orient4d; sos adds indices 3*t+j.
// tiers 2: filter, then the whole adaptive predicate; 3: filter, the *_mid stages on small
// slots, then the *_exact / *_sos_last stage on what they leave.
template <int kind, bool sos, int tiers = 2>
Run evaluate(EXEC& ex, const gg_test::Tuples& t) {
  const std::int64_t n = std::int64_t(t.size());
  auto dv = ex.template alloc<double>(t.v.size());
  ex.from_host(t.v.data(), std::int64_t(t.v.size()), dv.data());
  auto out = ex.template alloc<std::int8_t>(n);
  ex.fill(out.data(), n, std::int8_t(99));
  const double* v = dv.data();
  const int k = t.k, st = t.stride;
  auto P = [=] GG_HD(std::int64_t i, int j) { return v + (i * k + j) * st; };
  auto I = [=] GG_HD(std::int64_t i, int j) { return int(i * k + (j * 7) % k); };
  auto fast = GG_LAMBDA(std::int64_t i)->int {
    if (kind == 0) return pred::orient2d_fast(P(i, 0), P(i, 1), P(i, 2));
    if (kind == 1) return pred::orient3d_fast(P(i, 0), P(i, 1), P(i, 2), P(i, 3));
    if (kind == 2) return pred::incircle_fast(P(i, 0), P(i, 1), P(i, 2), P(i, 3));
    if (kind == 3) return pred::insphere_fast(P(i, 0), P(i, 1), P(i, 2), P(i, 3), P(i, 4));
    return pred::orient4d_fast(P(i, 0), P(i, 1), P(i, 2), P(i, 3), P(i, 4));
  };
  auto exact = GG_LAMBDA(std::int64_t i, double* s)->int {
    if (!sos) {
      if (kind == 0) return pred::orient2d_exact(P(i, 0), P(i, 1), P(i, 2), s);
      if (kind == 1) return pred::orient3d_exact(P(i, 0), P(i, 1), P(i, 2), P(i, 3), s);
      if (kind == 2) return pred::incircle_exact(P(i, 0), P(i, 1), P(i, 2), P(i, 3), s);
      if (kind == 3) return pred::insphere_exact(P(i, 0), P(i, 1), P(i, 2), P(i, 3), P(i, 4), s);
      return pred::orient4d_exact(P(i, 0), P(i, 1), P(i, 2), P(i, 3), P(i, 4), s);
    }
    if (kind == 0)
      return pred::orient2d_sos(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), s);
    if (kind == 1)
      return pred::orient3d_sos(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                I(i, 3), s);
    if (kind == 2)
      return pred::incircle_sos(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                I(i, 3), s);
    if (kind == 3)
      return pred::insphere_sos(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                I(i, 3), P(i, 4), I(i, 4), s);
    return pred::orient4d_sos(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                              I(i, 3), P(i, 4), I(i, 4), s);
  };
  constexpr int scratch = kind == 0   ? pred::kOrient2dScratch
                          : kind == 1 ? pred::kOrient3dScratch
                          : kind == 2 ? pred::kIncircleScratch
                          : kind == 3 ? pred::kInsphereScratch
                                      : pred::kOrient4dScratch;
  Run r;
  if constexpr (tiers == 2) {
    r.exact = split_pass(ex, n, out.data(), fast, exact, scratch).exact_items;
  } else {
    static_assert(kind != 0, "orient2d has no middle tier");
    auto mid = GG_LAMBDA(std::int64_t i, double* s)->int {
      if (!sos) {
        if (kind == 1) return pred::orient3d_mid(P(i, 0), P(i, 1), P(i, 2), P(i, 3), s);
        if (kind == 2) return pred::incircle_mid(P(i, 0), P(i, 1), P(i, 2), P(i, 3), s);
        if (kind == 3) return pred::insphere_mid(P(i, 0), P(i, 1), P(i, 2), P(i, 3), P(i, 4), s);
        return pred::orient4d_mid(P(i, 0), P(i, 1), P(i, 2), P(i, 3), P(i, 4), s);
      }
      if (kind == 1)
        return pred::orient3d_sos_mid(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                      I(i, 3), s);
      if (kind == 2)
        return pred::incircle_sos_mid(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                      I(i, 3), s);
      if (kind == 3)
        return pred::insphere_sos_mid(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                      I(i, 3), P(i, 4), I(i, 4), s);
      return pred::orient4d_sos_mid(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                    I(i, 3), P(i, 4), I(i, 4), s);
    };
    auto last = GG_LAMBDA(std::int64_t i, double* s)->int {
      if (!sos) return exact(i, s);  // the *_exact stages
      if (kind == 1)
        return pred::orient3d_sos_last(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2),
                                       P(i, 3), I(i, 3), s);
      if (kind == 2)
        return pred::incircle_sos_last(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2),
                                       P(i, 3), I(i, 3), s);
      if (kind == 3)
        return pred::insphere_sos_last(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2),
                                       P(i, 3), I(i, 3), P(i, 4), I(i, 4), s);
      return pred::orient4d_sos_last(P(i, 0), I(i, 0), P(i, 1), I(i, 1), P(i, 2), I(i, 2), P(i, 3),
                                     I(i, 3), P(i, 4), I(i, 4), s);
    };
    constexpr int mid_scratch =
        kind == 1   ? (sos ? pred::kOrient3dSosMidScratch : pred::kOrient3dMidScratch)
        : kind == 2 ? (sos ? pred::kIncircleSosMidScratch : pred::kIncircleMidScratch)
        : kind == 3 ? (sos ? pred::kInsphereSosMidScratch : pred::kInsphereMidScratch)
                    : (sos ? pred::kOrient4dSosMidScratch : pred::kOrient4dMidScratch);
    const SplitPassResult res =
        split_pass(ex, n, out.data(), fast, mid, mid_scratch, last, scratch);
    r.exact = res.exact_items;
    r.last = res.last_items;
  }
  r.signs.resize(n);
  ex.to_host(out.data(), n, r.signs.data());
  return r;
}

// The same predicates evaluated directly on the host.
template <int kind, bool sos>
std::vector<std::int8_t> host_reference(const gg_test::Tuples& t) {
  std::vector<double> s(pred::kInsphereScratch + pred::kOrient4dScratch);
  std::vector<std::int8_t> r(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    auto P = [&](int j) { return t.at(i, j); };
    auto I = [&](int j) { return int(i * t.k + (j * 7) % t.k); };
    int v;
    if (!sos) {
      if (kind == 0)
        v = pred::orient2d(P(0), P(1), P(2), s.data());
      else if (kind == 1)
        v = pred::orient3d(P(0), P(1), P(2), P(3), s.data());
      else if (kind == 2)
        v = pred::incircle(P(0), P(1), P(2), P(3), s.data());
      else if (kind == 3)
        v = pred::insphere(P(0), P(1), P(2), P(3), P(4), s.data());
      else
        v = pred::orient4d(P(0), P(1), P(2), P(3), P(4), s.data());
    } else {
      if (kind == 0)
        v = pred::orient2d_sos(P(0), I(0), P(1), I(1), P(2), I(2), s.data());
      else if (kind == 1)
        v = pred::orient3d_sos(P(0), I(0), P(1), I(1), P(2), I(2), P(3), I(3), s.data());
      else if (kind == 2)
        v = pred::incircle_sos(P(0), I(0), P(1), I(1), P(2), I(2), P(3), I(3), s.data());
      else if (kind == 3)
        v = pred::insphere_sos(P(0), I(0), P(1), I(1), P(2), I(2), P(3), I(3), P(4), I(4),
                               s.data());
      else
        v = pred::orient4d_sos(P(0), I(0), P(1), I(1), P(2), I(2), P(3), I(3), P(4), I(4),
                               s.data());
    }
    r[i] = std::int8_t(v);
  }
  return r;
}

// GG_TEST_TUPLES shrinks the batches (e.g. under compute-sanitizer, which is much slower).
int tuples_per_batch() {
  const char* e = std::getenv("GG_TEST_TUPLES");
  return e ? std::max(100, std::atoi(e)) : 20000;
}

// In-sphere tuples that only the last tier decides: five points on the plane z = x (so the
// determinant is exactly 0), four of them near 2^40 and the fifth near 0, so that no difference
// is exact. (Nearly cospherical points no longer reach the last tier: insphere_dw decides them.)
void add_coplanar_mixed(gg_test::Tuples& t, double scale) {
  std::mt19937_64 g(7);
  for (std::size_t c = 0; c < t.size(); c += 10)
    for (int j = 0; j < t.k; ++j) {
      double* p = t.v.data() + (c * t.k + j) * t.stride;
      const double m = double(g() % 4096), r = double(g() % 4096) - 2048;
      p[0] = j < 4 ? (0x1p40 + m) * scale : m * 0x1p-20 * scale;
      p[1] = (j < 4 ? r : r * 0x1p-20) * scale;
      p[2] = p[0];
    }
}

template <int kind, bool sos, int tiers = 2>
void compare(int dim, int k, bool sphere, int stride = 0) {
  EXEC ex;
  const int count = tuples_per_batch();
  for (double scale : {1.0, 0x1p-90, 0x1p90, 3e25}) {
    auto t = gg_test::make_tuples(dim, k, count, 100 + kind, scale, sphere, stride);
    if (kind == 3) add_coplanar_mixed(t, scale);
    Run r = evaluate<kind, sos, tiers>(ex, t);
    auto ref = host_reference<kind, sos>(t);
    EXPECT_GT(r.exact, count / 20) << "the exact pass was hardly exercised";
    if (tiers == 3) {  // the middle tier decides part of it, and leaves some to the last one
      EXPECT_LT(r.last, r.exact) << "scale " << scale;
      if (kind != 4) EXPECT_GT(r.last, 0) << "scale " << scale;
    }
    for (std::size_t i = 0; i < ref.size(); ++i) {
      ASSERT_EQ(int(r.signs[i]), int(ref[i]))
          << "kind " << kind << " sos " << sos << " scale " << scale << " case " << i;
      if (sos) ASSERT_NE(ref[i], 0);
    }
  }
}

TEST(SUITE, Orient2d) {
  compare<0, false>(2, 3, false);
}
TEST(SUITE, Orient3d) {
  compare<1, false>(3, 4, false);
}
TEST(SUITE, Incircle) {
  compare<2, false>(2, 4, true);
}
TEST(SUITE, Insphere) {
  compare<3, false>(3, 5, true);
}
TEST(SUITE, Orient4d) {
  compare<4, false>(3, 5, false, 4);
}
TEST(SUITE, Orient2dSos) {
  compare<0, true>(2, 3, false);
}
TEST(SUITE, Orient3dSos) {
  compare<1, true>(3, 4, false);
}
TEST(SUITE, IncircleSos) {
  compare<2, true>(2, 4, true);
}
TEST(SUITE, InsphereSos) {
  compare<3, true>(3, 5, true);
}
TEST(SUITE, Orient4dSos) {
  compare<4, true>(3, 5, false, 4);
}

// The three-tier pass (GPU-sized middle tier, full expansion on a second list).
TEST(SUITE, Orient3dTiered) {
  compare<1, false, 3>(3, 4, false);
}
TEST(SUITE, IncircleTiered) {
  compare<2, false, 3>(2, 4, true);
}
TEST(SUITE, InsphereTiered) {
  compare<3, false, 3>(3, 5, true);
}
TEST(SUITE, Orient4dTiered) {
  compare<4, false, 3>(3, 5, false, 4);
}
TEST(SUITE, Orient3dSosTiered) {
  compare<1, true, 3>(3, 4, false);
}
TEST(SUITE, IncircleSosTiered) {
  compare<2, true, 3>(2, 4, true);
}
TEST(SUITE, InsphereSosTiered) {
  compare<3, true, 3>(3, 5, true);
}
TEST(SUITE, Orient4dSosTiered) {
  compare<4, true, 3>(3, 5, false, 4);
}

}  // namespace
