// The tetrahedron store of delaunay3d: phase 1 builds it, phase 2 (repair.inl) rewrites it
// (internal).
#pragma once
#include <cstdint>

namespace gpugeom::del3d {

// One slot: four vertices (a positively oriented tetrahedron; index m is the infinity point)
// and the four neighbours (mesh/adjacency.hpp's encoding: the tetrahedron across the face
// opposite vertex k). A dead slot has v[0] = -1. 32 bytes: one memory sector per read.
struct alignas(32) Tet {
  std::int32_t v[4];
  std::int32_t n[4];
};

}  // namespace gpugeom::del3d
