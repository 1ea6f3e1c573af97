// Simplex adjacency, one encoding for every mesh module (delaunay2d's triangles, hull3d's
// facets, delaunay3d's tetrahedra): the neighbour of simplex s across the face opposite its
// local vertex k is stored as enc(n, j) = 4n + j, with n the neighbour's slot and j the
// neighbour's local index of its vertex opposite the same face, in 32 bits. Two readings:
//   Adjacency (the free functions enc / simplex_of / loc_of): signed, slots below 2^29, so
//     negative values stay free for "no neighbour" (hull3d's removed facets use -1);
//   WideAdjacency: the same bits read as unsigned, slots below 2^30, every value a neighbour
//     (delaunay2d, whose 2n triangles reach 2^30 at 2^29 points and are never without one;
//     delaunay3d, whose 7.3 tetrahedra a point reach 2^29 at 7·10^7 points: its stores stop at
//     2^30 - 1 slots, so that -1 stays free for its dead tetrahedra).
#pragma once
#include <cstdint>

#include "base/hd.hpp"

namespace gpugeom::mesh {

GG_INLINE std::int32_t enc(std::int32_t s, int k) {
  return s * 4 + k;
}
GG_INLINE std::int32_t simplex_of(std::int32_t e) {
  return e >> 2;
}
GG_INLINE int loc_of(std::int32_t e) {
  return e & 3;
}

struct Adjacency {
  static GG_INLINE std::int32_t enc(std::int32_t s, int k) { return mesh::enc(s, k); }
  static GG_INLINE std::int32_t simplex_of(std::int32_t e) { return mesh::simplex_of(e); }
  static GG_INLINE int loc_of(std::int32_t e) { return mesh::loc_of(e); }
};
struct WideAdjacency {
  static constexpr std::int64_t kMaxSlots = std::int64_t(1) << 30;
  static GG_INLINE std::int32_t enc(std::int32_t s, int k) {
    return std::int32_t(std::uint32_t(s) * 4u + std::uint32_t(k));
  }
  static GG_INLINE std::int32_t simplex_of(std::int32_t e) {
    return std::int32_t(std::uint32_t(e) >> 2);
  }
  static GG_INLINE int loc_of(std::int32_t e) { return e & 3; }
};

}  // namespace gpugeom::mesh
