// Exact determinants of the matrices behind every predicate, by cofactor expansion over
// expansions of the raw (untranslated) coordinates, so no rounded difference ever enters.
//
//   orient_minor<K>:  det of the (K+1)x(K+1) matrix with rows [p[c_0] .. p[c_{K-1}], 1]
//   lifted_minor<K>:  det of the (K+2)x(K+2) matrix with rows [p[c_0] .. p[c_{K-1}], w(p), 1]
//
// where w(p) is a lift given as an expansion (|p|^2 for in-circle/in-sphere, a fourth
// coordinate for orient4d). The simulation-of-simplicity code evaluates the same kind of
// minors on subsets of rows and columns. Sizes are compile-time so device code needs no
// allocation: callers pass scratch memory of the advertised size.
#pragma once
#include "predicates/expansion.hpp"

namespace gpugeom::exact {

// Longest result of orient_minor<K>.
template <int K>
struct Om {
  static constexpr int len = (K + 1) * 2 * Om<K - 1>::len;
  static constexpr int scratch = Om<K - 1>::len + 2 * Om<K - 1>::len + len + Om<K - 1>::scratch;
};
template <>
struct Om<0> {
  static constexpr int len = 1, scratch = 0;
};
template <>
struct Om<1> {
  static constexpr int len = 2, scratch = 0;
};

// Longest result of lifted_minor<K> with lifts of at most LW components, and its scratch.
template <int K, int LW>
struct Lm {
  static constexpr int term = 2 * LW * Om<K>::len;
  static constexpr int len = (K + 2) * term;
  static constexpr int scratch = Om<K>::len + term + 2 * Om<K>::len + term + len + Om<K>::scratch;
};

template <int K>
GG_HD int orient_minor(const double* const* rows, const int* cols, double* out, double* s) {
  if constexpr (K == 0) {
    out[0] = 1.0;
    return 1;
  } else if constexpr (K == 1) {
    double x, y;
    two_diff(rows[0][cols[0]], rows[1][cols[0]], x, y);
    int k = 0;
    if (y != 0.0) out[k++] = y;
    if (x != 0.0) out[k++] = x;
    return k;
  } else {
    double* sub = s;
    double* term = sub + Om<K - 1>::len;
    double* alt = term + 2 * Om<K - 1>::len;
    double* ss = alt + Om<K>::len;
    double* acc = out;
    double* other = alt;
    int len = 0;
    const double* r[K];
    for (int i = 0; i <= K; ++i) {
      for (int j = 0, m = 0; j <= K; ++j)
        if (j != i) r[m++] = rows[j];
      int sl = orient_minor<K - 1>(r, cols + 1, sub, ss);
      double c = rows[i][cols[0]];
      accumulate(acc, other, len, term, scale_expansion(sl, sub, (i & 1) ? -c : c, term));
    }
    settle(acc, len, out);
    return len;
  }
}

template <int K, int LW>
GG_HD int lifted_minor(const double* const* rows, const int* cols, const double* const* lift,
                       const int* liftlen, double* out, double* s) {
  using L = Lm<K, LW>;
  double* sub = s;
  double* term = sub + Om<K>::len;
  double* tmp1 = term + L::term;
  double* tmp2 = tmp1 + 2 * Om<K>::len;
  double* alt = tmp2 + L::term;
  double* ss = alt + L::len;
  double* acc = out;
  double* other = alt;
  int len = 0;
  const double* r[K + 1];
  for (int i = 0; i < K + 2; ++i) {
    for (int j = 0, m = 0; j < K + 2; ++j)
      if (j != i) r[m++] = rows[j];
    int sl = orient_minor<K>(r, cols, sub, ss);
    if ((i + K) & 1)
      for (int t = 0; t < sl; ++t) sub[t] = -sub[t];
    accumulate(acc, other, len, term,
               expansion_product(sl, sub, liftlen[i], lift[i], term, tmp1, tmp2));
  }
  settle(acc, len, out);
  return len;
}

// |p|^2 over the first D coordinates as an expansion of at most 2*D components.
template <int D>
GG_HD int square_lift(const double* p, double* out) {
  double parts[2 * D], tmp[2 * D];
  int len = 0;
  for (int c = 0; c < D; ++c) {
    double sq[2], x, y;
    two_product(p[c], p[c], x, y);
    int k = 0;
    if (y != 0.0) sq[k++] = y;
    if (x != 0.0) sq[k++] = x;
    len = expansion_sum(len, parts, k, sq, tmp);
    for (int i = 0; i < len; ++i) parts[i] = tmp[i];
  }
  for (int i = 0; i < len; ++i) out[i] = parts[i];
  return len;
}

// The lifts |p|^2 of N rows, as the pointer/length arrays lifted_minor and sos_resolve take.
template <int N, int D>
struct SquareLifts {
  double w[N][2 * D];
  const double* p[N];
  int len[N];
  GG_HD explicit SquareLifts(const double* const* rows) {
    for (int i = 0; i < N; ++i) {
      len[i] = square_lift<D>(rows[i], w[i]);
      p[i] = w[i];
    }
  }
};

}  // namespace gpugeom::exact
