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
// every voxel holds its nearest site (ties: first in raster order). Bands are chosen by size.
namespace cpu_impl {
void feature_transform_held(CpuExec& ex, const Layout& L, const Metric& M, std::uint32_t* feat);
}
namespace cuda_impl {
void feature_transform_held(CudaExec& ex, const Layout& L, const Metric& M, std::uint32_t* feat);
}
}  // namespace gpugeom::edt
