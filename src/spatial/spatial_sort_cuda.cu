// Hilbert sort compiled for the CUDA executor (host arrays in, host order out).
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "spatial/hilbert.hpp"
#include "spatial/spatial_sort_impl.hpp"

namespace gpugeom::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
#include "spatial/impl/hilbert_sort.inl"

void hilbert_order(const double* pts, std::int64_t n, int dim, const spatial::Box& box,
                   std::int32_t* order) {
  Exec ex;
  auto dp = ex.alloc<double>(std::size_t(n) * dim);
  auto dord = ex.alloc<std::int32_t>(std::size_t(n));
  ex.from_host(pts, n * dim, dp.data());
  if (dim == 2)
    hilbert_sort<2>(ex, dp.data(), n, dord.data(), box);
  else
    hilbert_sort<3>(ex, dp.data(), n, dord.data(), box);
  ex.to_host(dord.data(), n, order);
}
}  // namespace gpugeom::cuda_impl
