// The split of the points among the blocks of the several devices of one host
// (delaunay_devices.cpp), made where the assembling module prepared them (its first device:
// split_on.hpp) rather than on host threads: the blocks ask for a layout (the blocks' cells, the
// boxes each block holds, the bins of the finality test) once they know the points' bounds, and
// get back host arrays. The places are those of the prepared points (distinct, on the curve), so
// a block's ids name points near one another and a duplicate never reaches a block.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "gpugeom/blocks.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::blocks_detail {

// What the blocks ask for.
struct SplitLayout {
  CellGrid grid;  // the blocks' cells (block b is cell b)
  CellGrid bins;  // the finality test's bins
  std::int64_t blocks = 0;
  std::vector<double> lo, hi;       // boxes, dim coordinates each
  std::vector<std::int32_t> owner;  // each box's block, in increasing order
};

// What they get (host memory).
struct PointSplit {
  HostVector<double> q;                // the m prepared points, dim coordinates each, by place
  HostVector<std::int32_t> orig;       // each place's input index
  HostVector<std::int32_t> cell;       // each place's cell of the blocks' grid
  HostVector<std::int64_t> bin_order;  // places by bin (within a bin, increasing)
  HostVector<std::int64_t> bin_cuts;   // bin b's places: bin_order[bin_cuts[b]:bin_cuts[b + 1]]
  // Per block its places (its cell's and its boxes'), increasing.
  std::vector<HostVector<std::int32_t>> regions;
  double ms_copy = 0, ms_bins = 0, ms_regions = 0;
};

// The prepared points as the blocks see them: how many, their bounds, the split, and the
// places of a superset of the hull's extreme points, increasing (hull_on.hpp), which every block
// holds.
struct PreparedPoints {
  std::int64_t m = 0;
  const double* pts = nullptr;  // the m points by place, in the executor's memory (its device)
  PointBounds bounds;
  std::function<PointSplit(const SplitLayout&)> split;
  std::function<HostVector<std::int64_t>()> hull;
};

// The bounds of a module's box (lo[D], hi[D]) as the blocks read them.
template <int D, class Box>
PointBounds points_bounds(const Box& box) {
  PointBounds b;
  for (int j = 0; j < D; ++j) b.lo[j] = box.lo[j], b.hi[j] = box.hi[j];
  return b;
}

}  // namespace gpugeom::blocks_detail
