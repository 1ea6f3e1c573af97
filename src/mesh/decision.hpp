// The marker for a decision the filter could not make, shared by the mesh modules' decision
// arrays (int8): delaunay2d's edge tests, hull3d's point location and edge actions. Every
// decision a module takes is -1 (none) or a small non-negative value (a face, an action); an
// undecided one is kUndecided, or kUndecided + k where the test stopped at face k, and the exact
// stage goes on from there.
#pragma once
#include "base/hd.hpp"

namespace gpugeom::mesh {

constexpr int kUndecided = -128;
constexpr int kMaxUndecidedFace = 7;  // faces of a simplex of dimension 6 at most

GG_INLINE constexpr int undecided_at(int face) {
  return kUndecided + face;
}
GG_INLINE constexpr bool is_undecided(int d) {
  return d >= kUndecided && d <= kUndecided + kMaxUndecidedFace;
}
GG_INLINE constexpr int undecided_face(int d) {
  return d - kUndecided;
}

}  // namespace gpugeom::mesh
