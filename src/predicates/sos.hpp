// Simulation of simplicity (Edelsbrunner & Muecke's scheme, derived here for our matrices).
//
// Every input entry gets an infinitesimal perturbation eps^(2^bit): entry (row r, column c) of
// a predicate matrix, rows sorted in the perturbation order (below). A perturbed determinant is
// a polynomial in eps whose terms, in increasing power, are indexed by the integers mask = 1, 2,
// 3, ...: a mask is a set of perturbed entries (distinct rows, distinct columns) and its
// coefficient is the determinant with those rows replaced by unit vectors, i.e. a signed minor
// of the unperturbed matrix. The sign of the first nonzero coefficient is the answer. Because
// a mask that perturbs every coordinate column leaves the all-ones column alone, some term is
// always nonzero: the SoS predicates never return 0 (given distinct points or indices).
//
// Two orders of the points, both from each point's coordinates alone (never its index, the
// curve order or the other points), so a triangulation updated by inserting, moving or removing
// points, or built in blocks, equals the one a fresh run on the same point set gives:
//  - the lift order, for the lift column of in-circle, in-sphere and orient4d: coordinates
//    lexicographically (x, then y, then z) and decreasing, the largest point perturbed most.
//    This is CGAL's symbolic perturbation of Delaunay_triangulation_2/3 (Devillers & Teillaud):
//    the first terms perturb the lifts from the lexicographically largest point down, as CGAL's
//    do, so both give the same simplices on cocircular and cospherical input (tested);
//  - the coordinate order, for the coordinate columns: Z (Morton) order of the coordinates'
//    bits, in one frame for every input. It decides only orientation ties (points on a plane or
//    a line). The lexicographic order would push every point of a grid's hull plane out the
//    same way: the perturbed plane becomes a convex cap with every point a vertex, and the flat
//    tetrahedra between the cap and the grid's cubes, which phase 1 builds and the output drops,
//    grow sevenfold (grid 60^3: 530 761 against 75 958 in the curve order used before). A hash
//    scatters them (67 846) but leaves five times the failed vertices (705 against 130); the Z
//    order leaves 113 580 and 75 (docs/design-notes.md, "The perturbation depends on the points
//    alone").
// The index orders only equal points (duplicates, which the algorithms remove first, and
// symbolic points that may coincide with an input point).
//
// Bit order: for lifted predicates (in-circle, in-sphere, orient4d) the lift column of every
// point comes first (bits 0..k-1 in the lift order), then the coordinates, point by point in the
// coordinate order. Orientation predicates use the same coordinate order, so one global
// perturbation of the points serves all predicates and they agree with each other. Only the
// relative order of the bits matters, so bits can be numbered locally: the rows are sorted in
// the lift order, and corow[k] is the row of the point k-th in the coordinate order.
#pragma once
#include <cstdint>
#include <cstring>

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

// Does point a (index ia) come before point b (index ib) in the lift order: a's first D
// coordinates lexicographically greater than b's, or equal and ia < ib.
template <int D>
GG_HD inline bool lift_before(const double* a, int ia, const double* b, int ib) {
  for (int c = 0; c < D; ++c)
    if (a[c] != b[c]) return a[c] > b[c];
  return ia < ib;
}

// The coordinate order: Z (Morton) order of the coordinates' bits in one fixed frame, the
// doubles read as unsigned integers in their own order (-0 as 0). Of two points, the one lower
// in the coordinate whose bits differ highest comes first.
GG_HD inline std::uint64_t ordered_bits(double v) {
  std::uint64_t u = 0;
  if (v != 0.0) memcpy(&u, &v, sizeof u);
  return (u >> 63) ? ~u : (u | (1ull << 63));
}
template <int D>
GG_HD inline bool morton_before(const double* a, const double* b) {
  int dim = 0;
  std::uint64_t x = 0;
  for (int d = 0; d < D; ++d) {
    const std::uint64_t y = ordered_bits(a[d]) ^ ordered_bits(b[d]);
    if (x < y && x < (x ^ y)) dim = d, x = y;
  }
  return ordered_bits(a[dim]) < ordered_bits(b[dim]);
}

// Sorts rows (and lifts) into the lift order, comparing the first D coordinates of each row, and
// returns the parity of the permutation (+1 or -1); corow (N entries) receives the rows in the
// coordinate order (equal points: in the lift order).
template <int N, int D>
GG_HD int sort_rows(const double** rows, int* idx, const double** lift, int* liftlen, int* corow) {
  int parity = 1;
  for (int i = 1; i < N; ++i)
    for (int j = i; j > 0 && lift_before<D>(rows[j], idx[j], rows[j - 1], idx[j - 1]); --j) {
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
  for (int i = 0; i < N; ++i) corow[i] = i;
  for (int i = 1; i < N; ++i)
    for (int j = i; j > 0 && morton_before<D>(rows[corow[j]], rows[corow[j - 1]]); --j) {
      const int t = corow[j];
      corow[j] = corow[j - 1];
      corow[j - 1] = t;
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
// numbers: the same terms in the same order, so the same answer). Rows must be in the lift
// order, and corow gives the coordinate order (sort_rows); null: the same as the lift order.
// LW = 0: no lift column. from: the first mask to try (sos_past_first_terms, where the first
// terms are known to vanish: 1 tries every term).
template <int D, int LW, class Minors>
GG_HD int sos_resolve_by(const Minors& mn, const int* corow = nullptr, std::uint32_t from = 1) {
  constexpr bool kLift = LW > 0;
  constexpr int k = D + 1 + (kLift ? 1 : 0);  // rows, = columns
  constexpr int wbits = kLift ? k : 0;
  constexpr int nbits = k * D + wbits;
  constexpr int W = D;  // column id of the lift; coordinate columns are 0..D-1
  // The masks in increasing order, skipping those that cannot be terms: the bits are read from
  // the highest down, and where bit b clashes with the bits above it (same row or column, or
  // one too many), no mask with those bits from b up is a term, so the next candidate is the
  // next multiple of 2^b (for 5 coplanar points' in-sphere test, 51 candidates instead of 130).
  for (std::uint32_t mask = from; mask < (1u << nbits);) {
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
        if (corow) r = corow[r];
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

// The first terms of the perturbed determinant, found without sorting the rows (the loop
// above needs them sorted; on grids, where ties are common, the sorts were most of a tie's
// cost, and the first terms nearly always decide). The perturbation belongs to the points, not
// to the rows' places, so the coefficient of a term that perturbs one entry of row i is that
// entry's cofactor in the matrix as given, and the sign needs no parity. Both return the sign of
// det(M + perturbation) for the rows as given, or 0 where these terms all vanish (then the sorted
// loop decides, from its first term: the same answer either way, as these are its first terms).
//
// Where they all vanish, the sorted loop need not compute them again: every mask below
// sos_past_first_terms is one of them or no term at all (two lifts share the lift column; two
// coordinates of one point share its row). On a grid's hull planes that was 5 of the 11 minors
// an in-sphere tie computed, and 3 of 5 for an orientation.
template <int D, int LW>
GG_HD constexpr std::uint32_t sos_past_first_terms() {
  return LW > 0 ? 1u << (D + 2) : 1u << D;
}
//
// Lifted predicates (N = D + 2 rows [p w 1]): the first N terms perturb one lift each, from the
// first point in the lift order on (masks 1, 2, 4, ...; any two lifts share a column); the
// coefficient of row i's is (-1)^(i + D) det [p 1] without row i. They all vanish only when the
// points lie on one hyperplane.
template <int N, int D, class Minors>
GG_HD int sos_lift_terms(const double* const* rows, const int* idx, const Minors& mn) {
  static_assert(N == D + 2, "rows [p w 1]");
  unsigned done = 0;
  int cols[D];
  for (int c = 0; c < D; ++c) cols[c] = c;
  for (int t = 0; t < N; ++t) {
    int i = -1;
    for (int j = 0; j < N; ++j)
      if (!(done >> j & 1u) && (i < 0 || lift_before<D>(rows[j], idx[j], rows[i], idx[i]))) i = j;
    done |= 1u << i;
    int rl[N - 1], n = 0;
    for (int j = 0; j < N; ++j)
      if (j != i) rl[n++] = j;
    const int v = mn.orient(D, rl, cols);
    if (v != 0) return ((i + D) & 1) ? -v : v;
  }
  return 0;
}

// Orientation predicates (N = D + 1 rows [p 1]): the first D terms perturb the coordinates of
// the point first in the coordinate order, x first (masks 1, 2, 4, ...: two entries of one row
// are no term); the coefficient of its column c is (-1)^(i + c) det [p 1] without row i and
// column c. Where another point has its coordinates (the coordinate order then falls back on
// the lift order) this declines. from: where the sorted loop must begin (sos_resolve_by), set
// past these terms only where they were all taken and vanished.
template <int N, int D, class Minors>
GG_HD int sos_first_point_terms(const double* const* rows, const Minors& mn, std::uint32_t& from) {
  static_assert(N == D + 1, "rows [p 1]");
  from = 1;
  int i = 0;
  for (int j = 1; j < N; ++j)
    if (morton_before<D>(rows[j], rows[i])) i = j;
  int rl[N - 1], n = 0;
  for (int j = 0; j < N; ++j) {
    if (j == i) continue;
    bool same = true;
    for (int c = 0; c < D; ++c) same = same && rows[j][c] == rows[i][c];
    if (same) return 0;
    rl[n++] = j;
  }
  for (int c = 0; c < D; ++c) {
    int cols[D], q = 0;
    for (int k = 0; k < D; ++k)
      if (k != c) cols[q++] = k;
    const int v = mn.orient(D - 1, rl, cols);
    if (v != 0) return ((i + c) & 1) ? -v : v;
  }
  from = sos_past_first_terms<D, 0>();
  return 0;
}

template <int D, int LW>
GG_HD int sos_resolve(const double* const* rows, const double* const* lift, const int* liftlen,
                      double* s, const int* corow = nullptr, std::uint32_t from = 1) {
  return sos_resolve_by<D, LW>(ExpansionMinors<D, LW>{rows, lift, liftlen, s}, corow, from);
}

}  // namespace gpugeom::exact
