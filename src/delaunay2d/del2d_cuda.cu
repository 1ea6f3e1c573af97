// 2D Delaunay triangulation compiled for the CUDA executor.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <cuda/atomic>
#include <string>
#include <thrust/functional.h>
#include <vector>

#include "delaunay2d/del2d_backend.hpp"
#include "exec/cuda_exec.cuh"
#include "predicates/predicates.hpp"
#include "spatial/hilbert.hpp"

namespace gpugeom::del2d::cuda_impl {
using Exec = CudaExec;
#include "delaunay2d/impl/geometry.inl"
#include "delaunay2d/impl/prepare.inl"
#include "delaunay2d/impl/mesh.inl"
#include "delaunay2d/impl/triangulate.inl"
void triangulate(const double* xy, std::int64_t n, Output& out, Stats& stats) {
  triangulate_impl(xy, n, out, stats);
}
}  // namespace gpugeom::del2d::cuda_impl
