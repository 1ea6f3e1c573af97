/// @file
/// Exact point location in a triangulation (SciPy's Delaunay.find_simplex): for each query point,
/// a simplex that contains it, or -1 outside the convex hull.
///
/// Exactness: "contains" is decided by exact orientation tests without perturbation, so a query
/// on a shared edge, face or vertex gets one of the simplices that hold it (never -1), and a query
/// outside the hull by any margin gets -1. The triangulation must be convex (a Delaunay
/// triangulation or tetrahedralisation as this library returns it, with neighbors in its
/// convention: the simplex opposite vertex k, -1 on the hull).
///
/// Queries run on the host threads (RunOptions::threads), each a visibility walk from the simplex
/// found for the previous query of its thread (so sorted or clustered queries walk little), with
/// an exhaustive scan as the bound on any walk, so the answer never depends on the walk.
#pragma once
#include <cstdint>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// xy: n points (x, y interleaved); triangles / neighbors: 3 per triangle; queries: m points.
/// Throws Error(InvalidInput) for NaN/Inf queries or indices outside [0, n).
HostVector<std::int32_t> find_simplex2d(const double* xy, std::int64_t n,
                                        const std::int32_t* triangles,
                                        const std::int32_t* neighbors, std::int64_t num_triangles,
                                        const double* queries, std::int64_t m, int threads = 0);
/// xyz: n points; tetrahedra / neighbors: 4 per tetrahedron; queries: m points (x, y, z).
HostVector<std::int32_t> find_simplex3d(const double* xyz, std::int64_t n,
                                        const std::int32_t* tetrahedra,
                                        const std::int32_t* neighbors, std::int64_t num_tetrahedra,
                                        const double* queries, std::int64_t m, int threads = 0);

}  // namespace gpugeom
