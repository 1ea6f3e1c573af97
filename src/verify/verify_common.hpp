// Helpers shared by the checkers (internal to src/verify).
#pragma once
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "predicates/predicates.hpp"
#include "verify.hpp"

namespace gpugeom::verify::detail {

// Point v of an array of D coordinates per point, indexed in 64 bits (3 * v overflows an int32
// index from v = 715 827 883 on: hulls of 10^9 points reach it).
template <int D>
inline const double* at(const double* p, std::int64_t v) {
  return p + D * v;
}

inline double* scratch() {
  thread_local std::vector<double> s(pred::kInsphereScratch + pred::kOrient4dScratch);
  return s.data();
}
// Vertex indices in range, distinct within each cell, not duplicates; every kept point used.
bool check_cells(Report& r, std::int64_t n, const std::int32_t* cells, std::int64_t ncell, int k,
                 const std::int32_t* dup_of, const double* pts, int dim);
std::string cell_name(int k, std::int64_t c, const std::int32_t* cells);

// Edge keys: directed (u to v), and undirected (the lower index first).
std::uint64_t directed(std::uint32_t u, std::uint32_t v);
std::uint64_t undirected(std::uint32_t u, std::uint32_t v);
// Every interior edge of a valid triangulation locally Delaunay (exact in-circle; cocircular
// allowed), except the edges in `exempt` (undirected keys).
bool locally_delaunay(Report& r, const double* p, const std::int32_t* t, std::int64_t nt,
                      const std::unordered_set<std::uint64_t>& exempt);

}  // namespace gpugeom::verify::detail
