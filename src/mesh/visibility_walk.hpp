// The stochastic visibility walk of the CPU executor's cavity insertions (issue 53): 2D and 3D
// Delaunay and the 3D hull locate each point by it (delaunay2d/impl/one_by_one.inl,
// delaunay3d/impl/one_by_one.inl, hull3d/impl/one_by_one.inl), over their own records and
// tests. From a simplex, it leaves across a face with the point strictly beyond, trying the faces
// from one drawn at random (a walk that always prefers the same face can cycle where the
// triangulation is not Delaunay), never straight back across the face it came by.
//
// With other threads writing the store (threads), a record read may be stale or torn: a walk can
// only be misled by one, never corrupt anything, and where it ends the face back to the simplex it
// came from is tested too (the record that led there may have been stale), so that it ends only on
// a simplex that holds the point by the record it read; otherwise it gives up (-1) and the point
// waits.
#pragma once
#include <cstdint>

#include "mesh/adjacency.hpp"

namespace gpugeom::mesh::cavities {

// The slot (K faces a simplex, neighbour pointers read by Adj: mesh/adjacency.hpp) whose simplex
// holds the point, from slot t, its record left in R;
// -1 where the walk gives up: a record `ok` rejects (torn, removed), more than `steps` steps
// (steps < 0: no bound), or with threads an end the face back contradicts.
//   read(t) -> Rec (a record with neighbour pointers n[K]);
//   ok(R): the record can be trusted;
//   beyond(R, k): the point lies strictly beyond face k of R;
//   reached(t, R): each record read (where the walk got to; prefetches).
// rng: the walk's xorshift state, advanced once a step.
template <int K, class Adj, class Rec, class Read, class Ok, class Beyond, class Reached>
std::int32_t visibility_walk(std::int32_t t, std::uint32_t& rng, int steps, bool threads, Rec& R,
                             Read read, Ok ok, Beyond beyond, Reached reached) {
  std::int32_t came = -1;
  for (int step = 0; steps < 0 || step < steps; ++step) {
    const Rec T = read(t);  // (a local: kept in registers, where R is memory of the caller's)
    reached(t, T);
    if (!ok(T)) return -1;
    rng ^= rng << 13, rng ^= rng >> 17, rng ^= rng << 5;
    const int s = int(rng % unsigned(K));
    std::int32_t next = -1;  // (a neighbour across a face with the point on its far side)
    for (int j = 0; j < K && next < 0; ++j) {
      const int k = (s + j) % K;
      const std::int32_t nb = Adj::simplex_of(T.n[k]);
      if (nb != came && beyond(T, k)) next = nb;
    }
    if (next < 0) {
      if (threads && came >= 0)
        for (int k = 0; k < K; ++k)
          if (Adj::simplex_of(T.n[k]) == came && beyond(T, k)) return -1;
      R = T;
      return t;
    }
    came = t, t = next;
  }
  return -1;
}

}  // namespace gpugeom::mesh::cavities
