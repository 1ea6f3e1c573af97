// What the blocks of a multi-device triangulation hand the module that assembles it (the
// modules' assemble_blocks): each block's owned simplices in global input indices and their
// neighbours as global slots (block after block, each block's rows in its order; -1 none).
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "gpugeom/host_vector.hpp"

namespace gpugeom::blocks_detail {

struct OwnedBlocks {
  std::vector<HostVector<std::int64_t>> simplices, neighbors;  // K entries a simplex
  std::vector<std::int64_t> offsets{0};  // each block's first global slot, then the total
};

// The owned simplices as a mesh store (mesh/compact.hpp: live, get, order_names, prefetch) over
// the blocks' arrays: `rank` names each input point by its place on the points' curve (the
// single call's order names), so compact_live_sorted puts them in the single call's order.
template <int K, class Record>
struct OwnedStore {
  const std::int64_t* const* s;
  const std::int64_t* const* nb;
  const std::int64_t* off;
  int blocks;
  const std::int32_t* rank;
  void at(std::int64_t t, int& b, std::int64_t& i) const {
    b = int(std::upper_bound(off, off + blocks + 1, t) - off) - 1;
    i = t - off[b];
  }
  bool live(std::int64_t) const { return true; }
  void prefetch(std::int64_t) const {}
  void order_names(std::int64_t t, std::int32_t* w) const {
    int b;
    std::int64_t i;
    at(t, b, i);
    for (int k = 0; k < K; ++k) w[k] = rank[s[b][K * i + k]];
  }
  Record get(std::int64_t t) const {
    int b;
    std::int64_t i;
    at(t, b, i);
    Record r;
    for (int k = 0; k < K; ++k) {
      r.v[k] = std::int32_t(s[b][K * i + k]);
      r.n[k] = std::int32_t(nb[b][K * i + k]);
    }
    return r;
  }
};

}  // namespace gpugeom::blocks_detail
