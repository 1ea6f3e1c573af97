// The split of the prepared points among the blocks (point_split.hpp), on the executor that
// prepared them: the modules' frames (impl/assemble.inl) hand it to the blocks as
// PreparedPoints::split. On the host threads this was a quarter of a second at 10^7 3D points
// and half a second at 2·10^7 2D points (bins 0.1 s, regions 0.08 s in 3D), as long as a block's
// triangulation on its GPU; here it is a sort and a few passes where the points already are.
// The same source runs on the CPU executor, so both give the same arrays.
#pragma once
#include <cstdint>
#include <string>

#include "base/clock.hpp"
#include "base/hd.hpp"
#include "blocks/point_split.hpp"
#include "blocks/simplex_rules.hpp"
#include "gpugeom/common.hpp"

namespace gpugeom::blocks_detail {

namespace split_detail {
inline int bits_for(std::int64_t v) {  // the bits that hold 0..v
  int b = 1;
  while (b < 63 && (std::int64_t(1) << b) <= v) ++b;
  return b;
}
}  // namespace split_detail

// pts, orig: the m prepared points (D coordinates each) and their input indices, in the
// executor's memory.
template <int D, class Exec>
PointSplit split_on(Exec& ex, const double* pts, const std::int32_t* orig, std::int64_t m,
                    const SplitLayout& L) {
  PointSplit out;
  auto t0 = Clock::now();
  out.q.resize(std::size_t(m * D));
  out.orig.resize(std::size_t(m));
  ex.to_host(pts, m * D, out.q.data());
  ex.to_host(orig, m, out.orig.data());
  out.ms_copy = ms_since(t0);

  // The bins: places sorted by bin (stable, so increasing within a bin), and each bin's start.
  t0 = Clock::now();
  const CellGrid bins = L.bins;
  std::int64_t nbins = 1;
  for (int j = 0; j < D; ++j) nbins *= bins.counts[j];
  if (nbins >= (std::int64_t(1) << 31))
    throw Error(ErrorCode::Internal, "the devices' split: " + std::to_string(nbins) +
                                         " bins do not fit 32-bit keys (a bug: please report it)");
  {
    auto key_b = ex.template alloc<std::uint32_t>(std::size_t(m));
    auto place_b = ex.template alloc<std::int32_t>(std::size_t(m));
    std::uint32_t* key = key_b.data();
    std::int32_t* place = place_b.data();
    ex.for_each_index(
        m, GG_LAMBDA(std::int64_t w) {
          key[w] = std::uint32_t(cell_of(pts + w * D, bins, D));
          place[w] = std::int32_t(w);
        });
    ex.sort_by_key(key, place, m, split_detail::bits_for(nbins));
    auto order_b = ex.template alloc<std::int64_t>(std::size_t(m));
    auto cuts_b = ex.template alloc<std::int64_t>(std::size_t(nbins + 1));
    std::int64_t* order = order_b.data();
    std::int64_t* cuts = cuts_b.data();
    // cuts[b] is the first place whose bin is b or later: each w starts the bins after its
    // predecessor's up to its own
    ex.for_each_index(
        m + 1, GG_LAMBDA(std::int64_t w) {
          if (w < m) order[w] = place[w];
          const std::int64_t prev = w > 0 ? std::int64_t(key[w - 1]) : -1;
          const std::int64_t here = w < m ? std::int64_t(key[w]) : nbins;
          for (std::int64_t b = prev + 1; b <= here; ++b) cuts[b] = w;
        });
    out.bin_order.resize(std::size_t(m));
    out.bin_cuts.resize(std::size_t(nbins + 1));
    ex.to_host(order, m, out.bin_order.data());
    ex.to_host(cuts, nbins + 1, out.bin_cuts.data());
  }
  out.ms_bins = ms_since(t0);

  // The regions: per place its cell and a bit per block that holds it (its cell's, and each
  // block with a box holding it: in_box on the doubles, the rule of every pass), then per block
  // its places in increasing order.
  t0 = Clock::now();
  const CellGrid grid = L.grid;
  const std::int64_t k = L.blocks, nboxes = std::int64_t(L.owner.size());
  const std::int64_t words = (k + 31) / 32;
  auto lo_b = ex.template alloc<double>(std::size_t(nboxes * D));
  auto hi_b = ex.template alloc<double>(std::size_t(nboxes * D));
  auto owner_b = ex.template alloc<std::int32_t>(std::size_t(nboxes));
  ex.from_host(L.lo.data(), nboxes * D, lo_b.data());
  ex.from_host(L.hi.data(), nboxes * D, hi_b.data());
  ex.from_host(L.owner.data(), nboxes, owner_b.data());
  const double* lo = lo_b.data();
  const double* hi = hi_b.data();
  const std::int32_t* owner = owner_b.data();
  auto cell_b = ex.template alloc<std::int32_t>(std::size_t(m));
  auto mark_b = ex.template alloc<std::uint32_t>(std::size_t(m * words));
  std::int32_t* cell = cell_b.data();
  std::uint32_t* mark = mark_b.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t w) {
        const double* x = pts + w * D;
        const std::int64_t c = cell_of(x, grid, D);
        cell[w] = std::int32_t(c);
        std::uint32_t* mine = mark + w * words;
        for (std::int64_t i = 0; i < words; ++i) mine[i] = 0;
        mine[c / 32] |= 1u << (c % 32);
        for (std::int64_t b = 0; b < nboxes; ++b) {
          const std::int32_t to = owner[b];
          if ((mine[to / 32] >> (to % 32)) & 1u) continue;  // (held already)
          if (in_box(x, lo + b * D, hi + b * D, D)) mine[to / 32] |= 1u << (to % 32);
        }
      });
  out.cell.resize(std::size_t(m));
  ex.to_host(cell, m, out.cell.data());
  auto list_b = ex.template alloc<std::int32_t>(std::size_t(m));
  std::int32_t* list = list_b.data();
  out.regions.resize(std::size_t(k));
  for (std::int64_t b = 0; b < k; ++b) {
    const std::uint32_t* word = mark + b / 32;
    const std::uint32_t bit = 1u << (b % 32);
    const std::int64_t c = ex.compact_indices(
        m, GG_LAMBDA(std::int64_t w) { return (word[w * words] & bit) != 0; }, list);
    out.regions[std::size_t(b)].resize(std::size_t(c));
    ex.to_host(list, c, out.regions[std::size_t(b)].data());
  }
  out.ms_regions = ms_since(t0);
  return out;
}

}  // namespace gpugeom::blocks_detail
