#include <algorithm>
#include <chrono>
#include <functional>

#include "bench_problems.hpp"
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "predicates/predicates.hpp"
#include "exec/split_pass.hpp"
#include "spatial/hilbert.hpp"

namespace gpugeom::bench::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "spatial/impl/hilbert_sort.inl"
#include "impl/problems.inl"
}  // namespace gpugeom::bench::cuda_impl
