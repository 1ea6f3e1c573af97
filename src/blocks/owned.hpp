// What the blocks of a multi-device triangulation hand the module that assembles it (the
// modules' assemble_blocks): per block its owned simplices in global input indices and their
// neighbours' codes (a row of the block, -1 none, -2 another block's: block_pass.hpp), 32-bit,
// where the block made them (its device's memory; host memory on the CPU executor), with the
// answers to its face requests. The assembly copies them to its own device (a peer copy where
// the GPUs have one), turns the rows into global slots and writes the answers there, so the
// rows never pass through the host. (Input indices and slots fit: a single call's arrays are
// 32-bit too.)
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "base/hd.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::blocks_detail {

struct OwnedPart {
  std::shared_ptr<std::int32_t> simplices, neighbors;  // K entries a simplex, `count` simplices
  std::int64_t count = 0;
  int device = -1;  // where they are (-1: host memory)
  // The answers: at position pos[i] (row * K + face) the global slot across, -1 on the hull.
  HostVector<std::int64_t> pos, across;
};

struct OwnedBlocks {
  std::vector<OwnedPart> parts;
  std::vector<std::int64_t> offsets{0};  // each block's first global slot, then the total
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
