// The per-simplex rules of a distributed-Delaunay block, one simplex at a time and on either
// executor: the border it sends the other blocks (block_borders, borders.cpp), its owner and the
// code of each of its faces in the block's output (block_output, output.cpp). The host passes of
// gpugeom.dask and the passes of the several devices of one host (impl/block_pass.inl, on each
// block's device) call these, so the two cannot drift apart.
#pragma once
#include <cmath>
#include <cstdint>

#include "base/hd.hpp"
#include "blocks/circumball.hpp"
#include "gpugeom/blocks.hpp"

namespace gpugeom::blocks_detail {

// The cells of the blocks' grid, each box grown by `margin` (by value: it goes to the device).
struct BorderCells {
  CellGrid g;
  std::int64_t total = 1;
  double margin = 0;
  GG_HD void box(std::int64_t c, int dim, double* lo, double* hi) const {
    std::int64_t k[3] = {0, 0, 0};
    for (int j = dim - 1; j >= 0; --j) {
      k[j] = c % g.counts[j];
      c /= g.counts[j];
    }
    for (int j = 0; j < dim; ++j) {
      lo[j] = g.lo[j] + double(k[j]) * g.width[j] - margin;
      hi[j] = g.lo[j] + double(k[j] + 1) * g.width[j] + margin;
    }
  }
};

// A point's cell along axis j: floor((x - lo) / width), the same two roundings as
// gpugeom.dask's Grid, clamped to the grid (0 where the width is 0). Every pass that puts a point
// in a cell or bin uses it, so that a bin counted by one pass is the bin another splits by.
GG_HD inline std::int64_t cell_along(double x, const CellGrid& g, int j) {
  if (!(g.width[j] > 0)) return 0;
  const double f = floor((x - g.lo[j]) / g.width[j]);
  return f < 0 ? 0 : (f > double(g.counts[j] - 1) ? g.counts[j] - 1 : std::int64_t(f));
}

// A point's cell of the grid (row-major, the last axis fastest).
GG_HD inline std::int64_t cell_of(const double* x, const CellGrid& g, int dim) {
  std::int64_t c = 0;
  for (int j = 0; j < dim; ++j) c = c * g.counts[j] + cell_along(x[j], g, j);
  return c;
}

// Whether x lies in the closed box [lo, hi] (comparisons of the doubles: the rule that decides
// which points a block holds, the same in every pass).
GG_HD inline bool in_box(const double* x, const double* lo, const double* hi, int dim) {
  for (int j = 0; j < dim; ++j)
    if (!(x[j] >= lo[j] && x[j] <= hi[j])) return false;
  return true;
}

// The cells along axis j that [a, b] grown by `margin` meets: false where a > b, or where it
// lies beyond the grid and `clamp` is false; else the range clamped to the grid (a flat axis
// has one cell).
GG_HD inline bool cells_along(double a, double b, const CellGrid& g, int j, double margin,
                              bool clamp, std::int64_t* first, std::int64_t* last) {
  if (!(a <= b)) return false;
  if (!(g.width[j] > 0)) {
    *first = *last = 0;
    return true;
  }
  const double top = double(g.counts[j] - 1);
  const double f0 = floor((a - margin - g.lo[j]) / g.width[j]);
  const double f1 = floor((b + margin - g.lo[j]) / g.width[j]);
  if (!clamp && (f1 < 0 || f0 > top)) return false;
  *first = f0 < 0 ? 0 : (f0 > top ? g.counts[j] - 1 : std::int64_t(f0));
  *last = f1 < 0 ? 0 : (f1 > top ? g.counts[j] - 1 : std::int64_t(f1));
  return true;
}

// The lowest vertex's place (0..d1 - 1) in a simplex.
template <class I>
GG_HD int lowest_at(const I* v, int d1) {
  int at = 0;
  for (int k = 1; k < d1; ++k)
    if (v[k] < v[at]) at = k;
  return at;
}

// The border rule for one simplex `v` of a block's local triangulation, with its neighbours
// `nb` (-1: a hull face) and `own` (bit k: v[k] is an own point; not 0): calls send(t, places)
// for each other block t that must receive the vertices at the bits of `places`: those of a
// simplex whose closed circumball (grown by a bound of its rounding) meets t's cell, every cell
// where the centre is not trusted, and per hull face the face's own vertices for each cell its
// plane meets. Where `slabs` is given, *inside tells whether the ball misses them (the first
// finality test, on the same ball). own_lo/own_hi: the block's own cell. Why this is all a
// block's stars need: docs/design-notes.md ("A block is sent the borders of the others").
template <int D, class I, class Send>
GG_HD void simplex_borders(const double* pts, const I* v, const I* nb, std::uint32_t own,
                           std::int64_t block, const BorderCells& cells, const double* own_lo,
                           const double* own_hi, double scale, const Slabs* slabs, bool* inside,
                           Send&& send) {
  constexpr int d1 = D + 1;
  double c[D], reach;
  const bool trusted = circumball<D>(pts, v, c, &reach, scale);
  if (slabs) *inside = trusted && misses(*slabs, c, reach, D);
  if (!trusted) {  // a centre not trusted: its ball may meet any cell
    for (std::int64_t t = 0; t < cells.total; ++t)
      if (t != block) send(t, own);
  } else {
    // most balls lie well inside the own cell, whose neighbours' boxes (grown by the margin)
    // they then miss: no cell ranges to compute
    bool within = true;
    for (int j = 0; j < D; ++j)
      within = within && c[j] - reach > own_lo[j] + 2 * cells.margin &&
               c[j] + reach < own_hi[j] - 2 * cells.margin;
    std::int64_t first[3] = {0, 0, 0}, last[3] = {-1, 0, 0};
    if (!within)
      for (int j = 0; j < D; ++j)
        cells_along(c[j] - reach, c[j] + reach, cells.g, j, cells.margin, true, &first[j],
                    &last[j]);
    std::int64_t k[3] = {0, 0, 0};
    for (k[0] = first[0]; k[0] <= last[0]; ++k[0])
      for (k[1] = first[1]; k[1] <= last[1]; ++k[1])
        for (k[2] = first[2]; k[2] <= (D == 3 ? last[2] : 0); ++k[2]) {
          std::int64_t t = k[0] * cells.g.counts[1] + k[1];
          if (D == 3) t = t * cells.g.counts[2] + k[2];
          if (t == block) continue;
          double lo[3], hi[3], g2 = 0;
          cells.box(t, D, lo, hi);
          for (int j = 0; j < D; ++j) {
            const double gap = fmax(fmax(lo[j] - c[j], c[j] - hi[j]), 0.0);
            g2 += gap * gap;
          }
          if (sqrt(g2) <= reach) send(t, own);
        }
  }
  // the hull faces with an own vertex: the half-space beyond one holds no point, but a cell that
  // meets its plane may hold points on it (a grid's side), which a perturbed ball through the
  // face's points can reach
  for (int f = 0; f < d1; ++f) {
    if (nb[f] >= 0) continue;
    const std::uint32_t face = own & ~(1u << f);
    if (!face) continue;
    const double* p[3];
    int np_ = 0;
    for (int q = 0; q < d1; ++q)
      if (q != f) p[np_++] = pts + std::int64_t(v[q]) * D;
    // the normal (|u| |w| sin: the sine is its relative accuracy in 3D; in 2D the edge's
    // perpendicular is exact up to a rounding of its length)
    double nrm[3] = {0, 0, 0}, len2 = 0, top = 0, size = 1;
    if (D == 2) {
      nrm[0] = -(p[1][1] - p[0][1]);
      nrm[1] = p[1][0] - p[0][0];
    } else {
      const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
      const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
      nrm[0] = u[1] * w[2] - u[2] * w[1];
      nrm[1] = u[2] * w[0] - u[0] * w[2];
      nrm[2] = u[0] * w[1] - u[1] * w[0];
      size = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) *
             sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    }
    for (int j = 0; j < D; ++j) {
      len2 += nrm[j] * nrm[j];
      top = fmax(top, fabs(p[0][j]));
    }
    const double len = sqrt(len2);
    if (D == 2) size = len;
    // a face too flat for its plane to be trusted: every cell
    const bool flat = !(len > 1e-9 * size) || !(len > 0);
    // the plane's rounding over the distances of the bounds (at most twice scale + top)
    const double tol = len * cells.margin + 64.0 * kEps * size * (scale + top);
    for (std::int64_t t = 0; t < cells.total; ++t) {
      if (t == block) continue;
      bool meets = flat;
      if (!meets) {
        double lo[3], hi[3], below = 0, above = 0;
        cells.box(t, D, lo, hi);
        for (int j = 0; j < D; ++j) {
          const double a = nrm[j] * (lo[j] - p[0][j]), b = nrm[j] * (hi[j] - p[0][j]);
          below += fmin(a, b);
          above += fmax(a, b);
        }
        meets = below <= tol && above >= -tol;
      }
      if (meets) send(t, face);
    }
  }
}

// The output code of face k of an owned simplex v (block_output): across it the neighbour's row
// (`row`, where the neighbour t >= 0 is owned here), -2 where it is another block's, -1 on the
// global hull, and -3 for an open request (a face on the local hull without an own vertex: both
// simplices of a face with one are in that vertex's star; one without may be matched by another
// block, or be on the global hull). blk(u): the block of local point u.
template <class I, class Blk>
GG_HD std::int64_t face_code(const I* v, int d1, int k, std::int64_t t, std::int64_t row,
                             const Blk& blk) {
  if (t >= 0) return row >= 0 ? row : -2;
  const std::int64_t block = blk(v[lowest_at(v, d1)]);
  for (int j = 0; j < d1; ++j)
    if (j != k && blk(v[j]) == block) return -1;
  return -3;
}

// The request for face `face` of simplex v: its `d1 - 1` global ids (id(u) of local point u)
// sorted into key, and the local vertex whose block matches it (the face's lowest).
template <class I, class K, class Id>
GG_HD I request_key(const I* v, int d1, int face, const Id& id, K* key) {
  I low = -1;
  int n = 0;
  for (int j = 0; j < d1; ++j) {
    if (j == face) continue;
    const K x = K(id(v[j]));
    int at = n++;
    for (; at > 0 && key[at - 1] > x; --at) key[at] = key[at - 1];  // (insertion: 2 or 3 ids)
    key[at] = x;
    if (low < 0 || v[j] < low) low = v[j];
  }
  return low;
}

}  // namespace gpugeom::blocks_detail
