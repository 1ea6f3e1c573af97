// Exact point location by visibility walks (see include/gpugeom/locate.hpp).
//
// A walk leaves a simplex through a facet whose plane separates it from the query (an exact
// negative orientation with the query in place of the opposite vertex). In a Delaunay
// triangulation such walks end for any choice of facet; the choice here rotates with the step
// so that no fixed pattern can cycle in a non-Delaunay input, and a walk longer than the number
// of simplices falls back to the exhaustive scan, so a bad input costs time, never a wrong
// answer or a hang. Leaving the hull through a facet that separates means the query is outside
// (the triangulation is convex).
#include "gpugeom/locate.hpp"

#include <omp.h>

#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include "predicates/predicates.hpp"

namespace gpugeom {

namespace {

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
int side(const Mesh<D>& m, std::int64_t c, int k, const double* q, double* s) {
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
int beyond(const Mesh<D>& m, std::int64_t c, const double* q, int start, double* s) {
  for (int i = 0; i <= D; ++i) {
    const int k = (start + i) % (D + 1);
    if (side(m, c, k, q, s) < 0) return k;
  }
  return -1;
}

template <int D>
std::int32_t scan(const Mesh<D>& m, const double* q, double* s) {
  // Outside the hull no simplex holds q.
  for (std::int64_t c = 0; c < m.ncell; ++c)
    if (beyond(m, c, q, 0, s) < 0) return std::int32_t(c);
  return -1;
}

template <int D>
std::int32_t walk(const Mesh<D>& m, std::int64_t c, const double* q, double* s) {
  for (std::int64_t step = 0; step <= m.ncell; ++step) {
    const int k = beyond(m, c, q, int(step % (D + 1)), s);
    if (k < 0) return std::int32_t(c);
    const std::int32_t next = m.nbr[(D + 1) * c + k];
    if (next < 0) return -1;
    c = next;
  }
  return scan(m, q, s);
}

template <int D>
HostVector<std::int32_t> locate(const Mesh<D>& m, const double* q, std::int64_t nq, int threads) {
  if (nq < 0) throw Error(ErrorCode::InvalidArgument, "find_simplex: negative query count");
  for (std::int64_t i = 0; i < std::int64_t(D + 1) * m.ncell; ++i) {
    if (m.cells[i] < 0 || m.cells[i] >= m.n)
      throw Error(ErrorCode::InvalidInput, "find_simplex: simplex " + std::to_string(i / (D + 1)) +
                                               " has vertex " + std::to_string(m.cells[i]) +
                                               ", outside the " + std::to_string(m.n) + " points");
    if (m.nbr[i] < -1 || m.nbr[i] >= m.ncell)
      throw Error(ErrorCode::InvalidInput, "find_simplex: simplex " + std::to_string(i / (D + 1)) +
                                               " has neighbour " + std::to_string(m.nbr[i]) +
                                               ", outside the " + std::to_string(m.ncell) +
                                               " simplices");
  }
  for (std::int64_t i = 0; i < D * nq; ++i)
    if (!std::isfinite(q[i]))
      throw Error(ErrorCode::InvalidInput, "find_simplex: query point " + std::to_string(i / D) +
                                               " has a coordinate that is NaN or infinite");
  HostVector<std::int32_t> out(std::size_t(nq), -1);
  if (m.ncell == 0 || nq == 0) return out;
  const int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel num_threads(nt)
  {
    std::vector<double> s(D == 2 ? pred::kOrient2dScratch : pred::kOrient3dScratch);
    std::int64_t c = 0;  // each thread walks on from its previous answer
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < nq; ++i) {
      const std::int32_t r = walk(m, c, q + D * i, s.data());
      out[std::size_t(i)] = r;
      if (r >= 0) c = r;
    }
  }
  return out;
}

}  // namespace

HostVector<std::int32_t> find_simplex2d(const double* xy, std::int64_t n,
                                        const std::int32_t* triangles,
                                        const std::int32_t* neighbors, std::int64_t num_triangles,
                                        const double* queries, std::int64_t m, int threads) {
  return locate(Mesh<2>{xy, n, triangles, neighbors, num_triangles}, queries, m, threads);
}

HostVector<std::int32_t> find_simplex3d(const double* xyz, std::int64_t n,
                                        const std::int32_t* tetrahedra,
                                        const std::int32_t* neighbors, std::int64_t num_tetrahedra,
                                        const double* queries, std::int64_t m, int threads) {
  return locate(Mesh<3>{xyz, n, tetrahedra, neighbors, num_tetrahedra}, queries, m, threads);
}

}  // namespace gpugeom
