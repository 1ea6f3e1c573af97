// Hilbert sort compiled for the CPU executor.
#include "exec/cpu_exec.hpp"
#include "spatial/hilbert.hpp"
#include "spatial/spatial_sort_impl.hpp"

namespace gpugeom::cpu_impl {
using Exec = CpuExec;
#include "spatial/impl/hilbert_sort.inl"

void hilbert_order(const double* pts, std::int64_t n, int dim, const spatial::Box& box,
                   std::int32_t* order) {
  CpuExec ex;
  if (dim == 2)
    hilbert_sort<2>(ex, pts, n, order, box);
  else
    hilbert_sort<3>(ex, pts, n, order, box);
}
}  // namespace gpugeom::cpu_impl
