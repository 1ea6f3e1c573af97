// What the public 3D Delaunay entry gets back from a backend (internal).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "exec/dynamic_state.hpp"
#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"
#include "gpugeom/delaunay3d.hpp"

namespace gpugeom::del3d {

using ProgressFn = std::function<void(const Delaunay3dProgress&)>;

// The backends fill the public results' fields (their other fields are the public entry's):
// one result type per memory space.
using Output = Triangulation3d;
using DeviceOutput = DeviceTriangulation3d;

// triangulate: xyz holds n points on the host; triangulate_device: n points in the executor's
// memory. Both validate the coordinates on the executor (throw Error) and honour opt.into.
// Refuses counts no tetrahedralisation can be made of, or past the store's reach (Error).
void check_count(std::int64_t n);

// DynamicDelaunay3d's state on one executor (impl/dynamic.inl).
using Kept = detail::KeptState<Output, DeviceOutput>;

// One executor's entries (exec/dispatch.hpp): impl/entries.inl fills them for each executor.
struct Entries {
  std::unique_ptr<Kept> (*make_kept)(const Delaunay3dOptions& opt);
  void (*triangulate)(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt, Output& out,
                      Stats& stats);
  void (*triangulate_device)(const double* xyz, std::int64_t n, const Delaunay3dOptions& opt,
                             DeviceOutput& out, Stats& stats);
};
namespace cpu_impl {
extern const Entries entries;
}
namespace cuda_impl {
extern const Entries entries;
}

}  // namespace gpugeom::del3d
