// The 2D test entries (testing.hpp) compiled for the CUDA executor (see del2d_cpu.cpp).
#include <cooperative_groups.h>
#include "exec/cuda_exec.cuh"
#include "exec/tu_exec.hpp"
#include "delaunay2d/impl/unit.hpp"
#include "testing/backend.hpp"

namespace gpugeom::del2d::cuda_impl {
GG_TU_EXECUTOR(CudaExec)  // (exec/tu_exec.hpp: this unit's own type)
namespace edt_impl = gpugeom::edt::cuda_impl;
#include "delaunay2d/impl/unit.inl"
#include "testing/impl/del2d.inl"
}  // namespace gpugeom::del2d::cuda_impl
