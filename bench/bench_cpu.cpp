#include <algorithm>
#include <chrono>
#include <functional>

#include "bench_problems.hpp"
#include "exec/cpu_exec.hpp"
#include "predicates/predicates.hpp"
#include "exec/split_pass.hpp"
#include "spatial/hilbert.hpp"

namespace gpugeom::bench::cpu_impl {
using Exec = CpuExec;
#include "spatial/impl/hilbert_sort.inl"
#include "impl/problems.inl"
}  // namespace gpugeom::bench::cpu_impl
