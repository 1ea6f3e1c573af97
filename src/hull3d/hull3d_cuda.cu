// 3D convex hull compiled for the CUDA executor.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <type_traits>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "base/clock.hpp"
#include "exec/atomics.hpp"
#include "exec/deliver.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "exec/peak.hpp"
#include "hull3d/hull3d_backend.hpp"
#include "exec/scratch_slots.hpp"
#include "mesh/adjacency.hpp"
#include "mesh/compact.hpp"
#include "mesh/decision.hpp"
#include "mesh/flip_fix.hpp"
#include "mesh/first_tetrahedron.hpp"
#include "mesh/kept_points.hpp"
#include "mesh/prepare.hpp"
#include "mesh/priority.hpp"
#include "mesh/simplex_changes.hpp"
#include "mesh/work_list.hpp"
#include "predicates/predicates.hpp"

namespace gpugeom::hull3d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "hull3d/impl/geometry.inl"
#include "hull3d/impl/prepare.inl"
#include "hull3d/impl/surface.inl"
#include "hull3d/impl/construct.inl"
#include "hull3d/impl/flipflop.inl"
#include "hull3d/impl/hull.inl"
#include "hull3d/digital/impl/digital.inl"
#include "hull3d/impl/dynamic.inl"
void compute(const double* xyz, std::int64_t n, const Hull3dOptions& opt, Output& out,
             Stats& stats) {
  compute_impl(xyz, n, opt, out, stats);
}
void compute_device(const double* xyz, std::int64_t n, const Hull3dOptions& opt, DeviceOutput& out,
                    Stats& stats) {
  compute_device_impl(xyz, n, opt, out, stats);
}
}  // namespace gpugeom::hull3d::cuda_impl
