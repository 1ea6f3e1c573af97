// Simplices joined into classes, each class one Voronoi vertex (internal; the 2D and 3D Voronoi
// diagrams): simplices whose points lie on one circle or sphere exactly share a circumcentre,
// and the diagram gives them one vertex. The unions come from the lock-free union-find
// (union_find.hpp), whose roots are each class's smallest simplex whatever the order of the
// unions; the classes are numbered in the order of their smallest simplices, so the numbers are
// the same on both executors and any thread count.
#pragma once
#include <cstdint>

#include "base/hd.hpp"
#include "gpugeom/removed.hpp"
#include "mesh/union_find.hpp"

namespace gpugeom::mesh {

// The vertices along a walk round a point (a cell) or an edge (a 3D ridge): consecutive simplices
// of one class give one vertex, and a closed walk's last run is dropped where it is its first
// run's class.
struct ClassRun {
  std::int32_t first = -1, last = -1;
  std::int64_t runs = 0;
  GG_HD bool step(std::int32_t c) {  // whether class c starts a run (is written)
    if (runs && c == last) return false;
    if (!runs) first = c;
    last = c;
    ++runs;
    return true;
  }
  GG_HD std::int64_t length(bool closed) const {
    return closed && runs > 1 && last == first ? runs - 1 : runs;
  }
};

// The point whose Voronoi cell a point has: itself, or the one it duplicates. A point removed
// from a kept triangulation (kRemovedPoint in the duplicate map) has an empty cell.
struct CellSource {
  const std::int32_t* dup;  // (null: every point is a vertex)
  GG_HD std::int64_t operator()(std::int64_t i) const { return dup && dup[i] >= 0 ? dup[i] : i; }
  GG_HD bool removed(std::int64_t i) const { return dup && dup[i] == kRemovedPoint; }
};

template <class Exec>
struct Classes {
  typename Exec::template Buffer<std::int32_t> of;     // per simplex, its class
  typename Exec::template Buffer<std::int32_t> first;  // per class, its smallest simplex
  std::int64_t count = 0;
};

// n simplices, parent: their union-find forest after the unions; joined: how many unions were
// asked for (0: every simplex is a class of its own; some may have found their two simplices
// already joined, so the classes are counted here). parent is left with its paths halved.
// [synchronises]
template <class Exec>
Classes<Exec> number_classes(Exec& ex, std::int32_t* parent, std::int64_t n, std::int64_t joined) {
  using I32 = std::int32_t;
  using I64 = std::int64_t;
  Classes<Exec> C;
  C.of = ex.template alloc<I32>(std::size_t(n));
  I32* of = C.of.data();
  if (joined == 0) {
    C.count = n;
    C.first = ex.template alloc<I32>(std::size_t(n));
    I32* first = C.first.data();
    ex.for_each_index(
        n, GG_LAMBDA(I64 t) { of[t] = first[t] = I32(t); });
    return C;
  }
  // (finding only halves paths now: the roots stay where they are)
  ex.for_each_index(
      n, GG_LAMBDA(I64 t) { of[t] = uf_find(parent, I32(t)); });
  auto d_rank = ex.template alloc<I64>(std::size_t(n + 1));
  I64* rank = d_rank.data();
  ex.exclusive_scan_of(
      n + 1, GG_LAMBDA(I64 t)->I64 { return t < n && of[t] == t; }, rank);
  ex.to_host(rank + n, 1, &C.count);
  C.first = ex.template alloc<I32>(std::size_t(C.count));
  I32* first = C.first.data();
  ex.compact_indices(
      n, GG_LAMBDA(I64 t) { return of[t] == t; }, first);
  ex.for_each_index(
      n, GG_LAMBDA(I64 t) { of[t] = I32(rank[of[t]]); });
  return C;
}

}  // namespace gpugeom::mesh
