// Visibility walks to the simplex holding a point (internal; host and device code), shared by
// find_simplex2d/3d (locate.cpp) and the constrained triangulation's domain step.
//
// A walk leaves a simplex through a facet whose plane separates it from the query (an exact
// negative orientation with the query in place of the opposite vertex). In a Delaunay
// triangulation such walks end for any choice of facet; the choice here rotates with the step
// so that no fixed pattern can cycle in a non-Delaunay input, and a walk longer than the number
// of simplices falls back to the exhaustive scan, so a bad input costs time, never a wrong
// answer or a hang. Leaving the hull through a facet that separates means the query is outside
// (the triangulation is convex).
#pragma once
#include <cstdint>

#include "base/hd.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::locate_detail {

// D = 2 or 3: simplices of D + 1 vertices.
template <int D>
struct Mesh {
  const double* p;
  std::int64_t n;
  const std::int32_t* cells;
  const std::int32_t* nbr;
  std::int64_t ncell;
};

template <int D>
GG_HD inline int side(const Mesh<D>& m, std::int64_t c, int k, const double* q, double* s) {
  const double* v[D + 1];
  for (int j = 0; j <= D; ++j) v[j] = j == k ? q : m.p + std::int64_t(D) * m.cells[(D + 1) * c + j];
  if constexpr (D == 2)
    return pred::orient2d(v[0], v[1], v[2], s);
  else
    return pred::orient3d(v[0], v[1], v[2], v[3], s);
}

// -1 when q is in c (orientations all >= 0), else a facet it lies beyond (the first negative
// one from `start`).
template <int D>
GG_HD inline int beyond(const Mesh<D>& m, std::int64_t c, const double* q, int start, double* s) {
  for (int i = 0; i <= D; ++i) {
    const int k = (start + i) % (D + 1);
    if (side(m, c, k, q, s) < 0) return k;
  }
  return -1;
}

template <int D>
GG_HD inline std::int32_t scan(const Mesh<D>& m, const double* q, double* s) {
  // Outside the hull no simplex holds q.
  for (std::int64_t c = 0; c < m.ncell; ++c)
    if (beyond(m, c, q, 0, s) < 0) return std::int32_t(c);
  return -1;
}

template <int D>
GG_HD inline std::int32_t walk(const Mesh<D>& m, std::int64_t c, const double* q, double* s) {
  for (std::int64_t step = 0; step <= m.ncell; ++step) {
    const int k = beyond(m, c, q, int(step % (D + 1)), s);
    if (k < 0) return std::int32_t(c);
    const std::int32_t next = m.nbr[(D + 1) * c + k];
    if (next < 0) return -1;
    c = next;
  }
  return scan(m, q, s);
}

}  // namespace gpugeom::locate_detail
