// The feature transform over data an executor already holds, for modules built on the
// distance transform (cvd/ runs it once per Lloyd iteration on device-resident sites).
#pragma once
#include <cstdint>

#include "edt/edt_common.hpp"

namespace gpugeom {
struct CpuExec;
class CudaExec;
}  // namespace gpugeom

namespace gpugeom::edt {
// feat: kNone everywhere but at sites, which hold their own packed coordinates; on return
// every voxel holds its nearest site (ties: first in raster order). Bands are chosen by size;
// sites (how many, 0 if unknown) chooses the windowed passes.
namespace cpu_impl {
void feature_transform_held(CpuExec& ex, const Layout& L, const Metric& M, std::uint32_t* feat,
                            std::int64_t sites);
}
namespace cuda_impl {
void feature_transform_held(CudaExec& ex, const Layout& L, const Metric& M, std::uint32_t* feat,
                            std::int64_t sites);
}
}  // namespace gpugeom::edt
