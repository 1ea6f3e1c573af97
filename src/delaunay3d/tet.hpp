// The tetrahedron store of delaunay3d: phase 1 builds it, phase 2 (repair.inl) rewrites it
// (internal).
#pragma once
#include <cstdint>

#include "mesh/adjacency.hpp"

namespace gpugeom::del3d {

// The store's neighbour encoding: 4 per slot, read as unsigned (mesh::WideAdjacency), so that
// the store reaches 2^30 - 1 slots (10^8 points need about 7.3·10^8). -1, which would name face
// 3 of slot 2^30 - 1, means "no neighbour" (dead slots, faces phase 2 has not linked yet).
using TetAdjacency = mesh::WideAdjacency;
constexpr std::int64_t kMaxTetSlots = TetAdjacency::kMaxSlots - 1;
constexpr std::int32_t kNoNeighbour = -1;
GG_INLINE std::int32_t enc(std::int32_t s, int k) {
  return TetAdjacency::enc(s, k);
}
GG_INLINE std::int32_t simplex_of(std::int32_t e) {
  return TetAdjacency::simplex_of(e);
}
GG_INLINE int loc_of(std::int32_t e) {
  return TetAdjacency::loc_of(e);
}

// One slot: four vertices (a positively oriented tetrahedron; index m is the infinity point)
// and the four neighbours (enc above: the tetrahedron across the face opposite vertex k). A dead
// slot has v[0] = -1. 32 bytes: one memory sector per read.
struct alignas(32) Tet {
  std::int32_t v[4];
  std::int32_t n[4];
};

}  // namespace gpugeom::del3d
