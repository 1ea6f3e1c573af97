// What the public 3D Delaunay entry gets back from a backend (internal).
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
#include "gpugeom/host_vector.hpp"
#include "gpugeom/delaunay3d.hpp"

namespace gpugeom::del3d {

using ProgressFn = std::function<void(const Delaunay3dProgress&)>;

// The backends fill the public results' fields (their other fields are the public entry's):
// one result type per memory space.
using Output = Triangulation3d;
using DeviceOutput = DeviceTriangulation3d;

// Refuses counts no tetrahedralisation can be made of, or past the store's reach (Error).
void check_count(std::int64_t n);

// DynamicDelaunay3d's state on one executor (impl/dynamic.inl).
using Kept = detail::KeptState<Output, DeviceOutput>;

// One executor's entries (exec/dispatch.hpp, exec/point_entries.hpp): impl/entries.inl fills
// them for each executor.
using Entries = detail::PointEntries<Delaunay3dOptions, Output, DeviceOutput, Kept>;
GG_DECLARE_TABLE(Entries, entries)

// delaunay3d_devices' frame (impl/assemble.inl, on the executor of opt.backend and, on the GPU,
// opt.device): the points checked and prepared as delaunay3d prepares them, then `blocks` (the
// blocks on their devices, timed into the stats, handed the prepared points and their split on
// this executor: blocks/point_split.hpp), then their owned tetrahedra in delaunay3d's
// order, with its vertex map and hull facets: the arrays of a single call.
using BlocksFn = std::function<blocks_detail::OwnedBlocks(Delaunay3dStats&,
                                                          const blocks_detail::PreparedPoints&)>;
struct Assembly {
  void (*run)(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
              const BlocksFn& blocks, Output& out);
  // One block (blocks/block_pass.hpp), on opt.backend and, on the GPU, opt.device.
  void (*block)(const Delaunay3dOptions& opt, const blocks_detail::BlockTask& task,
                const blocks_detail::FinalTest& test, blocks_detail::BlockRows& out);
};
GG_DECLARE_TABLE(Assembly, assembly)

}  // namespace gpugeom::del3d
