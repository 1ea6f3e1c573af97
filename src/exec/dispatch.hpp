// Runs a module's backend function on the executor a run resolved to (internal): every module
// compiles its algorithm twice, into NS::cpu_impl and NS::cuda_impl (the latter only in CUDA
// builds), and each public entry picks one with this.
#pragma once
#include "gpugeom/common.hpp"

#ifdef GPUGEOM_HAVE_CUDA
#define GG_ON_EXECUTOR(backend, ns, fn, ...)                              \
  ((backend) == ::gpugeom::Backend::Cuda ? ns::cuda_impl::fn(__VA_ARGS__) \
                                         : ns::cpu_impl::fn(__VA_ARGS__))
#else
#define GG_ON_EXECUTOR(backend, ns, fn, ...) ((void)(backend), ns::cpu_impl::fn(__VA_ARGS__))
#endif
