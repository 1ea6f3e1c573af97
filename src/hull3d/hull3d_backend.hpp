// What the public convex hull entry gets back from a backend (internal).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "gpugeom/common.hpp"
#include "gpugeom/host_vector.hpp"

namespace gpugeom::hull3d {

struct Output {
  HostVector<std::int32_t> triangles;  // 3 per facet, input indices, counter-clockwise outside
  HostVector<std::int32_t> neighbors;  // 3 per facet
  HostVector<std::int32_t> vertices;   // sorted input indices of the extreme points
  // 4 per facet (unit outward normal, offset); NaN for a facet whose rounded normal vanished,
  // to be redone in long double on the host (planes_redo of them).
  HostVector<double> equations;
  std::int64_t planes_redo = 0;
};

// The result left on the device; the pointers own cudaMalloc'd memory.
struct DeviceOutput {
  std::shared_ptr<std::int32_t> triangles, neighbors, vertices;
  std::int64_t num_facets = 0, num_vertices = 0;
};

// xyz: n points on the host; validated on the executor (throws Error).
namespace cpu_impl {
void compute(const double* xyz, std::int64_t n, const RunOptions& run, Output& out, Stats& stats);
}
namespace cuda_impl {
void compute(const double* xyz, std::int64_t n, const RunOptions& run, Output& out, Stats& stats);
// xyz: n points in device memory.
void compute_device(const double* xyz, std::int64_t n, const RunOptions& run, DeviceOutput& out,
                    Stats& stats);
}  // namespace cuda_impl

}  // namespace gpugeom::hull3d
