// Every CUDA runtime call and kernel launch goes through these, so that a failure becomes a
// typed gpugeom::Error naming the call and the place, never a silent wrong answer.
#pragma once
#include <cuda_runtime.h>
#include <cxxabi.h>
#include <cstdlib>
#include <string>
#include <typeinfo>

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
// A failed launch, naming the kernel and, for the executor's generic kernels, the function it
// ran (the demangled type of the functor: the module and the step that launched it).
[[noreturn]] inline void throw_launch(cudaError_t e, const char* kernel, const char* functor,
                                      const char* file, int line) {
  std::string what = std::string("launch of ") + kernel;
  if (functor) {
    int st = 0;
    char* d = abi::__cxa_demangle(functor, nullptr, nullptr, &st);
    what += std::string(" running ") + (st == 0 && d ? d : functor);
    std::free(d);
  }
  throw_cuda(e, what.c_str(), file, line);
}
}  // namespace gpugeom::detail

#define GG_CUDA_CHECK(call)                                                                        \
  do {                                                                                             \
    cudaError_t gg_err_ = (call);                                                                  \
    if (gg_err_ != cudaSuccess) ::gpugeom::detail::throw_cuda(gg_err_, #call, __FILE__, __LINE__); \
  } while (0)

// After a kernel launch: name is the kernel's name (a string).
#define GG_CUDA_CHECK_LAUNCH(name)                                                 \
  do {                                                                             \
    cudaError_t gg_err_ = cudaGetLastError();                                      \
    if (gg_err_ != cudaSuccess)                                                    \
      ::gpugeom::detail::throw_launch(gg_err_, name, nullptr, __FILE__, __LINE__); \
  } while (0)
// The same for a generic kernel running functor type F.
#define GG_CUDA_CHECK_LAUNCH_OF(kernel_name, F)                                                    \
  do {                                                                                             \
    cudaError_t gg_err_ = cudaGetLastError();                                                      \
    if (gg_err_ != cudaSuccess)                                                                    \
      ::gpugeom::detail::throw_launch(gg_err_, kernel_name, typeid(F).name(), __FILE__, __LINE__); \
  } while (0)
