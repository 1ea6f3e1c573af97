/// @file
/// The Voronoi diagram of 3D points (issue 49), from their Delaunay tetrahedralisation
/// (delaunay3d.hpp), on either executor.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "gpugeom/common.hpp"
#include "gpugeom/delaunay3d.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// Statistics of a 3D Voronoi diagram: RunStats (phase "voronoi"; "upload" before it where the
/// points went up to CUDA; the one-call host entry adds, with tri, "copy_tetrahedralisation")
/// and the counters.
struct Voronoi3dStats : RunStats {
  std::int64_t voronoi_vertices = 0, voronoi_ridges = 0;  ///< the diagram's

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// Where voronoi3d and voronoi3d_device write the diagram, when given: the caller's arrays (host
/// memory for voronoi3d, device memory for voronoi3d_device; host memory where it runs on the
/// CPU executor), each at least as long as the result's array of that name: vertices 3
/// num_vertices, ridge_points 2 num_ridges, ridge_offsets num_ridges + 1, ridge_vertices
/// num_ridge_vertices, region_offsets num_points + 1, region_vertices num_region_vertices,
/// simplex_vertex the tetrahedralisation's num_tetrahedra. They are checked once the counts are
/// known and before anything is written (Error(InvalidArgument) naming the array and both
/// lengths). An output written into a caller's array is empty (null) in the result; the counts
/// say how much of it was written.
struct Voronoi3dBuffers {
  OutBuffer<double> vertices;
  OutBuffer<std::int32_t> ridge_points;
  OutBuffer<std::int64_t> ridge_offsets;
  OutBuffer<std::int32_t> ridge_vertices;
  OutBuffer<std::int64_t> region_offsets;
  OutBuffer<std::int32_t> region_vertices, simplex_vertex;
};

/// How voronoi3d (from a tetrahedralisation) and voronoi3d_device run: the executor
/// (RunOptions) and where the arrays go.
struct Voronoi3dOptions : RunOptions {
  Voronoi3dBuffers into;  ///< optional
};

/// The Voronoi diagram of the points (issue 49), dual to their Delaunay tetrahedralisation, in
/// SciPy's `Voronoi` layout with flat arrays. Its vertices are the circumcentres of the
/// tetrahedra, one per sphere: tetrahedra whose points lie on one sphere exactly (the exact
/// in-sphere test) share a vertex, numbered in the order of their first tetrahedra. A ridge
/// separates two points whose cells share a face of positive area (an edge of the Delaunay
/// subdivision); edges that only cut a cospherical cell into tetrahedra have none, so no ridge is
/// degenerate.
struct Voronoi3d {
  std::int64_t num_points = 0, num_vertices = 0, num_ridges = 0, num_ridge_vertices = 0,
               num_region_vertices = 0;
  HostVector<double> vertices;             ///< 3 per vertex
  HostVector<std::int32_t> ridge_points;   ///< 2 per ridge: the points it separates
  HostVector<std::int64_t> ridge_offsets;  ///< ridges + 1 offsets into ridge_vertices
  /// Each ridge's vertices in cyclic order; an unbounded ridge starts with -1 (the vertex at
  /// infinity), its first and last vertices then being where its two rays leave.
  HostVector<std::int32_t> ridge_vertices;
  /// Per input point, its cell's vertices in increasing order, -1 first for an unbounded cell.
  /// Duplicate points share the cell of the point they duplicate; a point removed from a kept
  /// tetrahedralisation has an empty cell.
  HostVector<std::int64_t> region_offsets;  ///< n + 1 offsets into region_vertices
  HostVector<std::int32_t> region_vertices;
  HostVector<std::int32_t> simplex_vertex;  ///< per tetrahedron, its Voronoi vertex
  Voronoi3dStats stats;
};
/// From a tetrahedralisation on the host (delaunay3d's, its arrays in the result), computed on
/// the executor opt picks: on the CPU executor from the caller's arrays where they are; on CUDA
/// the points and the tetrahedralisation go up once and only the diagram comes back (or goes
/// into opt.into). The arrays are the same on both. Throws Error(InvalidArgument) when tri does
/// not belong to these n points or an array of opt.into is too short.
Voronoi3d voronoi3d(const double* xyz, std::int64_t n, const Triangulation3d& tri,
                    const Voronoi3dOptions& opt = {});
/// The tetrahedralisation of host points and its Voronoi diagram in one call, both made on the
/// executor opt picks: on CUDA the points cross the bus once and only the results come back.
/// tri, when given, receives the tetrahedralisation (as delaunay3d returns it; opt.into is not
/// used). A composition of two capabilities: for the diagram in the caller's arrays, run
/// delaunay3d (or delaunay3d_device) and voronoi3d (or voronoi3d_device) with
/// Voronoi3dOptions::into. Throws as delaunay3d.
Voronoi3d voronoi3d(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                    Triangulation3d* tri = nullptr);

/// The result of voronoi3d_device: arrays in device memory (host memory on the CPU executor).
struct DeviceVoronoi3d {
  std::int64_t num_points = 0, num_vertices = 0, num_ridges = 0, num_ridge_vertices = 0,
               num_region_vertices = 0;
  std::shared_ptr<double> vertices;               ///< 3 * num_vertices
  std::shared_ptr<std::int32_t> ridge_points;     ///< 2 * num_ridges
  std::shared_ptr<std::int64_t> ridge_offsets;    ///< num_ridges + 1
  std::shared_ptr<std::int32_t> ridge_vertices;   ///< num_ridge_vertices
  std::shared_ptr<std::int64_t> region_offsets;   ///< num_points + 1
  std::shared_ptr<std::int32_t> region_vertices;  ///< num_region_vertices
  std::shared_ptr<std::int32_t> simplex_vertex;   ///< tri.num_tetrahedra
  Backend backend = Backend::Cuda;                ///< where the arrays are: Cuda = device memory
  Voronoi3dStats stats;
};
/// The same diagram for a tetrahedralisation left where delaunay3d_device or a kept one put it,
/// computed there (tri.backend's executor, opt.stream of opt.device; opt.backend is not read):
/// device_xyz its n points (device memory; host memory where tri.backend is Backend::Cpu). The
/// arrays as Voronoi3d's, in device memory of the call's resource (RunOptions::memory) (freed
/// when the last copy of their pointer goes), or in the caller's (opt.into). Throws as voronoi3d.
DeviceVoronoi3d voronoi3d_device(const double* device_xyz, std::int64_t n,
                                 const DeviceTriangulation3d& tri,
                                 const Voronoi3dOptions& opt = {});

}  // namespace gpugeom
