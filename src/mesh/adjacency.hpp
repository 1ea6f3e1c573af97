// Simplex adjacency, one encoding for every mesh module (delaunay2d's triangles, hull3d's
// facets, the tetrahedra to come): the neighbour of simplex s across the face opposite its
// local vertex k is stored as enc(n, j) = 4n + j, with n the neighbour's slot and j the
// neighbour's local index of its vertex opposite the same face. Two bits hold the local index
// of a triangle's or a tetrahedron's vertex, so slots stay below 2^29.
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

}  // namespace gpugeom::mesh
