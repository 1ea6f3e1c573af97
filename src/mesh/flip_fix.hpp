// The two-phase flip protocol of every mesh module (delaunay2d's 2-2 flips, hull3d's 2-2 and
// 3-1 flips, and the 2-3 / 3-2 flips to come).
//
// Phase 1: each winning flip rewrites its own slots only: the new simplices, their inner
// neighbour pointers, the slot's stamp (the round), and a note of where each outer face went;
// outer neighbour pointers are copied as they were. No thread writes a slot another flip owns,
// so flips of one round cannot race.
// Phase 2, once every flip of the round is done: each outer face (slot x, local l) of a flipped
// simplex looks at the old neighbour across it. If that neighbour did not flip this round, the
// neighbour's pointer is set back at x (only this thread knows x). If it flipped too, the face
// now lies somewhere in that neighbour's flip; x points there, and the neighbour's own phase 2
// points back at x. Each pointer therefore has exactly one writer.
//
// Where a face of a flipped slot went is the store's business (Store::moved): delaunay2d finds
// it by the edge's vertices in the slot and its partner (no extra array in its 32-byte record),
// hull3d reads a per-face remap array (a 3-1 flip spreads a slot's faces over other slots).
#pragma once
#include <cstdint>

#include "base/hd.hpp"
#include "mesh/adjacency.hpp"

namespace gpugeom::mesh {

// Phase 2 for outer face l of flipped slot x, whose pointer after phase 1 is `outer` (the old
// neighbour, as it was), `flipped` telling whether that neighbour changed this round. Store:
//   GG_HD void set(std::int32_t slot, int face, std::int32_t e): a neighbour pointer;
//   GG_HD std::int32_t moved(std::int32_t outer): where face loc_of(outer) of the changed slot
//     simplex_of(outer) went, encoded.
// Returns the final neighbour's slot. Adj: the encoding's reading (adjacency.hpp).
template <class Adj = Adjacency, class Store>
GG_HD std::int32_t fix_face(const Store& S, std::int32_t x, int l, std::int32_t outer,
                            bool flipped) {
  if (!flipped) {
    S.set(Adj::simplex_of(outer), Adj::loc_of(outer), Adj::enc(x, l));
    return Adj::simplex_of(outer);
  }
  const std::int32_t to = S.moved(outer);
  S.set(x, l, to);
  return Adj::simplex_of(to);
}

}  // namespace gpugeom::mesh
