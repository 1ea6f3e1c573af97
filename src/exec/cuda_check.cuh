// Every CUDA runtime call and kernel launch goes through these, so that a failure becomes a
// typed gpugeom::Error naming the call and the place, never a silent wrong answer.
#pragma once
#include <cuda_runtime.h>
#include <string>

#include "gpugeom/common.hpp"

namespace gpugeom::detail {
[[noreturn]] inline void throw_cuda(cudaError_t e, const char* what, const char* file, int line) {
  std::string msg = std::string("CUDA error in ") + what + " (" + file + ":" +
                    std::to_string(line) + "): " + cudaGetErrorString(e);
  if (e == cudaErrorMemoryAllocation)
    throw Error(ErrorCode::OutOfMemory,
                msg +
                    "; the problem does not fit in GPU memory: use a smaller input, or the "
                    "CPU backend (--backend cpu)");
  throw Error(ErrorCode::Cuda, msg);
}
}  // namespace gpugeom::detail

#define GG_CUDA_CHECK(call)                                                                        \
  do {                                                                                             \
    cudaError_t gg_err_ = (call);                                                                  \
    if (gg_err_ != cudaSuccess) ::gpugeom::detail::throw_cuda(gg_err_, #call, __FILE__, __LINE__); \
  } while (0)

#define GG_CUDA_CHECK_LAUNCH(name) GG_CUDA_CHECK(cudaGetLastError())
