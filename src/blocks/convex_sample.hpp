// Whether the points lie on a convex surface, judged on a sample (convex_sample.cpp): the rule by
// which the several devices of one host (delaunay_devices.cpp) give every point to one block, that
// is to the single call on the first device. gpugeom.dask takes the same rule with the same
// constants (python/gpugeom/dask/_delaunay.py, _on_convex_surface). It decides only where the work
// runs: one block holding every point gives the single call's triangulation as the split does.
#pragma once
#include <cstdint>

namespace gpugeom::blocks_detail {

// The sample: at most this many points, every ceil(m / kConvexSample)-th of the m.
constexpr std::int64_t kConvexSample = 4096;

// The stride of the sample of m points.
inline std::int64_t convex_sample_stride(std::int64_t m) {
  return m <= kConvexSample ? 1 : (m + kConvexSample - 1) / kConvexSample;
}

// True where at least half of the sample of the m points (dim = 2 or 3 coordinates each, host
// memory, as the caller gave them: duplicates count, and a NaN or an infinity in the sample says
// false) are extreme points of the sample's hull: points on a circle or a sphere, or on a shell
// thinner than the sample's spacing. Every block would hold them all (each holds the global hull's
// extreme points) and its balls span the hollow inside, where no ghost layer reaches; one
// triangulation of every point costs less. A flat sample (no hull) says false. Decided on the host
// with the CPU executor on one thread (a sample of 4096 3D points on a sphere: 3-4 ms; on all 16
// threads of the H200 host the 2D circle of 2·10^7 points took 160 ms where one thread gives 147).
bool on_convex_surface(const double* pts, int dim, std::int64_t m);

}  // namespace gpugeom::blocks_detail
