#include "exec/cuda_exec.cuh"
#define EXEC gpugeom::CudaExec
#define SUITE CudaSplitPass
#include "split_pass_suite.inl"
