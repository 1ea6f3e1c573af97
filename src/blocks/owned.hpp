// What the blocks of a multi-device triangulation hand the module that assembles it (the
// modules' assemble_blocks): the blocks' owned simplices in global input indices and their
// neighbours as global slots (block after block, each block's rows in its order; -1 none), as
// one pair of 32-bit arrays, so that the assembly copies them to its executor in one piece.
// (Input indices and slots fit: a single call's arrays are 32-bit too.)
#pragma once
#include <cstdint>
#include <vector>

#include "base/hd.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::blocks_detail {

struct OwnedBlocks {
  HostVector<std::int32_t> simplices, neighbors;  // K entries a simplex
  std::vector<std::int64_t> offsets{0};           // each block's first global slot, then the total
};

// The owned simplices as a mesh store (mesh/compact.hpp: live, get, order_names, prefetch) over
// the arrays in executor memory: `rank` names each input point by its place on the points'
// curve (the single call's order names), so compact_live_sorted puts them in the single call's
// order.
template <int K, class Record>
struct OwnedStore {
  const std::int32_t* s;
  const std::int32_t* nb;
  const std::int32_t* rank;
  GG_HD bool live(std::int64_t) const { return true; }
  GG_HD void prefetch(std::int64_t) const {}
  GG_HD void order_names(std::int64_t t, std::int32_t* w) const {
    for (int k = 0; k < K; ++k) w[k] = rank[s[K * t + k]];
  }
  GG_HD Record get(std::int64_t t) const {
    Record r;
    for (int k = 0; k < K; ++k) {
      r.v[k] = s[K * t + k];
      r.n[k] = nb[K * t + k];
    }
    return r;
  }
};

}  // namespace gpugeom::blocks_detail
