// The blocks' owned simplices (owned.hpp) where the assembling module's executor reads them, with
// the order names of the single call: shared by 2D's and 3D's assemble_blocks (their
// impl/assemble.inl), on either executor. Each block's rows are copied from where the block
// made them (its device, or the host on the CPU executor) into one pair of arrays, their rows
// turned into global slots and the answers to their face requests written in, so that the
// output order (compact_live_sorted) and the arrays a single call adds (vertex map, hull
// facets) are made there as a single call makes them.
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "blocks/owned.hpp"
#include "exec/atomics.hpp"
#include "gpugeom/common.hpp"
#include "mesh/compact.hpp"

namespace gpugeom::blocks_detail {

template <int K, class Exec>
struct OwnedOn {
  typename Exec::template Buffer<std::int32_t> s, nb, rank;
  OwnedStore<K, mesh::SimplexRecord<K>> store{};
  std::int64_t count = 0;
};

// orig: per point on the curve, its input index (the m distinct points prepared); n: inputs.
// Throws Error(Internal) where a face of another block's neighbour has no answer, or an answer
// is not for such a face (a bug).
template <int K, class Exec>
OwnedOn<K, Exec> owned_on(Exec& ex, const OwnedBlocks& B, const std::int32_t* orig, std::int64_t m,
                          std::int64_t n) {
  OwnedOn<K, Exec> o;
  o.count = B.offsets.back();
  o.rank = ex.template alloc<std::int32_t>(std::size_t(n));
  std::int32_t* rk = o.rank.data();
  ex.for_each_index(
      m, GG_LAMBDA(std::int64_t w) { rk[orig[w]] = std::int32_t(w); });
  o.s = ex.template alloc<std::int32_t>(std::size_t(K * o.count));
  o.nb = ex.template alloc<std::int32_t>(std::size_t(K * o.count));
  std::int32_t* s = o.s.data();
  std::int32_t* nb = o.nb.data();
  auto bad_b = ex.template alloc<std::int64_t>(2);  // (an answer not for a -2 face; a -2 left)
  std::int64_t* bad = bad_b.data();
  ex.fill(bad, 2, std::int64_t(-1));
  // every block's answers in one upload: positions, then the slots across
  std::vector<std::int64_t> at{0};
  for (const OwnedPart& p : B.parts) at.push_back(at.back() + std::int64_t(p.pos.size()));
  const std::int64_t answers = at.back();
  auto ans_b = ex.template alloc<std::int64_t>(std::size_t(2 * answers));
  {
    HostVector<std::int64_t> h(static_cast<std::size_t>(2 * answers));
    for (std::size_t b = 0; b < B.parts.size(); ++b) {
      std::copy(B.parts[b].pos.begin(), B.parts[b].pos.end(), h.begin() + at[b]);
      std::copy(B.parts[b].across.begin(), B.parts[b].across.end(), h.begin() + answers + at[b]);
    }
    ex.from_host(h.data(), 2 * answers, ans_b.data());
  }
  // (direct reads of the blocks' devices where the GPUs have them, until the copies have run)
  std::vector<decltype(ex.peer_access(0))> peers;
  for (const OwnedPart& p : B.parts) peers.push_back(ex.peer_access(p.device));
  for (std::size_t b = 0; b < B.parts.size(); ++b) {
    const OwnedPart& p = B.parts[b];
    const std::int64_t off = B.offsets[b], cells = K * p.count;
    if (!cells) continue;
    std::int32_t* ps = s + K * off;
    std::int32_t* pn = nb + K * off;
    ex.copy(p.simplices.get(), cells, ps);  // (from the block's device: a peer copy)
    ex.copy(p.neighbors.get(), cells, pn);
    const std::int64_t q = std::int64_t(p.pos.size());
    const std::int64_t* pos = ans_b.data() + at[b];
    const std::int64_t* across = ans_b.data() + answers + at[b];
    // the block's rows as global slots, the answers across its -2 faces, and none left
    ex.for_each_index(
        cells, GG_LAMBDA(std::int64_t c) {
          const std::int32_t t = pn[c];
          if (t >= 0) pn[c] = std::int32_t(t + off);
        });
    ex.for_each_index(
        q, GG_LAMBDA(std::int64_t i) {
          const std::int64_t c = pos[i];
          if (c < 0 || c >= cells || pn[c] != -2)
            atomic_max(&bad[0], i);
          else
            pn[c] = std::int32_t(across[i] < 0 ? -1 : across[i]);
        });
    ex.for_each_index(
        cells, GG_LAMBDA(std::int64_t c) {
          if (pn[c] == -2) atomic_max(&bad[1], c);
        });
  }
  std::int64_t h[2];
  ex.to_host(bad, 2, h);  // (synchronises: the blocks' rows may be freed after)
  if (h[0] >= 0 || h[1] >= 0)
    throw Error(ErrorCode::Internal,
                std::string("the several devices' assembly: ") +
                    (h[0] >= 0 ? "an answer is not for a face of another block's neighbour"
                               : "a face of another block's neighbour has no answer") +
                    " (a bug: please report it with the input)");
  o.store = {s, nb, rk};
  return o;
}

}  // namespace gpugeom::blocks_detail
