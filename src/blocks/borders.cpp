// The border a distributed-Delaunay block sends the others (include/gpugeom/blocks.hpp:
// block_borders): per other block A, the block's own points that are vertices of a local simplex
// whose closed circumball meets A's cell, or of a hull face whose plane meets it. Why that is
// every point of this block that A's stars can use is in docs/design-notes.md ("A block is sent
// the borders of the others"): the centre of a global ball through an own point q lies in q's
// Voronoi cell among this block's local points, so the ball lies in the union of the local balls
// round q (and, where the cell is unbounded, the half-spaces beyond q's hull faces).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/circumball.hpp"
#include "blocks/pass.hpp"

namespace gpugeom {

namespace {

using blocks_detail::circumball;
using blocks_detail::kEps;
using blocks_detail::misses;
using blocks_detail::Slabs;

struct Cells {
  const CellGrid& g;
  std::int64_t total = 1;
  double margin = 0;
  // cell c's box grown by the margin
  void box(std::int64_t c, int dim, double* lo, double* hi) const {
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

template <int D, class I>
void run(const double* pts, const I* simplices, const I* neighbors, std::int64_t m,
         const std::uint8_t* owned, std::int64_t block, const Cells& cells, double scale,
         const Slabs* slabs, std::uint8_t* inside, std::vector<std::vector<std::int64_t>>& found) {
  const int d1 = D + 1;
  const std::int64_t n_cells = cells.total;
  double own_lo[3], own_hi[3];  // the own cell's box (grown by the margin)
  cells.box(block, D, own_lo, own_hi);
#pragma omp parallel
  {
    auto& out = found[std::size_t(omp_get_thread_num())];
    // (target cell, local vertex) pairs of one simplex, as target * 4 + the vertex's place
    auto send = [&](const I* v, std::int64_t target, std::uint32_t places) {
      for (int k = 0; k < d1; ++k)
        if ((places >> k) & 1u) {
          out.push_back(target);
          out.push_back(std::int64_t(v[k]));
        }
    };
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t i = 0; i < m; ++i) {
      const I* v = simplices + i * d1;
      std::uint32_t own = 0;
      for (int k = 0; k < d1; ++k)
        if (owned[v[k]]) own |= 1u << k;
      if (inside) inside[i] = 0;
      if (!own) continue;
      double c[D], reach;
      const bool trusted = circumball<D>(pts, v, c, &reach, scale);
      // the first finality test of the star, on the same ball (circumballs_inside_region)
      if (inside && trusted && misses(*slabs, c, reach, D)) inside[i] = 1;
      if (!trusted) {
        // a centre not trusted: its ball may meet any cell
        for (std::int64_t t = 0; t < n_cells; ++t)
          if (t != block) send(v, t, own);
        continue;
      }
      // most balls lie well inside the own cell, whose neighbours' boxes (grown by the margin)
      // they then miss: no cell ranges to compute
      bool within = true;
      for (int j = 0; j < D; ++j)
        within = within && c[j] - reach > own_lo[j] + 2 * cells.margin &&
                 c[j] + reach < own_hi[j] - 2 * cells.margin;
      std::int64_t first[3] = {0, 0, 0}, last[3] = {-1, 0, 0};
      if (!within)
        for (int j = 0; j < D; ++j)
          blocks_detail::cells_along(c[j] - reach, c[j] + reach, cells.g, j, cells.margin, true,
                                     &first[j], &last[j]);
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
              const double gap = std::max(std::max(lo[j] - c[j], c[j] - hi[j]), 0.0);
              g2 += gap * gap;
            }
            if (std::sqrt(g2) <= reach) send(v, t, own);
          }
      // the hull faces with an own vertex: the half-space beyond one holds no point, but a cell
      // that meets its plane may hold points on it (a grid's side), which a perturbed ball
      // through the face's points can reach
      for (int f = 0; f < d1; ++f) {
        if (neighbors[i * d1 + f] >= 0) continue;
        std::uint32_t face = own & ~(1u << f);
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
          size = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) *
                 std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        }
        for (int j = 0; j < D; ++j) {
          len2 += nrm[j] * nrm[j];
          top = std::max(top, std::fabs(p[0][j]));
        }
        const double len = std::sqrt(len2);
        if (D == 2) size = len;
        // a face too flat for its plane to be trusted: every cell
        const bool flat = !(len > 1e-9 * size) || !(len > 0);
        // the plane's rounding over the distances of the bounds (at most twice scale + top)
        const double tol = len * cells.margin + 64.0 * kEps * size * (scale + top);
        for (std::int64_t t = 0; t < n_cells; ++t) {
          if (t == block) continue;
          bool meets = flat;
          if (!meets) {
            double lo[3], hi[3], below = 0, above = 0;
            cells.box(t, D, lo, hi);
            for (int j = 0; j < D; ++j) {
              const double a = nrm[j] * (lo[j] - p[0][j]), b = nrm[j] * (hi[j] - p[0][j]);
              below += std::min(a, b);
              above += std::max(a, b);
            }
            meets = below <= tol && above >= -tol;
          }
          if (meets) send(v, t, face);
        }
      }
    }
  }
}

template <class I>
BlockBorders borders_of(const double* points, int dim, const I* simplices, const I* neighbors,
                        std::int64_t m, std::int64_t n, const std::uint8_t* owned,
                        std::int64_t block, const CellGrid& grid, double margin, double scale,
                        const BlockBoxes* boxes, std::uint8_t* inside, int threads) {
  blocks_detail::check_dim(dim, "block_borders");
  Cells cells{grid, 1, margin};
  for (int j = 0; j < dim; ++j) cells.total *= grid.counts[j];
  if (block < 0 || block >= cells.total)
    throw Error(ErrorCode::InvalidArgument, "block_borders: block " + std::to_string(block) +
                                                " outside a grid of " +
                                                std::to_string(cells.total));
  blocks_detail::ThreadScope scope(threads);
  std::vector<std::vector<std::int64_t>> found(std::size_t(std::max(1, omp_get_max_threads())));
  Slabs slabs;
  if (boxes) slabs = blocks_detail::slabs_of(*boxes, dim);
  std::uint8_t* in = boxes ? inside : nullptr;
  if (m > 0) {
    if (dim == 2)
      run<2>(points, simplices, neighbors, m, owned, block, cells, scale, &slabs, in, found);
    else
      run<3>(points, simplices, neighbors, m, owned, block, cells, scale, &slabs, in, found);
  }
  // (target, vertex) keys, sorted and unique: the result does not depend on the threads
  std::vector<std::int64_t> keys;
  std::size_t total = 0;
  for (const auto& f : found) total += f.size() / 2;
  keys.reserve(total);
  for (const auto& f : found)
    for (std::size_t k = 0; k < f.size(); k += 2) keys.push_back(f[k] * n + f[k + 1]);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  BlockBorders out;
  out.vertices.resize(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::int64_t t = keys[k] / n;
    if (out.targets.empty() || out.targets.back() != t) {
      out.targets.push_back(t);
      out.offsets.push_back(std::int64_t(k));
    }
    out.vertices[k] = keys[k] % n;
  }
  out.offsets.push_back(std::int64_t(keys.size()));
  return out;
}

}  // namespace

BlockBorders block_borders(const double* points, int dim, const std::int64_t* simplices,
                           const std::int64_t* neighbors, std::int64_t m, std::int64_t n,
                           const std::uint8_t* owned, std::int64_t block, const CellGrid& grid,
                           double margin, double scale, const BlockBoxes* boxes,
                           std::uint8_t* inside, int threads) {
  return borders_of(points, dim, simplices, neighbors, m, n, owned, block, grid, margin, scale,
                    boxes, inside, threads);
}
BlockBorders block_borders(const double* points, int dim, const std::int32_t* simplices,
                           const std::int32_t* neighbors, std::int64_t m, std::int64_t n,
                           const std::uint8_t* owned, std::int64_t block, const CellGrid& grid,
                           double margin, double scale, const BlockBoxes* boxes,
                           std::uint8_t* inside, int threads) {
  return borders_of(points, dim, simplices, neighbors, m, n, owned, block, grid, margin, scale,
                    boxes, inside, threads);
}

}  // namespace gpugeom
