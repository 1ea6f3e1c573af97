#include <cuda/atomic>

#include "exec/cuda_exec.cuh"
#define EXEC gpugeom::CudaExec
#define SUITE CudaExecTest
#include "exec_suite.inl"
