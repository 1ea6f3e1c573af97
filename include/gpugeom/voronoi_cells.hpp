/// @file
/// Voronoi cells of 3D particles in a box, bounded or periodic (issue 49): per point its cell's
/// volume, surface area, centroid, faces and neighbours, as particle codes (Voro++, freud) use
/// them, on either executor.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom {

/// The caller's arrays for the cells (VoronoiCellsOptions::into; each optional, each as the
/// result's array of that name): host memory for voronoi_cells, device memory for
/// voronoi_cells_device (host memory on the CPU executor). volumes and areas need at least n
/// elements, centroids 3 n, face_offsets and vertex_offsets n + 1; the others depend on the
/// result: neighbors and face_areas at least num_faces, face_normals 3 num_faces,
/// face_vertex_offsets num_faces + 1, face_vertices num_face_vertices, vertices 3 num_vertices.
/// They are checked once the counts are known and before anything is written
/// (Error(InvalidArgument) naming the array and both lengths). An output written into a caller's
/// array is empty (null) in the result; the counts say how much of it was written.
struct VoronoiCellsBuffers {
  OutBuffer<double> volumes, areas, centroids;
  OutBuffer<std::int64_t> face_offsets;
  OutBuffer<std::int32_t> neighbors;
  OutBuffer<double> face_areas, face_normals;
  OutBuffer<std::int64_t> face_vertex_offsets;
  OutBuffer<std::int32_t> face_vertices;
  OutBuffer<std::int64_t> vertex_offsets;
  OutBuffer<double> vertices;
};

/// The box [lo, hi] and, per axis, whether it wraps round. Along an axis that does not wrap, the
/// cells are cut by the box's walls and the points must lie in [lo, hi]; along one that wraps,
/// a point's coordinate is taken modulo the box (any value is accepted) and its cell meets the
/// images of the points across the box's sides, as freud and Voro++ compute periodic cells.
struct VoronoiCellsOptions : RunOptions {
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  bool periodic[3] = {false, false, false};
  /// The polygons: each cell's vertices and each face's vertex list. Without them (false) the
  /// measures, neighbours and face areas and normals come sooner (each cell is built once, not
  /// twice) and the polygon arrays are left empty.
  bool polygons = true;
  VoronoiCellsBuffers into;  ///< optional
};

/// Statistics of the Voronoi cells: RunStats (phases "upload", "images" (the periodic images,
/// each attempt), "delaunay", "ridges", "cells", "cells_write") and the counters.
struct VoronoiCellsStats : RunStats {
  /// Periodic images added (last attempt), and the attempts: a periodic box is tried with a
  /// wider layer of images while some cell reaches past it.
  std::int64_t images = 0, attempts = 0;
  /// The faces of all cells.
  std::int64_t faces = 0;
  /// Cells a wall cuts (cut from the box), and of those, cells built again with more room than
  /// a thread keeps.
  std::int64_t cells_cut = 0, cell_overflows = 0;

  std::map<std::string, std::int64_t> counter_map() const override;
};

/// Every point's Voronoi cell within the box. The cells are the Voronoi diagram's (its
/// neighbours are the exact ridges of the Delaunay tetrahedralisation, voronoi3d.hpp), cut by the
/// walls of the box where it does not wrap. Their measures are computed in double precision: a
/// cell no wall cuts (in a periodic box, every cell) from the diagram's circumcentres round its
/// ridges; a cell a wall cuts from the box cut by its neighbours' bisector planes (a vertex within
/// 10^-12 of the cell's size from a plane counts as on it, so no face of area 10^-30 is left where
/// four cells meet at a point). VoronoiCellsStats::cells_cut says how many were cut.
///
/// - Faces: per cell, in the order of their neighbours (walls first), counter-clockwise seen from
///   outside. A face's neighbour is a point index, or a wall: -1 and -2 for the low and high x
///   walls, -3, -4 for y, -5, -6 for z (Voro++'s numbering). In a periodic box a point can meet
///   several images of one neighbour (and even of itself, in a box a few cells wide): one face
///   each.
/// - A duplicate point (equal to an earlier one) has an empty cell: volume 0, no faces. The
///   volumes of the others sum to the box's volume, up to rounding.
/// - Deterministic: the same arrays, bit for bit, on any thread count and on both executors.
struct VoronoiCells {
  HostVector<double> volumes;    ///< n
  HostVector<double> areas;      ///< n: each cell's surface area, walls included
  HostVector<double> centroids;  ///< 3 n
  /// Per cell, its faces face_offsets[i] .. face_offsets[i + 1]; per face its neighbour, area,
  /// outward unit normal and vertices (face_vertex_offsets, into face_vertices: indices of
  /// `vertices`, each cell holding its own).
  HostVector<std::int64_t> face_offsets;         ///< n + 1
  HostVector<std::int32_t> neighbors;            ///< one per face
  HostVector<double> face_areas;                 ///< one per face
  HostVector<double> face_normals;               ///< 3 per face
  HostVector<std::int64_t> face_vertex_offsets;  ///< faces + 1
  HostVector<std::int32_t> face_vertices;
  HostVector<std::int64_t> vertex_offsets;  ///< n + 1: each cell's vertices in `vertices`
  HostVector<double> vertices;              ///< 3 per vertex
  /// The points, faces, face vertex entries and cell vertices (the arrays' lengths, written into
  /// the caller's arrays or not).
  std::int64_t num_points = 0, num_faces = 0, num_face_vertices = 0, num_vertices = 0;
  VoronoiCellsStats stats;
};
/// Throws Error(InvalidArgument) for a box with hi <= lo or bounds that are not finite,
/// Error(InvalidInput) for a coordinate that is not finite or a point outside the box along an
/// axis that does not wrap; as delaunay3d otherwise.
VoronoiCells voronoi_cells(const double* xyz, std::int64_t n, const VoronoiCellsOptions& opt = {});

/// The result of voronoi_cells_device: arrays in device memory (host memory on the CPU executor).
struct DeviceVoronoiCells {
  std::int64_t num_points = 0, num_faces = 0, num_face_vertices = 0, num_vertices = 0;
  std::shared_ptr<double> volumes, areas, centroids;
  std::shared_ptr<std::int64_t> face_offsets;
  std::shared_ptr<std::int32_t> neighbors;
  std::shared_ptr<double> face_areas, face_normals;
  std::shared_ptr<std::int64_t> face_vertex_offsets;
  std::shared_ptr<std::int32_t> face_vertices;
  std::shared_ptr<std::int64_t> vertex_offsets;
  std::shared_ptr<double> vertices;
  Backend backend = Backend::Cuda;
  VoronoiCellsStats stats;
};
/// The same for points already on the executor (device memory for Backend::Cuda): the arrays as
/// VoronoiCells's, in device memory of the call's resource (RunOptions::memory) (freed when the
/// last copy of their pointer goes), the counts beside them.
DeviceVoronoiCells voronoi_cells_device(const double* device_xyz, std::int64_t n,
                                        const VoronoiCellsOptions& opt = {});

}  // namespace gpugeom
