// The blocks' owned simplices (owned.hpp) where the assembling module's executor reads them, with
// the order names of the single call: shared by 2D's and 3D's assemble_blocks (their
// impl/assemble.inl), on either executor. On the CPU executor the store reads the blocks' host
// arrays as they are; on the GPU they are copied to the device once, so that the output order
// (compact_live_sorted) and the arrays a single call adds (vertex map, hull facets) are made
// there as a single call makes them.
#pragma once
#include <cstdint>

#include "blocks/owned.hpp"
#include "gpugeom/common.hpp"
#include "mesh/compact.hpp"

namespace gpugeom::blocks_detail {

template <int K, class Exec>
struct OwnedOn {
  // (s, nb: empty on the CPU executor)
  typename Exec::template Buffer<std::int32_t> s, nb, rank;
  OwnedStore<K, mesh::SimplexRecord<K>> store{};
  std::int64_t count = 0;
};

// orig: per point on the curve, its input index (the m distinct points prepared); n: inputs.
template <int K, class Exec>
OwnedOn<K, Exec> owned_on(Exec& ex, const OwnedBlocks& B, const std::int32_t* orig, std::int64_t m,
                          std::int64_t n) {
  OwnedOn<K, Exec> o;
  o.count = B.offsets.back();
  o.rank = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* rk = o.rank.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t w) { rk[orig[w]] = std::int32_t(w); });
  const std::int32_t* s = B.simplices.data();
  const std::int32_t* nb = B.neighbors.data();
  if constexpr (Exec::backend != Backend::Cpu) {
    o.s = ex.template alloc<std::int32_t>(std::size_t(K * o.count));
    o.nb = ex.template alloc<std::int32_t>(std::size_t(K * o.count));
    ex.from_host(s, K * o.count, o.s.data());
    ex.from_host(nb, K * o.count, o.nb.data());
    s = o.s.data();
    nb = o.nb.data();
  }
  o.store = {s, nb, rk};
  return o;
}

}  // namespace gpugeom::blocks_detail
