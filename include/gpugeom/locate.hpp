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
/// an exhaustive scan as the bound on any walk, so the answer never depends on the walk. There is
/// no device entry: the walks are short, and the triangulation is on the host already.
#pragma once
#include <cstdint>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// The caller's array for the answers (m entries, as every capability's `into`): given, the
/// answers are written there and the result is empty.
struct LocateBuffers {
  OutBuffer<std::int32_t> simplices;  ///< the simplex of each query, -1 outside
};
/// Options of find_simplex2d and find_simplex3d. The walks run on the host threads
/// (RunOptions::threads); Backend::Cuda is refused (Error(Unsupported)), as there is no device
/// point location to run.
struct LocateOptions : RunOptions {
  LocateBuffers into;  ///< optional
};

/// xy: n points (x, y interleaved); triangles / neighbors: 3 per triangle; queries: m points.
/// Throws Error(InvalidInput) for NaN/Inf queries or indices outside [0, n), and
/// Error(InvalidArgument) for an `into.simplices` of another length than m.
HostVector<std::int32_t> find_simplex2d(const double* xy, std::int64_t n,
                                        const std::int32_t* triangles,
                                        const std::int32_t* neighbors, std::int64_t num_triangles,
                                        const double* queries, std::int64_t m,
                                        const LocateOptions& opt = {});
/// xyz: n points; tetrahedra / neighbors: 4 per tetrahedron; queries: m points (x, y, z).
HostVector<std::int32_t> find_simplex3d(const double* xyz, std::int64_t n,
                                        const std::int32_t* tetrahedra,
                                        const std::int32_t* neighbors, std::int64_t num_tetrahedra,
                                        const double* queries, std::int64_t m,
                                        const LocateOptions& opt = {});

}  // namespace gpugeom
