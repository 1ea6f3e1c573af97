// What the public 2D Delaunay entry gets back from a backend (internal).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "blocks/block_pass.hpp"
#include "blocks/owned.hpp"
#include "blocks/point_split.hpp"
#include "exec/dynamic_state.hpp"
#include "exec/point_entries.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/delaunay2d.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::del2d {

// The backends fill the public results' fields (their other fields are the public entry's):
// one result type per memory space.
using Output = Triangulation2d;
using DeviceOutput = DeviceTriangulation2d;
using DeviceVoronoiOutput = DeviceVoronoi2d;

// digital: Method::Digital from host points (digital/digital.hpp says what it
// reports); the points go to the executor once and every phase's arrays stay there. It starts
// from a triangulation (run_from_start in impl/triangulate.inl; src/testing enters that from
// host arrays).
// check_count refuses counts no triangulation can be made of (Error, as the public entries say).
void check_count(std::int64_t n);
// DynamicDelaunay2d's state on one executor (impl/dynamic.inl).
using Kept = detail::KeptState<Output, DeviceOutput>;

// One executor's entries (exec/dispatch.hpp, exec/point_entries.hpp): impl/entries.inl fills
// them for each executor.
struct Entries : detail::PointEntries<Delaunay2dOptions, Output, DeviceOutput, Kept> {
  void (*digital)(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Output& out,
                  Delaunay2dStats& stats);
};

// The Voronoi diagram's entries on one executor (impl/voronoi.inl, its own unit).
struct VoronoiEntries {
  // The diagram of nt triangles (tri, nb; dup may be null: no duplicates) of n points xy, all in
  // the executor's memory; into `host` where given (the host entry), else left in `out`. outer:
  // the calling executor's context (exec/exec_context.hpp), or null.
  void (*voronoi)(const double* xy, std::int64_t n, const std::int32_t* tri, const std::int32_t* nb,
                  const std::int32_t* dup, std::int64_t nt, const Voronoi2dOptions& run,
                  DeviceVoronoiOutput& out, RunStats& stats, Voronoi2d* host,
                  const detail::ExecContext* outer);
  // voronoi2d(xy, n, tri, opt): the same diagram from host arrays (dup: the duplicate map, n
  // entries), into v (its arrays or opt.into's): over them where the executor reads host
  // memory, else uploaded once.
  void (*of_host)(const double* xy, std::int64_t n, const std::int32_t* tri, const std::int32_t* nb,
                  const std::int32_t* dup, std::int64_t nt, const Voronoi2dOptions& opt,
                  Voronoi2d& v);
  // voronoi2d(xy, n, opt, tri) where the executor does not read host memory: the points go up
  // once, both structures are made there, and only the results come back. Null on the CPU.
  void (*from_host)(const double* xy, std::int64_t n, const Delaunay2dOptions& opt, Voronoi2d& v,
                    Triangulation2d* tri, Delaunay2dStats& stats);
};

GG_DECLARE_TABLE(Entries, entries)

// delaunay2d_devices' frame (impl/assemble.inl, on the executor of opt.backend and, on the GPU,
// opt.device): the points checked and prepared as delaunay2d prepares them, then `blocks` (the
// blocks on their devices, timed into the stats, handed the prepared points and their split on
// this executor: blocks/point_split.hpp), then their owned triangles in delaunay2d's
// order: the arrays of a single call.
using BlocksFn = std::function<blocks_detail::OwnedBlocks(Delaunay2dStats&,
                                                          const blocks_detail::PreparedPoints&)>;
struct Assembly {
  void (*run)(const double* xy, std::int64_t n, const Delaunay2dOptions& opt,
              const BlocksFn& blocks, Output& out);
  // One block (blocks/block_pass.hpp), on opt.backend and, on the GPU, opt.device.
  void (*block)(const Delaunay2dOptions& opt, const blocks_detail::BlockTask& task,
                const blocks_detail::FinalTest& test, blocks_detail::BlockRows& out);
};
GG_DECLARE_TABLE(Assembly, assembly)
GG_DECLARE_TABLE(VoronoiEntries, voronoi_entries)

}  // namespace gpugeom::del2d
