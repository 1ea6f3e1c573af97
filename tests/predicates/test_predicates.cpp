// Host tests of the exact predicates against an independent exact evaluator (GMP rationals on
// the same doubles), and of the simulation-of-simplicity sign rules.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "cases.hpp"
#include "predicates/predicates.hpp"

using namespace gpugeom;
using gg_test::make_tuples;

namespace {

std::vector<double> S(pred::kInsphereScratch + pred::kOrient4dScratch);
double* s() {
  return S.data();
}

int mpq_sign(const mpq_class& q) {
  const int s = mpq_sgn(q.get_mpq_t());
  return (s > 0) - (s < 0);
}

// Determinant by Laplace expansion (small n), exact.
mpq_class det(std::vector<std::vector<mpq_class>> m) {
  const std::size_t n = m.size();
  if (n == 1) return m[0][0];
  mpq_class r = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::vector<mpq_class>> sub;
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) sub.push_back(std::vector<mpq_class>(m[j].begin() + 1, m[j].end()));
    mpq_class t = m[i][0] * det(sub);
    r += (i % 2) ? -t : t;
  }
  return r;
}
// sign of det[p1-p0; p2-p0; ...] over the first `dim` coordinates (+ lift / 4th coordinate).
int ref_orient(const std::vector<const double*>& p, int dim,
               int lift /*0 none,1 squares,2 coord 3*/) {
  std::vector<std::vector<mpq_class>> m;
  for (std::size_t i = 1; i < p.size(); ++i) {
    std::vector<mpq_class> row;
    for (int d = 0; d < dim; ++d) row.push_back(mpq_class(p[i][d]) - mpq_class(p[0][d]));
    if (lift == 1) {
      mpq_class a = 0, b = 0;
      for (int d = 0; d < dim; ++d)
        a += mpq_class(p[i][d]) * mpq_class(p[i][d]), b += mpq_class(p[0][d]) * mpq_class(p[0][d]);
      row.push_back(a - b);
    }
    if (lift == 2) row.push_back(mpq_class(p[i][3]) - mpq_class(p[0][3]));
    m.push_back(row);
  }
  return mpq_sign(det(m));
}

bool pow2(double s) {
  int e;
  return std::frexp(s, &e) == 0.5;
}

struct Count {
  int exact = 0, zero = 0;
};

class Scales : public ::testing::TestWithParam<double> {};

TEST_P(Scales, Orient2dMatchesRationals) {
  Count c;
  auto t = make_tuples(2, 3, 3000, 7, GetParam(), false);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double *a = t.at(i, 0), *b = t.at(i, 1), *d = t.at(i, 2);
    const int ref = ref_orient({a, b, d}, 2, 0);
    ASSERT_EQ(pred::orient2d(a, b, d, s()), ref) << "case " << i;
    c.exact += pred::orient2d_fast(a, b, d) == 0;
    c.zero += ref == 0;
  }
  EXPECT_GT(c.exact, 100) << "the exact stage was hardly exercised";
  if (pow2(GetParam()))
    EXPECT_GT(c.zero, 10) << "exact degeneracies expected at power-of-two scales";
}

TEST_P(Scales, Orient3dMatchesRationals) {
  Count c;
  auto t = make_tuples(3, 4, 3000, 8, GetParam(), false);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double *a = t.at(i, 0), *b = t.at(i, 1), *d = t.at(i, 2), *e = t.at(i, 3);
    const int ref = ref_orient({a, b, d, e}, 3, 0);
    ASSERT_EQ(pred::orient3d(a, b, d, e, s()), ref) << "case " << i;
    c.exact += pred::orient3d_fast(a, b, d, e) == 0;
    c.zero += ref == 0;
  }
  EXPECT_GT(c.exact, 100);
  if (pow2(GetParam()))
    EXPECT_GT(c.zero, 10) << "exact degeneracies expected at power-of-two scales";
}

TEST_P(Scales, IncircleMatchesRationals) {
  Count c;
  auto t = make_tuples(2, 4, 3000, 9, GetParam(), true);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double *a = t.at(i, 0), *b = t.at(i, 1), *d = t.at(i, 2), *e = t.at(i, 3);
    // incircle = det[[a-e, |a-e|^2]...] = orient3d of lifted points with reversed sign rules:
    // det[b-a; c-a; d-a] (lifted) = -incircle
    const int ref = -ref_orient({a, b, d, e}, 2, 1);
    ASSERT_EQ(pred::incircle(a, b, d, e, s()), ref) << "case " << i;
    c.exact += pred::incircle_fast(a, b, d, e) == 0;
    c.zero += ref == 0;
  }
  EXPECT_GT(c.exact, 100);
  if (pow2(GetParam()))
    EXPECT_GT(c.zero, 10) << "exact degeneracies expected at power-of-two scales";
}

TEST_P(Scales, InsphereMatchesRationals) {
  Count c;
  auto t = make_tuples(3, 5, 2000, 10, GetParam(), true);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double *a = t.at(i, 0), *b = t.at(i, 1), *d = t.at(i, 2), *e = t.at(i, 3),
                 *f = t.at(i, 4);
    // orient4d of lifted points = det[b-a; c-a; d-a; e-a] (lifted) = -insphere
    const int ref = -ref_orient({a, b, d, e, f}, 3, 1);
    ASSERT_EQ(pred::insphere(a, b, d, e, f, s()), ref) << "case " << i;
    ASSERT_EQ(pred::orient4d_lifted(a, b, d, e, f, s()), -ref);
    c.exact += pred::insphere_fast(a, b, d, e, f) == 0;
    c.zero += ref == 0;
  }
  EXPECT_GT(c.exact, 100);
  if (pow2(GetParam()))
    EXPECT_GT(c.zero, 10) << "exact degeneracies expected at power-of-two scales";
}

// The semi-static in-sphere filter is never wrong (the rational sign or 0) on nearly
// cospherical, exactly cospherical and random tuples at every scale, and decides most of the
// random ones the permanent's filter decides (its bound is looser, not useless).
// f(i, points, the rational in-sphere sign) for every tuple of t.
template <class F>
void each_insphere_case(const gg_test::Tuples& t, F f) {
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double* p[5] = {t.at(i, 0), t.at(i, 1), t.at(i, 2), t.at(i, 3), t.at(i, 4)};
    f(i, p, -ref_orient({p[0], p[1], p[2], p[3], p[4]}, 3, 1));
  }
}

TEST_P(Scales, InsphereSemistaticNeverWrong) {
  int sharp = 0, both = 0;
  each_insphere_case(make_tuples(3, 5, 6000, 17, GetParam(), true),
                     [&](std::size_t i, const double* const* p, int ref) {
                       const int st = pred::insphere_semistatic(p[0], p[1], p[2], p[3], p[4]);
                       if (st != 0) ASSERT_EQ(st, ref) << "case " << i;
                       if (i % 3 != 2) return;  // (make_tuples: every third tuple is random)
                       const bool f = pred::insphere_fast(p[0], p[1], p[2], p[3], p[4]) != 0;
                       sharp += f, both += f && st != 0;
                     });
  EXPECT_GT(sharp, 1900);
  EXPECT_GE(both, sharp * 9 / 10);
}

// The double-word in-sphere tier is never wrong (it answers the rational sign or 0) and decides
// nearly all of the points a few ulps off a sphere that the filter cannot (the case it exists
// for: points rounded from a sphere), at every scale where its magnitudes hold.
TEST_P(Scales, InsphereDoubleWordNeverWrong) {
  int hard = 0, decided = 0, zeros = 0;
  each_insphere_case(make_tuples(3, 5, 3000, 16, GetParam(), true),
                     [&](std::size_t i, const double* const* p, int ref) {
                       const int dw = pred::insphere_dw(p[0], p[1], p[2], p[3], p[4]);
                       if (dw != 0) ASSERT_EQ(dw, ref) << "case " << i;
                       zeros += ref == 0 && dw == 0;
                       if (i % 3 == 0 && pred::insphere_fast(p[0], p[1], p[2], p[3], p[4]) == 0)
                         hard++, decided += dw != 0;
                     });
  EXPECT_GT(hard, 500) << "the nearly cospherical cases should defeat the filter";
  if (GetParam() != 0x1p-100)  // (there the differences fall below the tier's range)
    EXPECT_GE(decided, hard - hard / 100) << "of " << hard;
  if (pow2(GetParam())) EXPECT_GT(zeros, 10);
}

// Points rounded from a sphere far from the origin (UTM-like offsets, mm detail) and from tiny
// and huge spheres: the double-word tier agrees with the rationals wherever it answers.
TEST(Predicates, InsphereDoubleWordOnRoundedSpheres) {
  std::mt19937_64 g(21);
  std::uniform_real_distribution<double> U(-1, 1);
  int decided = 0, tried = 0;
  for (double offset : {0.0, 5.0e5, 4.2e6}) {
    for (double radius : {1e-3, 1.0, 1e3}) {
      for (int i = 0; i < 300; ++i) {
        double q[5][3];
        for (auto& p : q) {
          double v[3] = {U(g), U(g), U(g)};
          const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
          for (int k = 0; k < 3; ++k) p[k] = offset + radius * v[k] / l;
        }
        const int ref = -ref_orient({q[0], q[1], q[2], q[3], q[4]}, 3, 1);
        const int dw = pred::insphere_dw(q[0], q[1], q[2], q[3], q[4]);
        if (dw != 0) ASSERT_EQ(dw, ref) << offset << " " << radius << " " << i;
        tried++, decided += dw != 0;
        ASSERT_EQ(pred::insphere(q[0], q[1], q[2], q[3], q[4], s()), ref);
      }
    }
  }
  EXPECT_GT(decided, tried / 2);
}

TEST_P(Scales, Orient4dMatchesRationals) {
  Count c;
  auto t = make_tuples(3, 5, 2000, 11, GetParam(), false, 4);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double *a = t.at(i, 0), *b = t.at(i, 1), *d = t.at(i, 2), *e = t.at(i, 3),
                 *f = t.at(i, 4);
    const int ref = ref_orient({a, b, d, e, f}, 3, 2);
    ASSERT_EQ(pred::orient4d(a, b, d, e, f, s()), ref) << "case " << i;
    c.exact += pred::orient4d_fast(a, b, d, e, f) == 0;
    c.zero += ref == 0;
  }
  EXPECT_GT(c.exact, 100);
  if (pow2(GetParam()))
    EXPECT_GT(c.zero, 10) << "exact degeneracies expected at power-of-two scales";
}

// Powers of two keep integer degeneracies exact; 2^-100 and 2^100 test tiny and huge inputs.
INSTANTIATE_TEST_SUITE_P(Magnitudes, Scales,
                         ::testing::Values(1.0, 0x1p-100, 0x1p100, 1e-30, 3e25));

TEST(Predicates, ExactRange) {
  EXPECT_TRUE(pred::in_exact_range(0.0));
  EXPECT_TRUE(pred::in_exact_range(1e50));
  EXPECT_TRUE(pred::in_exact_range(-1e-40));
  EXPECT_FALSE(pred::in_exact_range(1e60));
  EXPECT_FALSE(pred::in_exact_range(1e-50));
}

// ---- simulation of simplicity ----

template <int K, class F>
void for_each_permutation(F f) {
  std::array<int, K> p;
  for (int i = 0; i < K; ++i) p[i] = i;
  do {
    int parity = 1;
    for (int i = 0; i < K; ++i)
      for (int j = i + 1; j < K; ++j)
        if (p[i] > p[j]) parity = -parity;
    f(p, parity);
  } while (std::next_permutation(p.begin(), p.end()));
}

TEST(Sos, PermutationConsistentAndNeverZero) {
  for (int round = 0; round < 3; ++round) {
    auto t2 = make_tuples(2, 4, 300, 20 + round, 1.0, round == 1);
    auto t3 = make_tuples(3, 5, 200, 30 + round, 1.0, round == 1);
    auto t4 = make_tuples(3, 5, 200, 40 + round, 1.0, false, 4);
    for (std::size_t i = 0; i < t2.size(); ++i) {
      const int ids[4] = {int(i * 4 + 3), int(i * 4), int(i * 4 + 2), int(i * 4 + 1)};
      const double* p[4] = {t2.at(i, 0), t2.at(i, 1), t2.at(i, 2), t2.at(i, 3)};
      const int o = pred::orient2d_sos(p[0], ids[0], p[1], ids[1], p[2], ids[2], s());
      const int ic =
          pred::incircle_sos(p[0], ids[0], p[1], ids[1], p[2], ids[2], p[3], ids[3], s());
      ASSERT_NE(o, 0);
      ASSERT_NE(ic, 0);
      if (int e = pred::orient2d(p[0], p[1], p[2], s())) ASSERT_EQ(o, e);
      if (int e = pred::incircle(p[0], p[1], p[2], p[3], s())) ASSERT_EQ(ic, e);
      for_each_permutation<3>([&](auto q, int par) {
        ASSERT_EQ(
            pred::orient2d_sos(p[q[0]], ids[q[0]], p[q[1]], ids[q[1]], p[q[2]], ids[q[2]], s()),
            par * o);
      });
      for_each_permutation<4>([&](auto q, int par) {
        ASSERT_EQ(pred::incircle_sos(p[q[0]], ids[q[0]], p[q[1]], ids[q[1]], p[q[2]], ids[q[2]],
                                     p[q[3]], ids[q[3]], s()),
                  par * ic);
      });
    }
    for (std::size_t i = 0; i < t3.size(); ++i) {
      const int ids[5] = {int(i * 5 + 4), int(i * 5 + 1), int(i * 5), int(i * 5 + 3),
                          int(i * 5 + 2)};
      const double* p[5] = {t3.at(i, 0), t3.at(i, 1), t3.at(i, 2), t3.at(i, 3), t3.at(i, 4)};
      const double* w[5] = {t4.at(i, 0), t4.at(i, 1), t4.at(i, 2), t4.at(i, 3), t4.at(i, 4)};
      const int o = pred::orient3d_sos(p[0], ids[0], p[1], ids[1], p[2], ids[2], p[3], ids[3], s());
      const int is = pred::insphere_sos(p[0], ids[0], p[1], ids[1], p[2], ids[2], p[3], ids[3],
                                        p[4], ids[4], s());
      const int o4 = pred::orient4d_sos(w[0], ids[0], w[1], ids[1], w[2], ids[2], w[3], ids[3],
                                        w[4], ids[4], s());
      ASSERT_NE(o, 0);
      ASSERT_NE(is, 0);
      ASSERT_NE(o4, 0);
      if (int e = pred::insphere(p[0], p[1], p[2], p[3], p[4], s())) ASSERT_EQ(is, e);
      for_each_permutation<4>([&](auto q, int par) {
        ASSERT_EQ(pred::orient3d_sos(p[q[0]], ids[q[0]], p[q[1]], ids[q[1]], p[q[2]], ids[q[2]],
                                     p[q[3]], ids[q[3]], s()),
                  par * o);
      });
      for_each_permutation<5>([&](auto q, int par) {
        ASSERT_EQ(pred::insphere_sos(p[q[0]], ids[q[0]], p[q[1]], ids[q[1]], p[q[2]], ids[q[2]],
                                     p[q[3]], ids[q[3]], p[q[4]], ids[q[4]], s()),
                  par * is);
        ASSERT_EQ(pred::orient4d_sos(w[q[0]], ids[q[0]], w[q[1]], ids[q[1]], w[q[2]], ids[q[2]],
                                     w[q[3]], ids[q[3]], w[q[4]], ids[q[4]], s()),
                  par * o4);
      });
    }
  }
}

// The first perturbation terms of the lifted tests, derived by hand from the bit order in
// sos.hpp, for inputs given in the lift order (coordinates lexicographically decreasing): they
// pin the scheme down, CGAL's rule included, not only its self-consistency. The indices do not
// matter for distinct points.
TEST(Sos, FirstTermsFollowTheDocumentedOrder) {
  // incircle of cocircular a > b > c > d: orient2d(b, c, d); one swap negates it.
  const double q[4][2] = {{5, 0}, {3, -4}, {0, 5}, {-5, 0}};
  EXPECT_EQ(pred::incircle(q[0], q[1], q[2], q[3], s()), 0);
  EXPECT_EQ(pred::incircle_sos(q[0], 0, q[1], 1, q[2], 2, q[3], 3, s()),
            pred::orient2d(q[1], q[2], q[3], s()));
  EXPECT_EQ(pred::incircle_sos(q[0], 3, q[1], 2, q[2], 1, q[3], 0, s()),
            pred::orient2d(q[1], q[2], q[3], s()));
  EXPECT_EQ(pred::incircle_sos(q[3], 0, q[1], 1, q[2], 2, q[0], 3, s()),
            -pred::orient2d(q[1], q[2], q[3], s()));
  // insphere of cospherical a > b > c > d > e: -orient3d(b, c, d, e). This is CGAL's answer
  // too: its perturbation looks at the lexicographically largest point first (a, the first
  // here) and returns orientation(e, b, c, d) = -orient3d(b, c, d, e).
  const double r[5][3] = {{5, 0, 0}, {3, 4, 0}, {0, 5, 0}, {0, 0, 5}, {0, -3, -4}};
  EXPECT_EQ(pred::insphere(r[0], r[1], r[2], r[3], r[4], s()), 0);
  EXPECT_EQ(pred::insphere_sos(r[0], 0, r[1], 1, r[2], 2, r[3], 3, r[4], 4, s()),
            -pred::orient3d(r[1], r[2], r[3], r[4], s()));
  EXPECT_EQ(pred::insphere_sos(r[0], 4, r[1], 3, r[2], 2, r[3], 1, r[4], 0, s()),
            -pred::orient3d(r[1], r[2], r[3], r[4], s()));
}

// The perturbation depends on the points alone: on small grids (almost every tuple degenerate),
// giving the same distinct points other indices never changes an answer.
TEST(Sos, IndicesDoNotMatterForDistinctPoints) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> u(-2, 2);
  int tested = 0;
  for (int i = 0; i < 4000; ++i) {
    double p[5][4];
    for (auto& x : p)
      for (double& c : x) c = double(u(rng));
    bool distinct = true;  // (in x and y, so also as 2D points)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < j; ++k)
        distinct = distinct && !(p[j][0] == p[k][0] && p[j][1] == p[k][1]);
    if (!distinct) continue;
    ++tested;
    int ia[5], ib[5];
    for (int j = 0; j < 5; ++j) ia[j] = j, ib[j] = int(rng() % 1000) * 5 + (4 - j);
    ASSERT_EQ(pred::orient2d_sos(p[0], ia[0], p[1], ia[1], p[2], ia[2], s()),
              pred::orient2d_sos(p[0], ib[0], p[1], ib[1], p[2], ib[2], s()));
    ASSERT_EQ(pred::incircle_sos(p[0], ia[0], p[1], ia[1], p[2], ia[2], p[3], ia[3], s()),
              pred::incircle_sos(p[0], ib[0], p[1], ib[1], p[2], ib[2], p[3], ib[3], s()));
    ASSERT_EQ(pred::orient3d_sos(p[0], ia[0], p[1], ia[1], p[2], ia[2], p[3], ia[3], s()),
              pred::orient3d_sos(p[0], ib[0], p[1], ib[1], p[2], ib[2], p[3], ib[3], s()));
    ASSERT_EQ(
        pred::insphere_sos(p[0], ia[0], p[1], ia[1], p[2], ia[2], p[3], ia[3], p[4], ia[4], s()),
        pred::insphere_sos(p[0], ib[0], p[1], ib[1], p[2], ib[2], p[3], ib[3], p[4], ib[4], s()));
    ASSERT_EQ(
        pred::orient4d_sos(p[0], ia[0], p[1], ia[1], p[2], ia[2], p[3], ia[3], p[4], ia[4], s()),
        pred::orient4d_sos(p[0], ib[0], p[1], ib[1], p[2], ib[2], p[3], ib[3], p[4], ib[4], s()));
  }
  EXPECT_GT(tested, 1000);
}

// The sorted loop alone (sos.hpp's sos_resolve over the rows sort_rows orders), times the sign
// each predicate's tie gives it: the reference for the first terms the predicates now take
// on the rows as given.
template <int N, int D, int LW>
int sorted_loop(const double* const* pts, const int* ids, int sign_factor) {
  const double* r[N];
  int idx[N], co[N];
  for (int i = 0; i < N; ++i) r[i] = pts[i], idx[i] = ids[i];
  if constexpr (LW > 0) {
    exact::SquareLifts<N, D> l(r);
    const int parity = exact::sort_rows<N, D>(r, idx, l.p, l.len, co);
    return sign_factor * parity * exact::sos_resolve<D, LW>(r, l.p, l.len, s(), co);
  } else {
    const int parity = exact::sort_rows<N, D>(r, idx, nullptr, nullptr, co);
    return sign_factor * parity * exact::sos_resolve<D, 0>(r, nullptr, nullptr, s(), co);
  }
}

// The first terms taken without sorting (the cofactors of the rows as given) agree with the
// sorted loop on ties: tiny grids, where most tuples are degenerate and many lie on one plane or
// line (so the shortcut declines and the loop decides), in whole numbers (the integer tier) and
// halves (the expansions), with the indices scrambled.
TEST(Sos, FirstTermsWithoutSortingMatchTheSortedLoop) {
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<int> u(-1, 1);
  int ties[4] = {};
  for (double scale : {1.0, 0.5}) {
    for (int i = 0; i < 20000; ++i) {
      double q[5][3];
      for (auto& x : q)
        for (double& c : x) c = scale * u(rng);
      const double* r[5] = {q[0], q[1], q[2], q[3], q[4]};
      int ids[5];
      for (int j = 0; j < 5; ++j) ids[j] = int(rng() % 1000) * 5 + j;
      auto distinct = [&](int n, int dim) {
        for (int j = 0; j < n; ++j)
          for (int k = 0; k < j; ++k)
            if (std::equal(q[j], q[j] + dim, q[k])) return false;
        return true;
      };
      if (distinct(3, 2) && pred::orient2d(r[0], r[1], r[2], s()) == 0) {
        ++ties[0];
        ASSERT_EQ(pred::orient2d_sos(r[0], ids[0], r[1], ids[1], r[2], ids[2], s()),
                  (sorted_loop<3, 2, 0>(r, ids, 1)));
      }
      if (distinct(4, 2) && pred::incircle(r[0], r[1], r[2], r[3], s()) == 0) {
        ++ties[1];
        ASSERT_EQ(pred::incircle_sos(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3], ids[3], s()),
                  (sorted_loop<4, 2, 4>(r, ids, 1)));
      }
      if (distinct(4, 3) && pred::orient3d(r[0], r[1], r[2], r[3], s()) == 0) {
        ++ties[2];
        const int want = sorted_loop<4, 3, 0>(r, ids, -1);
        ASSERT_EQ(pred::orient3d_sos(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3], ids[3], s()),
                  want);
        if (scale == 1.0)
          ASSERT_EQ(
              pred::orient3d_sos_quick(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3], ids[3]),
              want);
      }
      if (distinct(5, 3) && pred::insphere(r[0], r[1], r[2], r[3], r[4], s()) == 0) {
        ++ties[3];
        const int want = sorted_loop<5, 3, 6>(r, ids, -1);
        ASSERT_EQ(pred::insphere_sos(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3], ids[3], r[4],
                                     ids[4], s()),
                  want);
        if (scale == 1.0)
          ASSERT_EQ(pred::insphere_sos_quick(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3], ids[3],
                                             r[4], ids[4]),
                    want);
      }
    }
  }
  for (int t : ties) EXPECT_GT(t, 1000);
}

// Duplicated points (same coordinates, different indices) still get a consistent, nonzero answer.
TEST(Sos, DuplicatesAreOrderedByIndex) {
  const double a[3] = {1, 2, 3};
  EXPECT_NE(pred::orient3d_sos(a, 0, a, 1, a, 2, a, 3, s()), 0);
  EXPECT_EQ(pred::orient3d_sos(a, 0, a, 1, a, 2, a, 3, s()),
            -pred::orient3d_sos(a, 1, a, 0, a, 2, a, 3, s()));
}

}  // namespace

// The 128-bit integer stage agrees with the expansion arithmetic on whole-number inputs, from
// tiny grids (mostly cocircular) up to the largest magnitude it accepts, and declines beyond.
TEST(Incircle, IntegerStageMatchesExact) {
  std::mt19937_64 rng(99);
  for (double range : {3.0, 1000.0, 268435456.0}) {
    std::uniform_int_distribution<long long> u(-(long long)range, (long long)range);
    for (int i = 0; i < 20000; ++i) {
      double q[4][2];
      for (auto& p : q) p[0] = double(u(rng)), p[1] = double(u(rng));
      int si = 7;
      ASSERT_TRUE(pred::incircle_int(q[0], q[1], q[2], q[3], si));
      ASSERT_EQ(si, pred::incircle_exact(q[0], q[1], q[2], q[3], s())) << "range " << range;
    }
  }
  const double big[2] = {268435457.0, 0}, half[2] = {0.5, 0}, o[2] = {0, 0}, x[2] = {1, 0};
  int si = 7;
  EXPECT_FALSE(pred::incircle_int(big, o, x, o, si));
  EXPECT_FALSE(pred::incircle_int(half, o, x, o, si));
  EXPECT_EQ(si, 7);
}

// The 3D integer stages against GMP on whole-number inputs, from tiny grids (mostly degenerate)
// up to the largest magnitude each accepts, and declining beyond it or on fractions.
TEST(IntegerStages, MatchRationals) {
  std::mt19937_64 rng(7);
  int zeros = 0;
  for (double limit : {exact::kIntLimitOrient3d, exact::kIntLimitInsphere}) {
    const bool sphere = limit == exact::kIntLimitInsphere;
    for (double range : {2.0, 1000.0, limit}) {
      std::uniform_int_distribution<long long> u(-(long long)range, (long long)range);
      for (int i = 0; i < 4000; ++i) {
        double q[5][3];
        for (auto& p : q)
          for (double& c : p) c = double(u(rng));
        if (i % 4 == 0)  // extremes, where overflow would show
          for (auto& p : q)
            for (double& c : p) c = (rng() & 1) ? range : -range;
        int si = 7;
        if (sphere) {
          ASSERT_TRUE(pred::insphere_int(q[0], q[1], q[2], q[3], q[4], si));
          ASSERT_EQ(si, -ref_orient({q[0], q[1], q[2], q[3], q[4]}, 3, 1)) << "range " << range;
        } else {
          ASSERT_TRUE(pred::orient3d_int(q[0], q[1], q[2], q[3], si));
          ASSERT_EQ(si, ref_orient({q[0], q[1], q[2], q[3]}, 3, 0)) << "range " << range;
        }
        zeros += si == 0;
      }
    }
    const double over[3] = {limit + 1, 0, 0}, frac[3] = {0.5, 0, 0}, o[3] = {0, 0, 0};
    int si = 7;
    EXPECT_FALSE(pred::orient3d_int(o, o, o, sphere ? frac : over, si));
    EXPECT_FALSE(pred::insphere_int(o, o, o, o, sphere ? over : frac, si));
    EXPECT_EQ(si, 7);
  }
  EXPECT_GT(zeros, 500) << "small grids should give many exact degeneracies";
}

// The integer ties take the same perturbation terms as the expansions, so they give the same
// answers: compared term sequence against term sequence on small grids (almost every five
// points degenerate, so later terms are reached) and at the largest magnitudes accepted; the
// scratch-free predicates agree with the full ones and decline fractions.
TEST(IntegerStages, SosTiesMatchExpansions) {
  std::mt19937_64 rng(11);
  for (double range : {1.0, 2.0, 1000.0, exact::kIntLimitInsphere, exact::kIntLimitOrient3d}) {
    const bool lifted = range <= exact::kIntLimitInsphere;
    std::uniform_int_distribution<long long> u(-(long long)range, (long long)range);
    for (int i = 0; i < 3000; ++i) {
      double q[5][3];
      for (auto& p : q)
        for (double& c : p) c = double(u(rng));
      if (i % 5 == 0)
        for (auto& p : q)
          for (double& c : p) c = (rng() & 1) ? range : -range;
      const double* r[5] = {q[0], q[1], q[2], q[3], q[4]};
      long long p[5][3], w[5];
      for (int k = 0; k < 5; ++k) {
        for (int c = 0; c < 3; ++c) p[k][c] = (long long)q[k][c];
        w[k] = p[k][0] * p[k][0] + p[k][1] * p[k][1] + p[k][2] * p[k][2];
      }
      ASSERT_EQ((exact::sos_resolve_by<3, 0>(exact::IntMinors{p, nullptr})),
                (exact::sos_resolve<3, 0>(r, nullptr, nullptr, s())))
          << "range " << range;
      const int ids[5] = {3, 0, 4, 1, 2};
      const int o =
          pred::orient3d_sos_quick(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3], ids[3]);
      ASSERT_NE(o, pred::kUndecided);
      ASSERT_EQ(o, pred::orient3d_sos(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3], ids[3], s()));
      if (!lifted) continue;
      exact::SquareLifts<5, 3> l(r);
      ASSERT_EQ((exact::sos_resolve_by<3, 6>(exact::IntMinors{p, w})),
                (exact::sos_resolve<3, 6>(r, l.p, l.len, s())))
          << "range " << range;
      const int is = pred::insphere_sos_quick(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3],
                                              ids[3], r[4], ids[4]);
      ASSERT_NE(is, pred::kUndecided);
      ASSERT_EQ(is, pred::insphere_sos(r[0], ids[0], r[1], ids[1], r[2], ids[2], r[3], ids[3], r[4],
                                       ids[4], s()));
    }
  }
  const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0}, h[3] = {0.5, 0.5, 0};
  EXPECT_EQ(pred::orient3d_sos_quick(o, 0, x, 1, y, 2, h, 3), pred::kUndecided);
  EXPECT_EQ(pred::insphere_sos_quick(o, 0, x, 1, y, 2, h, 3, o, 4), pred::kUndecided);
}

// Tier 3 (exact translated determinant, or the bounded one) is never wrong: it answers the
// rational sign or kUndecided; it decides the exactly translatable cases and most of the rest.
// The split *_sos_mid / *_sos_last functions agree with the one-call SoS predicates.
TEST_P(Scales, TranslatedTierMatchesRationals) {
  int decided[3] = {0, 0, 0}, tried[3] = {0, 0, 0};
  std::vector<double> mid(pred::kInsphereSosMidScratch);
  auto t3 = make_tuples(3, 4, 1500, 12, GetParam(), false);
  auto tc = make_tuples(2, 4, 1500, 13, GetParam(), true);
  auto ts = make_tuples(3, 5, 1500, 14, GetParam(), true);
  auto t4 = make_tuples(3, 5, 1500, 15, GetParam(), false, 4);
  for (std::size_t i = 0; i < t3.size(); ++i) {
    auto P = [&](const gg_test::Tuples& t, int j) { return t.at(i, j); };
    const int r3 = pred::orient3d_translated(P(t3, 0), P(t3, 1), P(t3, 2), P(t3, 3), mid.data());
    const int rc = pred::incircle_translated(P(tc, 0), P(tc, 1), P(tc, 2), P(tc, 3), mid.data());
    const int rs =
        pred::insphere_translated(P(ts, 0), P(ts, 1), P(ts, 2), P(ts, 3), P(ts, 4), mid.data());
    const int r4 =
        pred::orient4d_translated(P(t4, 0), P(t4, 1), P(t4, 2), P(t4, 3), P(t4, 4), mid.data());
    const int ref[4] = {ref_orient({P(t3, 0), P(t3, 1), P(t3, 2), P(t3, 3)}, 3, 0),
                        -ref_orient({P(tc, 0), P(tc, 1), P(tc, 2), P(tc, 3)}, 2, 1),
                        -ref_orient({P(ts, 0), P(ts, 1), P(ts, 2), P(ts, 3), P(ts, 4)}, 3, 1),
                        ref_orient({P(t4, 0), P(t4, 1), P(t4, 2), P(t4, 3), P(t4, 4)}, 3, 2)};
    const int got[4] = {r3, rc, rs, r4};
    for (int k = 0; k < 4; ++k)
      if (got[k] != exact::kUndecided)
        ASSERT_EQ(got[k], ref[k]) << "predicate " << k << " case " << i;
    // the filter's undecided cases are the ones tier 3 exists for
    const bool hard[3] = {
        pred::orient3d_fast(P(t3, 0), P(t3, 1), P(t3, 2), P(t3, 3)) == 0,
        pred::incircle_fast(P(tc, 0), P(tc, 1), P(tc, 2), P(tc, 3)) == 0,
        pred::insphere_fast(P(ts, 0), P(ts, 1), P(ts, 2), P(ts, 3), P(ts, 4)) == 0};
    for (int k = 0; k < 3; ++k)
      if (hard[k]) tried[k]++, decided[k] += got[k] != exact::kUndecided;
    const int ids[5] = {int(5 * i + 2), int(5 * i), int(5 * i + 4), int(5 * i + 1), int(5 * i + 3)};
    const int sm = pred::insphere_sos_mid(P(ts, 0), ids[0], P(ts, 1), ids[1], P(ts, 2), ids[2],
                                          P(ts, 3), ids[3], P(ts, 4), ids[4], mid.data());
    const int sl = pred::insphere_sos_last(P(ts, 0), ids[0], P(ts, 1), ids[1], P(ts, 2), ids[2],
                                           P(ts, 3), ids[3], P(ts, 4), ids[4], s());
    if (sm != exact::kUndecided) ASSERT_EQ(sm, sl) << "case " << i;
    const int cm = pred::incircle_sos_mid(P(tc, 0), ids[0], P(tc, 1), ids[1], P(tc, 2), ids[2],
                                          P(tc, 3), ids[3], mid.data());
    const int cl = pred::incircle_sos_last(P(tc, 0), ids[0], P(tc, 1), ids[1], P(tc, 2), ids[2],
                                           P(tc, 3), ids[3], s());
    if (cm != exact::kUndecided) ASSERT_EQ(cm, cl) << "case " << i;
    const int om = pred::orient3d_sos_mid(P(t3, 0), ids[0], P(t3, 1), ids[1], P(t3, 2), ids[2],
                                          P(t3, 3), ids[3], mid.data());
    const int ol = pred::orient3d_sos_last(P(t3, 0), ids[0], P(t3, 1), ids[1], P(t3, 2), ids[2],
                                           P(t3, 3), ids[3], s());
    if (om != exact::kUndecided) ASSERT_EQ(om, ol) << "case " << i;
    ASSERT_NE(sl, 0);
    ASSERT_NE(cl, 0);
    ASSERT_NE(ol, 0);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(tried[k], 100) << "predicate " << k;
    // At power-of-two scales the integer-grid tuples (a third of all, half of the filter's
    // failures) translate exactly and are decided here; otherwise the bound still decides some.
    // (Measured: 54-62% at powers of two, 11-62% at the other scales.)
    EXPECT_GT(decided[k], pow2(GetParam()) ? tried[k] / 3 : tried[k] / 20) << "predicate " << k;
  }
}
