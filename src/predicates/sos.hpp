// Simulation of simplicity (Edelsbrunner & Muecke's scheme, derived here for our matrices).
//
// Every input entry gets an infinitesimal perturbation eps^(2^bit): entry (row r, column c) of
// a predicate matrix, rows sorted by the points' global indices. A perturbed determinant is a
// polynomial in eps whose terms, in increasing power, are indexed by the integers mask = 1, 2,
// 3, ...: a mask is a set of perturbed entries (distinct rows, distinct columns) and its
// coefficient is the determinant with those rows replaced by unit vectors, i.e. a signed minor
// of the unperturbed matrix. The sign of the first nonzero coefficient is the answer. Because
// a mask that perturbs every coordinate column leaves the all-ones column alone, some term is
// always nonzero: the SoS predicates never return 0 (given distinct indices).
//
// Bit order: for lifted predicates (in-circle, in-sphere, orient4d) the lift column of every
// point comes first (bits 0..k-1 by index), then the coordinates, point by point in index order.
// Orientation predicates use the same coordinate order, so one global perturbation of the
// points serves all predicates and they agree with each other. Only the relative order of the
// bits matters, so bits can be numbered locally after sorting the rows by global index.
#pragma once
#include <cstdint>

#include "predicates/determinant.hpp"

namespace gpugeom::exact {

constexpr int cmax(int a, int b) {
  return a > b ? a : b;
}

// Scratch (in doubles) needed by sos_resolve<D, LW>.
template <int D, int LW>
struct SosScratch {
  static constexpr int orient_part() {
    int m = 0;
    if constexpr (D >= 0) m = cmax(m, Om<D>::len + Om<D>::scratch);
    return m;
  }
  static constexpr int lifted_part() {
    if constexpr (LW == 0) {
      return 0;
    } else {
      return Lm<D - 1, LW>::len + Lm<D - 1, LW>::scratch;
    }
  }
  static constexpr int value = cmax(orient_part(), lifted_part());
};

template <int Q, int D>
GG_HD int orient_minor_sign(const double* const* rows, const int* cols, double* s) {
  int n = orient_minor<Q>(rows, cols, s, s + Om<Q>::len);
  return expansion_sign(n, s);
}

template <int Q, int LW>
GG_HD int lifted_minor_sign(const double* const* rows, const int* cols, const double* const* lift,
                            const int* liftlen, double* s) {
  int n = lifted_minor<Q, LW>(rows, cols, lift, liftlen, s, s + Lm<Q, LW>::len);
  return expansion_sign(n, s);
}

// Sorts rows (and lifts) by index; returns the parity of the permutation (+1 or -1).
template <int N>
GG_HD int sort_rows(const double** rows, int* idx, const double** lift, int* liftlen) {
  int parity = 1;
  for (int i = 1; i < N; ++i)
    for (int j = i; j > 0 && idx[j - 1] > idx[j]; --j) {
      auto sw = [](auto& a, auto& b) {
        auto t = a;
        a = b;
        b = t;
      };
      sw(rows[j - 1], rows[j]);
      sw(idx[j - 1], idx[j]);
      if (lift) {
        sw(lift[j - 1], lift[j]);
        sw(liftlen[j - 1], liftlen[j]);
      }
      parity = -parity;
    }
  return parity;
}

// The minors the perturbation's terms need, as expansions of the raw coordinates (any doubles in
// the exact range). rl: local row numbers; cols: coordinate columns.
template <int D, int LW>
struct ExpansionMinors {
  const double* const* rows;
  const double* const* lift;
  const int* liftlen;
  double* s;
  // det [p[cols] 1] over the q + 1 rows rl.
  GG_HD int orient(int q, const int* rl, const int* cols) const {
    const double* rr[D + 2];
    for (int i = 0; i <= q; ++i) rr[i] = rows[rl[i]];
    if (q == 0) return 1;
    if (q == 1) return orient_minor_sign<1, D>(rr, cols, s);
    if constexpr (D >= 2)
      if (q == 2) return orient_minor_sign<2, D>(rr, cols, s);
    if constexpr (D >= 3)
      if (q == 3) return orient_minor_sign<3, D>(rr, cols, s);
    return 0;
  }
  // det [p[cols] w 1] over the q + 2 rows rl.
  GG_HD int lifted(int q, const int* rl, const int* cols) const {
    if constexpr (LW > 0) {
      const double* rr[D + 2];
      const double* ll[D + 2];
      int lll[D + 2];
      for (int i = 0; i < q + 2; ++i) {
        rr[i] = rows[rl[i]];
        ll[i] = lift[rl[i]];
        lll[i] = liftlen[rl[i]];
      }
      if (q == 0) return lifted_minor_sign<0, LW>(rr, cols, ll, lll, s);
      if constexpr (D >= 2)
        if (q == 1) return lifted_minor_sign<1, LW>(rr, cols, ll, lll, s);
      if constexpr (D >= 3)
        if (q == 2) return lifted_minor_sign<2, LW>(rr, cols, ll, lll, s);
    }
    return 0;
  }
};

// Sign of the perturbed determinant of the matrix with rows [p[0..D-1], (w), 1], given that the
// unperturbed determinant is zero, with the minors from mn (above, or integer.hpp's for whole
// numbers: the same terms in the same order, so the same answer). Rows must be sorted by
// global index. LW = 0: no lift column.
template <int D, int LW, class Minors>
GG_HD int sos_resolve_by(const Minors& mn) {
  constexpr bool kLift = LW > 0;
  constexpr int k = D + 1 + (kLift ? 1 : 0);  // rows, = columns
  constexpr int wbits = kLift ? k : 0;
  constexpr int nbits = k * D + wbits;
  constexpr int W = D;  // column id of the lift; coordinate columns are 0..D-1
  // The masks in increasing order, skipping those that cannot be terms: the bits are read from
  // the highest down, and where bit b clashes with the bits above it (same row or column, or
  // one too many), no mask with those bits from b up is a term, so the next candidate is the
  // next multiple of 2^b (for 5 coplanar points' in-sphere test, 51 candidates instead of 130).
  for (std::uint32_t mask = 1; mask < (1u << nbits);) {
    int er[k], ec[k], m = 0;
    unsigned rused = 0, cused = 0;
    int clash = -1;
    for (int b = nbits - 1; b >= 0; --b) {
      if (!(mask >> b & 1u)) continue;
      int r, c;
      if (b < wbits) {
        r = b;
        c = W;
      } else {
        r = (b - wbits) / D;
        c = (b - wbits) % D;
      }
      if ((rused >> r & 1u) || (cused >> c & 1u) || m == k - 1) {
        clash = b;
        break;
      }
      rused |= 1u << r;
      cused |= 1u << c;
      er[m] = r;
      ec[m] = c;
      ++m;
    }
    if (clash >= 0) {
      mask = (mask | ((1u << clash) - 1u)) + 1u;
      continue;
    }
    ++mask;
    // (the entries from the lowest bit up, as the Laplace signs below were derived)
    for (int i = 0, j = m - 1; i < j; ++i, --j) {
      const int tr = er[i], tc = ec[i];
      er[i] = er[j], ec[i] = ec[j];
      er[j] = tr, ec[j] = tc;
    }
    // Remove each perturbed row/column (a unit row): Laplace along that row.
    int rl[k], rn = k;
    int cl[D + 2], cn = 0;
    for (int i = 0; i < k; ++i) rl[i] = i;
    for (int c = 0; c < D; ++c) cl[cn++] = c;
    if (kLift) cl[cn++] = W;
    cl[cn++] = D + 1;  // the ones column
    int sign = 1;
    for (int e = 0; e < m; ++e) {
      int pr = 0, pc = 0;
      while (rl[pr] != er[e]) ++pr;
      while (cl[pc] != ec[e]) ++pc;
      if ((pr + pc) & 1) sign = -sign;
      for (int i = pr; i + 1 < rn; ++i) rl[i] = rl[i + 1];
      for (int i = pc; i + 1 < cn; ++i) cl[i] = cl[i + 1];
      --rn;
      --cn;
    }
    int coords[D + 1], q = 0;
    bool has_w = false;
    for (int i = 0; i < cn - 1; ++i) {
      if (cl[i] == W && kLift)
        has_w = true;
      else
        coords[q++] = cl[i];
    }
    const int v = has_w ? mn.lifted(q, rl, coords) : mn.orient(q, rl, coords);
    if (v != 0) return sign * v;
  }
  return 0;  // unreachable: the mask perturbing every coordinate column gives +-1
}

template <int D, int LW>
GG_HD int sos_resolve(const double* const* rows, const double* const* lift, const int* liftlen,
                      double* s) {
  return sos_resolve_by<D, LW>(ExpansionMinors<D, LW>{rows, lift, liftlen, s});
}

}  // namespace gpugeom::exact
