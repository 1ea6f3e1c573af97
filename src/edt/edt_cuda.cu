// The distance transform compiled for the CUDA executor.
#include <chrono>
#include <cstdlib>
#include <functional>
#include <cmath>
#include <string>
#include <type_traits>

#include "edt/edt_backend.hpp"
#include "exec/cuda_exec.cuh"

namespace gpugeom::edt::cuda_impl {
using Exec = CudaExec;
#include "edt/impl/pba.inl"
#include "edt/impl/jfa.inl"
#include "edt/impl/run.inl"
void run(const Request& req, Output& out, Stats& stats) { run_impl(req, out, stats); }
}  // namespace gpugeom::edt::cuda_impl
