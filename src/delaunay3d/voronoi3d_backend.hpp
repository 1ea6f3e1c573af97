// The 3D Voronoi diagram's executor entries (internal; impl/voronoi.inl).
#pragma once
#include <cstdint>
#include <memory>

#include "exec/dispatch.hpp"
#include "exec/exec_context.hpp"
#include "gpugeom/voronoi3d.hpp"
#include "gpugeom/voronoi_cells.hpp"

namespace gpugeom::del3d {

// The 3D Voronoi diagram's and the Voronoi cells' entries on one executor (exec/dispatch.hpp;
// impl/voronoi_entries.inl fills them for each executor).
struct VoronoiEntries {
  // tet, nb: nt tetrahedra as Triangulation3d has them; dup: the duplicate map (null: none; a kept
  // tetrahedralisation's marks removed points), all in the executor's memory, as xyz. out: the
  // arrays in the executor's memory (its counts and arrays; the caller sets the rest), or, with
  // host, the host entry's result instead (then `out` is left empty). outer: the calling
  // executor's context (exec/exec_context.hpp), or null.
  void (*voronoi)(const double* xyz, std::int64_t n, const std::int32_t* tet,
                  const std::int32_t* nb, const std::int32_t* dup, std::int64_t nt,
                  const Voronoi3dOptions& run, DeviceVoronoi3d& out, Voronoi3dStats& stats,
                  Voronoi3d* host, const detail::ExecContext* outer);
  // voronoi3d(xyz, n, tri, opt): the same diagram from host arrays (dup: the duplicate map, n
  // entries), into v (its arrays or opt.into's): over them where the executor reads host
  // memory, else uploaded once.
  void (*of_host)(const double* xyz, std::int64_t n, const std::int32_t* tet,
                  const std::int32_t* nb, const std::int32_t* dup, std::int64_t nt,
                  const Voronoi3dOptions& opt, Voronoi3d& v);
  // voronoi3d(xyz, n, opt, tri) where the executor does not read host memory: the points go up
  // once, both structures are made there, and only the results come back. Null on the CPU.
  void (*from_host)(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt, Voronoi3d& v,
                    Triangulation3d* tri);
  // The Voronoi cells (impl/cells.inl) of n points in executor memory, or host memory where
  // on_host: into dev (executor memory) or, with host, into host's vectors.
  void (*cells)(const double* xyz, std::int64_t n, bool on_host, const VoronoiCellsOptions& opt,
                DeviceVoronoiCells* dev, VoronoiCells* host);
};
GG_DECLARE_TABLE(VoronoiEntries, voronoi_entries)

}  // namespace gpugeom::del3d
