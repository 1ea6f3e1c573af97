// What the public 2D Delaunay entry gets back from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::del2d {

struct Output {
  HostVector<std::int32_t> triangles;     // 3 per triangle, input indices, counter-clockwise
  HostVector<std::int32_t> neighbors;     // 3 per triangle, -1 on the hull
  HostVector<std::int32_t> duplicate_of;  // n entries
  std::int64_t num_duplicates = 0;
};

// The result left on the device; the pointers own cudaMalloc'd memory.
struct DeviceOutput {
  std::shared_ptr<std::int32_t> triangles, neighbors, duplicate_of;
  std::int64_t num_triangles = 0, num_duplicates = 0;
};

// xy: n points on the host. Validates the coordinates on the executor (throws Error).
namespace cpu_impl {
void triangulate(const double* xy, std::int64_t n, const RunOptions& run, Output& out,
                 Stats& stats);
}
namespace cuda_impl {
void triangulate(const double* xy, std::int64_t n, const RunOptions& run, Output& out,
                 Stats& stats);
// xy: n points in device memory.
void triangulate_device(const double* xy, std::int64_t n, const RunOptions& run, DeviceOutput& out,
                        Stats& stats);
}  // namespace cuda_impl

}  // namespace gpugeom::del2d
