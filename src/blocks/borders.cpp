// The border a distributed-Delaunay block sends the others (include/gpugeom/blocks.hpp:
// block_borders): per other block A, the block's own points that are vertices of a local simplex
// whose closed circumball meets A's cell, or of a hull face whose plane meets it. Why that is
// every point of this block that A's stars can use is in docs/design-notes.md ("A block is sent
// the borders of the others"): the centre of a global ball through an own point q lies in q's
// Voronoi cell among this block's local points, so the ball lies in the union of the local balls
// round q (and, where the cell is unbounded, the half-spaces beyond q's hull faces). The rule
// for one simplex is simplex_rules.hpp's, shared with the several devices' pass on the GPU.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/common.hpp"
#include "blocks/circumball.hpp"
#include "blocks/pass.hpp"
#include "blocks/simplex_rules.hpp"

namespace gpugeom {

namespace {

using blocks_detail::BorderCells;
using blocks_detail::Slabs;

template <int D, class I>
void run(const double* pts, const I* simplices, const I* neighbors, std::int64_t m,
         const std::uint8_t* owned, std::int64_t block, const BorderCells& cells, double scale,
         const Slabs* slabs, std::uint8_t* inside, std::vector<std::vector<std::int64_t>>& found) {
  const int d1 = D + 1;
  double own_lo[3], own_hi[3];  // the own cell's box (grown by the margin)
  cells.box(block, D, own_lo, own_hi);
#pragma omp parallel
  {
    auto& out = found[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t i = 0; i < m; ++i) {
      const I* v = simplices + i * d1;
      std::uint32_t own = 0;
      for (int k = 0; k < d1; ++k)
        if (owned[v[k]]) own |= 1u << k;
      if (inside) inside[i] = 0;
      if (!own) continue;
      bool in = false;
      // (target cell, local vertex) pairs of the simplex
      blocks_detail::simplex_borders<D>(pts, v, neighbors + i * d1, own, block, cells, own_lo,
                                        own_hi, scale, inside ? slabs : nullptr, &in,
                                        [&](std::int64_t t, std::uint32_t places) {
                                          for (int k = 0; k < d1; ++k)
                                            if ((places >> k) & 1u) {
                                              out.push_back(t);
                                              out.push_back(std::int64_t(v[k]));
                                            }
                                        });
      if (inside) inside[i] = in ? 1 : 0;
    }
  }
}

template <class I>
BlockBorders borders_of(const double* points, int dim, const I* simplices, const I* neighbors,
                        std::int64_t m, std::int64_t n, const std::uint8_t* owned,
                        std::int64_t block, const CellGrid& grid, double margin, double scale,
                        const BlockBoxes* boxes, std::uint8_t* inside, int threads) {
  blocks_detail::check_dim(dim, "block_borders");
  BorderCells cells{grid, 1, margin};
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
